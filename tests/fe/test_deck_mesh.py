"""A deck on the engine's mesh (roughcontact.fe.deck_mesh): the contact faces' elements become
the paper's transition elements whatever face of theirs touches (all 24 orientations of a
hexahedron), the interface elements join conforming faces, and every non-conforming or
unsupported arrangement is a clear error naming the node and its coordinates."""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

from roughcontact.fe.deck import read_deck
from roughcontact.fe.deck_mesh import FACES, ROTATIONS, _permutation, deck_mesh
from roughcontact.fe.deck_syntax import DeckError
from roughcontact.fe.element import HEX20, HEX21, HEX28
from roughcontact.fe.interface_element import INTERFACE18, INTERFACE32


def _label(normal) -> int:
    """The face S1-S6 with this outward reference normal."""
    axis = int(np.flatnonzero(np.abs(normal) > 0.5)[0])
    return next(k for k, (a, s) in FACES.items() if a == axis and s == int(np.sign(normal[axis])))


def turned(deck, rotation: int):
    """The same deck with every element's nodes listed in the order of a turned reference cube
    (the geometry is unchanged), the face labels of the surfaces and pressures following."""
    perm = _permutation(rotation)
    R = ROTATIONS[rotation]
    relabel = {k: _label(R @ np.eye(3)[FACES[k][0]] * FACES[k][1]) for k in FACES}
    surfaces = {name: tuple((e, relabel[f]) for e, f in faces) for name, faces in deck.surfaces.items()}
    steps = tuple(dataclasses.replace(st, dload={(e, relabel[f]): p for (e, f), p in st.dload.items()})
                  for st in deck.steps)
    return dataclasses.replace(deck, connectivity=deck.connectivity[:, perm], surfaces=surfaces, steps=steps)


@pytest.mark.parametrize("family, transition, interface, points", [
    ("quadratic", HEX21, INTERFACE18, 25), ("cubic", HEX28, INTERFACE32, 49)])
def test_blocks_and_interface_of_a_block_on_a_base(block_deck, write_deck, family, transition, interface, points):
    d = read_deck(write_deck(block_deck(n=2)))
    dm = deck_mesh(d, family)
    kinds = {b.name: len(b.cells) for b in dm.mesh.blocks}
    assert kinds == {f"BASEMAT/{transition.name}": 4, f"BLOCKMAT/{transition.name}": 4}  # one layer each
    (block,) = dm.mesh.interfaces
    assert block.element is interface and len(block.cells) == 4 and block.name == "0:ROUGH"
    assert np.unique(block.side("B")).size == points  # 5 x 5 or 7 x 7 interface nodes
    corners = dm.engine_index(d.nsets["BASENODES"])
    assert np.isin(block.side("A")[:, :4], corners).all()  # side A: the master (base) corners
    np.testing.assert_allclose(dm.mesh.points[block.side("A")], dm.mesh.points[block.side("B")], atol=1e-13)
    # side A is the master (the base): its face normal points up, from master to slave
    from roughcontact.fe.interface_element import face_frame

    R, dA = face_frame(interface.face, dm.mesh.points[block.side("A")], interface.face.nodes)
    assert np.allclose(R[..., 2, :], (0.0, 0.0, 1.0)) and np.all(dA > 0)


@pytest.mark.parametrize("family", ["quadratic", "cubic"])
def test_every_orientation_of_the_contact_face_gives_the_same_mesh(block_deck, write_deck, family):
    """The 24 orderings of an element's nodes (turns of its reference cube) with the contact
    surfaces' labels following: the same engine geometry and the same interface, to rounding."""
    d = read_deck(write_deck(block_deck(n=1)))
    ref = deck_mesh(d, family)

    def key(dm):
        pts = np.round(dm.mesh.points, 10)
        (block,) = dm.mesh.interfaces
        return (sorted(map(tuple, pts)), sorted(map(tuple, pts[block.side("A")].reshape(-1, 3))),
                sorted(tuple(sorted(map(tuple, pts[c]))) for b in dm.mesh.blocks for c in b.cells))

    expected = key(ref)
    for r in range(len(ROTATIONS)):
        dm = deck_mesh(turned(d, r), family)
        assert key(dm) == expected, r
        assert [b.element for b in dm.mesh.blocks] == [b.element for b in ref.mesh.blocks]


def test_turned_decks_solve_alike(block_deck, write_deck, law_file):
    """Three turns of the elements' node order: the same displacements at every deck node."""
    from roughcontact.fe.deck_run import run_deck_file

    d = read_deck(write_deck(block_deck(n=1, steps=({"pressure": 2.0, "increments": 1},))))
    law = law_file()
    u = []
    for r in (0, 7, 19):
        res = run_deck_file(turned(d, r), law, "cubic")
        ids, uu = res.node_sets(res.increments[-1])["BLOCKNODES"]
        u.append(uu)
    np.testing.assert_allclose(u[1], u[0], rtol=0, atol=1e-12 * np.abs(u[0]).max())
    np.testing.assert_allclose(u[2], u[0], rtol=0, atol=1e-12 * np.abs(u[0]).max())


def test_node_sets_keep_their_planes(block_deck, write_deck):
    """New points on a symmetry plane's edges join its set (so its support holds them); the
    cubic element's replaced mid-edge nodes leave the engine and the sets, and are reported by
    interpolation along their edges."""
    d = read_deck(write_deck(block_deck(n=2)))
    dm = deck_mesh(d, "cubic")
    P = dm.mesh.points
    for name, axis in (("XSYM", 0), ("YSYM", 1)):
        on_plane = np.flatnonzero(np.isclose(P[:, axis], 0.0, atol=1e-12))
        assert np.array_equal(dm.mesh.node_sets[name], on_plane)
    assert len(dm.replaced) == 2 * 12  # the mid-edge nodes of both faces' 12 edges
    for nid, (nodes, w) in dm.replaced.items():
        assert len(nodes) == 4 and w.sum() == pytest.approx(1.0)
        x = d.coords[d.node_index([nid])[0]]
        np.testing.assert_allclose(w @ P[nodes], x, atol=1e-13)  # the cubic edge reproduces its midpoint


def test_non_conforming_faces_name_the_node(block_deck, write_deck):
    text = block_deck(n=2)
    # move one node of the block's bottom (the slave) off its master node by a tenth of an element
    d = read_deck(write_deck(text))
    nid = int(d.nsets["BLOCKNODES"][0])
    i = d.node_index([nid])[0]
    coords = d.coords.copy()
    coords[i, 0] += 0.5
    bad = dataclasses.replace(d, coords=coords)
    with pytest.raises(DeckError, match=rf"slave node {nid} of BLOCKBOTTOM at \(0\.5, 0, 0\) has no node of BASETOP"):
        deck_mesh(bad, "quadratic")
    # a base twice as fine under the block: every slave node lies on a master node, the faces do not match
    d2 = read_deck(write_deck(_finer_base(text), "fine.inp"))
    with pytest.raises(DeckError, match="does not lie on one face of BASETOP"):
        deck_mesh(d2, "quadratic")


def _finer_base(text: str) -> str:
    """The block-on-base deck with the base meshed 4 × 4 instead of 2 × 2 (same footprint)."""
    from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines

    lines = text.splitlines()
    d = read_deck("x.inp", text)
    base = box_part(np.linspace(0, 10, 5), np.linspace(0, 10, 5), [-6.0, 0.0], first_node=50001, first_element=5001)
    block_start = lines.index("*NODE, NSET=BLOCKNODES")
    block_end = next(i for i in range(block_start + 1, len(lines)) if lines[i].startswith("*"))
    out = ["*HEADING", "finer base", *node_lines(base, "BASENODES"), *lines[block_start:block_end],
           *element_lines(base, "BASE")]
    block_el = lines.index("*ELEMENT, TYPE=C3D20, ELSET=BLOCK")
    out += lines[block_el:block_el + 1 + 2 * len(d.elsets["BLOCK"])]
    out += id_lines("*NSET, NSET=BASEBOTTOM", base.face_nodes["ZMIN"])
    out += ["*SURFACE, NAME=BLOCKBOTTOM", *(f"{e}, S1" for e in d.elsets["BLOCK"]),
            "*SURFACE, NAME=BASETOP", *(f"{e}, S2" for e in base.face_elements["ZMAX"]),
            "*MATERIAL, NAME=M", "*ELASTIC", "2e5, 0.3", "*SOLID SECTION, ELSET=BASE, MATERIAL=M",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=M", "*SURFACE INTERACTION, NAME=ROUGH",
            "*CONTACT PAIR, INTERACTION=ROUGH", "BLOCKBOTTOM, BASETOP", "*BOUNDARY", "BASEBOTTOM, ENCASTRE",
            "*STEP", "*STATIC", "*END STEP"]
    return "\n".join(out) + "\n"


def test_a_cubic_face_beside_a_quadratic_neighbour(block_deck, write_deck):
    """The master surface covering only part of a larger base's top: with 28-node elements the
    neighbour's quadratic edge does not conform (an error saying what to do); with 21-node
    elements it does."""
    text = block_deck(n=2, base_scale=2.0)
    d = read_deck(write_deck(text))
    under = tuple((e, f) for e, f in d.surfaces["BASETOP"]
                  if np.all(d.coords[d.node_index(d.connectivity[np.searchsorted(d.element_ids, e), :8]), :2] <= 10.0))
    partial = dataclasses.replace(d, surfaces={**d.surfaces, "BASETOP": under})
    with pytest.raises(DeckError, match="shares the contact-face edge .* of a 28-node transition element"):
        deck_mesh(partial, "cubic")
    dm = deck_mesh(partial, "quadratic")
    assert len(dm.mesh.interfaces[0].cells) == 4


@pytest.mark.parametrize("mutate, message", [
    (lambda d: {**d.surfaces, "BASETOP": d.surfaces["BASETOP"] + ((d.surfaces["BASETOP"][0][0], 3),)},
     "has faces on two contact surfaces"),
    (lambda d: {**d.surfaces, "BLOCKBOTTOM": d.surfaces["BLOCKBOTTOM"] + ((d.surfaces["BASETOP"][0][0], 2),)},
     "share node"),
])
def test_surfaces_that_cannot_be_joined(block_deck, write_deck, mutate, message):
    d = read_deck(write_deck(block_deck(n=1)))
    with pytest.raises(DeckError, match=message) as err:
        deck_mesh(dataclasses.replace(d, surfaces=mutate(d)), "quadratic")
    assert re.match(r".+\.inp:\d+: ", str(err.value))


def test_inverted_elements_and_missing_pairs(block_deck, write_deck):
    d = read_deck(write_deck(block_deck(n=1)))
    conn = d.connectivity.copy()
    conn[0, [0, 1]] = conn[0, [1, 0]]
    with pytest.raises(DeckError, match=rf"element {d.element_ids[0]} is inverted or degenerate"):
        deck_mesh(dataclasses.replace(d, connectivity=conn), "quadratic")
    with pytest.raises(DeckError, match="no \\*CONTACT PAIR"):
        deck_mesh(dataclasses.replace(d, contact_pairs=()), "quadratic")
    with pytest.raises(ValueError, match="family"):
        deck_mesh(d, "linear")
