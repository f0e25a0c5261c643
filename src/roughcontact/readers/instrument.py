"""Instrument files through SurfaceTopography (MIT; the ``measure`` extra): .x3p, .sur, .opd,
.opdx, .di, .plu, .plux, .datx, .al3d, .gwy, .vk3/4/6, .nms, .mi, .ibw, .nc, ….

An extension that one of its readers claims is never second-guessed: the file is read by the
reader(s) of that extension only (``open_topography(path, format=...)``), and a file they cannot
read is refused in one line — left to ``open_topography``'s detection, a corrupt ``.x3p`` of
random bytes was taken for another format (``hgt``, with heights of 10⁸). Only a name whose
extension no reader claims is detected from the content (stated in the notes). SurfaceTopography
stores heights as h[ix, iy] with physical sizes (Lx, Ly) = (nx dx, ny dy); the map here is
z[i, j] = h[j, i]."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from .. import limits
from .lengths import normalise

__all__ = ["INSTALL", "read_instrument"]

#: how to get the optional reader (one line for the error message)
INSTALL = "pip install '.[measure]' in the roughcontact checkout (or pip install SurfaceTopography)"


def _brief(exc: Exception) -> str:
    """SurfaceTopography's message on one line, at most 200 characters (and printable)."""
    text = f"{type(exc).__name__}: {' '.join(str(exc).split())}"
    # a corrupt file's bytes may be quoted in the message: unprintable ones as escapes
    text = "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii") for c in text[:200])
    return text if len(str(exc)) + len(type(exc).__name__) + 2 <= 200 else text + "…"


def formats_of_extension(suffix: str) -> list[str]:
    """SurfaceTopography's format names whose readers claim the extension ``suffix`` (".x3p" →
    ["x3p"]; ".dat" → ["asc", "metropro"]), in its order of detection; [] if none does."""
    from SurfaceTopography.IO import readers

    ext = suffix.lower().lstrip(".")
    return [r.format() for r in readers if ext and ext in (e.lower() for e in r.file_extensions())]


def _open(path):
    """(reader, note): SurfaceTopography's reader of ``path`` by its extension, or by detection
    from the content for an extension no reader claims (the note says which format was found)."""
    try:
        with warnings.catch_warnings():  # its MPI layer says it falls back to a stub: not ours to relay
            warnings.simplefilter("ignore")
            from SurfaceTopography import open_topography
    except ImportError:
        raise ValueError(f"{path}: reading instrument files needs SurfaceTopography, which is not "
                         f"installed: {INSTALL}") from None
    formats = formats_of_extension(Path(path).suffix)
    if not formats:
        try:
            reader = open_topography(str(path))
        except Exception as exc:  # SurfaceTopography's CannotDetectFileFormat, CorruptFile, …
            raise ValueError(f"{path}: SurfaceTopography cannot read it ({_brief(exc)})") from None
        return reader, (f"{path}: the extension names no instrument format; read as "
                        f"'{reader.format()}' (detected from the content)")
    failures = []
    for name in formats:
        try:
            return open_topography(str(path), format=name), None
        except Exception as exc:  # FileFormatMismatch, CorruptFile, …: this reader cannot read it
            failures.append(f"{name}: {_brief(exc)}")
    raise ValueError(f"{path}: not a readable {Path(path).suffix} file (SurfaceTopography's reader "
                     + "; ".join(failures) + "); a file of another format needs its own extension")


def read_instrument(path, *, channel: int | None = None) -> dict:
    """The map of an instrument file (the dict of :func:`roughcontact.readers.text.read_text`;
    ``source`` is SurfaceTopography's format name). ``channel``: which data channel (default:
    the first; the notes list the others)."""
    limits.check_file(path, "height map")  # a regular file within the size limit; SurfaceTopography opens it
    reader, detected = _open(path)
    channels = reader.channels
    index = 0 if channel is None else int(channel)
    if not 0 <= index < len(channels):
        raise ValueError(f"{path}: channel {index} does not exist (the file has {len(channels)}: "
                         + ", ".join(f"{i} {c.name}" for i, c in enumerate(channels)) + ")")
    info = channels[index]
    if info.dim != 2:
        raise ValueError(f"{path}: channel {index} is a {info.dim}-d scan, not a height map")
    nb = [int(n) for n in info.nb_grid_pts]
    limits.check_count(float(nb[0]) * float(nb[1]), "cells",
                       f"{path}: channel {index} declares {nb[0]} x {nb[1]} points")  # before reading them
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
    notes = [detected] if detected else []
    if len(channels) > 1:
        notes.append(f"{path}: channel {index} ({info.name}) of {len(channels)}: "
                     + ", ".join(f"{i} {c.name}" for i, c in enumerate(channels)))
    return {"heights": z, "dx": None if spacing is None else spacing[0], "dy": None if spacing is None else spacing[1],
            "xy_unit": unit if spacing is not None else None, "z_unit": unit, "source": reader.format(),
            "notes": notes}
