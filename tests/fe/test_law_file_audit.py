"""Issue 29 (B2): LAW.yaml as an input that may be wrong or hostile, and a law checked against the
deck it is read for.

* The file: a key given twice (YAML keeps the last silently), a 1 KB alias bomb, 50 000-deep
  nesting (RecursionError), bytes that are not UTF-8, /dev/zero and a FIFO — each one line
  naming the file, in bounded memory and time.
* Messages quote values through limits.describe (no ``np.float64(…)``), and name the law
  file and the key (a lay direction normal to the contact face).
* Units: the docs' own-model deck in mm and a copy in m (coordinates × 10⁻³, moduli and
  pressures × 10⁶) give the same closures; each with the other's length_unit is refused naming
  both numbers; E* comes from the deck's *ELASTIC (eq. (42)) where the law omits it and a
  stated one more than 1 % off is refused.
* docs/own-model.md defines every key the reader accepts, with its unit, and mu_o as the
  ratio it is.
"""

from __future__ import annotations

import copy
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

from roughcontact.asperity import effective_modulus
from roughcontact.fe.deck_run import SOLID_E_STAR_PA, check_law_file, run_deck_file
from roughcontact.fe.deck import read_deck
from roughcontact.fe.laws import LAW_KEYS, LawError, law_file_from_dict, read_law_file
from roughcontact.interface import friction

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "docs" / "examples"
DOC = ROOT / "docs" / "own-model.md"
STEEL, ALUMINIUM = (2.1e5, 0.3), (7.0e4, 0.33)  # block.inp's *ELASTIC [N/mm²]


def _law(**changes) -> dict:
    law = yaml.safe_load((EXAMPLES / "block.yaml").read_text())
    law["interactions"]["ROUGH"].update(changes)
    return law


def _one_line(exc) -> str:
    text = str(exc.value)
    assert "\n" not in text and len(text) < 600, text
    return text


# ---------------------------------------------------------------------------------------------
# the file
# ---------------------------------------------------------------------------------------------
def test_a_key_given_twice_names_the_key_and_both_lines(tmp_path):
    text = (EXAMPLES / "block.yaml").read_text()
    lines = text.splitlines()
    first = next(i for i, line in enumerate(lines, start=1) if line.startswith("length_unit:"))
    path = tmp_path / "law.yaml"
    path.write_text(text + "length_unit: m\n")
    with pytest.raises(LawError) as err:
        read_law_file(path)
    msg = _one_line(err)
    assert str(path) in msg and "'length_unit'" in msg
    assert f"lines {first} and {len(lines) + 1}" in msg
    # inside an interaction too
    nested = text.replace("    law: elastic", "    law: elastic\n    law: elastoplastic")
    path.write_text(nested)
    with pytest.raises(LawError, match=r"'law' is given twice .*lines \d+ and \d+"):
        read_law_file(path)


def test_an_alias_bomb_is_refused_in_bounded_memory(tmp_path):
    """The 'billion laughs': 9 levels of 9 aliases, ~1 KB, 9⁹ ≈ 3.9·10⁸ leaves when expanded.
    Refused at its first anchor, in a child process whose peak memory stays small."""
    rows = ["a: &a [x, x, x, x, x, x, x, x, x]"]
    for i in range(1, 9):
        prev, cur = chr(96 + i), chr(97 + i)
        rows.append(f"{cur}: &{cur} [{', '.join(['*' + prev] * 9)}]")
    rows.append("length_unit: *i")
    path = tmp_path / "bomb.yaml"
    path.write_text("\n".join(rows) + "\n")
    assert path.stat().st_size < 1200
    # the peak resident memory of a fresh process before and after the read: the imports alone
    # take some hundred MB, more or less with the machine's load and libraries; the read adds
    code = ("import resource, sys\nfrom roughcontact.fe.laws import read_law_file, LawError\n"
            "before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
            "try:\n    read_law_file(sys.argv[1])\nexcept LawError as e:\n    print(e)\n"
            "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before)\n")
    out = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True, timeout=120)
    message, added_kib = out.stdout.strip().splitlines()
    assert message.startswith(f"{path}: line 1: an anchor &a") and "aliases are not read" in message
    assert int(added_kib) < 50_000  # the expansion (9^9 references printed) would be GBs


@pytest.mark.parametrize("opening, closing", [("[", "]"), ("{a: ", "}")])
def test_deep_nesting_is_one_line(tmp_path, opening, closing):
    path = tmp_path / "deep.yaml"
    path.write_text("length_unit: " + opening * 50_000 + "1" + closing * 50_000 + "\n")
    with pytest.raises(ValueError) as err:
        read_law_file(path)
    assert _one_line(err).startswith(f"{path}: line 1: nested deeper than 64 levels")
    assert "ROUGHCONTACT_MAX_NESTING" in str(err.value)


def test_a_deep_moments_json_is_one_line(tmp_path):
    (tmp_path / "m.json").write_text("[" * 50_000 + "]" * 50_000)
    law = _law(moments="m.json")
    with pytest.raises(LawError) as err:
        law_file_from_dict(law, "law.yaml", tmp_path)
    assert _one_line(err).startswith("law.yaml: interactions.ROUGH.moments:") and "nested deeper" in str(err.value)


def test_not_utf8_names_the_file(tmp_path):
    path = tmp_path / "latin1.yaml"
    path.write_bytes((EXAMPLES / "block.yaml").read_bytes().replace(b"# the", "# thé".encode("latin-1"), 1))
    with pytest.raises(LawError) as err:
        read_law_file(path)
    assert str(path) in _one_line(err) and "not utf-8" in str(err.value)


def test_dev_zero_and_a_fifo_are_refused_without_reading(tmp_path):
    with pytest.raises(LawError) as err:
        read_law_file("/dev/zero")
    assert "/dev/zero" in _one_line(err) and "not a regular file" in str(err.value)
    fifo = tmp_path / "law.fifo"
    os.mkfifo(fifo)
    with pytest.raises(LawError, match="not a regular file"):  # would block forever if opened
        read_law_file(fifo)


def test_cli_dev_zero_is_exit_2(capsys):
    from roughcontact import cli

    code = cli.main(["fe", "run", str(EXAMPLES / "block.inp"), "--interface", "/dev/zero", "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "/dev/zero" in err and "Traceback" not in err


# ---------------------------------------------------------------------------------------------
# messages
# ---------------------------------------------------------------------------------------------
def test_numpy_values_are_quoted_as_numbers():
    law = _law(lay_direction=[np.float64(0.0), np.float64(1.0)])
    with pytest.raises(LawError) as err:
        law_file_from_dict(law, "law.yaml")
    assert "[0.0, 1.0]" in _one_line(err) and "np." not in str(err.value)
    law = _law(seating_pressure=np.float64(-1.0))
    with pytest.raises(LawError, match=r"seating_pressure: must be positive and finite, got -1.0$"):
        law_file_from_dict(law, "law.yaml")


def test_a_huge_value_is_quoted_briefly():
    law = _law(law="x" * 10_000_000)
    with pytest.raises(LawError) as err:
        law_file_from_dict(law, "law.yaml")
    assert len(_one_line(err)) < 200 and "…" in str(err.value)


def test_a_lay_direction_normal_to_the_face_names_the_law_file_and_key(tmp_path):
    path = tmp_path / "law.yaml"
    path.write_text(yaml.safe_dump(_law(lay_direction=[0, 0, 2])))
    with pytest.raises(LawError) as err:
        run_deck_file(EXAMPLES / "block.inp", path)
    msg = _one_line(err)
    assert msg.startswith(f"{path}: interactions.ROUGH.lay_direction: [0.0, 0.0, 2.0] is normal to a face")
    assert "np." not in msg and "BLOCKBOTTOM, BASETOP" in msg


# ---------------------------------------------------------------------------------------------
# a law for an interaction the deck lacks
# ---------------------------------------------------------------------------------------------
def test_a_law_the_deck_does_not_use_is_a_note(tmp_path):
    law = _law(friction="none")
    law["interactions"]["SPARE"] = copy.deepcopy(law["interactions"]["ROUGH"])  # no YAML anchor
    path = tmp_path / "law.yaml"
    path.write_text(yaml.safe_dump(law))
    res = run_deck_file(EXAMPLES / "block.inp", path)
    notes = res.summary(node_sets=False)["notes"]
    assert f"{path}: interactions.SPARE: the deck has no *SURFACE INTERACTION, NAME=SPARE; its law is not used" in notes
    assert not any("ROUGH: the deck has no" in n for n in notes)


# ---------------------------------------------------------------------------------------------
# units and E*
# ---------------------------------------------------------------------------------------------
def _deck_in_metres(src: Path, dst: Path) -> None:
    """block.inp with lengths in m and stresses in Pa: node coordinates × 10⁻³, *ELASTIC moduli
    and *DLOAD pressures × 10⁶ (forces unchanged, N). The included table (replaced by the law)
    is copied as it is."""
    out, block = [], None
    for line in (src / "block.inp").read_text().splitlines():
        if line.startswith("*"):
            block = line.split(",")[0].strip().upper()
            out.append(line)
            continue
        if line.startswith("**") or not line.strip():
            out.append(line)
            continue
        f = [v.strip() for v in line.split(",")]
        if block == "*NODE":
            line = ", ".join([f[0], *(repr(float(v) * 1e-3) for v in f[1:])])
        elif block == "*ELASTIC":
            line = f"{float(f[0]) * 1e6!r}, {f[1]}"
        elif block == "*DLOAD":
            line = f"{f[0]}, {f[1]}, {float(f[2]) * 1e6!r}"
        out.append(line)
    (dst / "block.inp").write_text("\n".join(out) + "\n")
    shutil.copy(src / "block-table.inp", dst / "block-table.inp")


def _law_in_metres() -> dict:
    law = _law()
    body = law["interactions"]["ROUGH"]
    law["length_unit"] = "m"
    body["seating_pressure"] *= 1e6  # N/mm² → Pa
    ortho = body["friction"]["orthotropic"]
    ortho["n_x"], ortho["n_y"] = ortho["n_x"] * 1e3, ortho["n_y"] * 1e3  # 1/mm → 1/m
    return law


@pytest.fixture(scope="module")
def decks(tmp_path_factory):
    mm, m = tmp_path_factory.mktemp("mm"), tmp_path_factory.mktemp("m")
    for f in EXAMPLES.iterdir():
        shutil.copy(f, mm / f.name)
    _deck_in_metres(EXAMPLES, m)
    (m / "block.yaml").write_text(yaml.safe_dump(_law_in_metres()))
    return mm, m


@pytest.fixture(scope="module")
def both_runs(decks):
    mm, m = decks
    return run_deck_file(mm / "block.inp", mm / "block.yaml"), run_deck_file(m / "block.inp", m / "block.yaml")


def test_the_deck_in_mm_and_in_m_give_the_same_closures(both_runs):
    """E* from the two *ELASTIC (eq. (42)) in each deck's own stress unit; the closures in µm
    the same (positive: the interface closes under the load), displacements scaled by 10³."""
    r_mm, r_m = both_runs
    E_mm = effective_modulus(*STEEL, *ALUMINIUM)
    assert r_mm.problem.E_star["ROUGH"] == pytest.approx(E_mm, rel=1e-12)
    assert r_m.problem.E_star["ROUGH"] == pytest.approx(E_mm * 1e6, rel=1e-12)
    a, b = r_mm.interface_fields(r_mm.increments[-1]), r_m.interface_fields(r_m.increments[-1])
    assert np.all(a["u_N_um"] > 0)
    np.testing.assert_allclose(b["u_N_um"], a["u_N_um"], rtol=1e-6)
    np.testing.assert_allclose(b["p_N"], a["p_N"] * 1e6, rtol=1e-6)
    np.testing.assert_allclose(r_m.increments[-1].u, r_mm.increments[-1].u * 1e-3, rtol=1e-6, atol=1e-15)


def test_a_law_in_m_on_the_mm_deck_is_refused_naming_both_numbers(decks, tmp_path):
    mm, m = decks
    E_mm = effective_modulus(*STEEL, *ALUMINIUM)
    path = tmp_path / "wrong.yaml"
    path.write_text((m / "block.yaml").read_text())
    with pytest.raises(LawError) as err:
        run_deck_file(mm / "block.inp", path)
    msg = _one_line(err)
    assert msg.startswith(f"{path}: length_unit m:") and f"E* = {E_mm:.6g}" in msg
    assert f"{E_mm:.3g} Pa, outside" in msg and f"with length_unit mm it is {E_mm * 1e6:.3g} Pa" in msg
    # and the reverse: the law of mm on the deck of m (E* 10¹⁸ Pa read in N/mm²)
    with pytest.raises(LawError, match=r"length_unit mm: .* outside .* with length_unit m it is"):
        run_deck_file(m / "block.inp", mm / "block.yaml")


def test_the_cli_refuses_it_with_exit_2(decks, capsys):
    from roughcontact import cli

    mm, m = decks
    code = cli.main(["fe", "run", str(mm / "block.inp"), "--interface", str(m / "block.yaml"), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "length_unit m" in err


def test_a_stated_E_star_is_checked_against_the_decks(decks, tmp_path):
    mm, _ = decks
    deck = read_deck(mm / "block.inp")
    E = effective_modulus(*STEEL, *ALUMINIUM)
    check_law_file(deck, law_file_from_dict(_law(E_star=E * 1.009), "law.yaml"))  # within 1 %
    with pytest.raises(LawError) as err:
        check_law_file(deck, law_file_from_dict(_law(E_star=E * 1.02), "law.yaml"))
    msg = _one_line(err)
    assert msg.startswith("law.yaml: interactions.ROUGH.E_star:") and f"{E * 1.02:.6g}" in msg
    assert f"the deck's E* = {E:.6g}" in msg and "block.inp:232" in msg


def test_stress_unit_must_agree_with_the_length_unit_and_lifts_the_range(decks):
    mm, _ = decks
    deck = read_deck(mm / "block.inp")
    law = _law()
    law["stress_unit"] = "Pa"
    with pytest.raises(LawError, match=r"stress_unit: Pa = 1 Pa contradicts length_unit mm, .* = 1e\+06 Pa"):
        law_file_from_dict(law, "law.yaml")
    law["stress_unit"] = "MPa"
    assert law_file_from_dict(law, "law.yaml").stress_unit == "MPa"
    # a genuinely soft pair (E* = 0.06 MPa): refused without stress_unit, read with it
    soft = law_file_from_dict({**_law(), "length_unit": "mm"}, "law.yaml")
    soft_deck = read_deck(mm / "block.inp", (mm / "block.inp").read_text().replace("210000.", "0.21")
                          .replace("70000.", "0.07"))
    assert effective_modulus(0.21, 0.3, 0.07, 0.33) * 1e6 < SOLID_E_STAR_PA[0]
    with pytest.raises(LawError, match="outside"):
        check_law_file(soft_deck, soft)
    check_law_file(soft_deck, law_file_from_dict(law, "law.yaml"))


# ---------------------------------------------------------------------------------------------
# the documentation
# ---------------------------------------------------------------------------------------------
def _key_table() -> dict[str, tuple[str, str]]:
    text = DOC.read_text()
    section = text[text.index("### Every key and its unit"):]
    section = section[:section.index("\n## ")]
    rows = re.findall(r"^\| `([^`]+)` \| ([^|]+) \| (.+) \|$", section, flags=re.M)
    return {key: (unit.strip(), meaning) for key, unit, meaning in rows}


def test_every_key_the_reader_accepts_is_defined_with_its_unit():
    table = _key_table()
    assert set(LAW_KEYS) == set(table), (set(LAW_KEYS) ^ set(table))
    assert all(unit for unit, _ in table.values())
    for key in ("seating_pressure", "E_star", "yield_strength", "pressure_range"):
        assert table[f"interactions.NAME.{key}"][0] == "deck stress"
    assert table["interactions.NAME.friction.orthotropic.n_x"][0] == "1/`length_unit`"
    assert table["interactions.NAME.moments.m00"][0] == "L²"


def test_the_reader_accepts_exactly_the_documented_keys():
    """A key outside LAW_KEYS is refused by the reader (so the table is complete both ways)."""
    law = _law(friction={"orthotropic": {"mu_m": 0.5, "mu_o": 0.2, "k": 0.0, "n_x": 1, "n_y": 1,
                                         "kt_over_kn": 0.7, "mu_0": 0.1}})
    with pytest.raises(LawError, match="unknown key 'mu_0'"):
        law_file_from_dict(law, "law.yaml")


def test_mu_o_is_documented_as_the_ratio_the_law_uses():
    """docs: the initial coefficient is mu_m·mu_o (eqs (89)–(90)); the library's law agrees:
    mu_m 0.5, mu_o 0.2 starts at |t|/p = 0.10 and tends to 0.5; mu_o 0.1 set as 'a coefficient'
    starts at 0.05 (the issue's 0.07 = 0.7 · 0.1)."""
    meaning = _key_table()["interactions.NAME.friction.orthotropic.mu_o"][1]
    assert "ratio, not a coefficient" in meaning and "μ_m·μ_o" in meaning
    law = law_file_from_dict(_law(friction={"orthotropic": {"mu_m": 0.5, "mu_o": 0.2, "k": 0.0, "n_x": 275,
                                                            "n_y": 275, "kt_over_kn": 0.7}}), "law.yaml")
    model = law.interactions["ROUGH"].friction.model(1000.0)
    assert isinstance(model, friction.OrthotropicHardening)
    assert model.mu(0.0, 0.0) == pytest.approx((0.10, 0.10), rel=1e-15)
    assert model.mu(1e6, 1e6) == pytest.approx((0.5, 0.5), rel=1e-12)
    assert friction.OrthotropicHardening(0.7, 0.7, 0.1, 0.1).mu(0.0, 0.0) == pytest.approx((0.07, 0.07))


@pytest.mark.parametrize("path, value, named", [
    (("length_unit",), [0, 0, 1], "length_unit"),
    (("stress_unit",), {"a": 1}, "stress_unit"),
    (("interactions", "ROUGH", "law"), ["elastic"], "law"),
    (("interactions", "ROUGH", "tangential_form"), {"a": 1}, "tangential_form"),
    (("interactions", "ROUGH", "moments", "unit"), [1, 2], "unit"),
])
def test_a_list_or_mapping_where_a_name_belongs_is_one_line_naming_the_key(path, value, named):
    """A mutation sweep of block.yaml found TypeError 'unhashable type' (through the CLI: exit 2
    with that text alone) where a unit or a law name was a YAML list or mapping."""
    law = _law()
    *parents, key = path
    node = law
    for p in parents:
        node = node[p]
    node[key] = value
    with pytest.raises(LawError) as err:
        law_file_from_dict(law, "law.yaml", EXAMPLES)
    assert named in _one_line(err) and "must be" in str(err.value)
