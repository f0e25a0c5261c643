"""``roughcontact fe run MODEL.inp --interface LAW.yaml``: the JSON of the issue, the ParaView
series, progress on stderr, and every bad deck or law a one-line error (exit 2) naming the file
and line; no convergence exit 1 naming the step."""

from __future__ import annotations

import json
import re

import pytest
import yaml

from roughcontact import cli
from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines

LAW = {"length_unit": "mm", "interactions": {"ROUGH": {
    "moments": {"m00": 0.0625, "m20": 8.0e-5, "m02": 8.0e-4, "m40": 1.04e-6, "m04": 1.04e-4, "unit": "um"},
    "lay_direction": [1, 0, 0], "E_star": 1.15e5, "law": "elastic", "seating_pressure": 1.0e-3,
    "friction": {"coulomb": {"mu": 0.3, "kt_over_kn": 0.7}}}}}


def deck(pressure=2.0) -> str:
    """A quarter block (1 element) on a base (1 element), two steps: a pressure, then a push
    sideways on the top with the pressure kept."""
    base = box_part([0, 5], [0, 5], [-5, 0])
    top = box_part([0, 5], [0, 5], [0, 5], first_node=101, first_element=11)
    return "\n".join([
        "*HEADING", "block on base", *node_lines(base, "BASENODES"), *node_lines(top, "BLOCKNODES"),
        *element_lines(base, "BASE"), *element_lines(top, "BLOCK"),
        *id_lines("*NSET, NSET=BOTTOM", base.face_nodes["ZMIN"]), *id_lines("*NSET, NSET=TOP", top.face_nodes["ZMAX"]),
        *id_lines("*NSET, NSET=XSYM", list(base.face_nodes["XMIN"]) + list(top.face_nodes["XMIN"])),
        *id_lines("*NSET, NSET=YSYM", list(base.face_nodes["YMIN"]) + list(top.face_nodes["YMIN"])),
        "*SURFACE, NAME=SLAVE", "11, S1", "*SURFACE, NAME=MASTER", "1, S2",
        "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1e5, 0.3", "*SOLID SECTION, ELSET=BASE, MATERIAL=STEEL",
        "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
        "*SURFACE INTERACTION, NAME=ROUGH", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR", "0., -1e-4", "10., 0.",
        "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=NODE TO SURFACE", "SLAVE, MASTER",
        "*BOUNDARY", "BOTTOM, ENCASTRE", "XSYM, XSYMM", "YSYM, YSYMM",
        "*STEP", "*STATIC", "0.5, 1.", "*DLOAD", f"11, P2, {pressure}", "*NODE PRINT, NSET=TOP", "U", "*END STEP",
        "*STEP", "*STATIC", "1., 1.", "*DLOAD", "11, P2, 0.5", "*END STEP", ""])


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def files(tmp_path):
    (tmp_path / "model.inp").write_text(deck())
    (tmp_path / "law.yaml").write_text(yaml.safe_dump(LAW))
    return tmp_path


def test_json_of_the_issue(capsys, files):
    code, out, err = run(capsys, "fe", "run", files / "model.inp", "--interface", files / "law.yaml", "--json")
    assert code == 0, err
    data = json.loads(out)
    for key in ("dofs", "interface_points", "seconds", "newton_iterations", "steps"):
        assert key in data
    assert data["interface_points"] == 9 and len(data["steps"]) == 2
    step = data["steps"][0]
    assert set(step["node_sets"]) == {"BASENODES", "BLOCKNODES", "BOTTOM", "TOP", "XSYM", "YSYM"}
    top = step["node_sets"]["TOP"]
    assert top["nodes"] == sorted(top["nodes"]) and len(top["u"]) == len(top["nodes"]) == 8
    assert all(len(u) == 3 for u in top["u"])
    iface = step["interface"]
    assert set(iface) == {"x", "y", "z", "u_N_um", "p_N", "t_1", "t_2", "slip_1_um", "slip_2_um", "status"}
    assert 1.9 < sum(iface["p_N"]) / 9 < 2.1 and set(iface["status"]) <= {"stick", "slip", "open"}  # ~ 2 N/mm^2
    assert "definition" in data["interface_axes"] and data["units"]["u_N_um"].startswith("um")
    assert any("*NODE PRINT ignored" in n for n in data["notes"])
    assert any("*SURFACE BEHAVIOR of interaction ROUGH replaced" in n for n in data["notes"])
    assert "step 2/2, increment 1/1" in err  # progress on stderr


def test_text_and_series(capsys, files):
    code, out, err = run(capsys, "fe", "run", files / "model.inp", "--interface", files / "law.yaml", "--quiet",
                         "--elements", "cubic", "--vtu", files / "out.pvd")
    assert code == 0 and err == "" and "16 interface points" in out and "step 2" in out
    assert (files / "out.pvd").exists() and len(list((files / "out").glob("*.vtu"))) == 2 * 3


@pytest.mark.parametrize("edit, message", [
    (lambda d, l: (d.replace("XSYM, XSYMM", "XSIM, XSYMM"), l), r"model\.inp:\d+: missing set: no \*NSET XSIM"),
    (lambda d, l: (d.replace("TYPE=C3D20,", "TYPE=C3D8I,"), l), r"model\.inp:\d+: unknown element type C3D8I"),
    (lambda d, l: (d.replace("1, S2", "1, S6"), l), r"non-conforming contact faces: slave node \d+ of SLAVE at"),
    (lambda d, l: (d, l.replace("ROUGH:", "SMOOTH:")), r"model\.inp:\d+: interaction ROUGH has no law"),
    (lambda d, l: (d.replace("11, P2, 0.5", "11, P9, 0.5"), l), r"model\.inp:\d+: load type 'P9'"),
    (lambda d, l: (d.replace("0.5, 1.\n*DLOAD", "0., 1.\n*DLOAD"), l), r"model\.inp:\d+: \*STATIC with zero increments"),
    (lambda d, l: (d.replace("2.1e5, 0.3", "-2.1e5, 0.3"), l), r"model\.inp:\d+: Young's modulus must be positive"),
    (lambda d, l: (d, l.replace("m40: 1.04e-06", "m40: -1.04e-06")), r"law\.yaml: interactions\.ROUGH\.moments: invalid"),
    (lambda d, l: (d.replace("*BOUNDARY", "*BOUNDARY, OP=NEW"), l), r"OP=NEW"),
])
def test_bad_decks_and_laws_are_one_line(capsys, files, edit, message):
    d, law = edit(deck(), yaml.safe_dump(LAW, default_flow_style=None))
    (files / "model.inp").write_text(d)
    (files / "law.yaml").write_text(law)
    code, out, err = run(capsys, "fe", "run", files / "model.inp", "--interface", files / "law.yaml", "--quiet")
    assert code == 2 and out == "" and len(err.splitlines()) == 1, err
    assert re.search(message, err), err


def test_missing_files_and_a_wrong_series_name(capsys, files):
    code, _, err = run(capsys, "fe", "run", files / "none.inp", "--interface", files / "law.yaml")
    assert code == 2 and "none.inp: no such file" in err
    code, _, err = run(capsys, "fe", "run", files / "model.inp", "--interface", files / "none.yaml")
    assert code == 2 and "cannot read" in err
    code, _, err = run(capsys, "fe", "run", files / "model.inp", "--interface", files / "law.yaml", "--vtu",
                       files / "out.vtu")
    assert code == 2 and ".pvd" in err


def test_no_convergence_is_exit_1_naming_the_step(capsys, files, monkeypatch):
    from roughcontact.fe import deck_run, solver

    real = solver.solve
    monkeypatch.setattr(deck_run, "solve", lambda model, levels, options=None, progress=None: real(
        model, levels, solver.NewtonOptions(max_iterations=1, max_cutbacks=0), progress))
    code, out, err = run(capsys, "fe", "run", files / "model.inp", "--interface", files / "law.yaml", "--quiet")
    assert code == 1 and out == "" and len(err.splitlines()) == 1
    assert re.search(r"step 1 \(.*model\.inp:\d+\): no convergence at increment 1 of 2", err)


def test_a_cut_back_is_reported_and_the_answer_kept(capsys, files, monkeypatch):
    """*STATIC's increments are cut back when Newton fails (here: at most 8 iterations; the first increment takes 10) and the
    cut-backs are said: on stderr per increment, in the JSON per step and in total; the answer
    is that of the run without cut-backs (a frictionless law: no path dependence)."""
    from roughcontact.fe import deck_run, solver

    law = yaml.safe_load((files / "law.yaml").read_text())
    law["interactions"]["ROUGH"]["friction"] = "none"
    (files / "free.yaml").write_text(yaml.safe_dump(law))
    argv = ("fe", "run", files / "model.inp", "--interface", files / "free.yaml", "--json")
    code, out, _ = run(capsys, *argv)
    plain = json.loads(out)
    real = solver.solve
    monkeypatch.setattr(deck_run, "solve", lambda model, levels, options=None, progress=None: real(
        model, levels, solver.NewtonOptions(max_iterations=8), progress))
    code, out, err = run(capsys, *argv)
    assert code == 0, err
    cut = json.loads(out)
    assert code == 0 and plain["cutbacks"] == 0 < cut["cutbacks"] == sum(s["cutbacks"] for s in cut["steps"])
    assert re.search(r"increment \d+/\d+: \d+ Newton iterations, \d+ cut-backs", err)
    for a, b in zip(plain["steps"], cut["steps"]):
        assert max(abs(x - y) for x, y in zip(b["interface"]["p_N"], a["interface"]["p_N"])) < 1e-7 * max(a["interface"]["p_N"])
