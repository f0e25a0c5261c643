"""A read deck as the engine's mesh: transition elements on the contact faces, interface
elements between conforming faces (docs/own-model.md).

Every C3D20 of the deck is a HEX20 (the node orders agree: VTK's quadratic hexahedron). An
element with a face on a surface of a ``*CONTACT PAIR`` becomes a transition element with that
face as its contact face (section 9 of Buczkowski & Kleiber 2009, as the beam and the punch):

* ``family="quadratic"``: HEX21 (Fig. 16), a new node at the face centre; 18-node interface
  elements (Fig. 17). HEX21 conforms with a HEX20 beside it.
* ``family="cubic"``: HEX28 (Fig. 11): the face's mid-edge nodes are replaced by two nodes at
  ±1/√5 of each edge, plus four inside the face; 32-node interface elements (Fig. 12). A HEX28
  does not conform with a HEX20 that shares its contact-face edge, so such a neighbour is an
  error (put the whole face of the body on the contact surface).

The element is first turned by a rotation of its reference cube so that the contact face is
its local ζ = −1 face (the convention of :mod:`.element`); new nodes sit where the HEX20's
geometry puts them; a node on an edge shared by two elements is one node.

Sets: a new node joins a deck node set (and a support) when every original node of the edge or
face it was made on is in it (a node set of a whole plane keeps its plane); a replaced mid-edge
node leaves the engine, and its displacement is reported by the cubic edge through its four
nodes (:attr:`DeckMesh.replaced`).

Tetrahedra: every C3D10 is a TET10 (the node orders agree, :mod:`.element`); its faces S1-S4
are TRI6 (6-node triangles) and need no transition element: the 12-node interface elements
join them directly (:data:`~.interface_element.INTERFACE12`). A contact pair must have the same
kind of faces on both sides: C3D10 on one side and C3D20 on the other is refused, naming the
pair.

Contact pairs: the master surface's faces are side A of the interface elements (normal from
master to slave), the slave's side B; every slave node must sit on a master node within
``rtol`` × the shortest edge of the contact faces, and every slave face on a master face
(conforming meshes); master faces beyond the slave surface stay free. Anything else is an error
naming the node and its coordinates.
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass

import numpy as np

from ..limits import describe
from .deck import Deck, DeckError
from .element import HEX20, HEX21, HEX28, TET10, TET10_FACES, TRI6, Element
from .interface_element import INTERFACE12, INTERFACE18, INTERFACE32
from .mesh import CellBlock, InterfaceBlock, Mesh, local_face
from .quadrature import simplex_rule, tensor_rule

__all__ = ["DeckMesh", "deck_mesh", "FACES", "FAMILIES", "face_of"]

FAMILIES = {"quadratic": HEX21, "cubic": HEX28}
_INTERFACE = {HEX21.name: INTERFACE18, HEX28.name: INTERFACE32, TET10.name: INTERFACE12}
#: deck element types read as the 10-node tetrahedron (the rest are hexahedra, deck.ELEMENT_TYPES)
TET_TYPES = {"C3D10": 10}
#: CalculiX/Abaqus faces S1 … S6 of a hexahedron as (reference axis, side): S1 ζ = −1 (nodes 1-4),
#: S2 ζ = +1 (5-8), S3 η = −1 (1, 5, 6, 2), S4 ξ = +1 (2, 6, 7, 3), S5 η = +1 (3, 7, 8, 4), S6 ξ = −1
FACES = {1: (2, -1), 2: (2, 1), 3: (1, -1), 4: (0, 1), 5: (1, 1), 6: (0, -1)}
DEFAULT_RTOL = 1e-6


def _rotations() -> list[np.ndarray]:
    """The 24 proper rotations of the reference cube; the identity and the half turn about x
    (which turns a top face down, as mesh.box does) first."""
    out = [np.eye(3), np.diag([1.0, -1.0, -1.0])]
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1.0, -1.0), repeat=3):
            R = np.zeros((3, 3))
            R[range(3), perm] = signs
            if np.linalg.det(R) > 0 and not any(np.array_equal(R, Q) for Q in out):
                out.append(R)
    return out


ROTATIONS = _rotations()


def _normal(face: int) -> np.ndarray:
    axis, side = FACES[face]
    n = np.zeros(3)
    n[axis] = side
    return n


def _rotation_for(face: int) -> int:
    """Index of the first rotation taking face ``face``'s outward normal to −ζ."""
    n = _normal(face)
    return next(k for k, R in enumerate(ROTATIONS) if np.allclose(R @ n, (0.0, 0.0, -1.0)))


@functools.lru_cache(maxsize=None)
def _permutation(rotation: int) -> np.ndarray:
    """perm[i] = the HEX20 node at R^T × (node i): the rotated element's node i is the original's perm[i]."""
    target = HEX20.nodes @ ROTATIONS[rotation]  # rows R^T p_i
    return np.array([int(np.flatnonzero(np.all(np.isclose(HEX20.nodes, t), axis=1))[0]) for t in target])


@functools.lru_cache(maxsize=None)
def _template(transition: Element) -> tuple:
    """For each node of a transition element: ("old", HEX20 index) where HEX20 has a node,
    ("edge", corner, corner, nearer corner, mid-edge node) for a new node on a contact-face edge,
    ("face",) for a new node inside the contact face (HEX20 local indices)."""
    out = []
    for p in transition.nodes:
        hit = np.flatnonzero(np.all(np.abs(HEX20.nodes - p) < 1e-12, axis=1))
        if hit.size:
            out.append(("old", int(hit[0])))
            continue
        edge = np.flatnonzero(np.isclose(np.abs(p[:2]), 1.0))
        if edge.size != 1:
            out.append(("face",))
            continue
        fixed, free = int(edge[0]), 1 - int(edge[0])
        corners = [i for i in range(4) if HEX20.nodes[i, fixed] == p[fixed]]
        near = next(i for i in corners if np.sign(HEX20.nodes[i, free]) == np.sign(p[free]))
        mid = int(np.flatnonzero(np.all(np.isclose(HEX20.nodes, np.where(np.arange(3) == free, 0.0, p)), axis=1))[0])
        out.append(("edge", corners[0], corners[1], near, mid))
    return tuple(out)


def face_of(element: Element, rotation: int, face: int):
    """The face element and local node indices (outward order) of deck face S``face`` of an
    element turned by ``ROTATIONS[rotation]`` (a TET10 is never turned: S1-S4 of TET10_FACES)."""
    if element is TET10:
        if face not in TET10_FACES:
            raise ValueError(f"a C3D10 has faces S1-S4, got S{describe(face)}")
        return TRI6, TET10_FACES[face]
    n = ROTATIONS[rotation] @ _normal(face)
    axis = int(np.flatnonzero(np.abs(n) > 0.5)[0])
    return local_face(element, axis, int(np.sign(n[axis])))


@dataclass(frozen=True, eq=False)
class DeckMesh:
    """The engine's mesh of a deck and the maps back to it.

    deck_nodes   deck node ids of the engine's first ``len(deck_nodes)`` points (the rest are new).
    replaced     {deck node id: (engine indices, weights)}: mid-edge nodes replaced by HEX28's.
    parents      (new point, deck node ids of the edge/face it was made on) for every new point.
    cells        {deck element id: (block index, cell index, rotation index)}.
    materials    material name of every block.
    pairs        the deck's contact pairs, in the order of ``mesh.interfaces``.
    """

    deck: Deck
    mesh: Mesh
    deck_nodes: np.ndarray
    replaced: dict
    parents: tuple
    cells: dict
    materials: tuple[str, ...]
    pairs: tuple
    family: str = "quadratic"

    def engine_index(self, ids) -> np.ndarray:
        """Engine point index of deck node ids (−1 where the node is not in the engine's mesh)."""
        ids = np.asarray(ids, dtype=np.int64)
        order = np.argsort(self.deck_nodes)
        pos = np.minimum(np.searchsorted(self.deck_nodes, ids, sorter=order), max(len(order) - 1, 0))
        idx = order[pos]
        return np.where(self.deck_nodes[idx] == ids, idx, -1)


def _is_tet(deck: Deck) -> np.ndarray:
    """(M,) True for the deck's C3D10 elements."""
    return np.array([t.upper() in TET_TYPES for t in deck.element_types], dtype=bool)


def _connectivity(deck: Deck, rows: np.ndarray, n: int) -> np.ndarray:
    """(len(rows), n) node ids of the elements ``rows`` (the first n of each row)."""
    return np.asarray(deck.connectivity)[rows][:, :n].astype(np.int64)


def _check_jacobians(deck: Deck):
    """DeckError naming the first element with det J ≤ 0 (inverted or degenerate)."""
    tet = _is_tet(deck)
    checks = ((HEX20, np.flatnonzero(~tet), np.vstack([tensor_rule("gauss", (2, 2, 2)).points, HEX20.nodes[:8] * 0.999]), "C3D20"),
              (TET10, np.flatnonzero(tet), np.vstack([simplex_rule("tet4").points, 0.001 + 0.996 * TET10.nodes[:4]]), "C3D10"))
    for element, rows, xi, name in checks:
        if not rows.size:
            continue
        dN = element.shape_gradients(xi)
        X = deck.coords[deck.node_index(_connectivity(deck, rows, element.n_nodes))]  # (m, n, 3)
        det = np.linalg.det(np.einsum("pak,cai->cpik", dN, X))
        bad = np.flatnonzero(~np.all(det > 0.0, axis=1))
        if bad.size:
            eid = int(deck.element_ids[rows[bad[0]]])
            raise DeckError(deck.where.get(("element", eid), deck.path),
                            f"element {eid} is inverted or degenerate (det J <= 0; {name} node order?)")


def _contact_faces(deck: Deck, tets: set) -> dict[int, tuple[int, int]]:
    """{element id: (face, pair index)} of every hexahedron's face on a contact pair's surface;
    a C3D10's face number is checked (S1-S4) and the element left as it is."""
    out = {}
    for k, pair in enumerate(deck.contact_pairs):
        for name in (pair.slave, pair.master):
            for eid, face in deck.surfaces[name]:
                if eid in tets:
                    if face not in TET10_FACES:
                        raise DeckError(pair.where, f"surface {name}: element {eid} is a C3D10, whose faces are "
                                                    f"S1-S4, got S{face}")
                    continue
                if eid in out and out[eid] != (face, k):
                    raise DeckError(pair.where, f"element {eid} has faces on two contact surfaces (S{out[eid][0]} "
                                                f"and S{face}): a transition element has one contact face; refine "
                                                "the mesh there")
                out[eid] = (face, k)
    return out


def deck_mesh(deck: Deck, family: str = "quadratic", rtol: float = DEFAULT_RTOL) -> DeckMesh:
    """The engine's mesh of ``deck`` (module docstring)."""
    if family not in FAMILIES:
        raise ValueError(f"family must be one of {', '.join(FAMILIES)}, got {describe(family)}")
    if not deck.contact_pairs:
        raise DeckError(deck.path, "the deck has no *CONTACT PAIR: nothing for the interface law to act on")
    _check_jacobians(deck)
    transition = FAMILIES[family]
    shape_at = HEX20.shape(transition.nodes)  # the HEX20 geometry at the transition element's nodes,
    shape_at[np.abs(shape_at) < 1e-12] = 0.0  # exactly from the edge's or face's own nodes (a plane stays one)
    is_tet = _is_tet(deck)
    on_contact = _contact_faces(deck, set(deck.element_ids[is_tet].tolist()))
    new_pos, new_key, parents = [], {}, []
    replaced_stencil = {}
    conn, kinds, rotations = [], [], []
    for row, eid in enumerate(deck.element_ids.tolist()):
        kind = TET10 if is_tet[row] else HEX20
        nodes = _connectivity(deck, np.array([row]), kind.n_nodes)[0]
        if eid not in on_contact:
            conn.append(nodes.tolist())
            kinds.append(kind)
            rotations.append(0)
            continue
        r = _rotation_for(on_contact[eid][0])
        perm = _permutation(r)
        ids, x = nodes[perm], deck.coords[deck.node_index(nodes)][perm]
        local = []
        for a, t in enumerate(_template(transition)):
            if t[0] == "old":
                local.append(int(ids[t[1]]))
                continue
            # a new node: on an edge of the contact face (shared with the neighbour) or inside it
            if t[0] == "edge":
                a_id, b_id = int(ids[t[1]]), int(ids[t[2]])
                key = ("edge", min(a_id, b_id), max(a_id, b_id), int(ids[t[3]]))
                parent = (a_id, b_id, int(ids[t[4]]))
            else:
                key = ("face", eid, a)
                parent = tuple(int(i) for i in ids[[0, 1, 2, 3, 8, 9, 10, 11]])
            if key not in new_key:
                new_key[key] = len(new_pos)
                new_pos.append(shape_at[a] @ x)
                parents.append(parent)
            local.append(-1 - new_key[key])  # new nodes: negative until numbered
        if transition is HEX28:  # the face's mid-edge nodes (HEX20 8-11) are replaced
            for m in range(8, 12):
                replaced_stencil.setdefault(int(ids[m]), (row, local, HEX20.nodes[m]))
        conn.append(local)
        kinds.append(transition)
        rotations.append(r)

    # replaced nodes must not be used by any element any more (HEX28 beside a HEX20)
    used = {i for c in conn for i in c if i >= 0}
    for nid in replaced_stencil:
        if nid in used:
            user = next(int(deck.element_ids[k]) for k, c in enumerate(conn) if nid in c)
            raise DeckError(deck.where.get(("element", user), deck.path),
                            f"element {user} shares the contact-face edge (node {nid}) of a 28-node transition "
                            "element without being one (cubic edges do not conform with quadratic ones): put its "
                            "face on the contact surface too, or use --elements quadratic")
    deck_nodes = np.array(sorted(used), dtype=np.int64)
    index = {int(n): i for i, n in enumerate(deck_nodes)}
    n_deck = len(deck_nodes)
    points = np.vstack([deck.coords[deck.node_index(deck_nodes)]] + ([np.array(new_pos)] if new_pos else []))

    def engine(i):
        return index[i] if i >= 0 else n_deck - 1 - i

    blocks, cells, materials, members = [], {}, [], {}
    for row, eid in enumerate(deck.element_ids.tolist()):
        key = (kinds[row].name, deck.element_material[eid])
        if key not in members:
            members[key] = len(members)
            blocks.append([])
            materials.append(key[1])
        b = members[key]
        cells[eid] = (b, len(blocks[b]), rotations[row])
        blocks[b].append([engine(i) for i in conn[row]])
    kind_of = {e.name: e for e in (HEX20, HEX21, HEX28, TET10)}
    cell_blocks = [CellBlock(f"{mat}/{kind}", kind_of[kind], np.array(blocks[b], dtype=np.int64))
                   for (kind, mat), b in members.items()]
    replaced = {}
    for nid, (row, local, p) in replaced_stencil.items():
        w = transition.shape(p[None, :])[0]
        nz = np.flatnonzero(np.abs(w) > 1e-12)
        replaced[nid] = (np.array([engine(local[a]) for a in nz]), w[nz])
    node_sets = {name: _engine_set(ids, index, parents, n_deck) for name, ids in deck.nsets.items()}
    mesh = Mesh(points, tuple(cell_blocks), node_sets, {}, (), "deck")
    interfaces = tuple(_interface(deck, mesh, cells, deck_nodes, k, pair, rtol)
                       for k, pair in enumerate(deck.contact_pairs))
    mesh = Mesh(points, mesh.blocks, node_sets, {}, interfaces, "deck")
    return DeckMesh(deck, mesh, deck_nodes, replaced,
                    tuple((n_deck + j, p) for j, p in enumerate(parents)), cells, tuple(materials),
                    deck.contact_pairs, family)


def _engine_set(ids, index, parents, n_deck) -> np.ndarray:
    """Engine points of a deck node set, with the new points made on its edges and faces."""
    members = set(int(i) for i in ids)
    out = [index[i] for i in members if i in index]
    out += [n_deck + j for j, p in enumerate(parents) if members.issuperset(p)]
    return np.array(sorted(out), dtype=np.int64)


def _faces(deck: Deck, mesh: Mesh, cells: dict, surface: str) -> tuple[np.ndarray, list[int]]:
    """(n, n_face) engine nodes of a surface's contact faces (outward order) and their elements."""
    rows, eids = [], []
    for eid, face in deck.surfaces[surface]:
        b, c, _ = cells[eid]
        block = mesh.blocks[b]
        _, idx = face_of(TET10, 0, face) if block.element is TET10 else local_face(block.element, 2, -1)
        rows.append(block.cells[c][list(idx)])
        eids.append(eid)
    return np.array(rows, dtype=np.int64), eids


def _interface(deck: Deck, mesh: Mesh, cells: dict, deck_nodes, k: int, pair, rtol: float) -> InterfaceBlock:
    """The interface elements of contact pair k: master faces (side A) joined to the slave faces
    lying on them (side B), node by node within rtol × the shortest contact-face edge."""
    from scipy.spatial import cKDTree

    slave, slave_el = _faces(deck, mesh, cells, pair.slave)
    master, master_el = _faces(deck, mesh, cells, pair.master)
    tet = [mesh.blocks[cells[e[0]][0]].element is TET10 for e in (slave_el, master_el)]
    if tet[0] != tet[1]:
        kind = {True: "C3D10", False: "C3D20"}
        raise DeckError(pair.where, f"contact pair {pair.slave}/{pair.master}: {kind[tet[0]]} faces on the slave, "
                                    f"{kind[tet[1]]} on the master; mixed tetrahedral-hexahedral contact is not "
                                    "supported (mesh both sides with the same element type)")
    if slave.shape[1] != master.shape[1]:
        raise DeckError(pair.where, "slave and master faces differ in type")
    P = mesh.points
    n_corners = 3 if tet[0] else 4
    corners = np.concatenate([slave[:, :n_corners], master[:, :n_corners]])
    edges = np.linalg.norm(P[corners] - P[np.roll(corners, 1, axis=1)], axis=-1)
    tol = rtol * float(edges.min())
    s_nodes, m_nodes = np.unique(slave), np.unique(master)
    shared = np.intersect1d(s_nodes, m_nodes)
    if shared.size:
        raise DeckError(pair.where, f"the surfaces {pair.slave} and {pair.master} share node "
                                    f"{_deck_id(shared[0], deck_nodes)}: give each body its own nodes")
    dist, near = cKDTree(P[m_nodes]).query(P[s_nodes], distance_upper_bound=tol)
    for i in np.flatnonzero(~np.isfinite(dist)):
        x = P[s_nodes[i]]
        raise DeckError(pair.where, f"non-conforming contact faces: slave node {_deck_id(s_nodes[i], deck_nodes)} of "
                                    f"{pair.slave} at ({x[0]:.9g}, {x[1]:.9g}, {x[2]:.9g}) has no node of {pair.master} "
                                    f"within {tol:.3g} (a slave node must sit on every master node)")
    master_of = dict(zip(s_nodes.tolist(), m_nodes[near].tolist()))
    slave_of = {m: s for s, m in master_of.items()}
    faces_by_nodes = {tuple(sorted(f)): j for j, f in enumerate(master.tolist())}
    rows = []
    for f, eid in zip(slave.tolist(), slave_el):
        j = faces_by_nodes.get(tuple(sorted(master_of[n] for n in f)))
        if j is None:
            raise DeckError(pair.where, f"non-conforming contact faces: the face of slave element {eid} does not lie "
                                        f"on one face of {pair.master} (the two meshes differ there)")
        rows.append(list(master[j]) + [slave_of[n] for n in master[j]])
    element = _INTERFACE[mesh.blocks[cells[slave_el[0]][0]].element.name]
    return InterfaceBlock(f"{k}:{pair.interaction}", element, np.array(rows, dtype=np.int64))


def _deck_id(point: int, deck_nodes) -> str:
    """A point's deck node id, or what it is when the reader made it."""
    return str(int(deck_nodes[point])) if point < len(deck_nodes) else f"(made on a contact face, point {point})"
