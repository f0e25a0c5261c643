"""The synthetic surface generator: the moments measured on generated maps recover the prescribed
ones within their statistical scatter, over seeds, resolutions and lay angles."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.synthetic import (
    _density_1d,
    grid_moments,
    lay_frame_spectrum,
    synthetic_surface,
)

#: (moments, shape (ny, nx), dx, dy): a light-tailed (alpha1 = 2) and a heavy-tailed (alpha1 = 10)
#: spectrum, each on grids that resolve it (checked below), at two resolutions
CASES = [
    (SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0), (128, 128), 0.4, 0.2),
    (SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0), (256, 256), 0.4, 0.2),
    (SpectralMoments(1.0, 1.0, 9.0, 10.0, 243.0), (512, 512), 0.2, 0.1),
    (SpectralMoments(0.25, 0.04, 1.0, 0.02, 6.0), (256, 512), 0.5, 0.1),
]
NAMES = ("m00", "m20", "m02", "m40", "m04", "m22")
POWERS = {"m00": (0, 0), "m20": (2, 0), "m02": (0, 2), "m40": (4, 0), "m04": (0, 4), "m22": (2, 2)}


def _lay_wavenumbers(shape, dx, dy, angle_deg):
    qx = 2 * np.pi * np.fft.fftfreq(shape[1], d=dx)[np.newaxis, :]
    qy = 2 * np.pi * np.fft.fftfreq(shape[0], d=dy)[:, np.newaxis]
    t = math.radians(angle_deg)
    return qx, qy, math.cos(t) * qx + math.sin(t) * qy, -math.sin(t) * qx + math.cos(t) * qy


def _measured(z, dx, dy, angle_deg):
    """Periodogram moments in the lay frame: by Parseval, Var of the spectral derivatives."""
    _, _, qa, qc = _lay_wavenumbers(z.shape, dx, dy, angle_deg)
    power = np.abs(np.fft.fft2(z)) ** 2 / z.size**2
    return {k: float((qa ** p * qc ** q * power).sum()) for k, (p, q) in POWERS.items()}


def _scatter(moments, shape, dx, dy, angle_deg):
    """Standard deviation of each periodogram moment: |Z_k|² is exponential with mean c_k and
    Z_k = conj Z_−k, so Var m̂ = Σ over pairs (2 w c)² = 2 Σ_k (w_k c_k)²."""
    qx, qy, qa, qc = _lay_wavenumbers(shape, dx, dy, angle_deg)
    c = lay_frame_spectrum(moments, qx, qy, angle_deg) * (2 * np.pi) ** 2 / (shape[0] * dy * shape[1] * dx)
    return {k: math.sqrt(2.0 * float(((qa ** p * qc ** q * c) ** 2).sum())) for k, (p, q) in POWERS.items()}


@pytest.mark.parametrize("alpha", [1.2, 2.0, 2.999, 3.0, 4.5, 10.0, 40.0])
def test_one_dimensional_densities_have_the_prescribed_moments(alpha):
    """Unit mass, <q^2> = 1 and <q^4> = alpha by adaptive quadrature (independent of the closed
    forms used to build the densities)."""
    moment = [quad(lambda q, k=k: q**k * _density_1d(q, 1.0, alpha), -np.inf, np.inf, limit=400)[0]
              for k in (0, 2, 4)]
    np.testing.assert_allclose(moment, [1.0, 1.0, alpha], rtol=1e-7)


@pytest.mark.parametrize("moments, shape, dx, dy", CASES)
def test_grids_resolve_the_spectrum(moments, shape, dx, dy):
    """The grids of CASES carry the prescribed moments to within 2 % (m00 ... m04), so that the
    round trip below tests the generator, not the grid."""
    g = grid_moments(moments, shape, dx, dy)
    prescribed = {**moments.as_dict(), "m22": moments.m20 * moments.m02 / moments.m00}
    for name in NAMES:
        assert g[name] == pytest.approx(prescribed[name], rel=0.02), name


@pytest.mark.parametrize("angle", [0.0, 30.0])
@pytest.mark.parametrize("moments, shape, dx, dy", CASES)
def test_round_trip_within_scatter(moments, shape, dx, dy, angle):
    """Over five seeds, every measured moment is within 4 standard deviations of its expectation
    on the grid, and the seed mean within 4/sqrt(5) of them; the expectation is the prescribed
    moment within the grid's resolution (test above)."""
    expected = grid_moments(moments, shape, dx, dy, lay_angle_deg=angle)
    sigma = _scatter(moments, shape, dx, dy, angle)
    runs = [_measured(synthetic_surface(moments, shape, dx, dy, seed=s, lay_angle_deg=angle), dx, dy, angle)
            for s in range(5)]
    for name in NAMES:
        values = np.array([r[name] for r in runs])
        # q = 0 is excluded from the map, included in the expectation: its share is below 1e-3 here
        assert np.all(np.abs(values - expected[name]) < 4 * sigma[name] + 1e-3 * expected[name]), name
        assert abs(values.mean() - expected[name]) < 4 * sigma[name] / math.sqrt(5) + 1e-3 * expected[name], name
        assert 0.0 < sigma[name] < 0.2 * expected[name]  # the test has power


def test_heights_are_gaussian_with_zero_mean():
    m = SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0)
    z = synthetic_surface(m, (256, 256), 0.4, 0.2, seed=3)
    assert abs(z.mean()) < 1e-12
    u = z.ravel() / z.std()
    assert abs(np.mean(u**3)) < 0.15 and abs(np.mean(u**4) - 3.0) < 0.3  # skewness, kurtosis


def test_seeded_periodic_and_oriented():
    m = SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0)
    a = synthetic_surface(m, (64, 128), 0.4, 0.2, seed=7)
    assert a.shape == (64, 128)
    np.testing.assert_array_equal(a, synthetic_surface(m, (64, 128), 0.4, 0.2, seed=7))
    assert not np.array_equal(a, synthetic_surface(m, (64, 128), 0.4, 0.2, seed=8))
    # rows are y, columns x: along x (the lay) the slopes are 3x smaller than along y
    gx = np.diff(a, axis=1, append=a[:, :1]) / 0.4  # periodic wrap: the last column meets the first
    gy = np.diff(a, axis=0, append=a[:1, :]) / 0.2
    assert gx.var() < 0.5 * gy.var()


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"shape": (3, 64)}, "shape"),
        ({"dx": 0.0}, "dx"),
        ({"dy": float("nan")}, "dy"),
        ({"seed": 1.5}, "seed"),
        ({"lay_angle_deg": float("inf")}, "lay_angle_deg"),
    ],
)
def test_bad_input(kwargs, match):
    args = {"shape": (64, 64), "dx": 0.4, "dy": 0.2, "seed": 0, **kwargs}
    with pytest.raises(ValueError, match=match):
        synthetic_surface(SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0), **args)
