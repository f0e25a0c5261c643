"""The contact commands (issue 29): the text output's unit headers stay apart; --hardness must
lie between Y and E*; --yield-coefficient 0 is one line; a --moments file is read within the
input limits and holds numbers only (`true` is not m00 = 1)."""

from __future__ import annotations

import json
import os
import re

import pytest

from roughcontact.contact.closures import resolve_material
from roughcontact.readers import moments_from_mapping
from roughcontact.statistics import SpectralMoments

FIVE = {"m00": 0.0625, "m20": 0.01, "m02": 0.02, "m40": 0.5, "m04": 1.0}
ARGS = [a for k, v in FIVE.items() for a in (f"--{k}", str(v))]


@pytest.fixture
def um_file(tmp_path):
    path = tmp_path / "um.json"
    path.write_text(json.dumps({**FIVE, "unit": "um"}))
    return path


@pytest.mark.parametrize("command", [["elastic"], ["elastoplastic", "--psi", "0.5"]])
def test_unit_headers_are_separated_and_aligned_with_their_columns(cli_run, um_file, command):
    """Before: '[unit of E*][unit of E* per um]' (16-character columns, 19-character units)."""
    code, out, err = cli_run(*command, "--moments", um_file, "--E-star", "1e5", "--s", "1", "2")
    assert code == 0, err
    names_line, units_line = out.splitlines()[1:3]
    names = names_line.split()
    units = re.findall(r"\[[^\]]*\]", units_line)
    assert len(units) == len(names) and "][" not in units_line, units_line
    assert "[unit of E* per um]" in units and "[um]" in units  # h and k_T in the file's unit
    # right-aligned: every unit ends where its column's name ends, two spaces at least before each
    name_ends = [m.end() for m in re.finditer(r"\S+", names_line)]
    unit_ends = [m.end() for m in re.finditer(r"\[[^\]]*\]", units_line)]
    assert unit_ends == name_ends
    assert all(units_line[m.start() - 2:m.start()] == "  " for m in re.finditer(r"\[", units_line))
    for row in out.splitlines()[3:5]:  # the numbers end there too
        assert [m.end() for m in re.finditer(r"\S+", row)] == name_ends


EP = ["elastoplastic", *ARGS, "--E-star", "1e5", "--s", "3"]


@pytest.mark.parametrize("hardness", ["2e5", "1e5", "1000", "2000"])
def test_hardness_outside_yield_strength_and_E_star_is_refused(cli_run, hardness):
    """Y = 2000 < H < E* = 1e5 (Tabor: H ≈ 2.8 Y; H ≥ E* is no material's): before, accepted."""
    code, out, err = cli_run(*EP, "--yield-strength", "2000", "--hardness", hardness)
    assert code == 2 and len(err.splitlines()) == 1 and out == "", err
    assert f"H = {float(hardness):g}" in err and "Y = 2000" in err and "E* = 100000" in err, err


def test_hardness_between_yield_strength_and_E_star_is_used(cli_json):
    d = cli_json(*EP, "--yield-strength", "2000", "--hardness", "6000")
    assert d["material"]["H"] == 6000.0 and d["material"]["Y"] == 2000.0


def test_hardness_is_checked_against_the_yield_strength_derived_from_psi():
    surface = SpectralMoments(**FIVE)
    y = resolve_material(surface, E_star=1e5, psi=0.5).Y  # Y of the closure yield-from-psi
    with pytest.raises(ValueError, match=f"Y derived from psi = {y:.6g}"):
        resolve_material(surface, E_star=1e5, psi=0.5, H=0.5 * y)
    assert resolve_material(surface, E_star=1e5, psi=0.5, H=1.5 * y).H == 1.5 * y


@pytest.mark.parametrize("closure", [["--psi", "0.5"], ["--yield-strength", "2000"]])
@pytest.mark.parametrize("value", ["0", "-1", "nan", "inf"])
def test_yield_coefficient_must_be_positive(cli_run, closure, value):
    """Before: --psi with --yield-coefficient 0 was a ZeroDivisionError traceback, -1 blamed Y."""
    code, _, err = cli_run(*EP, *closure, "--yield-coefficient", value)
    assert code == 2 and len(err.splitlines()) == 1 and "--yield-coefficient" in err, err


def test_library_refuses_a_zero_yield_coefficient():
    with pytest.raises(ValueError, match="yield_coefficient K_Y"):
        resolve_material(SpectralMoments(**FIVE), E_star=1e5, psi=0.5, yield_coefficient=0.0)


@pytest.mark.parametrize("key, value", [("m00", True), ("m40", False), ("m20", "0.01"), ("m04", None), ("m02", [0.02])])
def test_a_moment_that_is_not_a_number_is_refused_naming_it(cli_run, tmp_path, key, value):
    """Before: `"m00": true` ran as m00 = 1, `"m20": "0.01"` as 0.01."""
    path = tmp_path / "m.json"
    path.write_text(json.dumps({**FIVE, key: value}))
    code, _, err = cli_run("elastic", "--moments", path, "--E-star", "1e5", "--s", "1")
    assert code == 2 and len(err.splitlines()) == 1, err
    assert f"{path}: {key} must be a number" in err, err
    with pytest.raises(ValueError, match=f"{key} must be a number"):
        moments_from_mapping({"moments": {**FIVE, key: value}})


def test_integer_moments_are_numbers():
    assert moments_from_mapping({**FIVE, "m04": 1})[0].m04 == 1.0


def test_a_moments_file_nested_deeply_or_not_a_file_is_one_line(cli_run, tmp_path, monkeypatch):
    deep = tmp_path / "deep.json"
    deep.write_text('{"a": ' * 50_000 + "1" + "}" * 50_000)
    code, _, err = cli_run("elastic", "--moments", deep, "--E-star", "1e5", "--s", "1")
    assert code == 2 and "nested deeper than 64 levels" in err and len(err.splitlines()) == 1, err
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    code, _, err = cli_run("elastic", "--moments", fifo, "--E-star", "1e5", "--s", "1")
    assert code == 2 and "not a regular file" in err, err
    big = tmp_path / "big.json"
    with open(big, "wb") as f:
        f.truncate(3 * 1048576)  # sparse: 3 MB that take no disk
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "2")
    code, _, err = cli_run("elastic", "--moments", big, "--E-star", "1e5", "--s", "1")
    assert code == 2 and "exceed the limit of 2 MB" in err and "ROUGHCONTACT_MAX_INPUT_MB" in err, err
