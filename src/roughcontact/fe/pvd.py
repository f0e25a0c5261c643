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

from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from ..files import atomic_path
from . import assembly
from .deck_run import STATUS_NAMES, DeckResult
from .vtu import write_mesh, write_points

__all__ = ["write_series", "cell_stresses"]


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


def write_series(path, result: DeckResult) -> Path:
    """Write the series (module docstring) to ``path`` (a .pvd file in an existing folder);
    returns the path."""
    path = Path(path)
    if path.suffix.lower() != ".pvd":
        raise ValueError(f"the series is a .pvd file, got {path.name!r}")
    if not path.parent.is_dir():
        raise ValueError(f"no folder {path.parent} for {path.name}")
    folder = path.with_suffix("")
    folder.mkdir(exist_ok=True)
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
            entries.append(f'    <DataSet timestep="{inc.time!r}" part="{part}" '
                           f'file={quoteattr(f"{folder.name}/{file.name}")}/>')
    legend = ", ".join(f"{i} {name}" for i, name in enumerate(STATUS_NAMES))
    text = "\n".join(['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1">',
                      f"  <!-- roughcontact fe run: part 0 the bodies, part 1 the interface points; status: {legend} -->",
                      "  <Collection>", *entries, "  </Collection>", "</VTKFile>", ""])
    with atomic_path(path) as tmp:
        Path(tmp).write_text(text)
    return path
