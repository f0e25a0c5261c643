"""The BEM law table file (roughcontact.bem.law_table): the shared contract of issue 32 written and
read back exactly, every bad input one line naming the file, bounded reads, atomic writes."""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest

from roughcontact.bem.law_table import (FORMAT, BEMLawSamples, law_table_dict, normal_law_table, read_law_table,
                                        write_law_table)
from roughcontact.statistics.surface import SpectralMoments

TABLE1 = SpectralMoments(m00=0.0625, m20=8.0e-5, m02=8.0e-4, m40=1.04e-6, m04=1.04e-4)


def _samples(**changes) -> BEMLawSamples:
    """An exponential law p = p0 exp(−ḡ/u0) (Persson 2007: ln p linear in ḡ), K = p/u0 exactly."""
    p = np.array([0.5, 1.0, 2.0, 5.0, 10.0, 20.0])
    u0, p0 = 0.08, 300.0
    g = -u0 * np.log(p / p0)
    kw = dict(pressure=p, mean_gap=g, stiffness=p / u0, area_fraction=np.linspace(0.001, 0.02, p.size),
              length_unit="um", E_star=114000.0, periodic=True, moments=TABLE1, lay_angle_deg=12.5,
              source={"file": "scan.gsf", "sha256": "ab" * 32, "shape": [256, 256], "dx": 0.5, "dy": 0.5},
              solver={"pentol": 1e-4, "method": "ccg"}, stiffness_method="central differences, ±5 % in p")
    kw.update(changes)
    return BEMLawSamples(**kw)


def test_round_trip_is_exact(tmp_path):
    s = _samples(stress_unit="N/mm^2")
    write_law_table(tmp_path / "law.json", s, provenance={"command": "roughcontact bem scan.gsf"})
    data = json.loads((tmp_path / "law.json").read_text())
    assert data["format"] == FORMAT and data["version"] == 1 and data["moments"]["unit"] == "um"
    assert data["provenance"] == {"command": "roughcontact bem scan.gsf"} and data["stress_unit"] == "N/mm^2"
    r = read_law_table(tmp_path / "law.json")
    for name in ("pressure", "mean_gap", "stiffness", "area_fraction"):
        np.testing.assert_array_equal(getattr(r, name), getattr(s, name))  # JSON floats round-trip exactly
    assert r.moments == TABLE1 and r.E_star == 114000.0 and r.periodic is True and r.lay_angle_deg == 12.5
    assert r.source == s.source and r.solver == s.solver and r.stiffness_method == s.stiffness_method
    assert r.length_unit == "um" and r.stress_unit == "N/mm^2"
    # numpy scalars in the free-form mappings are written as plain numbers
    write_law_table(tmp_path / "np.json", _samples(solver={"pentol": np.float64(1e-4), "n": np.int64(3)}))
    assert read_law_table(tmp_path / "np.json").solver == {"pentol": 1e-4, "n": 3}


@pytest.mark.parametrize("change, message", [
    (lambda d: d.update(format="something"), "format must be 'roughcontact.bem-law-table'"),
    (lambda d: d.update(version=2), "version 2 is not read here"),
    (lambda d: d.pop("stiffness"), "missing key 'stiffness'"),
    (lambda d: d.update(colour="red"), "unknown key 'colour'"),
    (lambda d: d["pressure"].__setitem__(2, d["pressure"][1]), r"strictly increasing: pressure\[2\]"),
    (lambda d: d["pressure"].__setitem__(0, -1.0), r"positive and strictly increasing: pressure\[0\]"),
    (lambda d: d["mean_gap"].__setitem__(3, 5.0), r"mean_gap must fall strictly .*mean_gap\[3\]"),
    (lambda d: d["stiffness"].__setitem__(1, 0.0), r"stiffness must be positive: stiffness\[1\]"),
    (lambda d: d["stiffness"].__setitem__(1, None), r"stiffness\[1\] is not finite"),
    (lambda d: d["area_fraction"].__setitem__(0, 1.5), r"area_fraction\[0\]"),
    (lambda d: d.update(pressure=d["pressure"][:2]), "one length >= 3"),
    (lambda d: d.update(length_unit="furlong"), "length_unit must be one of m, mm, um, nm"),
    (lambda d: d["moments"].update(unit="mm"), "moments.unit 'mm' differs from length_unit 'um'"),
    (lambda d: d["moments"].update(m40=-1.0), "m40 must be positive"),
    (lambda d: d["moments"].pop("m04"), "moments lack m04"),
    (lambda d: d.update(E_star=0), "E_star must be a positive finite number"),
    (lambda d: d.update(E_star="114000"), "E_star must be a positive finite number"),
    (lambda d: d.update(periodic="yes"), "periodic must be true or false"),
    (lambda d: d.update(source=[1]), "source must be a mapping"),
    (lambda d: d.update(stiffness_method=""), "stiffness_method must say how K was obtained"),
    (lambda d: d.update(stress_unit="N/mm^2\n*INCLUDE"), "stress_unit must be null or a unit name"),
    (lambda d: d.update(provenance=3), "provenance must be a mapping or null"),
])
def test_bad_tables_are_one_line_naming_the_file(tmp_path, change, message):
    d = law_table_dict(_samples())
    change(d)
    path = tmp_path / "law.json"
    path.write_text(json.dumps(d))
    with pytest.raises(ValueError, match=message) as err:
        read_law_table(path)
    text = str(err.value)
    assert text.startswith(f"BEM law table {path}: ") and "\n" not in text and len(text) < 400


def test_micrometre_spellings_are_normalised(tmp_path):
    d = law_table_dict(_samples())
    d["length_unit"] = d["moments"]["unit"] = "µm"
    (tmp_path / "law.json").write_text(json.dumps(d))
    assert read_law_table(tmp_path / "law.json").length_unit == "um"


def test_reads_are_bounded(tmp_path, monkeypatch):
    with pytest.raises(ValueError, match="not a regular file|regular"):
        read_law_table("/dev/zero")
    (tmp_path / "nan.json").write_text('{"E_star": NaN}')
    with pytest.raises(ValueError, match="NaN is not JSON"):
        read_law_table(tmp_path / "nan.json")
    (tmp_path / "deep.json").write_text("[" * 100 + "]" * 100)
    with pytest.raises(ValueError, match="nested deeper"):
        read_law_table(tmp_path / "deep.json")
    write_law_table(tmp_path / "ok.json", _samples())
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", str(10 / 2**20))  # 10 bytes
    with pytest.raises(ValueError, match="ROUGHCONTACT_MAX_INPUT_MB"):
        read_law_table(tmp_path / "ok.json")
    with pytest.raises(ValueError, match="BEM law table"):
        read_law_table(tmp_path / "missing.json")


def test_writes_are_atomic(tmp_path):
    path = tmp_path / "law.json"
    write_law_table(path, _samples())
    before = path.read_bytes()
    with pytest.raises(TypeError):  # not samples: nothing written, the old file kept whole
        write_law_table(path, {"pressure": [1, 2, 3]})
    with pytest.raises(ValueError, match="provenance"):
        write_law_table(path, _samples(), provenance=[1])
    assert path.read_bytes() == before and os.listdir(tmp_path) == ["law.json"]
    if os.geteuid() != 0:
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o500)
        try:
            with pytest.raises(OSError):
                write_law_table(ro / "law.json", _samples())
            assert os.listdir(ro) == []
        finally:
            ro.chmod(0o700)


def test_the_samples_make_the_interface_law():
    """p = p0 exp(−ḡ/u0) is ln p linear in ḡ: the quintic through it is exact, so the law
    between the samples is the closed form to rounding, and a stress factor scales p, K and E*."""
    s = _samples()
    law = normal_law_table(s)
    assert law.level == "bem" and law.surface == TABLE1 and law.E_star == 114000.0
    g = np.linspace(s.mean_gap[-1], s.mean_gap[0], 37)
    p, k = law.evaluate(g)
    exact = 300.0 * np.exp(-g / 0.08)
    np.testing.assert_allclose(p, exact, rtol=1e-12)
    np.testing.assert_allclose(k, exact / 0.08, rtol=1e-12)
    assert law.max_error_pressure < 1e-12 and law.max_error_stiffness < 1e-12
    pa = normal_law_table(s, stress_factor=1e6)  # N/mm² → Pa
    assert pa.E_star == 1.14e11 and math.isclose(pa.evaluate(g[5])[0], 1e6 * p[5], rel_tol=1e-12)
    with pytest.raises(ValueError, match="stress_factor"):
        normal_law_table(s, stress_factor=0.0)
