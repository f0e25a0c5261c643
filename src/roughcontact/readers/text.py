"""Height maps from text: a grid (one row of the map per line) or XYZ points (x y z per line,
in any order), comma, semicolon, tab or space separated, with headers and comments.

* The file is UTF-8 (a byte-order mark is skipped), UTF-16 with its mark, or else Latin-1 (as
  instrument software on Windows writes ``µm``); lines end at LF (CR LF); it is read within
  ``ROUGHCONTACT_MAX_INPUT_MB`` and its table within ``ROUGHCONTACT_MAX_CELLS`` (:mod:`roughcontact.limits`).
* Comment lines start with ``#``, ``%`` or ``//``; a Gwyddion text export's comment header
  (``# Width: 10.00 µm``, ``# Height: 10.00 µm``, ``# Value units: m``) gives the lateral size and
  the units.
* Vendor header lines of key, value[, unit] before the data give the spacing and the units:
  ``"XY calibration","1.25","um/pixel"`` (also ``X calibration``, ``Y calibration``, ``pixel
  size``, ``spacing``; the unit per pixel or per point), ``"Z unit","nm"`` (also ``height unit``,
  ``value unit``), ``"XY unit","um"`` (also ``lateral unit``); a line of more than three fields
  names columns.
* A grid whose first row and first column are coordinates (evenly spaced, monotone, with an empty
  or labelled corner cell) gives dx, dy from them; when they count 0, 1, 2, … (or 1, 2, …) they are
  row and column numbers (a spreadsheet's or pandas' index), dropped without giving a spacing.
* Header lines (non-numeric, before the data; quoted or not) name the columns; a unit in brackets
  or parentheses after a name (``x [um]``, ``"z (nm)"``) is taken.
* Missing values: an empty field or ``nan``, ``na``, ``n/a``, ``-``, ``*``, ``***``, ``bad``,
  ``nodata``, ``null`` (NaN: the estimator works around them). A decimal comma is read where the
  fields are separated by semicolons, tabs or spaces.
* XYZ or grid: a header naming x, y, z columns, or a table much longer than wide (at most 6 columns,
  at least 50 rows per column) is read as points; their x, y must lie on a regular lattice (grid
  nodes absent from the file are missing points), or the file is refused with the reason — a
  50000 × 6 table is not a 50000 × 6 height map; a point far off the lattice of the others (beyond
  8 median absolute deviations of the coordinates from their median, where a full lattice reaches
  2) is refused naming its line, and the grid the points span is checked against
  ``ROUGHCONTACT_MAX_CELLS`` before it is allocated. The units of x and y may differ (``x [mm], y
  [um]``): both are converted to the finer of the two.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .. import limits
from .lengths import factor, normalise

__all__ = ["read_text", "grid_from_points"]

_MISSING = {"", "nan", "na", "n/a", "-", "*", "***", "bad", "nodata", "null"}
_COMMENT = ("#", "%", "//")
_UNIT = re.compile(r"^\s*\"?\s*([A-Za-z_][\w ]*?)\s*[\[(]\s*([^\])]+?)\s*[\])]\s*\"?\s*$")
_GWY = re.compile(r"^\s*(width|height|value units)\s*:\s*([-+0-9.eE]*)\s*(\S*)\s*$", re.IGNORECASE)
_SPACED_NAME = re.compile(r"[\"']?[^\s\[\]()\"']+(\s*[\[(][^\])]*[\])])?[\"']?")
# vendor header keys (lower case, runs of spaces/underscores as one space)
_SPACING_KEY = re.compile(r"^(xy|x|y|lateral)? ?(calibration|pixel size|pixel spacing|spacing|sampling interval)$")
_ZUNIT_KEY = re.compile(r"^(z|height|value|data) ?units?$")
_XYUNIT_KEY = re.compile(r"^(xy|lateral) ?units?$")
_PER_PIXEL = re.compile(r"\s*(/|per)\s*(pixels?|px|pix|points?|pt|samples?)\s*$", re.IGNORECASE)


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


def _decode(data: bytes) -> tuple[str, list]:
    """(text, notes) of a text file's bytes: UTF-8 (its byte-order mark skipped), UTF-16 with its
    mark, else Latin-1 (every byte a character: the ``µ`` of Windows instrument software)."""
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return data.decode("utf-16"), []
        except UnicodeDecodeError:
            pass
    try:
        return data.decode("utf-8-sig"), []
    except UnicodeDecodeError as exc:
        return data.decode("latin-1"), [f"not UTF-8 (byte {exc.start}): read as Latin-1"]


def read_text(path, *, layout: str = "auto") -> dict:
    """The map in a text file: {"heights", "dx", "dy", "xy_unit", "z_unit", "source", "notes"}
    (dx, dy, units None where the file does not say). ``layout``: "auto", "grid" or "xyz"."""
    text, decoding = _decode(limits.read_bytes(path, "height map"))
    notes = [f"{path}: {n}" for n in decoding]
    # LF or CR LF end a line, nothing else (str.splitlines also splits at \x0b, \x0c, \x1c-\x1e, \x85, \u2028)
    lines = text.split("\n")
    comments, header, data, vendor = [], [], [], {}
    for number, line in enumerate(lines, 1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith(_COMMENT):
            comments.append(stripped.lstrip("#%/ ").strip())
        elif data or _is_numeric(*_fields(stripped)):
            data.append((number, stripped))
        elif not _vendor_line(stripped, number, path, vendor):
            header.append((number, stripped))
    if not data:
        raise ValueError(f"{path}: no numeric data found")
    first, decimal_comma, delimiter = _fields(data[0][1])
    # the table's size before it is built: each field becomes a float
    limits.check_count(len(data) * len(first), "cells", f"{path}: {len(data)} data lines of {len(first)} fields")
    rows = []
    for number, line in data:
        try:
            rows.append(np.array([_number(f, decimal_comma) for f in _split(line, delimiter)], dtype=float))
        except ValueError as exc:
            raise ValueError(f"{path}, line {number}: not a number ({limits.describe(str(exc))})") from None
        if len(rows[-1]) != len(rows[0]):
            raise ValueError(f"{path}, line {number}: {len(rows[-1])} fields where the first data line has "
                             f"{len(rows[0])}")
    table = np.array(rows, dtype=float)
    del rows
    names, units, unknown = _columns(header, delimiter)
    meta = _gwyddion_header(comments)
    xyz_named = len(names) >= 3 and [n.lower() for n in names[:3]] == ["x", "y", "z"]
    tall = 3 <= table.shape[1] <= 6 and table.shape[0] >= 50 * table.shape[1]
    if layout == "xyz" or (layout == "auto" and (xyz_named or tall)):
        xy_unit, z_unit, unit_notes = _point_units(table, units, unknown, names, path)
        z, dx, dy, lattice_notes = grid_from_points(table, path, lines=[n for n, _ in data])
        return {"heights": z, "dx": dx, "dy": dy, "xy_unit": xy_unit or vendor.get("xy_unit"),
                "z_unit": z_unit or vendor.get("z_unit"), "source": "xyz",
                "notes": notes + unit_notes + lattice_notes}
    notes += [f"{path}: column {i + 1}: unit {limits.describe(u)} is not a length unit; not used"
              for i, u in unknown.items()]
    table, coords, coord_note = _coordinate_axes(table, header, path)  # first: they are not heights
    dx = dy = None
    xy_unit = meta.get("width", (None, None))[1]
    if "width" in meta and "height" in meta:
        dx, dy = meta["width"][0] / table.shape[1], meta["height"][0] / table.shape[0]
    if "dx" in vendor:
        dx, dy, xy_unit = vendor["dx"], vendor.get("dy", vendor["dx"]), vendor["xy_unit"]
        notes.append(f"{path}: spacing from the header: {vendor['said']}")
    if coord_note:
        notes.append(coord_note)
    if coords is not None:
        if dx is not None and not (np.isclose(coords[0], dx, rtol=1e-2) and np.isclose(coords[1], dy, rtol=1e-2)):
            raise ValueError(f"{path}: the coordinates in the first row and column (step {coords[0]:g}, "
                             f"{coords[1]:g}) contradict the header's spacing ({dx:g}, {dy:g})")
        dx, dy = coords
    return {"heights": table, "dx": dx, "dy": dy, "xy_unit": xy_unit or vendor.get("xy_unit"),
            "z_unit": meta.get("value units", (None, None))[1] or vendor.get("z_unit")
            or (units.get(0) if len(units) == 1 else None),
            "source": "grid", "notes": notes}


def _vendor_line(line: str, number: int, path, found: dict) -> bool:
    """Whether a header line is a vendor's key, value[, unit] line; its spacing and units go
    into ``found`` (dx, dy, xy_unit, z_unit, said). ValueError naming the line for a key it knows
    with a value it cannot read."""
    fields, _, _ = _fields(line)
    if len(fields) > 3:  # key, value, unit at most: a longer line names columns
        return False
    key = " ".join(fields[0].replace("_", " ").lower().split()) if fields else ""
    where = f"{path}, line {number}"
    if _ZUNIT_KEY.match(key) or _XYUNIT_KEY.match(key):
        if len(fields) < 2 or not fields[1]:
            raise ValueError(f"{where}: {limits.describe(fields[0])} names no unit")
        try:
            found["z_unit" if _ZUNIT_KEY.match(key) else "xy_unit"] = normalise(fields[1])
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
        return True
    m = _SPACING_KEY.match(key)
    if not m:
        return False
    try:
        value = float(fields[1].replace(",", "."))
    except (IndexError, ValueError):
        raise ValueError(f"{where}: {limits.describe(fields[0])} needs a number "
                         f"(got {limits.describe(fields[1] if len(fields) > 1 else '')})") from None
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"{where}: {limits.describe(fields[0])} = {limits.describe(value)} must be positive")
    text = fields[2] if len(fields) > 2 else ""
    if not text:
        raise ValueError(f"{where}: {limits.describe(fields[0])} states no unit (e.g. \"um/pixel\")")
    try:
        unit = normalise(_PER_PIXEL.sub("", text))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    axis = m.group(1) or "xy"
    previous = found.get("xy_unit")
    if previous is not None and previous != unit and "dx" in found:  # x and y in different units
        value *= factor(unit, previous)
        unit = previous
    found["xy_unit"] = unit
    if axis in ("xy", "lateral", "x"):
        found["dx"] = value
    if axis in ("xy", "lateral", "y"):
        found["dy"] = value
    if "dx" not in found:  # "Y calibration" alone: the same along x
        found["dx"] = value
    found["said"] = "; ".join(filter(None, [found.get("said"), f"line {number}: {fields[0]} {fields[1]} {text}"]))
    return True


def _even(values):
    """(first, step) of values evenly spaced (residuals of a straight line within 1 % of the
    step; at least 5 values), else None."""
    values = np.asarray(values, dtype=float)
    if values.size < 5 or not np.all(np.isfinite(values)):
        return None
    step = (values[-1] - values[0]) / (values.size - 1)
    if step == 0 or np.max(np.abs(values - (values[0] + step * np.arange(values.size)))) > 1e-2 * abs(step):
        return None
    return float(values[0]), float(step)


def _coordinate_axes(table, header, path):
    """(heights, (dx, dy) or None, note or None) of a grid whose first row and first column are
    coordinates: evenly spaced and monotone, and a corner cell that is empty (or a missing-value
    mark, or the label of a header line whose other fields are the x values). Heights are
    returned in increasing x and y (a decreasing axis is flipped, said in the note)."""
    x_row = None
    if table.shape[0] >= 6 and table.shape[1] >= 6 and np.isnan(table[0, 0]):
        x_row, body = table[0, 1:], table[1:]
    elif header and table.shape[1] >= 6:
        fields, decimal_comma, _ = _fields(header[-1][1])
        try:
            values = np.array([_number(f, decimal_comma) for f in fields[1:]])
            if len(fields) == table.shape[1] and _even(values) is not None:
                x_row, body = values, table
        except ValueError:
            pass
    if x_row is None or body.shape[0] < 5:
        return table, None, None
    along_x, along_y = _even(x_row), _even(body[:, 0])
    if along_x is None or along_y is None:
        return table, None, None
    z = body[:, 1:]
    counts = [(x_row[0], x_row[-1]), (body[0, 0], body[-1, 0])]
    if all(a in (0, 1) and b == a + n - 1 for (a, b), n in zip(counts, (z.shape[1], z.shape[0]))):
        return z, None, (f"{path}: the first row and column count 0, 1, 2, … (row and column numbers, "
                         "not coordinates): dropped; the spacing is not in the file")
    flipped = []
    if along_x[1] < 0:
        z, flipped = z[:, ::-1], flipped + ["x"]
    if along_y[1] < 0:
        z, flipped = z[::-1, :], flipped + ["y"]
    dx, dy = abs(along_x[1]), abs(along_y[1])
    note = (f"{path}: the first row and column are coordinates (x {x_row[0]:g} to {x_row[-1]:g}, "
            f"y {body[0, 0]:g} to {body[-1, 0]:g}): dx = {dx:g}, dy = {dy:g}"
            + (f"; the map is flipped along {' and '.join(flipped)} so that the coordinates increase"
               if flipped else ""))
    return z, (dx, dy), note


def _point_units(table, units, unknown, names, path):
    """(xy unit, z unit, notes) of x y z points from their column units; a y column in another
    unit than x is converted in place to the finer of the two."""
    notes = [f"{path}: column {names[i] if i < len(names) else i + 1}: unit {limits.describe(u)} is not a "
             "length unit; not used" for i, u in unknown.items() if i < 3]
    ux, uy = units.get(0), units.get(1)
    for known, other, i in ((ux, uy, 1), (uy, ux, 0)):
        if known and other is None and i in unknown:
            raise ValueError(f"{path}: x and y in units that cannot be reconciled: {known} and "
                             f"{limits.describe(unknown[i])}")
    if ux and uy and ux != uy:
        fine = ux if factor(ux, uy) < 1 else uy
        for column, unit in ((0, ux), (1, uy)):
            table[:, column] *= factor(unit, fine)
        notes.append(f"{path}: x in {ux}, y in {uy}: both taken in {fine}")
    elif (ux is None) != (uy is None):
        notes.append(f"{path}: {'y' if uy is None else 'x'} states no unit: taken in {ux or uy}, as "
                     f"{'x' if uy is None else 'y'}")
    xy = uy if ux is None else (ux if uy is None or ux == uy else (ux if factor(ux, uy) < 1 else uy))
    return xy, units.get(2), notes


def _columns(header, delimiter):
    """Column names, units (by column index) and units that are not length units (by column
    index, as written) from the last header line."""
    if not header:
        return [], {}, {}
    names, units, unknown = [], {}, {}
    line = header[-1][1]
    # space-separated: a unit in brackets belongs to the name before it ("x [mm] y [um] z [nm]")
    fields = _split(line, delimiter) if delimiter else [m.group(0) for m in _SPACED_NAME.finditer(line)]
    for i, field in enumerate(fields):
        m = _UNIT.match(field)
        name = (m.group(1) if m else field).strip().strip('"')
        names.append(name)
        if m:
            try:
                units[i] = normalise(m.group(2))
            except ValueError:
                unknown[i] = m.group(2)
    return names, units, unknown


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


def _far_off(table, lines, path):
    """ValueError naming the first point whose x or y lies far off the others: farther from the
    median than 8 median absolute deviations (a full lattice reaches 2, its edge). One stray point
    made the lattice's clustering merge all the others (\"points repeat\") or implied a grid of
    tens of GiB."""
    if not np.all(np.isfinite(table[:, :2])):
        return  # missing coordinates: _lattice says so
    far = np.zeros(table.shape[0], dtype=bool)
    bounds = []
    for column in (0, 1):
        v = table[:, column]
        median = np.median(v)
        mad = np.median(np.abs(v - median))
        if mad > 0:
            far |= np.abs(v - median) > 8 * mad
        bounds.append(v)
    if not far.any():
        return
    k = int(np.argmax(far))
    line = f", line {lines[k]}" if lines is not None else f", point {k + 1}"
    x, y = (bounds[c][~far] for c in (0, 1))
    more = int(far.sum()) - 1
    raise ValueError(f"{path}{line}: the point x = {table[k, 0]:g}, y = {table[k, 1]:g} lies far off the lattice of "
                     f"the others (x {x.min():g} to {x.max():g}, y {y.min():g} to {y.max():g})"
                     + (f", and {more} more point{'s' if more > 1 else ''}" if more else "")
                     + ": a stray point? remove it")


def grid_from_points(table, path="points", lines=None) -> tuple[np.ndarray, float, float, list]:
    """z[i, j] from rows (x, y, z[, …]) on a regular lattice (any order; absent nodes NaN).
    Returns (z, dx, dy, notes); ValueError if the points are not on a lattice, repeat, or one
    lies far off the others (naming its line: ``lines``, the file's line of each row), or the
    grid they span exceeds ``ROUGHCONTACT_MAX_CELLS`` (checked before it is allocated)."""
    table = np.asarray(table, dtype=float)
    if table.ndim != 2 or table.shape[1] < 3:
        raise ValueError(f"{path}: x y z points need at least 3 columns")
    _far_off(table, lines, path)
    try:
        _, dx, j = _lattice(table[:, 0], "x", path)
        _, dy, i = _lattice(table[:, 1], "y", path)
    except ValueError as exc:
        raise ValueError(f"{exc}: a table of {table.shape[0]} rows x {table.shape[1]} columns is neither a "
                         "height grid (one map row per line) nor x y z points on a grid; use --layout grid "
                         "if it is a grid") from None
    ny, nx = int(i.max()) + 1, int(j.max()) + 1
    limits.check_count(float(nx) * float(ny), "cells",
                       f"{path}: the points' lattice (x step {dx:g}, y step {dy:g}) spans {nx} x {ny} grid points")
    flat = i * nx + j
    if np.unique(flat).size != flat.size:
        raise ValueError(f"{path}: {flat.size - np.unique(flat).size} points repeat an (x, y) position")
    z = np.full((ny, nx), np.nan)
    z[i, j] = table[:, 2]
    notes = []
    if table.shape[1] > 3:
        notes.append(f"{path}: columns 4-{table.shape[1]} ignored (x y z are the first three)")
    if flat.size < 0.5 * z.size:  # e.g. a stray point not far enough to be refused widened the lattice
        notes.append(f"{path}: the {flat.size} points fill {100 * flat.size / z.size:.0f} % of the {nx} x {ny} "
                     "lattice they span; the rest is missing")
    return z, abs(dx), abs(dy), notes
