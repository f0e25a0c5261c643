"""Gwyddion Simple Field (.gsf): a text header ``Gwyddion Simple Field 1.0`` with ``Key = value``
lines (XRes, YRes, XReal, YReal [physical size], XYUnits, ZUnits, …), NUL padding to a multiple of
4 bytes, then XRes·YRes little-endian float32 heights, row by row (gwyddion.net, "GSF file
format"). Rows run along y (z[i, j] at x = j·XReal/XRes, y = i·YReal/YRes); NaN = no data."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .lengths import normalise

__all__ = ["MAGIC", "read_gsf"]

MAGIC = b"Gwyddion Simple Field 1.0\n"


def read_gsf(path) -> dict:
    """The map of a .gsf file (the dict of :func:`roughcontact.readers.text.read_text`)."""
    raw = Path(path).read_bytes()
    if not raw.startswith(MAGIC):
        raise ValueError(f"{path}: not a Gwyddion Simple Field file (no '{MAGIC.decode().strip()}' line)")
    end = raw.find(b"\0")
    if end < 0:
        raise ValueError(f"{path}: the header is not terminated (no NUL byte)")
    header = {}
    for line in raw[len(MAGIC):end].decode("utf-8", errors="replace").splitlines():
        if "=" in line:
            key, value = line.split("=", 1)
            header[key.strip()] = value.strip()
    try:
        nx, ny = int(header["XRes"]), int(header["YRes"])
    except (KeyError, ValueError):
        raise ValueError(f"{path}: the header needs integer XRes and YRes") from None
    start = end + (4 - end % 4)  # 1 to 4 NUL bytes: the data start at a multiple of 4
    data = np.frombuffer(raw, dtype="<f4", count=nx * ny, offset=start) if len(raw) >= start + 4 * nx * ny else None
    if data is None:
        raise ValueError(f"{path}: {len(raw) - start} data bytes where XRes*YRes*4 = {4 * nx * ny}")

    def unit(key):
        value = header.get(key)
        return normalise(value) if value else None

    size = {k: float(header[k]) for k in ("XReal", "YReal") if k in header}
    return {"heights": data.astype(float).reshape(ny, nx),
            "dx": size["XReal"] / nx if "XReal" in size else None,
            "dy": size["YReal"] / ny if "YReal" in size else None,
            "xy_unit": unit("XYUnits"), "z_unit": unit("ZUnits"), "source": "gsf", "notes": []}
