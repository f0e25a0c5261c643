"""Gwyddion Simple Field (.gsf): a text header ``Gwyddion Simple Field 1.0`` with ``Key = value``
lines (XRes, YRes, XReal, YReal [physical size], XYUnits, ZUnits, …), NUL padding to a multiple of
4 bytes, then XRes·YRes little-endian float32 heights, row by row (gwyddion.net, "GSF file
format"). Rows run along y (z[i, j] at x = j·XReal/XRes, y = i·YReal/YRes); NaN = no data."""

from __future__ import annotations

import math

import numpy as np

from .. import limits
from .lengths import normalise

__all__ = ["MAGIC", "read_gsf"]

MAGIC = b"Gwyddion Simple Field 1.0\n"


def read_gsf(path) -> dict:
    """The map of a .gsf file (the dict of :func:`roughcontact.readers.text.read_text`)."""
    raw = limits.read_bytes(path, "height map")
    if not raw.startswith(MAGIC):
        raise ValueError(f"{path}: not a Gwyddion Simple Field file (no '{MAGIC.decode().strip()}' line)")
    end = raw.find(b"\0")
    if end < 0:
        raise ValueError(f"{path}: the header is not terminated (no NUL byte)")
    header = {}
    for line in raw[len(MAGIC):end].decode("utf-8", errors="replace").split("\n"):
        if "=" in line:
            key, value = line.split("=", 1)
            header[key.strip()] = value.strip()

    def count(key):  # XRes, YRes: positive integers (XRes = 0 divided by zero, -64 misled numpy)
        try:
            n = int(header[key])
        except KeyError:
            raise ValueError(f"{path}: the header has no {key} (the number of points along "
                             f"{key[0].lower()})") from None
        except ValueError:
            raise ValueError(f"{path}: {key} = {limits.describe(header[key])} is not an integer") from None
        if n < 1:
            raise ValueError(f"{path}: {key} = {n}: the number of points must be at least 1")
        return n

    def length(key):  # XReal, YReal: the physical size, positive and finite
        try:
            value = float(header[key])
        except ValueError:
            raise ValueError(f"{path}: {key} = {limits.describe(header[key])} is not a number") from None
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{path}: {key} = {limits.describe(header[key])}: the size must be positive and finite")
        return value

    nx, ny = count("XRes"), count("YRes")
    limits.check_count(nx * ny, "cells", f"{path}: XRes x YRes = {nx} x {ny} points")
    start = end + (4 - end % 4)  # 1 to 4 NUL bytes: the data start at a multiple of 4
    if len(raw) < start + 4 * nx * ny:
        raise ValueError(f"{path}: {len(raw) - start} data bytes where XRes*YRes*4 = {4 * nx * ny}")
    data = np.frombuffer(raw, dtype="<f4", count=nx * ny, offset=start)

    def unit(key):
        value = header.get(key)
        try:
            return normalise(value) if value else None
        except ValueError as exc:
            raise ValueError(f"{path}: {key}: {exc}") from None

    size = {k: length(k) for k in ("XReal", "YReal") if k in header}
    return {"heights": data.astype(float).reshape(ny, nx),
            "dx": size["XReal"] / nx if "XReal" in size else None,
            "dy": size["YReal"] / ny if "YReal" in size else None,
            "xy_unit": unit("XYUnits"), "z_unit": unit("ZUnits"), "source": "gsf", "notes": []}
