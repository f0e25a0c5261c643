"""Example 9.2 as the paper reports it: Table 5 (the dissipation D of cases a, b, c with both
element families) under every reading of what the paper leaves open, with the frictionless
upper bound; the prose of section 9.2 as checks; the sensitivity of D. The runs are
:func:`roughcontact.examples.punch.run_punch` of the typed runs
:func:`roughcontact.examples.runs.punch_groups` builds; this module judges their datasets
(:func:`roughcontact.examples.punch.to_dataset`) and reports (no I/O).

A run's dataset has, per load level and contact point of the quarter, t_x, t_y, p_N [N/mm²],
the plastic slips slip_x_um, slip_y_um and the relative tangential displacements from the seated
state jump_x_um, jump_y_um [µm], the status; attributes D_<at>_<weight>_whole [N·mm or N/mm] and
max_index (the level of the maximum load).
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

from ..examples.punch import bound, mu_max
from ..interface.friction import SLIP, STICK
from .report import md_escape
from .verify import NOT_REPRODUCED, REPRODUCED, Check, claim_id, table_cell_checks

__all__ = ["FAMILY_ROW", "READING_LABEL", "slip_panel", "slip_rows", "reading_models", "table5_results",
           "run_bounds", "table5_checks", "punch_claims", "bound_checks", "reading_rows", "render_readings_markdown"]

#: the printed rows of Table 5 by element family
FAMILY_ROW = {"quadratic": "21-node", "cubic": "28-node"}

#: how the report and Figs 18/19 name the readings
READING_LABEL = {"main": "1000 N on the whole punch", "quarter": "1000 N on the quarter model",
                 "secant": "secant tangential law", "start": "k_T at the increment's start"}


def _reading_of(name: str, run: Mapping[str, Any]) -> str:
    """The reading (or sensitivity variant) of a run named <family>-<reading>-<case>."""
    family = run.family
    return name[len(family) + 1:len(name) - len(run.case) - 1]


def reading_models(families, readings) -> dict[str, dict[str, str]]:
    """The columns of Table 5: model "fe-<family>" (main reading) or "fe-<family>-<reading>"
    → its printed column and label."""
    out = {}
    for reading in readings:
        for fam in families:
            what = ("1000 N on the whole punch, (93) with k_T at the end of the increment" if reading == "main"
                    else f"the main reading but {READING_LABEL.get(reading, reading)}")
            out[f"fe-{fam}" + ("" if reading == "main" else f"-{reading}")] = {
                "paper_column": FAMILY_ROW[fam], "label": f"{FAMILY_ROW[fam]} elements, {what}"}
    return out


def table5_results(attrs: Mapping[str, Mapping[str, Any]], runs: Mapping[str, Mapping[str, Any]],
                   d_attr: str, readings) -> dict[str, dict[str, np.ndarray]]:
    """{model (:func:`reading_models`): {"D": values at the cases a, b, c}} of the frictional runs
    of the given readings, D read from the dataset attribute ``d_attr`` (e.g.
    "D_max_area_whole"), for verify.table_cell_checks."""
    out: dict[str, dict[str, list]] = {}
    for name, run in runs.items():
        reading = _reading_of(name, run)
        if run.case == "frictionless" or reading not in readings:
            continue
        model = f"fe-{run.family}" + ("" if reading == "main" else f"-{reading}")
        d = out.setdefault(model, {"D": [math.nan] * 3})
        d["D"]["abc".index(run.case)] = float(attrs[name][d_attr])
    return {m: {q: np.asarray(v) for q, v in per.items()} for m, per in out.items()}


def run_bounds(data: Mapping[str, Any], runs: Mapping[str, Any]) -> dict[str, float]:
    """The frictionless bound (:func:`roughcontact.examples.punch.bound`, whole punch [N·mm]) of
    every frictional run, from its own pressures and the relative displacements of the
    frictionless run it names (``run.bound``), from the unloaded start (the seated ones plus the
    seating's own, where the plastic slips of D start)."""
    out = {}
    for name, run in runs.items():
        if run.case == "frictionless":
            continue
        ds, free = data[name], data[run.bound]
        k, kf = int(ds.attrs["max_index"]), int(free.attrs["max_index"])
        jx, jy = (free[f"jump_{a}_um"].values[kf] + free[f"seating_jump_{a}_um"].values for a in "xy")
        slip = np.hypot(jx, jy) / 1000.0  # µm → mm
        out[name] = bound(ds["point_weight"].values, ds["p_N"].values[k], slip, mu_max(run.case))
    return out


def table5_checks(data: Mapping[str, Any], runs: Mapping[str, Any], cfg: Mapping[str, Any],
                  paper_table: Mapping[str, Any]) -> tuple[list[Check], dict, dict[str, float]]:
    """Every check of example 9.2 from the runs' datasets (run name → dataset; ``cfg``:
    config.yaml fe.punch): Table 5's cells under each reading, the prose of section 9.2 under the
    main reading and the sensitivity's, the printed D against each reading's bound. Returns the
    checks, the Table 5 models and the bounds."""
    readings = ["main", *cfg["readings"]]
    models = reading_models(cfg["families"], readings)
    attrs = {name: ds.attrs for name, ds in data.items()}
    results = table5_results(attrs, runs, cfg["d_attr"], readings)
    tolerances = {"printed_rounding": cfg["tolerances"]["printed_rounding"],
                  **{m: {"D": cfg["tolerances"]["D"]} for m in models}}
    checks = table_cell_checks("table5", paper_table, results, models, tolerances)
    claims_cfg = {**cfg["claims"], "d_attr": cfg["d_attr"]}
    for reading in ("main", cfg["sensitivity"]["reading"]):
        for fam in cfg["families"]:
            cases = {runs[n].case: data[n] for n in runs
                     if n.startswith(f"{fam}-{reading}-") and runs[n].case != "frictionless"}
            checks += punch_claims("table5", fam, cases, claims_cfg, reading)
    bounds = run_bounds(data, runs)
    for reading in readings:
        per_model = {f"fe-{fam}": {c: bounds[f"{fam}-{reading}-{c}"] for c in "abc"} for fam in cfg["families"]}
        checks += bound_checks("table5", per_model, paper_table, models, reading)
    return checks, models, bounds


def slip_panel(ds) -> dict[str, np.ndarray]:
    """One panel of Figs 18/19 (paper.plots.punch_slips): the points' x, y [mm], plastic slips ux, uy
    [µm] and status at the maximum load."""
    return {"x": ds["x"].values, "y": ds["y"].values, "ux": _at_max(ds, "slip_x_um"),
            "uy": _at_max(ds, "slip_y_um"), "status": _at_max(ds, "status")}


#: units of the columns of :func:`slip_rows` whose names do not carry them (CSV header)
SLIP_ROW_UNITS = {"t_x": "N/mm^2", "t_y": "N/mm^2", "p_N": "N/mm^2", "status": "1"}


def slip_rows(ds, **labels) -> list[dict]:
    """The CSV rows of a panel: ``labels`` (e.g. reading, case), then per point x_mm, y_mm,
    slip_x_um, slip_y_um, t_x, t_y, p_N [N/mm²] and status at the maximum load."""
    cols = {"x_mm": ds["x"].values, "y_mm": ds["y"].values,
            **{k: _at_max(ds, k) for k in ("slip_x_um", "slip_y_um", "t_x", "t_y", "p_N")}}
    status = _at_max(ds, "status")
    return [{**labels, **{k: float(v[i]) for k, v in cols.items()}, "status": int(status[i])}
            for i in range(status.size)]


def _claim(scene, cid, text, ok, detail, why, value=math.nan, tolerance=math.nan) -> Check:
    return Check(id=claim_id(scene, cid), kind="claim", scene=scene, verdict=REPRODUCED if ok else NOT_REPRODUCED,
                 detail=detail, description=text, value=float(value), tolerance=float(tolerance), tolerance_why=why)


def _at_max(ds, name):
    return ds[name].values[int(ds.attrs["max_index"])]


def _slip(ds):
    """|u_T^p| [µm] per point at the maximum load."""
    return np.hypot(_at_max(ds, "slip_x_um"), _at_max(ds, "slip_y_um"))


def _mirror(ds):
    """Index of each point's mirror image (x ↔ y)."""
    x, y = ds["x"].values, ds["y"].values
    key = {(round(a, 6), round(b, 6)): i for i, (a, b) in enumerate(zip(x, y))}
    return np.array([key[(round(b, 6), round(a, 6))] for a, b in zip(x, y)])


def punch_claims(scene: str, family: str, data: Mapping[str, Any], cfg: Mapping[str, Any],
                 reading: str = "main") -> list[Check]:
    """The prose of section 9.2 on one element family's runs of cases a, b, c under one reading
    (``data``: case → dataset), each checked with numbers; ``cfg`` holds the thresholds
    (config.yaml fe.punch.claims) and ``d_attr``. Check ids: claim:<scene>/<reading>/<family>/…"""
    a, b, c = (data[k] for k in "abc")
    tag = f"{reading}/{FAMILY_ROW[family]}"
    out = []
    slips = {k: _slip(ds) for k, ds in data.items()}
    # 1. adhesion in the centre, slip at the edge
    parts, ok = [], True
    for k, ds in data.items():
        st, x, y = _at_max(ds, "status"), ds["x"].values, ds["y"].values
        centre = st[np.argmin(np.hypot(x, y))] == STICK
        edge = np.isclose(np.maximum(x, y), max(x.max(), y.max()))
        ok &= bool(centre and np.any(st[edge] == SLIP))
        parts.append(f"{k}: centre {'stick' if centre else 'not stick'}, {int(np.count_nonzero(st[edge] == SLIP))} "
                     f"of {int(edge.sum())} edge points slip")
    out.append(_claim(scene, f"{tag}/stick-centre-slip-edge",
                      "Adhesion in the centre of the contact surface and a region of slip at the punch edge.",
                      ok, "; ".join(parts), "status at the maximum load (section 9.2)"))
    # 2. symmetry of (a), (b) in x <-> y, not of (c)
    cfg_sym = cfg["symmetry"]
    def asym(ds):
        m = _mirror(ds)
        sx, sy = _at_max(ds, "slip_x_um"), _at_max(ds, "slip_y_um")
        scale = max(np.max(np.hypot(sx, sy)), 1e-300)
        return float(np.max(np.abs(sx - sy[m])) / scale) if np.any(sx) or np.any(sy) else math.nan
    ab, cc = max(asym(a), asym(b)), asym(c)
    ok = ab <= cfg_sym["rtol"] and cc > cfg_sym["asymmetry"]
    out.append(_claim(scene, f"{tag}/symmetry-a-b-not-c",
                      "For the same directional parameters mu and nu and the same axial compliance the contact behaves "
                      "symmetrically (cases a, b); not for other axial parameters (case c).",
                      ok, f"relative x<->y asymmetry of the plastic slips: a, b {ab:.1e} (<= {cfg_sym['rtol']:g}), "
                          f"c {cc:.2e} (> {cfg_sym['asymmetry']:g})", cfg_sym["why"], value=cc))
    # 3. smaller plastic slip for larger friction coefficients: (a) mu = 0.2 against (b) mu = 0.5
    sa, sb = float(slips["a"].max()), float(slips["b"].max())
    out.append(_claim(scene, f"{tag}/smaller-slip-for-larger-mu",
                      "The values of the plastic displacements are smaller for larger principal friction coefficients.",
                      sa > sb, f"largest |u_T^p|: a (mu_m = 0.2) {sa:.3g} um, b (mu_m = 0.5) {sb:.3g} um",
                      "case a against case b (same k_T)", value=sa - sb))
    # 4. larger plastic slip for the larger axial contact stiffness: (c) k_Ty = k_N against (b) 0.7 k_N
    yc, yb = float(np.max(np.abs(_at_max(c, "slip_y_um")))), float(np.max(np.abs(_at_max(b, "slip_y_um"))))
    out.append(_claim(scene, f"{tag}/larger-slip-for-larger-axial-stiffness",
                      "The plastic displacements are greater for greater values of the axial contact stiffness.",
                      yc > yb, f"largest |u_y^p|: c (k_Ty = k_N) {yc:.3g} um, b (k_Ty = 0.7 k_N) {yb:.3g} um",
                      "case c against case b (same mu)", value=yc - yb))
    # 5. the greatest D in case (b)
    D = {k: float(ds.attrs[cfg["d_attr"]]) for k, ds in data.items()}
    out.append(_claim(scene, f"{tag}/largest-D-in-b",
                      "The greatest magnitude of the frictional dissipation energy was obtained for case b.",
                      D["b"] > max(D["a"], D["c"]), ", ".join(f"D_{k} = {v:.4g} N mm" for k, v in D.items()),
                      f"D read as {cfg['d_attr']}"))
    # 6. on unloading the tangential forces reverse while the total displacements keep their sign:
    #    the resultants over the slipped points (the paper speaks of forces, and single points
    #    where the slip direction turns may differ; their share is in the detail)
    parts, ok = [], True
    for k, ds in data.items():
        slipped = _slip(ds) > 0.0
        if not np.any(slipped):
            ok = False
            parts.append(f"{k}: nothing slipped")
            continue
        w = ds["point_weight"].values * slipped
        tm, te = _at_max(ds, "t_x"), ds["t_x"].values[-1]
        jm, je = _at_max(ds, "jump_x_um"), ds["jump_x_um"].values[-1]
        Fm, Fe, Jm, Je = (float(np.sum(w * v)) for v in (tm, te, jm, je))
        case_ok = Fm != 0.0 and np.sign(Fe) == -np.sign(Fm) and Jm != 0.0 and np.sign(Je) == np.sign(Jm)
        ok &= bool(case_ok)
        sel = slipped & (tm != 0.0)
        rev = float(np.mean(np.sign(te[sel]) == -np.sign(tm[sel])))
        keep = float(np.mean(np.sign(je[sel]) == np.sign(jm[sel])))
        parts.append(f"{k}: Σ w t_x {Fm:.3g} → {Fe:.3g} N, Σ w u_x {Jm:.3g} → {Je:.3g} mm²·µm "
                     f"(points: t_x reversed at {100 * rev:.0f} %, u_x kept its sign at {100 * keep:.0f} %)")
    out.append(_claim(scene, f"{tag}/unloading-reverses-tractions",
                      "In the unloading case the tangential forces change sign retaining the sign of the total displacements.",
                      ok, "; ".join(parts), cfg["unloading"]["why"]))
    # 7. the reversal comes at a greater load for the smaller friction coefficient
    def reversal_load(ds):
        k0 = int(ds.attrs["max_index"])
        F = (ds["t_x"].values * ds["point_weight"].values * (ds["x"].values > 0)).sum(axis=1)
        for k in range(k0 + 1, F.size):
            if np.sign(F[k]) == -np.sign(F[k0]) and F[k0] != 0.0:
                return float(ds["load_quarter"].values[k])
        return math.nan
    ra, rb = reversal_load(a), reversal_load(b)
    out.append(_claim(scene, f"{tag}/earlier-reversal-for-smaller-mu",
                      "For smaller friction coefficients the change of sign of the tangential forces corresponds to a "
                      "greater value of the force at unloading.",
                      ra > rb, f"quarter load at which the resultant tangential force Σ w t_x reverses: a {ra:.4g} N, "
                               f"b {rb:.4g} N", "case a (mu_m = 0.2) against case b (mu_m = 0.5)"))
    return out


def bound_checks(scene: str, bounds: Mapping[str, Mapping[str, float]], paper_table: Mapping[str, Any],
                 models: Mapping[str, Mapping[str, Any]], reading: str = "main") -> list[Check]:
    """One row per printed cell: is the printed D below the frictionless upper bound of our
    reading? (``bounds``: model → case → bound [N·mm].) A printed D above the bound cannot be the
    dissipation of that reading's problem, whatever the mesh or the friction law's details."""
    out = []
    for model, per_case in bounds.items():
        column = paper_table["columns"][models[model]["paper_column"]]["D"]
        for case, printed in zip(paper_table["rows"], column):
            b = per_case[case]
            ok = float(printed) <= b
            out.append(_claim(scene, f"{reading}/{models[model]['paper_column']}/printed-D-within-bound/case={case}",
                              f"The printed D of case {case} ({models[model]['paper_column']}) can be a dissipation of "
                              f"the {reading} reading's problem: it lies below that problem's frictionless bound.",
                              ok, f"printed {printed} N mm {'≤' if ok else '>'} bound {b:.4g} N mm "
                                  f"(μ_max Σ w p_N |δ_T,free|, whole punch)",
                              "an upper bound of D: friction only reduces the relative slip and |t_T| ≤ μ p_N",
                              value=b))
    return out


def reading_rows(attrs: Mapping[str, Mapping[str, Any]], runs: Mapping[str, Mapping[str, Any]],
                 bounds: Mapping[str, float]) -> list[dict]:
    """One row per run: the reading, family, case, D under every definition, the bound, the
    number of slipped points and the largest share of the friction limit used at the maximum load
    (1: some point slips), sizes and time."""
    rows = []
    for name, run in runs.items():
        a = attrs[name]
        family = run.family
        variant = _reading_of(name, run)
        rows.append({"run": name, "variant": variant, "family": family,
                     "case": run.case, **{k: float(v) for k, v in a.items() if str(k).startswith("D_")},
                     "bound": bounds.get(name, math.nan), "slipped_points": int(a["slipped_points"]),
                     "utilisation_max": float(a["utilisation_max"]),
                     "dofs": int(a["dofs"]), "interface_points": int(a["interface_points"]),
                     "seconds": float(a["seconds"])})
    return rows


def render_readings_markdown(rows: list[dict], checks: list[Check], provenance: Mapping[str, Any],
                             d_attr: str) -> str:
    """Table 5 under every reading, next to the frictionless bound, and the checks."""
    lines = ["# Example 9.2: Table 5 under every reading, the frictionless bound, the sensitivity", "",
             "Generated by the Snakemake workflow; " + ", ".join(f"{k} `{v}`" for k, v in provenance.items()) + ".",
             f"D in N·mm on the whole punch unless marked; the main definition is `{d_attr}` (t_T·u_T^p × the "
             "point's area at the maximum load). *bound*: μ_max Σ w p_N |δ_T| of the frictionless problem, an "
             "upper bound of D (friction only reduces the relative slip, |t_T| ≤ μ p_N). "
             "*max t_T/(μ p_N)*: the largest share of the friction limit (91) any point uses at the maximum "
             "load; below 1 nothing slips.", "",
             "| variant | elements | case | D (area, max) | D (area, end) | D (work, max) | D (unweighted, max) [N/mm] "
             "| bound | slipped points | max t_T/(μ p_N) | dofs | time [s] |", "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in sorted(rows, key=lambda r: (r["variant"] != "main", r["variant"].startswith("sens-"), r["variant"],
                                         r["family"], r["case"])):
        lines.append(f"| {r['variant']} | {FAMILY_ROW[r['family']]} | {r['case']} | {r['D_max_area_whole']:.4g} "
                     f"| {r['D_end_area_whole']:.4g} | {r['D_max_work_whole']:.4g} | {r['D_max_none_whole']:.4g} "
                     f"| {r['bound']:.4g} | {r['slipped_points']} | {r['utilisation_max']:.3f} | {r['dofs']} | {r['seconds']:.1f} |")
    lines += ["", "## Checks", "", "| check | verdict | detail |", "|---|---|---|"]
    lines += [f"| `{c.id}` | {c.verdict} | {md_escape(c.detail)} |" for c in checks]
    return "\n".join(lines) + "\n"
