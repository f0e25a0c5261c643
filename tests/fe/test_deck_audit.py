"""The deck reader against the audit of issue 29: lines split as CalculiX splits them (a character
that Python's ``str.splitlines`` takes for a line break must not start a live line inside a
comment), control characters outside comments refused naming the line, ``*STEP``/``*STATIC``
values that are not used said in a note, every input bounded before it is read or allocated, and
an ``*INCLUDE`` file outside the deck's folder never quoted in a message."""

from __future__ import annotations

import os
import sys
import time

import pytest

from roughcontact import limits
from roughcontact.fe.deck import MAX_ID, read_deck
from roughcontact.fe.deck_syntax import MAX_LINE_BYTES, DeckError, read_blocks

# the one-element deck of test_deck.py (a unit C3D20 with a section), rebuilt here
_NODES = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1),
          (0, -1, -1), (1, 0, -1), (0, 1, -1), (-1, 0, -1), (0, -1, 1), (1, 0, 1), (0, 1, 1), (-1, 0, 1),
          (-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
ELEMENT = "1, " + ", ".join(map(str, range(1, 16))) + ",\n16, 17, 18, 19, 20\n"


def minimal(body: str = "", steps: str = "*STEP\n*STATIC\n0.5, 1.\n*END STEP\n", element: str = ELEMENT) -> str:
    text = "*NODE, NSET=ALL\n" + "".join(f"{i + 1}, {(x + 1) / 2}, {(y + 1) / 2}, {(z + 1) / 2}\n"
                                         for i, (x, y, z) in enumerate(_NODES))
    text += "*ELEMENT, TYPE=C3D20, ELSET=E\n" + element
    text += "*MATERIAL, NAME=M\n*ELASTIC\n2.1e5, 0.3\n*SOLID SECTION, ELSET=E, MATERIAL=M\n"
    return text + body + steps


def line_of(text: str, needle: str) -> int:
    """1-based number of the first LF-separated line of ``text`` holding ``needle``."""
    return next(k for k, line in enumerate(text.split("\n"), start=1) if needle in line)


def error(path, **kw) -> DeckError:
    with pytest.raises(DeckError) as err:
        read_deck(path, **kw)
    assert "\n" not in str(err.value)  # one line
    return err.value


#: every character str.splitlines() breaks at, other than LF and CR LF
SEPARATORS = ["\r", "\x0b", "\x0c", "\x1c", "\x1d", "\x1e", "\x85", "\u2028", "\u2029"]


@pytest.mark.parametrize("sep", SEPARATORS, ids=[f"U+{ord(c):04X}" for c in SEPARATORS])
def test_a_separator_inside_a_comment_does_not_start_a_live_line(write_deck, sep):
    """The issue's ``** c<sep>TOPFACES, P2, 50.`` after a *DLOAD: CalculiX reads the whole line
    as a comment, so the pressure stays 5 (before: 50 was applied)."""
    steps = "*STEP\n*STATIC\n*DLOAD\nE, P2, 5.\n** c{}E, P2, 50.\n*END STEP\n"
    hidden = read_deck(write_deck(minimal(steps=steps.format(sep)), "hidden.inp"))
    whole = read_deck(write_deck(minimal(steps=steps.format(" ")), "whole.inp"))
    assert hidden.steps[0].dload == whole.steps[0].dload == {(1, 2): 5.0}


@pytest.mark.parametrize("sep", SEPARATORS + ["\x00", "\x1f", "\x7f", "\ufeff"],
                         ids=[f"U+{ord(c):04X}" for c in SEPARATORS + ["\x00", "\x1f", "\x7f", "\ufeff"]])
def test_a_control_character_in_a_data_line_is_one_line_naming_it(write_deck, sep):
    text = minimal(steps=f"*STEP\n*STATIC\n*DLOAD\nE, P2, 5.{sep}E, P2, 50.\n*END STEP\n")
    err = error(path := write_deck(text))
    assert str(err).startswith(f"{path}:{line_of(text, 'P2, 5.')}: a control character (U+{ord(sep):04X})")


def test_a_control_character_in_a_keyword_continuation_is_refused(write_deck):
    text = minimal("*NSET,\n\x1cNSET=A\n1\n")
    assert f":{line_of(text, chr(0x1c))}: a control character (U+001C)" in str(error(write_deck(text)))


def test_cr_lf_lines_read_as_lf_lines_and_tabs_are_blanks(write_deck):
    text = minimal("*BOUNDARY\n1, 1, 3\n", "*STEP\n*STATIC\n0.25,\t1.\n*DLOAD\nE, P2, 5.\n*END STEP\n")
    lf = read_deck(write_deck(text, "lf.inp"))
    crlf = read_deck(write_deck(text.replace("\n", "\r\n"), "crlf.inp"))
    assert crlf.steps[0].fractions == lf.steps[0].fractions == (0.25, 0.5, 0.75, 1.0)
    assert crlf.steps[0].dload == lf.steps[0].dload and crlf.steps[0].boundary == lf.steps[0].boundary
    assert (crlf.coords == lf.coords).all() and crlf.where[("node", 20)].endswith("crlf.inp:21")


def test_a_comment_after_blanks_is_a_comment_and_one_after_a_control_character_is_not(write_deck):
    ok = read_deck(write_deck(minimal(steps="*STEP\n*STATIC\n*DLOAD\nE, P2, 5.\n \t** E, P2, 50.\n*END STEP\n")))
    assert ok.steps[0].dload == {(1, 2): 5.0}
    text = minimal(steps="*STEP\n*STATIC\n*DLOAD\nE, P2, 5.\n\x0b** E, P2, 50.\n*END STEP\n")
    assert "a control character (U+000B)" in str(error(write_deck(text)))


def test_a_byte_order_mark_is_named_not_a_data_line(write_deck):
    err = error(path := write_deck("\ufeff" + minimal()))
    assert str(err).startswith(f"{path}:1: the file starts with a byte-order mark")
    assert "before the first keyword" not in str(err)


def test_a_line_longer_than_calculix_reads_is_refused(write_deck):
    """ccx reads 1319 bytes per fgets: the tail of a longer comment would be a live line there."""
    pad = "** " + "x" * (MAX_LINE_BYTES - 3)  # exactly the longest line CalculiX reads whole
    assert len(pad.encode()) == MAX_LINE_BYTES
    read_deck(write_deck(minimal(steps=f"*STEP\n*STATIC\n{pad}\n*END STEP\n"), "ok.inp"))
    text = minimal(steps=f"*STEP\n*STATIC\n*DLOAD\n{pad[:-9]}E, P2, 50.\n*END STEP\n")
    err = error(path := write_deck(text))
    assert str(err).startswith(f"{path}:{line_of(text, 'xE, P2, 50.')}: a line of {MAX_LINE_BYTES + 1} bytes")


# -- *STEP and *STATIC ---------------------------------------------------------------------------
def test_bare_nlgeom_is_geometric_nonlinearity_not_a_missing_value(write_deck):
    text = minimal(steps="*STEP, NLGEOM\n*STATIC\n*END STEP\n")
    err = error(path := write_deck(text))
    assert str(err).startswith(f"{path}:{line_of(text, 'NLGEOM')}: *STEP, NLGEOM (without a value: YES")
    assert "geometric nonlinearity" in str(err) and "not supported" in str(err) and "needs a value" not in str(err)
    assert read_deck(write_deck(minimal(steps="*STEP, NLGEOM=NO\n*STATIC\n*END STEP\n"), "no.inp")).steps


def test_step_values_are_kept_and_only_ignored_ones_get_a_note(write_deck):
    """Issue 31: INC= and *STATIC's minimum and maximum are honoured (tests/fe/test_incrementation.py),
    so no note; DIRECT ignores its minimum and maximum, a note each."""
    text = minimal(steps="*STEP, INC=1000\n*STATIC\n0.1, 1.0, 1e-6, 0.25\n*END STEP\n"
                         "*STEP\n*STATIC, DIRECT\n0.5, 1., 1e-3, 0.5\n*END STEP\n")
    d = read_deck(write_deck(text))
    static = f"{d.path}:{line_of(text, '0.5, 1., 1e-3')}"
    assert list(d.notes) == [f"{static}: *STATIC the minimum increment 0.001 ignored: DIRECT runs 2 fixed increments "
                             "(period / initial increment), each halved when Newton fails (up to six times)",
                             f"{static}: *STATIC the maximum increment 0.5 ignored: DIRECT runs 2 fixed increments "
                             "(period / initial increment), each halved when Newton fails (up to six times)"]
    first, second = d.steps
    assert (first.minimum, first.maximum, first.max_increments, first.direct) == (1e-6, 0.25, 1000, False)
    assert (second.minimum, second.maximum, second.max_increments, second.direct) == (None, None, None, True)
    assert first.fractions[-1] == 1.0 and len(first.fractions) == 10 and len(second.fractions) == 2


def test_a_second_static_data_line_is_refused(write_deck):
    text = minimal(steps="*STEP\n*STATIC\n0.5, 1.\n0.1, 1.\n*END STEP\n")
    said = str(error(path := write_deck(text)))
    assert said.startswith(f"{path}:{line_of(text, '0.1, 1.')}: *STATIC takes one data line")


@pytest.mark.parametrize("data, message", [
    ("1e-320, 1e300", "*STATIC: the initial increment 9.99989e-321 is subnormal: it must be positive and normal "
                      f"(at least {sys.float_info.min:g}) and at most the step period 1e+300"),
    ("1e-300, 1e300", "*STATIC: inf increments (period 1e+300 / initial increment 1e-300) exceed 100000"),
    ("2., 1.", "*STATIC: the initial increment 2 exceeds the step period 1 (it must be positive, normal and at most "
               "the period)"),  # as ccx: "initial increment size exceeds step size"
])
def test_static_increments_that_overflowed_are_one_line(write_deck, data, message):
    text = minimal(steps=f"*STEP\n*STATIC\n{data}\n*END STEP\n")
    assert str(error(path := write_deck(text))) == f"{path}:{line_of(text, data)}: {message}"


# -- bounds -------------------------------------------------------------------------------------
def test_an_include_of_a_huge_file_is_refused_before_reading(tmp_path):
    big = tmp_path / "big.inp"
    with open(big, "wb") as f:
        f.truncate(3 * 1024 ** 3)  # a sparse 3 GB file: reading it would take 3 GB
    (tmp_path / "m.inp").write_text("*NODE\n*INCLUDE, INPUT=big.inp\n")
    t0 = time.perf_counter()
    with pytest.raises(limits.InputLimitError) as err:
        read_blocks(tmp_path / "m.inp")
    assert time.perf_counter() - t0 < 5.0
    assert str(err.value) == (f"{tmp_path / 'm.inp'}:2: *INCLUDE file {big}: 3072 MB exceed the limit of 1024 MB "
                              "(the size of one input file; set ROUGHCONTACT_MAX_INPUT_MB to raise it (in MB))")


def test_the_deck_with_its_includes_is_bounded_together(tmp_path, monkeypatch):
    """One file of 0.6 MB included twice: each within 1 MB, the deck 1.2 MB."""
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "1")
    (tmp_path / "part.inp").write_text("** " + "x" * 1000 + "\n" * 1 + ("** y\n" * 120_000))
    (tmp_path / "m.inp").write_text("*NODE\n*INCLUDE, INPUT=part.inp\n*INCLUDE, INPUT=part.inp\n")
    with pytest.raises(limits.InputLimitError, match=r"m\.inp:3: \*INCLUDE file .*part\.inp: the deck with its "
                                                     r"\*INCLUDE files exceeds the limit of 1 MB"):
        read_blocks(tmp_path / "m.inp")


def _chain(tmp_path, depth: int):
    for k in range(depth):
        (tmp_path / f"f{k}.inp").write_text(f"*INCLUDE, INPUT=f{k + 1}.inp\n")
    (tmp_path / f"f{depth}.inp").write_text("1, 0., 0., 0.\n")
    (tmp_path / "m.inp").write_text("*NODE\n*INCLUDE, INPUT=f0.inp\n")
    return tmp_path / "m.inp"


def test_a_3000_deep_include_chain_is_one_line_at_the_limit(tmp_path):
    deck = _chain(tmp_path, 3000)
    with pytest.raises(limits.InputLimitError) as err:
        read_blocks(deck)
    assert str(err.value) == (f"{tmp_path / 'f31.inp'}:1: *INCLUDE nesting: 33 exceed the limit of 32 (the nesting "
                              "of *INCLUDE files; set ROUGHCONTACT_MAX_INCLUDE_DEPTH to raise it)")


def test_a_deep_include_chain_within_a_raised_limit_reads_without_recursion(tmp_path, monkeypatch):
    monkeypatch.setenv("ROUGHCONTACT_MAX_INCLUDE_DEPTH", "5000")
    (block,) = read_blocks(_chain(tmp_path, 3000))  # Python's recursion limit is 1000
    assert block.data[0].fields == ("1", "0.", "0.", "0.") and block.data[0].where.endswith("f3000.inp:1")


def test_generate_is_bounded_before_the_range_is_built(write_deck, monkeypatch):
    text = minimal("*NSET, NSET=BIG, GENERATE\n1, 2000000000\n")
    err = error(path := write_deck(text))
    assert isinstance(err, limits.InputLimitError)
    assert str(err) == (f"{path}:{line_of(text, '2000000000')}: *NSET, GENERATE 1, 2000000000, 1: the ids: "
                        "2000000000 exceed the limit of 20000000 (the ids a deck line may declare; set "
                        "ROUGHCONTACT_MAX_DECK_ITEMS to raise it)")
    # with the limit raised the range is still never built: the first id not defined is found lazily
    monkeypatch.setenv("ROUGHCONTACT_MAX_DECK_ITEMS", "3e9")
    t0 = time.perf_counter()
    assert str(error(path)).endswith(": GENERATE: node 21 is not defined")
    assert time.perf_counter() - t0 < 5.0


@pytest.mark.parametrize("field, message", [
    ("100000000000000000000", f"a node id must be a positive integer of at most {MAX_ID} (the engine indexes with "
                              "64-bit integers), got '100000000000000000000'"),
    (str(MAX_ID + 1), f"a node id must be a positive integer of at most {MAX_ID} (the engine indexes with 64-bit "
                      f"integers), got {MAX_ID + 1}"),
    ("9" * 1000, f"a node id must be a positive integer of at most {MAX_ID} (the engine indexes with 64-bit "
                 f"integers), got {limits.describe('9' * 1000)}"),  # int() of 5000 digits raises ValueError
    ("1_000", "a node id must be an integer, got '1_000'"),  # int() took it as 1000
    ("\u0661", "a node id must be an integer, got '\u0661'"),  # an Arabic-Indic one: int() took it as 1
])
def test_node_ids_beyond_what_the_engine_indexes_are_one_line(write_deck, field, message):
    text = minimal(f"*NODE\n{field}, 0., 0., 0.\n")
    err = error(path := write_deck(text))
    assert str(err) == f"{path}:{line_of(text, field[:30])}: {message}"


def test_a_node_id_at_the_largest_index_is_read(write_deck):
    d = read_deck(write_deck(minimal(f"*NODE\n{MAX_ID}, 0., 0., 2.\n")))
    assert int(d.node_ids[-1]) == MAX_ID and d.coords[-1].tolist() == [0.0, 0.0, 2.0]


@pytest.mark.parametrize("field", ["1_0.5", "inf", "nan", "0x10", "\u0661.0"])
def test_reals_are_read_as_fortran_reads_them(write_deck, field):
    text = minimal(f"*NODE\n30, {field}, 0., 0.\n")
    assert str(error(path := write_deck(text))) == (f"{path}:{line_of(text, '30, ')}: a coordinate must be a number, "
                                                    f"got {limits.describe(field)}")
    d = read_deck(write_deck(minimal("*NODE\n30, -.5D2, +1.E-1, 2\n"), "ok.inp"))
    assert d.coords[-1].tolist() == [-50.0, 0.1, 2.0]


def test_a_19_node_element_names_its_count_and_the_types(write_deck):
    """The issue's "with 40 nodes": a 19-node element followed by a 20-node one."""
    short = "1, " + ", ".join(map(str, range(1, 16))) + ",\n16, 17, 18, 19\n"
    text = minimal(element=short + "2, " + ", ".join(map(str, range(1, 16))) + ",\n16, 17, 18, 19, 20\n")
    err = error(path := write_deck(text))
    assert str(err) == (f"{path}:{line_of(text, '1, 1, 2')}: C3D20 element 1 with 19 nodes, and the next line "
                        f"({path}:{line_of(text, '2, 1, 2')}) has 21 fields, more than the 1 missing (C3D20 needs 20)")
    text = minimal(element=short)
    assert str(error(path := write_deck(text, "last.inp"))) == (
        f"{path}:{line_of(text, '1, 1, 2')}: C3D20 element 1 with 19 nodes (C3D20 needs 20)")


# -- *INCLUDE outside the deck's folder -----------------------------------------------------------
SECRET = "root:x:0:0:root:/root:/bin/bash\n"


def test_an_include_outside_the_folder_is_named_not_quoted(tmp_path):
    (tmp_path / "deck").mkdir()
    (tmp_path / "secret.txt").write_text(SECRET)
    deck = tmp_path / "deck" / "m.inp"
    deck.write_text(minimal("*NSET, NSET=X\n*INCLUDE, INPUT=../secret.txt\n"))
    err = error(deck)
    assert str(err).startswith(f"{tmp_path / 'secret.txt'}:1: the deck cannot use this line (a file outside the "
                               f"deck's folder, included at {deck}:")
    said = str(err).replace(str(tmp_path), "")  # the folder's name may hold "root" (pytest-of-root)
    assert "root" not in said.lower() and "bash" not in said and "x:0:0" not in said
    # the same file inside the folder: the message says what is wrong with it
    (tmp_path / "deck" / "secret.txt").write_text(SECRET)
    deck.write_text(minimal("*NSET, NSET=X\n*INCLUDE, INPUT=secret.txt\n"))
    assert "missing set: no *NSET ROOT:X:0:0:ROOT:/ROOT:/BIN/BASH" in str(error(deck))


def test_a_symlink_in_the_folder_to_a_file_outside_is_outside(tmp_path):
    (tmp_path / "deck").mkdir()
    (tmp_path / "secret.txt").write_text(SECRET)
    os.symlink(tmp_path / "secret.txt", tmp_path / "deck" / "link.inp")
    deck = tmp_path / "deck" / "m.inp"
    deck.write_text(minimal("*NSET, NSET=X\n*INCLUDE, INPUT=link.inp\n"))
    err = str(error(deck))
    assert err.startswith(f"{tmp_path / 'secret.txt'}:1: the deck cannot use this line")
    assert "root" not in err.replace(str(tmp_path), "").lower()


def test_an_include_outside_the_folder_is_read_when_valid(tmp_path):
    """Reading the user's own files is their right: a valid file outside the folder is read."""
    (tmp_path / "deck").mkdir()
    (tmp_path / "mesh.inp").write_text("30, 0., 0., 3.\n")
    deck = tmp_path / "deck" / "m.inp"
    deck.write_text(minimal("*NODE\n*INCLUDE, INPUT=../mesh.inp\n"))
    assert read_deck(deck).coords[-1].tolist() == [0.0, 0.0, 3.0]


def test_deck_values_in_messages_are_described_briefly(write_deck):
    text = minimal("*SURFACE, NAME=S\nE, " + "S" * 500 + "\n")
    err = str(error(path := write_deck(text)))
    assert err == f"{path}:{line_of(text, 'E, SSS')}: face {limits.describe('S' * 500)} is not one of S1 ... S6"
    assert len(err) < len(path) + 100
    text = minimal("*" + "FOO" * 100 + "\n")
    err = str(error(path := write_deck(text, "kw.inp")))
    assert err == (f"{path}:{line_of(text, 'FOOFOO')}: unsupported keyword *{limits.describe('FOO' * 100)} "
                   "(docs/own-model.md lists the subset)")


def test_the_element_family_is_described_without_a_numpy_repr(write_deck):
    import numpy as np

    from roughcontact.fe.deck_mesh import deck_mesh

    d = read_deck(write_deck(minimal()))
    with pytest.raises(ValueError) as err:
        deck_mesh(d, np.str_("cubicx"))  # a family read from an array, e.g. a config table
    assert str(err.value) == "family must be one of quadratic, cubic, got 'cubicx'"


def test_a_fifo_or_a_folder_as_deck_or_include_is_one_line(tmp_path):
    """Never opened (a FIFO blocks, /dev/zero never ends): limits.check_file first."""
    os.mkfifo(tmp_path / "pipe.inp")
    assert str(error(tmp_path / "pipe.inp")) == (f"{tmp_path / 'pipe.inp'}: not a regular file (a pipe or a device "
                                                 "is not read)")
    assert str(error(tmp_path)) == f"{tmp_path}: is a directory, not a file"
    (tmp_path / "m.inp").write_text("*NODE\n*INCLUDE, INPUT=pipe.inp\n")
    assert str(error(tmp_path / "m.inp")) == (f"{tmp_path / 'm.inp'}:2: *INCLUDE file {tmp_path / 'pipe.inp'}: not a "
                                              "regular file (a pipe or a device is not read)")
    (tmp_path / "latin1.inp").write_bytes(b"** caf\xe9\n")
    (tmp_path / "m.inp").write_text("*NODE\n*INCLUDE, INPUT=latin1.inp\n")
    assert str(error(tmp_path / "m.inp")) == (f"{tmp_path / 'm.inp'}:2: *INCLUDE file {tmp_path / 'latin1.inp'}: not "
                                              "utf-8 text (byte 6: b'\\xe9')")
