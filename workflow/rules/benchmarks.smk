# Speed against error (benchmarks/, issue 5): the benchmark suite as one job that takes every
# core, so that no other job runs while it times (timings on a loaded machine are meaningless).
# `benchmark_mode: quick` in the workflow (a few minutes; CI), `make bench` runs the full mode.
import sys

BENCH_SOURCES = sorted(str(p) for p in (REPO / "benchmarks").glob("*.py"))


rule speed_vs_error:
    """Time and error of every integrator at representative points; figure, report, data."""
    input:
        lib=PHYSICS_SOURCES,
        code=BENCH_SOURCES,
    output:
        png="paper_figures/speed_vs_error.png",
        md="paper_figures/speed_vs_error.md",
        data="results/benchmarks/speed_vs_error/results.nc",
    log:
        "logs/benchmarks/speed_vs_error.log",
    benchmark:
        "results/benchmarks/rules/speed_vs_error.tsv"
    params:
        py=sys.executable,
        mode=lambda w: "--quick" if config.get("benchmark_mode", "quick") == "quick" else "",
        out_dir="results/benchmarks/speed_vs_error",
    threads: workflow.cores
    shell:
        "{params.py} benchmarks/speed_vs_error.py --out-dir {params.out_dir} --figure {output.png} "
        "--report {output.md} {params.mode} > {log} 2>&1"
