"""The exported pressure–overclosure table checked in a real FE code, CalculiX (``ccx``).

Two problems (issue 14; docs/fe-export.md), built as CalculiX input decks from the table text of
:func:`roughcontact.interface.export.format_table` (format "calculix", lengths in mm):

* **block** — a steel cube (1 mm, one C3D8) on a base of modulus 1e12 N/mm² (rigid to 1e-12)
  through node-to-surface contact, under uniform pressures p, one step each: the closure of
  the interface must be the table's (and, within rtol, the law's) inverse c(p);
* **beam** — example 9.1 (:mod:`roughcontact.examples.beam`): the quarter beam x ∈ [0, 250],
  y ∈ [0, 5] mm, C3D20 elements on the engine's mesh lines (n_x uniform, n_z graded by
  z_ratio from the contact face), frictionless node-to-surface contact on a fixed rigid block,
  symmetry u_x = 0 on x = 0 and u_y = 0 on y = 0, the line load at x = 0 on the top face
  (1/6, 4/6, 1/6 of the quarter's load on the three nodes), seated at the initial load in
  step 1, loaded in step 2. u_N = the change of the bottom nodes' u_z from step 1 to step 2
  [µm], negative = approach (the engine's sign). Node-to-surface springs weight the corner and
  mid-side nodes of a quadratic face very differently, so single nodes ripple (corner and
  mid-side stations alternate by ~0.03 µm): deflections are compared as width averages over a
  corner and the adjacent mid-side station (:func:`width_and_half_element_average`), the same
  rule applied to the engine's interface points.

What CalculiX 2.20 needs (found by an independent run, issue 14): node-to-surface contact
(surface-to-surface with a tabular law fails), ≤ 200 rows (more are resampled evenly in
overclosure), the last row far above every pressure (the pressure is held constant beyond),
fields ≤ 20 characters, mm.

Deck builders and the .dat parser are pure; :func:`run_ccx` runs the program in a directory.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np

from ..examples.beam import BeamSpec
from ..fe.deck_writer import box_part, element_lines, id_lines, node_lines
from ..fe.mesh import graded

__all__ = ["CCX_INSTALL", "ccx_executable", "ccx_version", "skipped_line", "run_ccx", "table_lines", "block_deck",
           "beam_deck", "node_prints", "block_closures_um", "beam_deflections_um", "engine_deflections_um",
           "width_and_half_element_average"]

#: how to get ccx where it is missing (Debian/Ubuntu); the gate's expected_checks says the same
CCX_INSTALL = "apt-get install calculix-ccx"
_BLOCK_E, _BLOCK_NU = 2.1e5, 0.3  # N/mm²: a steel cube (its own compression is not measured)
_BASE_E = 1.0e12  # N/mm²: the base's compression is 1e-12 of the pressure per mm


def ccx_executable() -> str | None:
    """The path of ``ccx`` on PATH, or None."""
    return shutil.which("ccx")


def skipped_line() -> str:
    """Why the scene did not run where ccx is absent: "skipped: ccx not installed — `apt-get
    install calculix-ccx`" (the wording of every report, :func:`roughcontact.paper.verify.skipped_text`)."""
    from .verify import skipped_text

    return skipped_text("ccx", CCX_INSTALL)


def ccx_version(exe: str) -> str:
    """"2.20" from ``ccx -v`` (empty when it cannot be read)."""
    out = subprocess.run([exe, "-v"], capture_output=True, text=True, timeout=30).stdout
    m = re.search(r"Version\s+(\S+)", out)
    return m.group(1) if m else ""


def run_ccx(deck: str, name: str, workdir, *, exe: str | None = None, timeout: float = 600.0):
    """Write ``<workdir>/<name>.inp``, run ccx on it (one thread), return (the .dat text,
    seconds). RuntimeError with the tail of ccx's output when it fails or writes no .dat."""
    import os

    exe = exe or ccx_executable()
    if exe is None:
        raise RuntimeError(f"ccx is not installed (Debian/Ubuntu: {CCX_INSTALL})")
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / f"{name}.inp").write_text(deck)
    env = {**os.environ, "OMP_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1"}
    t0 = time.perf_counter()
    proc = subprocess.run([exe, name], cwd=workdir, capture_output=True, text=True, timeout=timeout, env=env)
    seconds = time.perf_counter() - t0
    (workdir / f"{name}.log").write_text(proc.stdout + proc.stderr)
    dat = workdir / f"{name}.dat"
    if proc.returncode != 0 or "*ERROR" in proc.stdout or not dat.exists():
        tail = "\n".join((proc.stdout + proc.stderr).splitlines()[-15:])
        raise RuntimeError(f"ccx failed on {name}.inp (exit {proc.returncode}):\n{tail}")
    return dat.read_text(), seconds


def table_lines(table_text: str) -> str:
    """The *SURFACE BEHAVIOR (and *FRICTION) lines of an exported table, comments and blank
    lines dropped: what goes under a deck's *SURFACE INTERACTION."""
    return "\n".join(line for line in table_text.splitlines() if line.strip() and not line.startswith("**"))


def _check_rows(table_text: str) -> None:
    rows = [line for line in table_text.splitlines() if line and not line.startswith("*")]
    if len(rows) > 200:
        raise ValueError(f"CalculiX resamples tables of more than 200 rows; got {len(rows)}")
    if any(len(field.strip()) > 20 for line in rows for field in line.split(",")):
        raise ValueError("CalculiX reads 20 characters per field: a field is longer")


def block_deck(table_text: str, pressures) -> str:
    """The block problem (module docstring): one step per pressure [N/mm²], each printing the
    displacements of the block's bottom nodes (set BOTTOM)."""
    _check_rows(table_text)
    p = [float(x) for x in pressures]
    if not p or any(not (x > 0) for x in p):
        raise ValueError(f"pressures must be positive, got {pressures!r}")
    head = f"""** roughcontact: block on a rigid base through the exported table (CalculiX)
*NODE, NSET=NALL
1, -0.5, -0.5, -1.0
2, 1.5, -0.5, -1.0
3, 1.5, 1.5, -1.0
4, -0.5, 1.5, -1.0
5, -0.5, -0.5, 0.0
6, 1.5, -0.5, 0.0
7, 1.5, 1.5, 0.0
8, -0.5, 1.5, 0.0
11, 0.0, 0.0, 0.0
12, 1.0, 0.0, 0.0
13, 1.0, 1.0, 0.0
14, 0.0, 1.0, 0.0
15, 0.0, 0.0, 1.0
16, 1.0, 0.0, 1.0
17, 1.0, 1.0, 1.0
18, 0.0, 1.0, 1.0
*ELEMENT, TYPE=C3D8, ELSET=BASE
1, 1, 2, 3, 4, 5, 6, 7, 8
*ELEMENT, TYPE=C3D8, ELSET=BLOCK
2, 11, 12, 13, 14, 15, 16, 17, 18
*NSET, NSET=BASENODES
1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=BLOCKNODES
11, 12, 13, 14, 15, 16, 17, 18
*NSET, NSET=BOTTOM
11, 12, 13, 14
*MATERIAL, NAME=BASEMAT
*ELASTIC
{_BASE_E:.6e}, 0.0
*MATERIAL, NAME=STEEL
*ELASTIC
{_BLOCK_E:.6e}, {_BLOCK_NU}
*SOLID SECTION, ELSET=BASE, MATERIAL=BASEMAT
*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL
*SURFACE, NAME=SLAVE
BLOCK, S1
*SURFACE, NAME=MASTER
BASE, S2
*SURFACE INTERACTION, NAME=ROUGH
{table_lines(table_text)}
*CONTACT PAIR, INTERACTION=ROUGH, TYPE=NODE TO SURFACE
SLAVE, MASTER
*BOUNDARY
BASENODES, 1, 3, 0.0
BLOCKNODES, 1, 2, 0.0
"""
    steps = []
    for x in p:
        steps.append(f"""*STEP, INC=1000
*STATIC
0.1, 1.0, 1e-6, 0.25
*DLOAD
BLOCK, P2, {x:.12e}
*NODE PRINT, NSET=BOTTOM
U
*END STEP""")
    return head + "\n".join(steps) + "\n"


def node_prints(dat: str, node_set: str) -> list[tuple[float, dict[int, np.ndarray]]]:
    """Every displacement print of ``node_set`` in a .dat file: [(time, {node: (ux, uy, uz)})]."""
    out = []
    for block in re.split(r"\n\s*displacements", dat):
        m = re.search(r"for set (\S+) and time\s+(\S+)", block)
        if not m or m.group(1).upper() != node_set.upper():
            continue
        rows = {}
        for line in block.splitlines()[1:]:
            parts = line.split()
            if len(parts) == 4 and parts[0].isdigit():
                rows[int(parts[0])] = np.array([float(v) for v in parts[1:]])
            elif rows and parts:  # the next print's header (e.g. *CONTACT PRINT's 4-column rows)
                break
        out.append((float(m.group(2)), rows))
    return out


def _at_step_ends(prints, n_steps):
    """The print at the end of each step (total times 1, 2, ..., n_steps with unit step times)."""
    ends = []
    for k in range(1, n_steps + 1):
        hit = [rows for t, rows in prints if abs(t - k) <= 1e-6]
        if not hit:
            raise RuntimeError(f"ccx did not finish step {k} (no print at time {k})")
        ends.append(hit[-1])
    return ends


def block_closures_um(dat: str, n_steps: int) -> np.ndarray:
    """The closure [µm] (= −u_z of the block's bottom, mean of its four nodes) at the end of
    each step. The base moves by pressure/1e12 mm: below 1e-10 µm here."""
    ends = _at_step_ends(node_prints(dat, "BOTTOM"), n_steps)
    return np.array([-1000.0 * np.mean([u[2] for u in rows.values()]) for rows in ends])


# ---------------------------------------------------------------------------------------------
# the beam of example 9.1
# ---------------------------------------------------------------------------------------------
def _beam_part(spec: BeamSpec):
    """The quarter beam's C3D20 mesh on the engine's mesh lines (n_x uniform, n_z graded by
    z_ratio from the contact face), node and element ids from 1."""
    return box_part(graded(0.0, spec.length / 2.0, spec.n_x, 1.0), [0.0, spec.width / 2.0],
                    graded(0.0, spec.height, spec.n_z, spec.z_ratio))


def beam_deck(table_text: str, spec: BeamSpec = BeamSpec()) -> str:
    """The beam problem (module docstring) on spec's geometry, loads and mesh lines (n_x, n_z,
    z_ratio; x_ratio 1, no load patch), E and ν. Prints u of the bottom nodes (set BOTTOM)."""
    _check_rows(table_text)
    if spec.load_patch != 0.0 or spec.x_ratio != 1.0:
        raise ValueError("the CalculiX beam takes the line load on a uniform x mesh (load_patch 0, x_ratio 1)")
    beam = _beam_part(spec)
    # the line load's nodes: y = 0, b/4, b/2 at x = 0 on the top (ids ascend with y)
    line = np.intersect1d(beam.face_nodes["XMIN"], beam.face_nodes["ZMAX"]).tolist()
    base0 = len(beam.node_ids) + 1
    lo, hi = -10.0, spec.length / 2.0 + 10.0
    base = [(lo, -5.0, -10.0), (hi, -5.0, -10.0), (hi, 10.0, -10.0), (lo, 10.0, -10.0),
            (lo, -5.0, 0.0), (hi, -5.0, 0.0), (hi, 10.0, 0.0), (lo, 10.0, 0.0)]
    nodes = "\n".join(node_lines(beam, "NALL", digits=12))
    nodes += "\n" + "\n".join(f"{base0 + n}, {a:.12g}, {b:.12g}, {c:.12g}" for n, (a, b, c) in enumerate(base))
    n_elements = len(beam.element_ids)

    def block(keyword, ids):
        return "\n".join(id_lines(keyword, ids))

    weights = np.array([1.0, 4.0, 1.0]) / 6.0
    quarter = 0.25

    def loads(total):
        return "\n".join(f"{n}, 3, {-total * quarter * w:.12e}" for n, w in zip(line, weights))

    return f"""** roughcontact: example 9.1 (quarter beam) on a rigid base through the exported table (CalculiX)
{nodes}
{chr(10).join(element_lines(beam, "BEAM"))}
*ELEMENT, TYPE=C3D8, ELSET=BASE
{n_elements + 1}, {", ".join(str(base0 + i) for i in range(8))}
{block("*ELSET, ELSET=CONTACTLAYER", beam.face_elements["ZMIN"])}
{block("*NSET, NSET=BOTTOM", beam.face_nodes["ZMIN"])}
{block("*NSET, NSET=XMIN", beam.face_nodes["XMIN"])}
{block("*NSET, NSET=YMIN", beam.face_nodes["YMIN"])}
{block("*NSET, NSET=BASENODES", range(base0, base0 + 8))}
*MATERIAL, NAME=BEAMMAT
*ELASTIC
{spec.E:.12e}, {spec.nu}
*MATERIAL, NAME=BASEMAT
*ELASTIC
{_BASE_E:.6e}, 0.0
*SOLID SECTION, ELSET=BEAM, MATERIAL=BEAMMAT
*SOLID SECTION, ELSET=BASE, MATERIAL=BASEMAT
*SURFACE, NAME=SLAVE
CONTACTLAYER, S1
*SURFACE, NAME=MASTER
BASE, S2
*SURFACE INTERACTION, NAME=ROUGH
{table_lines(table_text)}
*CONTACT PAIR, INTERACTION=ROUGH, TYPE=NODE TO SURFACE
SLAVE, MASTER
*BOUNDARY
BASENODES, 1, 3, 0.0
XMIN, 1, 1, 0.0
YMIN, 2, 2, 0.0
*STEP, INC=1000
*STATIC
0.25, 1.0, 1e-6, 0.5
*CLOAD
{loads(spec.initial_load)}
*NODE PRINT, NSET=BOTTOM
U
*END STEP
*STEP, INC=1000
*STATIC
0.0625, 1.0, 1e-6, 0.125
*CLOAD
{loads(spec.load)}
*NODE PRINT, NSET=BOTTOM
U
*END STEP
"""


def width_and_half_element_average(x, y, u, x_corner: float, x_mid: float) -> float:
    """The deflection at a corner station of the mesh, free of the node-to-surface ripple:
    u averaged across the width at x_corner and at the adjacent mid-side station x_mid (each
    with the edge weights of the quadratic face: (1/6, 4/6, 1/6) for three points across,
    (1/2, 1/2) for two), then the mean of the two stations. The ripple alternates between
    corner and mid-side stations and cancels; a smooth field is changed by its curvature
    over half an element only. Applied identically to ccx and to the engine."""
    x, y, u = (np.asarray(a, dtype=float) for a in (x, y, u))
    out = []
    for xs in (x_corner, x_mid):
        sel = np.isclose(x, xs, atol=1e-9)
        order = np.argsort(y[sel])
        vals = u[sel][order]
        if vals.size == 3:
            out.append(float(np.dot(vals, [1 / 6, 4 / 6, 1 / 6])))
        elif vals.size == 2:
            out.append(float(vals.mean()))
        else:
            raise ValueError(f"expected 2 or 3 points across the width at x = {xs:g}, got {vals.size}")
    return 0.5 * (out[0] + out[1])


def beam_deflections_um(dat: str, spec: BeamSpec = BeamSpec()) -> dict[str, float]:
    """u_N from the seated state [µm] (negative = approach) at the centre (x = 0) and the end
    (x = L/2) of the CalculiX beam (:func:`width_and_half_element_average`), and the spread of
    the single bottom nodes there (the ripple)."""
    beam = _beam_part(spec)
    seated, loaded = _at_step_ends(node_prints(dat, "BOTTOM"), 2)
    nodes = beam.face_nodes["ZMIN"]
    px, py = beam.coords[nodes - 1, 0], beam.coords[nodes - 1, 1]  # node ids 1, 2, … in coordinate order
    u = np.array([1000.0 * (loaded[n][2] - seated[n][2]) for n in nodes.tolist()])
    return _stations(px, py, u, beam.edges[0])


def engine_deflections_um(point_x, point_y, point_u_N_um, spec: BeamSpec = BeamSpec()) -> dict[str, float]:
    """The same measures from the engine's interface points (a BeamResult's dataset:
    point_x, point_y [mm], point_u_N_um)."""
    return _stations(point_x, point_y, point_u_N_um, graded(0.0, spec.length / 2.0, spec.n_x, 1.0))


def _stations(px, py, u, x_edges):
    half = 0.5 * (x_edges[1] - x_edges[0])
    end, end_half = x_edges[-1], 0.5 * (x_edges[-1] - x_edges[-2])
    out = {"centre_um": width_and_half_element_average(px, py, u, 0.0, half),
           "end_um": width_and_half_element_average(px, py, u, end, end - end_half)}
    for label, xs in (("centre", 0.0), ("end", end)):
        sel = np.isclose(px, xs, atol=1e-9)
        out[f"{label}_node_spread_um"] = float(np.ptp(np.asarray(u)[sel]))
    return out


# ---------------------------------------------------------------------------------------------
# the verification scene "calculix" (workflow rule fe_calculix)
# ---------------------------------------------------------------------------------------------
SCENE = "calculix"


def _check(model, quantity, row, row_key, ok, detail, description, target, value, error, tol, why, unit="",
           scene=SCENE):
    """A numerics check of a CalculiX scene (``scene``: this one, or ccx_friction's)."""
    from .verify import NOT_REPRODUCED, REPRODUCED, Check, numerics_id

    return Check(id=numerics_id(scene, model, quantity, row, row_key), kind="numerics", scene=scene,
                 verdict=REPRODUCED if ok else NOT_REPRODUCED, detail=detail, description=description,
                 model=model, quantity=quantity, s=row, unit=unit, target=float(target), value=float(value),
                 error=float(error), tolerance=float(tol), tolerance_why=why)


def _table_for(surface, E_star, p0, cfg):
    from ..interface.export import format_table, overclosure_table

    table = overclosure_table(surface, pressure_range=tuple(cfg["pressure_range"]), E_star=E_star,
                              rtol=cfg["rtol"], reference="seating", seating_pressure=p0)
    text = format_table(table, "calculix", length_scale=1e-3, length_unit="mm", stress_unit="N/mm^2")
    return table, text


def run_scene(cfg, beam_cfg, engine_points, workdir, *, exe=None, progress=print):
    """Run the block and the beams in ccx and compare: returns (rows, checks, timings).

    cfg: config.yaml ``calculix``; beam_cfg: config.yaml ``fe.beam`` (surface, E_star, spec, cases);
    engine_points: {case: (point_x, point_y, point_u_N_um)} of the engine's runs of ``cfg.family``;
    workdir: where the decks and ccx's files go (kept: the decks are complete examples)."""
    from ..statistics import SpectralMoments

    exe = exe or ccx_executable()
    spec = BeamSpec(elements=cfg["family"], **beam_cfg["spec"])
    E_star = float(beam_cfg["E_star"])
    rows, checks, timings = [], [], {}
    # -- block
    case = cfg["block_surface"]
    surface = SpectralMoments(m00=beam_cfg["cases"][case]["m00"], **beam_cfg["surface"])
    table, text = _table_for(surface, E_star, spec.seating_pressure, cfg)
    pressures = [float(p) for p in cfg["block_pressures"]]
    dat, timings["block"] = run_ccx(block_deck(text, pressures), "block", workdir, exe=exe)
    tol = cfg["tolerances"]["block"]
    for p, c in zip(pressures, block_closures_um(dat, len(pressures))):
        p_table = float(table.interpolate(c))
        p_law = float(table.law_pressure(c))
        err = p_law / p - 1.0
        ok = abs(err) <= tol["rtol"]
        rows.append({"problem": "block", "case": case, "m00": surface.m00, "pressure": p, "closure_um": c,
                     "table_pressure": p_table, "law_pressure": p_law, "law_rel_error": err,
                     "rows": table.n_rows, "table_max_error": table.max_error})
        checks.append(_check("ccx-block", "pressure", f"{p:g}", "p", ok,
                             f"ccx closure {c:.6f} um: law {p_law:.6g}, table {p_table:.6g} N/mm^2 vs applied {p:g} ({100 * err:+.4f} %)",
                             "block under uniform pressure: the law at ccx's closure vs the applied pressure",
                             p, p_law, err, tol["rtol"], tol["why"], "N/mm^2"))
    progress(f"block: {len(pressures)} pressures in {timings['block']:.2f} s")
    # -- beams
    tol = cfg["tolerances"]["beam"]
    for case in cfg["cases"]:
        surface = SpectralMoments(m00=beam_cfg["cases"][case]["m00"], **beam_cfg["surface"])
        table, text = _table_for(surface, E_star, spec.seating_pressure, cfg)
        dat, timings[f"beam-{case}"] = run_ccx(beam_deck(text, spec), f"beam-{case}", workdir, exe=exe)
        ours = beam_deflections_um(dat, spec)
        engine = engine_deflections_um(*engine_points[case], spec)
        for q in ("centre", "end"):
            diff = ours[f"{q}_um"] - engine[f"{q}_um"]
            ok = abs(diff) <= tol["atol"]
            rows.append({"problem": "beam", "case": case, "m00": surface.m00, "quantity": q,
                         "ccx_um": ours[f"{q}_um"], "engine_um": engine[f"{q}_um"], "difference_um": diff,
                         "ccx_node_spread_um": ours[f"{q}_node_spread_um"], "rows": table.n_rows,
                         "table_max_error": table.max_error, "ccx_seconds": timings[f"beam-{case}"]})
            checks.append(_check("ccx-beam", q, case, "case", ok,
                                 f"ccx {ours[f'{q}_um']:.5f} um vs engine {engine[f'{q}_um']:.5f} um ({diff:+.5f} um)",
                                 f"frictionless beam (example 9.1), u_N at the {q} from the seated state",
                                 engine[f"{q}_um"], ours[f"{q}_um"], diff, tol["atol"], tol["why"], "um"))
        progress(f"beam case {case}: {timings[f'beam-{case}']:.2f} s")
    return rows, checks, timings


def render_markdown(rows, checks, timings, version: str, skipped_reason: str = "") -> str:
    """paper_figures/calculix.md: what was run, the comparisons, the ccx times; or, with
    ``skipped_reason`` (e.g. :func:`skipped_line`), why it was skipped and how to run it."""
    lines = ["# The exported table in CalculiX (issue 14)", ""]
    if skipped_reason:
        return "\n".join(lines + [f"This scene was {skipped_reason}. With CalculiX installed, "
                                  "`snakemake fe_calculix` (or `make verify`) runs this scene's checks.", ""])
    lines += [f"CalculiX {version}; decks and outputs in `results/calculix/` (block.inp, beam-<case>.inp). "
              "Tables exported by `roughcontact.interface.export` (format calculix, mm, N/mm²), node-to-surface contact.", "",
              "## Block on a rigid base under uniform pressure", "",
              "| m00 [µm²] | p [N/mm²] | ccx closure [µm] | table p(c) | law p(c) | law vs p | rows |",
              "|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["problem"] == "block":
            lines.append(f"| {r['m00']:g} | {r['pressure']:g} | {r['closure_um']:.6f} | {r['table_pressure']:.6g} | "
                         f"{r['law_pressure']:.6g} | {100 * r['law_rel_error']:+.4f} % | {r['rows']} |")
    lines += ["", "## Frictionless beam of example 9.1 (u_N from the seated state, µm)", "",
              "Width averages over a corner and the adjacent mid-side station (the node-to-surface ripple cancels); "
              "the same rule on the engine's interface points.", "",
              "| case | m00 [µm²] | where | ccx | engine | ccx − engine | ccx node spread | rows | ccx s |",
              "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["problem"] == "beam":
            lines.append(f"| {r['case']} | {r['m00']:g} | {r['quantity']} | {r['ccx_um']:.5f} | {r['engine_um']:.5f} | "
                         f"{r['difference_um']:+.5f} | {r['ccx_node_spread_um']:.4f} | {r['rows']} | {r['ccx_seconds']:.1f} |")
    lines += ["", "Checks: " + ", ".join(f"{c.id.split('/', 1)[1]}: {c.verdict}" for c in checks),
              "", "ccx run times: " + ", ".join(f"{k} {v:.1f} s" for k, v in timings.items()), ""]
    return "\n".join(lines)
