# Tables 1-3: printed value, ours, relative error, tolerance, verdict per cell (md + csv), and
# the scene's verification rows (results/verify/<scene>.checks.csv).


rule mindlin_values:
    """k_N/k_T of one column (one Poisson ratio) of a Mindlin-table scene (Table 3), closed form."""
    input:
        lib=PHYSICS_SOURCES,
    output:
        "results/production/{scene}/{model}.nc",
    log:
        "logs/production/{scene}/{model}.log",
    benchmark:
        "results/benchmarks/production/{scene}/{model}.tsv"
    wildcard_constraints:
        scene=_alternation(MINDLIN_SCENES),
        model=r"[a-z0-9][a-z0-9-]*",
    params:
        scene=lambda w: w.scene,
        column=lambda w: w.model,
        b2_over_a2=lambda w: list(SCENES[w.scene]["b2_over_a2"]),
        nu=lambda w: float(SCENES[w.scene]["columns"][w.model]["nu"]),
    localrule: True
    script:
        "../scripts/mindlin_values.py"


def table_inputs(wildcards):
    sc = SCENES[wildcards.scene]
    out = {
        "production": [f"results/production/{wildcards.scene}/{m}.nc" for m in table_columns(wildcards.scene)],
    }
    if sc.get("accuracy", {}).get("reference"):
        out["reference"] = [
            f"results/reference/dps{REFERENCE_DPS}/{wildcards.scene}/{m}.nc" for m in sc["models"]
        ]
    return out


rule table:
    """Compare one table scene with the printed table; write it as markdown and CSV."""
    input:
        unpack(table_inputs),
        paper="config/paper_values.yaml",
        expected="config/expected_verdicts.yaml",
        code=REPORT_SOURCES,
    output:
        md="paper_figures/{scene}.md",
        csv="paper_figures/{scene}.csv",
        checks="results/verify/{scene}.checks.csv",
    log:
        "logs/table/{scene}.log",
    wildcard_constraints:
        scene=_alternation(PRINTED_TABLES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: SCENES[w.scene],
        models=lambda w: table_columns(w.scene),
        numerics_rtol=float(config["numerics_rtol"]),
        reference_dps=REFERENCE_DPS,
    localrule: True
    script:
        "../scripts/table.py"


# One target rule per table scene, named after it: `snakemake table1`.
for _scene in PRINTED_TABLES:

    rule:
        name:
            _scene
        localrule: True
        input:
            f"paper_figures/{_scene}.md",
            f"paper_figures/{_scene}.csv",
