"""roughcontact.bem.scan: the BEM of a map beside the model from its measured moments — the BEM
is solve_pressures on the map with its form removed, the model is model_at_pressures on the
measured moments (h = s√m00), dropouts are refused or filled, the size is checked first, and
the default ladder of a pressure range has 4 points per decade."""

import math

import numpy as np
import pytest

from roughcontact.bem import scan
from roughcontact.bem.compare import model_at_pressures
from roughcontact.bem.scan import bem_of_scan, check_bem_size, pressure_ladder
from roughcontact.bem.solver import SKIP_MESSAGE, STIFFNESS_STEP, available, solve_pressures
from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.limits import InputLimitError
from roughcontact.statistics.measure import measure_heights

requires_bem = pytest.mark.skipif(not available(), reason=SKIP_MESSAGE)
E_STAR = 1.14e5  # config/config.yaml bem.E_star [N/mm^2]


@pytest.fixture
def table1_map(families):
    s = BandLimitedSurface.design(families["table1"], hurst=0.8, k_high=16)
    return s.heights(64, 0), *s.spacing(64)


@requires_bem
@pytest.mark.parametrize("periodic, detrend", [(True, "mean"), (False, "plane")])
def test_bem_and_model_of_a_map(table1_map, periodic, detrend):
    z, dx, dy = table1_map
    tilted = z + 1e-3 * np.arange(z.shape[1])[np.newaxis, :] * dx if detrend == "plane" else z + 5.0
    p = [10.0, 100.0]
    r = bem_of_scan(tilted, dx, dy, E_star=E_STAR, pressures=p, periodic=periodic, detrend=detrend)
    # the BEM: solve_pressures on the map with its form removed (least squares here), same settings
    if detrend == "plane":
        y, x = np.mgrid[0:z.shape[0], 0:z.shape[1]]
        basis = np.column_stack([np.ones(z.size), (x * dx).ravel(), (y * dy).ravel()])
        residual = tilted - (basis @ np.linalg.lstsq(basis, tilted.ravel(), rcond=None)[0]).reshape(z.shape)
    else:
        residual = tilted - tilted.mean()
    ref = solve_pressures(residual, dx, dy, E_STAR, p, periodic=periodic, stiffness_step=STIFFNESS_STEP)
    assert r.periodic is periodic and r.boundary == ("periodic" if periodic else "free boundary (padded)")
    np.testing.assert_allclose(r.area_fraction, ref.area_fraction, rtol=0, atol=2.0 / z.size)
    np.testing.assert_allclose(r.mean_gap, ref.mean_gap, rtol=1e-6)
    np.testing.assert_allclose(r.stiffness, ref.stiffness, rtol=1e-3)
    # the model: model_at_pressures on the moments measure_heights finds, its gap h = s√m00
    m = measure_heights(tilted, dx, dy, detrend=detrend)
    model = model_at_pressures(m.moments, p, E_STAR)
    np.testing.assert_allclose(r.model["area_fraction"], model.area_fraction, rtol=1e-12)
    np.testing.assert_allclose(r.model["mean_gap"], model.s * math.sqrt(m.moments.m00), rtol=1e-12)
    np.testing.assert_allclose(r.model["stiffness"], model.stiffness, rtol=1e-12)
    np.testing.assert_allclose(r.ratio["mean_gap"], r.mean_gap / r.model["mean_gap"], rtol=1e-12)
    assert r.moment_values == m.values and r.lay_angle_deg == m.lay_angle_deg
    assert r.form["removed"] == detrend and r.missing_fraction == 0.0 and not r.filled


@requires_bem
def test_dropouts_refused_or_filled(table1_map):
    z, dx, dy = table1_map
    z = z.copy()
    z[5, 7] = z[20, 30] = z[21, 30] = np.nan
    with pytest.raises(ValueError, match="3 of the map's 4096 points are missing.*fill='harmonic'"):
        bem_of_scan(z, dx, dy, E_star=E_STAR, pressures=[10.0], periodic=True)
    r = bem_of_scan(z, dx, dy, E_star=E_STAR, pressures=[10.0], periodic=True, fill="harmonic")
    assert r.filled and r.missing_fraction == pytest.approx(3 / 4096) and np.isfinite(r.mean_gap).all()


@requires_bem
def test_moments_outside_the_model_keep_the_bem(table1_map):
    """A single cosine (narrow band: μ ≤ 0) still has a BEM; the model is absent and says why."""
    n = 64
    z = np.tile(np.cos(2 * np.pi * np.arange(n) / 16), (n, 1))
    r = bem_of_scan(z, 1.0, 1.0, E_star=1e3, pressures=[1.0], periodic=True, detrend="mean")
    assert r.model is None and r.ratio is None and "outside the model" in r.model_error
    assert r.area_fraction[0] > 0


def test_pressure_ladder():
    np.testing.assert_allclose(pressure_ladder(1.0, 100.0), np.geomspace(1.0, 100.0, 9), rtol=1e-15)
    assert pressure_ladder(1.0, 1.5).size == 3  # at least 3
    assert pressure_ladder(1.0, 10.0, 7).size == 7
    for bad in ((0.0, 1.0), (2.0, 1.0), (1.0, math.inf)):
        with pytest.raises(ValueError, match="0 < LO < HI"):
            pressure_ladder(*bad)
    with pytest.raises(ValueError, match="number of pressures"):
        pressure_ladder(1.0, 2.0, 1)
    with pytest.raises(ValueError, match="number of pressures"):
        pressure_ladder(1.0, 2.0, scan.MAX_PRESSURES + 1)


def test_size_checked_from_the_measured_bytes(monkeypatch):
    """The BEM's memory per point (measured: ~250 B periodic, ~620 B free) against the cells
    limit (sized for ~100 B per cell): a map of N points counts as 3N or 7N cells."""
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", str(3 * 100 * 100))
    check_bem_size((100, 100), True)
    with pytest.raises(InputLimitError, match="the BEM of a 100 x 100 map \\(free boundary"):
        check_bem_size((100, 100), False)
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", str(3 * 100 * 100 - 1))
    with pytest.raises(InputLimitError, match="ROUGHCONTACT_MAX_CELLS"):
        check_bem_size((100, 100), True)


def test_bad_map():
    with pytest.raises(ValueError, match="2-d"):
        bem_of_scan(np.ones(10), 1.0, 1.0, E_star=1.0, pressures=[1.0], periodic=True)
