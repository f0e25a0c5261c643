"""The keyword language of CalculiX/Abaqus input decks, as blocks of lines (no meaning yet).

A deck is a sequence of keyword blocks: a keyword line ``*NAME, PARAM=VALUE, FLAG`` followed by
its data lines (comma-separated fields). This module only reads that structure; what a keyword
means is :mod:`.deck`'s. The rules implemented (those of Abaqus and CalculiX):

* a line starting with ``**`` is a comment; blank lines are skipped;
* keyword names and parameter names are case-insensitive and their inner spaces normalised
  (``*solid  section`` is ``*SOLID SECTION``); parameter values and data fields keep their text
  (the reader upper-cases names of sets, materials and surfaces, as both codes do);
* a keyword line that ends with a comma continues on the next line;
* a data line that ends with a comma continues on the next line (element connectivities over
  two lines); fields are stripped, empty trailing fields dropped;
* ``*INCLUDE, INPUT=file`` inserts another file in place (nested; a path relative to the
  including file's folder, as ccx sees it when run in the deck's folder); a cycle is an error.

Every block and data line remembers its file and line number, so that every error the reader
raises (:class:`DeckError`) names where it comes from: ``model.inp:12: ...``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["DeckError", "DataLine", "Keyword", "read_blocks", "parse_blocks"]

_CONTROL = re.compile(r"[\x00-\x08\x0a-\x1f\x7f]")


class DeckError(ValueError):
    """A deck that cannot be read: the message starts with ``file:line:``."""

    def __init__(self, where: str, message: str):
        self.where = where
        super().__init__(f"{where}: {message}")


@dataclass(frozen=True)
class DataLine:
    """The fields of one data line (continuations joined) and where it starts."""

    fields: tuple[str, ...]
    where: str


@dataclass(frozen=True)
class Keyword:
    """One keyword block: the normalised upper-case ``name`` (e.g. "SOLID SECTION"), its
    parameters (upper-case names → value text, or None for a flag), its data lines, where
    the keyword line is."""

    name: str
    params: dict[str, str | None]
    data: tuple[DataLine, ...]
    where: str
    _used: set = field(default_factory=set, repr=False, compare=False)

    def param(self, name: str, default: str | None = None, *, required: bool = False) -> str | None:
        """The value of parameter ``name`` (upper case); DeckError if required and missing or
        given without a value."""
        self._used.add(name)
        if name not in self.params:
            if required:
                raise DeckError(self.where, f"*{self.name} needs the parameter {name}=")
            return default
        value = self.params[name]
        if value is None or value == "":
            raise DeckError(self.where, f"*{self.name}: the parameter {name} needs a value ({name}=...)")
        return value

    def flag(self, name: str) -> bool:
        """Whether the parameter ``name`` is present (a flag such as GENERATE)."""
        self._used.add(name)
        return name in self.params

    def check_params(self, allowed=()) -> None:
        """DeckError naming the first parameter that is neither read nor in ``allowed``."""
        for name in self.params:
            if name not in self._used and name not in allowed:
                raise DeckError(self.where, f"*{self.name}: the parameter {name} is not supported here")


def _normalise(name: str) -> str:
    return " ".join(name.upper().split())


def _split(text: str) -> list[str]:
    return [f.strip() for f in text.split(",")]


def _logical_lines(path: Path, stack: tuple[Path, ...], text: str | None = None):
    """(text, where) of every non-comment, non-blank line, *INCLUDE expanded, continuations
    of keyword lines joined (data continuations are joined by :func:`parse_blocks`)."""
    if text is None:
        try:
            text = path.read_text(encoding="utf-8", errors="strict")
        except UnicodeDecodeError as exc:
            raise DeckError(f"{path}", f"not a text file (UTF-8): {exc.reason}") from None
    raw = text.splitlines()
    i = 0
    while i < len(raw):
        line, start = raw[i].strip(), i + 1
        i += 1
        if not line or line.startswith("**"):
            continue
        where = f"{path}:{start}"
        if _CONTROL.search(line):
            raise DeckError(where, "control character in the line")
        if line.startswith("*"):
            while line.endswith(",") and i < len(raw) and not raw[i].lstrip().startswith("*"):
                nxt = raw[i].strip()
                i += 1
                if nxt and not nxt.startswith("**"):
                    line += " " + nxt
            name, *rest = _split(line[1:])
            if _normalise(name) == "INCLUDE":
                target = None
                for item in rest:
                    key, _, value = item.partition("=")
                    if _normalise(key) == "INPUT" and value.strip():
                        target = value.strip().strip('"')
                if target is None:
                    raise DeckError(where, "*INCLUDE needs INPUT=<file>")
                inc = (path.parent / target).resolve()
                if inc in stack:
                    raise DeckError(where, f"*INCLUDE of {target} makes a cycle")
                if not inc.is_file():
                    raise DeckError(where, f"*INCLUDE: no file {inc}")
                yield from _logical_lines(inc, stack + (inc,))
                continue
        yield line, where


def parse_blocks(lines) -> list[Keyword]:
    """Keyword blocks from (text, where) lines (keyword continuations already joined)."""
    blocks: list[Keyword] = []
    name, params, data, where = None, {}, [], ""
    pending: list[str] = []
    pending_where = ""

    def close():
        if pending:
            data.append(DataLine(tuple(f for f in pending if f != ""), pending_where))
        if name is not None:
            blocks.append(Keyword(name, params, tuple(data), where))

    for text, at in lines:
        if text.startswith("*"):
            close()
            pending = []
            head, *rest = _split(text[1:])
            name, params, data, where = _normalise(head), {}, [], at
            if not name:
                raise DeckError(at, "a keyword line without a keyword")
            for item in rest:
                if not item:
                    continue
                key, eq, value = item.partition("=")
                key = _normalise(key)
                if key in params:
                    raise DeckError(at, f"*{name}: the parameter {key} is given twice")
                params[key] = value.strip() if eq else None
            continue
        if name is None:
            raise DeckError(at, "a data line before the first keyword")
        fields = _split(text)
        if not pending:
            pending_where = at
        pending += fields
        if text.endswith(","):  # continues on the next line
            pending = pending[:-1]  # the empty field after the trailing comma
            continue
        data.append(DataLine(tuple(pending), pending_where))
        pending = []
    close()
    return blocks


def read_blocks(path, text: str | None = None) -> list[Keyword]:
    """The keyword blocks of the deck file ``path`` (module docstring for the rules), or of
    ``text`` named ``path`` (its *INCLUDEs relative to path's folder)."""
    path = Path(path)
    if text is None and not path.is_file():
        raise DeckError(str(path), "no such file")
    return parse_blocks(_logical_lines(path.resolve(), (path.resolve(),), text))
