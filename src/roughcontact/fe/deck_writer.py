"""Input decks of structured boxes of C3D20 elements (CalculiX/Abaqus syntax), as text.

:func:`box_part` meshes one axis-parallel box with element boundaries x, y, z into C3D20
elements (node (i, j, k) of the doubled grid exists where at most one index is odd; element
node order CalculiX/Abaqus = VTK's quadratic hexahedron) and names its faces: node sets and
element faces ``XMIN`` … ``ZMAX`` (faces S6, S4, S3, S5, S1, S2 of its elements). The
``*_lines`` helpers write the keyword blocks with full-precision numbers (``digits=None``: the
shortest text that reads back to the same float) or ``digits`` significant digits (CalculiX
reads at most 20 characters per field). The examples of section 9 and the tests build their
decks from these; nothing here knows contact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BoxPart", "box_part", "node_lines", "element_lines", "id_lines", "number"]

#: element faces of a box face: (name, face label S1-S6, axis, end)
BOX_FACES = (("XMIN", 6, 0, 0), ("XMAX", 4, 0, 1), ("YMIN", 3, 1, 0), ("YMAX", 5, 1, 1), ("ZMIN", 1, 2, 0),
             ("ZMAX", 2, 2, 1))
#: C3D20 corner and mid-edge nodes as steps (0, 1, 2) of the doubled grid within an element
_C3D20 = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2),
          (1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
          (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]


def number(x: float, digits: int | None = None) -> str:
    """A float as deck text: the shortest round-trip form, or ``digits`` significant digits."""
    return repr(float(x)) if digits is None else format(float(x), f".{digits}g")


@dataclass(frozen=True, eq=False)
class BoxPart:
    """One meshed box: node ids (n,) and coordinates (n, 3); element ids (m,) and their
    connectivity (m, 20) in node ids; per box face its node ids and element ids; the element
    boundaries; the element index (i, j, k) of every element."""

    node_ids: np.ndarray
    coords: np.ndarray
    element_ids: np.ndarray
    connectivity: np.ndarray
    face_nodes: dict[str, np.ndarray]
    face_elements: dict[str, np.ndarray]
    edges: tuple[np.ndarray, np.ndarray, np.ndarray]
    element_ijk: np.ndarray

    def face_label(self, face: str) -> int:
        """The element face label (1-6: S1 … S6) of box face ``face`` ("XMIN" … "ZMAX")."""
        return next(label for name, label, _, _ in BOX_FACES if name == face)


def box_part(x, y, z, *, first_node: int = 1, first_element: int = 1) -> BoxPart:
    """C3D20 mesh of the box with element boundaries ``x``, ``y``, ``z`` (strictly increasing)."""
    edges = [np.asarray(e, dtype=float) for e in (x, y, z)]
    for e, name in zip(edges, "xyz"):
        if e.ndim != 1 or e.size < 2 or not np.all(np.diff(e) > 0):
            raise ValueError(f"box_part: {name} edges must be >= 2 strictly increasing values")

    def doubled(e):
        out = np.empty(2 * e.size - 1)
        out[0::2], out[1::2] = e, 0.5 * (e[:-1] + e[1:])
        return out

    X, Y, Z = (doubled(e) for e in edges)
    I, J, K = np.meshgrid(np.arange(X.size), np.arange(Y.size), np.arange(Z.size), indexing="ij")
    keep = ((I % 2) + (J % 2) + (K % 2)) <= 1
    order = np.lexsort((I[keep], J[keep], K[keep]))  # x fastest, then y, then z
    ijk = np.column_stack([I[keep], J[keep], K[keep]])[order]
    lookup = -np.ones(I.shape, dtype=np.int64)
    lookup[tuple(ijk.T)] = np.arange(len(ijk))
    node_ids = first_node + np.arange(len(ijk), dtype=np.int64)
    coords = np.column_stack([X[ijk[:, 0]], Y[ijk[:, 1]], Z[ijk[:, 2]]])
    n = [e.size - 1 for e in edges]
    ei, ej, ek = (g.ravel() for g in np.meshgrid(np.arange(n[0]), np.arange(n[1]), np.arange(n[2]), indexing="ij"))
    el_order = np.lexsort((ei, ej, ek))
    el = np.column_stack([ei, ej, ek])[el_order]
    steps = np.array(_C3D20)
    conn = node_ids[lookup[tuple((2 * el[:, None, :] + steps[None, :, :]).transpose(2, 0, 1))]]
    element_ids = first_element + np.arange(len(el), dtype=np.int64)
    face_nodes, face_elements = {}, {}
    for name, _, axis, end in BOX_FACES:
        at = 0 if end == 0 else 2 * n[axis]
        face_nodes[name] = node_ids[ijk[:, axis] == at]
        face_elements[name] = element_ids[el[:, axis] == (0 if end == 0 else n[axis] - 1)]
    return BoxPart(node_ids, coords, element_ids, conn, face_nodes, face_elements, tuple(edges), el)


def node_lines(part: BoxPart, nset: str | None = None, digits: int | None = None) -> list[str]:
    """``*NODE`` block of a part."""
    head = "*NODE" + (f", NSET={nset}" if nset else "")
    return [head] + [f"{i}, {number(a, digits)}, {number(b, digits)}, {number(c, digits)}"
                     for i, (a, b, c) in zip(part.node_ids.tolist(), part.coords)]


def element_lines(part: BoxPart, elset: str, etype: str = "C3D20") -> list[str]:
    """``*ELEMENT`` block: the id and 15 nodes on the first line, 5 on the second."""
    out = [f"*ELEMENT, TYPE={etype}, ELSET={elset}"]
    for eid, c in zip(part.element_ids.tolist(), part.connectivity.tolist()):
        out.append(f"{eid}, " + ", ".join(map(str, c[:15])) + ",")
        out.append(", ".join(map(str, c[15:])))
    return out


def id_lines(keyword: str, ids, per_line: int = 16) -> list[str]:
    """A set block (e.g. ``*NSET, NSET=BASE``) listing ``ids``, 16 per line."""
    ids = [str(int(i)) for i in np.asarray(ids).ravel()]
    return [keyword] + [", ".join(ids[i:i + per_line]) for i in range(0, len(ids), per_line)]
