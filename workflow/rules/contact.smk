# Contact values of the table scenes: one job per (scene, model level) and integrator, at
# exactly the scene's printed separations and quantities.
#   reference   mpmath (slow, offline quality), cached per precision: results/reference/dps<N>/
#   production  numba at the scene's accuracy preset: results/production/


rule numba_warmup:
    """Compile every numba kernel once into numba's on-disk cache (or load it), before the jobs
    that use them run in parallel (quadrature.warm_up; docs/performance.md, caching). Local:
    on a cluster it compiles on the submit host, into the shared cache, without queueing."""
    localrule: True
    input:
        lib=PHYSICS_SOURCES,
    output:
        touch(KERNELS_WARM),
    log:
        "logs/numba_warmup.log",
    benchmark:
        "results/benchmarks/rules/numba_warmup.tsv"
    threads: 2  # its two parts in two processes (roughcontact.warmup); scaled down to --cores 1
    # first of all: most jobs wait for it, and a job that starts before it compiles on its own
    priority: 100
    shell:
        "python -m roughcontact.warmup --jobs {threads} > {log} 2>&1"


rule reference:
    """mpmath reference values of one table scene and model level (slow: cached per dps; the
    anisotropic model's come from the committed seed when the reference code is unchanged)."""
    input:
        lib=PHYSICS_SOURCES,
        seed="benchmarks/data/references.json",
        cache_code="benchmarks/references.py",
    output:
        "results/reference/dps{dps}/{scene}/{model}.nc",
    log:
        "logs/reference/dps{dps}/{scene}/{model}.log",
    benchmark:
        "results/benchmarks/reference/dps{dps}/{scene}/{model}.tsv"
    wildcard_constraints:
        dps=r"\d+",
        scene=_alternation(TABLE_SCENES),
        model=_alternation(MODEL_NAMES),
    params:
        job=lambda w: contact_job(w.scene, w.model, "reference", dps=int(w.dps)),
    threads: 1
    script:
        "../scripts/contact_values.py"


rule production:
    """Production (numba) values of one table scene and model level at its accuracy preset."""
    input:
        lib=PHYSICS_SOURCES,
        kernels=KERNELS_WARM,
    output:
        "results/production/{scene}/{model}.nc",
    log:
        "logs/production/{scene}/{model}.log",
    benchmark:
        "results/benchmarks/production/{scene}/{model}.tsv"
    wildcard_constraints:
        scene=_alternation(TABLE_SCENES),
        model=_alternation(MODEL_NAMES),
    params:
        job=lambda w: contact_job(w.scene, w.model, "production"),
    threads: 1
    script:
        "../scripts/contact_values.py"
