"""Prose claims of sections 6–10, evaluated on the figure scenes' data, and the elasto-plastic
numerics rows.

Each evaluator turns one sentence of the paper into a numerical criterion whose thresholds
come from the claim's entry in config/config.yaml (with the reason for them), and returns a
:class:`roughcontact.paper.verify.Check` whose detail gives the numbers. Pure functions of xarray
Datasets written by the workflow (no I/O):

* Figs 5–6 data (dims ``psi``, ``s``): a sweep with the elasto-plastic parts and
  ``material_H``; the load axis is W/(H A0).
* Figs 7–8 data (dims ``closure``, ``m00``, ``s``): elasto-plastic and purely elastic
  (``elastic_model_*``) pressure and stiffness.
* stiffness-sensitivity data (dims ``variant``, ``s`` and ``psi``, ``s``).
* friction law (section 8; scenes.slip_rule_geometry, hardening_path, fig18_paths): material
  points driven through the implicit return mapping.

"Fraction" names the part of the real area a claim is read against: ``plastic`` is A^p/A
(eq. (81), the captioned ordinate of Fig. 5), ``yielded`` is (A^ep + A^p)/A (past first yield).
Stiffness comparisons are made at equal nominal pressure W/A0 on the pressure range the claim
names: the separation at which W/A0 = w is found on a cubic Hermite interpolant of ln W(s) with
the exact slope d ln W/ds = −K √m00/W (K = −dW/dh), and K there from a cubic spline of ln K(s).
On the figures' grids (Δs = 0.1) this reproduces direct evaluation to ≤ 3e-8 relative (tests/
test_claims.py); monotonicity and ordering are judged with the tolerance RESOLUTION = 1e-6, the
resolution of the curves (plot preset ≤ 1e-7, interpolation ≤ 3e-8), so differences below it
count as equal.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Mapping

import numpy as np

from .verify import NOT_REPRODUCED, REPRODUCED, Check, claim_id

__all__ = ["EVALUATORS", "RESOLUTION", "evaluate", "fraction", "load_axis", "separation_at", "stiffness_at"]

#: relative (or, for area fractions, absolute) size below which two curve values count as equal
RESOLUTION = 1e-6


# ---------------------------------------------------------------------------------------
# quantities
# ---------------------------------------------------------------------------------------
def fraction(ds, which: str) -> np.ndarray:
    """A^p/A (``which="plastic"``) or (A^ep + A^p)/A (``"yielded"``), 0 where A = 0."""
    a = ds["area_fraction"].values
    if which == "plastic":
        part = ds["plastic_area_fraction"].values
    elif which == "yielded":
        part = ds["plastic_area_fraction"].values + ds["elastoplastic_area_fraction"].values
    else:
        raise ValueError(f"fraction must be 'plastic' or 'yielded', got {which!r}")
    return np.divide(part, a, out=np.zeros_like(a), where=a > 0)


def load_axis(ds) -> np.ndarray:
    """W/(H A0) over (psi, s): the abscissa of Figs 5–6."""
    return ds["pressure"].values / ds["material_H"].values[..., None]


def mean_pressure_over_H(ds) -> np.ndarray:
    """W/(A H) over (psi, s): the ordinate of Fig. 6."""
    return ds["pressure"].values / ds["area_fraction"].values / ds["material_H"].values[..., None]


def separation_at(s, pressure, stiffness, m00, w) -> np.ndarray:
    """The separations s at which the curve's W/A0 equals ``w``: roots of a cubic Hermite
    interpolant of ln W(s) with the exact slope −K √m00/W (dW/dh = −K, h = s √m00, eq. (23)).
    ValueError if a pressure lies outside the computed curve."""
    from scipy.interpolate import CubicHermiteSpline
    from scipy.optimize import brentq

    s, p, k = (np.asarray(a, float) for a in (s, pressure, stiffness))
    w = np.atleast_1d(np.asarray(w, float))
    if np.min(w) < p.min() * (1 - 1e-12) or np.max(w) > p.max() * (1 + 1e-12):
        raise ValueError(
            f"pressure range [{np.min(w):g}, {np.max(w):g}] is outside the computed curve "
            f"[{p.min():g}, {p.max():g}]: widen the scene's s grid"
        )
    order = np.argsort(s)
    s, p, k = s[order], p[order], k[order]
    spline = CubicHermiteSpline(s, np.log(p), -k * math.sqrt(m00) / p)
    out = np.empty(w.size)
    for i, target in enumerate(np.log(np.clip(w, p.min(), p.max()))):
        j = int(np.clip(np.searchsorted(-np.log(p), -target), 1, s.size - 1))  # ln W falls with s
        out[i] = brentq(lambda x: float(spline(x)) - target, s[j - 1], s[j], xtol=1e-14)
    return out


def stiffness_at(s, pressure, stiffness, m00, w) -> np.ndarray:
    """K at the nominal pressures ``w`` of one curve over s (see :func:`separation_at`)."""
    from scipy.interpolate import CubicSpline

    s_w = separation_at(s, pressure, stiffness, m00, w)
    order = np.argsort(s)
    return np.exp(CubicSpline(np.asarray(s, float)[order], np.log(np.asarray(stiffness, float)[order]))(s_w))


def _pressure_grid(claim, n=25) -> np.ndarray:
    lo, hi = (float(v) for v in claim["pressure_range"])
    return np.geomspace(lo, hi, n)


def _check(scene, claim, ok: bool, detail: str, value=math.nan, error=math.nan, tolerance=math.nan) -> Check:
    return Check(
        id=claim_id(scene, claim["id"]),
        kind="claim",
        scene=scene,
        verdict=REPRODUCED if ok else NOT_REPRODUCED,
        detail=detail,
        description=" ".join(str(claim["text"]).split()),
        target=float(claim.get("bound", claim.get("target", math.nan))),
        value=float(value),
        error=float(error),
        tolerance=float(tolerance),
        tolerance_why=" ".join(str(claim.get("why", "")).split()),
    )


def _psis(ds, claim, key_max="psi_max", key_min="psi_min"):
    """Indices of the ψ values a claim addresses: ψ ≤ psi_max and/or ψ > psi_min."""
    psi = ds["psi"].values
    keep = np.ones(psi.size, bool)
    if key_max in claim:
        keep &= psi <= float(claim[key_max])
    if key_min in claim:
        keep &= psi > float(claim[key_min])
    idx = np.flatnonzero(keep)
    if idx.size == 0:
        raise ValueError(f"claim {claim['id']}: no psi of the scene in the claimed range")
    return idx


# ---------------------------------------------------------------------------------------
# Figs 5–6
# ---------------------------------------------------------------------------------------
def small_psi_negligible(scene, claim, ds) -> Check:
    """"At small ψ the ratio A^p/A is very small even for the largest load": for ψ ≤ psi_max
    the chosen fraction stays ≤ bound at every load of the figure."""
    f = fraction(ds, claim["fraction"])
    idx = _psis(ds, claim)
    worst = {float(ds["psi"].values[i]): float(f[i].max()) for i in idx}
    value = max(worst.values())
    ok = value <= float(claim["bound"])
    parts = ", ".join(f"psi = {p:g}: {v:.3g}" for p, v in worst.items())
    detail = f"max {claim['fraction']} fraction over all loads — {parts} ({'≤' if ok else '>'} {claim['bound']:g})"
    return _check(scene, claim, ok, detail, value, value, float(claim["bound"]))


def large_psi_plastic_at_light_load(scene, claim, ds) -> Check:
    """"For ψ > 1 plastic flow will occur even at a very small load": for ψ > psi_min the
    chosen fraction at the lightest load of the figure (largest s) is ≥ bound."""
    f = fraction(ds, claim["fraction"])
    idx = _psis(ds, claim)
    light = int(np.argmax(ds["s"].values))
    x = load_axis(ds)
    vals = {float(ds["psi"].values[i]): (float(f[i, light]), float(x[i, light])) for i in idx}
    value = min(v for v, _ in vals.values())
    ok = value >= float(claim["bound"])
    parts = ", ".join(f"psi = {p:g}: {v:.3g} at W/(H A0) = {w:.2g}" for p, (v, w) in vals.items())
    detail = f"{claim['fraction']} fraction at the lightest load — {parts} ({'≥' if ok else '<'} {claim['bound']:g})"
    return _check(scene, claim, ok, detail, value, value, float(claim["bound"]))


def plastic_share_grows(scene, claim, ds) -> Check:
    """"For greater ψ at a given load the degree of plastic deformation is dominant; the effect
    increases as the separation becomes smaller": the chosen fraction is non-decreasing in ψ at
    every common load W/(H A0) and non-increasing in s at every ψ, to RESOLUTION (and not
    constant)."""
    f = fraction(ds, claim["fraction"])
    x = load_axis(ds)
    lo, hi = max(r.min() for r in x), min(r.max() for r in x)
    grid = np.geomspace(lo, hi, 30)
    on_grid = np.array([np.interp(np.log(grid), np.log(x[i][::-1]), f[i][::-1]) for i in range(x.shape[0])])
    order = np.argsort(ds["psi"].values)
    d_psi = np.diff(on_grid[order], axis=0)
    s_order = np.argsort(ds["s"].values)
    d_s = np.diff(f[:, s_order], axis=1)
    eps = RESOLUTION
    worst_psi, worst_s = float(d_psi.min()), float(d_s.max())
    ok = worst_psi >= -eps and worst_s <= eps and float(on_grid.max() - on_grid.min()) > 0.05
    detail = (
        f"{claim['fraction']} fraction at {grid.size} common loads W/(H A0) in [{lo:.2g}, {hi:.2g}]: "
        f"smallest step with increasing psi {worst_psi:.2g}; largest step with increasing s {worst_s:.2g}; "
        f"range {on_grid.min():.3g}…{on_grid.max():.3g}"
    )
    return _check(scene, claim, ok, detail, worst_psi, min(worst_psi, -worst_s), eps)


def mean_pressure_at_high_psi(scene, claim, ds) -> Check:
    """"At high ψ the normalized contact pressure W/AH approaches target": at the largest ψ of
    the figure, |W/(A H) − target| ≤ atol at every load. The detail also gives the value the
    model tends to (c_h of (66): every asperity's mean pressure is ≤ c_h H)."""
    r = mean_pressure_over_H(ds)
    i = int(np.argmax(ds["psi"].values))
    dev = np.abs(r[i] - float(claim["target"]))
    ok = bool(np.all(dev <= float(claim["atol"])))
    detail = (
        f"at psi = {ds['psi'].values[i]:g}: W/(A H) = {r[i].min():.4g}…{r[i].max():.4g} over the loads; "
        f"|W/(A H) − {claim['target']:g}| ≤ {dev.max():.3g} ({'≤' if ok else '>'} {claim['atol']:g}); "
        f"across psi the largest W/(A H) is {np.nanmax(r):.4g}"
    )
    return _check(scene, claim, ok, detail, float(r[i].mean()), float(dev.max()), float(claim["atol"]))


def deformation_regimes(scene, claim, ds) -> Check:
    """A cited classification (GW [1] or Bush et al. [19]): elastic for ψ < elastic_below
    (yielded fraction ≤ elastic_bound at every load), plastic for ψ > plastic_above (yielded
    fraction ≥ plastic_bound at every load) and load-dependent in between (the yielded fraction
    spans ≥ span over the loads)."""
    f = fraction(ds, "yielded")
    psi = ds["psi"].values
    rows, ok = [], True
    for i, p in enumerate(psi):
        lo, hi = float(f[i].min()), float(f[i].max())
        if p < float(claim["elastic_below"]):
            good, kind = hi <= float(claim["elastic_bound"]), "elastic"
        elif p > float(claim["plastic_above"]):
            good, kind = lo >= float(claim["plastic_bound"]), "plastic"
        else:
            good, kind = hi - lo >= float(claim["span"]), "load-dependent"
        ok &= good
        rows.append(f"psi = {p:g} ({kind}): {lo:.2g}…{hi:.2g}{'' if good else ' ✗'}")
    detail = "yielded fraction over the loads — " + "; ".join(rows)
    return _check(scene, claim, ok, detail)


# ---------------------------------------------------------------------------------------
# Figs 7–8
# ---------------------------------------------------------------------------------------
def _k(e, m00, w, model="elastoplastic"):
    """K at pressures ``w`` of one curve ``e`` (dims s) of the elasto-plastic or elastic model."""
    p, k = ("pressure", "stiffness") if model == "elastoplastic" else ("elastic_model_pressure", "elastic_model_stiffness")
    return stiffness_at(e["s"].values, e[p].values, e[k].values, m00, w)


def _curves_78(ds, closure, m_index, w):
    e = ds.sel(closure=closure).isel(m00=m_index)
    m00 = float(e["m00"])
    return _k(e, m00, w), _k(e, m00, w, "elastic")


def stiffness_decreases_with_m00(scene, claim, ds) -> Check:
    """"For higher m00 the contact stiffness is smaller": at every pressure of the range K is
    strictly decreasing in m00, for the elastic and the elasto-plastic model, every closure."""
    w = _pressure_grid(claim)
    order = np.argsort(ds["m00"].values)
    ok, worst, rows = True, -math.inf, []
    for closure in ds["closure"].values:
        k = np.array([_curves_78(ds, closure, j, w) for j in order])  # (m00, model, w)
        ratio = k[1:] / k[:-1]  # next m00 over previous
        worst = max(worst, float(ratio.max()))
        ok &= bool(np.all(ratio < 1.0 - RESOLUTION))
        rows.append(f"{closure}: K(m00 larger)/K(m00 smaller) ≤ {ratio.max():.3f}")
    detail = f"over W/A0 in [{w[0]:g}, {w[-1]:g}] — " + "; ".join(rows)
    return _check(scene, claim, ok, detail, worst, worst, 1.0)


def elastoplastic_below_elastic(scene, claim, ds) -> Check:
    """"The stiffness curves of the elasto-plastic model always underestimate the elastic
    ones": K_ep ≤ K_el at every pressure of the range, every m00, for the figure's closure."""
    w = _pressure_grid(claim)
    closure = claim["closure"]
    ratios = np.array([np.divide(*_curves_78(ds, closure, j, w)) for j in range(ds.sizes["m00"])])
    worst = float(ratios.max())
    ok = worst <= 1.0 + RESOLUTION
    detail = (
        f"{closure}: K_ep/K_el over W/A0 in [{w[0]:g}, {w[-1]:g}] and m00 = "
        f"{', '.join(f'{m:g}' for m in ds['m00'].values)}: {ratios.min():.4f}…{worst:.6f}"
    )
    return _check(scene, claim, ok, detail, worst, worst - 1.0, RESOLUTION)


def significant_gap_at_high_pressure(scene, claim, ds) -> Check:
    """"A significant difference between the elastic and elasto-plastic normal stiffness for
    the high normal pressure": 1 − K_ep/K_el at the top of the pressure range ≥ bound for the
    figure's closure (the other closures' numbers are in the detail)."""
    w = np.array([float(claim["pressure_range"][1])])
    gaps = {}
    for closure in ds["closure"].values:
        gaps[str(closure)] = [1.0 - float(np.divide(*_curves_78(ds, closure, j, w))[0]) for j in range(ds.sizes["m00"])]
    main = max(gaps[claim["closure"]])
    ok = main >= float(claim["bound"])
    rows = "; ".join(f"{c}: {', '.join(f'{g:.2%}' for g in v)}" for c, v in gaps.items())
    detail = (
        f"1 − K_ep/K_el at W/A0 = {w[0]:g} for m00 = {', '.join(f'{m:g}' for m in ds['m00'].values)} — "
        f"{rows} (figure's closure {claim['closure']}: {main:.2%} {'≥' if ok else '<'} {float(claim['bound']):.0%})"
    )
    return _check(scene, claim, ok, detail, main, main, float(claim["bound"]))


# ---------------------------------------------------------------------------------------
# stiffness sensitivity (section 7 and conclusions)
# ---------------------------------------------------------------------------------------
def _variant_change(ds, variant, model, w):
    def k_of(name):
        e = ds.sel(variant=name)
        return _k(e, float(e["variant_m00"]), w, model)

    return k_of(variant) / k_of("base") - 1.0


def no_effect_of_variants(scene, claim, ds) -> Check:
    """"The standard deviation of slopes and of curvatures have no observable effects on the
    normal stiffness": for each listed variant (moments scaled, m00 kept) |K/K_base − 1| ≤ bound
    at every pressure of the range, for each of ``models`` (elastic, elastoplastic); the detail
    compares with the
    ``reference_variant`` (e.g. m00 doubled), whose effect the paper calls primary."""
    w = _pressure_grid(claim)
    rows, worst = [], 0.0
    for variant in [*claim["variants"], claim.get("reference_variant")]:
        if variant is None:
            continue
        ch = np.array([_variant_change(ds, variant, m, w) for m in claim["models"]])
        a = np.abs(ch)
        if variant in claim["variants"]:
            worst = max(worst, float(a.max()))
        row = f"{variant}: up to {a.max():.1%} (at W/A0 = {w[np.argmax(a.max(axis=0))]:g})"
        if "light_load" in claim:
            light = a[:, w <= float(claim["light_load"])]
            row += f", ≤ {light.max():.1%} for W/A0 ≤ {claim['light_load']:g}" if light.size else ""
        rows.append(row)
    ok = worst <= float(claim["bound"])
    detail = (f"|K/K_base − 1| ({', '.join(claim['models'])}) at equal W/A0 in [{w[0]:g}, {w[-1]:g}] — "
              + "; ".join(rows))
    return _check(scene, claim, ok, detail, worst, worst, float(claim["bound"]))


def _k_psi(ds, w):
    """K_ep at pressures ``w`` for every ψ of the sensitivity data, ψ ascending."""
    order = np.argsort(ds["psi"].values)
    m00 = float(ds["variant_m00"].sel(variant="base"))
    out = [stiffness_at(ds["s"].values, ds["psi_pressure"].values[i], ds["psi_stiffness"].values[i], m00, w)
           for i in order]
    return ds["psi"].values[order], np.array(out)


def psi_sensitivity(scene, claim, ds) -> Check:
    """"The contact stiffness is very sensitive to ψ, increasing sharply as ψ decreases"
    (``expect: sharp``) or "increases slowly as ψ decreases" (``expect: slow``, conclusion 3):
    for the ψ within ``psi_range`` K_ep must not fall as ψ falls at any pressure (to
    RESOLUTION), and the rise between the two ψ of ``pair`` at the top pressure is ≥ bound
    (sharp) or < bound (slow). The detail also reports where, over all ψ of the scene, K_ep
    rises with ψ instead."""
    w = _pressure_grid(claim)
    psi, k = _k_psi(ds, w)
    rel = k[1:] / k[:-1] - 1.0  # K(next larger ψ)/K(ψ) − 1: should be ≤ 0
    lo_r, hi_r = (float(v) for v in claim["psi_range"])
    inside = (psi[:-1] >= lo_r) & (psi[1:] <= hi_r)
    monotone = bool(np.all(rel[inside] <= RESOLUTION))
    lo, hi = (float(v) for v in claim["pair"])
    i_lo, i_hi = int(np.argmin(np.abs(psi - lo))), int(np.argmin(np.abs(psi - hi)))
    rise = float(k[i_lo, -1] / k[i_hi, -1] - 1.0)
    sharp = rise >= float(claim["bound"])
    ok = monotone and (sharp if claim["expect"] == "sharp" else not sharp)
    inversions = [
        f"psi {psi[i]:g} → {psi[i + 1]:g}: K rises with psi by up to {rel[i].max():.1%} for W/A0 ≤ {w[rel[i] > RESOLUTION].max():g}"
        for i in range(rel.shape[0]) if np.any(rel[i] > RESOLUTION)
    ]
    detail = (
        f"K_ep at W/A0 = {w[-1]:g}: rises by {rise:.2%} from psi = {hi:g} to {lo:g} "
        f"({'≥' if sharp else '<'} {float(claim['bound']):.0%}), by {k[0, -1] / k[-1, -1] - 1.0:.1%} from psi = "
        f"{psi[-1]:g} to {psi[0]:g}; never falls as psi falls within psi in [{lo_r:g}, {hi_r:g}] at "
        f"W/A0 in [{w[0]:g}, {w[-1]:g}]: {'yes' if monotone else 'no'}"
        + (f"; elsewhere: {'; '.join(inversions)}" if inversions else "")
    )
    return _check(scene, claim, ok, detail, rise, rise, float(claim["bound"]))


# ---------------------------------------------------------------------------------------
# friction law (section 8, and the material-point basis of section 9.2's prose)
# ---------------------------------------------------------------------------------------
def _wrap(angle):
    """Angles mapped to (−π, π]."""
    return np.angle(np.exp(1j * np.asarray(angle, float)))


def _sliding_angles(ds, set_name, k=None):
    e = ds.sel(set=set_name)
    return e if k is None else e.sel(k=float(k))


def slip_rule(scene, claim, ds) -> Check:
    """Section 8.1's statements on the slip direction, on material points pushed into sliding:
    ``rule: coaxial`` — α = β (k = 0, or μ_x = μ_y); ``rule: normal`` — the slip is normal to
    the limit surface (91), ∥ ∂f/∂t (k = 1, associated); ``rule: eq118`` — tan β = tan α
    (ν_y/ν_x)² (118) for every k. The deviation (in rad) must be ≤ atol."""
    e = _sliding_angles(ds, claim["set"], claim.get("k"))
    a, b = e["alpha"].values, e["beta"].values
    rule = claim["rule"]
    if rule == "coaxial":
        dev = np.abs(_wrap(a - b))
    elif rule == "normal":
        mux, muy = float(e["mu_x"]), float(e["mu_y"])
        normal = np.arctan2(e["t_y"].values / muy**2, e["t_x"].values / mux**2)  # ∂f/∂t, eq. (106)
        dev = np.abs(_wrap(a - normal))
    elif rule == "eq118":
        r2 = e["nu_y_over_nu_x"].values[..., None] ** 2
        dev = np.abs(np.sin(b) * np.cos(a) - r2 * np.sin(a) * np.cos(b)) / np.hypot(1.0, r2)  # (118) × cos α cos β
    else:
        raise ValueError(f"unknown slip rule {rule!r}")
    worst = float(np.max(dev))
    spread = float(np.max(np.abs(_wrap(a - b))))
    ok = worst <= float(claim["atol"])
    which = f"k = {float(claim['k']):g}" if "k" in claim else "every k"
    detail = (
        f"set {claim['set']}, {which}: largest deviation "
        f"{worst:.2g} rad over {a.size} sliding points ({'≤' if ok else '>'} {float(claim['atol']):g}); "
        f"largest |α − β| there {np.degrees(spread):.3g}°"
    )
    return _check(scene, claim, ok, detail, worst, worst, float(claim["atol"]))


def on_limit_surface(scene, claim, ds) -> Check:
    """"The tangential traction can at most be equal to t_N μ_α" (section 8.1): after the
    return mapping every sliding traction lies on the limit ellipse (91), |f|/p_N ≤ atol."""
    f = np.sqrt((ds["t_x"] / ds["mu_x"]) ** 2 + (ds["t_y"] / ds["mu_y"]) ** 2) / float(ds.attrs["p_N"]) - 1.0
    worst = float(np.abs(f).max())
    ok = worst <= float(claim["atol"])
    detail = f"max |f|/p_N over {f.size} sliding points: {worst:.2g} ({'≤' if ok else '>'} {float(claim['atol']):g})"
    return _check(scene, claim, ok, detail, worst, worst, float(claim["atol"]))


def traction_follows_hardening(scene, claim, ds) -> Check:
    """(89): while sliding along x the traction ratio t_x/p_N equals μ_x(κ_x) of (89) at the
    accumulated slip, to rtol; the detail gives the hardening reached."""
    sliding = ds["kappa_x"].values > 0
    rel = np.abs(ds["traction_ratio"].values[sliding] / ds["mu_x_89"].values[sliding] - 1.0)
    worst = float(rel.max()) if rel.size else math.inf
    ok = worst <= float(claim["rtol"])
    detail = (
        f"{int(sliding.sum())} sliding steps: max |t_x/(p_N μ_x(κ_x)) − 1| = {worst:.2g} "
        f"({'≤' if ok else '>'} {float(claim['rtol']):g}); t_x/p_N from {ds['traction_ratio'].values[sliding][0]:.4g} "
        f"to {ds['traction_ratio'].values[-1]:.4g} (μ_m = {ds.attrs['mu_m']:g})"
    )
    return _check(scene, claim, ok, detail, worst, worst, float(claim["rtol"]))


def _end_of_loading(ds):
    return int(np.flatnonzero(ds["loading"].values)[-1])


def mirror_symmetry(scene, claim, ds) -> Check:
    """Section 9.2: "for the same directional parameters μ, ν and the same axial compliance
    parameters the behaviour must be symmetric; not so for other axial parameters": the response
    to the x↔y mirrored path is the mirrored response (to rtol) for the ``symmetric`` cases and
    differs by more than ``asymmetry`` for the ``asymmetric`` ones."""
    rows, ok = [], True
    for case in ds["case"].values:
        d, m = ds.sel(case=case, path="direct"), ds.sel(case=case, path="swapped")
        scale = float(np.max(np.hypot(d["t_x"], d["t_y"])))
        diff = float(max(np.abs(d["t_x"] - m["t_y"]).max(), np.abs(d["t_y"] - m["t_x"]).max())) / scale
        expect_sym = case in claim["symmetric"]
        good = diff <= float(claim["rtol"]) if expect_sym else diff > float(claim["asymmetry"])
        ok &= good
        rows.append(f"({case}) {'symmetric' if expect_sym else 'asymmetric'}: {diff:.2g}{'' if good else ' ✗'}")
    detail = "max |t(mirrored path) − mirrored t| / max|t| — " + "; ".join(rows)
    return _check(scene, claim, ok, detail)


def plastic_slip_order(scene, claim, ds) -> Check:
    """Section 9.2: "plastic displacements are smaller for larger principal friction
    coefficients" / "greater for greater values of the axial contact stiffness": the plastic
    slip (``component``: magnitude, x or y) at the end of loading is larger in case ``larger``
    than in case ``smaller``."""
    i = _end_of_loading(ds)

    def up(case):
        e = ds.sel(case=case, path="direct").isel(step=i)
        return {"magnitude": float(np.hypot(e["up_x"], e["up_y"])), "x": float(e["up_x"]), "y": float(e["up_y"])}[claim["component"]]

    big, small = up(claim["larger"]), up(claim["smaller"])
    ok = big > small
    detail = (f"plastic slip ({claim['component']}) at the end of loading: ({claim['larger']}) {big:.6g} "
              f"{'>' if ok else '≤'} ({claim['smaller']}) {small:.6g} [{ds['up_x'].attrs['units']}]")
    return _check(scene, claim, ok, detail, big - small, big / small - 1.0 if small else math.inf, 0.0)


def unloading_reverses_traction(scene, claim, ds) -> Check:
    """Section 9.2: "in the unloading case the tangential forces change sign retaining sign of
    the total displacements": for every case, during unloading the traction turns against the
    imposed displacement (t·u < 0) while u keeps its direction (u·u_max > 0)."""
    rows, ok = [], True
    for case in ds["case"].values:
        d = ds.sel(case=case, path="direct")
        un = ~d["loading"].values
        u = np.stack([d["u_x"].values, d["u_y"].values], -1)
        tr = np.stack([d["t_x"].values, d["t_y"].values], -1)
        u_end = u[_end_of_loading(ds)]
        reversed_ = un & (np.einsum("ij,ij->i", tr, u) < 0) & (u @ u_end > 0)
        good = bool(np.any(reversed_))
        ok &= good
        first = np.flatnonzero(reversed_)
        at = float(np.hypot(*u[first[0]])) if first.size else math.nan
        rows.append(f"({case}) traction reversed from |u| = {at:.3g} on unloading (|u_max| = {np.hypot(*u_end):.3g})")
    return _check(scene, claim, ok, "; ".join(rows))


def dissipation_nonnegative(scene, claim, ds) -> Check:
    """Section 9.2 defines the frictional dissipation D = t_T · u_T^p; it must be ≥ 0 and never
    decrease along every path (the second law for the slip rule)."""
    dis = ds["dissipation"].values
    worst_step = float(np.min(np.diff(dis, axis=-1)))
    ok = float(dis.min()) >= 0.0 and worst_step >= -1e-12 * float(np.abs(dis).max())
    final = ", ".join(f"({c}) {float(ds['dissipation'].sel(case=c, path='direct').isel(step=-1)):.4g}"
                      for c in ds["case"].values)
    detail = f"min D = {dis.min():.3g}, smallest step {worst_step:.2g}; D at the end: {final} [{ds['dissipation'].attrs['units']}]"
    return _check(scene, claim, ok, detail, worst_step, worst_step, 0.0)


# ---------------------------------------------------------------------------------------
# numerics: elasto-plastic production against the slow twin
# ---------------------------------------------------------------------------------------
def elastoplastic_numerics_checks(scene: str, ds, rtol: float, why: str) -> list[Check]:
    """One ``numerics`` check per check point and total (A/A0, W/A0, K/A0): |production −
    reference|/reference ≤ rtol (scenes.elastoplastic_numerics)."""
    from .verify import numerics_id

    cols = ds.attrs["columns"].split()
    totals = {
        "area_fraction": [c for c in cols if c.endswith("area_fraction")],
        "pressure": [c for c in cols if c.endswith("_pressure")],
        "stiffness": ["stiffness"],
    }
    out = []
    for point in ds["point"].values:
        e = ds.sel(point=point)
        for quantity, parts in totals.items():
            p = sum(float(e[f"production_{c}"]) for c in parts)
            r = sum(float(e[f"reference_{c}"]) for c in parts)
            err = (p - r) / abs(r) if r else math.inf
            ok = abs(err) <= rtol
            out.append(Check(
                id=numerics_id(scene, "elastoplastic", quantity, str(point), "point"),
                kind="numerics", scene=scene, verdict=REPRODUCED if ok else NOT_REPRODUCED,
                detail=(f"production {p:.12g} vs slow twin {r:.12g} (rtol {ds.attrs['reference_rtol']:g}): "
                        f"|rel. diff| {abs(err):.1e} {'≤' if ok else '>'} {rtol:.0e}"),
                description="elasto-plastic production vs slow twin", model="elastoplastic", quantity=quantity,
                s=str(point), target=r, value=p, error=err, tolerance=rtol, tolerance_why=why,
            ))
    return out


#: check name in config → evaluator(scene, claim, dataset) -> Check
EVALUATORS: dict[str, Callable[[str, Mapping[str, Any], Any], Check]] = {
    "small_psi_negligible": small_psi_negligible,
    "large_psi_plastic_at_light_load": large_psi_plastic_at_light_load,
    "plastic_share_grows": plastic_share_grows,
    "mean_pressure_at_high_psi": mean_pressure_at_high_psi,
    "deformation_regimes": deformation_regimes,
    "stiffness_decreases_with_m00": stiffness_decreases_with_m00,
    "elastoplastic_below_elastic": elastoplastic_below_elastic,
    "significant_gap_at_high_pressure": significant_gap_at_high_pressure,
    "no_effect_of_variants": no_effect_of_variants,
    "psi_sensitivity": psi_sensitivity,
    "slip_rule": slip_rule,
    "on_limit_surface": on_limit_surface,
    "traction_follows_hardening": traction_follows_hardening,
    "mirror_symmetry": mirror_symmetry,
    "plastic_slip_order": plastic_slip_order,
    "unloading_reverses_traction": unloading_reverses_traction,
    "dissipation_nonnegative": dissipation_nonnegative,
}


def evaluate(scene: str, claim: Mapping[str, Any], ds) -> Check:
    """Evaluate one configured claim on a scene's data (ValueError for an unknown check)."""
    try:
        fn = EVALUATORS[claim["check"]]
    except KeyError:
        raise ValueError(f"unknown claim check {claim.get('check')!r}; choose from {', '.join(EVALUATORS)}") from None
    return fn(scene, claim, ds)
