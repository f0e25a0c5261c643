# Speed against error (benchmarks/, issue 5): the benchmark suite as one job that takes every
# core, so that no other job runs while it times (timings on a loaded machine are meaningless).
# `benchmark_mode: quick` in the workflow (a few minutes; CI), `make bench` runs the full mode.

BENCH_MODE = config.get("benchmark_mode", "quick")
BENCH_QUICK = BENCH_MODE in ("quick", "ci")
# (not the workflow's own profiler, benchmarks/workflow_profile.py: it times the workflow, not the integrators)
BENCH_SOURCES = [code_fingerprint(p) for p in sorted((REPO / "benchmarks").glob("*.py")) if p.name != "workflow_profile.py"]


def _every_core(wildcards):
    """All cores of a local run. Evaluated only when the job is scheduled, so that a cluster run
    (--jobs, no --cores) of other targets does not need --cores; there the job asks for one."""
    from snakemake.exceptions import WorkflowError

    try:
        return workflow.cores
    except WorkflowError:
        return 1


rule speed_vs_error:
    """Time and error of every integrator at representative points, and the throughput of an
    m00 × ψ × s sweep (sub-grid, extrapolated to 10⁶ points); figure, report, data."""
    input:
        lib=PHYSICS_SOURCES,
        code=BENCH_SOURCES,
        kernels=KERNELS_WARM,  # it times the kernels, never their compilation (numba_warmup did that)
    output:
        png="paper_figures/speed_vs_error.png",
        pdf="paper_figures/speed_vs_error.pdf",  # vector, beside the PNG (plots.style.save)
        md="paper_figures/speed_vs_error.md",
        data="results/benchmarks/speed_vs_error/results.nc",
        sweep="results/benchmarks/sweep_throughput/results.json",
    log:
        "logs/benchmarks/speed_vs_error.log",
    benchmark:
        "results/benchmarks/rules/speed_vs_error.tsv"
    params:
        # quick (the reproduction) and ci: fewer points, no cold-compile probe (two fresh processes
        # compiling every kernel, ~1 min of CPU that measures numba, not the integrators); full:
        # everything (`make bench`)
        mode={"ci": "--quick --no-compile-probe", "quick": "--quick --no-compile-probe"}.get(BENCH_MODE, ""),
        out_dir="results/benchmarks/speed_vs_error",
        # sub-grid of the sweep timed (m00 × ψ combinations, 400 s each), extrapolated to 10⁶ points
        sweep_grid="--m00 3 --psi 3" if BENCH_QUICK else "--m00 5 --psi 5",
    threads: _every_core
    shell:
        "python benchmarks/sweep_throughput.py {params.sweep_grid} --json {output.sweep} > {log} 2>&1 && "
        "python benchmarks/speed_vs_error.py --out-dir {params.out_dir} --figure {output.png} "
        "--report {output.md} {params.mode} >> {log} 2>&1"
