"""Summit statistics (roughcontact.statistics.summits): without m22 the paper's closed forms
(17), (70), (71)-(73); with m22 Nayak's isotropic density and an independent Monte Carlo of the
six Gaussian variables; on a map the 8-neighbour summits against the expectation."""

import math

import numpy as np
import pytest

from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.statistics.summits import (SummitStatistics, gaussian_summit_statistics, map_summits,
                                             measure_summits)
from roughcontact.statistics.surface import SpectralMoments

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
ANISO = SpectralMoments(1.0, 0.5, 2.0, 1.0, 20.0)  # alpha1 = 4, alpha2 = 5


@pytest.mark.parametrize("m", [TABLE1, ANISO], ids=["table1", "alpha4-5"])
def test_without_m22_the_closed_forms(m):
    s = gaussian_summit_statistics(m)
    assert s.density == pytest.approx(m.summit_density, rel=1e-12)              # (17), E3
    assert s.mean_curvature == pytest.approx(m.mean_summit_curvature, rel=1e-12)  # (70)
    assert s.mean_height == pytest.approx(m.summit_mean_height, rel=1e-12)      # (73), E7
    assert s.height_std == pytest.approx(m.summit_height_std, rel=1e-12)        # (71)-(72), E6


def test_with_isotropic_m22_nayaks_density():
    """An elliptically stretched isotropic surface (alpha1 = alpha2, m22 = sqrt(m40 m04)/3):
    D = m4/(6 pi sqrt(3) m2) of the isotropic surface (Nayak 1971, eq. (32)), stretched:
    sqrt(m40 m04)/(6 pi sqrt(3) sqrt(m20 m02)), 2 pi/(3 sqrt 3) = 1.209 times (17)."""
    m = TABLE1
    s = gaussian_summit_statistics(m, math.sqrt(m.m40 * m.m04) / 3)
    nayak = math.sqrt(m.m40 * m.m04) / (6 * math.pi * math.sqrt(3) * math.sqrt(m.m20 * m.m02))
    assert s.density == pytest.approx(nayak, rel=1e-8)
    assert s.density / m.summit_density == pytest.approx(2 * math.pi / (3 * math.sqrt(3)), rel=1e-8)


def _monte_carlo(m, m22, n=2_000_000, seed=0):
    """Independent route: sample (xi1, xi4, xi5, xi6) with the covariance of Appendix A (m11 =
    m31 = m13 = 0) and weight each sample by det H on the maxima (Rice formula)."""
    cov = np.array([[m.m00, -m.m20, 0.0, -m.m02],
                    [-m.m20, m.m40, 0.0, m22],
                    [0.0, 0.0, m22, 0.0],
                    [-m.m02, m22, 0.0, m.m04]])
    x = np.random.default_rng(seed).multivariate_normal(np.zeros(4), cov, size=n)
    h, a, b, c = x.T
    det = a * c - b * b
    w = np.where((a < 0) & (c < 0) & (det > 0), det, 0.0)
    wt = w.sum()
    mean_h = (w * h).sum() / wt
    return {"density": w.mean() / (2 * math.pi * math.sqrt(m.m20 * m.m02)),
            "mean_curvature": (w * 0.5 * (np.abs(a) + np.abs(c))).sum() / wt,
            "mean_height": mean_h, "height_std": math.sqrt((w * (h - mean_h) ** 2).sum() / wt)}


@pytest.mark.parametrize("fraction", [0.0, 1 / 3, 0.6])
def test_with_m22_against_monte_carlo(fraction):
    m = ANISO
    m22 = fraction * math.sqrt(m.m40 * m.m04)
    s = gaussian_summit_statistics(m, m22).as_dict()
    mc = _monte_carlo(m, m22)
    for k, v in mc.items():
        assert s[k] == pytest.approx(v, rel=0.01), k  # 2e6 samples: ~0.2-0.4 % standard error


def test_bad_m22():
    with pytest.raises(ValueError, match="m22"):
        gaussian_summit_statistics(TABLE1, math.sqrt(TABLE1.m40 * TABLE1.m04))
    with pytest.raises(ValueError, match="m22"):
        gaussian_summit_statistics(TABLE1, -1e-9)
    with pytest.raises(TypeError):
        gaussian_summit_statistics({"m00": 1.0})


def test_map_summits_are_strict_8_neighbour_maxima():
    z = np.zeros((5, 5))
    z[2, 2] = 1.0
    z[0, 0] = 0.5  # a summit across the periodic edge
    mask = map_summits(z)
    assert mask[2, 2] and mask[0, 0] and mask.sum() == 2


def test_measured_summits_on_a_finely_sampled_map():
    """32 points per shortest wavelength: the map's summits approach the Gaussian expectation with
    the surface's m22 (not the model's, which has 1/1.21 of the density)."""
    m = TABLE1
    s = BandLimitedSurface.design(m, hurst=0.8, k_high=32)
    n = 1024
    stats = [measure_summits(s.heights(n, k), *s.spacing(n)) for k in range(3)]
    expected = gaussian_summit_statistics(m, s.grid_moments()["m22"])
    density = np.mean([x.density for x in stats])
    assert density == pytest.approx(expected.density, rel=0.1)
    assert abs(density / m.summit_density - 1.0) > 0.1
    assert np.mean([x.mean_curvature for x in stats]) == pytest.approx(expected.mean_curvature, rel=0.1)
    assert isinstance(stats[0], SummitStatistics) and stats[0].count > 200


def test_measure_summits_input():
    with pytest.raises(ValueError, match="2-d"):
        measure_summits(np.ones(10), 1.0, 1.0)
    with pytest.raises(ValueError, match="dx"):
        measure_summits(np.random.default_rng(0).normal(size=(8, 8)), 0.0, 1.0)
