# The verification report (one row per table cell, numerics check and prose claim; errata)
# and the gate that fails on a regression against config/expected_verdicts.yaml.


def errata_input(wildcards):
    path = Path("docs") / "errata.md"  # relative: the workflow stays relocatable
    return [str(path)] if (REPO / path).exists() else []


rule numerics_elastoplastic:
    """Elasto-plastic production vs the slow twin at one check point of a numerics scene (the
    twin, a nested adaptive cubature of 44-64 s per point, comes from the committed seed when
    its code is unchanged; one job per point so they run in parallel)."""
    input:
        lib=PHYSICS_SOURCES,
        kernels=KERNELS_WARM,
        seed="benchmarks/data/references.json",
        cache_code=["benchmarks/references.py", "workflow/scripts/numerics_elastoplastic.py"],
    output:
        "results/numerics/{scene}/point-{point}.nc",
    log:
        "logs/numerics/{scene}/point-{point}.log",
    benchmark:
        "results/benchmarks/numerics/{scene}/point-{point}.tsv"
    wildcard_constraints:
        scene=_alternation(NUMERICS_SCENES),
        point=r"\d+",
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: {**compute_config(w.scene), "points": [SCENES[w.scene]["points"][int(w.point)]]},
        surfaces=lambda w: {p["surface"]: surface_of(p["surface"]) for p in SCENES[w.scene]["points"]},
    threads: 1
    script:
        "../scripts/numerics_elastoplastic.py"


rule numerics_report:
    """The numerics rows of a numerics scene (results/verify/<scene>.checks.csv) and its CSV."""
    input:
        data=lambda w: [f"results/numerics/{w.scene}/point-{i}.nc" for i in range(len(SCENES[w.scene]["points"]))],
        code=REPORT_SOURCES,
    output:
        csv="paper_figures/{scene}.csv",
        checks="results/verify/{scene}.checks.csv",
    log:
        "logs/numerics/{scene}.report.log",
    wildcard_constraints:
        scene=_alternation(NUMERICS_SCENES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: SCENES[w.scene],
    localrule: True
    script:
        "../scripts/numerics_report.py"


def bem_report_input(wildcards):
    """The BEM comparison's report and checks where `snakemake bem` has produced them (the
    target is not part of `all`; VERIFICATION.md then says how to run it). A parameter, not an
    input: as an input it made `verify` rebuild the report at the configured scale, i.e. run
    the full-scale BEM after `snakemake bem --config bem_scale=ci` (CI). The report of whichever
    scale ran last is included; its appearance (the parameter's value) re-runs the report."""
    files = ["paper_figures/bem.md", "results/verify/bem.checks.csv"]
    return files if all((REPO / f).exists() for f in files) else []


rule verification_report:
    """paper_figures/VERIFICATION.md (+ CSV and a JSON summary) from every scene's checks and
    the speed-against-error report."""
    input:
        checks=scene_checks() + fe_checks() + gate_anchor_checks(),
        speed="paper_figures/speed_vs_error.md",
        fe_speed="paper_figures/fe_benchmark.md",
        calculix="paper_figures/calculix.md",
        ccx_friction="paper_figures/ccx_friction.md",
        expected="config/expected_verdicts.yaml",
        errata=errata_input,
        code=REPORT_SOURCES,
    output:
        md="paper_figures/VERIFICATION.md",
        csv="paper_figures/verification.csv",
        summary="results/verify/summary.json",
    log:
        "logs/verify/report.log",
    params:
        scene_titles={**{name: sc["title"] for name, sc in SCENES.items()}, **FE_TITLES, **GATE_ANCHOR_TITLES,
                      "bem": "The BEM on closed forms (optional target bem)"},
        reference_dps=REFERENCE_DPS,
        bem=bem_report_input,
    localrule: True
    script:
        "../scripts/verification_report.py"


rule verify:
    """Print the verification summary; fail (CI red) on any regression. Also builds every
    table and figure, since the report needs all their checks."""
    input:
        scene_targets(),
        fe_targets(),
        drawing_targets(),
        summary="results/verify/summary.json",
        report="paper_figures/VERIFICATION.md",
    output:
        "results/verify/passed",
    log:
        "logs/verify/gate.log",
    localrule: True
    script:
        "../scripts/verify_gate.py"
