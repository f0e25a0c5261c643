"""Tests of roughcontact.asperity: one elliptic-paraboloid asperity, elastic / elasto-plastic /
plastic (eqs. (46)–(47), (58)–(77), (86)–(87) of Buczkowski & Kleiber 2009).

References are independent where possible: mpmath K(e), E(e), closed-form spherical CEB/ZMC
expressions written out here, and central finite differences.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from roughcontact import asperity as asp
from roughcontact.asperity.ellipse import f1, f3, f4, hertz_factors
from roughcontact.statistics.surface import SpectralMoments

E1_CASES = [1e-12, 1e-3, 0.5, 1.0]
HERTZ = ["exact", "paper"]
E_STAR, Y = 1.14e5, 2070.0  # N/mm², the captions of Figs 5–8
KAPPA = 0.037  # 1/µm, a typical summit of Table 1's surface
MAT = asp.AsperityMaterial(E_STAR, Y)

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
ANISO = SpectralMoments(1.0, 0.5, 2.0, 1.0, 20.0)  # α1 = 4 ≠ α2 = 5


def _mp_KE(e1: float) -> tuple[float, float]:
    """K(e), E(e) from mpmath with m = 1 − e1² held exactly."""
    with mp.workdps(80):
        m = 1 - mp.mpf(e1) ** 2
        return float(mp.ellipk(m)), float(mp.ellipe(m))


def _rel(a, b):
    return np.abs(np.asarray(a) - np.asarray(b)) / np.abs(np.asarray(b))


# --- material ------------------------------------------------------------------------------


def test_material_defaults_and_continuous_K_v():
    assert MAT.H == pytest.approx(Y / 0.354, rel=1e-15)  # Tabor (68)
    assert MAT.K_v == pytest.approx(0.354 * 1.62, rel=1e-15) == pytest.approx(0.57348, rel=1e-15)
    assert MAT.K_v * MAT.H == pytest.approx(MAT.yield_coefficient * MAT.Y, rel=1e-15)
    assert MAT.load_jump_at_yield == pytest.approx(0.0, abs=1e-15)
    assert (MAT.c_h, MAT.wp_over_wc, MAT.yield_coefficient) == (0.967, 45.0, 1.62)
    explicit = asp.AsperityMaterial(E_STAR, Y, H=6000.0)
    assert explicit.K_v == pytest.approx(1.62 * Y / 6000.0)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(E_star=-1.0, Y=Y),
        dict(E_star=E_STAR, Y=0.0),
        dict(E_star=E_STAR, Y=float("nan")),
        dict(E_star=E_STAR, Y=Y, H=-5.0),
        dict(E_star=E_STAR, Y=Y, c_h=0.0),
        dict(E_star=E_STAR, Y=Y, wp_over_wc=1.0),
        dict(E_star=E_STAR, Y=Y, wp_over_wc=float("inf")),
        dict(E_star=E_STAR, Y=Y, K_v=-0.5),
        dict(E_star="stiff", Y=Y),
        dict(E_star=E_STAR, Y=Y, yield_coefficient=0.0),
    ],
)
def test_material_validation(kwargs):
    with pytest.raises(ValueError):
        asp.AsperityMaterial(**kwargs)


def test_input_validation():
    for bad in (dict(omega=-1e-3), dict(omega=np.nan), dict(kappa_m=0.0), dict(e1=0.0), dict(e1=1.5)):
        args = dict(omega=0.1, kappa_m=KAPPA, e1=0.5) | bad
        with pytest.raises(ValueError):
            asp.load(args["omega"], args["kappa_m"], args["e1"], MAT)
    with pytest.raises(ValueError):
        asp.AsperityMaterial.with_paper_K_v(E_STAR, Y, 0.7)
    with pytest.raises(ValueError):
        asp.load(0.1, KAPPA, 0.5, MAT, hertz="approx")


# --- (62)–(65): first yield --------------------------------------------------------------


@pytest.mark.parametrize("hertz", HERTZ)
@pytest.mark.parametrize("e1", E1_CASES)
def test_corrected_62_is_three_halves_W_over_A_and_printed_62_is_its_reciprocal(e1, hertz):
    w = np.array([1e-6, 1e-3, 0.1, 0.5]) * asp.critical_interference(KAPPA, e1, MAT, hertz=hertz)
    W = asp.load(w, KAPPA, e1, MAT, hertz=hertz)
    A = asp.area(w, KAPPA, e1, MAT, hertz=hertz)
    fac = asp.factors_from_e1(e1, hertz)
    corrected = E_STAR * np.sqrt(KAPPA * w / (fac.K * fac.E))  # (62) corrected
    assert np.all(_rel(1.5 * W / A, corrected) < 1e-13)
    assert np.all(_rel(asp.elastic_max_pressure(w, KAPPA, e1, MAT, hertz=hertz), corrected) < 1e-15)
    printed = np.sqrt(fac.K * fac.E) / (E_STAR * np.sqrt(KAPPA * w))  # (62) as printed
    assert np.all(_rel(printed * corrected, 1.0) < 1e-14)  # the exact reciprocal: it falls as
    assert np.all(np.diff(printed) < 0) and np.all(np.diff(1.5 * W / A) > 0)  # ω^{-1/2}, p_max rises
    pw = np.sqrt(fac.K * fac.E) / (E_STAR * np.sqrt(KAPPA * 4 * w))
    np.testing.assert_allclose(pw / printed, 0.5, rtol=1e-14)  # quadrupling ω halves the printed form


@pytest.mark.parametrize("e1", E1_CASES)
def test_critical_interference_65_from_corrected_62(e1):
    K, E = _mp_KE(e1)
    wc = asp.critical_interference(KAPPA, e1, MAT)
    assert wc == pytest.approx(K * E * (1.62 * Y / E_STAR) ** 2 / KAPPA, rel=1e-13)  # (65)
    assert asp.elastic_max_pressure(wc, KAPPA, e1, MAT) == pytest.approx(1.62 * Y, rel=1e-14)  # (63)
    assert asp.plastic_interference(KAPPA, e1, MAT) == pytest.approx(45.0 * wc, rel=1e-15)


# --- circular limit ------------------------------------------------------------------------


def test_circular_limit_reduces_to_ceb_and_zmc():
    R, H, Kv, ch = 1.0 / KAPPA, Y / 0.354, 0.354 * 1.62, 0.967
    wc = (math.pi * 1.62 * Y / (2.0 * E_STAR)) ** 2 * R  # CEB: ω_c = (π K H/(2E))² R with KH → K_Y Y
    wp = 45.0 * wc
    assert asp.critical_interference(KAPPA, 1.0, MAT) == pytest.approx(wc, rel=1e-14)
    w = np.concatenate([np.linspace(0, wc, 7), np.geomspace(wc * 1.001, wp * 0.999, 13), wp * np.array([1, 2, 10])])
    x = (w - wc) / (wp - wc)
    A_ref = np.where(
        w <= wc, math.pi * R * w,  # Hertz
        np.where(w >= wp, 2 * math.pi * R * w,  # fully plastic (CEB/ZMC): 2πRω
                 math.pi * R * w * (1 - 2 * x**3 + 3 * x**2)),  # ZMC (2000) template
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        p_ep = H * ch - H * (ch - 2 * Kv / 3) * (np.log(wp) - np.log(w)) / (np.log(wp) - np.log(wc))
    p_ep = np.where(w > 0, p_ep, 0.0)
    W_ref = np.where(w <= wc, 4 / 3 * E_STAR * math.sqrt(R) * w**1.5, np.where(w >= wp, A_ref * ch * H, A_ref * p_ep))
    r = asp.respond(w, KAPPA, 1.0, MAT)
    np.testing.assert_allclose(r.area, A_ref, rtol=1e-13, atol=0)
    np.testing.assert_allclose(r.load, W_ref, rtol=1e-13, atol=0)
    # CEB area (58) for a sphere: πR(2ω − ω_c)
    wq = np.array([wc, 3 * wc, wp])
    np.testing.assert_allclose(asp.ceb_plastic_area(wq, KAPPA, 1.0, MAT), math.pi * R * (2 * wq - wc), rtol=1e-14)


# --- continuity ----------------------------------------------------------------------------


@pytest.mark.parametrize("hertz", HERTZ)
@pytest.mark.parametrize("e1", E1_CASES)
def test_area_and_load_continuous_at_wc_and_wp(e1, hertz):
    kappa = np.array([1e-3, KAPPA, 2.0])
    wc = asp.critical_interference(kappa, e1, MAT, hertz=hertz)
    wp = asp.plastic_interference(kappa, e1, MAT, hertz=hertz)
    for joint, side in ((wc, np.inf), (wp, 0.0)):
        other = np.nextafter(joint, side)
        a, b = asp.respond(joint, kappa, e1, MAT, hertz=hertz), asp.respond(other, kappa, e1, MAT, hertz=hertz)
        assert np.all(a.regime != b.regime)
        assert np.all(_rel(a.area, b.area) <= 1e-12)
        assert np.all(_rel(a.load, b.load) <= 1e-12)


@pytest.mark.parametrize("e1", E1_CASES)
def test_f3_f4_equals_f1_makes_58_continuous_but_blend_must_end_on_61(e1):
    assert f3(e1) * f4(e1) == pytest.approx(f1(e1), rel=1e-14)
    wc = asp.critical_interference(KAPPA, e1, MAT)
    assert asp.ceb_plastic_area(wc, KAPPA, e1, MAT) == pytest.approx(asp.area(wc, KAPPA, e1, MAT), rel=1e-13)
    # at ω_p the blend (76) lands on (61) = 2 f3 π ω/κ_m; (58) is lower by (ω_c/ω_p)(2 − f4)/2
    wp = 45.0 * wc
    a61 = 2 * f3(e1) * math.pi * wp / KAPPA
    assert asp.area(np.nextafter(wp, 0), KAPPA, e1, MAT) == pytest.approx(a61, rel=1e-12)
    gap = 1 - asp.ceb_plastic_area(wp, KAPPA, e1, MAT) / a61
    assert gap == pytest.approx((2 - f4(e1)) / 90, rel=1e-12)
    assert 0.0111 <= gap <= 0.0223


def test_K_v_continuity_condition_and_the_papers_jump():
    # continuous iff K_v H = K_Y Y; the paper's K_v = 0.454 + 0.41ν meets it only at ν = 0.29141
    nu_star = (0.354 * 1.62 - 0.454) / 0.41
    assert nu_star == pytest.approx(0.291415, abs=1e-6)
    assert asp.AsperityMaterial.with_paper_K_v(E_STAR, Y, nu_star).load_jump_at_yield == pytest.approx(0, abs=1e-15)
    paper = asp.AsperityMaterial.with_paper_K_v(E_STAR, Y, 0.3)
    assert paper.K_v == pytest.approx(0.577)
    assert paper.load_jump_at_yield == pytest.approx(0.577 / 0.57348 - 1, rel=1e-12)
    assert paper.load_jump_at_yield == pytest.approx(0.006138, abs=1e-6)
    for e1 in E1_CASES:  # the jump is measured on the load itself, independent of shape
        wc = asp.critical_interference(KAPPA, e1, paper)
        jump = asp.load(np.nextafter(wc, np.inf), KAPPA, e1, paper) / asp.load(wc, KAPPA, e1, paper) - 1
        assert jump == pytest.approx(paper.load_jump_at_yield, rel=1e-10)
        assert asp.area(np.nextafter(wc, np.inf), KAPPA, e1, paper) == pytest.approx(asp.area(wc, KAPPA, e1, paper), rel=1e-12)
    # 0.454 + 0.41ν is Tabor × (64) to rounding; the jump is the fixed K_Y = 1.62 vs ν = 0.3
    nus = np.linspace(0.0, 0.5, 11)
    assert np.max(np.abs(asp.paper_K_v(nus) - 0.354 * asp.yield_coefficient_from_poisson(nus))) < 2.5e-4
    assert (1.62 - 1.282) / 1.158 == pytest.approx(0.29188, abs=1e-5)  # ν at which (64) gives 1.62


# --- stiffness -----------------------------------------------------------------------------


def _fd(e1, w, hertz="exact", mat=MAT, h_rel=1e-6):
    h = h_rel * w
    return (asp.load(w + h, KAPPA, e1, mat, hertz=hertz) - asp.load(w - h, KAPPA, e1, mat, hertz=hertz)) / (2 * h)


@pytest.mark.parametrize("hertz", HERTZ)
@pytest.mark.parametrize("e1", E1_CASES)
def test_stiffness_equals_finite_difference_in_every_regime(e1, hertz):
    wc = asp.critical_interference(KAPPA, e1, MAT, hertz=hertz)
    t = np.array([1e-3, 0.3, 1 - 1e-4, 1 + 1e-4, 1.5, 10.0, 30.0, 45 * (1 - 1e-4), 45 * (1 + 1e-4), 100.0, 1e4])
    w = t * wc
    reg = asp.regime(w, KAPPA, e1, MAT, hertz=hertz)
    assert set(reg.tolist()) == {asp.ELASTIC, asp.ELASTO_PLASTIC, asp.PLASTIC}
    k = asp.stiffness(w, KAPPA, e1, MAT, hertz=hertz)
    assert np.all(_rel(k, _fd(e1, w, hertz)) <= 1e-6)


@pytest.mark.parametrize("e1", E1_CASES)
def test_stiffness_jumps_at_the_joints_and_88_without_blend_derivative_is_wrong(e1):
    wc = asp.critical_interference(KAPPA, e1, MAT)
    wp = 45 * wc
    k = lambda w: asp.stiffness(w, KAPPA, e1, MAT)  # noqa: E731
    r_c = k(np.nextafter(wc, np.inf)) / k(wc)
    r_p = k(wp) / k(np.nextafter(wp, 0))
    assert r_c == pytest.approx(MAT.stiffness_ratio_at_yield, rel=1e-10)
    assert r_p == pytest.approx(MAT.stiffness_ratio_at_full_plasticity, rel=1e-10)
    assert r_c == pytest.approx(0.93449, abs=1e-5) and 1 / r_p == pytest.approx(1.15884, abs=1e-5)
    # dropping d g/dω (as (88) does) misses most of the elasto-plastic stiffness mid-transition
    w = 23 * wc
    fac = asp.factors_from_e1(e1)
    x = (w - wc) / (wp - wc)
    g = 3 * x**2 - 2 * x**3
    p = asp.mean_pressure(w, KAPPA, e1, MAT)
    A = asp.area(w, KAPPA, e1, MAT)
    no_dg = (fac.f1 + (2 * fac.f3 - fac.f1) * g) * math.pi / KAPPA * p + A * MAT.H * (
        MAT.c_h - 2 * MAT.K_v / 3
    ) / (w * math.log(45))
    assert _rel(no_dg, _fd(e1, w)) > 0.3


# --- monotonicity, limits, robustness --------------------------------------------------------


@pytest.mark.parametrize("hertz", HERTZ)
@pytest.mark.parametrize("e1", E1_CASES)
def test_load_and_area_increase_with_interference(e1, hertz):
    wc = asp.critical_interference(KAPPA, e1, MAT, hertz=hertz)
    w = np.concatenate([[0.0], np.geomspace(1e-8, 1e3, 4001) * wc])
    r = asp.respond(w, KAPPA, e1, MAT, hertz=hertz)
    assert np.all(np.diff(r.load) > 0) and np.all(np.diff(r.area) > 0)
    assert np.all(r.stiffness[1:] > 0)
    assert np.all(np.diff(r.regime) >= 0)


@pytest.mark.parametrize("e1", E1_CASES)
def test_mean_pressure_tends_to_c_h_H(e1):
    wc = asp.critical_interference(KAPPA, e1, MAT)
    w = np.array([0.0, 0.5, 1.0, 2.0, 20.0, 44.9, 45.0, 1e3, 1e8]) * wc
    r = asp.respond(w, KAPPA, e1, MAT)
    pm = asp.mean_pressure(w, KAPPA, e1, MAT)
    np.testing.assert_allclose(pm[1:], r.load[1:] / r.area[1:], rtol=1e-13)
    assert pm[0] == 0.0
    assert pm[2] == pytest.approx(2 / 3 * 1.62 * Y, rel=1e-14)  # (2/3) K_Y Y = 0.382 H at ω_c
    assert pm[2] / MAT.H == pytest.approx(0.38232, rel=1e-12)
    assert np.all(np.diff(pm) >= 0)
    np.testing.assert_allclose(pm[-3:], 0.967 * MAT.H, rtol=1e-14)
    assert 0.967 * MAT.H - pm[-4] < 2e-3 * MAT.H  # approached from below within the transition


@pytest.mark.parametrize("e1", [1e-100, 1e-12, 1e-3, 0.5, 1 - 1e-15, 1.0])
def test_small_interference_and_extreme_shapes_are_finite(e1):
    w = np.array([0.0, 1e-300, 1e-200, 1e-20, 1e-3, 1.0, 1e3])
    with np.errstate(divide="raise", invalid="raise", over="raise"):
        r = asp.respond(w, KAPPA, e1, MAT)
    for v in (r.area, r.load, r.stiffness):
        assert np.all(np.isfinite(v)) and np.all(v >= 0)
    assert r.area[0] == r.load[0] == r.stiffness[0] == 0.0
    assert r.area[1] < 1e-180 and np.all(np.diff(r.area) > 0) and np.all(np.diff(r.load) >= 0)


def test_near_circle_is_smooth_in_e1():
    w = np.array([0.1, 5.0, 50.0]) * asp.critical_interference(KAPPA, 1.0, MAT)
    for q in ("area", "load", "stiffness"):
        a = getattr(asp, q)(w, KAPPA, 1.0, MAT)
        b = getattr(asp, q)(w, KAPPA, 1 - 1e-12, MAT)
        assert np.all(_rel(b, a) < 1e-10)


def test_regime_codes_and_names():
    wc = asp.critical_interference(KAPPA, 0.5, MAT)
    reg = asp.regime(np.array([0.0, wc, np.nextafter(wc, 1), 45 * wc, 1e3 * wc]), KAPPA, 0.5, MAT)
    assert reg.tolist() == [0, 0, 1, 2, 2]
    assert [asp.REGIME_NAMES[i] for i in reg[[0, 2, 3]]] == ["elastic", "elasto-plastic", "plastic"]
    assert isinstance(asp.regime(0.0, KAPPA, 0.5, MAT), int)
    assert isinstance(asp.load(1e-3, KAPPA, 0.5, MAT), float)


def test_vectorised_broadcast_and_hertz_factors_input():
    lam = np.array([0.01, 0.1, 0.5, 1.0, 3.0])
    fac = hertz_factors(lam)
    w = np.geomspace(1e-4, 100.0, 7)[:, None]
    r = asp.respond(w, KAPPA, fac, MAT)
    assert r.load.shape == r.area.shape == r.regime.shape == (7, 5)
    for j, lj in enumerate(lam):
        e1j = float(fac.e1[j])
        np.testing.assert_allclose(r.load[:, j], asp.load(w[:, 0], KAPPA, e1j, MAT), rtol=1e-14)
    kappa = np.array([0.01, 0.1, 1.0])
    wc = asp.critical_interference(kappa, 0.3, MAT)
    np.testing.assert_allclose(wc * kappa, wc[0] * kappa[0], rtol=1e-15)  # ω_c ∝ 1/κ_m


# --- plasticity index, (74), (86)–(87) -------------------------------------------------------


@pytest.mark.parametrize("moments", [TABLE1, ANISO], ids=["table1", "alpha1_ne_alpha2"])
def test_74_equals_65_with_consistent_psi(moments):
    mat = asp.AsperityMaterial(E_STAR, Y) if moments is TABLE1 else asp.AsperityMaterial(200.0, 1.0)
    psi = asp.plasticity_index(moments, mat)
    # the defining algebra: ψ = (2/π)(E*/(K_Y Y))√(σ_s κ̄_m), σ_s² = c m00, κ̄_m = √(π/8)(√m04 + √m40)
    c = 1 - (math.pi / 2 - 1) * (moments.beta1 + moments.beta2)
    kbar = math.sqrt(math.pi / 8) * (math.sqrt(moments.m04) + math.sqrt(moments.m40))
    expected = 2 / math.pi * mat.E_star / mat.yield_pressure * (c * moments.m00) ** 0.25 * math.sqrt(kbar)
    assert psi == pytest.approx(expected, rel=1e-14)
    rng = np.random.default_rng(3)
    w4, w6 = rng.rayleigh(size=200) / math.sqrt(moments.mu), rng.rayleigh(size=200) / math.sqrt(moments.mu)
    w4[:3], w6[:3] = [1e-3, 1.0, 50.0], [1.0, 1e-3, 50.0]
    rho = asp.curvature_ratio(w4, w6, moments)
    assert np.any(rho > 1) and np.any(rho < 1)  # both orientations of the ellipse
    fac = hertz_factors(np.sqrt(rho))
    kappa = math.sqrt(moments.mu) * (w4 * math.sqrt(moments.m40) + w6 * math.sqrt(moments.m04)) / 2  # (44)
    wc = asp.critical_interference(kappa, fac, mat)  # (65)
    star = asp.critical_interference_star(w4, w6, moments, psi)  # (74)
    np.testing.assert_allclose(star * math.sqrt(moments.m00 * moments.mu), wc, rtol=1e-13)
    np.testing.assert_allclose(asp.gamma_87(rho, moments, psi) / w6, star, rtol=1e-15)  # (86)
    # the folded Hertz λ² ≤ 1 in (1 + λ²) is wrong for turned ellipses (ρ > 1)
    folded = star * (1 + rho) / (1 + np.minimum(rho, 1 / rho))
    assert np.all(_rel(folded[rho > 1.01], star[rho > 1.01]) > 1e-3)
    # the printed c = (2 − π/2)(β1 + β2) m00 of (72) does not give (65)
    c_printed = (2 - math.pi / 2) * (moments.beta1 + moments.beta2) * moments.m00
    assert np.all(_rel(star * math.sqrt(c_printed / c), star) > 0.4)
    # GW's (69) differs by the constant (2/π) H/(K_Y Y) = 1.110 with Tabor's H
    ratio = psi / asp.plasticity_index_gw(moments, mat.H, mat.E_star)
    assert ratio == pytest.approx(2 / math.pi * mat.H / (1.62 * mat.Y), rel=1e-14)
    if moments is TABLE1:
        assert ratio == pytest.approx(1.1101, abs=1e-4)


def test_plasticity_index_of_the_captions_and_closure():
    got = [asp.plasticity_index(SpectralMoments(m00, 8e-5, 8e-4, 1.04e-6, 1.04e-4), MAT) for m00 in (0.0625, 0.3125, 0.625)]
    np.testing.assert_allclose(got, [0.88, 1.35, 1.61], atol=0.006)  # docs/independent-studies.md; yet Figs 5–8 prescribe ψ = 0.35/0.5
    for psi in (0.35, 0.5, 2.0):
        y = asp.yield_strength_for_plasticity_index(psi, TABLE1, E_STAR)
        assert asp.plasticity_index(TABLE1, asp.AsperityMaterial(E_STAR, y)) == pytest.approx(psi, rel=1e-14)


@pytest.mark.parametrize("Y", [1e200, 1e-200])
def test_material_whose_first_yield_overflows_is_refused(Y):
    """Issue #12: Y = 1e200 (or ψ = 1e-160 through yield-from-psi) raised OverflowError in
    (K_Y Y/E*)² of (65); now a ValueError naming the condition."""
    with pytest.raises(ValueError, match=r"K_Y Y/E\*"):
        asp.AsperityMaterial(E_STAR, Y)
    y_psi = asp.yield_strength_for_plasticity_index(1e-160, TABLE1, E_STAR)
    with pytest.raises(ValueError, match=r"K_Y Y/E\*"):
        asp.AsperityMaterial(E_STAR, y_psi)
