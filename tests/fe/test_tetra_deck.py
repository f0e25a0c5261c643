"""C3D10 decks on the engine's mesh (roughcontact.fe.deck_mesh): TET10 cells, 12-node interface
elements between the S1-S4 faces of a contact pair, and the refusals (a C3D20 surface paired
with a C3D10 one, a face S5 on a tetrahedron, non-conforming triangles).

The decks are built as :class:`~roughcontact.fe.deck.Deck` objects from the tetrahedral boxes of
fe.tetra (the text reader of deck.py does not take C3D10 yet)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from roughcontact.fe.deck import ContactPair, Deck, Material
from roughcontact.fe.deck_mesh import deck_mesh
from roughcontact.fe.deck_syntax import DeckError
from roughcontact.fe.deck_writer import box_part
from roughcontact.fe.element import TET10, TET10_FACES
from roughcontact.fe.interface_element import INTERFACE12
from roughcontact.fe.interface_points import interface_points
from roughcontact.fe.tetra import box_tets

X, Y = 6.0, 4.0


def tet_part(mesh, first_node, first_element):
    """(node ids, coords, element ids, connectivity, {face: ((eid, S), ...)}) of a box_tets mesh."""
    cells = mesh.blocks[0].cells
    nids = first_node + np.arange(mesh.n_nodes)
    eids = first_element + np.arange(len(cells))
    surfaces = {}
    for name, fs in mesh.face_sets.items():
        out = []
        for c, nodes in zip(fs.cell_indices, fs.face_nodes):
            s = next(s for s, f in TET10_FACES.items() if np.array_equal(cells[c][list(f)], nodes))
            out.append((int(eids[c]), s))
        surfaces[name] = tuple(out)
    return nids, mesh.points, eids, nids[cells], surfaces


def make_deck(parts, types, surfaces, width=10):
    """A Deck of parts (node ids, coords, element ids, connectivity) with the contact pair
    SLAVE (the upper body's bottom) on MASTER (the lower body's top)."""
    conn = np.zeros((sum(len(p[2]) for p in parts), width), dtype=np.int64)
    row = 0
    for p in parts:
        conn[row:row + len(p[2]), :p[3].shape[1]] = p[3]
        row += len(p[2])
    element_ids = np.concatenate([p[2] for p in parts])
    node_ids = np.concatenate([p[0] for p in parts])
    return Deck(path="tets.inp", heading="", node_ids=node_ids, coords=np.vstack([p[1] for p in parts]),
                element_ids=element_ids, element_types=tuple(types), connectivity=conn,
                nsets={"ALL": np.sort(node_ids)}, elsets={}, surfaces=surfaces,
                materials={"STEEL": Material("STEEL", 210e3, 0.3, "tets.inp:1")},
                element_material={int(e): "STEEL" for e in element_ids}, interactions={"ROUGH": "ROUGH"},
                contact_pairs=(ContactPair("ROUGH", "SLAVE", "MASTER", "tets.inp:9"),), steps=())


def two_tet_deck(n_upper=(3, 2)):
    xe = lambda n: np.linspace(0.0, X, n + 1)  # noqa: E731
    ye = lambda n: np.linspace(0.0, Y, n + 1)  # noqa: E731
    lower = tet_part(box_tets(xe(3), ye(2), [-2.0, -1.0, 0.0]), 1, 1)
    upper = tet_part(box_tets(xe(n_upper[0]), ye(n_upper[1]), [0.0, 1.5]), 10001, 10001)
    surfaces = {"MASTER": lower[4]["zmax"], "SLAVE": upper[4]["zmin"]}
    return make_deck([lower[:4], upper[:4]], ["C3D10"] * (len(lower[2]) + len(upper[2])), surfaces), lower, upper


def test_tet_deck_gives_tet10_cells_and_12_node_interfaces():
    deck, lower, upper = two_tet_deck()
    dm = deck_mesh(deck)
    mesh = dm.mesh
    assert [b.element for b in mesh.blocks] == [TET10]
    assert len(mesh.blocks[0].cells) == len(deck.element_ids) == 6 * (3 * 2 * 2 + 3 * 2)
    assert mesh.n_nodes == len(deck.node_ids)  # no node made or dropped
    (block,) = mesh.interfaces
    assert block.element is INTERFACE12 and len(block.cells) == 2 * 3 * 2
    for rule in ("gauss", "lobatto"):
        pts = interface_points(mesh, rule)
        assert pts.weights.sum() == pytest.approx(X * Y, rel=1e-13)
        assert np.abs(pts.frames[:, 2] - (0.0, 0.0, 1.0)).max() < 1e-14  # master (lower) to slave
        # side B is the upper body: lifting it by c opens every point by c, no slip
        u = np.zeros((mesh.n_nodes, 3))
        up = dm.engine_index(upper[0])
        u[up, 2] = 0.01
        jumps = pts.jumps(u.ravel())
        assert np.abs(jumps - (0.0, 0.0, 0.01)).max() < 1e-15


def test_mixed_hex_and_tet_pair_is_refused_naming_the_pair():
    lower = box_part([0.0, 3.0, 6.0], [0.0, 2.0, 4.0], [-2.0, 0.0])
    lower_faces = tuple((int(e), lower.face_label("ZMAX")) for e in lower.face_elements["ZMAX"])
    upper = tet_part(box_tets([0.0, 3.0, 6.0], [0.0, 2.0, 4.0], [0.0, 1.5]), 10001, 10001)
    parts = [(lower.node_ids, lower.coords, lower.element_ids, lower.connectivity), upper[:4]]
    types = ["C3D20"] * len(lower.element_ids) + ["C3D10"] * len(upper[2])
    deck = make_deck(parts, types, {"MASTER": lower_faces, "SLAVE": upper[4]["zmin"]}, width=20)
    with pytest.raises(DeckError, match=r"^tets.inp:9: contact pair SLAVE/MASTER: C3D10 faces on the slave, "
                                        r"C3D20 on the master; mixed") as err:
        deck_mesh(deck)
    assert "\n" not in str(err.value)


def test_face_s5_of_a_tet_is_refused():
    deck, _, _ = two_tet_deck()
    e, _ = deck.surfaces["SLAVE"][0]
    bad = dataclasses.replace(deck, surfaces={**deck.surfaces, "SLAVE": ((e, 5),) + deck.surfaces["SLAVE"][1:]})
    with pytest.raises(DeckError, match=f"surface SLAVE: element {e} is a C3D10, whose faces are S1-S4, got S5"):
        deck_mesh(bad)


def test_non_conforming_triangles_are_refused():
    deck, _, _ = two_tet_deck(n_upper=(2, 2))
    with pytest.raises(DeckError, match="non-conforming contact faces"):
        deck_mesh(deck)


def test_inverted_tet_is_refused():
    deck, _, _ = two_tet_deck()
    conn = deck.connectivity.copy()
    conn[0, [1, 2]] = conn[0, [2, 1]]
    conn[0, [4, 6]] = conn[0, [6, 4]]  # corners 2 and 3 swapped with their edges: a mirrored tet
    conn[0, [8, 9]] = conn[0, [9, 8]]
    with pytest.raises(DeckError, match=r"element 1 is inverted or degenerate \(det J <= 0; C3D10 node order\?\)"):
        deck_mesh(dataclasses.replace(deck, connectivity=conn))
