"""roughcontact.limits: every read bounded (regular files within ROUGHCONTACT_MAX_INPUT_MB), declared
counts checked before allocating, JSON nesting bounded, input values quoted briefly in messages."""

from __future__ import annotations

import math
import os
import threading

import numpy as np
import pytest

from roughcontact import limits

MB = 1048576


# ---------------------------------------------------------------------------------------------
# describe
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("value, shown", [
    (np.float64(0.0), "0.0"), (np.float32(0.5), "0.5"), (np.int64(7), "7"), (np.bool_(True), "True"),
    (np.float64("inf"), "inf"), (-math.inf, "-inf"), (math.nan, "nan"), (True, "True"), (None, "None"),
    (1.25, "1.25"), (10 ** 29, str(10 ** 29)),
])
def test_describe_numbers_as_plain_numbers(value, shown):
    """numpy scalars without their repr (np.float64(0.0) leaked into messages before)."""
    assert limits.describe(value) == shown


def test_describe_big_integers_by_their_digits():
    assert limits.describe(10 ** 30) == "an integer of 31 digits"
    assert limits.describe(-(10 ** 4000)) == "an integer of 4001 digits"  # str() of it would raise


def test_describe_cuts_long_strings():
    text = limits.describe("x" * 10_000)
    assert text.startswith("'" + "x" * 60) and text.endswith("x…'") and len(text) <= 60 + 4
    assert limits.describe("x" * 60) == "'" + "x" * 60 + "'"
    assert limits.describe("a\nb") == r"'a\nb'"  # one line: the newline escaped
    assert len(limits.describe("y" * 100, limit=10)) <= 10 + 4


def test_describe_containers_by_type_and_length():
    assert limits.describe((np.float64(0.0), np.float64(1.0), 2)) == "(0.0, 1.0, 2)"
    assert limits.describe([1, 2.5]) == "[1, 2.5]"
    assert limits.describe((3,)) == "(3,)"
    assert limits.describe(list(range(7))) == "a list of 7 items"
    assert limits.describe({"a": 1, "b": 2}) == "a mapping of 2 keys"
    assert limits.describe(np.zeros((3, 4))) == "an array of shape (3, 4)"
    assert limits.describe(b"\x00" * 1000).startswith("b'\\x00") and len(limits.describe(b"\x00" * 1000)) <= 61


def test_describe_an_alias_bomb_without_building_its_repr():
    """A YAML alias bomb: each level is the previous one 9 times; its repr would be ~10^9 items."""
    level = ["lol"]
    for _ in range(9):
        level = [level] * 9
    assert limits.describe(level) == "a list of 9 items"
    assert limits.describe({"a": level}) == "a mapping of 1 key"


# ---------------------------------------------------------------------------------------------
# parse_json
# ---------------------------------------------------------------------------------------------
def test_parse_json_reads_json():
    assert limits.parse_json('{"a": [1, 2.5, null]}', "x.json") == {"a": [1, 2.5, None]}


@pytest.mark.parametrize("depth", [65, 1000, 50_000])
def test_parse_json_bounds_nesting(depth):
    """50 000 levels: json's C scanner ends in RecursionError; 65: beyond the default limit of 64."""
    with pytest.raises(limits.InputLimitError, match=r"^x.json: nested deeper than 64 levels \(set "
                                                     r"ROUGHCONTACT_MAX_NESTING to raise it\)$"):
        limits.parse_json("[" * depth + "]" * depth, "x.json")


def test_parse_json_nesting_limit_is_the_environment_variable(monkeypatch):
    assert limits.parse_json("[" * 64 + "]" * 64, "x") is not None  # exactly the limit
    monkeypatch.setenv("ROUGHCONTACT_MAX_NESTING", "100")
    assert limits.parse_json("[" * 100 + "]" * 100, "x") is not None
    with pytest.raises(limits.InputLimitError, match="nested deeper than 100 levels"):
        limits.parse_json("[" * 101 + "]" * 101, "x")
    monkeypatch.setenv("ROUGHCONTACT_MAX_NESTING", "-3")
    with pytest.raises(limits.InputLimitError, match="ROUGHCONTACT_MAX_NESTING='-3': must be a positive number"):
        limits.parse_json("[]", "x")


@pytest.mark.parametrize("constant", ["NaN", "Infinity", "-Infinity"])
def test_parse_json_refuses_nan(constant):
    with pytest.raises(ValueError, match=f"^x.json: {constant} is not JSON"):
        limits.parse_json(f'{{"m00": {constant}}}', "x.json")


def test_parse_json_syntax_error_names_line_and_column():
    with pytest.raises(ValueError, match=r"^x.json: not JSON \(line 2, column 7: Expecting value\)$"):
        limits.parse_json('{"a": 1,\n "b": }', "x.json")


# ---------------------------------------------------------------------------------------------
# read_bytes / read_text / check_file
# ---------------------------------------------------------------------------------------------
def test_read_a_regular_file(tmp_path):
    path = tmp_path / "a.txt"
    path.write_bytes("µm\n".encode())
    assert limits.read_bytes(path) == "µm\n".encode() and limits.read_text(path) == "µm\n"
    assert limits.check_file(path) == 4
    link = tmp_path / "link.txt"
    link.symlink_to(path)
    assert limits.read_text(link) == "µm\n"


def test_read_a_fifo_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    result = {}

    def read():
        try:
            limits.read_bytes(fifo, "scan")
        except ValueError as exc:
            result["error"] = str(exc)

    thread = threading.Thread(target=read, daemon=True)
    thread.start()
    thread.join(10)
    assert not thread.is_alive(), "read_bytes blocked on a FIFO"
    assert result["error"] == f"scan {fifo}: not a regular file (a pipe or a device is not read)"


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/null"])
def test_read_a_device_is_refused(device):
    if not os.path.exists(device):
        pytest.skip(f"no {device}")
    with pytest.raises(ValueError, match=f"^LAW.yaml {device}: not a regular file"):
        limits.read_text(device, "LAW.yaml")
    with pytest.raises(ValueError, match="not a regular file"):
        limits.check_file(device)


def test_read_a_directory_or_a_missing_file(tmp_path):
    with pytest.raises(ValueError, match=f"^deck {tmp_path}: is a directory, not a file$"):
        limits.read_bytes(tmp_path, "deck")
    with pytest.raises(ValueError, match=f"^deck {tmp_path / 'none.inp'}: no such file$"):
        limits.read_bytes(tmp_path / "none.inp", "deck")


def test_a_sparse_file_over_the_limit_is_refused_before_reading(tmp_path, monkeypatch):
    """3 MB that take no disk (truncate), the limit lowered to 2 MB: refused from its size, and
    read once the limit is raised to 4 MB."""
    big = tmp_path / "big.xyz"
    with open(big, "wb") as f:
        f.truncate(3 * MB)
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "2")
    assert limits.max_input_bytes() == 2 * MB
    message = (f"scan {big}: 3 MB exceed the limit of 2 MB (the size of one input file; "
               "set ROUGHCONTACT_MAX_INPUT_MB to raise it (in MB))")
    for read in (limits.read_bytes, limits.read_text, limits.check_file):
        with pytest.raises(limits.InputLimitError) as info:
            read(big, "scan")
        assert str(info.value) == message
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "4")
    assert len(limits.read_bytes(big)) == 3 * MB
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "0.5")  # fractions of a MB
    assert limits.max_input_bytes() == MB // 2


def test_the_default_input_limit_is_1024_mb(monkeypatch):
    monkeypatch.delenv("ROUGHCONTACT_MAX_INPUT_MB", raising=False)
    assert limits.max_input_bytes() == 1024 * MB
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", " ")
    assert limits.max_input_bytes() == 1024 * MB


@pytest.mark.parametrize("value", ["abc", "0", "-1", "nan", "inf"])
def test_a_bad_limit_variable_is_one_line(monkeypatch, value, tmp_path):
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", value)
    (tmp_path / "a").write_text("x")
    with pytest.raises(limits.InputLimitError, match=r"^ROUGHCONTACT_MAX_INPUT_MB=.*must be a positive number"):
        limits.read_bytes(tmp_path / "a")


def test_read_text_names_the_byte_that_is_not_utf8(tmp_path):
    path = tmp_path / "LAW.yaml"
    path.write_bytes(b"E_star: 1\n\xff\n")
    with pytest.raises(ValueError, match=rf"^law file {path}: not utf-8 text \(byte 10: b'\\xff'\)$"):
        limits.read_text(path, "law file")


# ---------------------------------------------------------------------------------------------
# check_count
# ---------------------------------------------------------------------------------------------
def test_check_count_within_and_beyond_the_limit(monkeypatch):
    monkeypatch.delenv("ROUGHCONTACT_MAX_DECK_ITEMS", raising=False)
    assert limits.check_count(20_000_000, "deck_items", "x") == 20_000_000
    with pytest.raises(limits.InputLimitError) as info:
        limits.check_count(2_000_000_000, "deck_items", "deck.inp, line 3: *NSET, GENERATE 1, 2000000000")
    assert str(info.value) == ("deck.inp, line 3: *NSET, GENERATE 1, 2000000000: 2000000000 exceed the limit of "
                               "20000000 (the ids a deck line may declare; set ROUGHCONTACT_MAX_DECK_ITEMS to raise it)")
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", "100")
    assert limits.check_count(100, "cells", "grid") == 100
    with pytest.raises(limits.InputLimitError, match=r"^grid: 1e\+08 exceed the limit of 100 \(the points of one "
                                                     r"height map; set ROUGHCONTACT_MAX_CELLS to raise it\)$"):
        limits.check_count(1e8, "cells", "grid")


@pytest.mark.parametrize("count", [math.inf, math.nan])
def test_check_count_refuses_non_finite_counts(count):
    with pytest.raises(limits.InputLimitError, match="exceed the limit"):
        limits.check_count(count, "cells", "grid")


def test_check_count_returns_an_int_and_accepts_a_huge_int_without_float_overflow():
    assert isinstance(limits.check_count(12.0, "cells", "grid"), int)
    with pytest.raises(limits.InputLimitError, match=r"^n: 1{40} exceed"):
        limits.check_count(int("1" * 40), "cells", "n")


def test_check_count_of_an_int_beyond_a_double_is_one_line():
    """A deck may declare 10^400 ids: the limit's message, not OverflowError."""
    with pytest.raises(limits.InputLimitError, match=r"^n: an integer of 401 digits exceed the limit"):
        limits.check_count(10 ** 400, "cells", "n")


def test_describe_keeps_exactly_limit_characters():
    assert limits.describe("x" * 10_000) == "'" + "x" * 60 + "…'"


def test_every_limit_is_in_the_usage_page():
    """A user refused by a limit finds the variable that raises it in docs/usage.md (the README's
    command reference until issue 33)."""
    from pathlib import Path

    usage = (Path(__file__).resolve().parents[1] / "docs" / "usage.md").read_text()
    for var, _default, _what, _unit in limits.LIMITS.values():
        assert f"`{var}`" in usage, var
