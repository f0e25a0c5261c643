# The exported pressure-overclosure table checked in CalculiX (config: calculix; issue 14), and one
# deck in CalculiX and in the engine (issue 23).
# OPTIONAL scene "calculix": it needs the program ccx (Debian package calculix-ccx). Without it
# the rule still succeeds and writes every output (the work directory with a note only, no
# checks, paper_figures/calculix.md saying "skipped: ccx not installed — ..."); the
# verification report, the gate and the gallery show the scene as skipped
# (tests/test_workflow.py runs this path with ccx hidden from PATH).

import shutil

CALCULIX = config["calculix"]
CALCULIX_RUNS = [f"{CALCULIX['family']}-{case}-main" for case in CALCULIX["cases"]]


rule fe_calculix:
    """Block and frictionless beam (example 9.1) in ccx with the exported tables, against the
    law and the engine's beam runs (roughcontact.paper.calculix); a block on a base as one deck
    in ccx and in the engine, refined (roughcontact.paper.calculix_deck)."""
    input:
        runs=fe_beam_dirs(CALCULIX_RUNS),
        code=FE_REPORT_SOURCES + FE_SOURCES + library_sources("paper/calculix.py", "paper/calculix_deck.py"),
        kernels=KERNELS_WARM,
    output:
        md="paper_figures/calculix.md",
        csv="paper_figures/calculix.csv",
        checks="results/verify/calculix.checks.csv",
        workdir=directory("results/calculix"),
    log:
        "logs/fe/calculix.log",
    benchmark:
        "results/benchmarks/fe/calculix.tsv"
    params:
        cfg=CALCULIX,
        beam_cfg=FE_BEAM,
        paths={run.split("-")[1]: path for run, path in fe_beam_paths(CALCULIX_RUNS).items()},
        # installing (or removing) ccx re-runs the scene: params are a rerun trigger
        ccx_installed=shutil.which("ccx") is not None,
    threads: 1
    script:
        "../scripts/fe_calculix.py"


rule fe_export_figure:
    """The figure of docs/fe-export.md: law vs exported rows and the error per row interval."""
    input:
        code=PHYSICS_SOURCES + library_sources("interface/export.py") + library_sources("paper/export_figure.py"),
        kernels=KERNELS_WARM,  # the normal-law tables: the kernels from the cache
    output:
        png="paper_figures/fe_export.png",
        csv="paper_figures/fe_export.csv",
    log:
        "logs/fe/fe_export_figure.log",
    benchmark:
        "results/benchmarks/fe/fe_export_figure.tsv"
    params:
        cfg=CALCULIX,
        beam_cfg=FE_BEAM,
    localrule: True
    script:
        "../scripts/fe_export_figure.py"
