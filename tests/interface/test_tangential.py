"""Tests of roughcontact.interface.tangential: Mindlin's k_N/k_T of an elliptical contact, the corrected
eqs. (96)–(97) and Table 3 of Buczkowski & Kleiber (2009).

References are independent of the module (which uses ellipse.elliptic_BD, i.e. scipy's Carlson
R_D and the DLMF series):

* the printed Table 3 (config/paper_values.yaml, the digits as printed);
* closed forms: the circle (2-ν)/(2(1-ν)), ν = 0, the reflection k(r) + k(1/r) = 2 + ν/(1-ν);
* mpmath.quad of Mindlin's integrals: the centre displacement of the no-slip traction
  q ∝ (1 - x²/A² - y²/B²)^(-1/2) under Cerruti's kernel (one formula for both B < A and B > A);
* the corrected (96) with N(e) from (97), evaluated with mpmath.ellipk/ellipe (AGM);
* the logarithmic asymptotes of limits (ii), (iii).
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import yaml

from roughcontact.interface.tangential import NU_MAX, NU_MIN, kn_over_kt

PAPER_VALUES = Path(__file__).resolve().parents[2] / "config" / "paper_values.yaml"


# --- Table 3 -------------------------------------------------------------------------------


def _nu(text: str) -> float:
    num, _, den = text.partition("/")
    return float(num) / float(den) if den else float(num)


def _table3():
    """The printed Table 3 as {"caption", "rows": [[label, cell(ν = 0), cell(¼), cell(½)], ...]}
    and the ν of its columns (headed "nu = 0.0", "nu = 1/4", "nu = 1/2")."""
    table = yaml.safe_load(PAPER_VALUES.read_text())["table3"]
    columns = list(table["columns"])
    nus = [_nu(c.split("=")[1].strip()) for c in columns]
    rows = [[label, *(table["columns"][c]["kn_over_kt"][i] for c in columns)] for i, label in enumerate(table["rows"])]
    return {"caption": " ".join(table["caption"].split()), "rows": rows}, nus


def reading_decade(label: str) -> float:
    """The reading of Table 3's first column: "10.E-03" → B²/A² = 10⁻³ (the exponent only)."""
    return 10.0 ** int(label.split("E")[1])


def _cells(reading):
    data, nus = _table3()
    for row in data["rows"]:
        r = reading(row[0])
        for nu, printed in zip(nus, row[1:]):
            yield row[0], r, nu, printed


def test_table3_file_is_the_printed_table():
    data, nus = _table3()
    assert data["caption"] == "Table 3 Ratio of k_N/k_T of bodies with the same elastic constants"
    assert nus == [0.0, 0.25, 0.5]
    assert [row[0] for row in data["rows"]] == [
        "10.E-03", "10.E-02", "10.E-01", "10.E-00", "10.E+01", "10.E+02", "10.E+03"
    ]
    assert sum(len(row) - 1 for row in data["rows"]) == 21
    assert all(isinstance(c, str) for row in data["rows"] for c in row)


def test_table3_reading_decades_reproduces_all_21_cells():
    """Reading "10.E-0k" as B²/A² = 10^±k: every cell within 1e-5 relative and within one unit of
    the last printed digit (5 decimals; '1.0' and '1.5' are exact)."""
    worst = 0.0  # (≈ 5.0e-6, at 10.E-01, ν = 1/2: the printed 1.36502 vs 1.3650268)
    n = 0
    for label, r, nu, printed in _cells(reading_decade):
        value = kn_over_kt(r, nu)
        p = float(printed)
        rel = abs(value - p) / p
        worst = max(worst, rel)
        n += 1
        assert rel < 1e-5, (label, nu, value, printed)
        decimals = len(printed.split(".")[1])
        ulp = 10.0**-max(decimals, 5)
        assert abs(value - p) <= ulp, (label, nu, value, printed)
    assert n == 21
    assert worst < 1e-5


@pytest.mark.parametrize(
    "reading",
    [
        pytest.param(lambda s: float(s), id="literal 10*10^k"),  # float("10.E-03") = 0.01
        pytest.param(lambda s: reading_decade(s) ** 2, id="B/A = 10^k"),
        pytest.param(lambda s: 1.0 / reading_decade(s), id="A²/B² = 10^k"),
    ],
)
def test_table3_other_readings_fail(reading):
    worst = max(
        abs(kn_over_kt(r, nu) - float(p)) / float(p) for _, r, nu, p in _cells(reading)
    )
    assert worst > 1e-2


# --- independent references ------------------------------------------------------------------


def mindlin_quad_ratio(r: float, dps: int = 30) -> mp.mpf:
    """X/K by mpmath.quad of Mindlin's integrals at the centre of the contact ellipse.

    With the no-slip traction q = q0 (1 - x²/A² - y²/B²)^(-1/2) and polar coordinates (s, φ) at
    the centre, ∫₀^{s_max} q ds = q0 (π/2) s_max(φ), s_max ∝ 1/sqrt(r cos²φ + sin²φ),
    r = B²/A². Cerruti's kernel (1-ν)/s + ν y²/s³ (force along y, i.e. along B) then gives
    k_N/k_T = 1 + ν/(1-ν) · ∫ sin²φ s_max dφ / ∫ s_max dφ. With t = tan φ = e^u:
    ∫₀^{π/2} s_max dφ ∝ ∫ t du/(sqrt(1+t²) sqrt(r+t²)), and sin²φ = t²/(1+t²).
    One formula for B < A and B > A (no branch, no elliptic-integral convention).
    """
    with mp.workdps(dps):
        rr = mp.mpf(r)
        u0 = mp.log(rr) / 2  # t = sqrt(r): where the integrands turn over
        lo, hi = min(u0, 0), max(u0, 0)
        n = max(1, int(abs(u0) / 8))  # split the logarithmic plateau into pieces of ≤ 8 in u
        pts = [-mp.inf] + [lo + (hi - lo) * i / n for i in range(n + 1)] + [mp.inf]
        if u0 == 0:
            pts = [-mp.inf, 0, mp.inf]

        scale = mp.sqrt(max(rr, 1))  # O(1) integrands: mp.quad's tolerance is absolute

        def den(u):
            t = mp.exp(u)
            return scale * t / (mp.sqrt(1 + t * t) * mp.sqrt(rr + t * t))

        def num(u):
            t = mp.exp(u)
            return den(u) * t * t / (1 + t * t)

        return mp.quad(num, pts) / mp.quad(den, pts)


def corrected_eq96(r: float, nu: float) -> mp.mpf:
    """The corrected (96) with N from (97), mpmath K, E (parameter m = modulus²):

    k_N/k_T = π(2-ν)/(4(1-ν)) · (1/K) · [2K/π ∓ ν/(2π²(2-ν)) · N/e],
    N(e) = 4π[(2/e - e)K - (2/e)E],  "-" with e² = 1 - B²/A² for B < A,
    "+" with k1² = 1 - A²/B² (N1, K1 of k1) for B > A."""
    dps = 40 + int(abs(math.log10(r)))
    with mp.workdps(dps):
        rr = mp.mpf(r)
        m = 1 - rr if rr <= 1 else 1 - 1 / rr
        sign = -1 if rr <= 1 else 1
        n = mp.mpf(nu)
        K = mp.ellipk(m)
        pref = mp.pi * (2 - n) / (4 * (1 - n))
        if m == 0:
            return pref / K * (2 * K / mp.pi)
        e = mp.sqrt(m)
        N = 4 * mp.pi * ((2 / e - e) * K - (2 / e) * mp.ellipe(m))  # eq. (97)
        return pref / K * (2 * K / mp.pi + sign * n / (2 * mp.pi**2 * (2 - n)) * N / e)


def printed_eq96(r: float, nu: float) -> float:
    """(96) exactly as printed: prefactor · (1/K)(2K/π) - ν/(2π²(2-ν)) · N/e in both branches."""
    with mp.workdps(40):
        rr = mp.mpf(r)
        m = 1 - rr if rr <= 1 else 1 - 1 / rr
        n = mp.mpf(nu)
        K, E = mp.ellipk(m), mp.ellipe(m)
        e = mp.sqrt(m)
        N = 4 * mp.pi * ((2 / e - e) * K - (2 / e) * E)
        pref = mp.pi * (2 - n) / (4 * (1 - n))
        return float(pref / K * (2 * K / mp.pi) - n / (2 * mp.pi**2 * (2 - n)) * N / e)


R_POINTS = [1e-300, 1e-30, 1e-6, 1e-3, 0.1, 0.5, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 2.0, 10.0, 1e3,
            1e6, 1e30, 1e300]


@pytest.mark.mpmath
@pytest.mark.parametrize("r", R_POINTS)
def test_matches_mpmath_quad_of_mindlin_integrals(r):
    ratio = mindlin_quad_ratio(r)
    for nu in (0.25, 0.5, -0.5):
        expected = float(1 + mp.mpf(nu) / (1 - mp.mpf(nu)) * ratio)
        assert kn_over_kt(r, nu) == pytest.approx(expected, rel=2e-15, abs=0), nu


@pytest.mark.mpmath
@pytest.mark.parametrize("r", [x for x in R_POINTS if x != 1.0])
@pytest.mark.parametrize("nu", [0.25, 0.5, 0.3])
def test_matches_corrected_eq96_eq97(r, nu):
    assert kn_over_kt(r, nu) == pytest.approx(float(corrected_eq96(r, nu)), rel=2e-15, abs=0)


def test_printed_eq96_does_not_reproduce_table3():
    """Evidence for the erratum: the printed (96) misses Table 3 in both branches (it is only
    right at B = A where N/e → 0), while the corrected form reproduces it."""
    data, nus = _table3()
    nu = 0.25
    misses = {}
    for row in data["rows"]:
        r = reading_decade(row[0])
        if r == 1.0:
            continue
        misses[row[0]] = printed_eq96(r, nu) - float(row[2])
    assert all(abs(d) > 0.01 for d in misses.values()), misses
    # e.g. B²/A² = 1e-3: printed (96) gives ≈ 0.908 against the tabulated 1.06874
    assert printed_eq96(1e-3, nu) == pytest.approx(0.908, abs=2e-3)
    # and the printed B > A branch falls below the circle value instead of rising to 1/(1-ν)
    assert printed_eq96(1e3, nu) < (2 - nu) / (2 * (1 - nu))


# --- limiting cases (i)–(iv) of section 8 ----------------------------------------------------

R_SWEEP = np.logspace(-300, 300, 61)


def test_limit_i_nu_zero_is_one():
    np.testing.assert_array_equal(kn_over_kt(R_SWEEP, 0.0), np.ones_like(R_SWEEP))


def _L(r):
    """L = ln(4/e1), e1 = min(B/A, A/B) = r^{±1/2}."""
    return math.log(4.0) + 0.5 * abs(math.log(r))


@pytest.mark.parametrize("nu", [0.25, 0.5, -0.5])
def test_limit_ii_b_over_a_to_zero_is_logarithmic(nu):
    c = nu / (1 - nu)
    # k_N/k_T = 1 + c/L (1 + O(e1² L)), e1² = r: the asymptote to rel ≤ 10 r L
    for r in (1e-6, 1e-10, 1e-14, 1e-20, 1e-100, 1e-300):
        L = _L(r)
        k = kn_over_kt(r, nu)
        # (k - 1 is a difference of doubles: allow 4 ulp of k absolute)
        assert (k - 1) == pytest.approx(c / L, rel=10 * r * L, abs=1e-15), r
    # it tends to 1 only logarithmically: still ≈ 1.00096 at r = 1e-300 for ν = 1/4
    if nu == 0.25:
        assert kn_over_kt(1e-300, nu) == pytest.approx(1.000961240685, abs=1e-12)
        assert kn_over_kt(1e-300, nu) - 1 > 9.6e-4
    # monotone approach to 1 as r decreases
    small = R_SWEEP[R_SWEEP <= 1]
    k = kn_over_kt(small, nu)
    d = np.diff(k)
    assert np.all(d > 0) if nu > 0 else np.all(d < 0)
    assert abs(k[0] - 1) < abs(k[-1] - 1)


@pytest.mark.parametrize("nu", [0.25, 0.5, -0.5])
def test_limit_iii_b_over_a_to_infinity_is_logarithmic(nu):
    c = nu / (1 - nu)
    for r in (1e6, 1e10, 1e14, 1e20, 1e100, 1e300):
        L = _L(r)
        k = kn_over_kt(r, nu)
        # k_N/k_T = 1/(1-ν) - c/L (1 + O(L/r))
        assert (1 / (1 - nu) - k) == pytest.approx(c / L, rel=10 * L / r, abs=1e-15), r
    big = R_SWEEP[R_SWEEP >= 1]
    k = kn_over_kt(big, nu)
    assert np.all(np.diff(k) > 0) if nu > 0 else np.all(np.diff(k) < 0)
    if nu == 0.25:  # ≈ 1.33238 at 1e300, still 1e-3 below 1/(1-ν) = 4/3
        assert 4 / 3 - kn_over_kt(1e300, nu) == pytest.approx(1 / (3 * _L(1e300)), abs=1e-15)


@pytest.mark.parametrize("nu", [-0.9, -0.25, 0.0, 0.1, 0.25, 1 / 3, 0.45, 0.5])
def test_limit_iv_circle_is_classical_mindlin(nu):
    expected = (2 - nu) / (2 * (1 - nu))  # Mindlin (1949), circular contact
    assert kn_over_kt(1.0, nu) == pytest.approx(expected, rel=1e-15)
    # the two branches (B < A: B(e)/K, B > A: D(k1)/K) meet continuously at B = A
    for d in (1e-15, 1e-12, 1e-9, 1e-6):
        lo, hi = kn_over_kt(1.0 - d, nu), kn_over_kt(1.0 + d, nu)
        # B ≈ π/4 + πm/32, K ≈ π/2 + πm/8 ⇒ B/K ≈ 1/2 - (1-r)/16: dk/dr = ν/(1-ν)/16 at r = 1
        assert abs(hi - lo) <= abs(nu / (1 - nu)) * d / 8 * 1.01 + 6e-16
        assert abs(0.5 * (hi + lo) - expected) <= 1e-15 + d * d


@pytest.mark.parametrize("nu", [-0.5, 0.25, 0.5])
def test_reflection_identity(nu):
    """B(e) + D(e) = K(e): k(r) + k(1/r) = 2 + ν/(1-ν) (the two branches are mirror images)."""
    r = np.logspace(-300, 300, 121)
    np.testing.assert_allclose(
        kn_over_kt(r, nu) + kn_over_kt(1 / r, nu), 2 + nu / (1 - nu), rtol=1e-15, atol=0
    )


def test_range_between_one_and_one_over_one_minus_nu():
    """Section 8: over 0 < ν < 0.5, k_N > k_T but never more than twice; in fact
    1 < k_N/k_T < 1/(1-ν) ≤ 2, increasing with B²/A²."""
    for nu in (0.1, 0.25, 0.5):
        k = kn_over_kt(R_SWEEP, nu)
        assert np.all(k > 1) and np.all(k < 1 / (1 - nu)) and np.all(k <= 2)
        assert np.all(np.diff(k) > 0)


# --- API: vectorisation, extremes, validation --------------------------------------------------


def test_scalar_in_float_out_and_broadcasting():
    assert isinstance(kn_over_kt(0.1, 0.25), float)
    r = np.array([[1e-3], [1.0], [1e3]])
    nu = np.array([0.0, 0.25, 0.5])
    out = kn_over_kt(r, nu)
    assert out.shape == (3, 3)
    for i in range(3):
        for j in range(3):
            assert out[i, j] == kn_over_kt(float(r[i, 0]), float(nu[j]))
    assert kn_over_kt([0.1, 10.0], 0.25).shape == (2,)


def test_extreme_ratios_finite():
    r = np.array([5e-324, 1e-308, 1e-300, 1e300, 1e308, 1.7976931348623157e308])
    k = kn_over_kt(r, 0.25)
    assert np.all(np.isfinite(k))
    assert np.all((k > 1) & (k < 4 / 3))


def test_nu_range_constants():
    assert (NU_MIN, NU_MAX) == (-1.0, 0.5)
    assert kn_over_kt(1.0, 0.5) == pytest.approx(1.5, rel=1e-15)  # incompressible: Table 3
    assert kn_over_kt(1.0, -0.999) < 1  # auxetic: k_T > k_N


BAD = {
    "r zero": (0.0, 0.25, "b2_over_a2"),
    "r negative": (-1.0, 0.25, "b2_over_a2"),
    "r nan": (float("nan"), 0.25, "b2_over_a2"),
    "r inf": (float("inf"), 0.25, "b2_over_a2"),
    "r in array": ([1.0, 0.0], 0.25, "b2_over_a2"),
    "nu above 1/2": (1.0, 0.5000001, "nu"),
    "nu one": (1.0, 1.0, "nu"),
    "nu -1": (1.0, -1.0, "nu"),
    "nu nan": (1.0, float("nan"), "nu"),
    "non-numeric": ("wide", 0.25, "real"),
    "shapes": ([1.0, 2.0], [0.1, 0.2, 0.3], "broadcast"),
}


@pytest.mark.parametrize("r,nu,word", BAD.values(), ids=BAD.keys())
def test_bad_input_raises_value_error(r, nu, word):
    with pytest.raises(ValueError, match=word):
        kn_over_kt(r, nu)
