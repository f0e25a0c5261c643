"""One deck, two codes: the block on a base of :mod:`roughcontact.examples.block_on_base` (two
materials, an eccentric load, the base larger than the block; not the paper's beam) run in
CalculiX with the exported pressure–overclosure table and in this engine with the statistical law
it tabulates, frictionless, on refined meshes (1×, 2×, 3× …): the mean vertical displacement of
the loaded face [µm] of both codes and their difference at every refinement. Both converge at
first order on these meshes, from opposite sides (the engine's order measured over refinements
1–3: 1.0), so the check (``cfg["tolerances"]["deck"]``) compares the first-order extrapolations
u∞ ≈ u_f + (u_f − u_c)·h_f/(h_c − h_f) from the two finest refinements of each code. Part of
the optional scene ``calculix`` (:mod:`.calculix`); without ccx it is skipped.

CalculiX: node-to-surface contact (the only form its tabular law runs with), C3D20. The engine:
the deck read as it is, its interaction replaced by the law (21-node transition + 18-node
interface elements). Both means are nodal means over the node set LOADED (the same rule).
"""

from __future__ import annotations

import time

import numpy as np

from ..examples.block_on_base import ALUMINIUM, MOMENTS, STEEL, BlockOnBase, block_on_base_deck
from .calculix import _check, node_prints, run_ccx, table_lines

__all__ = ["deck_scene", "run_refinement", "render_deck_markdown", "extrapolated"]


def extrapolated(refinements, values) -> float:
    """First-order extrapolation to h → 0 from the two finest refinements (h = 1/refinement)."""
    (rc, uc), (rf, uf) = sorted(zip(refinements, values))[-2:]
    hc, hf = 1.0 / rc, 1.0 / rf
    return uf + (uf - uc) * hf / (hc - hf)


def _loaded_mean_ccx(dat: str) -> float:
    """Mean u_z [µm] of the node set LOADED at the end of the step (total time 1)."""
    ends = [rows for t, rows in node_prints(dat, "LOADED") if abs(t - 1.0) <= 1e-6]
    if not ends:
        raise RuntimeError("ccx did not finish the step (no print of LOADED at time 1)")
    return 1000.0 * float(np.mean([u[2] for u in ends[-1].values()]))


def run_refinement(cfg, refine: int, workdir, *, exe=None) -> dict:
    """The deck at one refinement in ccx (exported table) and in the engine (the law): a row
    with both means [µm], their relative difference, sizes and times. cfg: config ``calculix``."""
    from ..asperity import effective_modulus
    from ..fe.deck import read_deck
    from ..fe.deck_run import run_deck_file
    from ..interface.export import format_table, overclosure_table
    from ..statistics import SpectralMoments

    d = cfg["deck"]
    E_star = effective_modulus(*STEEL, *ALUMINIUM)  # eq. (42): what the engine takes from the deck
    spec = BlockOnBase(refine=int(refine), pressure=float(d["pressure"]), increments=int(d["increments"]),
                       seating_pressure=float(d["seating_pressure"]))
    table = overclosure_table(SpectralMoments(**MOMENTS), pressure_range=tuple(cfg["pressure_range"]), E_star=E_star,
                              rtol=cfg["rtol"], reference="seating", seating_pressure=spec.seating_pressure)
    text = format_table(table, "calculix", length_scale=1e-3, length_unit="mm", stress_unit="N/mm^2")
    name = f"block-on-base-{refine}"
    dat, ccx_seconds = run_ccx(block_on_base_deck(spec, table_lines(text)), name, workdir, exe=exe,
                               timeout=float(d.get("timeout", 3600)))
    t0 = time.perf_counter()
    res = run_deck_file(read_deck(f"{workdir}/{name}.inp"), spec.law_file(), "quadratic")
    engine_seconds = time.perf_counter() - t0
    _, u = res.node_sets(res.increments[-1])["LOADED"]
    ccx, engine = _loaded_mean_ccx(dat), 1000.0 * float(u[:, 2].mean())
    return {"problem": "deck", "refine": int(refine), "dofs": res.n_dofs, "interface_points": res.problem.points.n_points,
            "ccx_um": ccx, "engine_um": engine, "rel_difference": ccx / engine - 1.0, "ccx_seconds": ccx_seconds,
            "engine_seconds": engine_seconds, "rows": table.n_rows}


def deck_scene(cfg, workdir, *, exe=None, progress=print):
    """Run the deck in ccx and in the engine at every refinement of ``cfg["deck"]``; returns
    (rows, checks, timings). cfg: config ``calculix`` (pressure_range, rtol, deck, tolerances)."""
    rows, timings = [], {}
    for refine in cfg["deck"]["refinements"]:
        r = run_refinement(cfg, refine, workdir, exe=exe)
        rows.append(r)
        timings[f"ccx-block-on-base-{refine}"] = r["ccx_seconds"]
        timings[f"engine-block-on-base-{refine}"] = r["engine_seconds"]
        progress(f"block on base, refinement {refine}: ccx {r['ccx_um']:.5f} um ({r['ccx_seconds']:.1f} s), "
                 f"engine {r['engine_um']:.5f} um ({r['engine_seconds']:.1f} s)")
    tol = cfg["tolerances"]["deck"]
    refs = [r["refine"] for r in rows]
    ccx_inf = extrapolated(refs, [r["ccx_um"] for r in rows])
    engine_inf = extrapolated(refs, [r["engine_um"] for r in rows])
    err = ccx_inf / engine_inf - 1.0
    rows.append({"problem": "deck", "refine": "h -> 0", "ccx_um": ccx_inf, "engine_um": engine_inf,
                 "rel_difference": err})
    finest = rows[-2]
    check = _check("ccx-deck", "loaded_face_uz", "extrapolated", "refine", abs(err) <= tol["rtol"],
                   f"extrapolated from refinements {refs[-2]}, {refs[-1]}: ccx {ccx_inf:.5f} um vs engine "
                   f"{engine_inf:.5f} um ({100 * err:+.2f} %); at refinement {finest['refine']} "
                   f"{100 * finest['rel_difference']:+.2f} %",
                   "block on a base (two materials, eccentric load): mean u_z of the loaded face, ccx vs the engine",
                   engine_inf, ccx_inf, err, tol["rtol"], tol["why"], "um")
    return rows, [check], timings


def render_deck_markdown(rows) -> list[str]:
    """The section of paper_figures/calculix.md: the mesh study of both codes."""
    lines = ["", "## One deck in both codes: a block on a base (two materials, eccentric load)", "",
             "`results/calculix/block-on-base-<refinement>.inp`, frictionless: ccx with the exported table "
             "(node-to-surface), the engine with the law (21-node + 18-node elements); the mean u_z of the "
             "loaded face (nodal mean over LOADED), µm.", "",
             "| refinement | dofs | interface points | ccx | engine | ccx / engine − 1 | ccx s | engine s |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["problem"] == "deck" and "dofs" in r:
            lines.append(f"| {r['refine']} | {r['dofs']} | {r['interface_points']} | {r['ccx_um']:.5f} | "
                         f"{r['engine_um']:.5f} | {100 * r['rel_difference']:+.2f} % | {r['ccx_seconds']:.1f} | "
                         f"{r['engine_seconds']:.1f} |")
        elif r["problem"] == "deck":
            lines.append(f"| h → 0 (first order) | | | {r['ccx_um']:.5f} | {r['engine_um']:.5f} | "
                         f"{100 * r['rel_difference']:+.2f} % | | |")
    return lines
