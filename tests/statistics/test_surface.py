"""SpectralMoments: validation, the summit pdf (18), D_sum (16)–(17) and the summit statistics
(70)–(73), checked by direct integration over (ω1, ω4, ω6) — not through the polar form the
integrators use."""

import math

import mpmath as mp
import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.statistics.surface import ProfileDensities

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
TABLE2 = SpectralMoments(3.0, 1.0, 81.0, 1.0, 6561.0)
# α1 ≠ α2: the case that exposes the swapped cross terms of the printed (15)
UNEQUAL = SpectralMoments(1.0, 0.5, 2.0, 1.0, 20.0)


# --------------------------------------------------------------------------------------
# a Cartesian tensor Gauss–Legendre rule with 30-digit mpmath nodes
# --------------------------------------------------------------------------------------
def _gl(n):
    """n-point Gauss–Legendre nodes/weights on [−1, 1] from mpmath at 30 digits
    (mpmath's rule of degree d has 3·2^(d−1) points: n ∈ {48, 96, 192})."""
    from mpmath.calculus.quadrature import GaussLegendre

    degree = {48: 5, 96: 6, 192: 7}[n]
    mp.mp.dps = 30
    nodes = GaussLegendre(mp.mp).calc_nodes(degree, mp.mp.prec)
    x = np.array([float(xi) for xi, _ in nodes])
    w = np.array([float(wi) for _, wi in nodes])
    return x, w


_GL_CACHE = {}


def _rule(n, a, b):
    if n not in _GL_CACHE:
        _GL_CACHE[n] = _gl(n)
    x, w = _GL_CACHE[n]
    return 0.5 * (b - a) * x + 0.5 * (a + b), 0.5 * (b - a) * w


def summit_expectation(surface, fn, n=48, width=9.0):
    """∫ fn · p_sum over ω1 ∈ ℝ, ω4, ω6 > 0 by a tensor rule; ω1 is sheared to
    z = ω1 − √β1 ω4 − √β2 ω6 (Jacobian 1) so that its window is [−width, width]."""
    mu = surface.mu
    w4, a4 = _rule(n, 0.0, width / math.sqrt(mu))
    w6, a6 = _rule(n, 0.0, width / math.sqrt(mu))
    z, az = _rule(n, -width, width)
    W4, W6, Z = np.meshgrid(w4, w6, z, indexing="ij")
    W1 = Z + math.sqrt(surface.beta1) * W4 + math.sqrt(surface.beta2) * W6
    weight = a4[:, None, None] * a6[None, :, None] * az[None, None, :]
    return float(np.sum(weight * fn(W1, W4, W6) * surface.summit_pdf(W1, W4, W6)))


# --------------------------------------------------------------------------------------
# validation
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "moments, fragment",
    [
        ((0.0, 1, 1, 1, 1), "m00 must be positive"),
        ((1, -1, 1, 1, 1), "m20 must be positive"),
        ((1, 1, float("nan"), 1, 1), "m02 must be finite"),
        ((1, 1, 1, float("inf"), 1), "m40 must be finite"),
        ((1, 1, 1, 1, "x"), "m04 must be a real number"),
        ((1, 1, 1, 1, 1), "mu = 1 - 1/alpha1 - 1/alpha2 > 0"),  # α1 = α2 = 1
        ((1, 1, 1, 2, 2), "alpha1 = m00*m40/m20^2 = 2"),  # μ = 0 exactly
    ],
)
def test_invalid_moments_raise_naming_the_condition(moments, fragment):
    with pytest.raises(ValueError, match=None) as err:
        SpectralMoments(*moments)
    assert fragment in str(err.value)


def test_bandwidth_parameters_closed_forms():
    s = TABLE2
    assert s.alpha1 == pytest.approx(3.0) and s.alpha2 == pytest.approx(3.0)
    assert s.mu == pytest.approx(1.0 / 3.0)
    assert TABLE1.alpha1 == pytest.approx(0.0625 * 1.04e-6 / 6.4e-9)


def test_summit_density_per_mm2_table1():
    # docs/independent-studies.md: 1041 summits/mm² for Table 1's surface (lengths in µm → ×1e6 per mm²)
    assert TABLE1.summit_density * 1e6 == pytest.approx(1041.3, abs=0.05)


# --------------------------------------------------------------------------------------
# the summit pdf and D_sum, by Cartesian integration
# --------------------------------------------------------------------------------------
@pytest.mark.mpmath
@pytest.mark.parametrize("surface", [TABLE1, TABLE2, UNEQUAL], ids=["table1", "table2", "a1!=a2"])
def test_summit_pdf_integrates_to_one(surface):
    total = summit_expectation(surface, lambda w1, w4, w6: 1.0)
    assert abs(total - 1.0) <= 1e-12


@pytest.mark.mpmath
def test_pdf_quadrature_has_converged():
    # the same integral with a finer rule and a wider window changes by < 1e-14
    a = summit_expectation(UNEQUAL, lambda w1, w4, w6: w1**2, n=48)
    b = summit_expectation(UNEQUAL, lambda w1, w4, w6: w1**2, n=96, width=10.0)
    assert abs(a - b) <= 1e-14 * abs(b)


def _printed_14(surface, w1, w4, w6, pairing="corrected"):
    """(14) with its printed prefactor; X with the corrected or the printed pairing of (15)."""
    mu, b1, b2 = surface.mu, surface.beta1, surface.beta2
    if pairing == "corrected":
        cross = -2 * math.sqrt(b1) * w1 * w4 - 2 * math.sqrt(b2) * w1 * w6
    else:  # as printed: √β1 with ω1ω6, √β2 with ω1ω4
        cross = -2 * math.sqrt(b1) * w1 * w6 - 2 * math.sqrt(b2) * w1 * w4
    X = w1**2 + (1 - b2) * w4**2 + (1 - b1) * w6**2 + cross + 2 * math.sqrt(b1 * b2) * w4 * w6
    pref = mu**2 / (2 * math.pi) ** 2.5 * math.sqrt(
        surface.m04 * surface.m40 / (surface.m02 * surface.m20)
    )
    return pref * np.abs(w4 * w6) * np.exp(-0.5 * X)


def _grid_integral(fn, lo1, hi1, lo4, hi4, lo6, hi6, n=96):
    x1, a1 = _rule(n, lo1, hi1)
    x4, a4 = _rule(n, lo4, hi4)
    x6, a6 = _rule(n, lo6, hi6)
    W1, W4, W6 = np.meshgrid(x1, x4, x6, indexing="ij")
    return float(np.sum(a1[:, None, None] * a4[None, :, None] * a6[None, None, :] * fn(W1, W4, W6)))


@pytest.mark.mpmath
@pytest.mark.parametrize("surface", [TABLE2, UNEQUAL], ids=["table2", "a1!=a2"])
def test_summit_density_17_equals_integral_16(surface):
    """(16) with the corrected limits (ω1 ∈ ℝ, ω4, ω6 > 0) gives (17) with exponent 1/2;
    the printed limits (ω1 > 0, ω4, ω6 ∈ ℝ) give exactly 2·D_sum (errata E2, E3)."""
    big = 12.0 / math.sqrt(surface.mu)
    f = lambda w1, w4, w6: _printed_14(surface, w1, w4, w6)  # noqa: E731
    corrected = sum(
        _grid_integral(f, lo, hi, 0, big, 0, big) for lo, hi in [(-14, 0), (0, 8), (8, 30)]
    )
    assert corrected == pytest.approx(surface.summit_density, rel=1e-10)
    printed_limits = sum(
        _grid_integral(f, lo, hi, a4, b4, a6, b6)
        for lo, hi in [(0, 8), (8, 30)]
        for a4, b4 in [(-big, 0), (0, big)]  # split at the kink of |ω4 ω6|
        for a6, b6 in [(-big, 0), (0, big)]
    )
    # printed limits: 2·D_sum exactly (the ω4, ω6 < 0 quadrant mirrors ω1 → −ω1)
    assert printed_limits == pytest.approx(2.0 * surface.summit_density, rel=1e-8)
    # the printed exponent 2 in (17) is not the integral
    printed_17 = (surface.m40 * surface.m04 / (surface.m20 * surface.m02)) ** 2 / (2 * math.pi) ** 2
    assert abs(printed_17 / corrected - 1) > 0.5


@pytest.mark.mpmath
def test_printed_pairing_of_15_is_wrong_when_alphas_differ():
    """With α1 ≠ α2 the printed cross terms of (15) give a different (wrong) density: its
    mean summit height differs from the closed form (73) (errata E1)."""
    s = UNEQUAL
    big = 12.0 / math.sqrt(s.mu)
    scale = math.sqrt(s.m00 * s.mu)

    def mean_height(pairing):
        f = lambda w1, w4, w6: _printed_14(s, w1, w4, w6, pairing)  # noqa: E731
        g = lambda w1, w4, w6: w1 * scale * _printed_14(s, w1, w4, w6, pairing)  # noqa: E731
        spans = [(-14, 0), (0, 8), (8, 30)]
        num = sum(_grid_integral(g, lo, hi, 0, big, 0, big) for lo, hi in spans)
        den = sum(_grid_integral(f, lo, hi, 0, big, 0, big) for lo, hi in spans)
        return num / den

    assert mean_height("corrected") == pytest.approx(s.summit_mean_height, rel=1e-10)
    # measured: the printed pairing moves δ by 0.57 % here, 10⁷ times the quadrature error
    assert abs(mean_height("printed") / s.summit_mean_height - 1) > 1e-3


def test_printed_18_prefactor_is_spurious():
    """(18) as printed carries (m04 m40/(m02 m20))^{3/2}: its integral is that factor, e.g.
    6.95e-5 for Table 1 and 729 for Table 2, instead of 1 (errata E4)."""
    for surface, expected in [(TABLE1, 6.95e-5), (TABLE2, 729.0)]:
        factor = (surface.m04 * surface.m40 / (surface.m02 * surface.m20)) ** 1.5
        assert factor == pytest.approx(expected, rel=2e-3)


# --------------------------------------------------------------------------------------
# summit statistics (70)–(73) by integration of p_sum
# --------------------------------------------------------------------------------------
@pytest.mark.mpmath
@pytest.mark.parametrize("surface", [TABLE1, UNEQUAL], ids=["table1", "a1!=a2"])
def test_summit_statistics_match_their_integrals(surface):
    sig = math.sqrt(surface.m00 * surface.mu)
    mean = summit_expectation(surface, lambda w1, w4, w6: sig * w1)
    var = summit_expectation(surface, lambda w1, w4, w6: (sig * w1 - mean) ** 2)
    kappa = summit_expectation(
        surface,
        lambda w1, w4, w6: 0.5 * math.sqrt(surface.mu)
        * (w4 * math.sqrt(surface.m40) + w6 * math.sqrt(surface.m04)),
    )
    assert mean == pytest.approx(surface.summit_mean_height, rel=1e-12)  # (73) corrected
    assert math.sqrt(var) == pytest.approx(surface.summit_height_std, rel=1e-12)  # (71)-(72)
    assert kappa == pytest.approx(surface.mean_summit_curvature, rel=1e-12)  # (70)


def test_printed_71_to_73_are_dimensionally_wrong():
    """(72) as printed, c = (2 − π/2)(β1 + β2) m00, and (73) with exponent 2 scale wrongly
    with m00: doubling all lengths must multiply σ by 2, δ by 2 (errata E6, E7)."""
    s, k = TABLE1, 2.0
    scaled = SpectralMoments(s.m00 * k**2, s.m20, s.m02, s.m40 / k**2, s.m04 / k**2)
    assert scaled.summit_height_std == pytest.approx(k * s.summit_height_std)
    assert scaled.summit_mean_height == pytest.approx(k * s.summit_mean_height)

    def printed_sigma(x):
        return math.sqrt((2 - math.pi / 2) * (x.beta1 + x.beta2) * x.m00 * x.m00)

    def printed_delta(x):
        return (x.m00 * math.pi / 2) ** 2 * (math.sqrt(x.beta1) + math.sqrt(x.beta2))

    assert printed_sigma(scaled) / printed_sigma(s) == pytest.approx(k**2)
    assert printed_delta(scaled) / printed_delta(s) == pytest.approx(k**4)


# --------------------------------------------------------------------------------------
# Nayak's profile densities (12)
# --------------------------------------------------------------------------------------
def test_profile_densities_round_trip_and_one_ninth_example():
    d = TABLE2.profile_densities()
    back = SpectralMoments.from_profile_densities(TABLE2.m00, d)
    for name in ("m00", "m20", "m02", "m40", "m04"):
        assert getattr(back, name) == pytest.approx(getattr(TABLE2, name), rel=1e-14)
    # the paper's example after (12): α1 = α2 = 3, m04/m40 = 9⁴ → one ninth along the grain
    assert d.zero_crossings_x / d.zero_crossings_y == pytest.approx(1 / 9)
    assert d.extrema_x / d.extrema_y == pytest.approx(1 / 9)
    # the printed (m40/m00)^{1/2}/π would give 1/81 for the extrema: contradicts the example
    printed = math.sqrt(TABLE2.m40 / TABLE2.m00) / math.sqrt(TABLE2.m04 / TABLE2.m00)
    assert printed == pytest.approx(1 / 81)


def test_profile_densities_are_rice_formulas():
    # Rice: zero crossings per unit length of a Gaussian profile = (1/π)√(m2/m0)
    d = UNEQUAL.profile_densities()
    assert isinstance(d, ProfileDensities)
    assert d.zero_crossings_x == pytest.approx(math.sqrt(0.5) / math.pi)
    assert d.extrema_y == pytest.approx(math.sqrt(20.0 / 2.0) / math.pi)


def test_separation_conventions():
    s = TABLE2
    assert float(s.l_from_s(1.0)) == pytest.approx(math.sqrt(3.0))
    assert float(s.s_from_h(math.sqrt(3.0))) == pytest.approx(1.0)


@pytest.mark.parametrize("value", ["1e-300", "1e300"])
def test_moments_that_under_or_overflow_are_refused(value):
    """Issue #12: all moments 1e-300 ended in ZeroDivisionError (m20² underflows), 1e300 in
    OverflowError: valid doubles whose derived statistics are not; ValueError names it."""
    with pytest.raises(ValueError, match="under- or overflow in double precision"):
        SpectralMoments(*(float(value),) * 5)
    # Table 1's surface with m00 in a unit 1e-160 times smaller: m00 m40 underflows
    with pytest.raises(ValueError, match="alpha1"):
        SpectralMoments(0.0625e-160, 8e-5, 8e-4, 1.04e-6 * 1e-160, 1.04e-4)
