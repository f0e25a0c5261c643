"""roughcontact export: JSON and text out, one-line errors (moments: test_moments_command.py)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from roughcontact import cli
from roughcontact.cli import measured
from roughcontact.interface.export import FORMATS, parse_table

TABLE1 = ["--m00", "0.0625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6", "--m04", "1.04e-4"]


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv):
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


def test_choices_match_library():
    assert measured.FORMATS == FORMATS


@pytest.mark.parametrize("fmt", FORMATS)
def test_export_writes_a_table_that_parses_back(capsys, tmp_path, fmt):
    path = tmp_path / f"table.{fmt}"
    d = run_json(capsys, "export", "--format", fmt, *TABLE1, "--E-star", "1.127e5", "--pressure-range", "1e-3", "10",
                 "--seating-pressure", "1e-2", "--length-scale", "1e-3", "--length-unit", "mm", "-o", path)
    p, c = parse_table(path.read_text())
    np.testing.assert_allclose(np.column_stack([p, c]), np.array(d["table"]), rtol=1e-12)
    assert d["rows"] == p.size and p[0] == 0.0 and d["max_error"] <= 1e-3
    assert d["reference"] == "seating" and d["units"]["overclosure"] == "mm"
    assert (fmt == "csv") == (d["cannot_express"] == [])
    code, out, err = run(capsys, "export", "--format", fmt, *TABLE1, "--E-star", "1.127e5", "--pressure-range",
                         "1e-3", "10")
    assert code == 0 and err == "" and "pressure" in out.lower()


def test_export_elastoplastic_with_friction(capsys):
    d = run_json(capsys, "export", "--format", "calculix", *TABLE1, "--E-star", "1.127e5", "--law", "elastoplastic",
                 "--psi", "0.35", "--pressure-range", "1e-3", "10", "--seating-pressure", "1e-2",
                 "--mu", "0.2", "--kt-over-kn", "0.7")
    assert d["level"] == "elastoplastic" and "*FRICTION" in d["text"]


@pytest.mark.parametrize(
    "extra, match",
    [
        (["--mu", "0.2"], "--kt-over-kn"),
        (["--psi", "0.3"], "elastoplastic"),
        (["--rtol", "1e-5", "--max-rows", "10"], "more than 10 rows"),
        (["--seating-pressure", "100"], "must lie in"),
    ],
)
def test_export_errors_are_one_line(capsys, extra, match):
    code, out, err = run(capsys, "export", "--format", "abaqus", *TABLE1, "--E-star", "1.127e5",
                         "--pressure-range", "1e-3", "10", *extra)
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and match in err, err
