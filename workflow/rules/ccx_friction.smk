# The full interface law inside CalculiX (issue 30; roughcontact.paper.ccx_friction, docs/ccx.md):
# the block on a base with orthotropic hardening friction and a tangential step, and the punch of
# example 9.2 (cases of config ccx_friction.punch_cases), each through `roughcontact ccx run` and
# `roughcontact fe run`. OPTIONAL scene "ccx_friction": it needs the ccx that `roughcontact ccx
# build` (make ccx-build) makes; the scene does not build it (minutes). Without it the rule still
# succeeds and writes every output with the one line of why (tests/test_workflow.py runs that path).

from roughcontact.ccx.build import find_build as _ccx_law_build

CCX_FRICTION = config["ccx_friction"]


rule ccx_friction:
    """The decks in ccx with the law as a user element and in the engine: displacements, forces,
    pressures, slips and dissipation side by side, with checks."""
    input:
        code=FE_SOURCES + library_sources("ccx", "paper/ccx_friction.py", "paper/calculix.py"),
    output:
        md="paper_figures/ccx_friction.md",
        csv="paper_figures/ccx_friction.csv",
        checks="results/verify/ccx_friction.checks.csv",
        workdir=directory("results/ccx_friction"),
    log:
        "logs/fe/ccx_friction.log",
    benchmark:
        "results/benchmarks/fe/ccx_friction.tsv"
    params:
        cfg=CCX_FRICTION,
        # building (or removing) the ccx with the law re-runs the scene: params are a rerun trigger
        ccx_build=(lambda b: b.info.get("key") if b else None)(_ccx_law_build()),
    threads: 1
    script:
        "../scripts/ccx_friction.py"
