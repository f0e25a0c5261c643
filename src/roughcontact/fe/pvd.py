"""A deck run as a ParaView series: ``OUT.pvd`` and, in the folder ``OUT/``, two VTU files per
converged increment — the bodies (``<k>.vtu``: point data ``displacement`` [deck length],
cell data ``stress`` (Voigt xx, yy, zz, yz, xz, xy, the mean over the element's Gauss points)
and ``von_mises`` [deck stress]) and the interface points (``<k>_interface.vtu``: the fields of
:meth:`~.deck_run.DeckResult.interface_fields` under the JSON's names and units, ``status``
0 stick, 1 slip, 2 open, and the axes ``e_1``, ``e_2``, ``n``). The series' time is the deck's
step time; part 0 the bodies, part 1 the interface. The status legend is written into the
.pvd as a comment (and in docs/own-model.md).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import secrets
import shutil
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from ..files import atomic_path
from ..limits import describe
from . import assembly
from .deck_run import STATUS_NAMES, DeckResult
from .vtu import write_mesh, write_points

__all__ = ["write_series", "cell_stresses"]

#: the temporary folder of a series being written: ``.OUT.<pid>.<random>.part`` next to ``OUT``
_TMP_PREFIX, _TMP_SUFFIX = ".", ".part"


def cell_stresses(result: DeckResult, u) -> list[np.ndarray]:
    """Per block of the mesh, the stress (n_cells, 6) [deck stress] averaged over each cell's
    Gauss points, for the displacements u (3N,)."""
    mesh, deck = result.problem.mesh, result.problem.dm.deck
    out = []
    for block, material in zip(mesh.blocks, result.problem.dm.materials):
        m = deck.materials[material]
        D = assembly.isotropic_elasticity(m.E, m.nu)
        rule = assembly.default_rule(block.element)
        _, sigma = assembly.strain_stress(mesh.points, block.element, block.cells, u, D, rule.points)
        out.append(np.einsum("cps,p->cs", sigma, rule.weights) / rule.weights.sum())
    return out


def _von_mises(s: np.ndarray) -> np.ndarray:
    xx, yy, zz, yz, xz, xy = s.T
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3.0 * (yz ** 2 + xz ** 2 + xy ** 2))


def _series_entries(folder: Path, final_name: str, result: DeckResult) -> list[str]:
    """Write the VTUs of every increment into ``folder``; the .pvd's DataSet lines, which name
    the files under the series' final folder name. The timestep is the increment's deck time
    as a plain decimal (``float`` repr: ParaView and ``float()`` read it; a numpy repr would
    not)."""
    pts = result.problem.points
    frames = {"e_1": pts.frames[:, 0], "e_2": pts.frames[:, 1], "n": pts.frames[:, 2]}
    entries = []
    for k, inc in enumerate(result.increments, start=1):
        stress = cell_stresses(result, inc.u)
        body = write_mesh(folder / f"{k:04d}.vtu", result.problem.mesh,
                          point_data={"displacement": inc.u.reshape(-1, 3)},
                          cell_data={"stress": stress, "von_mises": [_von_mises(s) for s in stress]})
        fields = result.interface_fields(inc)
        xyz = np.column_stack([fields.pop(c) for c in ("x", "y", "z")])
        iface = write_points(folder / f"{k:04d}_interface.vtu", xyz, {**fields, **frames})
        for part, file in enumerate((body, iface)):
            entries.append(f'    <DataSet timestep="{float(inc.time)!r}" part="{part}" '
                           f'file={quoteattr(f"{final_name}/{file.name}")}/>')
    return entries


def _remove_stale_temporaries(parent: Path, name: str) -> None:
    """Remove the temporary folders of series ``name`` whose writing process is gone (a run
    killed by SIGKILL cannot clean up): ``.<name>.<pid>.<random>.part`` with that pid not alive
    on this machine. A folder of a live process (a concurrent run) is left alone."""
    for tmp in parent.glob(f"{_TMP_PREFIX}{name}.*{_TMP_SUFFIX}"):
        try:
            pid = int(tmp.name[len(_TMP_PREFIX) + len(name) + 1:].split(".")[0])
            os.kill(pid, 0)
        except ValueError:
            continue  # not one of ours
        except ProcessLookupError:
            shutil.rmtree(tmp, ignore_errors=True)
        except PermissionError:
            continue  # alive, another user's


@contextlib.contextmanager
def _locked(directory: Path):
    """An exclusive flock on ``directory`` while its series are swapped (two runs into one
    OUT.pvd finish one after the other, each leaving a .pvd with its own folder)."""
    fd = os.open(directory, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # releases the lock


def write_series(path, result: DeckResult) -> Path:
    """Write the series (module docstring) to ``path`` (a .pvd file in an existing folder);
    returns the path.

    The VTUs are written into a temporary folder ``.OUT.<pid>.<random>.part`` next to ``OUT``;
    only when all are written is the old series removed and the new one renamed into place,
    the folder first and the .pvd last, under a lock on the parent folder. So a .pvd lists
    exactly the files of its own run, in its own folder (no stale files of a longer earlier
    run, no mix of two concurrent runs), and an interrupted run (an error, Ctrl-C, SIGKILL)
    leaves nothing under the final names (after SIGKILL a hidden temporary folder, removed by
    the next run into the same series)."""
    path = Path(path)
    if path.suffix.lower() != ".pvd":
        raise ValueError(f"the series is a .pvd file, got {describe(path.name)}")
    parent = path.parent
    if not parent.is_dir():
        raise ValueError(f"no folder {parent} for {path.name}")
    folder = path.with_suffix("")
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{folder} is not a folder: the series' files go into a folder of that name")
    _remove_stale_temporaries(parent, folder.name)
    tmp = parent / f"{_TMP_PREFIX}{folder.name}.{os.getpid()}.{secrets.token_hex(4)}{_TMP_SUFFIX}"
    tmp.mkdir()  # mode 0o777 minus the umask, like any new folder
    try:
        entries = _series_entries(tmp, folder.name, result)
        legend = ", ".join(f"{i} {name}" for i, name in enumerate(STATUS_NAMES))
        text = "\n".join(['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1">',
                          f"  <!-- roughcontact fe run: part 0 the bodies, part 1 the interface points; status: {legend} -->",
                          "  <Collection>", *entries, "  </Collection>", "</VTKFile>", ""])
        with _locked(parent), atomic_path(path) as pvd_tmp:  # the .pvd's rename too under the lock
            Path(pvd_tmp).write_text(text)
            # no .pvd while the folders are swapped: a .pvd never names another run's files
            path.unlink(missing_ok=True)
            old = None
            if folder.exists():
                old = parent / f"{_TMP_PREFIX}{folder.name}.{os.getpid()}.{secrets.token_hex(4)}.old{_TMP_SUFFIX}"
                os.rename(folder, old)
            os.rename(tmp, folder)
            # atomic_path renames pvd_tmp onto path as this block ends: the .pvd appears last
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return path
