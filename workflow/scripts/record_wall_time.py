"""Record the wall time of `make reproduce` (called by the Makefile after the workflow ends):
paper_figures/reproduction_time.md and results/benchmarks/reproduce_wall_time.json.

A run that started without results/ is a reproduction from scratch and replaces the recorded
from-scratch time; any other run is recorded as the latest incremental run (a completed
workflow re-run does nothing and takes seconds). Not a Snakemake rule: it measures the whole
workflow, so it runs after it."""

import argparse
import json
import os
import platform
from datetime import datetime, timezone
from pathlib import Path

from roughcontact import __version__, io


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--seconds", type=float, required=True)
    ap.add_argument("--cores", required=True)
    ap.add_argument("--fresh", choices=("yes", "no"), required=True)
    args = ap.parse_args(argv)
    store = Path("results/benchmarks/reproduce_wall_time.json")
    data = json.loads(store.read_text()) if store.exists() else {}
    entry = {
        "seconds": args.seconds,
        "cores_requested": args.cores,
        "cpu_count": os.cpu_count(),
        "loadavg_after": os.getloadavg(),
        "machine": platform.platform(),
        "commit": io.git_commit(),
        "version": __version__,
        "utc": datetime.now(timezone.utc).replace(microsecond=0).isoformat(),
    }
    data["from_scratch" if args.fresh == "yes" else "latest_incremental"] = entry
    io.write_text(store, json.dumps(data, indent=2, sort_keys=True) + "\n")
    lines = ["# Reproduction wall time", "",
             "Measured by `make reproduce` around the whole Snakemake workflow (goal: ≤ 5 min on 2 cores).", ""]
    for key, title in (("from_scratch", "from scratch (no results/ before the run)"),
                       ("latest_incremental", "latest run with results/ present")):
        if key in data:
            e = data[key]
            lines.append(f"- {title}: **{e['seconds']:.0f} s** with `CORES={e['cores_requested']}` on "
                         f"{e['cpu_count']} CPUs ({e['machine']}), commit `{e['commit'][:12]}`, {e['utc']}")
    io.write_text("paper_figures/reproduction_time.md", "\n".join(lines) + "\n")
    print("\n".join(lines[4:]))


if __name__ == "__main__":
    main()
