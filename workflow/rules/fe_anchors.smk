# Engine-free anchors of the FE numbers the gate reports (config: fe_anchors; issue 22): the
# beam of example 9.1 against a 2D plane-stress solution by a separate code, the punch of
# example 9.2 against its equilibrium, friction limit, dissipation and frictionless bound
# recomputed from the written fields (roughcontact.paper.fe_anchors). No optional tool needed.

from roughcontact.paper.fe_anchors import anchored_beam_runs

FE_ANCHORS = config["fe_anchors"]
#: the beam runs the 2D solution anchors (free sliding, at least the main mesh)
FE_BEAM_ANCHORED = anchored_beam_runs(FE_BEAM_RUNS, FE_BEAM["spec"])
FE_ANCHOR_SOURCES = REPORT_SOURCES + library_sources("paper/fe_anchors.py")


rule fe_beam_plane_stress:
    """The 2D plane-stress solution of every interface law the anchored beam runs use
    (roughcontact.paper.plane_stress), on the configured mesh and one half as fine."""
    input:
        code=PHYSICS_SOURCES + library_sources("paper/plane_stress.py"),
        kernels=KERNELS_WARM,
    output:
        "results/fe/beam_plane_stress.nc",
    log:
        "logs/fe/beam_plane_stress.log",
    benchmark:
        "results/benchmarks/fe/beam_plane_stress.tsv"
    params:
        runs={n: FE_BEAM_RUNS[n] for n in FE_BEAM_ANCHORED},
        cfg=FE_ANCHORS["beam"]["plane_stress"],  # not the tolerances: editing them re-runs only the report
    threads: 1
    script:
        "../scripts/fe_beam_plane_stress.py"


rule fe_beam_anchor:
    """The anchored beam runs against the 2D solutions: u_N at the centre and the end, the
    profile, the equilibrium of the written pressures."""
    input:
        runs=fe_beam_dirs(FE_BEAM_ANCHORED),
        reference="results/fe/beam_plane_stress.nc",
        expected="config/expected_verdicts.yaml",
        code=FE_ANCHOR_SOURCES,
    output:
        md="paper_figures/fe_beam_anchor.md",
        checks="results/verify/fe_beam_anchor.checks.csv",
    log:
        "logs/fe/fe_beam_anchor.log",
    params:
        runs={n: FE_BEAM_RUNS[n] for n in FE_BEAM_ANCHORED},
        paths=fe_beam_paths(FE_BEAM_ANCHORED),
        cfg=FE_ANCHORS["beam"],
    localrule: True
    script:
        "../scripts/fe_beam_anchor.py"


rule fe_punch_anchor:
    """Every punch run at every level: equilibrium, friction limit, dissipation, bound."""
    input:
        runs=[f"results/fe/punch/{g}" for g in FE_PUNCH_GROUPS],
        expected="config/expected_verdicts.yaml",
        code=FE_ANCHOR_SOURCES + library_sources("paper/fe_punch.py"),
    output:
        md="paper_figures/fe_punch_anchor.md",
        checks="results/verify/fe_punch_anchor.checks.csv",
    log:
        "logs/fe/fe_punch_anchor.log",
    params:
        runs=FE_PUNCH_RUNS,
        paths=fe_punch_paths(FE_PUNCH_RUNS),
        cfg=FE_ANCHORS["punch"],
        d_attr=FE_PUNCH["d_attr"],
    localrule: True
    script:
        "../scripts/fe_punch_anchor.py"
