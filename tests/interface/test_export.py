"""The exported pressure-overclosure tables: parsed back from the text, linear interpolation
between rows is within rtol of the law (direct integration, not the table it was built from) at
every row midpoint; zero-pressure first row; references; units; the friction block."""

import functools

import numpy as np
import pytest

from roughcontact.contact import elastic_contact, elastoplastic_contact, resolve_material
from roughcontact.contact.at_pressure import contact_at_pressure
from roughcontact.interface.export import (
    BEYOND_LAST_ROW,
    CALCULIX_MAX_ROWS,
    format_table,
    friction_block,
    length_scale_between,
    overclosure_table,
    parse_table,
    representative_pressure,
    stick_stiffness,
    unit_name,
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
    """k_T = a k_N at the chosen pressure, against the law by direct integration (not the table)."""
    surface = _surface(0.0625)
    table = _seated_table(0.0625, 1e-3)
    kN = elastic_contact(surface, table.h_ref / surface.height_std, E_STAR).stiffness[0]  # N/mm²/µm at p0
    ccx = friction_block(table, "calculix", 0.2, 0.7, kt_at=P0, length_scale=1e-3)
    mu, slope = (float(v) for v in ccx.splitlines()[-1].split(","))
    assert mu == 0.2 and slope == pytest.approx(0.7 * kN * 1e3, rel=1e-5)  # N/mm³
    abq = friction_block(table, "abaqus", 0.2, 0.7, kt_at=P0, length_scale=1e-3)
    gamma = float(next(line for line in abq.splitlines() if "ELASTIC SLIP" in line).split("=")[1])
    assert gamma == pytest.approx(0.2 * P0 / (0.7 * kN * 1e3), rel=1e-5)  # mm
    text = format_table(table, "calculix", length_scale=1e-3, friction=ccx)
    assert text.rstrip().endswith(ccx.splitlines()[-1])
    assert parse_table(text)[0].size == table.n_rows  # the *FRICTION keyword ends the table
    assert all(len(line) <= 132 for line in text.splitlines())  # CalculiX's line length


def test_stick_stiffness_default_and_range():
    """The default pressure of k_T: where k_N(P)² = k_N(p_min) k_N(p_max) (the constant with the
    smallest largest factor error over the range), checked by load control on the law itself;
    the range spans orders of magnitude (the issue: 10.6 N/mm³ at the seating pressure against
    ~6e4 at 10 N/mm²)."""
    surface = _surface(0.0625)
    table = _seated_table(0.0625, 1e-3)
    P = representative_pressure(table)
    k = contact_at_pressure(surface, [1e-4, P, 100.0], E_star=E_STAR).stiffness  # N/mm²/µm
    assert k[1] ** 2 == pytest.approx(k[0] * k[2], rel=1e-5)
    got = stick_stiffness(table, 0.7, length_scale=1e-3)
    assert got["pressure"] == P and got["k_T"] == pytest.approx(0.7 * k[1] * 1e3, rel=1e-5)
    (p_lo, k_lo), (p_hi, k_hi) = got["range"]
    assert (p_lo, p_hi) == (1e-4, 100.0)
    assert k_lo == pytest.approx(0.7 * k[0] * 1e3, rel=1e-5) and k_hi == pytest.approx(0.7 * k[2] * 1e3, rel=1e-5)
    assert got["factor"] == pytest.approx(k[2] / k[0], rel=1e-5) and got["factor"] > 1e3
    at10 = stick_stiffness(table, 0.7, 10.0, length_scale=1e-3)["k_T"]
    at_p0 = stick_stiffness(table, 0.7, P0, length_scale=1e-3)["k_T"]
    assert 1e3 * at_p0 < at10  # the seating pressure's k_T is far below the loaded one
    note = friction_block(table, "calculix", 0.2, 0.7, length_scale=1e-3)
    assert f"{k_lo:.4g}" in note and f"{k_hi:.4g}" in note
    with pytest.raises(ValueError, match="pressure range"):
        stick_stiffness(table, 0.7, 1e3)


@pytest.mark.parametrize("fmt, says", [("calculix", "CalculiX holds the last pressure"),
                                       ("abaqus", "Abaqus continues the last segment's slope"),
                                       ("csv", "CalculiX holds the last pressure, Abaqus continues the last slope")])
def test_header_says_what_each_code_does_beyond_the_last_row(fmt, says):
    text = format_table(_seated_table(0.0625, 1e-2), fmt)
    assert says in text and says in BEYOND_LAST_ROW[fmt] and "extrapolates" not in text


def test_length_scale_between_units():
    assert length_scale_between("um", "mm") == pytest.approx(1e-3, rel=1e-15)
    assert length_scale_between("µm", "m") == pytest.approx(1e-6, rel=1e-15)
    assert length_scale_between("mm", "um", 1e3) == pytest.approx(1e3)
    assert length_scale_between("um", "um") == 1.0
    assert length_scale_between("um", "furlong", 2.0) == 2.0
    with pytest.raises(ValueError, match="contradicts"):
        length_scale_between("um", "mm", 1.0)
    with pytest.raises(ValueError, match="cannot convert"):
        length_scale_between("um", "furlong")


@pytest.mark.parametrize("name", ["mm\n*INCLUDE, INPUT=/etc/passwd", "mm\r*INCLUDE", "mm\u2028*NODE", "\x00",
                                  "*INCLUDE", "", "x" * 41])
def test_unit_names_cannot_smuggle_deck_lines(name):
    with pytest.raises(ValueError, match="unit name"):
        unit_name("--length-unit", name)
    with pytest.raises(ValueError, match="unit name"):
        format_table(_seated_table(0.0625, 1e-2), "abaqus", length_unit=name)


@pytest.mark.parametrize("name", ["mm", "N/mm^2", "µm", "unit of E*", "N mm^-2", "MPa"])
def test_ordinary_unit_names_pass(name):
    assert unit_name("--stress-unit", name) == name


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
