# Finite-element examples of section 9 (config: fe). One job per case and element family
# (results/fe/beam/<family>-<case>/<variant>.nc with its VTU files), then Table 4, Fig. 13, the
# study of what the paper leaves open and the runs' speed and size.
import re


rule fe_beam_case:
    """The runs of one case and element family (roughcontact.examples.beam.run_beam: the beam's
    deck and law through the deck reader): the main run and the study's variants, each as
    <variant>.nc + .vtu + _interface.vtu in the job's directory."""
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
        provenance=lambda w: {"group": w.group, "fe_beam": {v: r.to_dict() for v, r in FE_BEAM_GROUPS[w.group].items()},
                              "units": dict(config["units"])},
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
        runs=fe_beam_dirs([n for n in FE_BEAM_MAIN if n.startswith("cubic-") and FE_BEAM_RUNS[n].law == "elastic"]),
        paper="config/paper_values.yaml",
        code=FE_REPORT_SOURCES,
    output:
        png="paper_figures/fig13.png",
        pdf="paper_figures/fig13.pdf",  # vector, beside the PNG (plots.style.save)
        csv="paper_figures/fig13.csv",
    log:
        "logs/fe/fig13.log",
    params:
        runs={n: FE_BEAM_RUNS[n] for n in FE_BEAM_MAIN if n.startswith("cubic-") and FE_BEAM_RUNS[n].law == "elastic"},
        paths=fe_beam_paths([n for n in FE_BEAM_MAIN if n.startswith("cubic-") and FE_BEAM_RUNS[n].law == "elastic"]),
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
        code=library_sources("fe", "paper/drawings.py", "paper/plots.py", "plots/style.py"),
    output:
        png="paper_figures/fig10.png",
        pdf="paper_figures/fig10.pdf",  # vector, beside the PNG (plots.style.save)
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
    """Speed and size of every FE run, beam and punch (dofs, points, iterations, wall time, peak
    memory)."""
    input:
        runs=fe_beam_dirs(FE_BEAM_RUNS) + [f"results/fe/punch/{g}" for g in FE_PUNCH_GROUPS],
        tsv=[f"results/benchmarks/fe/beam/{group}.tsv" for group in FE_BEAM_GROUPS]
        + [f"results/benchmarks/fe/punch/{group}.tsv" for group in FE_PUNCH_GROUPS],
        code=REPORT_SOURCES + library_sources("paper/fe_speed.py"),
    output:
        md="paper_figures/fe_benchmark.md",
        json="results/benchmarks/fe_runs.json",
    log:
        "logs/fe/fe_benchmark.log",
    params:
        examples={
            "Example 9.1, the beam": {
                "paths": fe_beam_paths(FE_BEAM_RUNS),
                "tsv": [f"results/benchmarks/fe/beam/{group}.tsv" for group in FE_BEAM_GROUPS],
                "main": [n for n in FE_BEAM_RUNS if n.endswith("-main")],
                "goal": 30.0,
                "what": "one per case and element family: the main run and its study variants",
            },
            "Example 9.2, the punch": {
                "paths": fe_punch_paths(FE_PUNCH_RUNS),
                "tsv": [f"results/benchmarks/fe/punch/{group}.tsv" for group in FE_PUNCH_GROUPS],
                "main": [n for n in FE_PUNCH_RUNS if "-main-" in n and not n.endswith("-frictionless")],
                "goal": 60.0,
                "what": "one per element family and reading: cases a, b, c and the frictionless problem",
            },
        },
    localrule: True
    script:
        "../scripts/fe_benchmark.py"


# ---------------------------------------------------------------------------------------------
# example 9.2: the flat punch (config: fe.punch)
# ---------------------------------------------------------------------------------------------
rule fe_punch_case:
    """The runs of one element family and reading (or study variant) of example 9.2
    (roughcontact.examples.punch.run_punch: the punch's deck and laws through the deck reader):
    cases a, b, c and the frictionless problem of the bound,
    each as <case>.nc (the whole load history) + .vtu + _interface.vtu (maximum load)."""
    input:
        lib=FE_SOURCES,
        kernels=KERNELS_WARM,
    output:
        directory("results/fe/punch/{group}"),
    log:
        "logs/fe/punch/{group}.log",
    benchmark:
        "results/benchmarks/fe/punch/{group}.tsv"
    wildcard_constraints:
        group="|".join(re.escape(name) for name in FE_PUNCH_GROUPS),
    params:
        runs=lambda w: FE_PUNCH_GROUPS[w.group],
        provenance=lambda w: {"group": w.group, "fe_punch": {n: r.to_dict() for n, r in FE_PUNCH_GROUPS[w.group].items()},
                              "units": dict(config["units"])},
    threads: 1
    script:
        "../scripts/fe_punch_run.py"


rule fe_table5:
    """Table 5 (main reading, both element families) with its cell checks, the prose of 9.2 as
    checks (main and sensitivity readings), and Table 5 under every reading with the bound."""
    input:
        runs=[f"results/fe/punch/{g}" for g in FE_PUNCH_GROUPS],
        paper="config/paper_values.yaml",
        expected="config/expected_verdicts.yaml",
        code=FE_REPORT_SOURCES + library_sources("paper/fe_punch.py"),
    output:
        md="paper_figures/table5.md",
        csv="paper_figures/table5.csv",
        readings_md="paper_figures/fe_punch_readings.md",
        readings_csv="paper_figures/fe_punch_readings.csv",
        checks="results/verify/table5.checks.csv",
    log:
        "logs/fe/table5.log",
    params:
        runs=FE_PUNCH_RUNS,
        paths=fe_punch_paths(FE_PUNCH_RUNS),
        cfg=FE_PUNCH,
    localrule: True
    script:
        "../scripts/fe_table5.py"


rule fe_punch_slips:
    """Figs 18 (21-node elements) and 19 (28-node): directions of the plastic slips at the contact
    points for cases a, b, c at the maximum load, under the main reading and the sensitivity's."""
    input:
        runs=[f"results/fe/punch/{g}" for g in FE_PUNCH_GROUPS if not g.split("-", 1)[1].startswith("sens-")],
        code=FE_REPORT_SOURCES + library_sources("paper/fe_punch.py"),
    output:
        png="paper_figures/{fig}.png",
        pdf="paper_figures/{fig}.pdf",  # vector, beside the PNG (plots.style.save)
        csv="paper_figures/{fig}.csv",
    log:
        "logs/fe/{fig}.log",
    wildcard_constraints:
        fig="fig18|fig19",
    params:
        family=lambda w: {"fig18": "quadratic", "fig19": "cubic"}[w.fig],
        readings=["main", FE_PUNCH["sensitivity"]["reading"]],
        paths=fe_punch_paths(FE_PUNCH_RUNS),
    localrule: True
    script:
        "../scripts/fe_punch_slips.py"


rule fe_punch_mesh_figure:
    """Figs 14 (21-node) and 15 (28-node): the quarter punch on the foundation, from the engine's mesh."""
    input:
        code=library_sources("fe", "paper/drawings.py", "paper/plots.py", "plots/style.py"),
    output:
        png="paper_figures/{fig}.png",
        pdf="paper_figures/{fig}.pdf",  # vector, beside the PNG (plots.style.save)
    log:
        "logs/fe/{fig}.log",
    wildcard_constraints:
        fig="fig14|fig15",
    params:
        geometry=lambda w: dict(FE_PUNCH["main"].get("geometry", {}),
                                family={"fig14": "quadratic", "fig15": "cubic"}[w.fig]),
    localrule: True
    script:
        "../scripts/fe_punch_mesh_figure.py"


for _fig in ("table5", "fig14", "fig15", "fig18", "fig19"):

    rule:
        name:
            _fig
        localrule: True
        input:
            [f"paper_figures/{_fig}.{ext}" for ext in (("md", "csv") if _fig == "table5" else ("png",))],


rule fe_punch:
    """Every output of example 9.2."""
    localrule: True
    input:
        [f"results/fe/punch/{g}" for g in FE_PUNCH_GROUPS],
        "paper_figures/table5.md", "paper_figures/fe_punch_readings.md",
        "paper_figures/fig14.png", "paper_figures/fig15.png", "paper_figures/fig18.png", "paper_figures/fig19.png",
