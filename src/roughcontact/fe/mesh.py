"""Structured hexahedral meshes of boxes, with transition layers and interface elements.

The examples of section 9 (Buczkowski & Kleiber 2009) are boxes: the beam (half of
500 × 10 × 120 mm, on its 500 × 10 face on a rigid base) and the punch (quarter of 20 × 20 × 10 mm)
on a foundation (quarter of 100 × 100 × 50 mm). :func:`box` meshes one box with hex20 elements
and, optionally, a layer of transition elements (HEX21 or HEX28) along its contact face;
:func:`rigid_base_interface` and :func:`interface_between` add zero-thickness interface elements;
:func:`merge` puts two bodies into one mesh. Symmetry is the caller's: mesh the half/quarter
domain and fix the normal displacement on the node sets "xmin"/"ymin".

Node positions. Every node sits on a lattice: along each axis, element i spans
[e_i, e_{i+1}] and its reference coordinate r ∈ {−1, −1/√5, 0, 1/√5, 1} is lattice step
4i + {0, 1, 2, 3, 4}. The step fixes the coordinate e_i + (e_{i+1} − e_i)(1 + r)/2, which is the
trilinear map of the element's 8 corners (the elements are axis-parallel boxes). Nodes of
neighbouring elements are merged by their integer steps — exactly, with no floating tolerance —
and each coordinate is computed once from its step, so shared nodes are bitwise identical.

Orientation. Every face set lists its faces' nodes in the face element's order such that
∂x/∂ξ × ∂x/∂η points OUT of the body (the "contact" set included: for the ζ = −1 face of a
transition element that is the ``contact_face`` order with ξ and η swapped). Interface elements
follow :mod:`.interface_element`: side A's normal points from A to B.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from .element import HEX20, HEX21, HEX28, LOBATTO4, QUAD8, QUAD9, QUAD16, TRI6, Element, Polynomials
from .interface_element import INTERFACE12, INTERFACE18, INTERFACE32, InterfaceElement
from ..limits import describe

__all__ = [
    "CellBlock", "FaceSet", "InterfaceBlock", "Mesh", "LATERAL28", "graded", "box",
    "rigid_base_interface", "merge", "interface_between", "local_face", "dofs",
]

#: reference positions of the lattice steps 0..4 inside one element (section "Node positions")
_LEVELS = np.array([-1.0, -LOBATTO4, 0.0, LOBATTO4, 1.0])
_FRACTION = (1.0 + _LEVELS[:4]) / 2.0  # fraction of the element length at steps 0..3
_STEPS = 4  # lattice steps per element
_FACES = {"xmin": (0, -1), "xmax": (0, 1), "ymin": (1, -1), "ymax": (1, 1), "zmin": (2, -1), "zmax": (2, 1)}
_TRANSITION = {"quadratic": HEX21, "cubic": HEX28}
_INTERFACE_OF = {QUAD9.name: INTERFACE18, QUAD16.name: INTERFACE32, TRI6.name: INTERFACE12}


def _lateral28_space() -> Polynomials:
    """Trace of HEX28 on a lateral face, (u along the face, v = ζ): cubic(u)·(1 − v)/2 ⊕
    quadratic(u)·(1 + v)/2 ⊕ linear(u)·(1 − v²) (element.py's face-layer space restricted)."""
    rows = [{(a, 0): 0.5, (a, 1): -0.5} for a in range(4)]
    rows += [{(a, 0): 0.5, (a, 1): 0.5} for a in range(3)]
    rows += [{(a, 0): 1.0, (a, 2): -1.0} for a in range(2)]
    exps = sorted({e for r in rows for e in r})
    coefficients = np.array([[r.get(e, 0.0) for e in exps] for r in rows])
    return Polynomials(np.array(exps, dtype=np.int64), coefficients)


#: the 9-node lateral face of HEX28: cubic edge (Lobatto nodes) at v = −1, quadratic edge at v = +1
LATERAL28 = Element("lateral28", np.array(
    [(-1, -1), (1, -1), (1, 1), (-1, 1), (-LOBATTO4, -1), (LOBATTO4, -1), (1, 0), (0, 1), (-1, 0)],
    dtype=float), _lateral28_space())


# ---------------------------------------------------------------------------------------------
# data
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class CellBlock:
    """Cells of one element type: ``cells`` (n, element.n_nodes) int64 node indices."""

    name: str
    element: Element
    cells: np.ndarray

    def __post_init__(self):
        cells = np.asarray(self.cells, dtype=np.int64).reshape(-1, self.element.n_nodes)
        object.__setattr__(self, "cells", cells)


@dataclass(frozen=True, eq=False)
class FaceSet:
    """Faces of cells of block ``block_index``: ``cell_indices`` (n,) and ``face_nodes``
    (n, face_element.n_nodes) global node indices in the face element's order, oriented so that
    ∂x/∂ξ × ∂x/∂η points out of the body."""

    block_index: int
    cell_indices: np.ndarray
    face_nodes: np.ndarray
    face_element: Element

    def __len__(self) -> int:
        return int(self.face_nodes.shape[0])


@dataclass(frozen=True, eq=False)
class InterfaceBlock:
    """Interface elements: ``cells`` (n, 2·n_face) int64, side A's face nodes then side B's."""

    name: str
    element: InterfaceElement
    cells: np.ndarray

    def __post_init__(self):
        cells = np.asarray(self.cells, dtype=np.int64).reshape(-1, self.element.n_nodes)
        object.__setattr__(self, "cells", cells)

    def side(self, which: str) -> np.ndarray:
        """Node indices (n, n_face) of side "A" or "B"."""
        n = self.element.face.n_nodes
        return {"A": self.cells[:, :n], "B": self.cells[:, n:]}[which]


@dataclass(frozen=True, eq=False)
class Mesh:
    """Nodes ``points`` (N, 3) [mm], volume ``blocks``, named ``node_sets`` (sorted unique int64
    arrays) and ``face_sets``, and ``interfaces``. ``name`` prefixes the sets in :func:`merge`."""

    points: np.ndarray
    blocks: tuple[CellBlock, ...]
    node_sets: dict[str, np.ndarray] = field(default_factory=dict)
    face_sets: dict[str, FaceSet] = field(default_factory=dict)
    interfaces: tuple[InterfaceBlock, ...] = ()
    name: str = "mesh"

    def __post_init__(self):
        points = np.asarray(self.points, dtype=float)
        if points.ndim != 2 or points.shape[1] != 3:
            raise ValueError(f"points must have shape (N, 3), got {points.shape}")
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "blocks", tuple(self.blocks))
        object.__setattr__(self, "interfaces", tuple(self.interfaces))
        object.__setattr__(self, "node_sets",
                           {k: np.unique(np.asarray(v, dtype=np.int64)) for k, v in self.node_sets.items()})
        for cells in [b.cells for b in self.blocks] + [i.cells for i in self.interfaces]:
            if cells.size and (cells.min() < 0 or cells.max() >= len(points)):
                raise ValueError("a cell refers to a node index outside 0..N-1")

    @property
    def n_nodes(self) -> int:
        return int(self.points.shape[0])

    @property
    def n_dofs(self) -> int:
        """Three displacement components per node."""
        return 3 * self.n_nodes

    def summary(self) -> dict:
        """Sizes: nodes, dofs, cells per block, interface elements, their integration points
        ((p + 1)² per element on quadrilaterals, 6 on triangles: the "gauss" rule) and distinct contact nodes (side B) per interface block."""
        return {
            "name": self.name,
            "nodes": self.n_nodes,
            "dofs": self.n_dofs,
            "cells": {b.name: len(b.cells) for b in self.blocks},
            "interface_elements": {i.name: len(i.cells) for i in self.interfaces},
            "interface_points": {i.name: len(i.cells) * len(i.element.rule("gauss").weights)
                                 for i in self.interfaces},
            "interface_nodes": {i.name: int(np.unique(i.side("B")).size) for i in self.interfaces},
        }


# ---------------------------------------------------------------------------------------------
# edges
# ---------------------------------------------------------------------------------------------
def dofs(nodes, components) -> np.ndarray:
    """Global dof indices of ``nodes`` × ``components`` (0 u_x, 1 u_y, 2 u_z; three dofs per
    node, node-major), e.g. the supported dofs of a node set."""
    return (3 * np.asarray(nodes)[:, None] + np.asarray(components)[None, :]).ravel()


def graded(a: float, b: float, n: int, ratio: float = 1.0) -> np.ndarray:
    """n + 1 element boundaries from a to b (a < b, mm) whose sizes grow geometrically, the
    last size being ``ratio`` × the first (ratio < 1: small elements at b). Ends are exact."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"graded: n must be an integer >= 1, got {describe(n)}")
    if not (np.isfinite(a) and np.isfinite(b) and a < b):
        raise ValueError(f"graded: need finite a < b, got a={describe(a)}, b={describe(b)}")
    if not (np.isfinite(ratio) and ratio > 0):
        raise ValueError(f"graded: ratio must be finite and > 0, got {describe(ratio)}")
    if n == 1 and ratio != 1.0:
        raise ValueError(f"graded: one element has no size ratio, got ratio={describe(ratio)}")
    q = ratio ** (1.0 / (n - 1)) if n > 1 else 1.0
    sizes = q ** np.arange(n)
    edges = a + (b - a) * np.concatenate([[0.0], np.cumsum(sizes)]) / sizes.sum()
    edges[0], edges[-1] = a, b  # the cumulative sum may miss b by an ulp
    return edges


def _check_edges(edges, axis: str) -> np.ndarray:
    e = np.asarray(edges, dtype=float)
    if e.ndim != 1 or e.size < 2 or not np.all(np.isfinite(e)) or not np.all(np.diff(e) > 0):
        raise ValueError(f"box: {axis}_edges must be >= 2 finite, strictly increasing values")
    return e


# ---------------------------------------------------------------------------------------------
# local faces of an element
# ---------------------------------------------------------------------------------------------
def _node_index(element: Element, point) -> int:
    hit = np.flatnonzero(np.all(np.abs(element.nodes - point) < 1e-12, axis=1))
    return int(hit[0]) if hit.size == 1 else -1


@lru_cache(maxsize=None)
def _local_face_cached(element: Element, axis: int, side: int):
    if axis == 2:  # (u, v) = (ξ, η) on top, (η, ξ) at the bottom: outward without sign flips
        i, j, sigma = (0, 1, 1) if side > 0 else (1, 0, 1)
    else:  # lateral: v = ζ, so the cubic edge of HEX28 is LATERAL28's v = −1 edge
        i, j = 1 - axis, 2
        sigma = side * int(np.cross(np.eye(3)[i], np.eye(3)[j])[axis])
    on_face = np.flatnonzero(np.abs(element.nodes[:, axis] - side) < 1e-12)
    for face in (element.face_element, QUAD8, LATERAL28):
        if face is None or face.n_nodes != on_face.size:
            continue
        p = np.zeros((face.n_nodes, 3))
        p[:, axis], p[:, i], p[:, j] = side, sigma * face.nodes[:, 0], face.nodes[:, 1]
        idx = tuple(_node_index(element, x) for x in p)
        if -1 not in idx:
            return face, idx
    raise ValueError(f"{element.name}: no face element fits the face {'ξηζ'[axis]} = {side:+d}")


def local_face(element: Element, axis: int, side: int) -> tuple[Element, tuple[int, ...]]:
    """The face of ``element`` at reference coordinate ``axis`` (0, 1, 2 = ξ, η, ζ) = ``side``
    (±1): its face element (QUAD8, QUAD9, QUAD16 or LATERAL28) and the element's local node
    indices in the face element's order, with ∂x/∂u × ∂x/∂v pointing out of the element."""
    return _local_face_cached(element, int(axis), int(side))


def _swap(face: Element) -> np.ndarray:
    """Permutation p with face.nodes[p[a]] = face.nodes[a] with u and v swapped: reordering a
    face's nodes by p reverses its normal (corner 0 stays)."""
    p = [_node_index(face, (v, u)) for u, v in face.nodes]
    if -1 in p:
        raise ValueError(f"{face.name} is not symmetric under u <-> v")
    return np.array(p)


# ---------------------------------------------------------------------------------------------
# one box
# ---------------------------------------------------------------------------------------------
def _steps(element: Element, flip) -> np.ndarray:
    """(n_nodes, 3) lattice steps 0..4 of the element's nodes, reference axes scaled by ``flip``."""
    r = element.nodes * np.asarray(flip, dtype=float)
    k = np.abs(r[:, :, None] - _LEVELS[None, None, :]).argmin(axis=2)
    if not np.allclose(_LEVELS[k], r, rtol=0.0, atol=1e-12):
        raise ValueError(f"{element.name}: a node is off the lattice −1, ±1/√5, 0, 1")
    return k


def _coordinates(edges: np.ndarray, steps: np.ndarray) -> np.ndarray:
    """Coordinates [mm] of lattice steps along one axis (e_i exact at element boundaries)."""
    i, k = np.divmod(steps, _STEPS)
    upper = edges[np.minimum(i + 1, edges.size - 1)]
    return np.where(k == 0, edges[i], edges[i] + (upper - edges[i]) * _FRACTION[k])


def box(x_edges, y_edges, z_edges, *, contact_face: str | None = None, family: str = "quadratic",
        name: str = "box") -> Mesh:
    """Mesh of the box spanned by the element boundaries ``x_edges``, ``y_edges``, ``z_edges``
    (mm, strictly increasing): hex20 cells, except the layer along ``contact_face`` ("bottom":
    z = z_edges[0], "top": z = z_edges[-1]) which is HEX21 (family "quadratic") or HEX28
    ("cubic") with its local ζ = −1 face on the contact face. Block "bulk" holds the hex20 cells
    and "transition" the transition layer.

    Node sets "xmin" … "zmax" (all nodes on each box face) and "contact". Face sets "xmin" …
    "zmax" (outward) and "contact" (the transition layer's ζ = −1 faces, QUAD9/QUAD16). A box face
    covered by both blocks (a lateral face with a transition layer and more than one layer of
    cells) is split: "<face>" holds the bulk's faces, "<face>.transition" the transition layer's.
    """
    edges = [_check_edges(e, a) for e, a in zip((x_edges, y_edges, z_edges), "xyz")]
    n = [e.size - 1 for e in edges]
    if family not in _TRANSITION:
        raise ValueError(f"box: family must be one of {sorted(_TRANSITION)}, got {describe(family)}")
    if contact_face not in (None, "bottom", "top"):
        raise ValueError(f"box: contact_face must be None, 'bottom' or 'top', got {describe(contact_face)}")

    # (block name, element, z layers, flip of reference axes): "top" turns the element upside
    # down by a rotation about x (ζ → −ζ with η → −η keeps det J > 0)
    layers = np.arange(n[2])
    groups = []
    if contact_face is None:
        groups.append(("bulk", HEX20, layers, (1, 1, 1)))
    else:
        t = 0 if contact_face == "bottom" else n[2] - 1
        flip = (1, 1, 1) if contact_face == "bottom" else (1, -1, -1)
        if n[2] > 1:
            groups.append(("bulk", HEX20, layers[layers != t], (1, 1, 1)))
        groups.append(("transition", _TRANSITION[family], np.array([t]), flip))

    dims = np.array([_STEPS * m + 1 for m in n], dtype=np.int64)  # lattice points per axis
    keys, grids = [], []
    for _, element, zs, flip in groups:
        ix, iy, iz = (g.ravel() for g in np.meshgrid(np.arange(n[0]), np.arange(n[1]), zs, indexing="ij"))
        grid = np.column_stack([ix, iy, iz])  # (n_cells, 3) element indices
        k = _STEPS * grid[:, None, :] + _steps(element, flip)[None, :, :]
        keys.append(k[..., 0] + dims[0] * (k[..., 1] + dims[1] * k[..., 2]))
        grids.append(grid)
    uniq, inverse = np.unique(np.concatenate([k.ravel() for k in keys]), return_inverse=True)
    lattice = np.column_stack([uniq % dims[0], (uniq // dims[0]) % dims[1], uniq // (dims[0] * dims[1])])
    points = np.column_stack([_coordinates(edges[a], lattice[:, a]) for a in range(3)])

    blocks, start = [], 0
    for (bname, element, _, _), k in zip(groups, keys):
        blocks.append(CellBlock(bname, element, inverse[start:start + k.size].reshape(k.shape)))
        start += k.size

    node_sets = {}
    for fname, (axis, side) in _FACES.items():
        node_sets[fname] = np.flatnonzero(lattice[:, axis] == (0 if side < 0 else dims[axis] - 1))
    face_sets = {}
    for fname, (axis, side) in _FACES.items():
        parts = []
        for b, ((_, element, _, flip), grid) in enumerate(zip(groups, grids)):
            sel = np.flatnonzero(grid[:, axis] == (0 if side < 0 else n[axis] - 1))
            if sel.size:
                face, idx = local_face(element, axis, side * flip[axis])
                parts.append(FaceSet(b, sel, blocks[b].cells[sel][:, idx], face))
        face_sets[fname] = parts[0]
        if len(parts) == 2:
            face_sets[fname + ".transition"] = parts[1]
    if contact_face is not None:
        cname = "zmin" if contact_face == "bottom" else "zmax"
        node_sets["contact"] = node_sets[cname]
        face_sets["contact"] = face_sets[cname]
    return Mesh(points, tuple(blocks), node_sets, face_sets, (), name)


# ---------------------------------------------------------------------------------------------
# interfaces and assemblies of bodies
# ---------------------------------------------------------------------------------------------
def _face_set(mesh: Mesh, name: str) -> tuple[FaceSet, InterfaceElement]:
    if name not in mesh.face_sets:
        raise ValueError(f"no face set {describe(name)} in mesh {describe(mesh.name)} (have {sorted(mesh.face_sets)})")
    fs = mesh.face_sets[name]
    if fs.face_element.name not in _INTERFACE_OF:
        raise ValueError(f"face set {describe(name)} has {fs.face_element.name} faces; "
                         "interface elements need quad9, quad16 or tri6 faces")
    return fs, _INTERFACE_OF[fs.face_element.name]


def _with(mesh: Mesh, **changes) -> Mesh:
    fields = dict(points=mesh.points, blocks=mesh.blocks, node_sets=mesh.node_sets,
                  face_sets=mesh.face_sets, interfaces=mesh.interfaces, name=mesh.name)
    fields.update(changes)
    return Mesh(**fields)


def _check_new_interface(mesh: Mesh, interface_name: str):
    if interface_name in {i.name for i in mesh.interfaces}:
        raise ValueError(f"mesh {describe(mesh.name)} already has an interface {describe(interface_name)}")


def rigid_base_interface(mesh: Mesh, face_set: str = "contact", interface_name: str = "interface",
                         base: str = "base") -> Mesh:
    """A new mesh with an interface element on every face of ``face_set``: side B is the body's
    face, side A new nodes at the same coordinates (node set ``base``, the rigid base, to be
    fixed). Side A's normal points into the body (from A to B)."""
    fs, element = _face_set(mesh, face_set)
    _check_new_interface(mesh, interface_name)
    if base in mesh.node_sets:
        raise ValueError(f"mesh {describe(mesh.name)} already has a node set {describe(base)}")
    side_b = fs.face_nodes[:, _swap(fs.face_element)]  # reversed: the outward normal turns inward
    body, inverse = np.unique(side_b, return_inverse=True)
    new = mesh.n_nodes + np.arange(body.size, dtype=np.int64)
    side_a = new[inverse.reshape(side_b.shape)]
    block = InterfaceBlock(interface_name, element, np.hstack([side_a, side_b]))
    return _with(mesh, points=np.vstack([mesh.points, mesh.points[body]]),
                 node_sets={**mesh.node_sets, base: new}, interfaces=mesh.interfaces + (block,))


def merge(a: Mesh, b: Mesh) -> Mesh:
    """Both meshes in one (b's nodes numbered after a's, no nodes merged): blocks, node sets,
    face sets and interfaces renamed "<mesh name>.<name>", e.g. "punch.zmax"."""
    if a.name == b.name:
        raise ValueError(f"merge: both meshes are named {describe(a.name)}; their sets would collide")
    parts = []
    for m, node_off, block_off in ((a, 0, 0), (b, a.n_nodes, len(a.blocks))):
        p = f"{m.name}."
        parts.append(dict(
            blocks=[CellBlock(p + c.name, c.element, c.cells + node_off) for c in m.blocks],
            node_sets={p + k: v + node_off for k, v in m.node_sets.items()},
            face_sets={p + k: FaceSet(f.block_index + block_off, f.cell_indices, f.face_nodes + node_off,
                                      f.face_element) for k, f in m.face_sets.items()},
            interfaces=[InterfaceBlock(p + i.name, i.element, i.cells + node_off) for i in m.interfaces]))
    pa, pb = parts
    return Mesh(np.vstack([a.points, b.points]), tuple(pa["blocks"] + pb["blocks"]),
                {**pa["node_sets"], **pb["node_sets"]}, {**pa["face_sets"], **pb["face_sets"]},
                tuple(pa["interfaces"] + pb["interfaces"]), f"{a.name}+{b.name}")


def _match_points(pa: np.ndarray, pb: np.ndarray, tol: float) -> np.ndarray:
    """For each point of pa (n, 3) the index of the point of pb within ``tol`` [mm] (pb may hold
    more points); ValueError unless every point of pa has its own partner. Snapping to a tol-grid
    finds almost all pairs at once; a pair that straddles a grid line is found by the brute-force
    pass over the few left over (one pa point at a time: pb may be a whole foundation's face)."""
    lookup = {tuple(q): j for j, q in enumerate(np.round(pb / tol).astype(np.int64))}
    match = np.array([lookup.get(tuple(q), -1) for q in np.round(pa / tol).astype(np.int64)], dtype=np.int64)
    left_a = np.flatnonzero(match < 0)
    if left_a.size:
        left_b = np.setdiff1d(np.arange(len(pb)), match[match >= 0])
        if left_b.size:
            for i in left_a:
                d = np.linalg.norm(pb[left_b] - pa[i], axis=1)
                match[i] = left_b[d.argmin()] if d.min() <= tol else -1
    if np.any(match < 0) or np.unique(match).size != match.size:
        raise ValueError("the two face sets do not carry coincident nodes (non-matching meshes)")
    return match


def interface_between(mesh: Mesh, face_set_a: str, face_set_b: str, interface_name: str = "interface",
                      rtol: float = 1e-9) -> Mesh:
    """A new mesh with interface elements joining ``face_set_a`` (the lower body's contact faces,
    side A, whose outward normal points to B) and ``face_set_b`` (the upper body's), matched node
    by node by coordinates (within rtol × the contact zone's size).

    Side A may cover more than side B (a foundation's whole top face under a smaller punch):
    every face of B is paired with the face of A at the same place and A's other faces are
    left free. ValueError unless every face of B has such a partner (node-matching meshes of
    the common surface) and the two sets have distinct nodes. Elements follow A's face order.
    """
    fa, element = _face_set(mesh, face_set_a)
    fb, element_b = _face_set(mesh, face_set_b)
    _check_new_interface(mesh, interface_name)
    if element_b is not element or len(fa) < len(fb):
        raise ValueError(f"face sets {describe(face_set_a)} and {describe(face_set_b)} differ in face type or count")
    nodes_a, inverse = np.unique(fa.face_nodes, return_inverse=True)
    nodes_b = np.unique(fb.face_nodes)
    if nodes_a.size < nodes_b.size or np.intersect1d(nodes_a, nodes_b).size:
        raise ValueError("the two face sets must carry distinct nodes, side A at least as many as side B")
    pa, pb = mesh.points[nodes_a], mesh.points[nodes_b]
    size = np.linalg.norm(np.ptp(np.vstack([pa, pb]), axis=0))
    partner = _match_points(pb, pa, rtol * max(size, 1.0))  # B node -> its A node (index into nodes_a)
    b_of_a = np.full(nodes_a.size, -1, dtype=np.int64)  # A node -> the B node on it, −1: none
    b_of_a[partner] = nodes_b
    side_b = b_of_a[inverse.reshape(fa.face_nodes.shape)]  # A's faces in B's node numbers
    # a face is known by its set of nodes: pair B's faces with A's faces whose nodes all face B nodes
    key_of_b = {tuple(k) for k in np.sort(fb.face_nodes, axis=1)}
    keys_a = [tuple(k) for k in np.sort(side_b, axis=1)]
    paired = np.array([k in key_of_b for k in keys_a], dtype=bool) & np.all(side_b >= 0, axis=1)
    if {keys_a[i] for i in np.flatnonzero(paired)} != key_of_b or paired.sum() != len(fb):
        raise ValueError(f"the faces of {describe(face_set_a)} and {describe(face_set_b)} do not coincide one to one")
    block = InterfaceBlock(interface_name, element, np.hstack([fa.face_nodes[paired], side_b[paired]]))
    return _with(mesh, interfaces=mesh.interfaces + (block,))
