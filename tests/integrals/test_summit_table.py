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
    tau = ep.elastoplastic_contact(surface, s, mat, accuracy="plot", validity="off")
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
    tau = ep.elastoplastic_contact(TABLE1, [5.0], mat, accuracy="plot", validity="off")
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
    tau = sweep.run_sweep(sweep.SweepSpec(**spec))
    tab = sweep.run_sweep(sweep.SweepSpec(**spec, route="table"))
    assert tab.attrs["route"] == "table"
    for f in ("area_fraction", "pressure", "stiffness"):
        np.testing.assert_allclose(tab[f].values, tau[f].values, rtol=2e-8, atol=0)
    with pytest.raises(ValueError, match="route"):
        sweep.SweepSpec(**spec, route="fast")
