"""Tetrahedral (TET10 = CalculiX C3D10) meshes of boxes, made by splitting hexahedra.

gmsh is not a dependency; the tests and the convergence study need tetrahedral meshes of the
same boxes the hexahedral examples use. :func:`hex_to_tets` splits every 8-node hexahedron
(corners in C3D8/VTK order: bottom 0-3 counter-clockwise, top 4-7 above them) into the six
tetrahedra of Kuhn's (Freudenthal's) triangulation of the cube: for every permutation
(a, b, c) of the axes, the path corner 0 → +e_a → +e_b → +e_c. All six share the cube's
diagonal from local corner 0 to corner 6, and every face of the cube is cut along its diagonal
through its lowest corner, so neighbouring hexahedra of a structured grid (all in the same
orientation) give conforming triangles. Each tetrahedron is ordered to have det J > 0
(corners 2 and 3 swapped where needed), and the six mid-edge nodes are the mid-points of the
straight edges, one node per edge shared by all its tetrahedra.

:func:`box_tets` meshes a box like :func:`.mesh.box` (no transition layer: the TRI6 faces of
TET10 are already the faces of the 12-node interface elements) with node sets and face sets
"xmin" … "zmax" (TRI6 faces, ∂x/∂u × ∂x/∂v outward, :data:`.element.TET10_FACES`).
:func:`face_labels` gives such a face set's CalculiX face labels S1-S4 (for ``*SURFACE`` and
``*DLOAD`` lines of a deck written from the mesh).
"""

from __future__ import annotations

import itertools

import numpy as np

from .element import TET10, TET10_FACES, TRI6
from .mesh import CellBlock, FaceSet, Mesh

__all__ = ["hex_to_tets", "box_tets", "face_labels", "KUHN"]

#: the cube's corners (i, j, k) in C3D8 order
_CUBE = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)])


def _kuhn() -> np.ndarray:
    """(6, 4) local hexahedron corners of Kuhn's six tetrahedra (module docstring)."""
    out = []
    for perm in itertools.permutations(range(3)):
        p = np.zeros(3, dtype=int)
        path = [p.copy()]
        for axis in perm:
            p[axis] = 1
            path.append(p.copy())
        out.append([int(np.flatnonzero(np.all(_CUBE == q, axis=1))[0]) for q in path])
    return np.array(out)


KUHN = _kuhn()
_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))  # TET10's mid-edge nodes 4-9


def hex_to_tets(points, hexes) -> tuple[np.ndarray, np.ndarray]:
    """Split hexahedra ``hexes`` (n, 8) (C3D8 corner order, indices into ``points`` (N, 3) [mm])
    into 6 n TET10 cells. Returns (points (N + new, 3), cells (6 n, 10)): the corner points
    first (unchanged), then one mid-edge point per distinct edge."""
    points = np.asarray(points, dtype=float)
    corners = np.asarray(hexes, dtype=np.int64)[:, KUHN].reshape(-1, 4)  # (6n, 4)
    x = points[corners]
    det = np.linalg.det(x[:, 1:] - x[:, :1])
    if np.any(det == 0.0):
        raise ValueError("hex_to_tets: a degenerate tetrahedron (flat hexahedron?)")
    corners[det < 0] = corners[det < 0][:, [0, 1, 3, 2]]
    pairs = np.stack([corners[:, list(e)] for e in _EDGES], axis=1)  # (6n, 6, 2)
    keys = np.sort(pairs, axis=2).reshape(-1, 2)
    uniq, inverse = np.unique(keys, axis=0, return_inverse=True)
    mids = len(points) + inverse.reshape(-1, 6)
    new = points[uniq].mean(axis=1)
    return np.vstack([points, new]), np.hstack([corners, mids])


def box_tets(x_edges, y_edges, z_edges, name: str = "box") -> Mesh:
    """TET10 mesh of the box with hexahedral grid lines ``x_edges`` × ``y_edges`` × ``z_edges``
    (mm, increasing), each grid cell split by :func:`hex_to_tets`. Block "bulk"; node sets and
    face sets "xmin" … "zmax" (module docstring)."""
    edges = [np.asarray(e, dtype=float) for e in (x_edges, y_edges, z_edges)]
    n = [e.size - 1 for e in edges]
    grid = np.stack(np.meshgrid(*edges, indexing="ij"), axis=-1).reshape(-1, 3)
    index = np.arange(grid.shape[0]).reshape([e.size for e in edges])
    hexes = []
    for i, j, k in itertools.product(*(range(m) for m in n)):
        hexes.append([index[i + a, j + b, k + c] for a, b, c in _CUBE])
    points, cells = hex_to_tets(grid, np.array(hexes))
    node_sets, face_sets = {}, {}
    faces = np.array([TET10_FACES[s] for s in range(1, 5)])  # (4, 6)
    all_faces = cells[:, faces]  # (c, 4, 6)
    for fname, (axis, value) in {"xmin": (0, 0), "xmax": (0, -1), "ymin": (1, 0), "ymax": (1, -1),
                                 "zmin": (2, 0), "zmax": (2, -1)}.items():
        on = np.abs(points[:, axis] - edges[axis][value]) <= 1e-12 * np.ptp(edges[axis])
        node_sets[fname] = np.flatnonzero(on)
        hit = np.all(on[all_faces], axis=2)  # (c, 4)
        c, s = np.nonzero(hit)
        face_sets[fname] = FaceSet(0, c, all_faces[c, s], TRI6)
    return Mesh(points, (CellBlock("bulk", TET10, cells),), node_sets, face_sets, (), name)


def face_labels(cells, face_set) -> np.ndarray:
    """CalculiX face numbers (1-4: S1-S4 of :data:`.element.TET10_FACES`) of the faces of a
    TET10 face set (``face_set.cell_indices`` into ``cells`` (c, 10), ``face_set.face_nodes``
    (n, 6) in TET10_FACES' order, as :func:`box_tets` makes them). A face that is not one of its
    cell's four is an error naming the face."""
    cells = np.asarray(cells)[np.asarray(face_set.cell_indices)]
    faces = np.asarray(face_set.face_nodes)
    out = np.zeros(len(faces), dtype=np.int64)
    for s in range(1, 5):
        out[np.all(cells[:, list(TET10_FACES[s])] == faces, axis=1)] = s
    bad = np.flatnonzero(out == 0)
    if bad.size:
        raise ValueError(f"face_labels: face {int(bad[0])} (nodes {faces[bad[0]].tolist()}) is not a face S1-S4 "
                         f"of its cell {int(np.asarray(face_set.cell_indices)[bad[0]])}")
    return out
