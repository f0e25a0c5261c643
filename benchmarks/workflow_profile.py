"""Profile of a whole `make reproduce`: CPU and wall time by job, by rule and by phase, and the
critical path (issue 33).

What it does: runs `make reproduce` (by default after removing results/, paper_figures/, logs/,
.snakemake/ and numba's on-disk cache, i.e. the workflow of a fresh clone; `.venv/` is kept and
its set-up time is measured separately by `make venv` on a fresh clone) with a ``sitecustomize``
hook on PYTHONPATH that makes every Python process of the run append one JSON line at exit
(start and end wall clock, ``os.times()`` CPU of itself and of its waited children, the rule and
outputs of a Snakemake ``script:`` job, the parent's command line of a ``shell:`` job). The jobs
(rule, outputs, inputs, start, end) come from Snakemake's own log; each Python process is
attributed to the job whose outputs or log it names.

CPU seconds are the stable measure on a shared machine (wall time grows with the load of other
processes); the load average at the start and at the end is recorded beside the wall time.

The critical path is the longest chain of dependent jobs, each weighted by its wall time
(from its Python processes where it has any, else from Snakemake's one-second timestamps): no
number of cores makes the run shorter than it.

Output: results/benchmarks/workflow_profile.md (tables) and .csv (one row per job), written
after the run; the raw records in results/benchmarks/workflow_profile.jsonl.

    .venv/bin/python benchmarks/workflow_profile.py            # fresh workflow, then the tables
    .venv/bin/python benchmarks/workflow_profile.py --keep     # no clean (what is left to do only)
    .venv/bin/python benchmarks/workflow_profile.py --analyse-only   # tables from the last run
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from datetime import datetime
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
OUT = REPO / "results" / "benchmarks"

HOOK = r'''
import atexit, json, os, sys, time
_T0 = time.time()
_LOG = os.environ.get("WORKFLOW_PROFILE_LOG")


def _record():
    try:
        t = os.times()
        smk = getattr(sys.modules.get("__main__"), "snakemake", None)
        rec = {"pid": os.getpid(), "ppid": os.getppid(), "start": _T0, "end": time.time(),
               "cpu_self": t.user + t.system, "cpu_children": t.children_user + t.children_system,
               "argv": sys.argv[:6]}
        if smk is not None and hasattr(smk, "rule"):
            rec["rule"] = smk.rule
            rec["output"] = [str(x) for x in smk.output]
        else:
            try:
                with open(f"/proc/{os.getppid()}/cmdline", "rb") as f:
                    rec["parent"] = f.read().replace(b"\0", b" ").decode(errors="replace")[:4000]
            except OSError:
                pass
        with open(_LOG, "a") as f:
            f.write(json.dumps(rec) + "\n")
    except Exception:
        pass


if _LOG:
    atexit.register(_record)
'''

_STAMP = re.compile(r"^\[(\w{3} \w{3} +\d+ \d\d:\d\d:\d\d \d{4})\]$")
_FIELD = re.compile(r"^    (input|output|log|jobid|wildcards): (.*)$")
_RULE = re.compile(r"^(?:local)?rule (\S+):$")
_FINISHED = re.compile(r"^Finished jobid: (\d+)")


def _stamp(text):
    return datetime.strptime(" ".join(text.split()), "%a %b %d %H:%M:%S %Y").timestamp()


def parse_snakemake_log(path):
    """{jobid: {rule, input, output, log, start, end}} from a Snakemake log (1 s resolution)."""
    jobs, now, current = {}, None, None
    for line in Path(path).read_text(errors="replace").splitlines():
        m = _STAMP.match(line)
        if m:
            now = _stamp(m.group(1))
            continue
        m = _RULE.match(line)
        if m:
            current = {"rule": m.group(1), "input": [], "output": [], "log": [], "start": now, "end": None}
            continue
        m = _FIELD.match(line)
        if m and current is not None:
            key, value = m.groups()
            if key == "jobid":
                jobs[int(value)] = current
            elif key != "wildcards":
                current[key] = [v.strip() for v in value.split(",") if v.strip()]
            continue
        m = _FINISHED.match(line)
        if m and int(m.group(1)) in jobs:
            jobs[int(m.group(1))]["end"] = now
    return jobs


def attribute(jobs, records):
    """Add cpu, t0, t1 (precise wall clock) to each job from the hook's records; return the
    Snakemake process's own record (None if absent)."""
    main = next((r for r in records if r["argv"] and r["argv"][0].endswith("snakemake")), None)
    # a process started by a job's Python process is in that one's children time already
    pids = {r["pid"] for r in records if r is not main}
    top = [r for r in records if r["ppid"] not in pids]
    by_output = {}
    for jid, job in jobs.items():
        for out in job["output"]:
            by_output.setdefault(out, jid)
    for job in jobs.values():
        job.update(cpu=0.0, procs=0, t0=None, t1=None)
    unattributed = []
    for r in top:
        if r is main:
            continue
        jid = None
        if r.get("output"):
            jid = by_output.get(r["output"][0])
        elif r.get("parent"):
            for cand, job in jobs.items():
                names = job["output"] + job["log"]
                if names and any(n in r["parent"] for n in names) and job["start"] is not None \
                        and job["start"] - 2 <= r["start"] <= (job["end"] or r["end"]) + 2:
                    jid = cand
                    break
        if jid is None:
            unattributed.append(r)
            continue
        job = jobs[jid]
        job["cpu"] += r["cpu_self"] + r["cpu_children"]
        job["procs"] += 1
        job["t0"] = r["start"] if job["t0"] is None else min(job["t0"], r["start"])
        job["t1"] = r["end"] if job["t1"] is None else max(job["t1"], r["end"])
    return main, unattributed


def wall(job):
    if job["t0"] is not None:
        return job["t1"] - job["t0"]
    if job["start"] is not None and job["end"] is not None:
        return job["end"] - job["start"]
    return 0.0


def critical_path(jobs):
    """The longest chain of dependent jobs by wall time: [(jobid, wall)], its total."""
    producer = {}
    for jid, job in jobs.items():
        for out in job["output"]:
            producer[out] = jid
    deps = {}
    for jid, job in jobs.items():
        d = set()
        for inp in job["input"]:
            if inp in producer:
                d.add(producer[inp])
            else:  # a file inside a directory output
                d.update(p for o, p in producer.items() if inp.startswith(o.rstrip("/") + "/"))
        d.discard(jid)
        deps[jid] = d
    best = {}

    def longest(jid, stack=()):
        if jid in best:
            return best[jid]
        prev = max(((longest(d, stack + (jid,)), d) for d in deps[jid] if d not in stack),
                   default=((0.0, []), None))
        (length, chain), _ = prev
        best[jid] = (length + wall(jobs[jid]), chain + [jid])
        return best[jid]

    sys.setrecursionlimit(10000)
    ends = [longest(j) for j in jobs]
    return max(ends, default=(0.0, []))


def _label(job):
    out = job["output"][0] if job["output"] else job["rule"]
    return out.replace("results/", "").replace("paper_figures/", "")


def report(run_dir, records_path, meta):
    logs = sorted((run_dir / ".snakemake" / "log").glob("*.snakemake.log"))
    if not logs:
        sys.exit(f"error: no Snakemake log under {run_dir / '.snakemake' / 'log'}: run the workflow first")
    jobs = parse_snakemake_log(logs[-1])
    records = [json.loads(line) for line in Path(records_path).read_text().splitlines() if line.strip()]
    main, unattributed = attribute(jobs, records)
    jobs = {j: job for j, job in jobs.items() if job["rule"] != "all"}
    length, chain = critical_path(jobs)
    rules = {}
    for job in jobs.values():
        r = rules.setdefault(job["rule"], {"jobs": 0, "cpu": 0.0, "wall": 0.0, "max_wall": 0.0})
        r["jobs"] += 1
        r["cpu"] += job["cpu"]
        r["wall"] += wall(job)
        r["max_wall"] = max(r["max_wall"], wall(job))
    job_cpu = sum(j["cpu"] for j in jobs.values())
    first = min((j["t0"] or j["start"]) for j in jobs.values() if (j["t0"] or j["start"]))
    last = max((j["t1"] or j["end"]) for j in jobs.values() if (j["t1"] or j["end"]))
    lines = ["# Profile of `make reproduce` (benchmarks/workflow_profile.py)", ""]
    lines += [f"- {k}: {v}" for k, v in meta.items()]
    if main:
        lines.append(f"- Snakemake process: started {main['start'] - meta.get('t_start', main['start']):.1f} s "
                     f"after make; parse and DAG until the first job: {first - main['start']:.1f} s; "
                     f"its own CPU {main['cpu_self']:.1f} s; CPU of everything it ran "
                     f"{main['cpu_children']:.1f} s")
    lines += [f"- jobs: {len(jobs)} ({sum(1 for j in jobs.values() if j['procs'])} with a Python process); "
              f"CPU of the jobs {job_cpu:.1f} s; first job start to last job end {last - first:.1f} s",
              f"- critical path (longest chain of dependent jobs by wall time): {length:.1f} s",
              f"- Python processes not attributed to a job: {len(unattributed)} "
              f"({sum(r['cpu_self'] + r['cpu_children'] for r in unattributed):.1f} s CPU)", "",
              "## By rule (CPU descending)", "", "| rule | jobs | CPU s | wall s (sum) | longest job s |",
              "|---|---:|---:|---:|---:|"]
    for name, r in sorted(rules.items(), key=lambda kv: -kv[1]["cpu"]):
        lines.append(f"| {name} | {r['jobs']} | {r['cpu']:.1f} | {r['wall']:.1f} | {r['max_wall']:.1f} |")
    lines += ["", "## The 30 largest jobs (CPU)", "", "| job | rule | CPU s | wall s |", "|---|---|---:|---:|"]
    for job in sorted(jobs.values(), key=lambda j: -j["cpu"])[:30]:
        lines.append(f"| {_label(job)} | {job['rule']} | {job['cpu']:.1f} | {wall(job):.1f} |")
    lines += ["", "## Critical path", "", "| job | rule | wall s | starts at s |", "|---|---|---:|---:|"]
    for jid in chain:
        job = jobs[jid]
        lines.append(f"| {_label(job)} | {job['rule']} | {wall(job):.1f} | {(job['t0'] or job['start']) - first:.1f} |")
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "workflow_profile.md").write_text("\n".join(lines) + "\n")
    with open(OUT / "workflow_profile.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["jobid", "rule", "output", "cpu_s", "wall_s", "start_s", "python_processes", "on_critical_path"])
        for jid, job in sorted(jobs.items(), key=lambda kv: (kv[1]["t0"] or kv[1]["start"] or 0)):
            w.writerow([jid, job["rule"], job["output"][0] if job["output"] else "", f"{job['cpu']:.2f}",
                        f"{wall(job):.2f}", f"{(job['t0'] or job['start'] or first) - first:.1f}", job["procs"],
                        int(jid in chain)])
    print("\n".join(lines))


def clean(run_dir):
    """What a fresh clone lacks: the workflow's results and numba's on-disk cache."""
    for name in ("results", "paper_figures", "logs", ".snakemake"):
        shutil.rmtree(run_dir / name, ignore_errors=True)
    for pattern in ("*.nbi", "*.nbc"):
        for path in (run_dir / "src").rglob(pattern):
            path.unlink()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--keep", action="store_true", help="do not clean first (profile what is left to do)")
    ap.add_argument("--analyse-only", action="store_true", help="only the tables, from the last run's records")
    ap.add_argument("--target", default="reproduce", help="make target to run (default: reproduce)")
    args = ap.parse_args(argv)
    records = REPO / ".snakemake" / "workflow_profile.jsonl"
    meta = {}
    if not args.analyse_only:
        if not args.keep:
            clean(REPO)
        (REPO / ".snakemake").mkdir(exist_ok=True)
        records.unlink(missing_ok=True)
        hook = Path(tempfile.mkdtemp(prefix="workflow_profile_"))
        (hook / "sitecustomize.py").write_text(HOOK)
        env = dict(os.environ, WORKFLOW_PROFILE_LOG=str(records),
                   PYTHONPATH=os.pathsep.join([str(hook)] + [p for p in [os.environ.get("PYTHONPATH")] if p]))
        load0 = Path("/proc/loadavg").read_text().split()[:3]
        t0 = time.time()
        ru0 = os.times()
        print(f"running make {args.target} (load {' '.join(load0)}) ...", file=sys.stderr)
        rc = subprocess.call(["make", args.target], cwd=REPO, env=env)
        t1 = time.time()
        ru1 = os.times()
        load1 = Path("/proc/loadavg").read_text().split()[:3]
        shutil.rmtree(hook, ignore_errors=True)
        meta = {"command": f"make {args.target}" + (" (after removing results and the numba cache)" if not args.keep else ""),
                "exit status": rc, "wall s": f"{t1 - t0:.1f}",
                "CPU s (every process of the run)": f"{(ru1.children_user + ru1.children_system) - (ru0.children_user + ru0.children_system):.1f}",
                "cores": os.cpu_count(), "load average at start (1, 5, 15 min)": " ".join(load0),
                "load average at end": " ".join(load1), "date": datetime.now().isoformat(timespec="seconds")}
        (OUT).mkdir(parents=True, exist_ok=True)
        (OUT / "workflow_profile.meta.json").write_text(json.dumps(dict(meta, t_start=t0), indent=1))
    else:
        path = OUT / "workflow_profile.meta.json"
        meta = json.loads(path.read_text()) if path.exists() else {}
    report(REPO, records, meta)


if __name__ == "__main__":
    main()
