# Tables 1-2: printed value, ours, relative error, tolerance, verdict per cell (md + csv), and
# the scene's verification rows (results/verify/<scene>.checks.csv).


def table_inputs(wildcards):
    sc = SCENES[wildcards.scene]
    out = {
        "production": [f"results/production/{wildcards.scene}/{m}.nc" for m in sc["models"]],
    }
    if sc["accuracy"]["reference"]:
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
        scene=_alternation(TABLE_SCENES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: SCENES[w.scene],
        models=lambda w: {m: config["models"][m] for m in SCENES[w.scene]["models"]},
        numerics_rtol=float(config["numerics_rtol"]),
        reference_dps=REFERENCE_DPS,
    localrule: True
    script:
        "../scripts/table.py"


# One target rule per table scene, named after it: `snakemake table1`.
for _scene in TABLE_SCENES:

    rule:
        name:
            _scene
        localrule: True
        input:
            f"paper_figures/{_scene}.md",
            f"paper_figures/{_scene}.csv",
