"""roughcontact export's foot-guns (issue 22): units converted or refused, not silently mixed;
the friction block's k_T at a chosen pressure with its range printed; unit names that cannot
smuggle keyword lines into a deck."""

from __future__ import annotations

import json

import numpy as np
import pytest

from roughcontact import cli
from roughcontact.interface.export import parse_table

TABLE1 = ["--m00", "0.0625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6", "--m04", "1.04e-4"]
BASE = ["export", *TABLE1, "--E-star", "1.127e5", "--pressure-range", "1e-3", "10", "--seating-pressure", "1e-2"]


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def export(capsys, fmt, *extra):
    code, out, err = run(capsys, *BASE, "--format", fmt, *extra, "--json")
    assert code == 0, err
    return json.loads(out)


@pytest.mark.parametrize("fmt", ["calculix", "abaqus", "csv"])
def test_known_units_are_converted(capsys, fmt):
    """Moments in µm (the default --moments-unit) and --length-unit mm: the overclosures come out
    in mm without --length-scale (before: µm numbers in an mm deck, 1000 × too large)."""
    um = export(capsys, fmt)
    mm = export(capsys, fmt, "--length-unit", "mm")
    given = export(capsys, fmt, "--length-unit", "mm", "--length-scale", "1e-3")
    assert um["units"]["overclosure"] == "um" and mm["units"]["overclosure"] == "mm"
    assert mm["length_scale"] == pytest.approx(1e-3, rel=1e-15) and um["length_scale"] == 1.0
    p, c = parse_table(mm["text"])
    np.testing.assert_allclose(c, np.array(um["table"])[:, 1] * 1e-3, rtol=1e-12)
    assert mm["text"] == given["text"]
    nm = export(capsys, fmt, "--moments-unit", "mm", "--length-unit", "um")  # moments in mm, deck in µm
    np.testing.assert_allclose(np.array(nm["table"])[:, 1], np.array(um["table"])[:, 1] * 1e3, rtol=1e-12)
    assert "moments (length unit um)" in um["text"] and "overclosure [mm]" in mm["text"]


@pytest.mark.parametrize("extra, match", [
    (["--length-unit", "mm", "--length-scale", "1"], "contradicts"),       # µm moments, mm deck, scale 1
    (["--length-unit", "mm", "--length-scale", "1e3"], "contradicts"),
    (["--length-unit", "furlong"], "cannot convert"),                      # unknown unit, no scale
    (["--moments-unit", "L", "--length-unit", "mm"], "cannot convert"),    # unknown moments unit
    (["--length-scale", "1e-3"], "--length-scale needs --length-unit"),
    (["--kt-at", "1"], "--kt-at goes with --mu"),
    (["--mu", "0.2", "--kt-over-kn", "0.7", "--kt-at", "100"], "pressure range"),
])
def test_mixed_units_and_bad_friction_options_are_one_line(capsys, extra, match):
    code, out, err = run(capsys, *BASE, "--format", "calculix", *extra)
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and match in err, err


def test_unknown_units_with_a_scale_pass(capsys):
    d = export(capsys, "abaqus", "--moments-unit", "L", "--length-unit", "L'", "--length-scale", "2")
    assert d["length_scale"] == 2.0 and d["units"]["overclosure"] == "L'"


def test_kt_at_a_chosen_pressure_and_the_range(capsys, tmp_path):
    """k_T for *FRICTION was taken at the seating pressure (10.6 N/mm³ where it is ~6e4 at
    10 N/mm²); now at --kt-at P or at the default pressure, with the range of k_T(p) printed."""
    at10 = export(capsys, "calculix", "--length-unit", "mm", "--mu", "0.2", "--kt-over-kn", "0.7", "--kt-at", "10")
    at_p0 = export(capsys, "calculix", "--length-unit", "mm", "--mu", "0.2", "--kt-over-kn", "0.7", "--kt-at", "1e-2")
    default = export(capsys, "calculix", "--length-unit", "mm", "--mu", "0.2", "--kt-over-kn", "0.7")
    f10, f0, fd = at10["friction"], at_p0["friction"], default["friction"]
    assert f10["kt_at"] == 10.0 and f0["kt_at"] == 1e-2 and fd["kt_at_default"] and not f10["kt_at_default"]
    assert f10["k_T"] > 100 * f0["k_T"]  # orders of magnitude apart
    slope = float(at10["text"].rstrip().splitlines()[-1].split(",")[1])
    assert slope == pytest.approx(f10["k_T"], rel=1e-12)
    (p_lo, k_lo), (p_hi, k_hi) = fd["k_T_range"]
    assert (p_lo, p_hi) == (1e-3, 10.0) and k_lo < f0["k_T"] < fd["k_T"] < f10["k_T"] <= k_hi
    assert fd["k_T"] == pytest.approx(np.sqrt(k_lo * k_hi), rel=1e-6)  # the minimax constant
    assert default["units"]["k_T"] == "unit of E*/mm"
    code, out, err = run(capsys, *BASE, "--format", "calculix", "--length-unit", "mm", "--mu", "0.2", "--kt-over-kn",
                         "0.7", "-o", tmp_path / "deck.inp")
    assert code == 0 and "the law's k_T(p) runs from" in out and "default" in out


@pytest.mark.parametrize("option", ["--length-unit", "--stress-unit", "--moments-unit"])
@pytest.mark.parametrize("name", ["mm\n*INCLUDE, INPUT=/etc/passwd", "mm\r\n*INCLUDE, INPUT=/etc/passwd",
                                  "mm\u2028*INCLUDE", "*INCLUDE, INPUT=/etc/passwd", "mm\x1b[2J"])
def test_unit_names_cannot_write_keyword_lines(capsys, option, name):
    """--length-unit $'mm\\n*INCLUDE, INPUT=/etc/passwd' wrote a live *INCLUDE line into the deck."""
    code, out, err = run(capsys, *BASE, "--format", "abaqus", option, name)
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and "unit name" in err and option in err, err
