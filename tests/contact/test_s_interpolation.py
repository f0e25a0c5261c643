"""Curves over s from a verified Chebyshev interpolant (contact/s_interpolation.py): exact for
polynomials, verified against direct evaluation between the nodes, falls back to direct
evaluation when it cannot verify, and elasto-plastic curves stay within the preset's bound."""

import math
from dataclasses import replace

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact import asperity as asp
from roughcontact.contact.elastoplastic import S_RTOL, elastoplastic_contact
from roughcontact.contact.s_interpolation import barycentric, interpolated_columns, lobatto_nodes
from roughcontact.contact.sweep import SweepSpec, combine, run_sweep, split

E_STAR = 1.14e5
FIG = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
FIELDS = ("area_fraction", "pressure", "stiffness", "elastic_area_fraction", "elastoplastic_area_fraction",
          "plastic_area_fraction", "elastic_pressure", "elastoplastic_pressure", "plastic_pressure")


def test_barycentric_reproduces_polynomials_and_hits_nodes():
    nodes = lobatto_nodes(-1.0, 6.0, 16)
    p = np.polynomial.Polynomial([0.3, -1.0, 0.2, 0.05, -0.01])
    values = np.column_stack([p(nodes), np.cos(nodes)])
    s = np.concatenate([np.linspace(-1.0, 6.0, 101), nodes[3:5]])
    out = barycentric(nodes, values, s)
    assert np.max(np.abs(out[:, 0] - p(s))) <= 1e-13 * np.max(np.abs(p(s)))
    assert np.array_equal(out[-2:], values[3:5])  # at a node: the node's value


def test_smooth_curve_is_interpolated_within_the_measured_bound():
    calls = []

    def model(s):
        calls.append(s.size)
        a = np.exp(-0.5 * s**2) * (1.5 + 0.2 * s)  # positive: interpolated in ln
        return np.column_stack([a, 0.3 * a, 0.7 * a, -a])  # a negative column too

    s = np.linspace(-1.0, 6.0, 400)
    cols, how = interpolated_columns(model, s, 1e-10, ((1, 2), (1, 2), (1, 2), (3,)))
    exact = model(s)
    assert how.method == "chebyshev" and how.error <= 1e-10
    assert np.max(np.abs(cols / exact - 1.0)) <= 1e-10
    assert sum(calls[:-1]) == how.nodes <= 65  # the nodes, not the 400 points


def test_not_verified_or_few_points_means_every_point_direct():
    def model(s):
        return np.column_stack([np.abs(s - 0.1234) + 1.0])  # a kink: no polynomial verifies to 1e-12

    s = np.linspace(-1.0, 1.0, 60)
    cols, how = interpolated_columns(model, s, 1e-12, ((0,),))
    assert how.method == "direct" and np.array_equal(cols, model(s))
    cols, how = interpolated_columns(model, s[:20], 1e-12, ((0,),))
    assert how.method == "direct" and how.nodes == 20


@pytest.mark.parametrize("psi, preset, s", [
    (1.0, "plot", np.linspace(0.5, 3.5, 60)),
    pytest.param(5.0, "plot", np.linspace(-1.0, 6.0, 200), marks=pytest.mark.slow),
    pytest.param(1.0, "table", np.linspace(-1.0, 6.0, 120), marks=pytest.mark.slow),
])
def test_elastoplastic_curve_within_the_preset_bound_of_direct_evaluation(psi, preset, s):
    """Measured: ≤ 1.1e-10 ("plot", 65 of 200 points evaluated) and ≤ 2e-14 ("table") against
    evaluating every point; the check asks for a tenth of the preset's bound (S_RTOL)."""
    mat = asp.AsperityMaterial(E_STAR, asp.yield_strength_for_plasticity_index(psi, FIG, E_STAR))
    # the figures' range: psi = 5 passes A/A0 = 1 near s = -1 (warned, not refused, as sweeps do)
    curve = elastoplastic_contact(FIG, s, mat, accuracy=preset, validity="warn")
    direct = elastoplastic_contact(FIG, s, mat, accuracy=preset, interpolate_s=False, validity="warn")
    how = curve.interpolation
    assert how.method == "chebyshev" and how.nodes < s.size and how.error <= S_RTOL[preset]
    bound = {"plot": 1e-8, "table": 1e-11}[preset]
    for f in FIELDS:
        a, d = getattr(curve, f), getattr(direct, f)
        total = direct.area_fraction if "area" in f else direct.pressure if "pressure" in f else direct.stiffness
        assert np.all(np.abs(a - d) <= bound * np.maximum(np.abs(d), 1e-3 * np.abs(total))), f
    attrs = curve.to_dataset().attrs
    assert attrs["s_interpolation"] == "chebyshev" and attrs["s_interpolation_error"] == how.error
    assert direct.interpolation.method == "direct" and math.isnan(direct.interpolation.error)


def test_sweep_states_the_interpolation_in_its_attributes():
    spec = SweepSpec(axes={"psi": [0.5]}, s=np.linspace(0.0, 4.0, 60),
                     fixed=dict(m00=0.0625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4, E_star=E_STAR),
                     with_elastic=False)
    ds = run_sweep(spec)
    assert ds.attrs["s_interpolation"] == "chebyshev"
    assert 0.0 <= ds.attrs["s_interpolation_error"] <= ds.attrs["s_interpolation_rtol"] == S_RTOL["plot"]
    assert ds.attrs["s_interpolation_nodes"] < 60
    pieces = [run_sweep(p) for p in split(replace(spec, axes={"psi": [0.5, 2.0]}), "psi", 2)]
    joined = combine(pieces, "psi")  # the whole sweep's attributes, not the first piece's
    assert joined.attrs["s_interpolation"] == "chebyshev"
    assert joined.attrs["s_interpolation_nodes"] == sum(p.attrs["s_interpolation_nodes"] for p in pieces)
    assert joined.attrs["s_interpolation_error"] == max(p.attrs["s_interpolation_error"] for p in pieces)


def test_bad_s_rtol_raises():
    mat = asp.AsperityMaterial(E_STAR, asp.yield_strength_for_plasticity_index(1.0, FIG, E_STAR))
    with pytest.raises(ValueError, match="s_rtol"):
        elastoplastic_contact(FIG, [1.0], mat, s_rtol=0.0)
