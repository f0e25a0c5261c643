"""The deck reader (roughcontact.fe.deck_syntax, fe.deck): the keyword language (case, comments,
continuations, *INCLUDE, GENERATE), Abaqus step semantics, and every bad deck a clear error
naming its file and line (never a keyword silently skipped)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from roughcontact.fe.deck import ELEMENT_TYPES, IGNORED, read_deck
from roughcontact.fe.deck_syntax import DeckError, read_blocks


def test_keyword_language(tmp_path):
    """Case-insensitive keywords and parameters, comments, blank lines, a keyword line and a
    data line continued by a trailing comma, *INCLUDE relative to the including file (nested)."""
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "nodes.inp").write_text("** nodes\n1, 0., 0., 0.\n*include, input=more.inp\n")
    (tmp_path / "sub" / "more.inp").write_text("2, 1., 0., 0.\n")
    (tmp_path / "m.inp").write_text("**a comment\n\n*Node,\n nset=ALL\n*INCLUDE, INPUT=sub/nodes.inp\n"
                                    "*nset ,  NSET=two, generate\n1, 2, 1\n*NSET, NSET=PAIR\n1,\n2\n")
    blocks = read_blocks(tmp_path / "m.inp")
    assert [b.name for b in blocks] == ["NODE", "NSET", "NSET"]  # included lines continue the *NODE block
    assert blocks[0].params == {"NSET": "ALL"} and blocks[1].params == {"NSET": "two", "GENERATE": None}
    assert blocks[0].data[0].fields == ("1", "0.", "0.", "0.") and blocks[0].data[0].where.endswith("nodes.inp:2")
    assert blocks[0].data[1].fields == ("2", "1.", "0.", "0.") and blocks[0].data[1].where.endswith("more.inp:1")
    assert blocks[2].data[0].fields == ("1", "2")  # joined over the trailing comma
    assert blocks[2].data[0].where.endswith("m.inp:9")


@pytest.mark.parametrize("text, message", [
    ("*INCLUDE, INPUT=a.inp\n", "cycle"),
    ("*INCLUDE, INPUT=none.inp\n", "no file"),
    ("*INCLUDE\n", "INPUT="),
    ("1, 2\n", "before the first keyword"),
    ("*NODE, NSET=A, NSET=B\n", "given twice"),
])
def test_syntax_errors_name_the_line(tmp_path, text, message):
    (tmp_path / "a.inp").write_text(text)
    with pytest.raises(DeckError, match=message) as err:
        read_blocks(tmp_path / "a.inp")
    assert re.search(r"a\.inp:\d+: ", str(err.value))


def minimal(body="", steps="*STEP\n*STATIC\n0.5, 1.\n*END STEP\n", elements="C3D20") -> str:
    """One C3D20 (unit cube) with a section; ``body`` before the steps."""
    nodes = np.array([(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1),
                      (0, -1, -1), (1, 0, -1), (0, 1, -1), (-1, 0, -1), (0, -1, 1), (1, 0, 1), (0, 1, 1), (-1, 0, 1),
                      (-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], dtype=float) / 2 + 0.5
    text = "*NODE, NSET=ALL\n" + "".join(f"{i + 1}, {x}, {y}, {z}\n" for i, (x, y, z) in enumerate(nodes))
    text += f"*ELEMENT, TYPE={elements}, ELSET=E\n1, " + ", ".join(map(str, range(1, 16))) + ",\n16, 17, 18, 19, 20\n"
    text += "*MATERIAL, NAME=M\n*ELASTIC\n2.1e5, 0.3\n*SOLID SECTION, ELSET=E, MATERIAL=M\n"
    return text + body + steps


def test_a_minimal_deck(write_deck):
    d = read_deck(write_deck(minimal("*BOUNDARY\n1, 1, 3\n")))
    assert d.connectivity.shape == (1, 20) and d.element_types == ("C3D20",) and d.materials["M"].E == 2.1e5
    assert d.steps[0].fractions == (0.5, 1.0) and d.steps[0].boundary == {(1, 1): 0.0, (1, 2): 0.0, (1, 3): 0.0}
    assert set(ELEMENT_TYPES) == {"C3D20", "C3D20R", "C3D10"}
    d = read_deck(write_deck(minimal(elements="C3D20R")))
    assert d.element_types == ("C3D20R",)


def test_element_connectivity_without_trailing_comma(write_deck):
    text = minimal().replace("15,\n16, 17", "15\n16, 17")
    assert read_deck(write_deck(text)).connectivity[0, 15] == 16


def test_generate_and_sets_of_sets(write_deck):
    d = read_deck(write_deck(minimal("*NSET, NSET=A, GENERATE\n1, 9, 4\n*NSET, NSET=B\nA, 20\n"
                                     "*NSET, NSET=C, ELSET=E\n*ELSET, ELSET=F, GENERATE\n1, 1\n")))
    assert d.nsets["A"].tolist() == [1, 5, 9] and d.nsets["B"].tolist() == [1, 5, 9, 20]
    assert d.nsets["C"].size == 20 and d.elsets["F"].tolist() == [1]


def test_steps_follow_abaqus_semantics(write_deck):
    """Loads persist until changed; OP=MOD changes the named entries; OP=NEW removes the rest
    first; supports persist; the increments come from *STATIC's initial increment and period."""
    steps = ("*STEP\n*STATIC\n0.25, 1.\n*CLOAD\n1, 3, -1.\n2, 3, -2.\n*DLOAD\nE, P2, 5.\n*END STEP\n"
             "*STEP\n*STATIC\n0.3, 0.9\n*CLOAD\n1, 3, -4.\n*END STEP\n"
             "*STEP\n*STATIC\n*CLOAD, OP=NEW\n3, 1, 1.\n*DLOAD, OP=NEW\n*BOUNDARY\n5, 1, 1, 0.01\n*END STEP\n")
    d = read_deck(write_deck(minimal("*BOUNDARY\n1, ENCASTRE\n", steps)))
    s1, s2, s3 = d.steps
    assert s1.fractions == (0.25, 0.5, 0.75, 1.0) and s1.cload == {(1, 3): -1.0, (2, 3): -2.0} and s1.dload == {(1, 2): 5.0}
    assert s2.fractions == pytest.approx((1 / 3, 2 / 3, 1.0)) and s2.fractions[-1] == 1.0 and s2.period == 0.9
    assert s2.cload == {(1, 3): -4.0, (2, 3): -2.0} and s2.dload == {(1, 2): 5.0}
    assert s3.fractions == (1.0,) and s3.cload == {(3, 1): 1.0} and s3.dload == {}
    assert s3.boundary == {(1, 1): 0.0, (1, 2): 0.0, (1, 3): 0.0, (5, 1): 0.01}


def test_output_requests_are_ignored_with_a_note_and_interaction_options_replaced(write_deck):
    body = ("*SURFACE, NAME=S\nE, S1\n*SURFACE INTERACTION, NAME=R\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n"
            "0., -1e-4\n1., 0.\n*FRICTION\n0.2, 1e4\n")
    steps = "*STEP\n*STATIC\n*NODE PRINT, NSET=ALL\nU\n*EL FILE\nS\n*CONTACT PRINT\nCSTR\n*END STEP\n"
    d = read_deck(write_deck(minimal(body, steps)))
    notes = "\n".join(d.notes)
    assert "*SURFACE BEHAVIOR of interaction R replaced by the law R" in notes and "*FRICTION" in notes
    for kw in ("*NODE PRINT", "*EL FILE", "*CONTACT PRINT"):
        assert f"{kw} ignored" in notes
    assert {"NODE PRINT", "EL FILE", "CONTACT PRINT", "NODE FILE"} <= set(IGNORED)


def test_deck_from_text_with_its_name():
    d = read_deck("virtual.inp", minimal())
    assert d.path == "virtual.inp" and d.connectivity.shape == (1, 20)


@pytest.mark.parametrize("body, steps, line, message", [
    # the bad decks that the reader sees (the others: test_deck_run, test_laws, the CLI)
    ("*BOUNDARY\nNOSUCHSET, 1, 3\n", None, "NOSUCHSET", "missing set: no *NSET NOSUCHSET"),
    ("*SURFACE, NAME=S\nNOSUCH, S1\n", None, "NOSUCH, S1", "missing set: no *ELSET NOSUCH"),
    (None, "*STEP\n*STATIC\n0., 1.\n*END STEP\n", "0., 1.", "zero increments"),
    (None, "*STEP\n*STATIC\n0.5, 0.\n*END STEP\n", "0.5, 0.", "period must be positive"),
    (None, "*STEP\n*STATIC\n*DLOAD\nE, P7, 1.\n*END STEP\n", "E, P7", "P1 ... P6"),
    (None, "*STEP\n*STATIC\n*DLOAD\n99, P2, 1.\n*END STEP\n", "99, P2", "element 99 is not defined"),
    ("*SURFACE, NAME=S\nE, S7\n", None, "E, S7", "S1 ... S6"),
    ("*FOO, BAR=1\n", None, "*FOO", "unsupported keyword *FOO"),
    ("*AMPLITUDE, NAME=A\n0., 0., 1., 1.\n", None, "*AMPLITUDE", "unsupported keyword *AMPLITUDE"),
    ("*BOUNDARY, OP=NEW\n1, 1, 3\n", None, "*BOUNDARY, OP=NEW", "OP=NEW"),
    ("*BOUNDARY\n1, 4, 6\n", None, "1, 4, 6", "displacements 1-3"),
    ("*CLOAD\n1, 3, 1.\n", None, "*CLOAD", "outside a *STEP"),
    ("*ELASTIC\n1., 0.3\n", None, "*ELASTIC", "outside a *MATERIAL"),
    (None, "*STEP, NLGEOM=YES\n*STATIC\n*END STEP\n", "NLGEOM", "geometrically linear"),
    (None, "*STEP\n*END STEP\n", "*STEP", "needs *STATIC"),
    (None, "*STEP\n*STATIC\n", "*STEP", "without *END STEP"),
    (None, "", None, "no *STEP"),
    ("*CONTACT PAIR, INTERACTION=NONE\nA, B\n", None, "*CONTACT PAIR", "interaction NONE is not defined"),
    ("*NODE\n1, 0., 0., 0.\n", None, "1, 0., 0., 0.", "node 1 is defined twice"),
    ("*NODE, SYSTEM=C\n30, 0., 0., 0.\n", None, "*NODE, SYSTEM", "SYSTEM is not supported"),
    ("*SURFACE, NAME=S, TYPE=NODE\nALL\n", None, "TYPE=NODE", "TYPE=NODE is not supported"),
    ("*SOLID SECTION, ELSET=E, MATERIAL=NONE\n", None, "MATERIAL=NONE", "material NONE is not defined"),
])
def test_bad_decks_are_errors_naming_the_line(write_deck, body, steps, line, message):
    text = minimal(body or "", steps if steps is not None else "*STEP\n*STATIC\n*END STEP\n")
    path = write_deck(text)
    with pytest.raises(DeckError, match=re.escape(message)) as err:
        read_deck(path)
    where = re.match(r"(.+):(\d+): ", str(err.value))
    assert where and where.group(1) == path
    if line is not None:
        assert line in text.splitlines()[int(where.group(2)) - 1]


@pytest.mark.parametrize("text, message", [
    ("*ELASTIC\n-2.1e5, 0.3\n", "Young's modulus must be positive"),  # a negative modulus
    ("*ELASTIC\n2.1e5, 0.5\n", "Poisson's ratio"),
    ("*ELASTIC\n2.1e5\n", "E, nu"),
])
def test_bad_materials(write_deck, text, message):
    with pytest.raises(DeckError, match=message):
        read_deck(write_deck(minimal().replace("*ELASTIC\n2.1e5, 0.3\n", text)))


def test_unknown_element_types_say_what_to_do(write_deck):
    with pytest.raises(DeckError, match="unknown element type C3D8: 8-node hexahedra cannot carry"):
        read_deck(write_deck(minimal(elements="C3D8")))
    with pytest.raises(DeckError, match=r"unknown element type C3D4: the engine runs 20-node hexahedra \(C3D20, "
                                        r"C3D20R\) and 10-node tetrahedra \(C3D10\)"):
        read_deck(write_deck(minimal(elements="C3D4")))
    with pytest.raises(DeckError, match=r"C3D10 element 1 with 20 nodes \(C3D10 needs 10\)"):
        read_deck(write_deck(minimal(elements="C3D10")))  # a hexahedron's connectivity under TYPE=C3D10


def test_elements_and_sections_checked(write_deck):
    with pytest.raises(DeckError, match="element 1 refers to node 99"):
        read_deck(write_deck(minimal().replace("16, 17, 18, 19, 20", "16, 17, 18, 19, 99")))
    with pytest.raises(DeckError, match="element 1 has no \\*SOLID SECTION"):
        read_deck(write_deck(minimal().replace("*SOLID SECTION, ELSET=E, MATERIAL=M\n", "")))
    with pytest.raises(DeckError, match="needs 20"):
        read_deck(write_deck(minimal().replace("16, 17, 18, 19, 20", "16, 17, 18, 19, 20, 21")))
