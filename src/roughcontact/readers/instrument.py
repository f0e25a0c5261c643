"""Instrument files through SurfaceTopography (MIT; the ``measure`` extra): .x3p, .sur, .opd,
.opdx, .di, .plu, .plux, .datx, .al3d, .gwy, .vk3/4/6, .nms, .mi, .ibw, .nc, … (its
``open_topography`` detects the format from the content). SurfaceTopography stores heights as
h[ix, iy] with physical sizes (Lx, Ly) = (nx dx, ny dy); the map here is z[i, j] = h[j, i]."""

from __future__ import annotations

import warnings

import numpy as np

from .lengths import normalise

__all__ = ["INSTALL", "read_instrument"]

#: how to get the optional reader (one line for the error message)
INSTALL = "pip install '.[measure]' in the roughcontact checkout (or pip install SurfaceTopography)"


def _open(path):
    try:
        with warnings.catch_warnings():  # its MPI layer says it falls back to a stub: not ours to relay
            warnings.simplefilter("ignore")
            from SurfaceTopography import open_topography
    except ImportError:
        raise ValueError(f"{path}: reading instrument files needs SurfaceTopography, which is not "
                         f"installed: {INSTALL}") from None
    try:
        return open_topography(str(path))
    except Exception as exc:  # SurfaceTopography's UnknownFileFormat, CorruptFile, …
        raise ValueError(f"{path}: SurfaceTopography cannot read it ({type(exc).__name__}: "
                         f"{' '.join(str(exc).split())})") from None


def read_instrument(path, *, channel: int | None = None) -> dict:
    """The map of an instrument file (the dict of :func:`roughcontact.readers.text.read_text`;
    ``source`` is SurfaceTopography's format name). ``channel``: which data channel (default:
    the first; the notes list the others)."""
    reader = _open(path)
    channels = reader.channels
    index = 0 if channel is None else int(channel)
    if not 0 <= index < len(channels):
        raise ValueError(f"{path}: channel {index} does not exist (the file has {len(channels)}: "
                         + ", ".join(f"{i} {c.name}" for i, c in enumerate(channels)) + ")")
    info = channels[index]
    if info.dim != 2:
        raise ValueError(f"{path}: channel {index} is a {info.dim}-d scan, not a height map")
    options = {}
    if info.physical_sizes is None:
        nx, ny = info.nb_grid_pts
        options["physical_sizes"] = (float(nx), float(ny))  # spacing 1; the caller must give dx
    try:
        topography = reader.topography(channel_index=index, **options)
    except Exception as exc:
        raise ValueError(f"{path}: SurfaceTopography cannot read channel {index} ({type(exc).__name__}: "
                         f"{' '.join(str(exc).split())})") from None
    if not getattr(topography, "is_uniform", True):
        raise ValueError(f"{path}: channel {index} is not sampled on a uniform grid")
    h = topography.heights()
    z = np.ma.filled(np.ma.asarray(h, dtype=float), np.nan).T
    nx, ny = topography.nb_grid_pts
    unit = normalise(topography.unit) if topography.unit else None
    spacing = None if "physical_sizes" in options else \
        (float(topography.physical_sizes[0]) / nx, float(topography.physical_sizes[1]) / ny)
    notes = []
    if len(channels) > 1:
        notes.append(f"{path}: channel {index} ({info.name}) of {len(channels)}: "
                     + ", ".join(f"{i} {c.name}" for i, c in enumerate(channels)))
    return {"heights": z, "dx": None if spacing is None else spacing[0], "dy": None if spacing is None else spacing[1],
            "xy_unit": unit if spacing is not None else None, "z_unit": unit, "source": reader.format(),
            "notes": notes}
