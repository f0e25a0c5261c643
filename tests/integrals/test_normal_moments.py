"""The Gaussian moments J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt (ν = 0, 1/2, 1, 3/2) from the Chebyshev
tables (normal_moments.py, evaluated by production.gaussian_moments) against their slow twin,
mpmath's parabolic-cylinder form at 30 digits, over the whole a-range; closed forms; the
underflow to exact zero; and (mpmath tier) that regenerating the tables reproduces the data file.
"""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.special import ndtr

from roughcontact.integrals import normal_moments
from roughcontact.integrals.production import gaussian_moments, normal_moment

NU = ("0", "0.5", "1", "1.5")


def _mp_values(a_values):
    with mp.workdps(30):
        return [[normal_moments.mp_moment(nu, float(a)) for nu in NU] for a in a_values]


def _a_grid():
    """Random points over [−38.6, 60], every piece boundary and its neighbours, the tails."""
    rng = np.random.default_rng(20260423)
    edges = np.arange(-12.0, 13.0)
    near = np.concatenate([edges, np.nextafter(edges, -np.inf), np.nextafter(edges, np.inf)])
    return np.concatenate([rng.uniform(-38.6, 60.0, 160), near, [-38.55, -30.0, -20.0, 0.0, 1e-300, -1e-300,
                                                                   25.0, 1e3, 1e8]])


def test_tables_match_mpmath_everywhere():
    """≤ 1.5e-15 relative for every ν wherever J_ν is a normal double (measured: 7e-16)."""
    a = _a_grid()
    got = gaussian_moments(a)
    ref = _mp_values(a)
    worst = 0.0
    for i, ai in enumerate(a):
        for k in range(4):
            r = ref[i][k]
            if abs(r) < 1e-300:  # subnormal range: an absolute criterion
                assert abs(got[i, k] - float(r)) <= 1e-310, (ai, NU[k])
                continue
            err = float(abs(mp.mpf(got[i, k]) / r - 1))
            worst = max(worst, err)
            assert err < 1.5e-15, (ai, NU[k], err)
    assert worst > 0.0  # the comparison ran on real values


def test_closed_forms_where_they_do_not_cancel():
    """J_0 = Φ(a), J_1 = aΦ(a) + φ(a) (GW's F_0, F_1), where neither cancels (a ≥ −1)."""
    a = np.linspace(-1.0, 8.0, 37)
    J = gaussian_moments(a)
    phi = np.exp(-0.5 * a * a) / math.sqrt(2 * math.pi)
    np.testing.assert_allclose(J[:, 0], ndtr(a), rtol=2e-15)
    np.testing.assert_allclose(J[:, 2], a * ndtr(a) + phi, rtol=2e-15)


def test_positive_increasing_and_large_a_powers():
    a = np.linspace(-37.0, 40.0, 3001)  # J_ν ≥ 1e-300 (normal doubles)
    J = gaussian_moments(a)
    assert np.all(J > 0) and np.all(np.diff(J[:, 1:], axis=0) > 0)
    assert np.all(np.diff(J[:, 0], axis=0) >= -2.3e-16)  # J_0 = Φ(a) → 1: flat to 1 ulp
    big = np.array([1e4, 1e8])  # J_ν(a) = a^ν (1 + ν(ν−1)/(2a²) + O(a⁻⁴)) = E[(Z + a)^ν]
    nu = np.array([0.0, 0.5, 1.0, 1.5])
    expected = big[:, None] ** nu * (1.0 + nu * (nu - 1.0) / (2.0 * big[:, None] ** 2))
    np.testing.assert_allclose(gaussian_moments(big), expected, rtol=1e-15)


def test_deep_tail_underflows_to_exact_zero_not_nan():
    J = gaussian_moments([-38.7, -40.0, -1e3, -1e300])
    assert np.all(J == 0.0)
    J = gaussian_moments([-38.5])  # J < φ(a) ≈ 1e-322: a subnormal, never NaN
    assert np.all(np.isfinite(J)) and np.all(J >= 0) and np.all(J < 1e-320)


def test_normal_moment_columns_and_validation():
    a = np.array([-3.0, 0.0, 2.0])
    np.testing.assert_array_equal(normal_moment(a), gaussian_moments(a)[:, 1:])
    with pytest.raises(ValueError, match="finite"):
        normal_moment([0.0, np.nan])


@pytest.mark.mpmath
def test_regenerating_the_tables_reproduces_the_data_file():
    tab, worst = normal_moments.build_table()
    stored = normal_moments.table()
    np.testing.assert_allclose(tab, stored, rtol=0, atol=1e-16 * np.abs(stored).max())
    assert worst < 1e-17  # the largest dropped Chebyshev coefficient (relative to its piece)
