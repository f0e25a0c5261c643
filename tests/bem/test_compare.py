"""The model at the BEM's loads and the comparison's arithmetic (roughcontact.bem.compare)."""

import math

import numpy as np
import pytest

from roughcontact.asperity.laws import plasticity_index
from roughcontact.bem.compare import (holding_ranges, kappa, ladder_stiffness, model_at_pressures,
                                      plastic_material, richardson, seed_mean)
from roughcontact.contact.at_pressure import contact_at_pressure


def test_model_at_pressures_is_load_control(families):
    m = families["table1"]
    p = [1.0, 10.0, 400.0]
    r = model_at_pressures(m, p, 1.14e5)
    ref = contact_at_pressure(m, p, E_star=1.14e5, model="bgk", hertz="exact", validity="off")
    np.testing.assert_allclose(r.area_fraction, ref.area_fraction, rtol=1e-12)
    np.testing.assert_allclose(r.s, ref.s, rtol=1e-12)
    # Table 1 at s = 2.0: W/A0 = 11.9 N/mm^2 (the paper's anisotropic column, within the model's
    # exact-Hertz offset of ~6 %, expected_verdicts.yaml)
    assert any("A/A0" in w or "separation" in w for w in r.warnings)  # 400 N/mm^2 is outside the range


def test_ladder_stiffness_of_an_exponential_law():
    """p = p0 exp(-g/u0): K = -dp/dg = p/u0 (ln p linear in g: the differences are exact)."""
    u0, p0 = 0.2, 300.0
    p = np.array([1.0, 2.0, 5.0, 10.0, 20.0])
    g = -u0 * np.log(p / p0)
    np.testing.assert_allclose(ladder_stiffness(p, g), p / u0, rtol=1e-12)


def test_ladder_stiffness_second_order_on_a_power_law():
    """p = g^-3 on a ladder of factor 2: within 3 % (the accuracy stated in the docstring)."""
    p = 2.0 ** np.arange(6)
    g = p ** (-1 / 3)
    exact = 3 * p ** (4 / 3)
    assert np.max(np.abs(ladder_stiffness(p, g)[1:-1] / exact[1:-1] - 1)) < 0.03
    # the ends, second-order one-sided: within 5 % on this strongly curved ln p(g) (first-order: 12 %)
    assert np.max(np.abs(ladder_stiffness(p, g)[[0, -1]] / exact[[0, -1]] - 1)) < 0.05


def test_ladder_stiffness_input():
    with pytest.raises(ValueError, match="fall"):
        ladder_stiffness([1.0, 2.0, 3.0], [1.0, 1.0, 0.5])
    with pytest.raises(ValueError, match="length"):
        ladder_stiffness([1.0, 2.0], [1.0, 0.5])


def test_kappa_definition(families):
    m = families["alpha3"]
    assert kappa(0.02, 10.0, 1.14e5, m) == pytest.approx(0.02 * 1.14e5 * math.sqrt(m.m20 + m.m02) / 10.0)


def test_seed_mean():
    mean, sem = seed_mean([[1.0, 2.0], [3.0, 2.0], [2.0, 2.0]])
    np.testing.assert_allclose(mean, [2.0, 2.0])
    np.testing.assert_allclose(sem, [1.0 / math.sqrt(3), 0.0])
    mean, sem = seed_mean([[1.0, 2.0]])
    np.testing.assert_allclose(sem, [0.0, 0.0])


def test_holding_ranges():
    p = [1, 2, 5, 10, 20, 50]
    ratio = [0.7, 0.92, 0.95, 1.08, 1.15, 0.95]
    area = [0.001, 0.002, 0.005, 0.01, 0.02, 0.05]
    r10 = holding_ranges(p, ratio, area, 0.10)
    assert [(r.p_low, r.p_high) for r in r10] == [(2.0, 10.0), (50.0, 50.0)]
    assert r10[0].worst == pytest.approx(0.08) and r10[0].area_high == 0.01
    r20 = holding_ranges(p, ratio, area, 0.20)
    assert [(r.p_low, r.p_high) for r in r20] == [(2.0, 50.0)]
    assert holding_ranges(p, [2.0] * 6, area, 0.1) == []


def test_richardson_recovers_limit_and_order():
    """f(h) = f∞ + c h^p on h, h/2, h/4: the limit and p exactly, per element."""
    limit = np.array([2.0, -1.0, 0.3])
    order = np.array([1.0, 2.0, 1.5])
    c = np.array([0.4, -0.2, 0.05])
    f = [limit + c * h ** order for h in (1.0, 0.5, 0.25)]
    r = richardson(*f)
    np.testing.assert_allclose(r.order, order, rtol=1e-10)
    np.testing.assert_allclose(r.value, limit, rtol=1e-10)
    assert r.extrapolated.all()
    np.testing.assert_allclose(r.error, np.abs(c * 0.25 ** order / limit), rtol=1e-10)
    np.testing.assert_array_equal(r.finest, f[2])


def test_richardson_refuses_oscillation_and_low_order():
    """Non-monotone values, or an order below min_order: the finest value, flagged, with the last
    change as its error; a grid factor of 3 changes p by ln 2/ln 3."""
    r = richardson([1.0, 1.0], [1.1, 0.9], [1.05, 0.85], min_order=0.5)
    assert not r.extrapolated[0] and math.isnan(r.order[0])
    assert r.value[0] == 1.05 and r.error[0] == pytest.approx(0.05 / 1.05)
    # second element: differences 0.1, 0.05 -> p = 1 at ratio 2, but only ln2/ln3 = 0.63 at ratio 3
    assert r.extrapolated[1] and r.value[1] == pytest.approx(0.80)
    r3 = richardson([1.0], [0.9], [0.85], ratio=3.0, min_order=0.7)
    assert not r3.extrapolated[0] and r3.order[0] == pytest.approx(math.log(2) / math.log(3))
    with pytest.raises(ValueError, match="one shape"):
        richardson([1.0, 2.0], [1.0], [1.0])
    with pytest.raises(ValueError, match="finite"):
        richardson([np.nan], [1.0], [1.0])


def test_holding_ranges_of_any_quantity():
    """The 5/10/20 % ranges of made-up model/BEM ratios (gap or stiffness): contiguous runs."""
    p = [1, 2, 5, 10, 20, 50]
    ratio = [0.97, 1.04, 1.08, 0.93, 0.85, 0.6]
    a = [0.001, 0.002, 0.005, 0.01, 0.02, 0.05]
    assert [(r.p_low, r.p_high) for r in holding_ranges(p, ratio, a, 0.05)] == [(1, 2)]
    assert [(r.p_low, r.p_high) for r in holding_ranges(p, ratio, a, 0.10)] == [(1, 10)]
    r20 = holding_ranges(p, ratio, a, 0.20)
    assert [(r.p_low, r.p_high) for r in r20] == [(1, 20)] and r20[0].worst == pytest.approx(0.15)
    assert holding_ranges(p, [1.5] * 6, a, 0.2) == []


@pytest.mark.parametrize("psi", [0.5, 1.0, 5.0])
def test_plastic_material_has_the_index(families, psi):
    m = families["table1"]
    mat = plastic_material(m, 1.14e5, psi)
    assert plasticity_index(m, mat) == pytest.approx(psi, rel=1e-12)
    assert mat.H == pytest.approx(mat.Y / 0.354, rel=1e-12)  # Tabor (68)
    assert mat.c_h == 0.967 and mat.yield_coefficient == 1.62
