"""What a failed write says: the file, the reason, and whether the disk is full (no physics, no
roughcontact imports; beside :mod:`roughcontact.files`, whose atomic writes leave nothing under the
file's name when they fail).

Libraries that write for us hide the cause: netCDF/HDF5 report a full disk only as "NetCDF: HDF
error", matplotlib lets ``OSError: [Errno 28]`` through as a traceback. :func:`write_error` turns
either into one line, :class:`WriteError` (a ValueError: the command line prints it, exit 2).
"""

from __future__ import annotations

import errno
import os
import shutil
from pathlib import Path

__all__ = ["WriteError", "write_error"]


class WriteError(ValueError):
    """A file the library writes could not be written: one line naming the file and why (the
    disk being full said as such); nothing is left under the file's name (files.atomic_path).
    A ValueError, so the command line prints it as one line (exit 2)."""


#: a write that fails with less free space than this (or than the data need) failed on a full disk
_DISK_FULL_BYTES = 1 << 20


def write_error(path: str | os.PathLike, exc: BaseException, what: str = "file", needed: int = 0) -> WriteError:
    """The :class:`WriteError` of a failed write of ``path``: the reason (``exc``'s strerror),
    and "the disk is full" where the error says so (ENOSPC; EDQUOT: "your disk quota is exceeded")
    or where it does not but the file system of ``path`` has less than max(1 MiB, ``needed``
    bytes) free (then the free space is stated): libraries that hide the errno report a full
    disk otherwise (netCDF/HDF5: "NetCDF: HDF error"). Call it while the partial file still
    exists (its blocks then count as used)."""
    path = Path(path)
    reason = (exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)) or type(exc).__name__
    code = exc.errno if isinstance(exc, OSError) else None
    free = None
    try:
        free = shutil.disk_usage(path.parent if path.parent.exists() else Path.cwd()).free
    except OSError:
        pass
    low = free is not None and free < max(_DISK_FULL_BYTES, needed)
    if code == getattr(errno, "EDQUOT", None):
        note = "; your disk quota is exceeded: free space and run again"
    elif code == errno.ENOSPC or low:
        shown = f" ({free / 1048576:.3g} MB free on {path.parent})" if low else ""
        note = f"; the disk is full{shown}: free space and run again"
    else:
        note = ""
    return WriteError(f"{what} {path}: cannot write it ({' '.join(reason.split())}){note}; nothing written")
