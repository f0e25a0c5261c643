"""Large contact interfaces (issue 31): a plate on a base with full-face contact, run through
``roughcontact fe run --solver S`` for each linear strategy of roughcontact.fe.solver.

    .venv/bin/python benchmarks/fe_large_interface.py [--sizes 16x2x4 24x3x5] [--solvers ...]
        [--friction] [--timeout 900] [--ccx] [--ccx-timeout 1800] [--out results/benchmarks]

The deck (CalculiX/Abaqus syntax, C3D20, mm, N): a steel plate 60 × 60 × 10 mm on a cast-iron
base 60 × 60 × 20 mm (the plate's bottom on the base's top over the whole face, node for node);
size NxAxB = N × N elements in plan, A layers through the plate, B through the base, or
NXxNYxAxB for NX × NY in plan (60 × 60·NY/NX mm; 24x32x8x12 is issue 31's acceptance size:
209 022 dofs, 2417 contact nodes; 12x16x4x6 its half refinement, 29 418 dofs). The nodes of
the loaded faces are the NSET LOADED; their mean u_z is ``loaded_mean_uz_mm`` in the output. The base
is held at its bottom, the plate's top in its plane (u_x = u_y = 0) and pressed by 12 N/mm² on
its third x ≥ 40 mm (an eccentric load). The interface: the statistical law of
benchmarks/block_on_base.py (elastic, seated at 1e-3 N/mm²), frictionless or with ``--friction``
Coulomb friction (μ = 0.2, k_T/k_N = 0.7: an unsymmetric tangent where points slip). 10 equal
increments. Each run is a child process: wall and CPU time and peak RSS from os.wait4, the
load average before and after (benchmarks/fe_block_on_base.py ``measure``). With ``--ccx`` each
size also runs in CalculiX with the same law (``roughcontact ccx run``, issue 30: the law as a
user element; 2 threads, as the engine's PARDISO), stopped after --ccx-timeout seconds; skipped
with a note when ``roughcontact ccx build`` has not been run. Writes fe_large_interface.json and
.md under --out.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import block_on_base as bob  # noqa: E402
from fe_block_on_base import measure  # noqa: E402
from machine import info  # noqa: E402

from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines  # noqa: E402

SOLVERS = ("sparse-krylov", "condensed-krylov", "sparse", "condensed")
PLAN, PLATE_T, BASE_T = 60.0, 10.0, 20.0  # mm
PRESSURE = 12.0  # N/mm² on the third x ≥ 40 mm of the plate's top
INCREMENTS = 10


def parse_size(size: str) -> tuple[int, int, int, int]:
    """NxAxB (N × N in plan) or NXxNYxAxB (NX × NY in plan) → (NX, NY, A, B)."""
    v = [int(x) for x in size.split("x")]
    if len(v) == 3:
        v = [v[0], v[0], v[1], v[2]]
    if len(v) != 4 or min(v) < 1:
        raise ValueError(f"--sizes {size!r}: expected NxAxB or NXxNYxAxB with positive integers")
    return tuple(v)


def plate_on_base_deck(n: int, plate_layers: int, base_layers: int, ny: int | None = None) -> str:
    """The deck text (module docstring) of size n × ny in plan (ny = n by default); the plan
    is PLAN mm along x and PLAN·ny/n along y (square elements in plan)."""
    ny = n if ny is None else ny
    plan = np.linspace(0.0, PLAN, n + 1)
    plan_y = np.linspace(0.0, PLAN * ny / n, ny + 1)
    base = box_part(plan, plan_y, np.linspace(-BASE_T, 0.0, base_layers + 1))
    plate = box_part(plan, plan_y, np.linspace(0.0, PLATE_T, plate_layers + 1),
                     first_node=len(base.node_ids) + 1, first_element=len(base.element_ids) + 1)
    top = plate.face_elements["ZMAX"]
    centre_x = 0.5 * (plan[:-1] + plan[1:])[plate.element_ijk[top - plate.element_ids[0], 0]]
    loaded = top[centre_x > 2.0 * PLAN / 3.0]
    # the nodes of the loaded faces (their mean u_z: the result compared between refinements)
    loaded_nodes = np.unique(plate.connectivity[loaded - plate.element_ids[0]])
    loaded_nodes = loaded_nodes[plate.coords[loaded_nodes - plate.node_ids[0], 2] == PLATE_T]

    def lines(*blocks):
        return "\n".join(line for b in blocks for line in b)

    dt = 1.0 / INCREMENTS
    return f"""** roughcontact benchmark: plate on base, full-face contact, {n}x{plate_layers}x{base_layers}
*HEADING
plate on base {n}x{plate_layers}x{base_layers}
{lines(node_lines(base, "NALL", digits=12), node_lines(plate, digits=12)[1:])}
{lines(element_lines(base, "BASE"), element_lines(plate, "PLATE"))}
{lines(id_lines("*ELSET, ELSET=PLATEBOTTOMEL", plate.face_elements["ZMIN"]),
       id_lines("*ELSET, ELSET=BASETOPEL", base.face_elements["ZMAX"]),
       id_lines("*NSET, NSET=PLATETOP", plate.face_nodes["ZMAX"]),
       id_lines("*NSET, NSET=BASEBOTTOM", base.face_nodes["ZMIN"]),
       id_lines("*NSET, NSET=LOADED", loaded_nodes))}
*MATERIAL, NAME=STEEL
*ELASTIC
2.1e5, 0.3
*MATERIAL, NAME=CASTIRON
*ELASTIC
1.1e5, 0.26
*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL
*SOLID SECTION, ELSET=BASE, MATERIAL=CASTIRON
*SURFACE, NAME=SLAVE, TYPE=ELEMENT
PLATEBOTTOMEL, S1
*SURFACE, NAME=MASTER, TYPE=ELEMENT
BASETOPEL, S2
*SURFACE INTERACTION, NAME=ROUGH
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD
*CONTACT PAIR, INTERACTION=ROUGH, TYPE=SURFACE TO SURFACE
SLAVE, MASTER
*BOUNDARY
BASEBOTTOM, 1, 3, 0.0
PLATETOP, 1, 2, 0.0
*STEP, INC=1000
*STATIC
{dt:.12g}, 1.0, {dt * 2.0 ** -10:.6g}, {dt:.12g}
*DLOAD
{chr(10).join(f"{e}, P2, {PRESSURE:.12e}" for e in loaded)}
*END STEP
"""


def law_yaml(friction: bool) -> str:
    """LAW.yaml of the interaction ROUGH: block_on_base's law, frictionless or Coulomb."""
    m = {k: f"{v:.6e}" for k, v in bob.MOMENTS.items()}
    E_star = 1.0 / ((1 - 0.3 ** 2) / 2.1e5 + (1 - 0.26 ** 2) / 1.1e5)
    return ("length_unit: mm\ninteractions:\n  ROUGH:\n"
            f"    moments: {{m00: {m['m00']}, m20: {m['m20']}, m02: {m['m02']}, m40: {m['m40']}, m04: {m['m04']}, unit: um}}\n"
            f"    lay_direction: [1, 0, 0]\n    E_star: {E_star!r}\n    law: elastic\n"
            f"    seating_pressure: {bob.SEATING_PRESSURE!r}\n"
            f"    friction: {'{coulomb: {mu: 0.2, kt_over_kn: 0.7}}' if friction else 'none'}\n")


def run(size: str, solver: str, friction: bool, timeout: float, workdir: Path) -> dict:
    """One run of the deck of ``size``: ``solver`` a linear strategy of ``fe run``, or "ccx"."""
    n, ny, a, b = parse_size(size)
    deck, law = workdir / f"plate_{size}.inp", workdir / ("LAW_friction.yaml" if friction else "LAW.yaml")
    deck.write_text(plate_on_base_deck(n, a, b, ny))
    law.write_text(law_yaml(friction))
    exe = shutil.which("roughcontact") or str(Path(sys.executable).with_name("roughcontact"))
    how = (["ccx", "run", str(deck), "--interface", str(law), "--threads", "2", "--timeout", f"{timeout:g}"]
           if solver == "ccx" else ["fe", "run", str(deck), "--interface", str(law), "--solver", solver])
    row = measure([exe, *how, "--json", "--quiet"], workdir, timeout + 60.0)
    out = {"size": size, "solver": solver, "friction": friction, **{k: row[k] for k in (
        "exit", "timeout", "wall_s", "cpu_s", "peak_rss_mb", "load_before", "load_after")}}
    if row["exit"] == 0:
        res = json.loads(row["output"])
        step = res["steps"][-1]
        out.update(dofs=res["dofs"], interface_points=res["interface_points"],
                   newton_iterations=res["newton_iterations"], cutbacks=res["cutbacks"],
                   max_p_N=max(step["interface"]["p_N"]),
                   mean_u_N_um=float(np.mean(step["interface"]["u_N_um"])),
                   loaded_mean_uz_mm=float(np.mean(np.asarray(step["node_sets"]["LOADED"]["u"]).reshape(-1, 3)[:, 2])))
    else:
        out["stderr"] = row["stderr"][-300:]
    return out


def _ccx_built() -> bool:
    """Whether `roughcontact ccx build` has made the ccx with the law (else a note, no ccx rows)."""
    from roughcontact.ccx.build import find_build

    if find_build() is None:
        print("ccx rows skipped: run `roughcontact ccx build` first (docs/ccx.md)", file=sys.stderr)
        return False
    return True


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", nargs="+", default=["16x2x4"])
    ap.add_argument("--solvers", nargs="*", default=list(SOLVERS), help="linear strategies of fe run (none: ccx only)")
    ap.add_argument("--friction", action="store_true")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--ccx", action="store_true", help="also run each size in CalculiX with the law (ccx run)")
    ap.add_argument("--ccx-timeout", type=float, default=1800.0)
    ap.add_argument("--out", type=Path, default=Path("results/benchmarks"))
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for size in args.sizes:
            for solver in [*args.solvers, *(["ccx"] if args.ccx and _ccx_built() else [])]:
                row = run(size, solver, args.friction, args.ccx_timeout if solver == "ccx" else args.timeout, Path(tmp))
                rows.append(row)
                print(json.dumps(row), flush=True)
    args.out.mkdir(parents=True, exist_ok=True)
    name = "fe_large_interface" + ("_friction" if args.friction else "")
    (args.out / f"{name}.json").write_text(json.dumps({"machine": info(), "rows": rows}, indent=1))
    lines = ["| size | dofs | interface points | solver | wall [s] | CPU [s] | peak RSS [MB] | Newton iterations "
             "| mean u_z of LOADED [mm] | load before/after |",
             "|---|---:|---:|---|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        wall = f"{r['wall_s']:.1f}" if r["exit"] == 0 else f"> {r['wall_s']:.0f} (stopped)" if r["timeout"] else "failed"
        uz = f"{r['loaded_mean_uz_mm']:.7e}" if "loaded_mean_uz_mm" in r else ""
        lines.append(f"| {r['size']} | {r.get('dofs', '')} | {r.get('interface_points', '')} | {r['solver']} | {wall} "
                     f"| {r['cpu_s']:.1f} | {r['peak_rss_mb']:.0f} | {r.get('newton_iterations', '')} | {uz} "
                     f"| {r['load_before']}/{r['load_after']} |")
    (args.out / f"{name}.md").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
