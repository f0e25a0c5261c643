"""Parameter sweeps (sweep.py): labelled, equal to direct calls, exact under split/combine,
validated before computing."""

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.contact.closures import resolve_material
from roughcontact.contact import elastic_contact
from roughcontact.contact.elastoplastic import elastoplastic_contact
from roughcontact.contact.sweep import SweepSpec, chunk_count, combine, run_sweep, split

FIXED = dict(m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4, E_star=1.14e5)
UNITS = {"length": "um", "stress": "N/mm^2"}


def spec(**kw):
    args = dict(axes={"m00": [0.0625, 0.625], "psi": [0.35, 2.0]}, s=[0.0, 1.5, 3.0], fixed=FIXED, units=UNITS)
    args.update(kw)
    return SweepSpec(**args)


@pytest.fixture(scope="module")
def swept():
    calls = []
    ds = run_sweep(spec(), progress=lambda done, total: calls.append((done, total)))
    return ds, calls


def test_values_are_the_direct_calls(swept):
    ds, _ = swept
    s = ds["s"].values
    for m00 in (0.0625, 0.625):
        surface = SpectralMoments(m00, *(FIXED[k] for k in ("m20", "m02", "m40", "m04")))
        el = elastic_contact(surface, s, FIXED["E_star"], accuracy="plot")
        for psi in (0.35, 2.0):
            mat = resolve_material(surface, E_star=FIXED["E_star"], psi=psi)
            ep = elastoplastic_contact(surface, s, mat, accuracy="plot")
            point = ds.sel(m00=m00, psi=psi)
            for f in ("area_fraction", "pressure", "stiffness", "plastic_area_fraction", "elastoplastic_pressure"):
                np.testing.assert_array_equal(point[f].values, getattr(ep, f), err_msg=f)
            for f in ("area_fraction", "pressure", "stiffness"):
                np.testing.assert_array_equal(point[f"elastic_model_{f}"].values, getattr(el, f), err_msg=f)
            assert float(point["material_psi"]) == pytest.approx(psi, rel=1e-14)
            assert float(point["material_Y"]) == mat.Y


def test_labels_units_progress(swept):
    ds, calls = swept
    assert ds["pressure"].dims == ("m00", "psi", "s")
    assert ds["pressure"].attrs["units"] == "N/mm^2" and ds["stiffness"].attrs["units"] == "N/mm^2/um"
    assert ds["m00"].attrs["units"] == "um^2" and ds["psi"].attrs["units"] == "1"
    assert all("units" in ds[v].attrs and "long_name" in ds[v].attrs for v in [*ds.data_vars, *ds.coords])
    assert ds.attrs["closure"] == "yield-from-psi"
    assert calls == [(i, 4) for i in range(1, 5)]
    # parts sum to totals
    parts = ds.elastic_area_fraction + ds.elastoplastic_area_fraction + ds.plastic_area_fraction
    np.testing.assert_allclose(parts, ds.area_fraction, rtol=1e-15)


def test_split_and_combine_are_exact(swept):
    ds, _ = swept
    pieces = split(spec(), "psi", 2)
    assert [list(p.axes["psi"]) for p in pieces] == [[0.35], [2.0]]
    joined = combine([run_sweep(p) for p in pieces], "psi")
    for v in ds.data_vars:
        np.testing.assert_array_equal(joined[v].transpose(*ds[v].dims).values, ds[v].values, err_msg=v)


def test_chunk_count():
    sp = spec(axes={"m00": np.linspace(0.05, 0.6, 10), "psi": [0.5]})
    assert chunk_count(sp, "m00", points_per_job=6) == 5  # 30 points, 3 per m00 value
    assert chunk_count(sp, "m00", points_per_job=1) == 10  # never more than the axis length
    assert chunk_count(sp, "m00", points_per_job=10**6) == 1


@pytest.mark.parametrize(
    "kw, fragment",
    [
        (dict(axes={"alpha": [1.0]}), "unknown sweep parameter 'alpha'"),
        (dict(axes={"m20": [1e-4]}), "both swept and fixed: m20"),
        (dict(axes={"psi": [0.5]}), "sweep needs values for m00"),
        (dict(axes={"m00": [0.1]}), "give the plasticity index psi or the yield strength Y"),
        (dict(axes={"m00": [0.1, 0.1], "psi": [1.0]}), "repeated values"),
        (dict(axes={"m00": [0.1, np.nan], "psi": [1.0]}), "finite numbers"),
        (dict(s=[]), "non-empty 1-D list of finite separations"),
        (dict(closure="gw"), "closure must be one of"),
        # m00 = 0.005 makes alpha < 2 (mu < 0): rejected before anything is integrated
        (dict(axes={"m00": [0.0625, 0.005], "psi": [1.0]}), "violate mu"),
        (dict(axes={"m00": [0.0625], "psi": [-1.0]}), "psi must be finite and positive"),
    ],
)
def test_bad_specs_fail_before_computing(kw, fragment):
    with pytest.raises(ValueError) as e:
        run_sweep(spec(**kw))
    assert fragment in str(e.value)


def test_a_sweep_takes_its_moments_from_a_moments_file(tmp_path):
    """`moments: surface.json` in a sweep configuration fixes the moments that are not swept,
    converted into the configuration's length unit (issue 20: piping a scan into a sweep)."""
    import json

    from roughcontact.contact.sweep import spec_from_config

    (tmp_path / "surface.json").write_text(json.dumps(
        {"m00": 0.0625e-6, "m20": 8e-5, "m02": 8e-4, "m40": 1.04, "m04": 104.0, "unit": "mm"}))
    cfg = {"axes": {"m00": [0.0625, 0.125], "psi": [0.5]}, "s": [1.0, 2.0], "fixed": {"E_star": 1.14e5},
           "moments": str(tmp_path / "surface.json"), "closure": "yield-from-psi"}
    spec = spec_from_config(cfg, {"length": "um", "stress": "N/mm^2"})
    assert spec.fixed["m40"] == pytest.approx(1.04e-6) and spec.fixed["m20"] == 8e-5 and "m00" not in spec.fixed
    with pytest.raises(ValueError, match="both in fixed and in the moments file"):
        spec_from_config({**cfg, "fixed": {"E_star": 1.14e5, "m20": 1e-4}})


def test_axis_interpolated_within_its_measured_bound():
    """An axis (here m00 over a factor 2) with ≥ AXIS_MIN_POINTS values comes from a Chebyshev
    interpolant in ln m00 checked at the midpoints of its nodes; the error measured there is in
    the attributes, within the axis tolerance, and the interpolated sweep agrees with every
    value computed directly to the "plot" bound (1e-8 relative to each field's total)."""
    from roughcontact.contact.sweep import AXIS_MIN_POINTS, AXIS_RTOL

    axes = {"m00": np.geomspace(0.0625, 0.125, AXIS_MIN_POINTS + 3), "psi": [1.0]}
    s = [0.0, 1.0, 2.5]
    interp = run_sweep(spec(axes=axes, s=s, with_elastic=False, interpolate_axes=("m00", "psi")))
    direct = run_sweep(spec(axes=axes, s=s, with_elastic=False))
    assert interp.attrs["m00_interpolation"] == "chebyshev"
    assert 0.0 < interp.attrs["m00_interpolation_error"] <= interp.attrs["m00_interpolation_rtol"] == AXIS_RTOL["plot"]
    assert interp.attrs["m00_interpolation_nodes"] < axes["m00"].size  # fewer model evaluations than values
    assert "m00_interpolation" not in direct.attrs and "psi_interpolation" not in interp.attrs  # off by default
    for total, parts in (("area_fraction", ("elastic_area_fraction", "plastic_area_fraction")),
                         ("pressure", ("elastoplastic_pressure",)), ("stiffness", ())):
        scale = np.abs(direct[total].values)
        for f in (total, *parts):
            err = np.abs(interp[f].values - direct[f].values) / scale
            assert np.nanmax(err) <= 1e-8, (f, np.nanmax(err))
    np.testing.assert_array_equal(interp["material_psi"].values, direct["material_psi"].values)


def test_axis_that_does_not_verify_is_computed_directly():
    """ψ over 0.2 … 5 (steep at the yield onset) fails the midpoint check on every grid cheaper
    than its 20 values: every value is computed, the same numbers as without interpolation,
    and the attributes say so."""
    axes = {"m00": [0.0625], "psi": np.geomspace(0.2, 5.0, 20)}
    s = [0.0, 2.5]
    interp = run_sweep(spec(axes=axes, s=s, with_elastic=False, interpolate_axes=("psi",)))
    direct = run_sweep(spec(axes=axes, s=s, with_elastic=False))
    assert interp.attrs["psi_interpolation"] == "direct" and np.isnan(interp.attrs["psi_interpolation_error"])
    for v in direct.data_vars:
        np.testing.assert_array_equal(interp[v].values, direct[v].values, err_msg=v)
