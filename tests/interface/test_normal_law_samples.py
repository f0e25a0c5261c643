"""NormalLawTable.from_samples (roughcontact.interface.normal_law_samples): a normal law through
given samples — a BEM load ladder — with the statistical table's interpolant and tails, and a
stated error that is an honest (conservative) estimate.

The independent reference: samples of the statistical elastic law itself (Table 1's surface,
E* = 114000 N/mm², contact.elastic_contact), whose value between the samples is known by direct
integration."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from roughcontact.contact import elastic_contact
from roughcontact.contact.at_pressure import contact_at_pressure
from roughcontact.interface import InterfaceLaw, NormalLawTable
from roughcontact.statistics.surface import SpectralMoments

TABLE1 = SpectralMoments(m00=0.0625, m20=8.0e-5, m02=8.0e-4, m40=1.04e-6, m04=1.04e-4)
E_STAR = 114000.0
#: fractions of every sample interval where the table is compared with the law
BETWEEN = np.linspace(0.05, 0.95, 7)


def _elastic(s):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # light and heavy ends beyond the model's quantitative range
        return elastic_contact(TABLE1, s, E_STAR, model="bgk", hertz="exact", validity="off")


def _statistical_samples(per_decade: int, lo=1e-3, hi=10.0):
    """(h, W/A0, K/A0) of the elastic law at per_decade pressures a decade over [lo, hi] N/mm²."""
    target = np.logspace(math.log10(lo), math.log10(hi), round(per_decade * math.log10(hi / lo)) + 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = np.asarray(contact_at_pressure(TABLE1, target, E_star=E_STAR, model="bgk", hertz="exact",
                                           validity="off").s)
    c = _elastic(s)
    return s * TABLE1.height_std, np.asarray(c.pressure), np.asarray(c.stiffness)


def _measured_error(table, h):
    """Largest relative errors of p_N and k_N between the nodes against direct integration."""
    hs = np.sort(h)
    between = (hs[:-1, None] + np.diff(hs)[:, None] * BETWEEN).ravel()
    ref = _elastic(between / TABLE1.height_std)
    p, k = table.evaluate(between)
    return float(np.max(np.abs(p / ref.pressure - 1))), float(np.max(np.abs(k / ref.stiffness - 1)))


def test_the_stated_error_bounds_the_error_against_the_law_and_falls_with_density():
    """5 samples a decade over 1e-3 … 10 N/mm²: the table's p_N and k_N between the samples are
    within its own stated estimate of the statistical law (direct integration); at 3, 5 and 10 a
    decade the error falls with the spacing Δ as about Δ⁵ (p) and Δ⁴ (k), and the estimate
    stays above it (measured: 7e-10, 5e-11, 1e-12 in p; 3e-9, 4e-10, 2e-11 in k; the estimate
    6–55 times the error)."""
    errors = {}
    for per in (3, 5, 10):
        h, p, k = _statistical_samples(per)
        table = NormalLawTable.from_samples(h, p, k, surface=TABLE1, E_star=E_STAR)
        assert table.level == "bem" and table.n_nodes == h.size and table.rtol == max(
            table.max_error_pressure, table.max_error_stiffness)
        err_p, err_k = _measured_error(table, h)
        assert err_p <= table.max_error_pressure and err_k <= table.max_error_stiffness, (per, err_p, err_k)
        errors[per] = (err_p, err_k)
        if per == 5:
            assert table.rtol < 1e-8  # the stated estimate at the brief's density
    for a, b in ((3, 5), (5, 10)):
        order_p = math.log(errors[a][0] / errors[b][0]) / math.log(b / a)
        order_k = math.log(errors[a][1] / errors[b][1]) / math.log(b / a)
        assert order_p > 4.5 and order_k > 3.5, (a, b, order_p, order_k)


def test_the_same_interpolant_as_the_statistical_table():
    """Samples taken at the nodes of an adaptively built table give that very table: the nodes,
    q, q' and the q'' of the three-node quintic are the same (one machinery)."""
    built = NormalLawTable.build(TABLE1, "elastic", E_star=E_STAR, pressure_range=(1e-2, 10.0), accuracy="plot")
    p = np.exp(built.q)
    sampled = NormalLawTable.from_samples(built.h[::-1], p[::-1], (-p * built.dq)[::-1], surface=TABLE1,
                                          E_star=E_STAR)
    np.testing.assert_allclose(sampled.kernel_table, built.kernel_table, rtol=1e-13, atol=0.0)
    h = np.linspace(built.h_min, built.h_light + 0.3, 101)
    for a, b in zip(sampled.evaluate(h), built.evaluate(h)):
        np.testing.assert_allclose(a, b, rtol=1e-12)


def test_outside_the_samples():
    """Light end: the module's tail, p_light z², zero at h_open = h_light + 2/|q'(h_light)|;
    heavy end: ValueError, and InterfaceLaw.extrapolated's tangent for trial states."""
    h, p, k = _statistical_samples(5, 1e-2, 10.0)
    table = NormalLawTable.from_samples(h, p, k, surface=TABLE1, E_star=E_STAR)
    h_light, p_light, k_light = h[0], p[0], k[0]  # the samples run from light to heavy
    assert table.h_open == pytest.approx(h_light + 2 * p_light / k_light, rel=1e-12)
    d = 0.3 * (table.h_open - h_light)
    z = 1 - k_light / p_light * d / 2
    assert table.evaluate(h_light + d)[0] == pytest.approx(p_light * z * z, rel=1e-12)
    assert table.evaluate(table.h_open + 1.0) == (0.0, 0.0)
    with pytest.raises(ValueError, match="below the heavy end"):
        table.evaluate(h[-1] - 1e-3)
    law = InterfaceLaw.from_pressure(table, 1.0, 0.7)
    assert law.p0 == pytest.approx(1.0, rel=1e-12)
    with pytest.raises(ValueError, match="exceeds the heavy end"):
        law.normal(law.u_max + 1e-3)
    p_x, k_x = law.extrapolated().normal(law.u_max + 1e-3)
    assert p_x > table.p_max and k_x > 0.0
    with pytest.raises(ValueError, match="no direct integration"):
        table.direct([h[2]])


def test_noisy_stiffness_is_refused_naming_the_interval():
    """K three times too large at one sample of an exponential law: the interpolant through it
    cannot be proven to fall, and the message says where and why."""
    u0 = 0.08
    p = np.geomspace(0.5, 50.0, 9)
    h = -u0 * np.log(p / 300.0)
    k = p / u0
    NormalLawTable.from_samples(h, p, k, surface=TABLE1, E_star=E_STAR)  # the clean samples make a law
    k[4] *= 3.0
    with pytest.raises(ValueError, match=r"not proven to fall between h = .* too noisy") as err:
        NormalLawTable.from_samples(h, p, k, surface=TABLE1, E_star=E_STAR)
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("change, message", [
    (lambda h, p, k: (h[:4], p[:4], k[:4]), "length >= 5"),
    (lambda h, p, k: (h, p, np.r_[k[:-1], np.nan]), "samples k must be finite"),
    (lambda h, p, k: (h, p[::-1], k), "p must fall as h grows"),
    (lambda h, p, k: (np.r_[h[:-1], h[0]], p, k), "same separation"),
    (lambda h, p, k: (h, -p, k), "positive"),
])
def test_bad_samples(change, message):
    p = np.geomspace(0.5, 50.0, 7)
    h = -0.08 * np.log(p / 300.0)
    with pytest.raises(ValueError, match=message):
        NormalLawTable.from_samples(*change(h, p, p / 0.08), surface=TABLE1, E_star=E_STAR)
    with pytest.raises(ValueError, match="name its source"):
        NormalLawTable.from_samples(h, p, p / 0.08, surface=TABLE1, E_star=E_STAR, level="elastic")
    with pytest.raises(ValueError, match="E_star"):
        NormalLawTable.from_samples(h, p, p / 0.08, surface=TABLE1, E_star=-1.0)
