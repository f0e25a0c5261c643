"""roughcontact export (issue 29): every row checked before anything is written (a non-finite one:
exit 1 naming it, nothing under -o); a --moments-unit that contradicts the moments file refused;
the k_T(p) note only where a *FRICTION block is written, naming the pressure of k_T."""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest

from roughcontact.interface.export import NonFiniteTableError, format_table, overclosure_table, parse_table
from roughcontact.statistics import SpectralMoments

UM = {"m00": 0.0625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}
TABLE1 = [a for k, v in UM.items() for a in (f"--{k}", str(v))]
LAW = ["--E-star", "1.127e5", "--pressure-range", "1e-3", "10"]


@pytest.mark.parametrize("fmt, extra", [("calculix", []), ("abaqus", []), ("csv", []),
                                        ("abaqus", ["--mu", "0.1", "--kt-over-kn", "0.8"])])
def test_a_non_finite_row_writes_nothing(cli_run, tmp_path, fmt, extra):
    """--stress-scale 1e308 overflows the pressures of the upper rows: before, t.inp was written with
    `inf` rows and the command then failed (exit 1)."""
    out = tmp_path / "t.inp"
    out.write_text("the deck of an earlier run\n")
    code, stdout, err = cli_run("export", *TABLE1, *LAW, "--format", fmt, "--stress-scale", "1e308", *extra, "-o", out)
    assert code == 1 and stdout == "" and len(err.splitlines()) == 1, err
    assert "is not finite" in err and f"-o {out} not written" in err, err
    assert out.read_text() == "the deck of an earlier run\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.inp"]  # no .part left


def test_the_first_non_finite_row_is_named_with_its_pressure():
    """The row named is the first whose pressure times the scale exceeds the largest double."""
    table = overclosure_table(SpectralMoments(**UM), pressure_range=(1e-3, 10.0), E_star=1.127e5,
                              reference="mean-plane")
    scale = 1e308 / 2.0  # p * scale is finite up to p = float max / scale = 3.595...
    first = int(np.argmax(table.pressure > sys.float_info.max / scale)) + 1
    with pytest.raises(NonFiniteTableError, match=rf"^row {first} of {table.n_rows} is not finite: pressure inf = "
                                                  rf"{table.pressure[first - 1]:.6g} \(unit of E\*\)"):
        format_table(table, "calculix", stress_scale=scale)
    assert isinstance(NonFiniteTableError("x"), ValueError)
    p, _ = parse_table(format_table(table, "calculix", stress_scale=1e300))  # large but finite: written
    assert p[-1] == pytest.approx(10.0 * 1e300, rel=1e-12)


def _nm_file(tmp_path):
    """The moments of UM in nm (m00·1e6 nm², m40·1e-6 nm⁻²), stating their unit."""
    nm = {"m00": UM["m00"] * 1e6, "m20": UM["m20"], "m02": UM["m02"], "m40": UM["m40"] * 1e-6,
          "m04": UM["m04"] * 1e-6, "unit": "nm"}
    path = tmp_path / "nm.json"
    path.write_text(json.dumps(nm))
    return path


def test_moments_unit_contradicting_the_file_is_refused(cli_run, tmp_path):
    """Before: the file's nm were used and --moments-unit um silently ignored."""
    path = _nm_file(tmp_path)
    code, out, err = cli_run("export", "--moments", path, *LAW, "--format", "csv", "--moments-unit", "um")
    assert code == 2 and out == "" and len(err.splitlines()) == 1, err
    assert "--moments-unit um" in err and f"{path}, whose moments are in nm" in err, err
    code, _, err = cli_run("export", "--moments", path, *LAW, "--format", "csv", "--moments-unit", "parsec")
    assert code == 2 and "--moments-unit: unknown length unit" in err, err


def test_moments_unit_agreeing_with_the_file_or_absent_uses_the_file(cli_json, tmp_path):
    path = _nm_file(tmp_path)
    same = cli_json("export", "--moments", path, *LAW, "--format", "csv", "--moments-unit", "nanometre")
    absent = cli_json("export", "--moments", path, *LAW, "--format", "csv", "--length-unit", "um")
    by_flags = cli_json("export", *TABLE1, *LAW, "--format", "csv")  # µm, the default --moments-unit
    assert same["moments_unit"] == "nm" and absent["moments_unit"] == "nm" and by_flags["moments_unit"] == "um"
    # the same surface: the nm table, converted to µm, is the µm table
    assert np.array(absent["table"]) == pytest.approx(np.array(by_flags["table"]), rel=1e-9)
    assert np.array(same["table"])[:, 1] == pytest.approx(1e3 * np.array(by_flags["table"])[:, 1], rel=1e-9)


@pytest.mark.parametrize("fmt", ["calculix", "abaqus"])
def test_kt_note_only_with_friction_naming_its_pressure(cli_run, tmp_path, fmt):
    base = ["export", *TABLE1, *LAW, "--format", fmt, "-o", tmp_path / "t.inp"]
    code, out, err = cli_run(*base)
    assert code == 0, err
    notes = [line for line in out.splitlines() if line.startswith("not expressed:")]
    assert notes and not any("k_T" in n for n in notes), notes  # before: "k_T(p) ... (k_T(p0))" without --mu
    code, out, err = cli_run(*base, "--mu", "0.1", "--kt-over-kn", "0.8", "--kt-at", "0.5")
    assert code == 0, err
    kt = [line for line in out.splitlines() if line.startswith("not expressed: k_T(p)")]
    assert len(kt) == 1 and "p = 0.5, from --kt-at" in kt[0] and "p0" not in kt[0], kt
    code, out, err = cli_run(*base, "--mu", "0.1", "--kt-over-kn", "0.8", "--json")
    d = json.loads(out)
    p = d["friction"]["kt_at"]
    assert any(f"p = {p:.6g}, the default" in n for n in d["cannot_express"]), d["cannot_express"]
