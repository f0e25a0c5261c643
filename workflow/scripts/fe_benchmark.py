"""Speed and size of the FE runs (rule fe_benchmark): each run's dofs, interface points, Newton
iterations and solve time (from its netCDF file), and each job's wall time, CPU time and peak
memory (from Snakemake's benchmark TSV), for the beam (example 9.1) and the punch (9.2);
paper_figures/fe_benchmark.md and a JSON copy."""

import csv
import json
import os
import platform
from pathlib import Path

from roughcontact import io
from roughcontact.paper import fe_speed


def _tsv(path):
    with open(path) as fh:
        return next(csv.DictReader(fh, delimiter="\t"))


def _cpu():
    try:
        return next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor() or platform.machine()


def run(examples, out, summary, log):
    with io.log_to(log):
        sections, jobs = {}, []
        for title, ex in examples.items():
            rows = []
            for name, nc in ex["paths"].items():
                ds = io.read_netcdf(nc)
                rows.append(fe_speed.run_row(name, ds.attrs, ds["newton_iterations"].values))
            sections[title] = {"rows": rows, "main": ex["main"], "goal": ex["goal"], "what": ex["what"]}
            for tsv in ex["tsv"]:
                bench, job = _tsv(tsv), Path(tsv).stem
                jobs.append({"job": job, "example": title, "runs": sum(r["run"].startswith(job + "-") for r in rows),
                             "wall_s": float(bench["s"]), "cpu_s": float(bench["cpu_time"]),
                             "max_rss_mb": float(bench["max_rss"])})
        machine = {"cpu": _cpu(), "cores": os.cpu_count(), "loadavg": [round(x, 2) for x in os.getloadavg()]}
        io.write_text(out, fe_speed.render_benchmark_markdown(sections, jobs, machine))
        io.write_text(summary, json.dumps({"machine": machine, "examples": sections, "jobs": jobs}, indent=1))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.examples, sm.output.md, sm.output.json, sm.log[0])
