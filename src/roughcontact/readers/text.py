"""Height maps from text: a grid (one row of the map per line) or XYZ points (x y z per line,
in any order), comma, semicolon, tab or space separated, with headers and comments.

* Comment lines start with ``#``, ``%`` or ``//``; a Gwyddion text export's comment header
  (``# Width: 10.00 µm``, ``# Height: 10.00 µm``, ``# Value units: m``) gives the lateral size and
  the units.
* Header lines (non-numeric, before the data; quoted or not) name the columns; a unit in brackets
  or parentheses after a name (``x [um]``, ``"z (nm)"``) is taken.
* Missing values: an empty field or ``nan``, ``na``, ``n/a``, ``-``, ``*``, ``***``, ``bad``,
  ``nodata``, ``null`` (NaN: the estimator works around them). A decimal comma is read where the
  fields are separated by semicolons, tabs or spaces.
* XYZ or grid: a header naming x, y, z columns, or a table much longer than wide (at most 6 columns,
  at least 50 rows per column) is read as points; their x, y must lie on a regular lattice (grid
  nodes absent from the file are missing points), or the file is refused with the reason — a
  50000 × 6 table is not a 50000 × 6 height map.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .lengths import normalise

__all__ = ["read_text", "grid_from_points"]

_MISSING = {"", "nan", "na", "n/a", "-", "*", "***", "bad", "nodata", "null"}
_COMMENT = ("#", "%", "//")
_UNIT = re.compile(r"^\s*\"?\s*([A-Za-z_][\w ]*?)\s*[\[(]\s*([^\])]+?)\s*[\])]\s*\"?\s*$")
_GWY = re.compile(r"^\s*(width|height|value units)\s*:\s*([-+0-9.eE]*)\s*(\S*)\s*$", re.IGNORECASE)


def _split(line: str, delimiter):
    fields = line.split(delimiter) if delimiter else line.split()
    return [f.strip().strip('"').strip("'").strip() for f in fields]


def _number(text: str, decimal_comma: bool) -> float:
    if text.lower() in _MISSING:
        return np.nan
    return float(text.replace(",", ".") if decimal_comma else text)


def _fields(line: str):
    """(fields, decimal comma?, delimiter) of a line: the first of ; tab , present, else spaces."""
    delimiter = next((d for d in (";", "\t", ",") if d in line), None)
    decimal_comma = delimiter != "," and re.search(r"\d,\d", line) is not None
    return _split(line, delimiter), decimal_comma, delimiter


def _is_numeric(fields, decimal_comma, delimiter=None) -> bool:
    try:
        values = [_number(f, decimal_comma) for f in fields]
    except ValueError:
        return False
    return any(np.isfinite(values))


def read_text(path, *, layout: str = "auto") -> dict:
    """The map in a text file: {"heights", "dx", "dy", "xy_unit", "z_unit", "source", "notes"}
    (dx, dy, units None where the file does not say). ``layout``: "auto", "grid" or "xyz"."""
    file = Path(path)
    lines = file.read_text(errors="replace").splitlines()
    comments, header, data = [], [], []
    for number, line in enumerate(lines, 1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith(_COMMENT):
            comments.append(stripped.lstrip("#%/ ").strip())
        elif data or _is_numeric(*_fields(stripped)):
            data.append((number, stripped))
        else:
            header.append((number, stripped))
    if not data:
        raise ValueError(f"{path}: no numeric data found")
    _, decimal_comma, delimiter = _fields(data[0][1])
    rows = []
    for number, line in data:
        try:
            rows.append([_number(f, decimal_comma) for f in _split(line, delimiter)])
        except ValueError as exc:
            raise ValueError(f"{path}, line {number}: not a number ({exc})") from None
        if len(rows[-1]) != len(rows[0]):
            raise ValueError(f"{path}, line {number}: {len(rows[-1])} fields where the first data line has "
                             f"{len(rows[0])}")
    table = np.array(rows, dtype=float)
    names, units = _columns(header, delimiter)
    meta = _gwyddion_header(comments)
    xyz_named = len(names) >= 3 and [n.lower() for n in names[:3]] == ["x", "y", "z"]
    tall = 3 <= table.shape[1] <= 6 and table.shape[0] >= 50 * table.shape[1]
    if layout == "xyz" or (layout == "auto" and (xyz_named or tall)):
        z, dx, dy, notes = grid_from_points(table, path)
        xy_unit = units.get(0) or units.get(1)
        return {"heights": z, "dx": dx, "dy": dy, "xy_unit": xy_unit, "z_unit": units.get(2), "source": "xyz",
                "notes": notes}
    dx = dy = None
    if "width" in meta and "height" in meta:
        dx, dy = meta["width"][0] / table.shape[1], meta["height"][0] / table.shape[0]
    return {"heights": table, "dx": dx, "dy": dy, "xy_unit": meta.get("width", (None, None))[1],
            "z_unit": meta.get("value units", (None, None))[1] or (units.get(0) if len(units) == 1 else None),
            "source": "grid", "notes": []}


def _columns(header, delimiter):
    """Column names and units (by column index) from the last header line."""
    if not header:
        return [], {}
    names, units = [], {}
    for i, field in enumerate(_split(header[-1][1], delimiter)):
        m = _UNIT.match(field)
        name = (m.group(1) if m else field).strip().strip('"')
        names.append(name)
        if m:
            try:
                units[i] = normalise(m.group(2))
            except ValueError:
                pass
    return names, units


def _gwyddion_header(comments) -> dict:
    meta = {}
    for c in comments:
        m = _GWY.match(c)
        if m:
            key, value, unit = m.group(1).lower(), m.group(2), m.group(3)
            try:
                meta[key] = (float(value) if value else None, normalise(unit or value))
            except ValueError:
                continue
    return meta


def _lattice(values, name, path):
    """(origin, step, index) of values on a regular lattice, or ValueError."""
    finite = values[np.isfinite(values)]
    if finite.size != values.size:
        raise ValueError(f"{path}: the {name} column has missing values")
    unique = np.unique(finite)
    span = unique[-1] - unique[0]
    if unique.size < 5:
        raise ValueError(f"{path}: only {unique.size} distinct {name} values; a map needs at least 5 along each axis")
    # cluster values closer than 1e-6 of the span (text rounding)
    keep = np.concatenate([[True], np.diff(unique) > 1e-6 * span])
    unique = unique[keep]
    step = float(np.median(np.diff(unique)))
    index = (values - unique[0]) / step
    if np.max(np.abs(index - np.round(index))) > 1e-3:
        raise ValueError(f"{path}: the points' {name} coordinates are not on a regular lattice "
                         f"({unique.size} distinct values, median spacing {step:g})")
    return float(unique[0]), step, np.round(index).astype(np.int64)


def grid_from_points(table, path="points") -> tuple[np.ndarray, float, float, list]:
    """z[i, j] from rows (x, y, z[, …]) on a regular lattice (any order; absent nodes NaN).
    Returns (z, dx, dy, notes); ValueError if the points are not on a lattice or repeat."""
    table = np.asarray(table, dtype=float)
    if table.ndim != 2 or table.shape[1] < 3:
        raise ValueError(f"{path}: x y z points need at least 3 columns")
    try:
        _, dx, j = _lattice(table[:, 0], "x", path)
        _, dy, i = _lattice(table[:, 1], "y", path)
    except ValueError as exc:
        raise ValueError(f"{exc}: a table of {table.shape[0]} rows x {table.shape[1]} columns is neither a "
                         "height grid (one map row per line) nor x y z points on a grid; use --layout grid "
                         "if it is a grid") from None
    ny, nx = int(i.max()) + 1, int(j.max()) + 1
    flat = i * nx + j
    if np.unique(flat).size != flat.size:
        raise ValueError(f"{path}: {flat.size - np.unique(flat).size} points repeat an (x, y) position")
    z = np.full((ny, nx), np.nan)
    z[i, j] = table[:, 2]
    notes = []
    if table.shape[1] > 3:
        notes.append(f"{path}: columns 4-{table.shape[1]} ignored (x y z are the first three)")
    if dy < 0 or dx < 0:
        raise ValueError(f"{path}: decreasing coordinates")
    return z, abs(dx), abs(dy), notes
