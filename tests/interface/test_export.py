"""The exported pressure-overclosure tables: parsed back from the text, linear interpolation
between rows is within rtol of the law (direct integration, not the table it was built from) at
every row midpoint; zero-pressure first row; references; units; the friction block."""

import functools

import numpy as np
import pytest

from roughcontact.contact import elastic_contact, elastoplastic_contact, resolve_material
from roughcontact.interface.export import (
    CALCULIX_MAX_ROWS,
    format_table,
    friction_block,
    overclosure_table,
    parse_table,
)
from roughcontact.statistics import SpectralMoments

E_STAR = 1.1274666666666667e5  # N/mm², example 9.1
P0 = 4.9 / 5000.0  # the beam's seating pressure [N/mm²]


def _surface(m00):
    return SpectralMoments(m00, 8e-5, 8e-4, 1.04e-6, 1.04e-4)  # µm


def _law(surface, h, material=None):
    s = np.asarray(h) / surface.height_std
    if material is None:
        return elastic_contact(surface, s, E_STAR).pressure
    return elastoplastic_contact(surface, s, material).pressure


@functools.lru_cache(maxsize=None)
def _seated_table(m00, rtol):
    return overclosure_table(_surface(m00), pressure_range=(1e-4, 100.0), E_star=E_STAR, rtol=rtol,
                             reference="seating", seating_pressure=P0)


@pytest.mark.parametrize("fmt", ["abaqus", "calculix", "csv"])
@pytest.mark.parametrize("m00, rtol", [(0.625, 1e-3), (0.0625, 1e-3), (0.0625, 1e-2)])
def test_rows_within_rtol_at_every_midpoint(fmt, m00, rtol):
    surface = _surface(m00)
    table = _seated_table(m00, rtol)
    text = format_table(table, fmt, length_scale=1e-3)  # µm -> mm
    p, c = parse_table(text)
    c = c * 1e3
    assert p.size == table.n_rows and p[0] == 0.0 and np.all(np.diff(p) > 0) and np.all(np.diff(c) > 0)
    assert p[1] == pytest.approx(1e-4, rel=1e-12) and p[-1] == pytest.approx(100.0, rel=1e-12)
    mid_c, mid_p = 0.5 * (c[1:-1] + c[2:]), 0.5 * (p[1:-1] + p[2:])
    exact = _law(surface, table.h_ref - mid_c)
    err = np.abs(mid_p / exact - 1.0)
    assert err.max() <= rtol, err.max()
    assert err.max() > 0.5 * rtol  # the rows are not wastefully dense
    # rows themselves lie on the law (to the 13 printed digits and the law table's rtol/100)
    np.testing.assert_allclose(p[1:], _law(surface, table.h_ref - c[1:]), rtol=rtol / 50)
    # the seating reference: overclosure 0 at p0
    assert np.interp(0.0, c, p) == pytest.approx(P0, rel=rtol)
    # first row: zero pressure on the tangent at the light end
    k = elastic_contact(surface, (table.h_ref - c[1]) / surface.height_std, E_STAR).stiffness[0]
    assert c[0] == pytest.approx(c[1] - p[1] / k, rel=1e-6)


def test_mean_plane_reference_and_row_count():
    surface = _surface(0.3125)
    table = overclosure_table(surface, pressure_range=(1e-3, 1000.0), E_star=E_STAR, reference="mean-plane")
    # c = -h: the pressure at overclosure -h is W(h)
    h = np.array([0.5, 1.0])
    np.testing.assert_allclose(table.interpolate(-h), _law(surface, h), rtol=1e-3)
    assert table.n_rows < CALCULIX_MAX_ROWS
    with pytest.raises(ValueError, match="more than 20 rows"):
        overclosure_table(surface, pressure_range=(1e-3, 10.0), E_star=E_STAR, reference="mean-plane", max_rows=20)


def test_elastoplastic_law():
    surface = _surface(0.0625)
    material = resolve_material(surface, E_star=E_STAR, psi=0.35)
    table = overclosure_table(surface, pressure_range=(1e-3, 10.0), material=material, rtol=1e-3,
                              reference="seating", seating_pressure=1e-2)
    p, c = parse_table(format_table(table, "abaqus"))
    mid_c, mid_p = 0.5 * (c[1:-1] + c[2:]), 0.5 * (p[1:-1] + p[2:])
    assert np.max(np.abs(mid_p / _law(surface, table.h_ref - mid_c, material) - 1.0)) <= 1e-3


def test_units_and_syntax():
    surface = _surface(0.0625)
    table = overclosure_table(surface, pressure_range=(1e-3, 10.0), E_star=E_STAR, reference="seating",
                              seating_pressure=1e-2)
    text = format_table(table, "calculix", length_scale=1e-3, stress_scale=1e6, length_unit="mm", stress_unit="Pa")
    lines = text.splitlines()
    assert "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR" in lines
    rows = [line for line in lines if not line.startswith("*")]
    assert all(len(f.strip()) <= 20 for line in rows for f in line.split(","))
    p, c = parse_table(text)
    np.testing.assert_allclose(p, table.pressure * 1e6, rtol=1e-12)
    np.testing.assert_allclose(c, table.overclosure * 1e-3, rtol=1e-12)
    csv = format_table(table, "csv").splitlines()
    assert [l for l in csv if not l.startswith("#")][0] == "pressure,overclosure"


def test_friction_block():
    surface = _surface(0.0625)
    table = _seated_table(0.0625, 1e-3)
    kN = elastic_contact(surface, table.h_ref / surface.height_std, E_STAR).stiffness[0]  # N/mm²/µm
    ccx = friction_block(table, "calculix", 0.2, 0.7, length_scale=1e-3)
    mu, slope = (float(v) for v in ccx.splitlines()[-1].split(","))
    assert mu == 0.2 and slope == pytest.approx(0.7 * kN * 1e3, rel=1e-5)  # N/mm³
    abq = friction_block(table, "abaqus", 0.2, 0.7, length_scale=1e-3)
    gamma = float(abq.splitlines()[1].split("=")[1])
    assert gamma == pytest.approx(0.2 * P0 / (0.7 * kN * 1e3), rel=1e-5)  # mm
    text = format_table(table, "calculix", length_scale=1e-3, friction=ccx)
    assert text.rstrip().endswith(ccx.splitlines()[-1])
    assert parse_table(text)[0].size == table.n_rows  # the *FRICTION keyword ends the table


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"pressure_range": (1.0, 0.1)}, "p_min < p_max"),
        ({"pressure_range": (0.0, 1.0)}, "p_min < p_max"),
        ({"rtol": 0.5}, "rtol"),
        ({"reference": "seating"}, "seating pressure"),
        ({"reference": "seating", "seating_pressure": 50.0}, "must lie in"),
        ({"reference": "top"}, "reference"),
        ({"E_star": None}, "exactly one"),
    ],
)
def test_bad_input(kwargs, match):
    args = {"pressure_range": (1e-3, 10.0), "E_star": E_STAR, "reference": "mean-plane", **kwargs}
    with pytest.raises(ValueError, match=match):
        overclosure_table(_surface(0.0625), **args)
