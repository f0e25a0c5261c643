"""The summit-table route (integrals.summit_table) against the τ = r t route and by refinement.

The τ-route is itself checked against the scipy twin (tests/contact/test_elastoplastic.py);
the two routes share nothing but the θ-nodes and the per-asperity law, so agreement within the
preset's bound checks the table's construction (the y-substitution, the r-rule, the
interpolation of ln ρ and the convolution)."""

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.asperity import AsperityMaterial, yield_strength_for_plasticity_index
from roughcontact.contact import elastoplastic as ep

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
ALPHA22 = SpectralMoments(1.0, 1.0, 1.0, 2.2, 2.2)
E = 1.14e5
FIELDS = ep.ElastoPlasticCurves.FIELDS


def _material(surface, psi):
    return AsperityMaterial(E, yield_strength_for_plasticity_index(psi, surface, E))


def _rel(a, b):
    """max relative difference per field, parts against max(|part|, 1e-3 |total|)."""
    out = {}
    for f in FIELDS:
        x, y = getattr(a, f), getattr(b, f)
        total = getattr(b, "area_fraction" if "area" in f else "pressure" if "pressure" in f else "stiffness")
        scale = np.maximum(np.abs(y), 1e-3 * np.abs(total))
        out[f] = float(np.max(np.where(scale > 0, np.abs(x - y) / np.where(scale > 0, scale, 1.0), 0.0)))
    return out


@pytest.mark.parametrize("surface,psi", [(TABLE1, 1.0), (TABLE1, 5.0), (ALPHA22, 1.0)])
def test_table_route_matches_tau_route_at_plot(surface, psi):
    mat = _material(surface, psi)
    s = np.linspace(-0.5, 4.0, 10)
    tau = ep.elastoplastic_contact(surface, s, mat, accuracy="plot", validity="off", route="tau")
    tab = ep.elastoplastic_contact(surface, s, mat, accuracy="plot", validity="off", route="table")
    err = _rel(tab, tau)
    # both routes within the "plot" bound 1e-8 of the truth: within 2e-8 of each other
    assert max(err.values()) <= 2e-8, err


def test_table_refinement_plot_against_table_preset():
    """The "plot" table against the "table"-preset table (finer θ, r, y and convolution rules):
    the difference estimates the "plot" table's error, which must be within its bound 1e-8."""
    mat = _material(TABLE1, 1.0)
    s = np.linspace(0.0, 3.5, 6)
    plot = ep.elastoplastic_contact(TABLE1, s, mat, accuracy="plot", validity="off", route="table")
    fine = ep.elastoplastic_contact(TABLE1, s, mat, accuracy="table", validity="off", route="table")
    err = _rel(plot, fine)
    assert max(err.values()) <= 1e-8, err


def test_table_is_reused_and_widened():
    mat = _material(TABLE1, 2.0)
    ep._TABLES.clear()
    ep.elastoplastic_contact(TABLE1, [1.0, 2.0], mat, accuracy="plot", validity="off", route="table")
    first = next(iter(ep._TABLES.values()))
    ep.elastoplastic_contact(TABLE1, [1.5], mat, accuracy="plot", validity="off", route="table")
    assert next(iter(ep._TABLES.values())) is first  # covered: reused
    wide = ep.elastoplastic_contact(TABLE1, [5.0], mat, accuracy="plot", validity="off", route="table")
    table = next(iter(ep._TABLES.values()))
    assert table is not first and table.covers(TABLE1.l_from_s(1.0), TABLE1.l_from_s(5.0))
    tau = ep.elastoplastic_contact(TABLE1, [5.0], mat, accuracy="plot", validity="off", route="tau")
    assert abs(wide.area_fraction[0] / tau.area_fraction[0] - 1) <= 2e-8


def test_unknown_route_is_refused():
    with pytest.raises(ValueError, match="route"):
        ep.elastoplastic_contact(TABLE1, [1.0], _material(TABLE1, 1.0), route="fast")


@pytest.mark.parametrize("psi", [1.0, 50.0])
def test_table_error_bound_is_finite_and_within_tolerance(psi):
    """Parts that are exactly 0 at some y (a regime beyond the r-range) are interpolated as
    fractions: the measured interpolation bound stays finite and within the tolerance."""
    from roughcontact.integrals.summit_table import table_settings_for

    ep._TABLES.clear()
    ep.elastoplastic_contact(TABLE1, [0.0, 2.0], _material(TABLE1, psi), accuracy="plot", validity="off", route="table")
    table = next(iter(ep._TABLES.values()))
    assert 0.0 <= table.interp_error <= table_settings_for("plot").interp_tol


def test_sweep_passes_the_route_through():
    from roughcontact.contact import sweep

    spec = dict(axes={"psi": [0.5, 5.0]}, s=np.linspace(0.0, 3.0, 7),
                fixed={"m00": 0.0625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4, "E_star": E},
                with_elastic=False, validity="off")
    tau = sweep.run_sweep(sweep.SweepSpec(**spec, route="tau"))
    tab = sweep.run_sweep(sweep.SweepSpec(**spec, route="table"))
    assert tab.attrs["route"] == tab.attrs["route_used"] == "table" and tau.attrs["route_used"] == "tau"
    for f in ("area_fraction", "pressure", "stiffness"):
        np.testing.assert_allclose(tab[f].values, tau[f].values, rtol=2e-8, atol=0)
    with pytest.raises(ValueError, match="route"):
        sweep.SweepSpec(**spec, route="fast")


# --------------------------------------------------------------------------------------
# route="auto" (the default): the rule of contact.elastoplastic._auto_tables
# --------------------------------------------------------------------------------------
def test_auto_is_the_default_and_follows_its_rule():
    """No table cached: a single separation and one s-interpolated curve of one material stay on
    τ (their τ cost, 1 and 33 evaluations, is below the build's 70); 200 separations evaluated
    directly and a surface with ≥ 11 materials take the table; a cached table is then used by
    every call it covers. The route taken is recorded on the curves and in their Dataset."""
    import inspect

    assert inspect.signature(ep.elastoplastic_contact).parameters["route"].default == "auto"
    assert inspect.signature(ep.elastoplastic_contact_many).parameters["route"].default == "auto"
    mat = _material(TABLE1, 1.0)
    kw = dict(accuracy="plot", validity="off")
    ep.clear_table_cache()
    assert ep.elastoplastic_contact(TABLE1, [1.0], mat, **kw).route == "tau"
    curve = ep.elastoplastic_contact(TABLE1, np.linspace(0.0, 2.0, 200), mat, **kw)
    assert curve.route == "tau" and curve.interpolation.method == "chebyshev"
    assert not ep._TABLES
    direct = ep.elastoplastic_contact(TABLE1, np.linspace(0.0, 2.0, 200), mat, interpolate_s=False, **kw)
    assert direct.route == "table" and len(ep._TABLES) == 1
    warm = ep.elastoplastic_contact(TABLE1, [1.0], mat, **kw)  # covered by the cached table
    assert warm.route == "table" and warm.to_dataset().attrs["route"] == "table"
    outside = ep.elastoplastic_contact(TABLE1, [6.0], mat, **kw)  # not covered: one separation on τ
    assert outside.route == "tau"
    # the two routes agree within twice the "plot" bound where both ran
    err = _rel(ep.elastoplastic_contact(TABLE1, [1.0], mat, route="tau", **kw), warm)
    assert max(err.values()) <= 2e-8, err
    mats = [_material(TABLE1, p) for p in np.geomspace(0.1, 10.0, 11)]
    ep.clear_table_cache()
    few = ep.elastoplastic_contact_many(TABLE1, np.linspace(0.0, 2.0, 60), mats[:10], **kw)
    assert {c.route for c in few} == {"tau"}
    many = ep.elastoplastic_contact_many(TABLE1, np.linspace(0.0, 2.0, 60), mats, **kw)
    assert {c.route for c in many} == {"table"}


def test_auto_break_even_is_the_stated_cost_model():
    """The rule's numbers as documented: τ evaluations (33 for an s-interpolated curve of ≥ 48),
    k-material τ cost 0.4 + 0.6 k, build 70 τ separations ("plot"), the shared build 2.5 + 0.06 k."""
    assert ep._tau_evaluations(1, True) == 1 and ep._tau_evaluations(47, True) == 47
    assert ep._tau_evaluations(48, True) == 33 and ep._tau_evaluations(200, False) == 200
    assert ep._build_cost(1, "plot") == 70.0 and ep._build_cost(1, "table") == 80.0
    assert ep._build_cost(4, "plot") == pytest.approx(70.0 * (2.5 + 0.24))
    assert ep._tau_cost(70, 1, False) >= ep._build_cost(1, "plot") > ep._tau_cost(69, 1, False)
    # the documented thresholds: 11 materials of an interpolated curve; 88 and 96 direct separations for 2 and 3
    assert ep._tau_cost(60, 11, True) >= ep._build_cost(11, "plot") > ep._tau_cost(60, 10, True)
    assert ep._tau_cost(88, 2, False) >= ep._build_cost(2, "plot") > ep._tau_cost(87, 2, False)
    assert ep._tau_cost(96, 3, False) >= ep._build_cost(3, "plot") > ep._tau_cost(95, 3, False)


def test_mixed_call_takes_each_materials_route():
    """auto with one material's table cached and the others not (below the break-even): the
    cached one on the table, the rest on τ — each the numbers of its own route's call."""
    mats = [_material(TABLE1, p) for p in (0.5, 2.0)]
    kw = dict(accuracy="plot", validity="off")
    s = np.array([0.5, 1.0, 2.0])
    ep.clear_table_cache()
    ep.elastoplastic_contact(TABLE1, s, mats[1], route="table", **kw)
    got = ep.elastoplastic_contact_many(TABLE1, s, mats, **kw)
    assert [c.route for c in got] == ["tau", "table"]
    ref = [ep.elastoplastic_contact(TABLE1, s, mats[0], route="tau", **kw),
           ep.elastoplastic_contact(TABLE1, s, mats[1], route="table", **kw)]
    for a, b in zip(got, ref):
        for f in FIELDS:
            np.testing.assert_array_equal(getattr(a, f), getattr(b, f), err_msg=f)


def test_table_cache_is_bounded_in_bytes(monkeypatch):
    """Least recently used tables leave once the cache holds more than TABLE_CACHE_BYTES."""
    kw = dict(accuracy="plot", validity="off", route="table")
    mats = [_material(TABLE1, p) for p in (0.5, 1.0, 2.0)]
    ep.clear_table_cache()
    ep.elastoplastic_contact(TABLE1, [1.0], mats[0], **kw)
    one = ep.table_cache_bytes()
    assert one > 0
    monkeypatch.setattr(ep, "TABLE_CACHE_BYTES", int(2.5 * one))
    ep.elastoplastic_contact(TABLE1, [1.0], mats[1], **kw)
    ep.elastoplastic_contact(TABLE1, [1.0], mats[0], **kw)  # used again: now the most recent
    ep.elastoplastic_contact(TABLE1, [1.0], mats[2], **kw)
    kept = [key[-1] for key in ep._TABLES]
    assert kept == [mats[0], mats[2]] and ep.table_cache_bytes() <= ep.TABLE_CACHE_BYTES
    ep.clear_table_cache()
    assert ep.table_cache_bytes() == 0


def test_sweep_defaults_to_auto():
    from roughcontact.contact import sweep

    spec = sweep.SweepSpec(axes={"psi": [0.5, 5.0]}, s=[0.0, 1.0],
                           fixed={"m00": 0.0625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4,
                                  "E_star": E}, with_elastic=False, validity="off")
    assert spec.route == "auto"
    assert sweep.spec_from_config({"axes": {"psi": [0.5]}, "s": [1.0], "fixed": dict(spec.fixed)}).route == "auto"
    ep.clear_table_cache()
    ds = sweep.run_sweep(spec)
    assert ds.attrs["route"] == "auto" and ds.attrs["route_used"] == "tau"  # 2 materials, 2 separations


def test_no_kernel_reads_the_thread_count():
    """numba.get_num_threads() inside a kernel is a dynamic global, and numba then does not cache
    the kernel: the shared build's _sh_rho_array compiled for ~4.6 s in every process (issue 33)."""
    import inspect

    import numba

    from roughcontact.integrals import kernels

    dispatchers = {k: f for k, f in vars(kernels).items() if isinstance(f, numba.core.registry.CPUDispatcher)}
    assert "_sh_rho_array" in dispatchers
    for name, f in dispatchers.items():
        assert "get_num_threads" not in inspect.getsource(f.py_func), name
        assert type(f._cache).__name__ != "NullCache", name
