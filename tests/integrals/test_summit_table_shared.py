"""The shared build of the summit table (integrals.summit_table.build_tables): one set of
material-free densities per surface for every material of a sweep.

Judges: the per-material build (build_table: an r-quadrature per (y, θ) with the law of
_st_node; the shared build shares nothing with it but the θ-nodes: it integrates densities in
v = ln(τ/T) with the law pieces reassembled from eq. (65)'s scaling), the τ = r t route (itself
checked against the scipy twin in tests/contact/test_elastoplastic.py) and the scipy twin
directly. Each route is within the "plot" bound 1e-8 of the truth, so two of them agree within
2e-8; measured: shared against per-material ≤ 7e-11, against the τ route ≤ 3e-9."""

import math

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.asperity import AsperityMaterial, yield_strength_for_plasticity_index
from roughcontact.contact import elastoplastic as ep
from roughcontact.integrals.reference_elastoplastic import reference_integrals
from roughcontact.integrals.summit_table import build_table, build_tables, shared_scale, table_settings_for

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
ALPHA22 = SpectralMoments(1.0, 1.0, 1.0, 2.2, 2.2)
E = 1.14e5
FIELDS = ep.ElastoPlasticCurves.FIELDS
#: both sides within the "plot" bound 1e-8 of the truth
PAIR = 2e-8
PSIS = (0.05, 0.5, 2.0, 10.0, 50.0)


def _material(surface, psi, **kw):
    return AsperityMaterial(E, yield_strength_for_plasticity_index(psi, surface, E), **kw)


def _floored_rel(a, b):
    """max relative difference per column (n_l, 8), parts against max(|part|, 1e-3 |total|) (the
    load jump a part of K, as ``stiffness_jump`` of ``stiffness`` in test_summit_table.py)."""
    tot = np.concatenate([np.repeat(b[:, 0:3].sum(1, keepdims=True), 3, 1),
                          np.repeat(b[:, 3:6].sum(1, keepdims=True), 3, 1), b[:, 6:7], np.abs(b[:, 6:7])], 1)
    scale = np.maximum(np.abs(b), 1e-3 * tot)
    return np.where(scale > 0, np.abs(a - b) / np.where(scale > 0, scale, 1.0), 0.0).max(axis=0)


def _curves_rel(a, b):
    """_floored_rel of two ElastoPlasticCurves over A^e, A^ep, A^p, W^e, W^ep, W^p, K (jump
    included) and the jump, by name."""
    names = FIELDS[3:9] + ("stiffness", "stiffness_jump")

    def cols(c):
        return np.stack([getattr(c, f) for f in names], axis=1)

    return dict(zip(names, _floored_rel(cols(a), cols(b))))


def _inputs(surface, materials, hertz="exact", accuracy="plot"):
    nodes = ep._theta_geometry(surface, hertz, accuracy)[0]
    sigma = math.sqrt(surface.m00 * surface.mu)
    tc1s = [ep._tc1(surface, hertz, accuracy, m) for m in materials]
    return nodes, tc1s, sigma, [ep._material_constants(m) for m in materials]


@pytest.mark.parametrize("surface,hertz", [(TABLE1, "exact"), (ALPHA22, "paper")])
def test_shared_build_matches_per_material_builds(surface, hertz):
    """Every column of every material, ψ = 0.05 … 50 (all-elastic to all-plastic), at
    separations over the table's range."""
    mats = [_material(surface, p) for p in PSIS]
    nodes, tc1s, sigma, cons = _inputs(surface, mats, hertz)
    l = surface.l_from_s(np.linspace(-1.0, 6.0, 15))
    shared = build_tables(nodes, tc1s, sigma, cons, "plot", l.min(), l.max())
    for k, psi in enumerate(PSIS):
        one = build_table(nodes, tc1s[k], sigma, cons[k], "plot", l.min(), l.max())
        err = _floored_rel(shared[k].columns(l), one.columns(l))
        assert err.max() <= PAIR, (psi, err)
        assert shared[k].interp_error <= table_settings_for("plot").interp_tol  # its measured bound


def test_shared_build_at_the_table_preset():
    """The "table" preset (bound 1e-11): both builds within it of the truth, so within 2e-11."""
    mats = [_material(TABLE1, p) for p in (0.05, 1.0, 5.0, 50.0)]
    nodes, tc1s, sigma, cons = _inputs(TABLE1, mats, accuracy="table")
    l = TABLE1.l_from_s(np.linspace(-1.0, 6.0, 12))
    shared = build_tables(nodes, tc1s, sigma, cons, "table", l.min(), l.max())
    for k in range(len(mats)):
        one = build_table(nodes, tc1s[k], sigma, cons[k], "table", l.min(), l.max())
        err = _floored_rel(shared[k].columns(l), one.columns(l))
        assert err.max() <= 2e-11, (k, err)


def test_shared_build_mixes_materials_of_every_constant():
    """Materials differing in E*, Y, c_h and ω_p/ω_c share a build (t_c1 ∝ (K_Y Y/E*)², eq. (65));
    each agrees with its own per-material build."""
    base = yield_strength_for_plasticity_index(1.0, TABLE1, E)
    mats = [AsperityMaterial(E, base), AsperityMaterial(0.5 * E, 2.0 * base, wp_over_wc=20.0),
            AsperityMaterial(2.0 * E, 0.3 * base, c_h=2.5), AsperityMaterial(E, 5.0 * base, wp_over_wc=110.0)]
    nodes, tc1s, sigma, cons = _inputs(TABLE1, mats)
    assert shared_scale(tc1s) is not None
    l = TABLE1.l_from_s(np.linspace(-0.5, 4.0, 10))
    shared = build_tables(nodes, tc1s, sigma, cons, "plot", l.min(), l.max())
    for k in range(len(mats)):
        one = build_table(nodes, tc1s[k], sigma, cons[k], "plot", l.min(), l.max())
        err = _floored_rel(shared[k].columns(l), one.columns(l))
        assert err.max() <= PAIR, (k, err)


def test_shared_build_with_the_papers_load_jump():
    """K_v = 0.454 + 0.41ν: the load-jump density at u = β (errata E17) against the per-material build."""
    mats = [AsperityMaterial.with_paper_K_v(E, yield_strength_for_plasticity_index(p, TABLE1, E), 0.3)
            for p in (0.05, 1.0, 5.0, 50.0)]
    nodes, tc1s, sigma, cons = _inputs(TABLE1, mats)
    assert all(c[-1] for c in cons)
    l = TABLE1.l_from_s(np.linspace(-0.5, 4.0, 10))
    shared = build_tables(nodes, tc1s, sigma, cons, "plot", l.min(), l.max())
    for k in range(len(mats)):
        one = build_table(nodes, tc1s[k], sigma, cons[k], "plot", l.min(), l.max())
        a, b = shared[k].columns(l), one.columns(l)
        assert np.all(b[:, 7] > 0.0)
        err = _floored_rel(a, b)
        assert err.max() <= PAIR, (k, err)


def test_api_uses_the_shared_build_and_matches_the_tau_route():
    """route="table" with ≥ SHARED_MIN materials builds them together (one build for all ψ) and
    agrees with the τ route, extreme ψ = 0.05 and 50 included."""
    mats = [_material(TABLE1, p) for p in PSIS]
    assert len(mats) >= ep.SHARED_MIN
    s = np.linspace(-0.5, 4.0, 8)
    ep._TABLES.clear()
    calls = []
    original = ep.build_tables

    def spy(*args, **kwargs):
        calls.append(len(args[1]))
        return original(*args, **kwargs)

    ep.build_tables = spy
    try:
        tab = ep.elastoplastic_contact_many(TABLE1, s, mats, accuracy="plot", validity="off", route="table")
    finally:
        ep.build_tables = original
    assert calls == [len(mats)]
    tau = ep.elastoplastic_contact_many(TABLE1, s, mats, accuracy="plot", validity="off", interpolate_s=False,
                                        route="tau")
    for psi, a, b in zip(PSIS, tab, tau):
        err = _curves_rel(a, b)
        assert max(err.values()) <= PAIR, (psi, err)


def test_materials_that_cannot_share_are_refused():
    mats = [_material(TABLE1, p) for p in (1.0, 2.0)]
    nodes, tc1s, sigma, cons = _inputs(TABLE1, mats)
    bent = [tc1s[0], tc1s[1] * np.linspace(1.0, 1.1, tc1s[1].size)]
    assert shared_scale(bent) is None
    with pytest.raises(ValueError, match="multiples"):
        build_tables(nodes, bent, sigma, cons, "plot", 0.0, 1.0)
    beta = shared_scale(tc1s)
    assert beta[0] == 1.0 and beta[1] == pytest.approx(float(np.median(tc1s[1] / tc1s[0])), rel=1e-15)


@pytest.mark.parametrize("psi,s", [(0.05, 0.5), (50.0, 2.0)])
def test_shared_build_matches_the_slow_twin_coarse(psi, s):
    """The scipy twin (reference_integrals, rtol 1e-6) at the extreme ψ of a sweep."""
    mats = [_material(TABLE1, p) for p in (psi, 1.0, 3.0, 10.0)]
    cur = ep.elastoplastic_contact_many(TABLE1, [s], mats, accuracy="plot", validity="off", route="table")[0]
    ref = reference_integrals(TABLE1, s, mats[0], rtol=1e-6)
    got = np.array([cur.elastic_area_fraction[0], cur.elastoplastic_area_fraction[0], cur.plastic_area_fraction[0],
                    cur.elastic_pressure[0], cur.elastoplastic_pressure[0], cur.plastic_pressure[0], cur.stiffness[0]])
    for k in range(7):
        group = slice(0, 3) if k < 3 else slice(3, 6) if k < 6 else slice(6, 7)
        scale = max(abs(ref[k]), 1e-3 * abs(float(np.sum(ref[group]))))
        assert abs(got[k] - ref[k]) <= 1e-5 * scale, (k, got[k], ref[k])


def test_a_failed_shared_build_falls_back_to_per_material_builds(monkeypatch):
    """A shared build that cannot meet its tolerance raises ArithmeticError; the route then builds
    every material alone (the same numbers as calls with one material each)."""
    mats = [_material(TABLE1, p) for p in (0.5, 1.0, 2.0, 4.0)]

    def fail(*args, **kwargs):
        raise ArithmeticError("v-panels")

    ep._TABLES.clear()
    monkeypatch.setattr(ep, "build_tables", fail)
    got = ep.elastoplastic_contact_many(TABLE1, [0.5, 1.5], mats, accuracy="plot", validity="off", route="table")
    ep._TABLES.clear()
    for m, curve in zip(mats, got):
        one = ep.elastoplastic_contact(TABLE1, [0.5, 1.5], m, accuracy="plot", validity="off", route="table")
        np.testing.assert_array_equal(curve.pressure, one.pressure)
        np.testing.assert_array_equal(curve.stiffness, one.stiffness)
