"""One elliptic-paraboloid asperity against a rigid flat: elastic, elasto-plastic and fully
plastic contact (sections 5–7 of Buczkowski & Kleiber 2009).

Equation numbers are the paper's. Corrections of the printed paper are marked
``[erratum (NN)]`` and listed in docs/errata.md. Pure numpy, vectorised, no I/O.

Geometry and units
------------------
An asperity is described by its mean curvature κ_m = (|ξ4| + |ξ6|)/2 [1/L] (eqs. (43)–(44)),
the shape of its Hertz contact ellipse, and the interference ω ≥ 0 [L]. The shape is either
e1 = B/A ∈ (0, 1] (the complementary modulus, eq. (30)) or a :class:`~roughcontact.asperity.ellipse.
HertzFactors` (from :func:`~roughcontact.asperity.ellipse.hertz_factors`); everything elliptic
(K(e), E(e), f1 … f4) comes from :mod:`roughcontact.asperity.ellipse`. Stresses in the unit of E*;
area in L², load in (stress)·L², stiffness dW/dω in (stress)·L.

The model (ZMC / Jeng–Wang template, section 6; ω_p = (ω_p/ω_c)·ω_c)
-------------------------------------------------------------------
* elastic, 0 ≤ ω ≤ ω_c (eqs. (46)–(47)):
      A = f1 π ω/κ_m,   W = f2 (4/3) E* ω^{3/2} κ_m^{-1/2}
* elasto-plastic, ω_c < ω < ω_p (eqs. (75)–(77), polynomial and brackets restored):
      x = (ω − ω_c)/(ω_p − ω_c),   g(x) = 3x² − 2x³
      A = [f1 + (2 f3 − f1) g(x)] π ω/κ_m
      p_a = c_h H − H (c_h − (2/3) K_v) ln(ω_p/ω)/ln(ω_p/ω_c),   W = A p_a
* fully plastic, ω ≥ ω_p (eqs. (61), (67)):
      A = 2 f3 π ω/κ_m,   W = A c_h H

First yield (eqs. (62)–(65)): the Hertz maximum pressure is p_max = E* √(κ_m ω/(K(e) E(e)))
= (3/2) W/A [erratum (62): printed inverted], and p_max = K_Y·Y (63) gives
ω_c = K(e) E(e) (K_Y Y/E*)²/κ_m (65). K_Y (the paper's "K" of (63)–(64), 1.62) is called
``yield_coefficient`` here to keep it apart from the elliptic integral K(e).

The plastic branch is (61)/(67), not the CEB/Horng area (58): the cubic blend of (76) ends at
2 f3 π ω/κ_m, so only (61) is continuous at ω_p; (58) lies below it there by the relative
amount (ω_c/ω_p)(2 − f4)/2 (1.1 % for a circle, → 2.2 % as e1 → 0). (58) is still provided
(:func:`ceb_plastic_area`); it joins the elastic area at ω_c because f3·f4 = f1 exactly.

Continuity
----------
Area: continuous at ω_c (g(0) = 0) and at ω_p (g(1) = 1); even C¹ (g'(0) = g'(1) = 0).
Load at ω_p: continuous (p_a(ω_p) = c_h H). Load at ω_c: the elastic mean pressure there is
(2/3) p_max = (2/3) K_Y Y, the elasto-plastic one (2/3) K_v H, so the load is continuous iff

      K_v · H = K_Y · Y.

With Tabor's H = Y/0.354 (68) and K_Y = 1.62 this is K_v = 0.354·1.62 = 0.57348 (the default,
``K_v=None``). The paper's K_v = 0.454 + 0.41ν [60] meets it only for ν = 0.29141 and makes
the load jump up by K_v H/(K_Y Y) − 1 = +0.614 % at ν = 0.3 [erratum (75)]. (0.354·(64) =
0.4538 + 0.4099ν: the paper's K_v is Tabor × (64); the jump comes from fixing K_Y = 1.62, i.e.
(64) at ν ≈ 0.2917, while taking K_v at ν = 0.3.)

Stiffness dW/dω is piecewise analytic (with the derivative of the cubic blend and of the log
pressure; the printed (88) lacks the former [erratum (88)]). It is discontinuous at both joints
even when the load is continuous: at ω_c it drops by the factor 2/3 + (c_h H/(K_Y Y) − 2/3)/ln r
(0.9345 with the defaults), at ω_p by 1/(1 + (1 − (2/3) K_v/c_h)/ln r) (1/1.1588), r = ω_p/ω_c.
At a joint, the value of the regime containing the point is returned (elastic at ω_c, plastic
at ω_p), i.e. the left derivative at ω_c and the right one at ω_p.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..statistics.surface import SpectralMoments
from ..validation import positive
from .ellipse import HertzFactors, elliptic_KE, f1 as _f1, f2 as _f2, f3 as _f3, f4 as _f4, hertz_factors
from .material import AsperityMaterial

__all__ = [
    "ELASTIC",
    "ELASTO_PLASTIC",
    "PLASTIC",
    "REGIME_NAMES",
    "AsperityResponse",
    "factors_from_e1",
    "critical_interference",
    "plastic_interference",
    "elastic_max_pressure",
    "blend",
    "respond",
    "area",
    "load",
    "stiffness",
    "mean_pressure",
    "regime",
    "ceb_plastic_area",
    "plasticity_index",
    "plasticity_index_gw",
    "yield_strength_for_plasticity_index",
    "curvature_ratio",
    "gamma_87",
    "critical_interference_star",
]

#: Regime codes returned by :func:`regime`.
ELASTIC, ELASTO_PLASTIC, PLASTIC = 0, 1, 2
REGIME_NAMES = ("elastic", "elasto-plastic", "plastic")


# --- shape -------------------------------------------------------------------------------


def factors_from_e1(e1, hertz: str = "exact") -> HertzFactors:
    """HertzFactors (e1, f1, f2, f3, f4, K, E) of a contact ellipse given e1 = B/A ∈ (0, 1].

    hertz="exact": exact K, E (eqs. (28), (48)); hertz="paper": K, E and f1, f2 from the A&S
    polynomials (36)–(39); f3, f4 (59)–(60) always exact (as in :func:`ellipse.hertz_factors`)."""
    if hertz not in ("exact", "paper"):
        raise ValueError(f"hertz must be 'exact' or 'paper', not {hertz!r}")
    a = np.asarray(e1, dtype=float)
    if np.any(~((a > 0.0) & (a <= 1.0))):
        raise ValueError("e1 = B/A must lie in (0, 1] (e1 = 0 is a degenerate strip contact)")
    K, E = elliptic_KE(a, hertz)
    return HertzFactors(a if a.ndim else float(a), _f1(a, hertz), _f2(a, hertz), _f3(a), _f4(a), K, E)


def _shape(shape, hertz: str) -> HertzFactors:
    if isinstance(shape, HertzFactors):
        if np.any(~(np.asarray(shape.e1, dtype=float) > 0.0)):
            raise ValueError("HertzFactors with e1 ≤ 0 (degenerate strip contact) are not allowed")
        return shape
    return factors_from_e1(shape, hertz)


def _kappa(kappa_m) -> np.ndarray:
    k = np.asarray(kappa_m, dtype=float)
    if np.any(~((k > 0.0) & np.isfinite(k))):
        raise ValueError("kappa_m (mean curvature, eq. 43) must be finite and positive")
    return k


def _omega(omega) -> np.ndarray:
    w = np.asarray(omega, dtype=float)
    if np.any(~((w >= 0.0) & np.isfinite(w))):
        raise ValueError("omega (interference) must be finite and ≥ 0")
    return w


def _out(x, scalar: bool):
    return x.item() if scalar else x


# --- first yield ---------------------------------------------------------------------------


def critical_interference(kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """ω_c = K(e) E(e) (K_Y Y/E*)²/κ_m [L], eq. (65).

    Derived from the corrected (62), p_max = E* √(κ_m ω/(K E)), set equal to K_Y Y (63).
    For a circle (K = E = π/2) this is CEB's ω_c = (π K_Y Y/(2E*))² R, R = 1/κ_m.
    ``shape``: e1 ∈ (0, 1] or HertzFactors; vectorised (broadcast)."""
    s = _shape(shape, hertz)
    k = _kappa(kappa_m)
    K, E = np.asarray(s.K, dtype=float), np.asarray(s.E, dtype=float)
    wc = K * E * (material.yield_pressure / material.E_star) ** 2 / k  # eq. (65)
    return _out(wc, wc.ndim == 0)


def plastic_interference(kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """ω_p = (ω_p/ω_c)·ω_c [L] (section 5, ω_p/ω_c = 45 after Jamari & Schipper [60])."""
    wc = np.asarray(critical_interference(kappa_m, shape, material, hertz=hertz))
    wp = material.wp_over_wc * wc
    return _out(wp, wp.ndim == 0)


def elastic_max_pressure(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """Hertz maximum pressure p_max = E* √(κ_m ω/(K(e) E(e))) [stress], eq. (62) corrected.

    [erratum (62)]: printed as √(K E)/(E* √(κ_m ω)), which is the reciprocal (and has units of
    1/stress). The corrected form equals (3/2) W/A of (46)–(47), since f2/f1 = π/(2√(K E)).
    Purely elastic (ignores yield); vectorised."""
    s = _shape(shape, hertz)
    w, k = _omega(omega), _kappa(kappa_m)
    p = material.E_star * np.sqrt(k * w / (np.asarray(s.K) * np.asarray(s.E)))  # eq. (62) corrected
    return _out(p, p.ndim == 0)


def blend(x):
    """Cubic template g(x) = 3x² − 2x³ of (76)–(77), (80), (84) (restored powers; (88) shows
    them), and g'(x) = 6x(1 − x). g(0) = 0, g(1) = 1, g'(0) = g'(1) = 0."""
    x = np.asarray(x, dtype=float)
    return x * x * (3.0 - 2.0 * x), 6.0 * x * (1.0 - x)


# --- the piecewise model -------------------------------------------------------------------


class AsperityResponse(NamedTuple):
    """Area [L²], load [stress·L²], stiffness dW/dω [stress·L] and regime code of one asperity."""

    area: np.ndarray | float
    load: np.ndarray | float
    stiffness: np.ndarray | float
    regime: np.ndarray | int


def respond(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact") -> AsperityResponse:
    """Area, load, stiffness dW/dω and regime of one asperity at interference ω (all at once).

    omega [L] ≥ 0, kappa_m [1/L] > 0, shape = e1 ∈ (0, 1] or HertzFactors; broadcast together.
    Regimes: elastic ω ≤ ω_c, elasto-plastic ω_c < ω < ω_p, plastic ω ≥ ω_p (module docstring).
    """
    s = _shape(shape, hertz)
    w, k = _omega(omega), _kappa(kappa_m)
    arrs = np.broadcast_arrays(w, k, *(np.asarray(v, dtype=float) for v in (s.f1, s.f2, s.f3, s.K, s.E)))
    shape_out = arrs[0].shape
    w, k, F1, F2, F3, KK, EE = (a.reshape(-1) for a in arrs)

    m = material
    wc = KK * EE * (m.yield_pressure / m.E_star) ** 2 / k  # eq. (65)
    r = m.wp_over_wc
    wp = r * wc  # ω_p = 45 ω_c (section 5)
    ln_r = math.log(r)
    H = m.H
    dp = H * (m.c_h - (2.0 / 3.0) * m.K_v)  # H (c_h − (2/3) K_v), eq. (75)

    A = np.zeros_like(w)
    W = np.zeros_like(w)
    S = np.zeros_like(w)
    reg = np.full(w.shape, ELASTIC, dtype=np.int8)

    el = w <= wc
    pl = (w >= wp) & ~el
    ep = ~(el | pl)
    reg[ep] = ELASTO_PLASTIC
    reg[pl] = PLASTIC

    if np.any(el):
        we, ke = w[el], k[el]
        root = np.sqrt(we / ke)  # (ω/κ_m)^{1/2}
        A[el] = F1[el] * math.pi * we / ke  # eq. (46)
        W[el] = F2[el] * (4.0 / 3.0) * m.E_star * we * root  # eq. (47)
        S[el] = 2.0 * F2[el] * m.E_star * root  # eq. (54): dW/dω of (47)
    if np.any(ep):
        we, ke, f1e = w[ep], k[ep], F1[ep]
        d = 2.0 * F3[ep] - f1e  # 2 f3 − f1 = E D/(e1 B K) > 0
        t = we / wc[ep]  # ω/ω_c ∈ (1, r)
        x = (t - 1.0) / (r - 1.0)  # x = (ω − ω_c)/(ω_p − ω_c), eq. (76) [erratum: powers]
        g, dg = blend(x)
        bracket = f1e + d * g  # [f1 + (2 f3 − f1) g(x)], eq. (76)/(80) [erratum: brackets]
        A[ep] = bracket * math.pi * we / ke  # eq. (76)
        p = m.c_h * H - dp * np.log(r / t) / ln_r  # eq. (75): ln(ω_p/ω)/ln(ω_p/ω_c)
        W[ep] = A[ep] * p  # eq. (77)
        dA = (bracket + d * dg * t / (r - 1.0)) * math.pi / ke  # d/dω of (76): ω dx/dω = t/(r−1)
        S[ep] = dA * p + (bracket * math.pi / ke) * dp / ln_r  # + A dp/dω, dp/dω = dp/(ω ln r)
    if np.any(pl):
        wpl, kpl = w[pl], k[pl]
        A[pl] = 2.0 * F3[pl] * math.pi * wpl / kpl  # eq. (61)
        W[pl] = A[pl] * m.c_h * H  # eq. (67)
        S[pl] = 2.0 * F3[pl] * math.pi * m.c_h * H / kpl  # d/dω of (67)

    scalar = len(shape_out) == 0
    return AsperityResponse(
        _out(A.reshape(shape_out), scalar),
        _out(W.reshape(shape_out), scalar),
        _out(S.reshape(shape_out), scalar),
        int(reg.reshape(shape_out)) if scalar else reg.reshape(shape_out),
    )


def area(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """Contact area A(ω) [L²]: (46) | (76) | (61) by regime. See :func:`respond`."""
    return respond(omega, kappa_m, shape, material, hertz=hertz).area


def load(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """Contact load W(ω) [stress·L²]: (47) | (77) | (67) by regime. See :func:`respond`."""
    return respond(omega, kappa_m, shape, material, hertz=hertz).load


def stiffness(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """Normal stiffness dW/dω [stress·L], analytic per regime (eq. (54) in the elastic one;
    the derivative of (77) incl. the cubic blend and the log pressure; d(67)/dω). Not (88).
    At ω_c the elastic (left) value, at ω_p the plastic (right) value. See :func:`respond`."""
    return respond(omega, kappa_m, shape, material, hertz=hertz).stiffness


def regime(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """Regime code: ELASTIC (0) for ω ≤ ω_c, ELASTO_PLASTIC (1) for ω_c < ω < ω_p, PLASTIC (2)
    for ω ≥ ω_p; names in REGIME_NAMES."""
    return respond(omega, kappa_m, shape, material, hertz=hertz).regime


def mean_pressure(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """Mean contact pressure W/A [stress], evaluated without the ratio (0 at ω = 0):
    (2/3) p_max (elastic, (62)), p_a of (75) (elasto-plastic), c_h H (plastic, (66))."""
    s = _shape(shape, hertz)
    w, k = _omega(omega), _kappa(kappa_m)
    arrs = np.broadcast_arrays(w, k, np.asarray(s.K, dtype=float), np.asarray(s.E, dtype=float))
    w, k, KK, EE = arrs
    m = material
    wc = KK * EE * (m.yield_pressure / m.E_star) ** 2 / k  # eq. (65)
    r = m.wp_over_wc
    t = w / wc
    dp = m.H * (m.c_h - (2.0 / 3.0) * m.K_v)
    p_ep = m.c_h * m.H - dp * np.log(r / np.maximum(t, 1.0)) / math.log(r)  # eq. (75)
    p = np.where(
        w <= wc,
        (2.0 / 3.0) * m.E_star * np.sqrt(k * w / (KK * EE)),  # (2/3) p_max, eq. (62) corrected
        np.where(w >= r * wc, m.c_h * m.H, p_ep),  # eq. (66) | eq. (75)
    )
    return _out(p, p.ndim == 0)


def ceb_plastic_area(omega, kappa_m, shape, material: AsperityMaterial, *, hertz: str = "exact"):
    """Horng/CEB volume-conserving plastic area, eq. (58) (for ω ≥ ω_c) [L²]:

        A^p = f3 π ω/κ_m [2 − (ω_c/ω)(2 − f4)] = f3 π [2ω − ω_c (2 − f4)]/κ_m

    (written without the 1/ω). At ω_c it equals f3 f4 π ω_c/κ_m = f1 π ω_c/κ_m, the elastic
    area (46), because f3·f4 = f1 exactly; for ω ≫ ω_c it tends to (61). Not used by
    :func:`respond` (the ZMC blend (76) joins (61), not (58), at ω_p)."""
    s = _shape(shape, hertz)
    w, k = _omega(omega), _kappa(kappa_m)
    wc = np.asarray(critical_interference(k, s, material))
    a = np.asarray(s.f3) * math.pi * (2.0 * w - wc * (2.0 - np.asarray(s.f4))) / k  # eq. (58)
    return _out(a, a.ndim == 0)


# --- plasticity index and the dimensionless critical interference (69), (74), (86)–(87) -----


def plasticity_index(moments: SpectralMoments, material: AsperityMaterial) -> float:
    """ψ = (2/π) (E*/(K_Y Y)) √(σ_s κ̄_m): the plasticity index for which (74)/(87) reproduce
    the physical ω_c of (65) exactly.

    σ_s = summit-height std (71)–(72) with the dimensionless c = 1 − (π/2 − 1)(β1 + β2)
    [erratum (72)], κ̄_m = √(π/8)(√m04 + √m40) (70). Equating (74)·√(m00 μ) with (65) for
    κ_m = √μ ω6 √m04 (1 + ρ)/2 gives ψ² = (4/π²)(E*/(K_Y Y))² σ_s κ̄_m. A CEB-type index; GW's
    (69) √(σ κ̄_m) E*/H differs by the constant (2/π) H/(K_Y Y) (1.110 with Tabor's H and
    K_Y = 1.62). Dimensionless."""
    return (2.0 / math.pi) * (material.E_star / material.yield_pressure) * math.sqrt(
        moments.summit_height_std * moments.mean_summit_curvature
    )


def plasticity_index_gw(moments: SpectralMoments, H: float, E_star: float) -> float:
    """Greenwood–Williamson plasticity index ψ = √(σ_s κ̄_m) E*/H, eq. (69) (σ_s from (71)–(72)
    corrected, κ̄_m from (70))."""
    root = math.sqrt(moments.summit_height_std * moments.mean_summit_curvature)
    return root * positive("E_star", E_star) / positive("H", H)  # eq. (69)


def yield_strength_for_plasticity_index(
    psi: float, moments: SpectralMoments, E_star: float, yield_coefficient: float = 1.62
) -> float:
    """Y that makes :func:`plasticity_index` equal ψ at fixed E*, K_Y and moments (a consistent
    closure when ψ is prescribed, as in Figs 5–8): Y = (2/π) E* √(σ_s κ̄_m)/(K_Y ψ)."""
    psi = positive("psi", psi)
    return (2.0 / math.pi) * float(E_star) * math.sqrt(
        moments.summit_height_std * moments.mean_summit_curvature
    ) / (float(yield_coefficient) * psi)


def curvature_ratio(omega4, omega6, moments: SpectralMoments):
    """Oriented curvature ratio ρ = |ξ4|/|ξ6| = ω4 √m40/(ω6 √m04) (ξ4 = −ω4 √(m40 μ), ξ6 =
    −ω6 √(m04 μ), eq. (13)). The λ² of (74)/(87) must be this ρ (it may exceed 1); the Hertz
    λ² of (27) is min(ρ, 1/ρ)."""
    w4, w6 = np.asarray(omega4, dtype=float), np.asarray(omega6, dtype=float)
    rho = w4 * math.sqrt(moments.m40) / (w6 * math.sqrt(moments.m04))
    return _out(rho, rho.ndim == 0)


def gamma_87(rho, moments: SpectralMoments, psi: float, shape=None, *, hertz: str = "exact"):
    """γ of eq. (87), ω_c* = γ/ω6 (86):

        γ = √(8c) K(e) E(e) (√m04 + √m40)/(π^{3/2} μ √m04 (1 + ρ) ψ²)

    with the dimensionless c = σ_s²/m00 = 1 − (π/2 − 1)(β1 + β2) [erratum (72): printed
    (2 − π/2)(β1 + β2) m00] and ρ = |ξ4|/|ξ6| (:func:`curvature_ratio`; the printed λ² must be
    this oriented ratio, not the folded Hertz λ² ≤ 1). ``shape``: e1 or HertzFactors of the
    contact ellipse; ``None`` → hertz_factors(√ρ, hertz) (which folds ρ > 1)."""
    rho_a = np.asarray(rho, dtype=float)
    if np.any(~(rho_a > 0.0)):
        raise ValueError("rho = |ξ4|/|ξ6| must be positive")
    s = hertz_factors(np.sqrt(rho_a), hertz) if shape is None else _shape(shape, hertz)
    psi = positive("psi", psi)
    c = moments.summit_height_std**2 / moments.m00  # eq. (72) corrected, dimensionless
    g = (
        math.sqrt(8.0 * c)
        * np.asarray(s.K)
        * np.asarray(s.E)
        * (math.sqrt(moments.m04) + math.sqrt(moments.m40))
        / (math.pi**1.5 * moments.mu * math.sqrt(moments.m04) * (1.0 + rho_a) * psi**2)
    )  # eq. (87)
    return _out(g, g.ndim == 0)


def critical_interference_star(
    omega4, omega6, moments: SpectralMoments, psi: float, shape=None, *, hertz: str = "exact"
):
    """Dimensionless critical interference ω_c* = ω_c/√(m00 μ), eq. (74) = (86)–(87):

        ω_c* = √(8c) K E (√m04 + √m40)/(π^{3/2} ω6 μ √m04 (1 + ρ) ψ²),
        ρ = ω4 √m40/(ω6 √m04)

    (c dimensionless, see :func:`gamma_87`). With ψ = :func:`plasticity_index` this equals
    (65)/√(m00 μ) exactly for κ_m = √μ (ω4 √m40 + ω6 √m04)/2 (eq. (44))."""
    w6 = np.asarray(omega6, dtype=float)
    if np.any(~(w6 > 0.0)) or np.any(~(np.asarray(omega4, dtype=float) > 0.0)):
        raise ValueError("summit curvatures omega4, omega6 must be positive (eq. 16)")
    rho = curvature_ratio(omega4, w6, moments)
    v = np.asarray(gamma_87(rho, moments, psi, shape, hertz=hertz)) / w6  # eq. (86)
    return _out(v, v.ndim == 0)
