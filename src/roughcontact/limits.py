"""Bounds on what an input may make the library read or allocate, and short descriptions of
input values for messages (no physics, no roughcontact imports).

Every file a user hands the library (a scan, a deck and its ``*INCLUDE`` files, LAW.yaml, a
moments or result JSON) is read through :func:`read_bytes` / :func:`read_text`: a regular file
(not a FIFO or a device such as ``/dev/zero``, which would block or never end) of at most
:func:`max_input_bytes`. Every allocation whose size an input declares (a grid's cells, a
``GENERATE`` range, a mesh's elements) is checked first with :func:`check_count`. Each limit is
one environment variable; the message of a refused input names the limit and that variable, so a
user with a genuinely large input knows how to raise it.

Values quoted in messages go through :func:`describe`: bounded in length (a YAML alias bomb of
1 KB expands to hundreds of MB when printed with ``repr``), numpy scalars as plain numbers
(``0.0``, not ``np.float64(0.0)``).
"""

from __future__ import annotations

import json
import math
import os
import stat
from pathlib import Path
from typing import Any

__all__ = ["InputLimitError", "max_input_bytes", "max_count", "read_bytes", "read_text", "check_count",
           "check_file", "describe", "parse_json", "LIMITS"]

#: name -> (environment variable, default, what it bounds, unit)
LIMITS = {
    "input_mb": ("ROUGHCONTACT_MAX_INPUT_MB", 1024, "the size of one input file", "MB"),
    # 8192² cells: the largest maps instruments write; the moments' FFTs take ~100 B per cell
    "cells": ("ROUGHCONTACT_MAX_CELLS", 8192 * 8192, "the points of one height map", ""),
    # a deck's nodes/elements/set members; 2·10⁷ nodes is far beyond what the engine solves in 24 GiB
    "deck_items": ("ROUGHCONTACT_MAX_DECK_ITEMS", 20_000_000, "the ids a deck line may declare", ""),
    # a bound on building a model, not a promise that it solves: the direct solver's memory grows
    # faster than the unknowns (docs/performance.md: 61 570 of them took 2.9 GB)
    "fe_dofs": ("ROUGHCONTACT_MAX_FE_DOFS", 2_000_000, "the unknowns of one finite-element model", ""),
    "include_depth": ("ROUGHCONTACT_MAX_INCLUDE_DEPTH", 32, "the nesting of *INCLUDE files", ""),
    "nesting": ("ROUGHCONTACT_MAX_NESTING", 64, "the nesting of a JSON or YAML document", ""),
}


class InputLimitError(ValueError):
    """An input that exceeds one of :data:`LIMITS` (a ValueError: the CLI prints one line, exit 2)."""


def _limit(name: str) -> float:
    var, default, what, _unit = LIMITS[name]
    text = os.environ.get(var)
    if text is None or not text.strip():
        return default
    try:
        value = float(text)
    except ValueError:
        raise InputLimitError(f"{var}={describe(text)}: must be a positive number ({what})") from None
    if not (math.isfinite(value) and value > 0):
        raise InputLimitError(f"{var}={describe(text)}: must be a positive number ({what})")
    return value


def max_input_bytes() -> int:
    """The largest input file read, in bytes (``ROUGHCONTACT_MAX_INPUT_MB``, default 1024 MB)."""
    return int(_limit("input_mb") * 1024 * 1024)


def max_count(name: str) -> int:
    """The limit ``name`` of :data:`LIMITS` (its environment variable, else its default)."""
    return int(_limit(name))


def _raise_hint(name: str) -> str:
    var, _default, _what, unit = LIMITS[name]
    return f"set {var} to raise it" + (f" (in {unit})" if unit else "")


def check_count(count: float, name: str, what: str) -> int:
    """``count`` as an int if it is within the limit ``name`` (:data:`LIMITS`), else
    InputLimitError naming ``what``, the limit and how to raise it. Call it *before* allocating."""
    limit = max_count(name)
    # an int is compared as an int: math.isfinite(10**400) raises OverflowError
    if (not isinstance(count, int) and not math.isfinite(count)) or count > limit:
        shown = f"{count:.3g}" if isinstance(count, float) else (
            str(count) if len(str(count)) <= 60 else describe(count))
        raise InputLimitError(f"{what}: {shown} exceed the limit of {limit} ({LIMITS[name][2]}; {_raise_hint(name)})")
    return int(count)


def _checked_regular(path: Path, what: str) -> int:
    """The size of ``path`` if it is a regular file within :func:`max_input_bytes`."""
    try:
        st = os.stat(path)  # follows symlinks: a link to a regular file is fine
    except FileNotFoundError:
        raise ValueError(f"{what} {path}: no such file") from None
    except OSError as exc:
        raise ValueError(f"{what} {path}: cannot read it ({exc.strerror or exc})") from None
    if stat.S_ISDIR(st.st_mode):
        raise ValueError(f"{what} {path}: is a directory, not a file")
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"{what} {path}: not a regular file (a pipe or a device is not read)")
    limit = max_input_bytes()
    if st.st_size > limit:
        raise InputLimitError(
            f"{what} {path}: {st.st_size / 1048576:.0f} MB exceed the limit of {limit / 1048576:.0f} MB "
            f"({LIMITS['input_mb'][2]}; {_raise_hint('input_mb')})")
    return st.st_size


def read_bytes(path: str | os.PathLike, what: str = "input file") -> bytes:
    """The bytes of ``path``: a regular file of at most :func:`max_input_bytes` (checked before
    reading, and the read itself is capped, should the file grow meanwhile). ValueError (one
    line naming ``what`` and the path) otherwise."""
    path = Path(path)
    size = _checked_regular(path, what)
    limit = max_input_bytes()
    try:
        with open(path, "rb") as f:
            # at most one byte beyond the size seen (f.read(n) reserves n bytes up front)
            data = f.read(min(size, limit) + 1)
    except OSError as exc:
        raise ValueError(f"{what} {path}: cannot read it ({exc.strerror or exc})") from None
    if len(data) > size:
        raise ValueError(f"{what} {path}: grew while it was read (a file still being written?)")
    return data


def check_file(path: str | os.PathLike, what: str = "input file") -> int:
    """Check without reading that ``path`` is a regular file within the size limit (for readers
    that open the file themselves, e.g. numpy or an instrument library); return its size."""
    return _checked_regular(Path(path), what)


def read_text(path: str | os.PathLike, what: str = "input file", encoding: str = "utf-8") -> str:
    """:func:`read_bytes` decoded; a file that is not valid ``encoding`` is one line naming the
    file and the byte offset."""
    data = read_bytes(path, what)
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as exc:
        raise ValueError(f"{what} {path}: not {encoding} text (byte {exc.start}: {data[exc.start:exc.start + 1]!r})") from None


def describe(value: Any, limit: int = 60) -> str:
    """A short, readable rendering of an input value for a message: numpy scalars as plain
    numbers, arrays by shape, containers by type and length, anything longer than ``limit``
    characters cut with "…". Never builds the full repr of a large or deeply nested value."""
    if isinstance(value, bool) or value is None:
        return repr(value)
    if hasattr(value, "dtype") and getattr(value, "shape", None) == ():  # a numpy scalar
        value = value.item()
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) or math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, int):
        text = str(value) if abs(value) < 10 ** 30 else f"an integer of {len(str(abs(value)))} digits"
        return text
    if isinstance(value, str):
        text = repr(value[:limit])
        return text if len(value) <= limit else text[:-1] + "…" + text[-1]
    if hasattr(value, "shape") and hasattr(value, "dtype"):
        return f"an array of shape {tuple(int(n) for n in value.shape)}"
    if isinstance(value, dict):
        return f"a mapping of {len(value)} key{'' if len(value) == 1 else 's'}"
    if isinstance(value, (list, tuple)):
        if len(value) <= 6 and all(isinstance(v, (int, float)) or hasattr(v, "dtype") for v in value):
            text = "(" + ", ".join(describe(v, limit) for v in value) + ("," if len(value) == 1 else "") + ")"
            if isinstance(value, list):
                text = "[" + text[1:-1].rstrip(",") + "]"
            if len(text) <= limit:
                return text
        return f"a list of {len(value)} item{'' if len(value) == 1 else 's'}"
    text = object.__repr__(value) if not isinstance(value, (bytes, bytearray)) else repr(bytes(value[:limit]))
    return text if len(text) <= limit else text[:limit] + "…"


def _depth(value: Any, limit: int) -> int:
    """The nesting depth of parsed JSON/YAML, without recursion (stops at ``limit`` + 1)."""
    deepest, stack = 0, [(value, 1)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, (dict, list)):
            deepest = max(deepest, depth)
            if deepest > limit:
                return deepest
            stack.extend((v, depth + 1) for v in (item.values() if isinstance(item, dict) else item))
    return deepest


def parse_json(text: str, what: str) -> Any:
    """``json.loads`` of an input with its errors as one line naming ``what``: a syntax error
    with its line and column, nesting beyond ``ROUGHCONTACT_MAX_NESTING`` (json's recursion would
    otherwise end in RecursionError), NaN/Infinity refused (not JSON)."""
    limit = max_count("nesting")

    def constant(name):
        raise ValueError(f"{what}: {name} is not JSON (write a number or null)")

    try:
        value = json.loads(text, parse_constant=constant)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{what}: not JSON (line {exc.lineno}, column {exc.colno}: {exc.msg})") from None
    except RecursionError:  # json's C scanner stops at the interpreter's recursion limit (~1000)
        raise InputLimitError(f"{what}: nested deeper than {limit} levels ({_raise_hint('nesting')})") from None
    if _depth(value, limit) > limit:
        raise InputLimitError(f"{what}: nested deeper than {limit} levels ({_raise_hint('nesting')})")
    return value
