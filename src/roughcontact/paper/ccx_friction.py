"""The full interface law inside CalculiX against the engine (issue 30; the optional scene
``ccx_friction``, workflow rule ``ccx_friction``; docs/ccx.md).

Decks, each run by ``roughcontact ccx run`` (:func:`roughcontact.ccx.run.run_deck_in_ccx`, the
ccx of ``roughcontact ccx build``) and by ``roughcontact fe run`` (quadratic family) on the
same file with the same law file:

* **block** — the block on a base of :mod:`roughcontact.examples.block_on_base` (an aluminium
  block on a larger steel base, C3D20) with the orthotropic hardening friction of section 8.1:
  an eccentric pressure, then a force along x (a tangential step) with the pressure held; as
  written (each code grows the increments by its own rule) and **block-fixed**, the same deck
  with the same fixed increments in both (``--increments``): friction is path-dependent, so only
  there do the dissipations compare one to one;
* **punch a–c** — the punch of example 9.2 (:mod:`roughcontact.examples.punch`, the shipped
  deck punch.inp, the quarter) with the law files of Fig. 18's cases a–c: seated, loaded by the
  patch, unloaded.

Per deck and step: the mean displacement of the loaded node set (block: LOADED; punch:
PUNCHBOTTOMNODES), the largest relative tangential displacement of the contact faces (block:
CONTACTSLAVE − CONTACTMASTER at coincident nodes), the normal force Σ A p_N, the largest p_N
and plastic slip, and the dissipated energy Σ A D (A the area each interface point stands for).
Checks (``cfg["tolerances"]``): the mean displacement of every step; in the block's tangential
step the relative tangential displacement against the engine's largest; for block-fixed also
the dissipated energy. What remains between the codes is the face centre (the engine's 21-node
elements have a node there, the deck's C3D20 not) and, where the increments grow, the paths
(docs/ccx.md); points are not compared one to one (ccx's are per element, the engine's merged
per node pair).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

__all__ = ["SCENE", "TOOL", "INSTALL", "installed_tools", "scene_decks", "run_scene", "render_markdown", "skipped_line"]

SCENE = "ccx_friction"


#: the scene's tool (config/expected_verdicts.yaml ``requires``) and how to get it
TOOL, INSTALL = "ccx-with-the-law", "make ccx-build"


def skipped_line() -> str:
    """The one line of the skipped scene (VERIFICATION.md, the gate, the scene's page): no ccx
    built with the law; where the build cannot run, what to install (the build's own line)."""
    from ..ccx.build import missing_tools
    from .verify import skipped_text

    missing = missing_tools()
    return skipped_text(TOOL, f"apt-get install {' '.join(missing)}; {INSTALL}" if missing else INSTALL)


def installed_tools(expectations) -> list[str]:
    """The tools optional scenes require (:func:`.verify.required_tools`) that are at hand: a
    program on PATH, or for this scene the ccx built with the law (ccx.build.find_build)."""
    import shutil

    from ..ccx.build import find_build
    from .verify import required_tools

    return [t for t in required_tools(expectations) if (find_build() is not None if t == TOOL else shutil.which(t))]


def scene_decks(cfg, workdir) -> list[tuple[str, Path, Path, str, int | None]]:
    """(name, deck, law file, loaded node set, fixed increments or None) of every run of the
    scene, the decks written to ``workdir`` where generated. cfg: config ``ccx_friction``."""
    from ..examples.block_on_base import BlockOnBase, block_on_base_deck
    from ..examples.shipped import DECKS
    from ..fe.laws import Orthotropic

    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    b = cfg["block"]
    f = b["friction"]
    spec = BlockOnBase(refine=int(b["refine"]), pressure=float(b["pressure"]), increments=int(b["increments"]),
                       seating_pressure=float(b["seating_pressure"]), shear=float(b["shear"]),
                       friction=Orthotropic(tuple(f["mu_m"]), tuple(f["mu_o"]), tuple(f["n"]), tuple(f["kt_over_kn"])))
    (workdir / "block.inp").write_text(block_on_base_deck(spec))
    (workdir / "block.yaml").write_text(spec.law_file().to_yaml())
    decks = [("block", workdir / "block.inp", workdir / "block.yaml", "LOADED", None),
             ("block-fixed", workdir / "block.inp", workdir / "block.yaml", "LOADED", spec.increments)]
    decks += [(f"punch-{case}", DECKS / "punch.inp", DECKS / f"punch-{case}.yaml", "PUNCHBOTTOMNODES", None)
              for case in cfg["punch_cases"]]
    return decks


def _relative_tangential(run, step: int, xyz) -> np.ndarray | None:
    ns = run["steps"][step]["node_sets"]
    if "CONTACTSLAVE" not in ns:
        return None
    s = dict(zip(ns["CONTACTSLAVE"]["nodes"], np.asarray(ns["CONTACTSLAVE"]["u"])))
    m = dict(zip(ns["CONTACTMASTER"]["nodes"], np.asarray(ns["CONTACTMASTER"]["u"])))
    by_place = {tuple(np.round(xyz[n], 9)): n for n in m}
    return np.array([s[n][:2] - m[by_place[tuple(np.round(xyz[n], 9))]][:2] for n in sorted(s)])


def _step_row(name, k, ccx, engine, result, loaded, xyz):
    """One deck's step: the engine's ``fe run`` JSON ``engine`` and its DeckResult ``result`` (the
    points' areas and dissipation, which the JSON does not carry)."""
    from ..interface import friction

    fc = ccx["steps"][k]["interface"]
    fe = {**engine["steps"][k]["interface"], "D": result.step_end(k + 1).state[:, friction.DISSIPATION]}
    areas = result.problem.points.weights
    uc = np.asarray(ccx["steps"][k]["node_sets"][loaded]["u"]).mean(axis=0)
    ue = np.asarray(engine["steps"][k]["node_sets"][loaded]["u"]).mean(axis=0)
    row = {"deck": name, "step": k + 1, "ccx_u_mean": uc.tolist(), "engine_u_mean": ue.tolist(),
           "u_rel_difference": float(np.linalg.norm(uc - ue) / np.linalg.norm(ue))}
    for code, f, a in (("ccx", fc, np.asarray(ccx["interface_area"])), ("engine", fe, areas)):
        row[f"{code}_normal_force"] = float(np.sum(a * np.asarray(f["p_N"])))
        row[f"{code}_p_N_max"] = float(np.max(f["p_N"]))
        row[f"{code}_slip_max_um"] = float(np.max(np.hypot(f["slip_1_um"], f["slip_2_um"])))
        row[f"{code}_dissipation"] = float(np.sum(a * np.asarray(f["D"])))
        row[f"{code}_slipping"] = int(f["status"].count("slip"))
    rc, re = _relative_tangential(ccx, k, xyz), _relative_tangential(engine, k, xyz)
    if rc is not None:
        largest = float(np.abs(re).max())
        row["tangential_largest_um"] = 1000.0 * largest
        row["tangential_difference"] = float(np.abs(rc - re).max() / largest) if largest > 0 else 0.0
    return row


def _check(name, quantity, step, ok, detail, description, target, value, error, tol):
    from .calculix import _check as calculix_check

    return calculix_check(f"ccx-{name}", quantity, f"step{step}", "step", ok, detail, description, target, value,
                          error, tol["rtol"], tol["why"], scene=SCENE)


def _checks(row, last: bool, tol) -> list:
    """The checks of one deck's step (module docstring)."""
    name, k = row["deck"], row["step"]
    out = [_check(name, "loaded_u_mean", k, row["u_rel_difference"] <= tol["displacement"]["rtol"],
                  f"|u_ccx - u_engine| / |u_engine| = {row['u_rel_difference']:.2%} (mean over {row['loaded']})",
                  f"{name}: the mean displacement of {row['loaded']} in ccx (the law as a user element) and the engine",
                  np.linalg.norm(row["engine_u_mean"]), np.linalg.norm(row["ccx_u_mean"]), row["u_rel_difference"],
                  tol["displacement"])]
    if "tangential_difference" in row and last:
        out.append(_check(name, "tangential_jump", k, row["tangential_difference"] <= tol["tangential"]["rtol"],
                          f"largest |difference| {row['tangential_difference']:.2%} of the engine's largest "
                          f"{row['tangential_largest_um']:.4g} um",
                          f"{name}: the relative tangential displacement of the contact faces, ccx and the engine",
                          row["tangential_largest_um"], row["tangential_largest_um"], row["tangential_difference"],
                          tol["tangential"]))
    if row["fixed"] and last:
        error = row["ccx_dissipation"] / row["engine_dissipation"] - 1.0
        out.append(_check(name, "dissipation", k, abs(error) <= tol["dissipation"]["rtol"],
                          f"sum A D: ccx {row['ccx_dissipation']:.6g}, engine {row['engine_dissipation']:.6g} "
                          f"({error:+.2%})", f"{name}: the energy dissipated by friction, the same increments in both",
                          row["engine_dissipation"], row["ccx_dissipation"], error, tol["dissipation"]))
    return out


def run_scene(cfg, workdir, executable, *, progress=print):
    """Every run in ccx and in the engine; (rows, checks, timings). cfg: config ``ccx_friction``."""
    from ..ccx.run import run_deck_in_ccx
    from ..fe.deck import read_deck
    from ..fe.deck_run import run_deck_file

    rows, checks, timings = [], [], {}
    for name, deck, laws, loaded, increments in scene_decks(cfg, workdir):
        t0 = time.perf_counter()
        ccx = run_deck_in_ccx(deck, laws, executable, keep=Path(workdir) / name, progress=progress,
                              increments=increments)
        timings[f"ccx-{name}"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        result = run_deck_file(deck, laws, increments=increments)
        timings[f"engine-{name}"] = time.perf_counter() - t0
        engine = result.summary()
        d = read_deck(deck)
        xyz = dict(zip(d.node_ids.tolist(), d.coords))
        n = len(engine["steps"])
        for k in range(n):
            row = {**_step_row(name, k, ccx, engine, result, loaded, xyz), "loaded": loaded,
                   "fixed": increments is not None}
            rows.append(row)
            progress(f"{name} step {k + 1}: mean u {row['u_rel_difference']:.2%} apart")
            checks += _checks(row, k == n - 1, cfg["tolerances"])
    return rows, checks, timings


def render_markdown(rows, checks, timings, build: dict, skipped_reason: str = "") -> str:
    """paper_figures/ccx_friction.md."""
    lines = ["# The interface law inside CalculiX: ccx with the law as a user element against the engine", ""]
    if skipped_reason:
        return "\n".join(lines + [skipped_reason, ""])
    lines += [f"ccx {build.get('ccx', '?')} built by `roughcontact ccx build` (key {build.get('key', '?')}, "
              f"gfortran {build.get('gfortran', '?')}); docs/ccx.md. Per deck and step: the mean displacement of the "
              "loaded node set (ccx, engine, relative difference), the normal force Σ A p_N [N], the largest p_N "
              "[N/mm²], the largest plastic slip [µm], the dissipated energy Σ A D [N/mm² · µm · mm²] and the slipping "
              "points, ccx / engine.", "",
              "| deck | step | mean u ccx [mm] | mean u engine [mm] | difference | normal force | p_N max | slip max | "
              "dissipation | slipping points |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        def pair(key, fmt=".4g"):
            return f"{r['ccx_' + key]:{fmt}} / {r['engine_' + key]:{fmt}}"

        lines.append(f"| {r['deck']} | {r['step']} | {', '.join(f'{v:.4g}' for v in r['ccx_u_mean'])} | "
                     f"{', '.join(f'{v:.4g}' for v in r['engine_u_mean'])} | {r['u_rel_difference']:.2%} | "
                     f"{pair('normal_force')} | {pair('p_N_max')} | {pair('slip_max_um')} | {pair('dissipation')} | "
                     f"{pair('slipping', 'd')} |")
    tang = [r for r in rows if "tangential_difference" in r]
    if tang:
        lines += ["", "Relative tangential displacement of the contact faces (at coincident nodes): "
                  + "; ".join(f"{r['deck']} step {r['step']}: largest {r['tangential_largest_um']:.4g} µm, "
                              f"difference {r['tangential_difference']:.2%} of it" for r in tang),
                  "", "block-fixed is block with the same fixed increments in both codes (`--increments`); as "
                  "written, each code grows the increments by its own rule and friction is path-dependent "
                  "(docs/ccx.md)."]
    lines += ["", "Checks: " + ", ".join(f"{c.id} {c.verdict}" for c in checks), "",
              "Seconds: " + ", ".join(f"{k} {v:.1f}" for k, v in timings.items()), ""]
    return "\n".join(lines)
