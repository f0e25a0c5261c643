"""Surfaces with exactly five prescribed moments (roughcontact.bem.surfaces): every realisation,
every grid, to round-off; the same surface on every grid; bad input refused."""

import math

import numpy as np
import pytest

from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.statistics.measure import measure_heights
from roughcontact.statistics.surface import SpectralMoments

MOMENTS = ("m00", "m20", "m02", "m40", "m04")


HURST, K_HIGH = 0.8, 32  # config/config.yaml, bem (tests/bem/conftest.py reads it)


def design(m, **kw):
    return BandLimitedSurface.design(m, hurst=HURST, k_high=kw.pop("k_high", K_HIGH), **kw)


def test_the_config_uses_these_design_parameters(bem_cfg):
    assert (bem_cfg["hurst"], bem_cfg["k_high"]) == (HURST, K_HIGH)


def test_config_families_are_the_papers_shapes(families):
    """table1 is Table 1's surface; alpha3 has Table 2's alpha = 3 and m02/m20 = 81 with Table 1's
    m00 and m02 (issue 21)."""
    t1, a3 = families["table1"], families["alpha3"]
    assert t1.as_dict() == {"m00": 0.0625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}
    assert a3.m00 == t1.m00 and a3.m02 == t1.m02
    assert a3.alpha1 == pytest.approx(3.0, rel=1e-14) and a3.alpha2 == pytest.approx(3.0, rel=1e-14)
    assert a3.m02 / a3.m20 == pytest.approx(81.0, rel=1e-14)


@pytest.mark.parametrize("seed", [0, 1, 7])
def test_every_realisation_has_the_five_moments_to_round_off(family, seed):
    """Measured on the map (periodogram, no window, no detrending) = the targets, ~1e-15."""
    m = family[1]
    s = design(m)
    n = 128
    z = s.heights(n, seed)
    measured = measure_heights(z, *s.spacing(n), estimator="spectral", window="none", detrend="none",
                               lay_angle_deg=0.0).lay
    for k in MOMENTS:
        assert measured[k] == pytest.approx(getattr(m, k), rel=1e-12), k
    assert abs(measured["m11"]) < 1e-12 * math.sqrt(m.m20 * m.m02)
    assert abs(z.mean()) < 1e-12 * math.sqrt(m.m00)


def test_grid_moments_are_the_targets_and_m22_is_the_stretched_isotropic_one(family):
    m = family[1]
    g = design(m).grid_moments()
    for k in MOMENTS:
        assert g[k] == pytest.approx(getattr(m, k), rel=1e-13), k
    assert abs(g["m11"]) < 1e-14 * math.sqrt(m.m20 * m.m02)  # the half-plane sum cancels in pairs
    # isotropic in the lattice: m22 = sqrt(m40 m04)/3 up to the lattice's anisotropy (Nayak 1971)
    assert g["m22"] / math.sqrt(m.m40 * m.m04) == pytest.approx(1.0 / 3.0, rel=2e-3)


def test_the_same_surface_on_every_grid(family):
    """A trigonometric polynomial sampled at n and 2n points: the finer grid's every other point
    is the coarser grid's map."""
    m = family[1]
    s = design(m)
    z1, z2 = s.heights(128, 3), s.heights(256, 3)
    np.testing.assert_allclose(z2[::2, ::2], z1, rtol=0, atol=1e-13 * np.abs(z1).max())
    assert s.pixels_per_shortest_wavelength(256) == 256 / K_HIGH
    dx, dy = s.spacing(256)
    assert dx / dy == pytest.approx(math.sqrt(m.m02 / m.m20), rel=2e-3)  # the stretch: pixels follow the lay


def test_seeds_give_different_phases(families):
    s = design(families["table1"])
    assert not np.allclose(s.heights(96, 0), s.heights(96, 1))
    np.testing.assert_array_equal(s.heights(96, 5), s.heights(96, 5))


def test_heights_are_gaussian_enough_over_seeds(families):
    """Random phases of many modes: the pooled heights' skewness and excess kurtosis are small."""
    s = design(families["alpha3"])
    z = np.concatenate([s.heights(128, k).ravel() for k in range(6)]) / math.sqrt(s.moments.m00)
    assert abs(np.mean(z**3)) < 0.1
    assert abs(np.mean(z**4) - 3.0) < 0.3


@pytest.mark.parametrize("kwargs, message", [
    ({"hurst": 1.2}, "hurst"),
    ({"hurst": 0.0}, "hurst"),
    ({"k_high": 3}, "k_high"),
])
def test_bad_design_input(kwargs, message, families):
    with pytest.raises(ValueError, match=message):
        BandLimitedSurface.design(families["table1"], **kwargs)


def test_unequal_bandwidths_are_refused():
    m = SpectralMoments(1.0, 0.5, 2.0, 1.0, 20.0)  # alpha1 = 4, alpha2 = 5
    with pytest.raises(ValueError, match="alpha1 = alpha2"):
        BandLimitedSurface.design(m)


def test_unreachable_alpha_is_refused():
    m = SpectralMoments(1.0, 1.0, 1.0, 500.0, 500.0)  # alpha = 500 > what k_high = 8 gives
    with pytest.raises(ValueError, match="outside"):
        BandLimitedSurface.design(m, k_high=8)


@pytest.mark.parametrize("n, seed, message", [(32, 0, "n must"), (128, -1, "seed"), (128, 1.5, "seed"),
                                              (128.0, 0, "n must")])
def test_bad_grid_or_seed(n, seed, message, families):
    with pytest.raises(ValueError, match=message):
        design(families["table1"]).heights(n, seed)
