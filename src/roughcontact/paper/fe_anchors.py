"""Engine-free anchors of the FE numbers the verification gate reports (issue 22).

Table 4 is checked against the paper in 20 % bands and the FE studies compare runs of the same
engine with each other, so an error common to every run (a lost factor, a wrong unit in the
output path) would leave the gate green. Here every reported number meets something that does
not come out of the 3D engine (and needs no optional tool):

* **the beam** (scene ``fe_beam_anchor``): each run of example 9.1 with free sliding and at least
  the main mesh against a converged 2D plane-stress solution of the same problem by a separate
  code (:mod:`roughcontact.paper.plane_stress`): u_N at the centre, at the end, the whole profile
  along the contact centre line (Fig. 13), and the equilibrium of the written interface
  pressures with the applied load;
* **the punch** (scene ``fe_punch_anchor``): each run of example 9.2 at every load level, from
  the fields written to its dataset: the interface pressures carry the seating pressure and the
  patch load (Σ w p_N = p0 A + P), the tangential tractions obey the friction limit of the case
  (μ_min p_N ≤ |t_T| at slipping points, |t_T| ≤ μ_max p_N everywhere, 0 without friction),
  the reported dissipation equals Σ w t_T·u_T^p of the written fields, and lies below the
  frictionless bound; and an energy balance (issue 29) that a common factor of the slips and D
  does not pass: the plastic slips rebuilt from the written relative displacements (from the
  nodal displacements, not from the law's state), tractions and tangential stiffnesses through
  the elastic law (93) of the run's tangential form, and D as the work of the written tractions
  on those slips, Σ_n Σ_q w_q t_T,n·Δu_T,n^p (backward Euler, the kernel's own rule), against the
  reported slips and D.

Tolerances are data (config.yaml ``fe_anchors``), each from a measured discretisation or
round-off error. Pure functions (no I/O): the workflow scripts read and write.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Mapping

import numpy as np

from ..limits import describe
from .report import md_escape
from .verify import NOT_REPRODUCED, REPRODUCED, Check, numerics_id

if TYPE_CHECKING:  # the runs' types, for the reader (this module only reads their fields)
    from ..examples.beam import BeamRun
    from ..examples.punch import PunchRun

__all__ = ["BEAM_SCENE", "PUNCH_SCENE", "anchored_beam_runs", "law_key", "beam_anchor_checks",
           "punch_anchor_checks", "stiffness_fields", "rebuilt_slips", "punch_energy_checks", "render_markdown"]

BEAM_SCENE, PUNCH_SCENE = "fe_beam_anchor", "fe_punch_anchor"


# ---------------------------------------------------------------------------------------------
# the beam
# ---------------------------------------------------------------------------------------------
def law_key(run: BeamRun) -> str:
    """The interface law of a beam run (:class:`~roughcontact.examples.beam.BeamRun`) as a label:
    runs with the same label share one 2D solution (the workflow checks that they share the 2D
    problem too, :func:`roughcontact.paper.plane_stress.plane_stress_beam`)."""
    law = run.law if run.law == "elastic" else (f"elastoplastic-Y{run.Y:g}" if run.Y is not None
                                                else f"elastoplastic-psi{run.psi:g}")
    return f"m00={run.m00:g}/{law}/E*={run.E_star:.8g}"


def anchored_beam_runs(runs: Mapping[str, BeamRun], main_spec: Mapping[str, Any]) -> list[str]:
    """The runs (name → :class:`~roughcontact.examples.beam.BeamRun`) the 2D solution anchors:
    free sliding (the 2D code has no tangential law) on at least the main mesh (``main_spec``:
    config.yaml ``fe.beam.spec``; the coarser study meshes are meant to be unconverged)."""
    return [name for name, run in runs.items()
            if run.tangential == "free" and run.spec.n_x >= main_spec["n_x"] and run.spec.n_z >= main_spec["n_z"]]


def _check(scene, model, quantity, row, ok, detail, description, target, value, error, tol, why, unit="") -> Check:
    return Check(id=numerics_id(scene, model, quantity, row, "run"), kind="numerics", scene=scene,
                 verdict=REPRODUCED if ok else NOT_REPRODUCED, detail=detail, description=description, model=model,
                 quantity=quantity, s=row, unit=unit, target=float(target), value=float(value), error=float(error),
                 tolerance=float(tol), tolerance_why=" ".join(str(why).split()))


def beam_anchor_checks(runs: Mapping[str, BeamRun], data: Mapping[str, Any],
                       reference: Mapping[str, Mapping[str, np.ndarray]], cfg: Mapping[str, Any]) -> list[Check]:
    """Four checks per anchored run (``runs``: name → :class:`~roughcontact.examples.beam.BeamRun`;
    ``data``: name → the run's dataset, :meth:`roughcontact.examples.beam.BeamResult.to_dataset`):
    u_N at the centre and the end and the largest deviation along the centre line against the 2D
    solution of its law
    (``reference[law_key(run)]``: x_mm, u_N_um, and error_centre_um, error_end_um, the 2D
    solution's change from a mesh half as fine), and |4 Σ w p_N − P|/P of the written points.
    ``cfg``: config ``fe_anchors.beam.tolerances`` (centre, end, profile, equilibrium)."""
    out = []
    for name, run in runs.items():
        ds, ref = data[name], reference[law_key(run)]
        model, row = f"fe-{run.family}", f"{run.case}-{name.split('-', 2)[2]}"
        x2, u2 = np.asarray(ref["x_mm"], dtype=float), np.asarray(ref["u_N_um"], dtype=float)
        for q, attr, at in (("u_N_centre", "u_N_centre_um", 0), ("u_N_end", "u_N_end_um", -1)):
            tol = cfg["centre" if at == 0 else "end"]
            ours, target = float(ds.attrs[attr]), float(u2[at])
            err = (ours - target) / abs(target)
            est = float(ref["error_centre_um" if at == 0 else "error_end_um"])
            ok = abs(err) <= tol["rtol"]
            out.append(_check(BEAM_SCENE, model, q, row, ok,
                              f"3D {ours:+.5f} um vs 2D plane stress {target:+.5f} um (2D: {est:.1e} um from a mesh half "
                              f"as fine): "
                              f"{100 * err:+.3f} % {'≤' if ok else '>'} {100 * tol['rtol']:g} %",
                              f"u_N at the {'centre' if at == 0 else 'end'} against the engine-free 2D solution",
                              target, ours, err, tol["rtol"], tol["why"], "um"))
        x3, u3 = ds["x"].values, ds["u_N_um"].values
        dev = np.abs(u3 - np.interp(x3, x2, u2))
        scale = float(np.max(np.abs(u2)))
        err = float(dev.max() / scale)
        tol = cfg["profile"]
        ok = err <= tol["rtol"]
        out.append(_check(BEAM_SCENE, model, "u_N_profile", row, ok,
                          f"largest |3D − 2D| along the centre line {dev.max():.2e} um at x = {x3[int(dev.argmax())]:g} mm, "
                          f"{100 * err:.3f} % of max |u_N| {'≤' if ok else '>'} {100 * tol['rtol']:g} %",
                          "u_N along the contact centre line (Fig. 13) against the 2D solution", 0.0, err, err,
                          tol["rtol"], tol["why"]))
        load = float(run.spec.load)
        carried = 4.0 * float(np.sum(ds["point_weight"].values * ds["point_p_N"].values))  # quarter model
        err = abs(carried - load) / load
        tol = cfg["equilibrium"]
        ok = err <= tol["rtol"]
        out.append(_check(BEAM_SCENE, model, "equilibrium", row, ok,
                          f"4 Σ w p_N of the written points {carried:.10g} N vs the applied {load:g} N: {err:.1e}",
                          "the written interface pressures carry the applied load", load, carried, err, tol["rtol"],
                          tol["why"], "N"))
    return out


# ---------------------------------------------------------------------------------------------
# the punch
# ---------------------------------------------------------------------------------------------
def _mu_range(case: str) -> tuple[float, float]:
    """(μ_min, μ_max) of (89) for a Fig. 18 case: μ runs from μ_m μ_o (no slip yet) to μ_m."""
    from ..examples.section9 import FIG18_CASES

    c = FIG18_CASES[case]
    lo, hi = sorted((c["mu_m"] * c["mu_o"], c["mu_m"]))
    return lo, hi


def punch_anchor_checks(runs: Mapping[str, PunchRun], data: Mapping[str, Any],
                        bounds: Mapping[str, float], quarter_area: Mapping[str, float],
                        cfg: Mapping[str, Any], d_attr: str) -> list[Check]:
    """Checks of every punch run (name → :class:`~roughcontact.examples.punch.PunchRun`) from its
    dataset (:func:`roughcontact.examples.punch.to_dataset`):
    equilibrium at every level (``quarter_area``: name → the quarter punch's top area [mm²]),
    the friction limit at every point and level, the reported D against the fields
    (``d_attr`` and its "end" twin), and D ≤ the frictionless bound (``bounds``: name → bound,
    :func:`roughcontact.paper.fe_punch.run_bounds`). ``cfg``: config ``fe_anchors.punch.tolerances``."""
    out = []
    for name, run in runs.items():
        ds = data[name]
        model, row = f"fe-{run.family}", name.split("-", 1)[1]
        w = ds["point_weight"].values
        p = ds["p_N"].values  # (level, point)
        # 1. Σ w p_N = p0 A + P at every level
        applied = float(run.spec.seating_pressure) * quarter_area[name] + ds["load_quarter"].values
        carried = p @ w
        err_levels = np.abs(carried - applied) / applied
        k = int(np.argmax(err_levels))
        tol = cfg["equilibrium"]
        ok = float(err_levels.max()) <= tol["rtol"]
        out.append(_check(PUNCH_SCENE, model, "equilibrium", row, ok,
                          f"worst of {applied.size} levels: Σ w p_N {carried[k]:.10g} N vs p0 A + P {applied[k]:.10g} N "
                          f"(quarter): {err_levels[k]:.1e}", "the written interface pressures carry the seating pressure "
                          "and the patch load at every level", applied[k], carried[k], err_levels[k], tol["rtol"],
                          tol["why"], "N"))
        # 2. the friction limit
        t = np.hypot(ds["t_x"].values, ds["t_y"].values)
        tol = cfg["friction_limit"]
        if run.case == "frictionless":
            worst = float(t.max())
            ok = worst <= tol["atol_frictionless"]
            out.append(_check(PUNCH_SCENE, model, "friction_limit", row, ok,
                              f"largest |t_T| without friction {worst:.1e} N/mm^2", "no tangential traction without "
                              "friction", 0.0, worst, worst, tol["atol_frictionless"], tol["why"], "N/mm^2"))
        else:
            lo, hi = _mu_range(run.case)
            pos = p > 0.0
            over = float(np.max(np.where(pos, t / np.where(pos, hi * p, 1.0), 0.0))) - 1.0
            slip = (ds["status"].values == 1) & pos
            under = float(np.max(np.where(slip, 1.0 - t / np.where(slip, lo * p, 1.0), -np.inf))) if slip.any() else -1.0
            worst = max(over, under)
            ok = worst <= tol["rtol"]
            out.append(_check(PUNCH_SCENE, model, "friction_limit", row, ok,
                              f"largest |t_T|/(mu_max p_N) − 1 = {over:+.1e} (mu_max {hi:g}); at the {int(slip.sum())} "
                              f"slipping point-levels largest 1 − |t_T|/(mu_min p_N) = {under:+.1e} (mu_min {lo:g})",
                              "the tangential tractions obey the case's friction limit (89), (91)", 0.0, worst, worst,
                              tol["rtol"], tol["why"]))
            # 3. the reported D against the written fields; 4. D below the frictionless bound
            tol = cfg["dissipation"]
            errs = []
            for attr, level in ((d_attr, int(ds.attrs["max_index"])), (d_attr.replace("_max_", "_end_"), -1)):
                per_point = (ds["t_x"].values[level] * ds["slip_x_um"].values[level]
                             + ds["t_y"].values[level] * ds["slip_y_um"].values[level]) / 1000.0  # µm → mm
                weights = w if "_area_" in attr else 1.0
                fields = 4.0 * float(np.sum(weights * per_point))
                reported = float(ds.attrs[attr])
                errs.append((abs(reported - fields) / max(abs(fields), abs(reported), tol["floor"]), attr, reported,
                             fields))
            err, attr, reported, fields = max(errs)
            ok = err <= tol["rtol"]
            out.append(_check(PUNCH_SCENE, model, "dissipation", row, ok,
                              f"{attr} {reported:.10g} N mm vs 4 Σ w t_T·u_T^p of the written fields {fields:.10g} N mm "
                              f"(worst of max load, end): {err:.1e}", "the reported dissipation is the one of the fields",
                              fields, reported, err, tol["rtol"], tol["why"], "N mm"))
            b, d = float(bounds[name]), float(ds.attrs[d_attr])
            ok = 0.0 <= d <= b
            out.append(_check(PUNCH_SCENE, model, "bound", row, ok,
                              f"0 ≤ D = {d:.4g} N mm {'≤' if d <= b else '>'} frictionless bound {b:.4g} N mm",
                              "D lies between 0 and the frictionless bound (friction only reduces slip, |t_T| ≤ mu p_N)",
                              b, d, d - b, 0.0, "an upper bound, no tolerance", "N mm"))
    return out


def stiffness_fields(result) -> tuple[dict[str, tuple], dict[str, float]]:
    """What the energy balance needs beyond :func:`roughcontact.examples.punch.to_dataset`, from a
    :class:`~roughcontact.examples.punch.PunchResult`: (variables, attributes) for its dataset —
    the tangential stiffnesses k_Tx, k_Ty = a k_N(u_N) (93) of every point at every level
    [N/mm² per µm] (0 where open), the cut-backs per level, and those of the unloaded start
    (u_N = 0), where the seating increment starts."""
    from ..interface import friction

    law, incs = result.material.normal, result.deck.increments
    per_um = 1000.0 / result.material.length_per_mm  # law length unit → µm
    closure = np.stack([inc.state[:, friction.U_N] for inc in incs])
    kx, ky = law.tangential(closure)
    kx0, ky0 = law.tangential(np.full(1, result.material.closure0))
    unit = "N/mm^2/um"
    variables = {f"k_T{a}": (("level", "point"), np.asarray(k, dtype=float) / per_um, {
        "units": unit, "long_name": f"tangential stiffness k_T{a} = a k_N(u_N) of the elastic law (93)"})
        for a, k in (("x", kx), ("y", ky))}
    variables["cutbacks"] = ("level", np.asarray([inc.cutbacks for inc in incs], dtype=np.int32),
                             {"units": "1", "long_name": "Newton cut-backs (halved sub-steps) of the level"})
    return variables, {"k_Tx_unloaded": float(kx0[0]) / per_um, "k_Ty_unloaded": float(ky0[0]) / per_um}


def rebuilt_slips(ds, tangential_form: str) -> dict[str, np.ndarray]:
    """The plastic slips u_x^p, u_y^p [µm] (level, point) rebuilt from the written relative
    displacements J (from the unloaded start: jump + seating_jump), tractions t and stiffnesses
    k_T by the elastic law (93) of ``tangential_form`` (roughcontact.interface.friction,
    "Tangential forms"), from the unloaded start (t = 0, u^p = 0, k_T of u_N = 0):

    * incremental-end:   Δu^p_n = ΔJ_n − (t_n − t_n−1)/k_T,n
    * incremental-start: Δu^p_n = ΔJ_n − (t_n − t_n−1)/k_T,n−1
    * secant:            Δu^p_n = ΔJ_n − (t_n/k_T,n − t_n−1/k_T,n−1)

    with t/k_T and Δu^p = 0 where the stiffness is 0 (an open point neither loads nor slips).
    Exact for one step per level (``cutbacks`` 0); a cut-back level is two or more steps."""
    out = {}
    for a in "xy":
        t = ds[f"t_{a}"].values
        k = ds[f"k_T{a}"].values
        J = ds[f"jump_{a}_um"].values + ds[f"seating_jump_{a}_um"].values[None, :]
        prev = lambda x, first: np.vstack([np.full((1, x.shape[1]), first), x[:-1]])  # noqa: E731
        tp, kp, Jp = prev(t, 0.0), prev(k, float(ds.attrs[f"k_T{a}_unloaded"])), prev(J, 0.0)

        def over(x, y):
            return np.divide(x, y, out=np.zeros_like(x), where=y > 0.0)

        if tangential_form == "incremental-end":
            elastic, active = over(t - tp, k), k > 0.0
        elif tangential_form == "incremental-start":
            elastic, active = over(t - tp, kp), kp > 0.0
        elif tangential_form == "secant":
            elastic, active = over(t, k) - over(tp, kp), k > 0.0
        else:
            raise ValueError(f"unknown tangential form {describe(tangential_form)}")
        out[a] = np.cumsum(np.where(active, J - Jp - elastic, 0.0), axis=0)
    return out


def punch_energy_checks(runs: Mapping[str, PunchRun], data: Mapping[str, Any], cfg: Mapping[str, Any]) -> list[Check]:
    """Two checks per frictional punch run (name → :class:`~roughcontact.examples.punch.PunchRun`,
    ``data``: name → its dataset with :func:`stiffness_fields`): the written plastic slips against
    :func:`rebuilt_slips` (largest difference relative to the largest relative displacement), and
    the reported D — the work D_<max|end>_work_whole and D_max_area_whole — against the work of
    the written tractions on the rebuilt slips, 4 Σ_q w_q Σ_n t_n·Δu^p_n, and 4 Σ_q w_q t·u^p at
    the maximum load [N mm]. ``cfg``: config ``fe_anchors.punch.tolerances.energy``
    {rtol, floor, why}."""
    out = []
    rtol, floor, why = float(cfg["rtol"]), float(cfg["floor"]), cfg["why"]
    for name, run in runs.items():
        if run.case == "frictionless":
            continue
        ds = data[name]
        model, row = f"fe-{run.family}", name.split("-", 1)[1]
        if "k_Tx" not in ds:
            out.append(_check(PUNCH_SCENE, model, "slip_balance", row, False, "the run's dataset has no k_Tx, k_Ty "
                              "(written by workflow/scripts/fe_punch_run.py since issue 29): re-run it",
                              "the written slips against the elastic law", 0.0, math.nan, math.nan, rtol, why))
            out.append(_check(PUNCH_SCENE, model, "work_balance", row, False, "no k_Tx, k_Ty in the dataset",
                              "D against the work of the tractions", 0.0, math.nan, math.nan, rtol, why, "N mm"))
            continue
        cut = int(np.sum(ds["cutbacks"].values))
        rebuilt = rebuilt_slips(ds, run.tangential_form)
        scale = max(float(np.max(np.abs(ds[f"jump_{a}_um"].values + ds[f"seating_jump_{a}_um"].values)))
                    for a in "xy")
        dev = {a: np.abs(rebuilt[a] - ds[f"slip_{a}_um"].values) for a in "xy"}
        a = max("xy", key=lambda k: float(dev[k].max()))
        n, q = np.unravel_index(int(np.argmax(dev[a])), dev[a].shape)
        err = float(dev[a].max()) / max(scale, 1e-300)
        ok = err <= rtol and cut == 0
        out.append(_check(PUNCH_SCENE, model, "slip_balance", row, ok,
                          f"written u_{a}^p {ds[f'slip_{a}_um'].values[n, q]:.10g} um vs rebuilt from J, t, k_T "
                          f"({run.tangential_form}) {rebuilt[a][n, q]:.10g} um at level {n}, point {q} "
                          f"(x {float(ds['x'].values[q]):g}, y {float(ds['y'].values[q]):g} mm): {err:.1e} of the "
                          f"largest |J| {scale:.4g} um" + (f"; {cut} cut-back(s): not one step per level" if cut else ""),
                          "the written plastic slips follow from the written relative displacements and tractions "
                          "through the elastic law (93)", 0.0, err, err, rtol, why))
        w = ds["point_weight"].values
        t = {a: ds[f"t_{a}"].values for a in "xy"}
        du = {a: np.diff(np.vstack([np.zeros((1, w.size)), rebuilt[a]]), axis=0) for a in "xy"}
        work = 4.0 * np.cumsum((t["x"] * du["x"] + t["y"] * du["y"]) @ w) / 1000.0  # µm → mm, whole punch
        k_max = int(ds.attrs["max_index"])
        area = 4.0 * float(w @ (t["x"][k_max] * rebuilt["x"][k_max] + t["y"][k_max] * rebuilt["y"][k_max])) / 1000.0
        rows = [("D_max_work_whole", float(work[k_max])), ("D_end_work_whole", float(work[-1])),
                ("D_max_area_whole", area)]
        errs = [(abs(float(ds.attrs[attr]) - ours) / max(abs(ours), abs(float(ds.attrs[attr])), floor), attr,
                 float(ds.attrs[attr]), ours) for attr, ours in rows]
        err, attr, reported, ours = max(errs)
        ok = err <= rtol and cut == 0
        out.append(_check(PUNCH_SCENE, model, "work_balance", row, ok,
                          f"{attr} {reported:.10g} N mm vs the work of the written tractions on the rebuilt slips "
                          f"{ours:.10g} N mm (worst of work at max load, at the end, and t·u^p at max load): {err:.1e}",
                          "D is the work of the run's own tractions on its own slips (energy balance)", ours, reported,
                          err, rtol, why, "N mm"))
    return out


def render_markdown(title: str, checks, rows_2d: list[dict], provenance: Mapping[str, Any]) -> str:
    """paper_figures/fe_beam_anchor.md or fe_punch_anchor.md: the 2D solutions (beam) and every check."""
    lines = [f"# {title}", "",
             "Generated by the Snakemake workflow; " + ", ".join(f"{k} `{v}`" for k, v in provenance.items()) + ".",
             "Every number the gate reports for examples 9.1 and 9.2 meets something that does not come out of the 3D "
             "engine (roughcontact.paper.fe_anchors): a 2D plane-stress solution of the beam by a separate code "
             "(roughcontact.paper.plane_stress), the punch's equilibrium, friction limit, dissipation and frictionless "
             "bound recomputed from the written fields.", ""]
    if rows_2d:
        lines += ["## The beam in 2D plane stress (u_N from the seated state, µm)", "",
                  "| law | mesh | u_N centre | u_N end | change from the mesh half as fine (centre, end) | dofs | time [s] |",
                  "|---|---|---:|---:|---|---:|---:|"]
        for r in rows_2d:
            lines.append(f"| {r['law']} | {r['mesh']} | {r['u_N_centre_um']:+.6f} | {r['u_N_end_um']:+.6f} | "
                         f"{r['error_centre_um']:.1e}, {r['error_end_um']:.1e} | {r['dofs']} | {r['seconds']:.1f} |")
        lines.append("")
    lines += ["## Checks", "", "| check | verdict | detail |", "|---|---|---|"]
    lines += [f"| `{c.id}` | {c.verdict} | {md_escape(c.detail)} |" for c in checks]
    return "\n".join(lines) + "\n"
