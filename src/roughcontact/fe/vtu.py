"""VTU export (ParaView) of FE meshes, interface faces and interface-point fields, via meshio.

Cell mapping (VTK has no 21- or 28-node hexahedron):

* HEX20 → VTK quadratic hexahedron ("hexahedron20"); the node orders are the same. TET10 (C3D10)
  → "tetra10" and its 6-node faces → "triangle6", as they are (the same node orders).
* HEX21 → "hexahedron20" of its nodes 0–19, which are exactly HEX20's. The contact-face centre
  (node 20) is a point of the file with its data, but the cell draws that face serendipity-wise.
* HEX28 → "hexahedron20" too: its corners, top and vertical mid-edge nodes are nodes of the mesh;
  its contact-face edges have no mid-edge node, so the file gets one extra point per such edge,
  placed and valued by HEX28's own interpolation at the edge midpoint (the cubic edge through its
  4 nodes). These extra points follow the mesh's nodes (indices ≥ mesh.n_nodes) and are shared by
  the elements on either side of the edge, so the exported cells stay conforming (no cracks when
  warped by displacement) — unlike 8-node hexahedra, whose straight edges would not match the
  quadratic faces of the hex20 above. No conforming subdivision of HEX28 into VTK cells uses only
  its own nodes (its top face has none at ±1/√5). The contact face itself is drawn exactly by
  :func:`write_interfaces`.
* Interface elements (:func:`write_interfaces`, a separate file, so that the faces do not
  overlap the volume's boundary): side B's face, QUAD9 → "quad9" (VTK biquadratic quad, same
  order); QUAD16 → 3 × 3 bilinear "quad" cells through its 4 × 4 nodes.
* Interface points (:func:`write_points`): one "vertex" cell per point.

Files are written atomically: to a temporary file in the target's directory, given the mode
0o666 & ~umask like an ordinary new file, then renamed over the target.
"""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np

from ..files import atomic_path
from .element import HEX20_NODES, Element
from .mesh import Mesh

__all__ = ["write_mesh", "write_interfaces", "write_points", "hex20_view"]


# ---------------------------------------------------------------------------------------------
# cells
# ---------------------------------------------------------------------------------------------
#: elements and faces whose node order is VTK's: written as they are (C3D10 = VTK's quadratic
#: tetra: corners, then the mid-edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3; TRI6 = quadratic triangle)
DIRECT_CELLS = {"tet10": "tetra10"}
DIRECT_FACES = {"quad9": "quad9", "tri6": "triangle6"}

def _hex20_stencils(element: Element):
    """For each of HEX20's 20 reference nodes: the element's node there (index ≥ 0), or −1 and
    the element's shape-function weights at that point (only the nonzero ones kept)."""
    idx, stencils = [], {}
    for a, x in enumerate(HEX20_NODES):
        hit = np.flatnonzero(np.all(np.abs(element.nodes - x) < 1e-12, axis=1))
        idx.append(int(hit[0]) if hit.size == 1 else -1)
        if hit.size != 1:
            w = element.shape(x[None, :])[0]
            nz = np.flatnonzero(np.abs(w) > 1e-12)
            stencils[a] = (nz, w[nz])
    return np.array(idx), stencils


def hex20_view(mesh: Mesh):
    """The volume as VTK quadratic hexahedra.

    Returns (cells, extra_ids, extra_weights): cells a list of (n_cells, 20) int64 arrays, one
    per block, indexing the mesh's nodes and, from mesh.n_nodes on, extra points; an extra point
    is Σ_k extra_weights[m, k] · (node extra_ids[m, k]) (a ragged stencil padded with weight 0).
    Extra points with the same stencil nodes (an edge shared by two cells) are one point.
    """
    cells, stencil_ids, stencil_w, owners = [], [], [], []
    for b, block in enumerate(mesh.blocks):
        if block.element.name in DIRECT_CELLS:  # written as they are (write_mesh)
            cells.append(block.cells)
            continue
        idx, stencils = _hex20_stencils(block.element)
        out = np.where(idx >= 0, block.cells[:, np.maximum(idx, 0)], -1)
        for a, (nz, w) in stencils.items():
            stencil_ids.append(block.cells[:, nz])
            stencil_w.append(np.broadcast_to(w, (len(block.cells), w.size)))
            owners.append((b, a))
        cells.append(out)
    if not stencil_ids:
        return cells, np.zeros((0, 1), np.int64), np.zeros((0, 1))
    width = max(s.shape[1] for s in stencil_ids)

    def pad(s, value):
        return np.pad(s, ((0, 0), (0, width - s.shape[1])), constant_values=value)

    ids = np.vstack([pad(s, -1) for s in stencil_ids])
    w = np.vstack([pad(s, 0.0) for s in stencil_w])
    key = np.sort(ids, axis=1)  # the same edge seen from both neighbours has the same node set
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    start = 0
    for (b, a), s in zip(owners, stencil_ids):
        cells[b][:, a] = mesh.n_nodes + inverse.reshape(-1)[start:start + len(s)]
        start += len(s)
    ids, w = ids[first], w[first]
    return cells, np.where(ids >= 0, ids, 0), w


def _extend(values: np.ndarray, ids: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Node values (N, ...) with the extra points' interpolated values appended (integer data
    rounded back to integers)."""
    v = np.asarray(values)
    extra = np.einsum("mk,mk...->m...", w, v[ids].astype(float))
    if not np.issubdtype(v.dtype, np.floating):
        extra = np.rint(extra).astype(v.dtype)
    return np.concatenate([v, extra.astype(v.dtype, copy=False)])


def _subquads(face: Element) -> np.ndarray:
    """(k, 4) local node indices of the bilinear quads through a tensor-grid face's nodes,
    counter-clockwise in (u, v) like the face itself."""
    us, vs = np.unique(face.nodes[:, 0]), np.unique(face.nodes[:, 1])
    grid = np.full((vs.size, us.size), -1)
    for a, (u, v) in enumerate(face.nodes):
        grid[np.searchsorted(vs, v), np.searchsorted(us, u)] = a
    if np.any(grid < 0):
        raise ValueError(f"{face.name}: nodes do not form a tensor grid")
    return np.array([[grid[j, i], grid[j, i + 1], grid[j + 1, i + 1], grid[j + 1, i]]
                     for j in range(vs.size - 1) for i in range(us.size - 1)])


# ---------------------------------------------------------------------------------------------
# writing
# ---------------------------------------------------------------------------------------------
def _write(path, m: meshio.Mesh) -> Path:
    """Write ``m`` as VTU to ``path`` atomically, mode 0o666 & ~umask (files.atomic_path)."""
    path = Path(path)
    with atomic_path(path) as tmp:
        meshio.write(tmp, m, file_format="vtu")
    return path


def _check_point_data(point_data, n: int) -> dict[str, np.ndarray]:
    out = {}
    for name, v in (point_data or {}).items():
        v = np.asarray(v)
        if v.shape[:1] != (n,):
            raise ValueError(f"point data {name!r} has {v.shape[:1]} rows, expected {n}")
        out[name] = v
    return out


def write_mesh(path, mesh: Mesh, point_data=None, cell_data=None) -> Path:
    """Write the volume cells of ``mesh`` (module docstring for the cell mapping) to ``path``.

    point_data  {name: (N, ...) per-node values}, e.g. displacement (N, 3) [mm]; extra HEX28
                mid-edge points get the element's interpolation of them.
    cell_data   {name: [one (n_cells, ...) array per mesh block]}.
    """
    cells, ids, w = hex20_view(mesh)
    data = _check_point_data(point_data, mesh.n_nodes)
    cdata = {}
    for name, arrays in (cell_data or {}).items():
        arrays = [np.asarray(a) for a in arrays]
        if [len(a) for a in arrays] != [len(c) for c in cells]:
            raise ValueError(f"cell data {name!r} needs one array per block with one row per cell")
        cdata[name] = arrays
    kinds = [DIRECT_CELLS.get(block.element.name, "hexahedron20") for block in mesh.blocks]
    m = meshio.Mesh(_extend(mesh.points, ids, w), list(zip(kinds, cells)),
                    point_data={k: _extend(v, ids, w) for k, v in data.items()}, cell_data=cdata)
    return _write(path, m)


def write_interfaces(path, mesh: Mesh, point_data=None) -> Path:
    """Write side B's faces of every interface block of ``mesh`` (QUAD9 as "quad9", QUAD16 as
    3 × 3 "quad"), over all the mesh's points so that per-node ``point_data`` (N, ...) applies.
    Cell data "element": the interface element each cell belongs to (index in its block)."""
    if not mesh.interfaces:
        raise ValueError(f"mesh {mesh.name!r} has no interface elements")
    blocks, owner = [], []
    for block in mesh.interfaces:
        face, side_b = block.element.face, block.side("B")
        element_ids = np.arange(len(side_b))
        if face.name in DIRECT_FACES:
            blocks.append((DIRECT_FACES[face.name], side_b))
            owner.append(element_ids)
        else:
            sub = _subquads(face)
            blocks.append(("quad", side_b[:, sub].reshape(-1, 4)))
            owner.append(np.repeat(element_ids, len(sub)))
    m = meshio.Mesh(mesh.points, blocks, point_data=_check_point_data(point_data, mesh.n_nodes),
                    cell_data={"element": owner})
    return _write(path, m)


def write_points(path, xyz, point_data=None) -> Path:
    """Write a point cloud, one VTK vertex per point: ``xyz`` (n, 3) [mm], ``point_data``
    {name: (n, ...)}, e.g. traction (n, 3) [N/mm²], gap (n,) [mm], status (n,) int
    (0 stick, 1 slip, 2 open) at every interface integration point."""
    xyz = np.asarray(xyz, dtype=float)
    if xyz.ndim != 2 or xyz.shape[1] != 3:
        raise ValueError(f"xyz must have shape (n, 3), got {xyz.shape}")
    cells = [("vertex", np.arange(len(xyz), dtype=np.int64)[:, None])]
    return _write(path, meshio.Mesh(xyz, cells, point_data=_check_point_data(point_data, len(xyz))))


def write_solution(path, mesh: Mesh, u, point_fields, points_path=None) -> tuple[Path, Path]:
    """A solved model for ParaView: the volume with the displacement ``u`` (3N,) [mm] to
    ``path`` and the interface points with ``point_fields`` (name → per-point array; ``x`` (n, 3)
    [mm] the positions) to ``points_path`` (default: ``path``'s stem + "_interface.vtu")."""
    path = Path(path)
    points_path = Path(points_path) if points_path is not None else path.with_name(path.stem + "_interface.vtu")
    fields = dict(point_fields)
    xyz = fields.pop("x")
    write_mesh(path, mesh, point_data={"displacement_mm": np.asarray(u, dtype=float).reshape(-1, 3)})
    write_points(points_path, xyz, fields)
    return path, points_path
