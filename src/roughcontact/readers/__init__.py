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

from . import lengths
from .moments_file import load_moments, moments_from_mapping, moments_in_unit

__all__ = ["HeightMap", "read_height_map", "TEXT_SUFFIXES", "LAYOUTS", "load_moments", "moments_from_mapping",
           "moments_in_unit"]

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


def read_height_map(path, *, layout: str = "auto", channel: int | None = None) -> HeightMap:
    """The height map in ``path`` (module docstring for the formats). ``layout`` for text files:
    "auto" (points when the header names x, y, z or the table is much longer than wide), "grid"
    or "xyz"; ``channel``: the data channel of an instrument file. ValueError (one line) for a
    missing, empty or unreadable file."""
    file = Path(path)
    if layout not in LAYOUTS:
        raise ValueError(f"layout must be one of {', '.join(LAYOUTS)}; got {layout!r}")
    if not file.is_file():
        raise ValueError(f"no such file: {path}")
    suffix = file.suffix.lower()
    if suffix == ".npy":
        try:
            z = np.load(file, allow_pickle=False)
        except ValueError as exc:
            raise ValueError(f"{path}: not a numeric .npy array ({exc})") from None
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
    return HeightMap(heights=z.astype(float), dx=found["dx"], dy=found["dy"], xy_unit=found["xy_unit"],
                     z_unit=found["z_unit"], source=found["source"], notes=tuple(found["notes"]))
