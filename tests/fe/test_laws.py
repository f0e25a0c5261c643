"""LAW.yaml (roughcontact.fe.laws): the issue's schema read as written, its alternatives, unit
conversions, and a clear error for every bad law naming the file and the key."""

from __future__ import annotations

import json

import pytest
import yaml

from roughcontact.fe.laws import (
    Coulomb, LawError, NoFriction, Orthotropic, Stick, law_file_from_dict, read_law_file,
)
from roughcontact.interface import friction

#: the issue's example, verbatim (comments included)
ISSUE = """\
length_unit: mm            # the deck's length unit; forces in N, stresses in N/mm^2 (say how others work)
interactions:
  ROUGH:                   # a *SURFACE INTERACTION name of the deck
    moments: {m00: 0.0625, m20: 8.0e-5, m02: 8.0e-4, m40: 1.04e-6, m04: 1.04e-4, unit: um}
    lay_direction: [1, 0, 0]       # the moments' x axis (along the lay) in the deck's axes
    E_star: 78065.86               # optional: else from the two bodies' *ELASTIC (eq. 42)
    law: elastic                   # or elastoplastic, with psi or yield_strength
    seating_pressure: 1.0e-3       # relative displacements are measured from this state
    friction: none                 # or {coulomb: {mu: 0.2, kt_over_kn: 0.7}}
                                   # or {orthotropic: {mu_m: 0.5, mu_o: 0.5, nu_x: 0.125, nu_y: 0.125,
                                   #     n_x: 275, n_y: 275, kt_over_kn: [0.7, 1.0]}}  (n in 1/length_unit)
"""


def test_the_issues_example_reads_as_written(tmp_path):
    (tmp_path / "law.yaml").write_text(ISSUE)
    f = read_law_file(tmp_path / "law.yaml")
    law = f.interactions["ROUGH"]
    assert f.length_unit == "mm" and law.moments_unit == "um" and law.moments.m00 == 0.0625
    assert law.lay_direction == (1.0, 0.0, 0.0) and law.E_star == 78065.86 and law.law == "elastic"
    assert law.seating_pressure == 1e-3 and law.friction == NoFriction() and law.law_per_deck("mm") == 1000.0


def test_the_issues_friction_alternatives(tmp_path):
    d = yaml.safe_load(ISSUE)
    body = d["interactions"]["ROUGH"]
    body["friction"] = {"coulomb": {"mu": 0.2, "kt_over_kn": 0.7}}
    c = law_file_from_dict(d).interactions["ROUGH"].friction
    assert c == Coulomb(0.2, (0.7, 0.7)) and c.model(1000.0) == friction.IsotropicHardening(mu_m=0.2)
    body["friction"] = {"orthotropic": {"mu_m": 0.5, "mu_o": 0.5, "nu_x": 0.125, "nu_y": 0.125, "n_x": 275,
                                        "n_y": 275, "kt_over_kn": [0.7, 1.0]}}
    o = law_file_from_dict(d).interactions["ROUGH"].friction
    assert isinstance(o, Orthotropic) and o.factors() == (0.7, 1.0) and o.k == 0.0
    # n in 1/length_unit: 275 1/mm is 0.275 1/um in the law's unit (Fig. 18's cases)
    assert o.model(1000.0) == friction.OrthotropicHardening(0.5, 0.5, 0.5, 0.5, 0.275, 0.275, k=0.0)
    body["friction"] = {"stick": {"kt_over_kn": [0.8, 0.9]}}
    assert law_file_from_dict(d).interactions["ROUGH"].friction == Stick((0.8, 0.9))


def test_round_trip_and_other_units(tmp_path):
    d = yaml.safe_load(ISSUE)
    d["length_unit"] = "m"
    d["interactions"]["rough"] = d["interactions"].pop("ROUGH")  # names are case-insensitive
    d["interactions"]["rough"].update(law="elastoplastic", psi=0.5, pressure_range=[1e-6, 1e3],
                                      tangential_form="secant")
    f = law_file_from_dict(d)
    law = f.interactions["ROUGH"]
    assert law.law_per_deck("m") == 1e6 and law.pressure_range == (1e-6, 1e3)
    again = law_file_from_dict(yaml.safe_load(f.to_yaml()))
    assert again == f


def test_moments_from_a_moments_json_file(tmp_path):
    """`roughcontact moments --json` output (top-level m00 ... m04, the length unit in units.dx)."""
    (tmp_path / "m.json").write_text(json.dumps({"m00": 0.0625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6,
                                                 "m04": 1.04e-4, "units": {"dx": "um"}}))
    d = yaml.safe_load(ISSUE)
    d["interactions"]["ROUGH"]["moments"] = "m.json"
    law = law_file_from_dict(d, "law.yaml", tmp_path).interactions["ROUGH"]
    assert law.moments.m04 == 1.04e-4 and law.moments_unit == "um"
    (tmp_path / "n.json").write_text(json.dumps({"m00": 1.0, "units": {"dx": "L"}}))
    d["interactions"]["ROUGH"]["moments"] = "n.json"
    with pytest.raises(LawError, match="does not state its length unit"):
        law_file_from_dict(d, "law.yaml", tmp_path)


@pytest.mark.parametrize("change, message", [
    (lambda b: b["moments"].update(m40=-1e-6), "invalid moments: m40 must be positive"),  # invalid moments
    (lambda b: b["moments"].update(m00=0.0), "invalid moments"),
    (lambda b: b["moments"].pop("unit"), "missing key 'unit'"),
    (lambda b: b["moments"].update(unit="inch"), "moments.unit"),
    (lambda b: b.update(law="plastic"), "law must be elastic or elastoplastic"),
    (lambda b: b.update(law="elastoplastic"), "exactly one of psi and yield_strength"),
    (lambda b: b.update(psi=0.35), "psi and yield_strength belong to law: elastoplastic"),
    (lambda b: b.update(seating_pressure=0), "seating_pressure"),
    (lambda b: b.update(lay_direction=[0, 0, 0]), "lay_direction"),
    (lambda b: b.update(lay_direction=[1, 0]), "lay_direction"),
    (lambda b: b.update(colour="red"), "unknown key 'colour'"),
    (lambda b: b.update(friction={"coulomb": {"mu": 0.2}}), "missing key 'kt_over_kn'"),
    (lambda b: b.update(friction={"viscous": {}}), "unknown friction 'viscous'"),
    (lambda b: b.update(friction={"orthotropic": {"mu_m": 0.5, "mu_o": 0.5, "nu_x": 0.1, "nu_y": 0.2, "n_x": 1,
                                                  "n_y": 1, "kt_over_kn": 0.7}}), "give k instead"),
    (lambda b: b.update(pressure_range=[10, 1]), "p_light < p_max"),
    (lambda b: b.update(tangential_form="total"), "tangential_form"),
])
def test_bad_laws_name_the_key(change, message):
    d = yaml.safe_load(ISSUE)
    change(d["interactions"]["ROUGH"])
    with pytest.raises(LawError, match=message) as err:
        law_file_from_dict(d, "law.yaml")
    assert str(err.value).startswith("law.yaml: interactions.ROUGH")


def test_bad_files(tmp_path):
    (tmp_path / "a.yaml").write_text("length_unit: [\n")
    with pytest.raises(LawError, match="not YAML"):
        read_law_file(tmp_path / "a.yaml")
    with pytest.raises(LawError, match="cannot read"):
        read_law_file(tmp_path / "none.yaml")
    with pytest.raises(LawError, match="length_unit"):
        law_file_from_dict({"length_unit": "furlong", "interactions": {}})
    with pytest.raises(LawError, match="at least one interaction"):
        law_file_from_dict({"length_unit": "mm", "interactions": {}})
    d = yaml.safe_load(ISSUE)
    d["interactions"]["rough"] = d["interactions"]["ROUGH"]
    with pytest.raises(LawError, match="given twice"):
        law_file_from_dict(d)


def test_the_material_in_the_decks_units():
    """An mm deck with µm moments: the engine's InterfaceMaterial converts lengths by 1000 and
    the law's reference state carries the seating pressure; n per mm becomes n per µm."""
    d = yaml.safe_load(ISSUE)
    d["interactions"]["ROUGH"]["friction"] = {"orthotropic": {"mu_m": 0.5, "mu_o": 0.5, "nu_x": 0.125, "nu_y": 0.125,
                                                              "n_x": 275, "n_y": 275, "kt_over_kn": [0.7, 1.0]}}
    law = law_file_from_dict(d).interactions["ROUGH"]
    m = law.material("mm", law.E_star)
    assert m.length_per_mm == 1000.0 and m.model.n_x == pytest.approx(0.275)
    assert m.normal.p0 == pytest.approx(1e-3, rel=1e-9) and (m.normal.kT_over_kN_x, m.normal.kT_over_kN_y) == (0.7, 1.0)
    assert m.normal.table.p_max >= 0.1 * law.E_star  # the default range: up to 0.1 E*
    with pytest.raises(LawError, match="seating_pressure 0.001 lies outside"):
        law.material("mm", 1e-3)  # E* in the wrong unit: the default range [1e-20, 1e-4] misses p0
