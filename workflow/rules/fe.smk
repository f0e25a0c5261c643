# Finite-element examples of section 9 (config: fe). One job per case and element family
# (results/fe/beam/<family>-<case>/<variant>.nc with its VTU files), then Table 4, Fig. 13, the
# study of what the paper leaves open and the runs' speed and size.
import re


rule fe_beam_case:
    """The runs of one case and element family (roughcontact.fe.beam.beam_case): the main
    run and the study's variants, each as <variant>.nc + .vtu + _interface.vtu in the job's
    directory."""
    input:
        lib=FE_SOURCES,
        kernels=KERNELS_WARM,
    output:
        directory("results/fe/beam/{group}"),
    log:
        "logs/fe/beam/{group}.log",
    benchmark:
        "results/benchmarks/fe/beam/{group}.tsv"
    wildcard_constraints:
        group="|".join(re.escape(name) for name in FE_BEAM_GROUPS),
    params:
        runs=lambda w: FE_BEAM_GROUPS[w.group],
        provenance=lambda w: {"group": w.group, "fe_beam": FE_BEAM_GROUPS[w.group], "units": dict(config["units"])},
    threads: 1
    script:
        "../scripts/fe_beam_run.py"


rule fe_table4:
    """Table 4 regenerated (both element families) with its cell checks and the prose claims."""
    input:
        runs=fe_beam_dirs(FE_BEAM_MAIN),
        paper="config/paper_values.yaml",
        expected="config/expected_verdicts.yaml",
        code=FE_REPORT_SOURCES,
    output:
        md="paper_figures/table4.md",
        csv="paper_figures/table4.csv",
        checks="results/verify/table4.checks.csv",
    log:
        "logs/fe/table4.log",
    params:
        runs={name: FE_BEAM_RUNS[name] for name in FE_BEAM_MAIN},
        paths=fe_beam_paths(FE_BEAM_MAIN),
        cfg=FE_BEAM,
    localrule: True
    script:
        "../scripts/fe_table4.py"


rule fe_fig13:
    """Fig. 13: u_N along the beam for the three m00 (elastic, 28-node elements)."""
    input:
        runs=fe_beam_dirs([n for n in FE_BEAM_MAIN if n.startswith("cubic-") and FE_BEAM_RUNS[n]["law"] == "elastic"]),
        paper="config/paper_values.yaml",
        code=FE_REPORT_SOURCES,
    output:
        png="paper_figures/fig13.png",
        csv="paper_figures/fig13.csv",
    log:
        "logs/fe/fig13.log",
    params:
        runs={n: FE_BEAM_RUNS[n] for n in FE_BEAM_MAIN if n.startswith("cubic-") and FE_BEAM_RUNS[n]["law"] == "elastic"},
        paths=fe_beam_paths([n for n in FE_BEAM_MAIN if n.startswith("cubic-") and FE_BEAM_RUNS[n]["law"] == "elastic"]),
    localrule: True
    script:
        "../scripts/fe_fig13.py"


rule fe_beam_study:
    """What the paper leaves open, measured: tangential restraint, E*, mesh convergence."""
    input:
        runs=fe_beam_dirs(FE_BEAM_RUNS),
        expected="config/expected_verdicts.yaml",
        code=FE_REPORT_SOURCES,
    output:
        md="paper_figures/fe_beam_study.md",
        csv="paper_figures/fe_beam_study.csv",
        checks="results/verify/fe_beam_study.checks.csv",
    log:
        "logs/fe/fe_beam_study.log",
    params:
        runs=FE_BEAM_RUNS,
        paths=fe_beam_paths(FE_BEAM_RUNS),
        cfg=FE_BEAM,
    localrule: True
    script:
        "../scripts/fe_beam_study.py"


rule fe_fig10:
    """Fig. 10: the beam model (quarter mesh, supports, load), drawn from the engine's mesh."""
    input:
        code=library_sources("fe", "paper/drawings.py", "paper/plots.py"),
    output:
        png="paper_figures/fig10.png",
    log:
        "logs/fe/fig10.log",
    params:
        spec=dict(FE_BEAM["spec"], elements=FE_BEAM["families"][0]),
    localrule: True
    script:
        "../scripts/fe_fig10.py"


rule table4:
    localrule: True
    input: "paper_figures/table4.md", "paper_figures/table4.csv"


rule fig13:
    localrule: True
    input: "paper_figures/fig13.png", "paper_figures/fig13.csv"


rule fig10:
    localrule: True
    input: "paper_figures/fig10.png"


rule fe_beam:
    """Every output of example 9.1."""
    localrule: True
    input:
        fe_beam_dirs(FE_BEAM_RUNS),
        fe_targets(),


rule fe_benchmark:
    """Speed and size of every beam run (dofs, points, iterations, wall time, peak memory)."""
    input:
        runs=fe_beam_dirs(FE_BEAM_RUNS),
        tsv=[f"results/benchmarks/fe/beam/{group}.tsv" for group in FE_BEAM_GROUPS],
        code=FE_REPORT_SOURCES,
    output:
        md="paper_figures/fe_benchmark.md",
        json="results/benchmarks/fe_beam.json",
    log:
        "logs/fe/fe_benchmark.log",
    params:
        paths=fe_beam_paths(FE_BEAM_RUNS),
    localrule: True
    script:
        "../scripts/fe_benchmark.py"
