"""Example 9.2, the punch on the foundation (roughcontact.examples.punch: its deck and laws through
the deck reader), on a coarse quarter model: equilibrium of the interface with the applied loads,
x <-> y symmetry of cases a/b (not c), the dissipation's readings and its frictionless upper
bound, the friction limit at every point, unloading back to the seated state, and the
specification's validation."""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact.examples import punch
from roughcontact.examples.punch import PunchRun, PunchSpec
from roughcontact.examples.punch_geometry import PunchGeometry
from roughcontact.interface import friction

SURFACE = {"m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}  # section 9.2, um units
COARSE = {"family": "quadratic", "n_punch": 2, "n_outer": 2, "n_depth": 2}  # 5 x 5 contact points (nodal Lobatto rule)
SEATING = 0.1  # N/mm^2
QUARTER_TOP = 10.0 * 10.0  # mm^2, the quarter punch's top face


def run(case, load=1000.0, load_on="quarter", increments=4, geometry=None, **extra):
    """One coarse run; the elastic law (it coincides with the elasto-plastic one at these
    pressures, Table 4) keeps the set-up cheap."""
    spec = PunchSpec(geometry=PunchGeometry(**{**COARSE, **(geometry or {})}), load=load, load_on=load_on,
                     seating_pressure=SEATING, increments=increments, unload_increments=increments)
    return punch.run_punch(PunchRun(case=case, spec=spec, m00=0.625, surface=tuple(SURFACE.items()), law="elastic",
                                    psi=None, **extra))


@pytest.fixture(scope="module")
def runs():
    return {case: run(case) for case in ("a", "b", "c", "frictionless")}


def pair_index(x):
    """For every point (x, y), the index of the point (y, x)."""
    key = {(round(a, 9), round(b, 9)): i for i, (a, b) in enumerate(x[:, :2])}
    return np.array([key[(round(b, 9), round(a, 9))] for a, b in x[:, :2]])


def test_mu_max_is_the_largest_coefficient_of_89():
    # (89): mu runs from mu_m mu_o (no slip) to mu_m (kappa -> infinity)
    assert punch.mu_max("a") == pytest.approx(0.2)
    assert punch.mu_max("b") == pytest.approx(0.5) == punch.mu_max("c")


def test_bound_is_the_weighted_sum_and_four_quarters_make_the_whole():
    w, p, d = np.array([1.0, 2.0]), np.array([3.0, 0.5]), np.array([1e-3, 4e-3])
    quarter = punch.bound(w, p, d, 0.5, whole=False)
    assert quarter == pytest.approx(0.5 * (3e-3 + 4e-3), rel=1e-15)
    assert punch.bound(w, p, d, 0.5) == pytest.approx(4.0 * quarter, rel=1e-15)
    with pytest.raises(ValueError, match="same contact points"):
        punch.bound(w, p, d[:1], 0.5)
    with pytest.raises(ValueError, match="mu_max"):
        punch.bound(w, p, d, 0.0)


@pytest.mark.parametrize("kwargs, message", [
    ({"nu": 0.5}, "nu"), ({"load": -1.0}, "load"), ({"load_on": "half"}, "load_on"),
    ({"increments": 0}, "increments"), ({"increments": 2.5}, "increments"), ({"unload_increments": -1}, "unload"),
    ({"seating_pressure": 0.0}, "seating_pressure"), ({"increments": True}, "increments"),
])
def test_spec_rejects_bad_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        punch.PunchSpec(**kwargs)


def test_levels_go_up_to_the_quarter_load_and_back():
    spec = punch.PunchSpec(load=1000.0, increments=4, unload_increments=2)
    assert spec.quarter_load == 250.0
    assert punch.PunchSpec(load=1000.0, load_on="quarter").quarter_load == 1000.0
    np.testing.assert_allclose(spec.levels, [0, 62.5, 125, 187.5, 250, 125, 0])
    assert spec.levels[spec.max_index] == spec.quarter_load
    assert punch.PunchSpec(unload_increments=0).levels[-1] == punch.PunchSpec().quarter_load


@pytest.mark.parametrize("case", ["a", "b", "c", "frictionless"])
def test_interface_carries_the_applied_load(runs, case):
    r = runs[case]
    w = r.points.weights
    assert np.sum(w) == pytest.approx(QUARTER_TOP, rel=1e-12)  # the points tile the quarter's face
    for k, expected in ((0, 0.0), (r.spec.max_index, 1000.0), (-1, 0.0)):
        p_N = -r.deck.increments[k].tractions[:, 2]
        assert np.sum(w * p_N) == pytest.approx(expected + SEATING * QUARTER_TOP, rel=1e-9)
    assert punch.summary_of(r)["equilibrium_error_max_load"] < 1e-8


@pytest.mark.parametrize("case", ["a", "b"])
def test_cases_a_and_b_are_symmetric_in_x_and_y(runs, case):
    d = runs[case].fields()
    x = np.column_stack([d["x_mm"], d["y_mm"]])
    j = pair_index(x)
    scale = np.max(np.abs(d["t_x"]))
    np.testing.assert_allclose(d["t_x"], d["t_y"][j], atol=1e-8 * scale)
    np.testing.assert_allclose(d["slip_x_um"], d["slip_y_um"][j], atol=1e-9)
    np.testing.assert_allclose(d["p_N"], d["p_N"][j], rtol=1e-8)
    np.testing.assert_array_equal(d["status"], d["status"][j])


def test_case_c_is_not_symmetric(runs):
    d = runs["c"].fields()
    j = pair_index(np.column_stack([d["x_mm"], d["y_mm"]]))
    # k_Ty = k_N > k_Tx = 0.7 k_N: the y tractions are the stiffer ones
    assert np.max(np.abs(d["t_x"] - d["t_y"][j])) > 1e-3 * np.max(np.abs(d["t_x"]))


@pytest.mark.parametrize("case", ["a", "b", "c"])
def test_friction_limit_and_dissipation_bounds(runs, case):
    r = runs[case]
    d = r.fields()
    assert np.all(d["utilisation"] <= 1.0 + 1e-10)
    assert np.all((d["status"] == friction.SLIP) == np.isclose(d["utilisation"], 1.0, atol=1e-10, rtol=0))
    for at in ("max", "end"):
        assert punch.dissipation(r, at=at, weight="work") >= 0.0
        for weight in ("area", "none", "work"):
            assert punch.dissipation(r, at=at, weight=weight) == pytest.approx(
                4.0 * punch.dissipation(r, at=at, weight=weight, whole=False), rel=1e-14)
    D = punch.dissipation(r, whole=False)
    bound = punch.frictionless_bound(r, runs["frictionless"], punch.mu_max(case), whole=False)
    assert 0.0 <= D <= bound
    # the dissipated work at the maximum load is at most the paper's t_T u_T^p while the
    # tractions only grow along a straight plastic path (hardening: |t_T| rises with the slip)
    assert punch.dissipation(r, weight="work") <= punch.dissipation(r) * (1 + 1e-12) + 1e-15


def test_something_slips_at_the_quarter_reading(runs):
    """A test of the tests: the coarse model does reach the friction limit somewhere."""
    for case in ("a", "b", "c"):
        assert np.any(runs[case].fields()["status"] == friction.SLIP)
        assert punch.dissipation(runs[case]) > 0.0


def test_smaller_friction_slips_more(runs):
    """Case a (mu_m = 0.2) against b (0.5): the paper's 'smaller plastic slip for larger friction'."""
    slip = {c: np.hypot(runs[c].fields()["slip_x_um"], runs[c].fields()["slip_y_um"]).sum()
            for c in ("a", "b")}
    assert slip["a"] > slip["b"]


def test_small_load_does_not_slip():
    r = run("b", load=1.0, load_on="whole", increments=1)
    assert punch.dissipation(r) == 0.0 and punch.dissipation(r, weight="work") == 0.0
    assert not np.any(r.fields()["status"] == friction.SLIP)


def test_unloading_returns_to_the_seated_pressures(runs):
    r = runs["frictionless"]
    p0, p_end = (-r.deck.increments[k].tractions[:, 2] for k in (0, -1))
    np.testing.assert_allclose(p_end, p0, rtol=1e-6)


def test_dataset_is_labelled_and_finite(runs):
    ds = punch.to_dataset(runs["b"])
    assert ds.sizes == {"level": 9, "point": 25}
    for name, var in ds.data_vars.items():
        assert "units" in var.attrs, name
        assert np.all(np.isfinite(var.values)), name
    assert ds.attrs["D_max_area_whole"] == pytest.approx(punch.dissipation(runs["b"]), rel=1e-15)
    assert ds.attrs["max_index"] == 4 and ds.attrs["utilisation_max"] <= 1.0 + 1e-10
    np.testing.assert_allclose(ds["load_quarter"].values, runs["b"].spec.levels)
    # relative displacements are measured from the seated state
    np.testing.assert_array_equal(ds["jump_x_um"].isel(level=0).values, 0.0)


def test_load_patch_is_applied_where_stated():
    """A wider patch spreads the same load: the pressure under the punch's centre falls."""
    narrow, wide = (run("frictionless", increments=1, geometry={"load_patch": s}) for s in (10.0, 20.0))
    centre = [np.argmin(np.hypot(r.fields()["x_mm"], r.fields()["y_mm"])) for r in (narrow, wide)]
    p = [r.fields()["p_N"][i] for r, i in zip((narrow, wide), centre)]
    assert p[0] > p[1]
    assert wide.spec.geometry.load_half == 10.0 and narrow.spec.geometry.load_half == 5.0
