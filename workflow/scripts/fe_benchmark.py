"""Speed and size of the beam runs (rule fe_benchmark): each run's dofs, interface points,
Newton iterations and solve time (from its netCDF file), and each job's wall time, CPU time and
peak memory (from Snakemake's benchmark TSV); paper_figures/fe_benchmark.md."""

import csv
import json
import os
import platform
from pathlib import Path

from roughcontact import io
from roughcontact.paper import fe_beam


def _tsv(path):
    with open(path) as fh:
        return next(csv.DictReader(fh, delimiter="\t"))


def _cpu():
    try:
        return next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor() or platform.machine()


def run(paths, tsv_paths, out, summary, log):
    with io.log_to(log):
        rows = []
        for name, nc in paths.items():
            ds = io.read_netcdf(nc)
            its = [int(i) for i in ds["newton_iterations"].values]
            rows.append({"run": name, "dofs": int(ds.attrs["dofs"]), "interface_points": int(ds.attrs["interface_points"]),
                         "iterations": its, "iterations_total": sum(its), "seconds": float(ds.attrs["seconds"])})
        jobs = []
        for tsv in tsv_paths:
            bench = _tsv(tsv)
            jobs.append({"job": Path(tsv).stem, "runs": sum(r["run"].startswith(Path(tsv).stem + "-") for r in rows),
                         "wall_s": float(bench["s"]), "cpu_s": float(bench["cpu_time"]),
                         "max_rss_mb": float(bench["max_rss"])})
        machine = {"cpu": _cpu(), "cores": os.cpu_count(), "loadavg": [round(x, 2) for x in os.getloadavg()]}
        io.write_text(out, fe_beam.render_benchmark_markdown(rows, jobs, machine))
        io.write_text(summary, json.dumps({"machine": machine, "runs": rows, "jobs": jobs}, indent=1))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.paths, list(sm.input.tsv), sm.output.md, sm.output.json, sm.log[0])
