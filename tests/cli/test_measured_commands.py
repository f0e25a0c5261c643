"""roughcontact moments and roughcontact export: files in, JSON and text out, one-line errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from roughcontact import cli
from roughcontact.cli import measured
from roughcontact.interface.export import FORMATS, parse_table
from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.measure import ESTIMATORS, measure_heights
from roughcontact.statistics.synthetic import synthetic_surface

M = SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0)
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
    assert measured.ESTIMATORS == ESTIMATORS
    assert measured.FORMATS == FORMATS


@pytest.mark.parametrize("suffix", [".npy", ".csv", ".txt"])
def test_moments_of_a_file_equal_the_library(capsys, tmp_path, suffix):
    z = synthetic_surface(M, (64, 96), 0.4, 0.2, seed=2, lay_angle_deg=25.0)
    path = tmp_path / f"map{suffix}"
    if suffix == ".npy":
        np.save(path, z)
    else:
        np.savetxt(path, z, delimiter="," if suffix == ".csv" else " ", fmt="%.17g")
    d = run_json(capsys, "moments", path, "--dx", "0.4", "--dy", "0.2", "--estimator", "fd", "--length-unit", "um")
    ref = measure_heights(z, 0.4, 0.2, estimator="fd")
    for k, v in ref.moments.as_dict().items():
        assert d[k] == pytest.approx(v, rel=1e-12), k
    assert d["lay_angle_deg"] == pytest.approx(ref.lay_angle_deg, rel=1e-12)
    assert d["m11_map"] == pytest.approx(ref.m11_map, rel=1e-12)
    assert d["units"]["m00"] == "um^2" and d["units"]["m40"] == "1/um^2"
    assert d["warnings"] == [] and d["shape"] == [64, 96]
    coarse = measure_heights(z[::2, ::2], 0.8, 0.4, estimator="fd", lay_angle_deg=ref.lay_angle_deg).moments
    assert d["at_twice_the_interval"]["m04"] == pytest.approx(coarse.m04, rel=1e-12)
    assert d["ratio_to_twice_the_interval"]["m04"] == pytest.approx(ref.moments.m04 / coarse.m04, rel=1e-12)
    code, out, err = run(capsys, "moments", path, "--dx", "0.4", "--dy", "0.2")
    assert code == 0 and "lay_angle_deg" in out and "m22_over_sqrt_m40_m04" in out


def test_moments_saves_the_rotated_map(capsys, tmp_path):
    z = synthetic_surface(M, (64, 64), 0.4, 0.4, seed=4, lay_angle_deg=30.0)
    np.save(tmp_path / "z.npy", z)
    d = run_json(capsys, "moments", tmp_path / "z.npy", "--dx", "0.4", "--save-rotated", tmp_path / "r.npy")
    r = np.load(tmp_path / "r.npy")
    assert r.shape == z.shape and np.isnan(r).any() and np.isfinite(r[32, 32])
    assert abs(d["lay_angle_deg"] - 30.0) < 5.0


def test_moments_z_scale(capsys, tmp_path):
    z = synthetic_surface(M, (64, 64), 0.4, 0.2, seed=3)
    np.save(tmp_path / "z.npy", z * 1000.0)  # heights in nm, dx in um
    d = run_json(capsys, "moments", tmp_path / "z.npy", "--dx", "0.4", "--dy", "0.2", "--z-scale", "1e-3")
    assert d["m00"] == pytest.approx(measure_heights(z, 0.4, 0.2).moments.m00, rel=1e-12)


@pytest.mark.parametrize("content, match", [(None, "no such file"), ("1,2,x\n", "not a numeric grid"),
                                            ("1,2,3\n4,5,6\n", "at least 5")])
def test_moments_errors_are_one_line(capsys, tmp_path, content, match):
    path = tmp_path / "bad.csv"
    if content is not None:
        path.write_text(content)
    code, out, err = run(capsys, "moments", path, "--dx", "1")
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and match in err


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
