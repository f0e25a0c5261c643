"""FE linear solvers on the beam of example 9.1: full sparse refactorisation (SuperLU) against
the bulk condensed onto the interface dofs, on meshes from coarse to twice the main one.

    .venv/bin/python benchmarks/fe_linear_solvers.py [--repeat 3] [--out results/benchmarks]

Both strategies solve the same Newton iterations (the displacements agree to round-off, checked
here); the wall time of the whole solve (median of --repeat runs, interleaved) is what differs.
Writes fe_linear_solvers.json and .md under --out, with the machine's load average.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from machine import info  # noqa: E402

from roughcontact import SpectralMoments  # noqa: E402
from roughcontact.examples.beam import BeamRun, BeamSpec, run_beam  # noqa: E402
from roughcontact.fe.solver import NewtonOptions  # noqa: E402

MESHES = [("quadratic", 12, 3), ("cubic", 12, 3), ("quadratic", 25, 6), ("cubic", 25, 6),
          ("quadratic", 50, 12), ("cubic", 50, 12)]
SOLVERS = ("sparse", "condensed")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", type=Path, default=Path("results/benchmarks"))
    args = ap.parse_args(argv)
    surface = SpectralMoments(0.625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    rows = []
    for family, nx, nz in MESHES:
        run = BeamRun(spec=BeamSpec(elements=family, n_x=nx, n_z=nz), m00=surface.m00)  # E* = 1.057e5/0.9375
        times = {s: [] for s in SOLVERS}
        results = {}
        for _ in range(args.repeat):
            for solver in SOLVERS:  # interleaved: a load change hits both
                r = run_beam(run, options=NewtonOptions(linear_solver=solver))
                times[solver].append(r.seconds)
                results[solver] = r
        diff = abs(results["sparse"].u_N_um - results["condensed"].u_N_um).max()
        row = {"family": family, "n_x": nx, "n_z": nz, "dofs": results["sparse"].n_dofs,
               "interface_points": results["sparse"].n_points,
               "newton_iterations": int(results["sparse"].newton_iterations.sum()),
               **{f"{s}_s": statistics.median(times[s]) for s in SOLVERS}, "max_diff_um": float(diff)}
        rows.append(row)
        print(json.dumps(row), flush=True)
    machine = info()
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "fe_linear_solvers.json").write_text(json.dumps({"machine": machine, "rows": rows}, indent=1))
    lines = ["# FE linear solvers (beam of example 9.1, m00 = 0.625, elastic, free sliding)", "",
             f"{machine['cpu']}, {machine['cores']} cores, load average {machine['loadavg']}; median of "
             f"{args.repeat} interleaved runs of the whole solve (17 load levels).", "",
             "| elements | n_x × n_z | dofs | interface points | Newton iterations | sparse [s] | condensed [s] | "
             "condensed/sparse | max |Δu_N| [µm] |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['family']} | {r['n_x']} × {r['n_z']} | {r['dofs']} | {r['interface_points']} "
                     f"| {r['newton_iterations']} | {r['sparse_s']:.2f} | {r['condensed_s']:.2f} "
                     f"| {r['condensed_s'] / r['sparse_s']:.2f} | {r['max_diff_um']:.1e} |")
    (args.out / "fe_linear_solvers.md").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
