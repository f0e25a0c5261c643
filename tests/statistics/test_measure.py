"""Moments measured on maps and profiles: closed forms for sinusoids, the synthetic round trip,
lay-angle recovery, map vs profile pair, and the leakage the window removes."""

import math

import numpy as np
import pytest

from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.derivatives import derivative_fields
from roughcontact.statistics.measure import _spectral, measure_heights, measure_profiles, rotate_map
from roughcontact.statistics.synthetic import grid_moments, lay_frame_spectrum, synthetic_surface

# rms slope ~3 (the unit check's warning is expected here: these tests are about the estimators)
pytestmark = pytest.mark.filterwarnings("ignore::roughcontact.statistics.measure.MeasurementWarning")
M = SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0)
SHAPE, DX, DY = (256, 256), 0.4, 0.2  # resolves M (tests/statistics/test_synthetic.py)
PERIODIC = {"estimator": "spectral", "window": "none", "detrend": "mean"}


def _plane_wave(shape, dx, dy, kx, ky, amplitude=0.3):
    """A cos(qx x + qy y) with wavenumbers on the grid (periodic)."""
    ny, nx = shape
    qx, qy = 2 * np.pi * kx / (nx * dx), 2 * np.pi * ky / (ny * dy)
    y, x = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    return amplitude * np.cos(qx * x + qy * y), qx, qy


def test_plane_wave_spectral_and_fd_closed_forms():
    """For z = A cos(q·x): m_pq = A²/2 qx^p qy^q exactly (spectral); the order-2 central
    differences see sin(q d)/d instead of q (their transfer function), the second derivative
    its square (the stencil applied twice)."""
    z, qx, qy = _plane_wave((64, 96), 0.5, 0.25, 7, 3)
    a2 = 0.3**2 / 2
    # (one wave has mu < 0, which SpectralMoments refuses: the estimators are called directly)
    r = _spectral(z, 0.5, 0.25, "none", 0.0)
    want = {"m00": a2, "m20": a2 * qx**2, "m02": a2 * qy**2, "m11": a2 * qx * qy, "m40": a2 * qx**4,
            "m04": a2 * qy**4, "m22": a2 * qx**2 * qy**2, "m31": a2 * qx**3 * qy, "m13": a2 * qx * qy**3}
    for k, v in want.items():
        assert r[k] == pytest.approx(v, rel=1e-10), k
    f = derivative_fields(np.tile(z, (3, 3)), 0.5, 0.25, order=2)  # periodic: the middle copy has no edge
    f = {k: v[64:128, 96:192] for k, v in f.items()}
    sx, sy = math.sin(qx * 0.5) / 0.5, math.sin(qy * 0.25) / 0.25
    y, x = np.meshgrid(np.arange(64) * 0.25, np.arange(96) * 0.5, indexing="ij")
    phase = qx * x + qy * y
    np.testing.assert_allclose(f["zx"], -0.3 * sx * np.sin(phase), atol=1e-12)
    np.testing.assert_allclose(f["zxy"], -0.3 * sx * sy * np.cos(phase), atol=1e-12)
    np.testing.assert_allclose(f["zyy"], -0.3 * sy**2 * np.cos(phase), atol=1e-12)


@pytest.mark.parametrize("angle", [0.0, 30.0, -60.0, 75.0])
def test_lay_angle_recovered_within_scatter(angle):
    """The lay angle of a synthetic map is found within 4 sigma of its sampling scatter,
    sigma_theta = sigma(m11)/(m02 − m20), sigma(m11)² = 2 Σ (q_a q_c c_k)² (periodogram)."""
    dx = dy = 0.15
    shape = (384, 384)
    qx = 2 * np.pi * np.fft.fftfreq(shape[1], d=dx)[np.newaxis, :]
    qy = 2 * np.pi * np.fft.fftfreq(shape[0], d=dy)[:, np.newaxis]
    t = math.radians(angle)
    qa, qc = math.cos(t) * qx + math.sin(t) * qy, -math.sin(t) * qx + math.cos(t) * qy
    c = lay_frame_spectrum(M, qx, qy, angle) * (2 * np.pi) ** 2 / (shape[0] * dy * shape[1] * dx)
    sigma = math.degrees(math.sqrt(2 * float(((qa * qc * c) ** 2).sum())) / (M.m02 - M.m20))
    for seed in range(3):
        z = synthetic_surface(M, shape, dx, dy, seed=seed, lay_angle_deg=angle)
        r = measure_heights(z, dx, dy, **PERIODIC)
        err = (r.lay_angle_deg - angle + 90.0) % 180.0 - 90.0
        assert abs(err) < 4 * sigma, (seed, err, sigma)
        assert abs(r.lay["m11"]) < 1e-9 * r.lay["m02"]  # m11 = 0 in the lay frame
        assert r.lay["m20"] < r.lay["m02"]  # x along the lay: the smaller slope variance
    assert sigma < 1.0  # the check is sharp to a degree


@pytest.mark.parametrize("estimator", ["spectral", "fd"])
def test_map_moments_round_trip(estimator):
    """Measured five moments within 4 sigma (periodogram scatter) + the estimator's grid bias of
    the prescribed ones, over three seeds; fd on a map that samples M four times finer."""
    shape, dx, dy = (SHAPE, DX, DY) if estimator == "spectral" else ((512, 512), 0.1, 0.05)
    expected = grid_moments(M, shape, dx, dy)
    options = {"window": "none", "detrend": "mean"} if estimator == "spectral" else {}
    for seed in range(3):
        z = synthetic_surface(M, shape, dx, dy, seed=seed)
        r = measure_heights(z, dx, dy, estimator=estimator, lay_angle_deg=0.0, **options)
        got = r.moments.as_dict()
        for k in ("m00", "m20", "m02", "m40", "m04"):
            # 15 %: the periodogram scatter of these maps is 2-6 % (test_synthetic), and fd's
            # transfer-function bias at these resolutions is below 5 % (plane-wave test)
            assert got[k] == pytest.approx(expected[k], rel=0.15), (seed, k)


def test_map_versus_profile_pair():
    """All rows and all columns as profiles give the map's moments to rounding (Parseval, same
    detrending); eight profiles each way give them within the profiles' larger scatter."""
    z = synthetic_surface(M, SHAPE, DX, DY, seed=4)
    m = measure_heights(z, DX, DY, lay_angle_deg=0.0, **PERIODIC).moments
    # rows are profiles along x; columns along y: mean removed per profile vs per map
    zc = z - z.mean()
    full = measure_profiles(zc, zc.T, DX, DY, estimator="spectral", window="none", detrend="none")
    for k in ("m20", "m02", "m40", "m04"):
        assert getattr(full, k) == pytest.approx(getattr(m, k), rel=1e-12), k
    assert full.m00 == pytest.approx(m.m00, rel=1e-12)
    few = measure_profiles(z[::32, :], z[:, ::32].T, DX, DY, **PERIODIC)
    for k in ("m00", "m20", "m02", "m40", "m04"):
        assert getattr(few, k) == pytest.approx(getattr(m, k), rel=0.25), k
    assert SpectralMoments.from_profiles(z[::32, :], z[:, ::32].T, DX, DY, **PERIODIC) == few


def test_window_removes_edge_leakage_of_a_non_periodic_map():
    """A 128 x 128 piece of a periodic map is not periodic: without a window the edge jump
    leaks to high wavenumbers and inflates m40 and m04 several-fold; the Hann window and the fd
    estimator recover them within 15 %."""
    big = synthetic_surface(M, (512, 512), 0.1, 0.05, seed=5)
    piece = big[:256, :256]
    ref = grid_moments(M, (512, 512), 0.1, 0.05)
    raw = measure_heights(piece, 0.1, 0.05, estimator="spectral", window="none", lay_angle_deg=0.0).moments
    hann = measure_heights(piece, 0.1, 0.05, estimator="spectral", lay_angle_deg=0.0).moments
    fd = measure_heights(piece, 0.1, 0.05, estimator="fd", lay_angle_deg=0.0).moments
    assert raw.m40 > 2.0 * ref["m40"]
    for est in (hann, fd):
        for k in ("m20", "m02", "m40", "m04"):
            assert getattr(est, k) == pytest.approx(ref[k], rel=0.3), k


def test_from_heights_and_anisotropy_report():
    z = synthetic_surface(M, SHAPE, DX, DY, seed=6, lay_angle_deg=20.0)
    r = measure_heights(z, DX, DY, **PERIODIC)
    assert SpectralMoments.from_heights(z, DX, DY, **PERIODIC) == r.moments
    a = r.anisotropy()
    # separable spectrum: m22 = m20 m02/m00 = 9, sqrt(m40 m04) = sqrt(486) -> 0.41
    assert a["m22_over_sqrt_m40_m04"] == pytest.approx(9 / math.sqrt(486), rel=0.15)
    assert abs(a["m31_over_sqrt_m40_m22"]) < 0.15 and abs(a["m13_over_sqrt_m04_m22"]) < 0.15
    assert abs(r.m11_map) > 0.5  # the map frame is 20 degrees off the lay


def test_rotate_map_undoes_a_rotation():
    z, *_ = _plane_wave((101, 101), 0.1, 0.1, 0, 0)
    y, x = np.mgrid[0:101, 0:101] * 0.1
    z = np.sin(0.7 * (np.cos(0.5) * x + np.sin(0.5) * y))  # varies along 0.5 rad only
    r = rotate_map(z, 0.1, 0.1, math.degrees(0.5))
    inner = r[30:70, 30:70]
    assert np.nanstd(inner, axis=0).max() < 0.02  # along the new y (across the wave) ~ constant


@pytest.mark.parametrize(
    "z, kwargs, match",
    [
        (np.zeros((8, 8)), {}, "flat"),
        (np.ones((3, 8)), {}, "at least 5"),
        (np.full((8, 8), np.nan), {}, "missing"),
        (np.full((8, 8), np.inf), {}, "infinite"),
        (np.ones(8), {}, "2-d"),
        (np.random.default_rng(0).random((8, 8)), {"dx": -1.0}, "dx"),
        (np.random.default_rng(0).random((8, 8)), {"estimator": "wavelet"}, "estimator"),
    ],
)
def test_bad_input(z, kwargs, match):
    args = {"dx": 0.1, **kwargs}
    with pytest.raises(ValueError, match=match):
        measure_heights(z, **args)
