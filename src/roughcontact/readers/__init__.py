"""Reading measured height maps and moment files: the door for a user with real data.

:func:`read_height_map` reads

* ``.npy`` (a 2-d array z[i, j] at x = j·dx, y = i·dy; no units or spacing in the file);
* text: a grid (one map row per line) or XYZ points, CSV / semicolon / tab / space separated, with
  headers, comments and missing values (:mod:`.text`);
* ``.gsf``, Gwyddion Simple Field (:mod:`.gsf`);
* every instrument format SurfaceTopography reads (.x3p, .sur, .opd, .datx, .plu, .gwy, .nc, …;
  :mod:`.instrument`), when the optional ``measure`` extra is installed — without it such a
  file is refused with one line saying how to install it.

The result states the units where the file has them; :meth:`HeightMap.in_unit` converts heights
and spacing into one length unit (:mod:`.lengths`). :func:`load_moments` reads the five moments
and their unit from a JSON file (``roughcontact moments ... --json``) for the commands and input
files that take ``--moments``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from .. import limits
from . import lengths
from .moments_file import load_moments, moments_from_mapping, moments_in_unit

__all__ = ["HeightMap", "read_height_map", "unit_warning", "UnitWarning", "TEXT_SUFFIXES", "LAYOUTS", "load_moments",
           "moments_from_mapping", "moments_in_unit"]

TEXT_SUFFIXES = (".csv", ".txt", ".dat", ".asc", ".xyz", ".tsv")
LAYOUTS = ("auto", "grid", "xyz")


@dataclass(frozen=True)
class HeightMap:
    """A measured map: heights z[i, j] at x = j·dx, y = i·dy (NaN: not measured), the spacing and
    the units as far as the file gives them (None: not in the file), the format read, notes."""

    heights: np.ndarray
    dx: float | None
    dy: float | None
    xy_unit: str | None
    z_unit: str | None
    source: str
    notes: tuple = ()

    def in_unit(self, unit: str) -> "HeightMap":
        """Heights and spacing in ``unit`` (both of the map's units must be known)."""
        unit = lengths.normalise(unit)
        if self.z_unit is None or (self.dx is not None and self.xy_unit is None):
            raise ValueError("the units of the map are not known: state them (z_unit, xy_unit)")
        fz = lengths.factor(self.z_unit, unit)
        fxy = lengths.factor(self.xy_unit, unit) if self.dx is not None else 1.0
        return replace(self, heights=self.heights * fz, dx=None if self.dx is None else self.dx * fxy,
                       dy=None if self.dy is None else self.dy * fxy, xy_unit=unit if self.dx is not None else None,
                       z_unit=unit)


def _read_npy(file: Path) -> np.ndarray:
    """The 2-d numeric array of a ``.npy`` file, its header checked before the data are read
    (NumPy's format, ``numpy.lib.format``: magic, version, a header dict of descr, fortran_order,
    shape): an empty or truncated file, an object array or one of more points than
    ``ROUGHCONTACT_MAX_CELLS`` is one line, and no memory is allocated for it."""
    fmt = np.lib.format
    try:
        with open(file, "rb") as f:
            version = fmt.read_magic(f)
            if version not in ((1, 0), (2, 0)):  # 3.0: utf-8 field names of structured arrays only
                raise ValueError(f"version {version[0]}.{version[1]} of the format (1.0 and 2.0 are read)")
            read_header = fmt.read_array_header_1_0 if version == (1, 0) else fmt.read_array_header_2_0
            shape, _fortran_order, dtype = read_header(f)
            offset = f.tell()
    except (ValueError, EOFError, OSError) as exc:  # empty (EOFError), not .npy, a bad header
        raise ValueError(f"{file}: not a .npy array ({' '.join(str(exc).split())[:200]})") from None
    if len(shape) != 2 or dtype.kind not in "biuf":  # not complex, object, strings, records
        raise ValueError(f"{file}: expected a 2-d numeric map of real numbers, got shape {tuple(shape)} ({dtype})")
    limits.check_count(int(np.prod(shape, dtype=object)), "cells",
                       f"{file}: the array's {shape[0]} x {shape[1]} points")
    size = file.stat().st_size
    if size < offset + shape[0] * shape[1] * dtype.itemsize:
        raise ValueError(f"{file}: truncated: the header declares {shape[0]} x {shape[1]} values of "
                         f"{dtype.itemsize} bytes, the file holds {size - offset} data bytes")
    try:
        return np.load(file, allow_pickle=False)
    except (ValueError, EOFError, OSError) as exc:
        raise ValueError(f"{file}: not a numeric .npy array ({' '.join(str(exc).split())[:200]})") from None


def read_height_map(path, *, layout: str = "auto", channel: int | None = None) -> HeightMap:
    """The height map in ``path`` (module docstring for the formats). ``layout`` for text files:
    "auto" (points when the header names x, y, z or the table is much longer than wide), "grid"
    or "xyz"; ``channel``: the data channel of an instrument file. ValueError (one line) for a
    missing, empty or unreadable file."""
    file = Path(path)
    if layout not in LAYOUTS:
        raise ValueError(f"layout must be one of {', '.join(LAYOUTS)}; got {limits.describe(layout)}")
    limits.check_file(file, "height map")  # a regular file (not a FIFO, /dev/zero) within the size limit
    suffix = file.suffix.lower()
    if suffix == ".npy":
        z = _read_npy(file)
        found = {"heights": z, "dx": None, "dy": None, "xy_unit": None, "z_unit": None, "source": "npy", "notes": []}
    elif suffix in TEXT_SUFFIXES or layout != "auto":
        from .text import read_text

        found = read_text(file, layout=layout)
    elif suffix == ".gsf":
        from .gsf import read_gsf

        found = read_gsf(file)
    else:
        from .instrument import read_instrument

        found = read_instrument(file, channel=channel)
    z = np.asarray(found["heights"])
    if z.ndim != 2 or not np.issubdtype(z.dtype, np.number):
        raise ValueError(f"{path}: expected a 2-d numeric map, got shape {z.shape} ({z.dtype})")
    if z.size == 0:
        raise ValueError(f"{path}: the map has no points (shape {z.shape})")
    return HeightMap(heights=z.astype(float), dx=found["dx"], dy=found["dy"], xy_unit=found["xy_unit"],
                     z_unit=found["z_unit"], source=found["source"], notes=tuple(found["notes"]))


class UnitWarning(UserWarning):
    """A map whose numbers are implausible in the units they are read in (:func:`unit_warning`)."""


def unit_warning(found: HeightMap, xy_unit: str, z_unit: str, file, *, dx: float | None = None,
                 options: tuple = ("--xy-unit", "--z-unit")) -> str | None:
    """A warning, naming ``file``, when the map read in ``xy_unit`` (its spacing ``dx``, default
    the file's) and ``z_unit`` (its heights) is implausible for a measured surface
    (:data:`lengths.PLAUSIBLE`: e.g. an XYZ export in metres taken in µm has a sampling interval
    of 1.25 pm and an rms height of 0.1 pm), saying which unit was probably meant and the options
    (``options``: of the lateral unit, of the heights) that state it; None if plausible."""
    dx = found.dx if dx is None else dx
    z = found.heights[np.isfinite(found.heights)]
    rms = float(np.std(z)) if z.size > 1 else 0.0  # about the mean: form included, an order of magnitude is enough
    doubts, fixes = [], []
    for quantity, value, unit, option in (("sampling interval", dx, xy_unit, options[0]),
                                          ("rms height", rms, z_unit, options[1])):
        if value is None or not np.isfinite(value) or value == 0:
            continue
        low, high, _ = lengths.PLAUSIBLE[quantity]
        metres = abs(value) * lengths.METRES[lengths.normalise(unit)]
        if low <= metres <= high:
            continue
        article = "an" if quantity[0] == "r" else "a"
        doubts.append(f"{article} {quantity} of {value:.3g} {unit} ({lengths.in_metres(metres)})")
        meant = lengths.likely_unit(value, unit, quantity)
        if meant is not None:
            fixes.append((option, meant))
    if not doubts:
        return None
    ranges = "; ".join(f"{q}s of {lengths.in_metres(lo)} to {lengths.in_metres(hi)}"
                       for q, (lo, hi, _) in lengths.PLAUSIBLE.items())
    meant = sorted({u for _, u in fixes})
    advice = (f": the values look like {' and '.join(_UNIT_WORDS.get(u, u) for u in meant)}: pass "
              + " ".join(f"{o} {u}" for o, u in fixes)) if fixes else ": check the units of the file"
    return (f"{file}: implausible for a measured surface: {' and '.join(doubts)} (instruments measure {ranges})"
            + advice)


_UNIT_WORDS = {"m": "metres", "mm": "millimetres", "um": "micrometres", "nm": "nanometres"}
