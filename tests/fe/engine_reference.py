"""Runs of the beam (example 9.1) and the punch (example 9.2) whose results are recorded in
tests/fe/data/engine_reference.json, to hold the FE engine's results fixed while its linear
solvers, assembly and Newton loop change (issue 23: "unchanged to round-off, 1e-9").

The values were written by the engine as it was before issue 23 (commit 6539136):

    .venv/bin/python tests/fe/engine_reference.py --write

tests/fe/test_engine_reference.py re-runs them and compares.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

DATA = Path(__file__).resolve().parent / "data" / "engine_reference.json"
SURFACE = {"m20": 8.0e-5, "m02": 8.0e-4, "m40": 1.04e-6, "m04": 1.04e-4}
BEAM_SPEC = {"n_x": 25, "n_z": 6, "z_ratio": 4.0, "increments": 16, "load": 1962.0, "initial_load": 4.9}

#: name → (kind, run dict of beam_case / punch_case); "fast": in the fast tier
RUNS = {
    "beam-quadratic-1-free": ("beam", {"family": "quadratic", "m00": 0.625, "law": "elastic", "tangential": "free"}),
    "beam-cubic-1-free": ("beam", {"family": "cubic", "m00": 0.625, "law": "elastic", "tangential": "free"}),
    "beam-quadratic-3-coulomb": ("beam", {"family": "quadratic", "m00": 0.0625, "law": "elastic",
                                          "tangential": "coulomb", "mu": 0.1}),
    "beam-quadratic-4-elastoplastic": ("beam", {"family": "quadratic", "m00": 0.625, "law": "elastoplastic",
                                                "psi": 0.35, "tangential": "free"}),
    "punch-quadratic-b": ("punch", {"case": "b", "geometry": {"family": "quadratic"}}),
    "punch-cubic-c": ("punch", {"case": "c", "geometry": {"family": "cubic"}}),
}
FAST = ("beam-quadratic-1-free",)
#: in the slow tier (the other recorded runs are for `engine_reference.py` by hand: all agreed
#: to ≤ 3e-13 when issue 23 was merged)
SLOW = ("beam-quadratic-3-coulomb", "punch-quadratic-b")


def run(name: str) -> dict:
    """The recorded quantities of one run (lists of floats)."""
    kind, extra = RUNS[name]
    if kind == "beam":
        from roughcontact.fe.beam import beam_case

        r = beam_case({"case": "x", "E_star": 1.057e5 / 0.9375, "psi": 0.35, "surface": SURFACE,
                       "spec": BEAM_SPEC, **extra})
        sol = r.solution
        return {"u_N_um": r.u_N_um.tolist(), "p_N": r.p_N.tolist(),
                "u_final": sol.final.u[::11].tolist(),  # a sample of the dofs
                "tractions_final": sol.final.tractions.ravel().tolist(),
                "newton_iterations": r.newton_iterations.tolist()}
    from roughcontact.fe.punch import dissipation, punch_case

    r = punch_case({"m00": 0.625, "surface": SURFACE, "law": "elastoplastic", "psi": 0.35, **extra})
    sol = r.solution
    return {"state_max": r.max_increment.state.ravel().tolist(),
            "state_end": sol.final.state.ravel().tolist(),
            "u_max": r.max_increment.u[::11].tolist(),
            "dissipation": [dissipation(r, at=a, weight=w) for a in ("max", "end") for w in ("area", "work")],
            "newton_iterations": [int(i.iterations) for i in sol.increments]}


def compare(recorded: dict, now: dict) -> dict[str, float]:
    """The largest difference of every quantity relative to its largest recorded magnitude."""
    out = {}
    for key, ref in recorded.items():
        if key == "newton_iterations":
            continue
        a, b = np.asarray(ref, dtype=float), np.asarray(now[key], dtype=float)
        out[key] = float(np.max(np.abs(a - b)) / max(np.max(np.abs(a)), 1e-300))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="record the values of this engine")
    ap.add_argument("runs", nargs="*", default=list(RUNS))
    args = ap.parse_args(argv)
    if args.write:
        DATA.parent.mkdir(exist_ok=True)
        DATA.write_text(json.dumps({name: run(name) for name in args.runs}) + "\n")
        return 0
    recorded = json.loads(DATA.read_text())
    for name in args.runs:
        now = run(name)
        print(name, compare(recorded[name], now),
              "iterations", recorded[name]["newton_iterations"] == now["newton_iterations"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
