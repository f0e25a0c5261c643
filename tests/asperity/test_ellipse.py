"""Tests of roughcontact.asperity.ellipse: the Hertz contact ellipse of one asperity (eqs. (26)–(48),
(58)–(60) of Buczkowski & Kleiber 2009).

References are independent of the module: closed forms, mpmath (ellipk/ellipe via the AGM,
numerical differentiation, findroot) and scipy.special.ellipk/ellipe (Cephes polynomials,
not the Carlson forms the module uses).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
import scipy.special as sc

from roughcontact.asperity import ellipse as el

E1_POINTS = [1e-300, 1e-12, 1e-3, 0.3, 0.9, 1.0 - 1e-9, 1.0]


# --- independent references ----------------------------------------------------------------


def _dps_for(e1: float) -> int:
    """Digits needed so that m = 1 - e1² is represented exactly enough in mpmath."""
    return 40 + (int(-2 * math.log10(e1)) if 0 < e1 < 1 else 0)


def _mp_BDKE(e1: float):
    """(B, D, K, E) from mpmath.ellipk/ellipe(m) with B = (E - m1 K)/m, D = (K - E)/m."""
    with mp.workdps(_dps_for(e1)):
        m1 = mp.mpf(e1) ** 2
        m = 1 - m1
        K, E = mp.ellipk(m), mp.ellipe(m)
        if m == 0:
            return mp.pi / 4, mp.pi / 4, K, E
        return (E - m1 * K) / m, (K - E) / m, K, E


def _mp_lambda2_printed27(e1: float):
    """λ² from (27) *as printed*, with k = e and dK/dk by numerical differentiation."""
    with mp.workdps(40):
        k = mp.sqrt(1 - mp.mpf(e1) ** 2)
        Kk = lambda kk: mp.ellipk(kk**2)  # noqa: E731
        dK = mp.diff(Kk, k)
        return (k * Kk(k) - (1 - k**2) * dK) / dK


def _mp_e1_of_lambda(lam: float):
    """e1 solving (27) with mpmath (findroot in ln e1), λ² = (K - E)(1 - m)/(E - m1 K)."""
    x0 = math.log(lam) - 0.5 * math.log(max(math.log(4 / lam), 1.0)) if lam < 0.5 else 1.3 * math.log(lam)
    with mp.workdps(_dps_for(lam) + 10):

        def F(x):
            e1 = mp.exp(x)
            m1 = e1**2
            m = 1 - m1
            K, E = mp.ellipk(m), mp.ellipe(m)
            return 2 * x + mp.log((K - E) / (E - m1 * K)) - 2 * mp.log(mp.mpf(lam))

        return mp.exp(mp.findroot(F, mp.mpf(x0)))


def _rel(x, ref) -> float:
    return float(abs((mp.mpf(float(x)) - ref) / ref))


# --- closed forms ----------------------------------------------------------------------------


def test_circle_closed_forms():
    B, D = el.elliptic_BD(1.0)
    K, E = el.elliptic_KE(1.0)
    assert B == pytest.approx(math.pi / 4, rel=1e-15) and D == pytest.approx(math.pi / 4, rel=1e-15)
    assert K == pytest.approx(math.pi / 2, rel=1e-15) and E == pytest.approx(math.pi / 2, rel=1e-15)
    for f in (el.f1, el.f2):
        assert f(1.0) == pytest.approx(1.0, abs=1e-15)
    assert el.f3(1.0) == pytest.approx(1.0, abs=1e-15) and el.f4(1.0) == pytest.approx(1.0, abs=1e-15)
    assert el.lambda_squared(1.0) == pytest.approx(1.0, abs=1e-15)
    assert el.fig4_curves(0.0) == pytest.approx((1.0, 1.0), abs=1e-15)
    # paper polynomials: a0 + a1 + a2 = 1.5707963 (π/2 to 7 decimals)
    Kp, Ep = el.elliptic_KE(1.0, "paper")
    assert abs(Kp - math.pi / 2) < 3e-8 and abs(Ep - math.pi / 2) < 3e-8
    # e1 = 0: B = 1, D = K = inf, E = 1, λ = 0
    assert el.elliptic_BD(0.0) == (1.0, math.inf)
    assert el.elliptic_KE(0.0) == (math.inf, 1.0)
    assert el.lambda_squared(0.0) == 0.0 and el.e1_from_lambda(0.0) == 0.0


def test_eccentricity_is_stable():
    for e1 in (0.0, 0.5, 1 - 1e-12, 1.0):
        with mp.workdps(50):
            ref = mp.sqrt(1 - mp.mpf(e1) ** 2)
        got = el.eccentricity(e1)
        if ref == 0:
            assert got == 0.0
        else:
            assert _rel(got, ref) < 2e-16


# --- elliptic integrals against mpmath --------------------------------------------------------


@pytest.mark.parametrize("e1", E1_POINTS)
def test_BDKE_against_mpmath(e1):
    """Achieved: ≤ 3.1e-16 relative for B, D, K, E on these points (bound asserted 1e-15)."""
    B, D = el.elliptic_BD(e1)
    K, E = el.elliptic_KE(e1)
    rB, rD, rK, rE = _mp_BDKE(e1)
    for got, ref in ((B, rB), (D, rD), (K, rK), (E, rE)):
        assert _rel(got, ref) <= 1e-15


def test_BDKE_dense_against_scipy_cephes():
    e1 = np.concatenate([np.logspace(-7.9, 0, 400), 1 - np.logspace(-15, -1, 50)])
    m1 = e1**2
    K, E = el.elliptic_KE(e1)
    Kref = sc.ellipkm1(m1)  # Cephes polynomial, independent of the Carlson forms
    Eref = sc.ellipe(1 - m1)
    assert np.max(np.abs(K / Kref - 1)) < 2e-15
    assert np.max(np.abs(E / Eref - 1)) < 2e-15


def test_B_carlson_form_is_cancellation_free():
    """B = e1² R_D(0, 1, e1²)/3 is accurate at both ends; (E - m1 K)/m is not as e1 → 1."""
    for e1 in (1e-7, 1e-3, 0.5, 1 - 1e-6, 1 - 1e-9):
        B, _ = el.elliptic_BD(e1)
        assert _rel(B, _mp_BDKE(e1)[0]) < 5e-16
    e1 = 1 - 1e-9
    m1 = e1 * e1
    K, E = sc.ellipkm1(m1), sc.ellipe(1 - m1)
    naive = (E - m1 * K) / ((1 - e1) * (1 + e1))
    assert _rel(naive, _mp_BDKE(e1)[0]) > 1e-10


def test_tiny_e1_is_finite_and_asymptotic():
    for e1 in (1e-305, 1e-300, 1e-200):
        L = math.log(4.0) - math.log(e1)
        K, E = el.elliptic_KE(e1)
        assert K == pytest.approx(L, rel=1e-15) and E == pytest.approx(1.0, rel=1e-15)
        v1, v2 = el.f1(e1), el.f2(e1)
        assert np.isfinite(v1) and np.isfinite(v2)
        # f1 ~ 1/(e1 ln(4/e1)), f2 ~ π/(2 e1 ln(4/e1)^{3/2}) (K → ln(4/e1), E → 1)
        assert v1 * e1 * L == pytest.approx(1.0, rel=1e-14)
        assert v2 * e1 * L**1.5 == pytest.approx(math.pi / 2, rel=1e-14)


def test_f1_asymptotics_converge():
    e1 = np.logspace(-300, -1, 60)
    L = np.log(4.0 / e1)
    dev = np.abs(el.f1(e1) * e1 * L - 1)
    # E ≈ 1 + (m1/2)(L - 1/2), K ≈ L + (m1/4)(L - 1): deviation O(e1² L), → 0
    assert np.all(dev <= e1**2 * L + 4e-16)
    assert dev[-1] > dev[0]


# --- A&S polynomials (36)–(39) -----------------------------------------------------------------


def _as_grid():
    m1 = np.concatenate([np.logspace(-300, 0, 3001), np.linspace(0, 1, 200001)[1:]])
    return np.sqrt(m1), m1


def test_polynomials_hold_their_bounds_barely():
    e1, m1 = _as_grid()
    K, E = el.elliptic_KE(e1, "paper")
    Kref, Eref = sc.ellipkm1(m1), sc.ellipe(1 - m1)
    errK, errE = np.abs(K - Kref), np.abs(E - Eref)
    assert errK.max() <= el.AS_K_BOUND and errE.max() <= el.AS_E_BOUND
    # the bounds are nearly attained (max 2.993e-5 near m1 = 0.1435, 3.917e-5 near m1 = 0.1444)
    assert errK.max() > 0.99 * el.AS_K_BOUND and errE.max() > 0.97 * el.AS_E_BOUND
    assert 0.14 < m1[np.argmax(errK)] < 0.15 and 0.14 < m1[np.argmax(errE)] < 0.15


def test_printed_a2_of_39_does_not_violate_bound():
    """Erratum (39): a2 = 0.10778112 (printed) vs 0.1077812 (A&S 17.3.36). Numerically
    immaterial: max |ε| 3.9172e-5 (printed) vs 3.9174e-5 (A&S), both ≤ 4e-5; the misprint
    only shows at the circle, E(e=0) - π/2 = -1.07e-7 instead of -2.7e-8."""
    assert el.PRINTED_E_A2 != el.AS_E_COEFFS[0][2]
    e1, m1 = _as_grid()
    Eref = sc.ellipe(1 - m1)
    _, Ep = el.elliptic_KE(e1, "paper", a2_printed=True)
    _, Ea = el.elliptic_KE(e1, "paper")
    assert np.abs(Ep - Eref).max() <= el.AS_E_BOUND
    assert abs(np.abs(Ep - Eref).max() - np.abs(Ea - Eref).max()) < 1e-8
    _, Ep1 = el.elliptic_KE(1.0, "paper", a2_printed=True)
    _, Ea1 = el.elliptic_KE(1.0, "paper")
    assert 1.0e-7 < math.pi / 2 - Ep1 < 1.1e-7 and 2.6e-8 < math.pi / 2 - Ea1 < 2.8e-8


# --- λ(e1): (27), (32), monotonicity -----------------------------------------------------------


@pytest.mark.parametrize("e1", [1e-3, 0.1, 0.5, 0.9])
def test_lambda_squared_matches_printed_27(e1):
    """(27) as printed (k K - (1-k²) dK/dk)/(dK/dk), k = e, equals e1² D/B."""
    assert _rel(el.lambda_squared(e1), _mp_lambda2_printed27(e1)) < 1e-14


def test_lambda_monotone_at_most_one_so_a_is_semimajor():
    """λ² = b²/a² ≤ 1 for every e1 (with equality only for the circle), so in (27) b ≤ a:
    a is the semi-MAJOR axis (the text of section 3 says semi-minor). From (20),
    b²/a² = |ξ4|/|ξ6|, so a lies along the direction of smaller curvature."""
    e1 = np.concatenate([[0.0], np.logspace(-150, 0, 2000)])
    lam2 = el.lambda_squared(e1)
    assert np.all(np.diff(lam2) > 0)
    assert np.all(lam2 <= 1.0) and lam2[-1] == pytest.approx(1.0, abs=1e-15)
    assert np.all(lam2[:-1] < 1.0)
    # e1 ≤ λ (D ≥ B): the contact ellipse is more eccentric than the geometric one
    assert np.all(e1 <= np.sqrt(lam2) * (1 + 1e-15))
    lam = el.lambda_from_e1(e1)
    assert np.all(np.diff(lam) > 0)


def test_27_and_32_agree_as_e1_to_0():
    e1 = np.logspace(-150, -1, 50)
    lam_exact = el.lambda_from_e1(e1) ** 2 / e1**2  # = D/B, avoids underflow
    lam_32 = np.log(4.0 / e1) - 1.0  # (32) divided by e1²
    rel = np.abs(lam_exact / lam_32 - 1)
    L = np.log(4.0 / e1)
    # leading correction (D/B)/(L - 1) - 1 ≈ e1² L/2  (DLMF 19.12 expansions)
    assert np.all(rel <= e1**2 * L + 1e-15)
    assert rel[0] < 1e-15 and rel[-1] > 1e-3
    assert el.lambda_squared_small_e1(1e-3) == pytest.approx(1e-6 * (math.log(4000.0) - 1), rel=1e-15)


def test_johnson_approximation_loosely():
    """Johnson's e1 ≈ λ^{4/3}: exact at the circle, within 16 % for λ ≥ 0.1, 3.5 % for λ ≥ 0.3."""
    lam = np.linspace(0.1, 1.0, 91)
    rel = lam ** (4 / 3) / el.e1_from_lambda(lam) - 1
    assert np.all(np.abs(rel) < 0.16)
    assert np.all(np.abs(rel[lam >= 0.3]) < 0.035)
    assert rel[-1] == pytest.approx(0.0, abs=1e-15)


# --- λ → e1 inversion ----------------------------------------------------------------------------


def test_inversion_roundtrip():
    lam = np.concatenate([np.logspace(-300, 0, 3001), 1 - np.logspace(-16, -1, 100)])
    e1 = el.e1_from_lambda(lam)
    back = el.lambda_from_e1(e1)
    assert np.max(np.abs(back / lam - 1)) <= 1e-13  # achieved 4.4e-16
    assert el.e1_from_lambda(1.0) == 1.0 and el.e1_from_lambda(0.0) == 0.0
    # λ > 1: the ellipse turns, use 1/λ
    assert el.e1_from_lambda(4.0) == el.e1_from_lambda(0.25)
    assert el.e1_from_lambda(np.array([2.0, 0.5])).tolist() == [el.e1_from_lambda(0.5)] * 2


@pytest.mark.mpmath
@pytest.mark.parametrize("lam", [1e-150, 1e-10, 0.01, 0.1, 0.5, 0.9, 1 - 1e-6])
def test_inversion_against_mpmath(lam):
    assert _rel(el.e1_from_lambda(lam), _mp_e1_of_lambda(lam)) <= 1e-14


def test_inversion_slope_at_circle_is_kink():
    """λ² ≈ 1 - (3/4) m near e = 0 (closed-form Taylor expansion) ⇒ de1/dλ = 4/3 for λ → 1⁻,
    and -4/3 for λ → 1⁺ (axis turn): a kink at λ = 1."""
    h = 1e-6
    left = (el.e1_from_lambda(1.0) - el.e1_from_lambda(1 - h)) / h
    right = (el.e1_from_lambda(1 + h) - el.e1_from_lambda(1.0)) / h
    assert left == pytest.approx(4 / 3, rel=1e-5) and right == pytest.approx(-4 / 3, rel=1e-5)


# --- the paper's fit (33) ------------------------------------------------------------------------


def test_paper_33_constants():
    assert el.PAPER_LAMBDA_POLE == pytest.approx(1 / 1.3211, rel=1e-15)
    assert el.PAPER_LAMBDA_CLIP == pytest.approx(1 / 1.7988, rel=1e-15)
    assert 0.5559 < el.PAPER_LAMBDA_CLIP < 0.5560 and 0.7569 < el.PAPER_LAMBDA_POLE < 0.7570
    assert el.e1_from_lambda_paper_raw(el.PAPER_LAMBDA_CLIP) == pytest.approx(1.0, rel=1e-14)


def test_paper_33_exceeds_one_then_pole():
    assert el.e1_from_lambda_paper_raw(0.5558) < 1.0 < el.e1_from_lambda_paper_raw(0.5560)
    assert el.e1_from_lambda_paper_raw(0.75) > 30  # blows up towards the pole
    for bad in (el.PAPER_LAMBDA_POLE, 0.8, 1.0, 2.0):
        with pytest.raises(ValueError):
            el.e1_from_lambda_paper_raw(bad)
    # clipped: circle from the clip point on, through the pole, up to 1 and (turned) beyond
    lam = np.array([el.PAPER_LAMBDA_CLIP, 0.6, el.PAPER_LAMBDA_POLE, 0.9, 1.0, 1.5])
    assert np.all(el.e1_from_lambda(lam, "paper") == 1.0)
    assert el.e1_from_lambda(0.3, "paper") == pytest.approx(0.4777 * 0.3 / (1 - 1.3211 * 0.3), rel=1e-15)
    assert el.e1_from_lambda(1 / 0.3, "paper") == el.e1_from_lambda(0.3, "paper")


def test_paper_33_within_one_percent_only_on_narrow_range():
    """|e1(33)/e1(27) - 1| ≤ 1 % exactly on 0.0764 ≤ λ ≤ 0.1624 (one interval); outside it
    the error grows to 14 % at λ = 0.3, 76 % at 0.5 and diverges (log-slowly) as λ → 0."""
    lam = np.linspace(1e-4, el.PAPER_LAMBDA_CLIP * (1 - 1e-9), 50001)
    rel = np.abs(el.e1_from_lambda_paper_raw(lam) / el.e1_from_lambda(lam) - 1)
    inside = lam[rel <= 0.01]
    assert 0.0763 < inside.min() < 0.0765 and 0.1623 < inside.max() < 0.1625
    assert inside.size == np.count_nonzero((lam >= inside.min()) & (lam <= inside.max()))
    for lam0, lo, hi in ((0.3, 0.13, 0.15), (0.5, 0.75, 0.77), (1e-3, 0.37, 0.39), (1e-100, 6.0, 6.6)):
        r = el.e1_from_lambda_paper_raw(lam0) / el.e1_from_lambda(lam0) - 1
        assert lo < r < hi


@pytest.mark.mpmath
def test_paper_33_one_percent_edges_against_mpmath():
    for lam, inside in ((0.0763, False), (0.0765, True), (0.078, True), (0.1623, True), (0.1625, False)):
        r = abs(0.4777 * lam / (1 - 1.3211 * lam) / _mp_e1_of_lambda(lam) - 1)
        assert (r <= 0.01) == inside


# --- f1–f4 ------------------------------------------------------------------------------------------


def test_f3_f4_product_and_circle():
    e1 = np.concatenate([np.logspace(-300, 0, 400), 1 - np.logspace(-16, -1, 50)])
    assert np.max(np.abs(el.f3(e1) * el.f4(e1) / el.f1(e1) - 1)) < 5e-16
    assert el.f3(1.0) == 1.0 and el.f4(1.0) == 1.0


@pytest.mark.parametrize("e1", [1e-3, 0.3, 0.9, 1 - 1e-6, 1 - 1e-10])
def test_f3_f4_match_printed_59_60_in_mpmath(e1):
    """(59)–(60) as printed, evaluated in 50-digit arithmetic, vs the rearranged float forms.
    The printed forms in double precision lose ~1e-6 relative at e1 = 1 - 1e-10."""
    with mp.workdps(50):
        x = mp.mpf(e1)
        e2 = 1 - x**2
        K, E = mp.ellipk(e2), mp.ellipe(e2)
        f3r = E * e2 / (2 * mp.sqrt(1 - e2) * (E - K * (1 - e2)))  # (59) printed
        f4r = 2 * (E - (1 - e2) * K) / (K * e2)  # (60) printed
    assert _rel(el.f3(e1), f3r) < 1e-14 and _rel(el.f4(e1), f4r) < 1e-14
    if e1 == 1 - 1e-10:
        K, E = el.elliptic_KE(e1)
        e2 = el.eccentricity(e1) ** 2
        assert _rel(E * e2 / (2 * e1 * (E - K * (1 - e2))), f3r) > 1e-8


@pytest.mark.parametrize("lam", [0.05, 0.2, 0.6, 0.95])
def test_f1_f2_reproduce_hertz_ellipse(lam):
    """Johnson (Contact Mechanics §4.2) Hertz relations, solved in mpmath for given principal
    curvatures κ_s = λ² κ_l, reproduce A_i = f1 π ω/κ_m and W_i = f2 (4/3) E* κ_m^{-1/2} ω^{3/2}
    with κ_m = (κ_s + κ_l)/2 (43), i.e. R_m = 2R'R''/(R' + R'') — not (R' + R'')^{1/2}."""
    with mp.workdps(30):
        ks, kl, w, Es = mp.mpf(lam) ** 2 * 3, mp.mpf(3), mp.mpf("0.01"), mp.mpf(2)

        def ratio(e):  # B'/A' = κ_l/κ_s as a function of the eccentricity e
            K, E = mp.ellipk(e**2), mp.ellipe(e**2)
            return (E / (1 - e**2) - K) / (K - E) - kl / ks

        e = mp.findroot(ratio, (mp.mpf("1e-3"), 1 - mp.mpf("1e-25")), solver="ridder")
        K, E = mp.ellipk(e**2), mp.ellipe(e**2)
        # δ = p0 b K/E*;  A' = κ_s/2 = (p0 b/E*)(K - E)/(e² a²)
        p0b = w * Es / K
        a = mp.sqrt(p0b * (K - E) / (e**2 * Es * ks / 2))
        b = a * mp.sqrt(1 - e**2)
        p0 = p0b / b
        area, load = mp.pi * a * b, 2 * mp.pi * a * b * p0 / 3
        km = (ks + kl) / 2  # eq. (43)
        e1_ref = b / a
    hf = el.hertz_factors(lam)
    assert _rel(hf.e1, e1_ref) < 1e-13
    assert _rel(hf.f1 * math.pi * float(w) / float(km), area) < 1e-13
    assert _rel(hf.f2 * 4 / 3 * float(Es) * float(km) ** -0.5 * float(w) ** 1.5, load) < 1e-13
    # dimensional check of the printed R_m = (R' + R'')^{1/2}: scaling all curvatures by s
    # scales the Hertz area by 1/s, but (R'+R'')^{1/2} scales as s^{-1/2}.
    s = 4.0
    Rm_printed = lambda kk: math.sqrt(2 / kk[0] + 2 / kk[1])  # noqa: E731  R = 1/(2A'), 1/(2B')
    k = (float(ks), float(kl))
    assert Rm_printed((k[0] * s, k[1] * s)) / Rm_printed(k) == pytest.approx(s**-0.5)
    assert (1 / (km * s)) / (1 / km) == pytest.approx(1 / s)


def test_fig4_curves_both_options():
    e = np.linspace(0.0, 0.999, 1000)
    for hertz in ("exact", "paper"):
        c1, c2 = el.fig4_curves(e, hertz)
        assert c1[0] == pytest.approx(1.0, abs=2e-7) and c2[0] == pytest.approx(1.0, abs=2e-7)
        assert np.all(c1 >= c2 - 1e-7)
    c1, c2 = el.fig4_curves(e)
    assert np.all(np.diff(c1[1:]) > 0) and np.all(np.diff(c2[1:]) > 0)  # exact: increasing
    # the polynomials are not: paper f2 dips by ~2e-8 just after e = 0 (f2(0) = 1 + 1.7e-8)
    x1, x2 = el.fig4_curves(e)
    p1, p2 = el.fig4_curves(e, "paper")
    assert np.max(np.abs(p1 / x1 - 1)) < 6e-5 and np.max(np.abs(p2 / x2 - 1)) < 6e-5
    with mp.workdps(30):
        m = mp.mpf("0.25")
        f1r = mp.ellipe(m) / (mp.ellipk(m) * mp.sqrt(1 - m))
        f2r = mp.pi * mp.sqrt(mp.ellipe(m)) / (2 * mp.ellipk(m) ** 1.5 * mp.sqrt(1 - m))
    v1, v2 = el.fig4_curves(0.5)
    assert _rel(v1, f1r) < 1e-15 and _rel(v2, f2r) < 1e-15


# --- hertz_factors, kinks -------------------------------------------------------------------------


def test_hertz_factors_fields_and_turn():
    lam = np.array([1e-6, 0.2, 0.7, 1.0])
    for hertz in ("exact", "paper"):
        hf = el.hertz_factors(lam, hertz)
        assert set(hf._fields) == {"e1", "f1", "f2", "f3", "f4", "K", "E"}
        turned = el.hertz_factors(1 / lam, hertz)
        for a, b in zip(hf, turned):
            np.testing.assert_array_equal(a, b)
        np.testing.assert_allclose(hf.f1, hf.E / (hf.K * hf.e1), rtol=1e-15)
    paper = el.hertz_factors(0.7, "paper")
    assert paper.e1 == 1.0 and abs(paper.f1 - 1) < 1e-7  # circle beyond the clip
    with pytest.raises(ValueError):
        el.hertz_factors(0.5, "bogus")


def test_kinks():
    assert el.kinks("exact") == (1.0,)
    assert el.kinks("paper") == (el.PAPER_LAMBDA_CLIP, 1.0)
    # paper: corner at the clip point. e1 has left slope 0.4777/(1 - 1.3211 λ)² = 6.77 and
    # right slope 0; f4 ≈ 1 - m/8 near the circle inherits it (left slope ≈ +6.77/4).
    # f1, f2 are flat to first order in m = e² at the circle, so their corner is weak
    # (slope ≈ -1.3e-3 from the polynomial error only) but still a kink.
    c, h = el.PAPER_LAMBDA_CLIP, 1e-7

    def slopes(field, hertz):
        f = lambda x: getattr(el.hertz_factors(x, hertz), field)  # noqa: E731
        return (f(c) - f(c - h)) / h, (f(c + h) - f(c)) / h

    left, right = slopes("e1", "paper")
    assert left == pytest.approx(0.4777 / (1 - 1.3211 * c) ** 2, rel=1e-5) and right == 0.0
    left, right = slopes("f4", "paper")
    assert left == pytest.approx(0.4777 / (1 - 1.3211 * c) ** 2 / 4, rel=1e-3) and right == 0.0
    left, right = slopes("f1", "paper")
    assert left != 0.0 and right == 0.0
    # the exact factors are smooth there
    for field in ("e1", "f1", "f2", "f4"):
        d1, d2 = slopes(field, "exact")
        assert d1 == pytest.approx(d2, rel=1e-4)


def test_input_validation():
    with pytest.raises(ValueError):
        el.elliptic_BD(1.5)
    with pytest.raises(ValueError):
        el.f1(-0.1)
    with pytest.raises(ValueError):
        el.e1_from_lambda(-1.0)
    with pytest.raises(ValueError):
        el.elliptic_KE(0.5, "bogus")
    with pytest.raises(ValueError):
        el.fig4_curves(1.0)
