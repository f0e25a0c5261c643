"""`make bench-fe`: the block-on-base deck (benchmarks/block_on_base.py) refined 1×, 2×, 3× in
CalculiX (ccx, the exported pressure–overclosure table) and in roughcontact's engine (the
statistical law itself): dofs, wall time, CPU time, peak memory, increments and Newton
iterations per code and size, with the machine's load average before and after every run.

    .venv/bin/python benchmarks/fe_block_on_base.py [--refine 1 2 3] [--codes ccx engine]
        [--engine auto|cli|api] [--out results/benchmarks/fe_block_on_base] [--ccx-timeout 7200]

The engine runs the deck through ``roughcontact fe run MODEL.inp --interface LAW.yaml --json``
(issue 23) when that command exists ("cli"; "auto" picks it when ``roughcontact fe run --help``
works), otherwise the same geometry through the API (`box`, `merge`, `interface_between`:
"api"), each run in a fresh process, as ccx is: the wall time is everything a user waits for
(start-up, the law's table, assembly, the solve). Without ccx on PATH its rows say so and the
engine still runs. Writes <out>/results.json and <out>/results.md; the decks and law files
stay in <out>/decks/ (complete examples in both codes' input).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import block_on_base as bob  # noqa: E402

CODES = ("ccx", "engine")


def law_yaml(problem: bob.BlockOnBase) -> str:
    """LAW.yaml (issue 23's schema) of the deck's interaction ROUGH."""
    m = {k: f"{v:.6e}" for k, v in bob.MOMENTS.items()}  # "8.000000e-05": a float in YAML 1.1 too
    return (
        "length_unit: mm\n"
        "interactions:\n"
        "  ROUGH:\n"
        f"    moments: {{m00: {m['m00']}, m20: {m['m20']}, m02: {m['m02']}, m40: {m['m40']}, "
        f"m04: {m['m04']}, unit: um}}\n"
        "    lay_direction: [1, 0, 0]\n"
        f"    E_star: {problem.E_star!r}\n"
        "    law: elastic\n"
        f"    seating_pressure: {bob.SEATING_PRESSURE!r}\n"
        "    friction: none\n")


def write_inputs(problem: bob.BlockOnBase, directory: Path) -> tuple[Path, Path]:
    """The deck and the law file of one refinement."""
    directory.mkdir(parents=True, exist_ok=True)
    deck = directory / f"block_on_base_{problem.refine}x.inp"
    law = directory / "LAW.yaml"
    deck.write_text(bob.calculix_deck(problem, bob.calculix_table(problem)))
    law.write_text(law_yaml(problem))
    return deck, law


def _load() -> float:
    return round(os.getloadavg()[0], 2)


def measure(cmd, cwd, timeout: float, env=None) -> dict:
    """Run ``cmd`` in ``cwd``: its wall and CPU seconds and peak RSS [MB] (os.wait4: this child
    alone), exit code (None after ``timeout`` s: killed), standard output (the JSON of the
    engine's runs) and the tail of standard error, the load before and after."""
    load_before = _load()
    killed = []
    with tempfile.TemporaryFile("w+") as log, tempfile.TemporaryFile("w+") as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=log, stderr=err, text=True, env=env)
        timer = threading.Timer(timeout, lambda: (killed.append(True), proc.kill()))
        timer.start()
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        timer.cancel()
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
        log.seek(0)
        err.seek(0)
        out, stderr = log.read(), err.read()
    return {"exit": None if killed else proc.returncode, "timeout": timeout if killed else None,
            "wall_s": wall, "cpu_s": usage.ru_utime + usage.ru_stime, "peak_rss_mb": usage.ru_maxrss / 1024.0,
            "output": out, "stderr": stderr[-1000:], "load_before": load_before, "load_after": _load()}


# ---------------------------------------------------------------------------------------------
# CalculiX
# ---------------------------------------------------------------------------------------------
def parse_sta(text: str) -> dict:
    """Increments (converged), attempts and Newton iterations (all attempts) of a ccx .sta file."""
    rows = [line.split() for line in text.splitlines() if re.match(r"\s+\d+\s+\d+\s+\d+U?\s+\d+\s", line)]
    converged = [r for r in rows if not r[2].endswith("U")]
    return {"increments": len(converged), "attempts": len(rows), "cutbacks": len(rows) - len(converged),
            "newton_iterations": sum(int(r[3]) for r in rows)}


def run_ccx(problem, deck: Path, timeout: float) -> dict:
    exe = shutil.which("ccx")
    if exe is None:
        return {"code": "ccx", "skipped": "ccx is not installed (Debian/Ubuntu: apt-get install calculix-ccx)"}
    env = {**os.environ, "OMP_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1"}
    row = measure([exe, deck.stem], deck.parent, timeout, env)
    row.update(code="ccx", dofs=bob.deck_dofs(problem))
    sta = deck.with_suffix(".sta")
    if sta.exists():
        row.update(parse_sta(sta.read_text()))
    dat = deck.with_suffix(".dat")
    if row["exit"] == 0 and dat.exists():
        row["mean_uz_block_bottom_mm"] = _ccx_mean_uz(dat.read_text())
    row["output"] = row["output"][-500:]
    return row


def _ccx_mean_uz(dat: str) -> float:
    from roughcontact.paper.calculix import node_prints

    prints = node_prints(dat, "BLOCKBOTTOM")
    rows = prints[-1][1]
    return float(sum(u[2] for u in rows.values()) / len(rows))


# ---------------------------------------------------------------------------------------------
# the engine
# ---------------------------------------------------------------------------------------------
def cli_available() -> bool:
    """``roughcontact fe run`` exists (issue 23's deck command)."""
    exe = shutil.which("roughcontact") or str(Path(sys.executable).with_name("roughcontact"))
    try:
        return subprocess.run([exe, "fe", "run", "--help"], capture_output=True, timeout=120).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


def run_engine(problem, deck: Path, law: Path, how: str, timeout: float) -> dict:
    if how == "cli":
        exe = shutil.which("roughcontact") or str(Path(sys.executable).with_name("roughcontact"))
        row = measure([exe, "fe", "run", deck.name, "--interface", law.name, "--json"], deck.parent, timeout)
        if row["exit"] == 0:
            out = json.loads(row["output"][row["output"].index("{"):])
            last = out["steps"][-1]
            bottom = np.array(last["node_sets"]["BLOCKBOTTOM"]["u"], dtype=float)
            row.update(dofs=out["dofs"], interface_points=out["interface_points"], solve_s=out["seconds"],
                       newton_iterations=out["newton_iterations"], cutbacks=out["cutbacks"],
                       increments=sum(s["increments"] for s in out["steps"]),
                       max_p_N=float(np.max(last["interface"]["p_N"])),
                       mean_uz_block_bottom_mm=float(np.mean(bottom[:, 2])))
    else:
        row = measure([sys.executable, str(Path(__file__).resolve()), "--engine-child", str(problem.refine)],
                      deck.parent, timeout)
        if row["exit"] == 0:
            row.update(json.loads(row["output"].strip().splitlines()[-1]))
    row.update(code="engine", path=how)
    row["output"] = row["output"][-500:]
    return row


def engine_child(refine: int) -> int:
    """One engine run through the API (in its own process); prints one JSON line."""

    from roughcontact.fe.solver import NewtonOptions, linear_strategy, solve

    t0 = time.perf_counter()
    problem = bob.BlockOnBase(refine=refine)
    mesh, model = bob.engine_model(problem)
    t1 = time.perf_counter()
    sol = solve(model, problem.levels, NewtonOptions())
    t2 = time.perf_counter()
    bottom = mesh.node_sets["block.contact"]
    print(json.dumps({
        "dofs": int(3 * mesh.n_nodes), "free_dofs": model.n_dofs, "interface_points": model.points.n_points,
        "strategy": linear_strategy(model), "setup_s": t1 - t0, "solve_s": t2 - t1,
        "increments": len(sol.increments), "cutbacks": int(sum(i.cutbacks for i in sol.increments)),
        "newton_iterations": int(sum(i.iterations for i in sol.increments)),
        "max_p_N": float(np.max(-sol.final.tractions[:, 2])),
        "mean_uz_block_bottom_mm": float(np.mean(sol.final.u.reshape(-1, 3)[bottom, 2]))}))
    return 0


# ---------------------------------------------------------------------------------------------
# report
# ---------------------------------------------------------------------------------------------
def render(rows, machine) -> str:
    lines = ["# FE benchmark: block on base, CalculiX against roughcontact", "",
             f"{machine['cpu']}, {machine['cores']} cores; every run in its own process, one thread "
             "(ccx: OMP_NUM_THREADS=1, its default SPOOLES solver; the engine: one BLAS thread). "
             "Wall time is what a user waits for (start-up, table, assembly, solve); the load "
             "average (1 min) before and after each run says how busy the shared machine was.", "",
             "| refine | code | dofs | wall [s] | CPU [s] | peak RSS [MB] | increments | cut-backs | Newton iterations "
             "| mean u_z block bottom [µm] | load before/after |",
             "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        if "skipped" in r:
            lines.append(f"| {r['refine']} | {r['code']} | – | skipped: {r['skipped']} | | | | | | | |")
            continue
        status = "" if r.get("exit") == 0 else (" (timeout)" if r.get("timeout") else f" (exit {r.get('exit')})")
        uz = r.get("mean_uz_block_bottom_mm")
        lines.append(
            f"| {r['refine']} | {r['code']}{' (' + r['path'] + ')' if 'path' in r else ''}{status} | {r.get('dofs', '–')} "
            f"| {r['wall_s']:.1f} | {r.get('cpu_s', float('nan')):.1f} | {r.get('peak_rss_mb', float('nan')):.0f} "
            f"| {r.get('increments', '–')} | {r.get('cutbacks', '–')} | {r.get('newton_iterations', '–')} "
            f"| {'–' if uz is None else f'{1000 * uz:.4f}'} | {r['load_before']} / {r['load_after']} |")
    by = {(r["refine"], r["code"]): r for r in rows if "skipped" not in r and r.get("exit") == 0}
    speed = [f"{k}×: {by[(k, 'ccx')]['wall_s'] / by[(k, 'engine')]['wall_s']:.1f}× (wall), "
             f"{by[(k, 'ccx')]['cpu_s'] / by[(k, 'engine')]['cpu_s']:.1f}× (CPU)"
             for k in sorted({r['refine'] for r in rows}) if (k, "ccx") in by and (k, "engine") in by]
    if speed:
        lines += ["", "engine faster than ccx by " + "; ".join(speed) + "."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--refine", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--codes", nargs="+", choices=CODES, default=list(CODES))
    ap.add_argument("--engine", choices=("auto", "cli", "api"), default="auto")
    ap.add_argument("--out", type=Path, default=Path("results/benchmarks/fe_block_on_base"))
    ap.add_argument("--ccx-timeout", type=float, default=7200.0)
    ap.add_argument("--engine-timeout", type=float, default=3600.0)
    ap.add_argument("--engine-child", type=int, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.engine_child is not None:
        return engine_child(args.engine_child)
    from machine import info

    how = args.engine if args.engine != "auto" else ("cli" if cli_available() else "api")
    # rows of earlier runs into the same --out are kept unless re-measured (runs can be split)
    previous = args.out / "results.json"
    rows = json.loads(previous.read_text())["rows"] if previous.exists() else []
    for refine in sorted(args.refine):
        problem = bob.BlockOnBase(refine=refine)
        deck, law = write_inputs(problem, (args.out / "decks").resolve())
        for code in args.codes:
            row = run_ccx(problem, deck, args.ccx_timeout) if code == "ccx" else \
                run_engine(problem, deck, law, how, args.engine_timeout)
            row["refine"] = refine
            rows = [r for r in rows if (r["refine"], r["code"]) != (refine, code)] + [row]
            print(json.dumps({k: v for k, v in row.items() if k != "output"}), flush=True)
    machine = info()
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "results.json").write_text(json.dumps({"machine": machine, "rows": rows}, indent=1) + "\n")
    rows.sort(key=lambda r: (r["refine"], CODES.index(r["code"])))
    (args.out / "results.md").write_text(render(rows, machine))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
