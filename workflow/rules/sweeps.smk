# Parameter sweeps (config `sweeps:`): each sweep is split along one axis into jobs
# (results/sweeps/<name>/part-<i>.nc, one Snakemake job each, so a cluster profile can run them
# on many nodes) and joined into results/sweeps/<name>.nc. `snakemake sweeps` builds them all.


rule sweep_part:
    """One part of a sweep (roughcontact.contact.sweep.split): the elasto-plastic model over its grid."""
    input:
        lib=PHYSICS_SOURCES,
        kernels=KERNELS_WARM,
        moments=lambda w: [SWEEPS[w.sweep]["moments"]] if SWEEPS[w.sweep].get("moments") else [],
    output:
        "results/sweeps/{sweep}/part-{part}.nc",
    log:
        "logs/sweeps/{sweep}/part-{part}.log",
    benchmark:
        "results/benchmarks/sweeps/{sweep}/part-{part}.tsv"
    wildcard_constraints:
        sweep=_alternation(list(SWEEPS)),
        part=r"\d+",
    params:
        name=lambda w: w.sweep,
        part=lambda w: int(w.part),
        sweep_config=lambda w: SWEEPS[w.sweep],
        units=dict(config["units"]),
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    script:
        "../scripts/sweep_part.py"


rule sweep_merge:
    """Join the parts of a sweep into one labelled netCDF file."""
    input:
        parts=lambda w: sweep_parts(w.sweep),
    output:
        "results/sweeps/{sweep}.nc",
    log:
        "logs/sweeps/{sweep}/merge.log",
    wildcard_constraints:
        sweep=_alternation(list(SWEEPS)),
    params:
        name=lambda w: w.sweep,
        sweep_config=lambda w: SWEEPS[w.sweep],
    localrule: True
    script:
        "../scripts/sweep_merge.py"


rule sweeps:
    """Every configured sweep."""
    localrule: True
    input:
        [f"results/sweeps/{name}.nc" for name in SWEEPS],
