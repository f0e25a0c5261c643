# Figures: curves at plotting accuracy (results/curves/<scene>.nc), then the PNG, the data as
# CSV and the prose-claim checks (results/verify/<scene>.checks.csv). A scene with `uses:`
# (Fig. 6) is drawn from another scene's curves, computed once.


rule curves_bearing_ratio:
    """A_G/A_B(s) of each surface of a bearing-ratio scene (Fig. 3), production quadrature."""
    input:
        lib=PHYSICS_SOURCES,
        kernels=KERNELS_WARM,
    output:
        "results/curves/{scene}.nc",
    log:
        "logs/curves/{scene}.log",
    benchmark:
        "results/benchmarks/curves/{scene}.tsv"
    wildcard_constraints:
        scene=_alternation(BEARING_SCENES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: compute_config(w.scene),
        surfaces=lambda w: {c["surface"]: surface_of(c["surface"]) for c in SCENES[w.scene]["curves"]},
        provenance=lambda w: scene_provenance(w.scene),
    script:
        "../scripts/curves_bearing_ratio.py"


rule curves_hertz_factors:
    """f1(e), f2(e) of a Hertz-factor scene (Fig. 4), for each Hertz option."""
    input:
        lib=PHYSICS_SOURCES,
    output:
        "results/curves/{scene}.nc",
    log:
        "logs/curves/{scene}.log",
    benchmark:
        "results/benchmarks/curves/{scene}.tsv"
    wildcard_constraints:
        scene=_alternation(HERTZ_SCENES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: compute_config(w.scene),
        provenance=lambda w: scene_provenance(w.scene),
    script:
        "../scripts/curves_hertz_factors.py"


rule curves_elastoplastic:
    """Elasto-plastic curves of one scene (Figs 5-8, stiffness sensitivity): exactly the
    surfaces, plasticity indices, closures and separations the scene declares."""
    input:
        lib=PHYSICS_SOURCES,
        kernels=KERNELS_WARM,
    output:
        "results/curves/{scene}.nc",
    log:
        "logs/curves/{scene}.log",
    benchmark:
        "results/benchmarks/curves/{scene}.tsv"
    wildcard_constraints:
        scene=_alternation(EP_SCENES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: compute_config(w.scene),
        surface=lambda w: surface_of(SCENES[w.scene]["surface"]),
        units=dict(config["units"]),
        provenance=lambda w: scene_provenance(w.scene),
    threads: 2
    script:
        "../scripts/curves_elastoplastic.py"


rule curves_friction:
    """Material points of the interface friction law (section 8) driven through the return
    mapping: the slip rule (Fig. 9), a slip-hardening curve, Fig. 18's cases (a)-(c)."""
    input:
        lib=PHYSICS_SOURCES,
        kernels=KERNELS_WARM,  # Fig. 18's elasto-plastic normal-law table: the kernels from the cache
    output:
        "results/curves/{scene}.nc",
    log:
        "logs/curves/{scene}.log",
    benchmark:
        "results/benchmarks/curves/{scene}.tsv"
    wildcard_constraints:
        scene=_alternation(FRICTION_SCENES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: compute_config(w.scene),
        surface=lambda w: surface_of(SCENES[w.scene]["surface"]) if "surface" in SCENES[w.scene] else None,
        units=dict(config["units"]),
        provenance=lambda w: scene_provenance(w.scene),
    threads: 1
    script:
        "../scripts/curves_friction.py"


rule figure:
    """Plot a figure scene, export its data as CSV and check its prose claims."""
    input:
        data=lambda w: f"results/curves/{curves_of(w.scene)}.nc",
        expected="config/expected_verdicts.yaml",
        code=REPORT_SOURCES,
    output:
        png="paper_figures/{scene}.png",
        pdf="paper_figures/{scene}.pdf",  # vector, beside the PNG (plots.style.save)
        csv="paper_figures/{scene}.csv",
        checks="results/verify/{scene}.checks.csv",
    log:
        "logs/figure/{scene}.log",
    wildcard_constraints:
        scene=_alternation(FIGURE_SCENES),
    params:
        scene=lambda w: w.scene,
        scene_config=lambda w: SCENES[w.scene],
    localrule: True
    script:
        "../scripts/figure.py"


# One target rule per figure scene, named after it: `snakemake fig3`.
for _scene in FIGURE_SCENES:

    rule:
        name:
            _scene
        localrule: True
        input:
            f"paper_figures/{_scene}.png",
            f"paper_figures/{_scene}.csv",
