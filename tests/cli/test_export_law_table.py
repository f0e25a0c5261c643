"""``roughcontact export --law-table FILE`` (issue 32): the pressure–overclosure table of a BEM law
table instead of the moments, through the same row selection (interface.export.overclosure_table).

The reference: a table file made of samples of the statistical elastic law, whose export from
the moments is known — the rows of the one are the law of the other within the BEM law's stated
error plus rtol."""

from __future__ import annotations

import json
import re
import warnings

import numpy as np
import pytest

from roughcontact.bem.law_table import BEMLawSamples, write_law_table
from roughcontact.contact import elastic_contact
from roughcontact.contact.at_pressure import contact_at_pressure
from roughcontact.interface import NormalLawTable
from roughcontact.interface.export import parse_table
from roughcontact.statistics.surface import SpectralMoments

TABLE1 = SpectralMoments(m00=0.0625, m20=8.0e-5, m02=8.0e-4, m40=1.04e-6, m04=1.04e-4)
MOMENTS = ["--m00", "0.0625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6", "--m04", "1.04e-4"]
E_STAR = 114000.0


@pytest.fixture(scope="module")
def table_file(tmp_path_factory):
    target = np.geomspace(1e-3, 100.0, 26)  # 5 a decade
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = np.asarray(contact_at_pressure(TABLE1, target, E_star=E_STAR, model="bgk", hertz="exact",
                                           validity="off").s)
        c = elastic_contact(TABLE1, s, E_STAR, model="bgk", hertz="exact", validity="off")
    samples = BEMLawSamples(pressure=c.pressure, mean_gap=s * TABLE1.height_std, stiffness=c.stiffness,
                            area_fraction=c.area_fraction, length_unit="um", E_star=E_STAR, periodic=True,
                            moments=TABLE1, lay_angle_deg=0.0, source={"file": "statistical law"}, solver={},
                            stiffness_method="exact, eq. (55)")
    path = tmp_path_factory.mktemp("export") / "law.json"
    write_law_table(path, samples)
    return path


def test_the_bem_export_is_the_law_of_the_table(table_file, cli_json):
    """Every row of the CSV from --law-table (0.01 … 50 N/mm², rtol 1e-3, seated at 1 N/mm², in
    mm) lies on the statistical law within the table file's stated error; the piecewise-linear
    table is within rtol of it between the rows (the export's own check, max_error)."""
    out = cli_json("export", "--law-table", table_file, "--format", "csv", "--pressure-range", "0.01", "50",
                   "--seating-pressure", "1", "--length-unit", "mm", "--stress-unit", "N/mm^2")
    assert out["law"] == "bem" and out["level"] == "bem" and out["moments_unit"] == "um" and out["E_star"] == E_STAR
    assert out["max_error"] <= 1e-3 and out["law_table"]["samples"] == 26
    stated = max(out["law_table"]["error_estimate"].values())
    assert stated < 1e-6
    p, c_mm = parse_table(out["text"])
    law = NormalLawTable.build(TABLE1, "elastic", E_star=E_STAR, pressure_range=(1e-3, 100.0))
    h_ref = law.separation_at(1.0)
    assert out["h_ref"] == pytest.approx(h_ref, rel=stated)
    rows = p > 0
    exact = law.evaluate(h_ref - 1e3 * c_mm[rows])[0]
    np.testing.assert_allclose(p[rows], exact, rtol=2 * stated + 1e-6)
    moments = cli_json("export", *MOMENTS, "--E-star", E_STAR, "--format", "csv", "--pressure-range", "0.01", "50",
                       "--seating-pressure", "1", "--length-unit", "mm", "--stress-unit", "N/mm^2")
    assert abs(out["rows"] - moments["rows"]) <= 2  # the same row selection on (almost) the same law


def test_calculix_with_friction_and_the_rendered_summary(table_file, cli_run, tmp_path):
    code, out, err = cli_run("export", "--law-table", table_file, "--format", "calculix", "--pressure-range",
                             "0.001", "100", "--seating-pressure", "0.1", "--mu", "0.3", "--kt-over-kn", "0.7",
                             "--E-star", "114500", "-o", tmp_path / "t.inp")
    assert code == 0, err
    assert "the BEM law of" in out and "adds to rtol" in out
    text = (tmp_path / "t.inp").read_text()
    assert "bem law, E* = 114000" in text and "*FRICTION" in text


@pytest.mark.parametrize("extra, message", [
    (["--m00", "0.0625"], "--law-table replaces the moments and the statistical law: drop --m00"),
    (["--law", "elastoplastic"], "drop --law"),
    (["--E-star", "1"], r"E\* = 1 differs from the table's 114000"),
    (["--moments-unit", "mm"], "--moments-unit mm contradicts the table's length unit um"),
])
def test_bad_combinations(table_file, cli_run, extra, message):
    code, out, err = cli_run("export", "--law-table", table_file, "--format", "csv", "--pressure-range", "0.01",
                             "10", *extra)
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert re.search(message, err), err


def test_the_range_is_the_ladders(table_file, cli_run, tmp_path):
    code, _, err = cli_run("export", "--law-table", table_file, "--format", "csv", "--pressure-range", "0.01", "1000")
    assert code == 2 and "reaches beyond the BEM table's pressures 0.001 ... 100" in err
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"format": "roughcontact.bem-law-table"}))
    code, _, err = cli_run("export", "--law-table", bad, "--format", "csv", "--pressure-range", "0.01", "1")
    assert code == 2 and f"--law-table: BEM law table {bad}" in err
    code, _, err = cli_run("export", *MOMENTS, "--format", "csv", "--pressure-range", "0.01", "1")
    assert code == 2 and "one of the arguments --E-star --E1 is required (or --law-table FILE)" in err
