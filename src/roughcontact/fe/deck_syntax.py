"""The keyword language of CalculiX/Abaqus input decks, as blocks of lines (no meaning yet).

A deck is a sequence of keyword blocks: a keyword line ``*NAME, PARAM=VALUE, FLAG`` followed by
its data lines (comma-separated fields). This module only reads that structure; what a keyword
means is :mod:`.deck`'s. The rules implemented (those of Abaqus and CalculiX):

* lines end at LF, a CR just before it dropped (CR LF): the lines CalculiX's ``readinput.c``
  reads with ``fgets``, at most 1319 bytes each (a longer line it reads as several lines, so
  one is an error here). Nothing else breaks a line: a vertical tab, form feed, U+001C-U+001E,
  NEL (U+0085) or U+2028/U+2029 is a character of its line, allowed in a comment and an error
  anywhere else (as is every other control character but the tab, and a byte-order mark: the
  first line of a file that starts with one is not a keyword line for CalculiX);
* a line whose first characters other than blanks (spaces, tabs) are ``**`` is a comment; blank
  lines are skipped;
* keyword names and parameter names are case-insensitive and their inner spaces normalised
  (``*solid  section`` is ``*SOLID SECTION``); parameter values and data fields keep their text
  (the reader upper-cases names of sets, materials and surfaces, as both codes do);
* a keyword line that ends with a comma continues on the next line (comments between skipped);
* a data line that ends with a comma continues on the next line (element connectivities over
  two lines); fields are stripped of blanks, empty trailing fields dropped;
* ``*INCLUDE, INPUT=file`` inserts another file in place (nested up to
  ``ROUGHCONTACT_MAX_INCLUDE_DEPTH`` levels; a path relative to the including file's folder, as
  ccx sees it when run in the deck's folder); a cycle is an error. Every file is read through
  :mod:`roughcontact.limits` (a regular file within the size limit), and the deck with all its
  included files together within that limit too (a file included many times over).

Every block and data line remembers its file and line number (:class:`Where`), so that every
error the reader raises (:class:`DeckError`) names where it comes from: ``model.inp:12: ...``.
A file included from outside the main deck's folder may be any file the user can read: an error
on one of its lines names the file and line but does not quote the line (docs/own-model.md).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from .. import limits

__all__ = ["DeckError", "DeckLimitError", "DataLine", "Keyword", "Where", "read_blocks", "parse_blocks", "shown",
           "MAX_LINE_BYTES"]

#: refused outside comments: C0 controls but the tab, DEL, C1 controls (NEL U+0085 among them),
#: the line and paragraph separators U+2028/U+2029 and the byte-order mark U+FEFF
_CONTROL = re.compile("[\x00-\x08\x0a-\x1f\x7f-\x9f\u2028\u2029\ufeff]")
#: CalculiX reads a line with fgets(buff, 1320, f) (readinput.c): at most 1319 bytes
MAX_LINE_BYTES = 1319
_BLANKS = " \t"  # what CalculiX removes from a line (readinput.c); str.strip() would remove \x0b, \x1c, U+2028 ...


def shown(text: str) -> str:
    """A name from the deck as a message shows it: as written if short and printable, else
    through :func:`limits.describe` (quoted, cut)."""
    return text if len(text) <= 60 and text.isprintable() else limits.describe(text)


class Where(str):
    """``file:line`` of a deck line. ``outside``: the file lies outside the main deck's folder
    (an error there does not quote the line); ``via``: where it was included from."""

    outside: bool = False
    via: str = ""


def _where(path: Path, line: int, outside: bool = False, via: str = "") -> Where:
    w = Where(f"{path}:{line}")
    w.outside, w.via = outside, via
    return w


class DeckError(ValueError):
    """A deck that cannot be read: the message starts with ``file:line:``. On a line of a file
    outside the main deck's folder (:attr:`Where.outside`) the message does not quote the line
    unless ``quotes=False`` says it quotes nothing of it."""

    def __init__(self, where: str, message: str, *, quotes: bool = True):
        if quotes and getattr(where, "outside", False):
            message = ("the deck cannot use this line (a file outside the deck's folder, included at "
                       f"{where.via}: its lines are not quoted; see docs/own-model.md for what a deck may hold)")
        self.where = where
        super().__init__(f"{where}: {message}")


class DeckLimitError(DeckError, limits.InputLimitError):
    """A deck beyond one of :data:`roughcontact.limits.LIMITS` (file size, *INCLUDE nesting, ids)."""


def _limited(where, exc: Exception):
    """A DeckError at ``where`` with the message of a limits error (a limit or an unreadable file)."""
    cls = DeckLimitError if isinstance(exc, limits.InputLimitError) else DeckError
    return cls(where, str(exc), quotes=False)


def check_count(count, name: str, where, what: str) -> int:
    """:func:`limits.check_count` as a DeckLimitError at ``where``."""
    try:
        return limits.check_count(count, name, what)
    except limits.InputLimitError as exc:
        raise _limited(where, exc) from None


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
                raise DeckError(self.where, f"*{self.name}: the parameter {shown(name)} is not supported here")


def _normalise(name: str) -> str:
    return " ".join(name.upper().split())


def _split(text: str) -> list[str]:
    return [f.strip(_BLANKS) for f in text.split(",")]


def _significant(path: Path, text: str, outside: bool, via: str):
    """(text without surrounding blanks, Where) of the lines of one file that are neither blank
    nor comments; DeckError on a control character or an overlong line."""
    if text.startswith("\ufeff"):
        raise DeckError(_where(path, 1, outside, via), "the file starts with a byte-order mark (U+FEFF), which "
                        "CalculiX reads as part of the first line: save the file as UTF-8 without BOM", quotes=False)
    for n, raw in enumerate(text.split("\n"), start=1):  # LF only: not str.splitlines (module docstring)
        if raw.endswith("\r"):  # CR LF
            raw = raw[:-1]
        if len(raw) > MAX_LINE_BYTES // 4 and len(raw.encode("utf-8", "surrogatepass")) > MAX_LINE_BYTES:
            raise DeckError(_where(path, n, outside, via), f"a line of {len(raw.encode('utf-8', 'surrogatepass'))} "
                            f"bytes: CalculiX reads at most {MAX_LINE_BYTES} bytes per line and the rest as a line "
                            "of its own (split it; a data line continues after a trailing comma)", quotes=False)
        line = raw.strip(_BLANKS)
        if not line or line.startswith("**"):
            continue
        where = _where(path, n, outside, via) if outside else f"{path}:{n}"  # a plain str: most lines
        bad = _CONTROL.search(line)
        if bad:
            raise DeckError(where, f"a control character (U+{ord(bad.group()):04X}) in the line, outside a comment "
                                   "(CalculiX would read it as part of the line; only a tab may stand between fields)",
                            quotes=False)
        yield line, where


class _File:
    """One file being read: its significant lines and one line of look-ahead."""

    def __init__(self, path: Path, lines):
        self.path, self.lines, self.ahead = path, lines, None

    def next(self):
        if self.ahead is not None:
            item, self.ahead = self.ahead, None
            return item
        return next(self.lines, None)


def _logical_lines(path: Path, text: str | None = None):
    """(text, where) of every non-comment, non-blank line, *INCLUDE expanded (without
    recursion: the nesting is bounded by a limit, not by Python's stack), continuations of
    keyword lines joined (data continuations are joined by :func:`parse_blocks`)."""
    root = path.parent
    total, limit = len(text or ""), limits.max_input_bytes()  # bytes read so far (a text given: its characters)
    if text is None:
        try:
            total, text = limits.check_file(path, "deck"), limits.read_text(path, "deck")
        except ValueError as exc:  # "deck PATH: why" as "PATH: why"
            raise type(_limited(path, exc))(str(path), str(exc).removeprefix(f"deck {path}: "), quotes=False) from None
    stack = [_File(path, _significant(path, text, False, ""))]
    while stack:
        f = stack[-1]
        item = f.next()
        if item is None:
            stack.pop()
            continue
        line, where = item
        if not line.startswith("*"):
            yield line, where
            continue
        while line.endswith(","):  # a keyword line continued on the next line
            nxt = f.next()
            if nxt is not None and nxt[0].startswith("*"):
                f.ahead = nxt
            if nxt is None or f.ahead is not None:
                break
            line += " " + nxt[0]
        name, *rest = _split(line[1:])
        if _normalise(name) != "INCLUDE":
            yield line, where
            continue
        target = None
        for item in rest:
            key, _, value = item.partition("=")
            if _normalise(key) == "INPUT" and value.strip(_BLANKS):
                target = value.strip(_BLANKS).strip('"')
        if target is None:
            raise DeckError(where, "*INCLUDE needs INPUT=<file>")
        inc = (f.path.parent / target).resolve()
        if any(inc == g.path for g in stack):
            raise DeckError(where, f"*INCLUDE of {shown(target)} makes a cycle")
        if not inc.exists():
            raise DeckError(where, f"*INCLUDE: no file {inc}")
        check_count(len(stack), "include_depth", where, "*INCLUDE nesting")
        try:  # its size first: a file included many times over is counted every time, before it is read
            total += limits.check_file(inc, "*INCLUDE file")
            if total > limit:
                var = limits.LIMITS["input_mb"][0]
                what = limits.LIMITS["input_mb"][2]
                raise DeckLimitError(where, f"*INCLUDE file {inc}: the deck with its *INCLUDE files exceeds the limit "
                                            f"of {limit / 1048576:.0f} MB ({what}, counted over the deck and every "
                                            f"file it includes; set {var} to raise it, in MB)", quotes=False)
            inc_text = limits.read_text(inc, "*INCLUDE file")
        except DeckError:
            raise
        except ValueError as exc:  # not a regular file, too large, not UTF-8
            raise _limited(where, exc) from None
        outside = not inc.is_relative_to(root)
        stack.append(_File(inc, _significant(inc, inc_text, outside, str(where))))


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
                    raise DeckError(at, f"*{name}: the parameter {shown(key)} is given twice")
                params[key] = value.strip(_BLANKS) if eq else None
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
    return parse_blocks(_logical_lines(Path(path).resolve(), text))
