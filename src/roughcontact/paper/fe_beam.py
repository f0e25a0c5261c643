"""Example 9.1 as the paper reports it: Table 4 (cells, prose claims, equilibrium), the study of
what the paper leaves open (tangential restraint, E*, printed Y, mesh) and the runs' speed and
size. The runs themselves are :func:`roughcontact.examples.beam.run_beam` of the typed runs
:func:`roughcontact.examples.runs.beam_runs` builds from config.yaml ``fe.beam``; this module only
judges and reports them
(no I/O; the workflow scripts read and write), so editing it never re-runs a computation.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

from .report import md_escape
from .verify import NOT_REPRODUCED, REPRODUCED, Check, claim_id, numerics_id

__all__ = ["table4_results", "table4_claims", "equilibrium_checks", "study_checks", "QUANTITIES"]

#: Table 4's quantities and the dataset attributes they come from
QUANTITIES = {"u_N_centre": "u_N_centre_um", "u_N_end": "u_N_end_um"}


def table4_results(attrs: Mapping[str, Mapping[str, Any]], runs: Mapping[str, Any],
                   cases: list[str]) -> dict[str, dict[str, np.ndarray]]:
    """{model "fe-<family>": {quantity: values at the printed cases}} from the runs' dataset
    attributes (``attrs[run]``), for :func:`roughcontact.paper.verify.table_cell_checks`."""
    out: dict[str, dict[str, list]] = {}
    for name, run in runs.items():
        model = out.setdefault(f"fe-{run.family}", {q: [math.nan] * len(cases) for q in QUANTITIES})
        for q, attr in QUANTITIES.items():
            model[q][cases.index(run.case)] = float(attrs[name][attr])
    return {m: {q: np.asarray(v) for q, v in per.items()} for m, per in out.items()}


def _claim(scene, cid, text, ok, detail, why, value=math.nan, error=math.nan, tolerance=math.nan) -> Check:
    return Check(id=claim_id(scene, cid), kind="claim", scene=scene, verdict=REPRODUCED if ok else NOT_REPRODUCED,
                 detail=detail, description=text, value=float(value), error=float(error),
                 tolerance=float(tolerance), tolerance_why=why)


def table4_claims(scene: str, results: Mapping[str, Mapping[str, np.ndarray]], cases: Mapping[str, Mapping],
                  open_points: Mapping[str, int], claims_cfg: Mapping[str, Any]) -> list[Check]:
    """The prose of 9.1 about Table 4 / Fig. 13 as checks, for every element family:
    signs of the elastic rows, their order in m00, "strongly depend on m00", "no systematic
    difference between elastic and elasto-plastic", "some nodes at the outer edge … not in contact"."""
    names = list(cases)
    elastic = [i for i, c in enumerate(names) if cases[c]["law"] == "elastic"]
    by_m00 = sorted(elastic, key=lambda i: -cases[names[i]]["m00"])  # decreasing m00
    out = []
    for model, r in results.items():
        c, e = r["u_N_centre"], r["u_N_end"]
        signs = bool(np.all(c[elastic] < 0.0) and np.all(e[elastic] > 0.0))
        out.append(_claim(
            scene, f"{model}/elastic-signs",
            "Elastic rows of Table 4: the centre approaches (u_N < 0) and the ends open (u_N > 0).",
            signs, f"centre {np.round(c[elastic], 4).tolist()} um, end {np.round(e[elastic], 4).tolist()} um",
            "signs of the printed elastic rows (negative centre, positive ends)"))
        order = bool(np.all(np.diff(c[by_m00]) > 0.0) and np.all(np.diff(e[by_m00]) > 0.0))
        out.append(_claim(
            scene, f"{model}/m00-ordering",
            "Elastic rows of Table 4: the centre approach shrinks and the end opening grows as m00 falls.",
            order, f"by m00 = {[cases[names[i]]['m00'] for i in by_m00]}: centre {np.round(c[by_m00], 4).tolist()}, "
                   f"end {np.round(e[by_m00], 4).tolist()} um", "the order of the printed elastic rows"))
        cfg = claims_cfg["m00_dependence"]
        ratio = c[by_m00[0]] / c[by_m00[-1]]
        out.append(_claim(
            scene, f"{model}/strong-m00-dependence",
            "The maximum surface deflections occur in the middle of the beam and these values strongly depend on m00.",
            ratio >= cfg["ratio"], f"centre deflection ratio m00 = {cases[names[by_m00[0]]]['m00']} / "
                                   f"{cases[names[by_m00[-1]]]['m00']}: {ratio:.3f} (>= {cfg['ratio']:g})",
            cfg["why"], value=ratio, tolerance=cfg["ratio"]))
        cfg = claims_cfg["elastoplastic_equals_elastic"]
        pairs = [(i, j) for i in elastic for j, n in enumerate(names)
                 if cases[n]["law"] == "elastoplastic" and cases[n]["m00"] == cases[names[i]]["m00"]]
        diff = max(max(abs(c[j] - c[i]), abs(e[j] - e[i])) for i, j in pairs)
        out.append(_claim(
            scene, f"{model}/no-systematic-elastoplastic-difference",
            "There is no systematic difference between the results obtained by the elastic and elasto-plastic models.",
            diff <= cfg["atol"], f"largest |elasto-plastic − elastic| over the rows: {diff:.2e} um "
                                 f"(<= {cfg['atol']:g} um); the printed rows differ by up to 0.483 um",
            cfg["why"], value=diff, error=diff, tolerance=cfg["atol"]))
        n_open = sum(int(open_points[model][n]) for n in names)
        out.append(_claim(
            scene, f"{model}/edge-separation",
            "In several cases some nodes at the outer edge of the beam were detected not to be in contact (separation occurs).",
            n_open > 0, f"open interface points at the final load, summed over the six cases: {n_open}",
            "an open point has p_N = 0 (beyond the law's light-end tail)"))
    return out


def equilibrium_checks(scene: str, attrs: Mapping[str, Mapping[str, Any]], runs: Mapping[str, Any],
                       cfg: Mapping[str, Any]) -> list[Check]:
    """One row per run: |integrated interface pressure − applied load| / applied load at the
    final load (every result records it; Newton's force criterion bounds it)."""
    out = []
    for name, run in runs.items():
        err = float(attrs[name]["equilibrium_error"])
        ok = err <= cfg["rtol"]
        out.append(Check(
            id=numerics_id(scene, f"fe-{run.family}", "equilibrium", run.case, "case"), kind="numerics",
            scene=scene, verdict=REPRODUCED if ok else NOT_REPRODUCED,
            detail=f"|Σ w p_N − P|/P = {err:.1e} {'≤' if ok else '>'} {cfg['rtol']:.0e}",
            description="equilibrium: applied load = integrated interface pressure", model=f"fe-{run.family}",
            quantity="equilibrium", s=run.case, value=err, error=err, tolerance=cfg["rtol"],
            tolerance_why=cfg["why"]))
    return out


def study_checks(scene: str, main: Mapping[str, float], variants: Mapping[str, Mapping[str, float]],
                 cfg: Mapping[str, Any], elastic_case: Mapping[str, str]) -> list[Check]:
    """Checks of the study: mesh convergence (main mesh vs the finest, per family), the E*
    choice, and the centre's insensitivity to the tangential restraint.

    main      {"<family>/<case>/<quantity>": value of the main run}.
    variants  {"<family>/<case>/<variant>": {quantity: value}} (variant "mesh-<nx>x<nz>",
              "estar-caption", "printed-Y", "<tangential>[-<mu>]").
    elastic_case  {case: the elastic case of the same m00} (the reference of "printed-Y")."""
    out = []
    conv = cfg["convergence"]
    finest = max((v for v in variants if "/mesh-" in v), key=lambda v: _mesh_size(v), default=None)
    for key in sorted(v for v in variants if "/mesh-" in v and _mesh_size(v) == _mesh_size(finest)):
        family, case, variant = key.split("/")
        for q in QUANTITIES:
            ref, val = variants[key][q], main[f"{family}/{case}/{q}"]
            err = (val - ref) / abs(ref)
            ok = abs(err) <= conv["rtol"]
            out.append(Check(
                id=numerics_id(scene, f"fe-{family}", q, case, "case") + "/mesh", kind="numerics", scene=scene,
                verdict=REPRODUCED if ok else NOT_REPRODUCED,
                detail=f"main mesh {val:.5f} um vs {variant} {ref:.5f} um: {100 * err:+.3f} %",
                description="mesh convergence of the beam (main mesh vs the finest)", model=f"fe-{family}",
                quantity=q, s=case, unit="um", target=ref, value=val, error=err, tolerance=conv["rtol"],
                tolerance_why=conv["why"]))
    eff = cfg["E_star_effect"]
    dev = [abs(variants[k][q] - main[f"{k.split('/')[0]}/{k.split('/')[1]}/{q}"])
           for k in variants if k.endswith("/estar-caption") for q in QUANTITIES]
    if dev:
        out.append(_claim(scene, "estar-choice", "E* = 1.14e5 (caption) or 1.127e5 (text) changes the deflections by < 0.001 um.",
                          max(dev) <= eff["atol"], f"largest change {max(dev):.2e} um over the elastic rows",
                          eff["why"], value=max(dev), error=max(dev), tolerance=eff["atol"]))
    ep = cfg["printed_Y_effect"]
    dev = [abs(variants[k][q] - main[f"{k.split('/')[0]}/{elastic_case[k.split('/')[1]]}/{q}"])
           for k in variants if k.endswith("/printed-Y") for q in QUANTITIES]
    if dev:
        out.append(_claim(scene, "elastoplastic-with-printed-Y-equals-elastic",
                          "With the printed Y = 2070 N/mm² (closure 'material'), the elasto-plastic deflections equal the elastic ones.",
                          max(dev) <= ep["atol"], f"largest |elasto-plastic (Y = 2070) − elastic| {max(dev):.2e} um",
                          ep["why"], value=max(dev), error=max(dev), tolerance=ep["atol"]))
    tan = cfg["centre_tangential"]
    dev = [abs(variants[k]["u_N_centre"] - main[f"{k.split('/')[0]}/{k.split('/')[1]}/u_N_centre"])
           for k in variants if k.split("/")[2].startswith(("stick", "coulomb"))]
    if dev:
        out.append(_claim(scene, "centre-insensitive-to-tangential-restraint",
                          "The centre deflections move by < 0.05 um across the tangential restraints (free, stick, Coulomb).",
                          max(dev) <= tan["atol"], f"largest change of the centre deflection {max(dev):.4f} um",
                          tan["why"], value=max(dev), error=max(dev), tolerance=tan["atol"]))
    return out


def _mesh_size(key: str | None) -> int:
    if key is None:
        return -1
    nx, nz = key.split("/mesh-")[1].split("x")
    return int(nx) * int(nz)


def variant_of(name: str) -> str:
    """The variant of a run name "<family>-<case>-<variant>"."""
    return name.split("-", 2)[2]


def study_rows(attrs: Mapping[str, Mapping[str, Any]], runs: Mapping[str, Any]) -> list[dict]:
    """One row per run: what varies, the deflections and the cost."""
    rows = []
    for name, run in runs.items():
        a = attrs[name]
        rows.append({
            "run": name, "family": run.family, "case": run.case, "m00": run.m00, "law": run.law,
            "variant": variant_of(name), "tangential": run.tangential, "mu": run.mu,
            "E_star": run.E_star, "n_x": a["spec_n_x"], "n_z": a["spec_n_z"],
            "u_N_centre_um": float(a["u_N_centre_um"]), "u_N_end_um": float(a["u_N_end_um"]),
            "open_points": int(a["open_points"]), "dofs": int(a["dofs"]), "interface_points": int(a["interface_points"]),
            "seconds": float(a["seconds"]),
        })
    return rows


def render_study_markdown(rows: list[dict], checks: list[Check], provenance: Mapping[str, Any]) -> str:
    """The study as Markdown: tangential restraint and E* (elastic rows, the variants' elements), then the
    mesh convergence (case 1, both families), then the checks."""
    head = ["# Example 9.1: what the paper leaves open, measured", "",
            "Generated by the Snakemake workflow; " + ", ".join(f"{k} `{v}`" for k, v in provenance.items()) + ".",
            "u_N in µm from the seated state (negative = approach). The main reading (free sliding, "
            "E* = E1/(1 − ν1²), the main mesh) is the `main` variant; Table 4 uses it.", ""]
    fam = next((r["family"] for r in rows if r["variant"] not in ("main",) and not r["variant"].startswith("mesh-")),
               "cubic")
    label = "28-node" if fam == "cubic" else "21-node"
    tan = [r for r in rows if r["family"] == fam and r["law"] == "elastic" and not r["variant"].startswith("mesh-")]
    lines = head + [f"## Tangential restraint and E* (elastic rows, {label} elements)", "",
                    "| m00 [µm²] | variant | tangential | μ | E* [N/mm²] | u_N centre | u_N end | open points |",
                    "|---:|---|---|---:|---:|---:|---:|---:|"]
    for r in sorted(tan, key=lambda r: (-r["m00"], r["variant"] != "main", r["variant"])):
        lines.append(f"| {r['m00']:g} | {r['variant']} | {r['tangential']} | {'' if r['mu'] is None else format(r['mu'], 'g')} "
                     f"| {r['E_star']:.6g} | {r['u_N_centre_um']:+.4f} | {r['u_N_end_um']:+.4f} | {r['open_points']} |")
    law = [r for r in rows if r["family"] == fam and r["variant"] in ("main", "printed-Y")]
    lines += ["", f"## Normal law ({label} elements, free sliding)", "",
              "| m00 [µm²] | law | closure | u_N centre | u_N end |", "|---:|---|---|---:|---:|"]
    for r in sorted(law, key=lambda r: (-r["m00"], r["law"], r["variant"])):
        closure = "–" if r["law"] == "elastic" else ("material, Y = 2070 N/mm²" if r["variant"] == "printed-Y"
                                                       else "yield-from-psi, ψ = 0.35")
        lines.append(f"| {r['m00']:g} | {r['law']} | {closure} | {r['u_N_centre_um']:+.6f} | {r['u_N_end_um']:+.6f} |")
    mesh = [r for r in rows if r["case"] == "1" and (r["variant"] == "main" or r["variant"].startswith("mesh-"))]
    lines += ["", "## Mesh convergence (case 1: m00 = 0.625, elastic, free sliding)", "",
              "| elements | n_x × n_z | dofs | interface points | u_N centre | u_N end | time [s] |",
              "|---|---:|---:|---:|---:|---:|---:|"]
    for r in sorted(mesh, key=lambda r: (r["family"], r["dofs"])):
        lines.append(f"| {r['family']} | {r['n_x']} × {r['n_z']} | {r['dofs']} | {r['interface_points']} "
                     f"| {r['u_N_centre_um']:+.5f} | {r['u_N_end_um']:+.5f} | {r['seconds']:.1f} |")
    lines += ["", "## Checks", "", "| check | verdict | detail |", "|---|---|---|"]
    lines += [f"| `{c.id}` | {c.verdict} | {md_escape(c.detail)} |" for c in checks]
    return "\n".join(lines) + "\n"
