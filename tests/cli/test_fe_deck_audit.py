"""``roughcontact fe run DECK --interface LAW.yaml`` on the bad decks of issue 29's audit: each one
line on stderr and exit 2 naming the file and line (no traceback, nothing read beyond the
limits), a comment that hides a line ccx never reads runs as ccx runs it, and the *STEP/*STATIC
values the engine does not use are each a note in the output."""

from __future__ import annotations

import json
import os

import pytest
import yaml

from roughcontact import cli
from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines

LAW = {"length_unit": "mm", "interactions": {"ROUGH": {
    "moments": {"m00": 0.0625, "m20": 8.0e-5, "m02": 8.0e-4, "m40": 1.04e-6, "m04": 1.04e-4, "unit": "um"},
    "lay_direction": [1, 0, 0], "law": "elastic", "seating_pressure": 1.0e-3,
    "friction": {"coulomb": {"mu": 0.3, "kt_over_kn": 0.7}}}}}

STEP = "*STEP\n*STATIC\n0.5, 1.\n*DLOAD\n11, P2, 2.\n*END STEP\n"


def deck(step: str = STEP, model: str = "") -> str:
    """A quarter block (1 element) on a base (1 element) under a pressure of 2 on its top (the
    deck of test_fe_run_command.py); ``model`` goes before the steps."""
    base = box_part([0, 5], [0, 5], [-5, 0])
    top = box_part([0, 5], [0, 5], [0, 5], first_node=101, first_element=11)
    return "\n".join([
        "*HEADING", "block on base", *node_lines(base, "BASENODES"), *node_lines(top, "BLOCKNODES"),
        *element_lines(base, "BASE"), *element_lines(top, "BLOCK"),
        *id_lines("*NSET, NSET=BOTTOM", base.face_nodes["ZMIN"]),
        *id_lines("*NSET, NSET=XSYM", list(base.face_nodes["XMIN"]) + list(top.face_nodes["XMIN"])),
        *id_lines("*NSET, NSET=YSYM", list(base.face_nodes["YMIN"]) + list(top.face_nodes["YMIN"])),
        "*SURFACE, NAME=SLAVE", "11, S1", "*SURFACE, NAME=MASTER", "1, S2",
        "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1e5, 0.3", "*SOLID SECTION, ELSET=BASE, MATERIAL=STEEL",
        "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
        "*SURFACE INTERACTION, NAME=ROUGH", "*CONTACT PAIR, INTERACTION=ROUGH", "SLAVE, MASTER",
        "*BOUNDARY", "BOTTOM, ENCASTRE", "XSYM, XSYMM", "YSYM, YSYMM", ""]) + model + step


def line_of(text: str, needle: str) -> int:
    return next(k for k, line in enumerate(text.split("\n"), start=1) if needle in line)


@pytest.fixture
def law(tmp_path):
    (tmp_path / "law.yaml").write_text(yaml.safe_dump(LAW))
    return tmp_path / "law.yaml"


def fe_run(capsys, deck_path, law, *extra):
    code = cli.main(["fe", "run", str(deck_path), "--interface", str(law), "--quiet", *map(str, extra)])
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(capsys, deck_path, law) -> str:
    code, out, err = fe_run(capsys, deck_path, law)
    assert code == 2 and out == "" and err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith("roughcontact: error: ")
    return err[len("roughcontact: error: "):-1]


def test_a_comment_hides_no_load(capsys, tmp_path, law):
    """The issue's ``** c\\x0bTOPFACES, P2, 50.``: the mean contact pressure stays 2, not 50."""
    for name, sep in (("vt.inp", "\x0b"), ("ls.inp", "\u2028"), ("nel.inp", "\x85")):
        (tmp_path / name).write_text(deck(STEP.replace("*END STEP", f"** c{sep}11, P2, 50.\n*END STEP")))
        code, out, err = fe_run(capsys, tmp_path / name, law, "--json")
        assert code == 0, err
        p_N = json.loads(out)["steps"][0]["interface"]["p_N"]
        assert 1.9 < sum(p_N) / len(p_N) < 2.1


@pytest.mark.parametrize("make, needle, message", [
    (lambda: deck(STEP.replace("11, P2, 2.", "11, P2, 2.\x0b11, P2, 50.")), "P2, 2.", "a control character (U+000B)"),
    (lambda: "\ufeff" + deck(), None, "the file starts with a byte-order mark (U+FEFF)"),
    (lambda: deck(STEP.replace("*STEP", "*STEP, NLGEOM")), "NLGEOM",
     "*STEP, NLGEOM (without a value: YES, as Abaqus reads it): geometric nonlinearity"),
    (lambda: deck(model="*NSET, NSET=BIG, GENERATE\n1, 2000000000\n"), "2000000000",
     "*NSET, GENERATE 1, 2000000000, 1: the ids: 2000000000 exceed the limit of 20000000"),
    (lambda: deck(model="*NODE\n100000000000000000000, 0., 0., 0.\n"), "100000000000000000000",
     "a node id must be a positive integer of at most 9223372036854775807"),
    (lambda: deck(STEP.replace("0.5, 1.", "1e-320, 1e300")), "1e-320",
     "*STATIC: the initial increment 9.99989e-321 is subnormal"),
    # the "with 40 nodes": a 19-node element, then the next one in the same *ELEMENT block
    (lambda: deck().replace("16, 9, 10, 12, 11\n*ELEMENT, TYPE=C3D20, ELSET=BLOCK\n", "16, 9, 10, 12\n"), "1, 1, 3",
     "C3D20 element 1 with 19 nodes, and the next line"),
])
def test_bad_decks_are_one_line_exit_2(capsys, tmp_path, law, make, needle, message):
    text = make()
    (tmp_path / "m.inp").write_text(text)
    said = one_line_error(capsys, tmp_path / "m.inp", law)
    line = line_of(text, needle) if needle else 1
    assert said.startswith(f"{tmp_path / 'm.inp'}:{line}: {message}"), said


def test_a_huge_include_and_a_deep_include_chain_are_one_line(capsys, tmp_path, law):
    with open(tmp_path / "big.inp", "wb") as f:
        f.truncate(3 * 1024 ** 3)  # sparse: nothing is written, nothing may be read
    (tmp_path / "m.inp").write_text(deck(model="*INCLUDE, INPUT=big.inp\n"))
    said = one_line_error(capsys, tmp_path / "m.inp", law)
    assert said.startswith(f"{tmp_path / 'm.inp'}:") and "big.inp: 3072 MB exceed the limit of 1024 MB" in said
    for k in range(3000):
        (tmp_path / f"f{k}.inp").write_text(f"*INCLUDE, INPUT=f{k + 1}.inp\n")
    (tmp_path / "f3000.inp").write_text("** the end\n")
    (tmp_path / "m.inp").write_text(deck(model="*INCLUDE, INPUT=f0.inp\n"))
    said = one_line_error(capsys, tmp_path / "m.inp", law)
    assert said == (f"{tmp_path / 'f31.inp'}:1: *INCLUDE nesting: 33 exceed the limit of 32 (the nesting of *INCLUDE "
                    "files; set ROUGHCONTACT_MAX_INCLUDE_DEPTH to raise it)")


def test_an_include_outside_the_folder_is_not_echoed(capsys, tmp_path, law):
    (tmp_path / "deck").mkdir()
    (tmp_path / "secret").write_text("alice:x:1000:1000:Alice,,,:/srv/alice:/bin/bash\n")
    (tmp_path / "deck" / "m.inp").write_text(deck(model="*NSET, NSET=X\n*INCLUDE, INPUT=../secret\n"))
    said = one_line_error(capsys, tmp_path / "deck" / "m.inp", law)
    assert said.startswith(f"{tmp_path / 'secret'}:1: the deck cannot use this line")
    assert "alice" not in said.lower() and "bash" not in said
    if os.path.isfile("/etc/passwd"):  # the issue's own probe
        (tmp_path / "deck" / "m.inp").write_text(deck(model="*NSET, NSET=X\n*INCLUDE, INPUT=/etc/passwd\n"))
        said = one_line_error(capsys, tmp_path / "deck" / "m.inp", law)
        said = said.replace(str(tmp_path), "")  # the folder's name may hold "root" (pytest-of-root)
        assert said.startswith("/etc/passwd:") and "/bin/" not in said and "root" not in said.lower()


def test_step_values_are_honoured_and_the_command_line_overrides_them(capsys, tmp_path, law):
    """Issue 31: INC= and *STATIC's minimum and maximum are honoured (no note); --increments and
    --max-increments replace them, a note each; too few increments exit 1 naming the step."""
    text = deck(STEP.replace("*STEP", "*STEP, INC=50").replace("0.5, 1.", "0.5, 1., 1e-5, 0.5"))
    (tmp_path / "m.inp").write_text(text)
    code, out, err = fe_run(capsys, tmp_path / "m.inp", law)
    assert code == 0, err
    assert not [line for line in out.splitlines() if line.startswith("note: ") and ("STATIC" in line or "INC" in line)]
    assert "(time 1, 2 increments)" in out
    code, out, err = fe_run(capsys, tmp_path / "m.inp", law, "--increments", 4, "--max-increments", 8)
    assert code == 0, err
    assert "(time 1, 4 increments)" in out
    where = f"{tmp_path / 'm.inp'}"
    assert f"note: {where}:{line_of(text, '1e-5')}: --increments 4 overrides *STATIC's initial increment 0.5: the step " \
           "runs 4 fixed increments of 0.25" in out.splitlines()
    assert f"note: {where}:{line_of(text, 'INC=50')}: --max-increments 8 overrides *STEP, INC=50" in out.splitlines()
    code, out, err = fe_run(capsys, tmp_path / "m.inp", law, "--increments", 4, "--max-increments", 3)
    assert code == 1 and out == "" and "Traceback" not in err
    assert err.startswith(f"roughcontact: error: step 1 ({where}:{line_of(text, 'INC=50')}): its 4 fixed increments "
                          "(period 1 / initial increment 0.25) exceed the maximum number of increments 3")
    for bad in ("0", "100001"):
        code, out, err = fe_run(capsys, tmp_path / "m.inp", law, "--max-increments", bad)
        assert code == 2 and err == f"roughcontact: error: --max-increments {bad}: must lie in 1 ... 100000\n"
