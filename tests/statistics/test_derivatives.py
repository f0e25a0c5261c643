"""Derivative stencils around dropouts and edges, the harmonic fill, and what measure_heights
reports beside the moments: scales, uncertainty, warnings, refusals."""

import math
import warnings

import numpy as np
import pytest

from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.derivatives import derivative_fields, first_derivative, stencil_weights
from roughcontact.statistics.dropouts import fill_harmonic, missing_fraction
from roughcontact.statistics.measure import MeasurementWarning, measure_heights
from roughcontact.statistics.synthetic import synthetic_surface

M = SpectralMoments(0.01, 0.001, 0.01, 3e-4, 0.03)  # µm; m02/m20 = 10, slopes ~0.1


def test_central_weights_are_the_textbook_ones():
    np.testing.assert_allclose(stencil_weights(range(-2, 3)), [1 / 12, -2 / 3, 0, 2 / 3, -1 / 12], atol=1e-14)
    np.testing.assert_allclose(stencil_weights(range(-3, 4)),
                               [-1 / 60, 3 / 20, -3 / 4, 0, 3 / 4, -3 / 20, 1 / 60], atol=1e-14)


@pytest.mark.parametrize("order", [2, 4, 6, 8])
def test_exact_for_polynomials_next_to_holes_and_edges(order):
    """Every stencil (central of order p, off-centre with p + 3 nodes) is exact for polynomials of
    degree p: the derivative of x^p is exact at every measured point, edges and holes included."""
    rng = np.random.default_rng(order)
    x = np.linspace(-1.0, 1.0, 41)
    z = np.tile(x**order + 0.3 * x, (6, 1))
    z[rng.random(z.shape) < 0.1] = np.nan
    d = first_derivative(z, x[1] - x[0], 1, order=order)
    ok = np.isfinite(d)
    assert ok.sum() > 0.7 * np.isfinite(z).sum()
    want = np.broadcast_to(order * x ** (order - 1) + 0.3, z.shape)
    np.testing.assert_allclose(d[ok], want[ok], rtol=1e-8, atol=1e-8)
    assert not np.isfinite(d[~np.isfinite(z)]).any()
    central = first_derivative(z, x[1] - x[0], 1, order=order, off_centre=False)
    assert np.isnan(central[:, : order // 2]).all() and np.isfinite(central).sum() < ok.sum()


def test_a_coarser_step_is_the_decimated_map():
    """The fields at step 2 on the full map are, at every other point, the central fields of the
    map sampled at 2 dx (the scales of measure_heights use every point, not one sub-lattice)."""
    z = synthetic_surface(M, (96, 128), 0.25, seed=2, lay_angle_deg=20.0)
    fine = derivative_fields(z, 0.25, 0.25, step=2, off_centre=False)
    coarse = derivative_fields(z[::2, ::2], 0.5, 0.5, off_centre=False)
    for k in fine:
        a, b = fine[k][::2, ::2], coarse[k]
        ok = np.isfinite(b)
        np.testing.assert_allclose(a[ok], b[ok], rtol=1e-10, atol=1e-12)


def test_harmonic_fill_reproduces_a_plane_and_reports_the_fraction():
    y, x = np.mgrid[0:30, 0:40]
    z = 0.5 + 0.1 * x - 0.2 * y
    holed = z.copy()
    holed[10:15, 5:12] = np.nan
    holed[0, 0] = np.nan
    assert missing_fraction(holed) == pytest.approx(36 / 1200)
    filled = fill_harmonic(holed)
    np.testing.assert_allclose(filled[1:, :], z[1:, :], atol=1e-10)  # an inner hole: the plane
    # at the map's corner (zero normal slope there) the mean of the two neighbours
    assert filled[0, 0] == pytest.approx(0.5 * (z[0, 1] + z[1, 0]))
    with pytest.raises(ValueError, match="no measured point"):
        fill_harmonic(np.full((5, 5), np.nan))


def test_spectral_needs_a_complete_map_or_a_stated_fill():
    z = synthetic_surface(M, (128, 128), 0.25, seed=1)
    z[40:44, 50:60] = np.nan
    with pytest.raises(ValueError, match="complete map"):
        measure_heights(z, 0.25, estimator="spectral")
    r = measure_heights(z, 0.25, estimator="spectral", fill="harmonic")
    assert r.fill == "harmonic" and r.missing_fraction == pytest.approx(40 / 128**2)


def test_more_than_half_missing_is_refused():
    z = synthetic_surface(M, (64, 64), 0.25, seed=1)
    z[:, :33] = np.nan
    with pytest.raises(ValueError, match="of the map is missing"):
        measure_heights(z, 0.25)


@pytest.mark.parametrize("z", [np.full((20, 30), 3.7), 1.0 + 0.01 * np.arange(30)[None, :] * np.ones((20, 1))])
def test_a_flat_map_has_no_roughness_and_no_lay(z):
    """A constant map (or a plane) gave m00 = 1.6e-29 and a lay of -45 deg; now a clear error."""
    with pytest.raises(ValueError, match="flat"):
        measure_heights(z, 0.5)


def test_uncertainty_matches_the_scatter_over_independent_maps():
    """The batch-means standard uncertainty of one map is the scatter of the moments over
    independent maps, within a factor 2 (8 seeds)."""
    runs = [measure_heights(synthetic_surface(M, (192, 192), 0.25, seed=s, lay_angle_deg=30.0), 0.25)
            for s in range(8)]
    for k in ("m00", "m20", "m02", "m40", "m04"):
        scatter = np.std([r.values[k] for r in runs], ddof=1)
        reported = np.mean([r.uncertainty[k] for r in runs])
        assert 0.5 < reported / scatter < 2.0, (k, reported, scatter)
    lay = np.std([r.lay_angle_deg for r in runs], ddof=1)
    assert 0.5 < np.mean([r.uncertainty["lay_angle_deg"] for r in runs]) / lay < 2.0


def test_scales_and_the_resolution_check():
    """On a map that resolves its spectrum the moments at 2 dx are within 10 % (no warning); on a
    map sampled four times coarser the curvatures change and a warning says so."""
    fine = measure_heights(synthetic_surface(M, (256, 256), 0.25, seed=3), 0.25)
    assert [s["factor"] for s in fine.scales] == [1, 2, 4] and fine.notes == ()
    assert fine.scales[1]["m00"] == fine.values["m00"]
    assert fine.validity()["curvatures_resolved"]
    with pytest.warns(MeasurementWarning, match="between dx and 2 dx"):
        coarse = measure_heights(synthetic_surface(M, (256, 256), 1.0, seed=3), 1.0)
    assert coarse.validity()["curvatures_resolved"] is False and not coarse.validity()["model_applies"]


def test_heights_in_nm_with_dx_in_um_are_named():
    z = synthetic_surface(M, (128, 128), 0.25, seed=4) * 1000.0  # nm heights, µm spacing
    with pytest.warns(MeasurementWarning, match=r"rms slope is .*scale factor 0.001"):
        r = measure_heights(z, 0.25)
    assert any("0.001" in n for n in r.notes)
    with pytest.warns(MeasurementWarning, match="scale factor 1e\\+06"):
        measure_heights(z * 1e-9, 0.25)  # heights in m


def test_a_narrow_band_map_is_measured_not_refused():
    """Two waves crossing at +-30 deg to x: every direction sees one wavenumber (alpha1 = alpha2 = 1),
    mu = -1, outside the model; the moments are still given, with a warning (the old code refused
    with exit 2)."""
    y, x = np.mgrid[0:128, 0:128] * 0.25
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    z = 0.1 * np.cos(x * c + y * s) + 0.1 * np.cos(x * c - y * s + 0.3)
    with pytest.warns(MeasurementWarning, match="mu = "):
        r = measure_heights(z, 0.25)
    assert r.validity()["mu"] <= 0 and r.values["m04"] > 0
    with pytest.raises(ValueError, match="outside the model"):
        r.moments  # noqa: B018  (the model's SpectralMoments cannot hold them)


def test_an_isotropic_map_has_no_lay():
    iso = SpectralMoments(0.01, 0.01, 0.01, 0.03, 0.03)
    z = synthetic_surface(iso, (256, 256), 0.25, seed=5)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = measure_heights(z, 0.25)
    messages = [str(w.message) for w in caught]
    assert any("no lay" in m for m in messages) or r.uncertainty["lay_angle_deg"] > 5.0, messages
    assert math.isfinite(r.lay_angle_deg)
