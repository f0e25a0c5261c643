"""Record the wall time of `make reproduce` (called by the Makefile, not a Snakemake rule: it
measures the whole workflow, so it runs after it), and of the environment's set-up before it.

    record_wall_time.py setup --make-start T --created yes|no --load-start "L1 L5 L15" --out .venv/.setup.json
        after `make` created .venv/ and installed into it: the seconds since make started
    record_wall_time.py --seconds S --cores N --fresh yes|no [--setup .venv/.setup.json --make-start T --load-start L]
        after the workflow: paper_figures/reproduction_time.md and results/benchmarks/reproduce_wall_time.json

A run that started without results/ is a reproduction from scratch and replaces the recorded
from-scratch time; any other run is recorded as the latest incremental run (a completed
workflow re-run does nothing and takes seconds). When the same `make` also created .venv/ (a
fresh clone), the set-up time is part of the entry and of the total — the time a new user
waits for `make reproduce` — with the load average at make's start and at the end."""

import argparse
import json
import os
import platform
import time
from datetime import datetime, timezone
from pathlib import Path

from roughcontact import __version__, io


def _setup(args):
    entry = {"seconds": round(time.time() - args.make_start, 1), "make_start": args.make_start,
             "created_venv": args.created == "yes", "python": platform.python_version(),
             "loadavg_before": args.load_start, "loadavg_after": " ".join(f"{x:.2f}" for x in os.getloadavg()),
             "utc": datetime.now(timezone.utc).replace(microsecond=0).isoformat()}
    io.write_text(args.out, json.dumps(entry, indent=2) + "\n")
    print(f"environment set up in {entry['seconds']:.0f} s" + (" (.venv/ created)" if entry["created_venv"] else ""))


def _setup_of_this_make(path, make_start):
    """The set-up entry if this same `make` created .venv/ (else None)."""
    if not path or not Path(path).exists():
        return None
    setup = json.loads(Path(path).read_text())
    return setup if setup.get("created_venv") and abs(setup.get("make_start", 0) - make_start) < 1e-3 else None


def _line(title, e):
    text = (f"- {title}: **{e['seconds']:.0f} s** for the workflow with `CORES={e['cores_requested']}` on "
            f"{e['cpu_count']} CPUs ({e['machine']}), commit `{e['commit'][:12]}`, {e['utc']}, load average "
            f"{e.get('loadavg_start') or '?'} at the start, {' '.join(f'{x:.2f}' for x in e['loadavg_after'])} at the end")
    if e.get("setup_seconds") is not None:
        text += (f"; with creating `.venv/` and installing ({e['setup_seconds']:.0f} s, Python {e['python']}) "
                 f"**{e['total_seconds']:.0f} s** from `make reproduce` to the end")
    return text


def main(argv=None):
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="command")
    setup = sub.add_parser("setup")
    setup.add_argument("--make-start", type=float, required=True)
    setup.add_argument("--created", choices=("yes", "no"), required=True)
    setup.add_argument("--load-start", default="")
    setup.add_argument("--out", required=True)
    ap.add_argument("--seconds", type=float)
    ap.add_argument("--cores")
    ap.add_argument("--fresh", choices=("yes", "no"))
    ap.add_argument("--setup", default="", help="the .setup.json of `make` (set-up time of .venv/)")
    ap.add_argument("--make-start", type=float, default=0.0)
    ap.add_argument("--load-start", default="")
    args = ap.parse_args(argv)
    if args.command == "setup":
        return _setup(args)
    if args.seconds is None or args.cores is None or args.fresh is None:
        ap.error("--seconds, --cores and --fresh are required")
    store = Path("results/benchmarks/reproduce_wall_time.json")
    data = json.loads(store.read_text()) if store.exists() else {}
    entry = {
        "seconds": args.seconds,
        "cores_requested": args.cores,
        "cpu_count": os.cpu_count(),
        "loadavg_start": args.load_start,
        "loadavg_after": os.getloadavg(),
        "machine": platform.platform(),
        "commit": io.git_commit(),
        "version": __version__,
        "utc": datetime.now(timezone.utc).replace(microsecond=0).isoformat(),
    }
    setup = _setup_of_this_make(args.setup, args.make_start)
    if setup is not None:
        entry.update(setup_seconds=setup["seconds"], python=setup["python"],
                     total_seconds=round(time.time() - args.make_start, 1))
    data["from_scratch" if args.fresh == "yes" else "latest_incremental"] = entry
    io.write_text(store, json.dumps(data, indent=2, sort_keys=True) + "\n")
    lines = ["# Reproduction wall time", "",
             "Measured by `make reproduce` around the whole Snakemake workflow, and, where the same `make` "
             "created `.venv/` (a fresh clone), from its start (goal: ≤ 5 min on 2 cores).", ""]
    for key, title in (("from_scratch", "from scratch (no results/ before the run)"),
                       ("latest_incremental", "latest run with results/ present")):
        if key in data:
            lines.append(_line(title, data[key]))
    io.write_text("paper_figures/reproduction_time.md", "\n".join(lines) + "\n")
    print("\n".join(lines[4:]))


if __name__ == "__main__":
    main()
