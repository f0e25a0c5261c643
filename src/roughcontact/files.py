"""Atomic file writes that honour the umask (no physics, no roughcontact imports).

Every file the library and the workflow write goes through :func:`atomic_path`: written to a
temporary name next to the target and renamed into place, so a job killed midway never leaves a
half-written result under the final name, and created with the mode ``open(path, "w")`` would
give (0666 minus the umask) so that other users and web servers can read the reports.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path
from typing import Iterator

__all__ = ["atomic_path", "remove_partial_files"]

#: the temporaries of :func:`atomic_path`: ``.<name>.<random>.part`` next to the target
_PART_PREFIX, _PART_SUFFIX = ".", ".part"


def _umask() -> int:
    """The process umask, read without changing it where /proc allows (no race with threads;
    elsewhere it is set and restored, there being no getter)."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except OSError:
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _atomic_target(path: Path) -> Path:
    """A fresh temporary file next to ``path``, with the mode a plain ``open(path, "w")``
    would give (0666 minus the umask): ``tempfile.mkstemp`` creates 0600 files and
    ``os.replace`` keeps the mode, which would leave reports unreadable to other users."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f"{_PART_PREFIX}{path.name}.", suffix=_PART_SUFFIX, dir=path.parent)
    try:
        os.fchmod(fd, 0o666 & ~_umask())
    finally:
        os.close(fd)
    return Path(tmp)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; when the block succeeds it is renamed onto
    ``path`` (readable as the umask allows), when it fails it is removed: a job killed or
    failing midway never leaves a half-written file under the final name."""
    path = Path(path)
    tmp = _atomic_target(path)
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def remove_partial_files(*roots: str | os.PathLike) -> list[Path]:
    """Remove the temporaries :func:`atomic_path` leaves under ``roots`` when its process dies
    without running its cleanup (SIGKILL, the OOM killer, a power loss); return what was removed.

    Only for directories no writer can be using at the time: the workflow calls it when a run
    starts (``onstart``, under Snakemake's lock on the working directory), so that a run resumed
    after a hard kill leaves no ``.fig18.pdf.*.part`` behind."""
    removed = []
    for root in map(Path, roots):
        if not root.is_dir():
            continue
        for tmp in root.rglob(f"{_PART_PREFIX}*{_PART_SUFFIX}"):
            if tmp.is_file() and tmp.name.startswith(_PART_PREFIX):
                tmp.unlink(missing_ok=True)
                removed.append(tmp)
    return removed
