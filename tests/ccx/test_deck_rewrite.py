"""The deck of `roughcontact ccx run` (roughcontact.ccx.deck_rewrite): constants that read back
exactly, the face data of the engine's elements, the pair's faces joined as the engine joins them,
the interaction replaced and the prints added. No CalculiX needed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from roughcontact.ccx.deck_rewrite import (HEADER, NDEPVAR, USER_TYPES, decode, encode, pair_elements, rewrite,
                                           section_values)
from roughcontact.fe.deck import read_deck
from roughcontact.fe.deck_mesh import deck_mesh
from roughcontact.fe.deck_syntax import read_blocks
from roughcontact.fe.interface_element import face_frame
from roughcontact.fe.laws import read_law_file

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"


@pytest.fixture(scope="module")
def block():
    deck = read_deck(EXAMPLES / "block.inp")
    laws = read_law_file(EXAMPLES / "block.yaml")
    return deck, laws, pair_elements(deck_mesh(deck, "quadratic"), laws)


def test_constants_read_back_to_the_same_doubles_within_twenty_characters():
    rng = np.random.default_rng(7)
    values = np.concatenate([rng.normal(size=200) * 10.0 ** rng.integers(-300, 300, size=200),
                             [0.0, -0.0, 1.0, -1.0, 1 / 3, np.pi, 5e-324, 1.7976931348623157e308, -2.2250738585072014e-308]])
    texts = encode(values)
    assert max(map(len, texts)) <= 20  # CalculiX reads f20.0 (usersections.f)
    np.testing.assert_array_equal(decode(texts), values)
    # and as gfortran would add them: hi + lo in double, in order
    assert all(float(texts[2 * i]) + float(texts[2 * i + 1]) == v for i, v in enumerate(values))
    with pytest.raises(ValueError, match="not finite"):
        encode([np.nan])


@pytest.mark.parametrize("face_name", sorted(USER_TYPES))
def test_face_data_are_the_engine_elements_at_a_rule_exact_for_its_area(block, face_name):
    _, _, pairs = block
    v = np.array(section_values(pairs[0].constants, face_name))
    nf, nq, npar, ntab = (int(v[HEADER.index(k)]) for k in ("n_face", "n_points", "n_par", "n_tab"))
    assert (nf, nq) == {"quad9": (8, 9), "tri6": (6, 6)}[face_name]
    points = v[len(HEADER) + npar + 4 * ntab:].reshape(nq, 1 + 3 * nf)
    w, N, dxi, deta = points[:, 0], points[:, 1:1 + nf], points[:, 1 + nf:1 + 2 * nf], points[:, 1 + 2 * nf:]
    assert w.sum() == pytest.approx({"quad9": 4.0, "tri6": 0.5}[face_name], rel=1e-14)  # reference areas
    np.testing.assert_allclose(N.sum(axis=1), 1.0, rtol=0, atol=1e-14)  # partition of unity
    np.testing.assert_allclose(dxi.sum(axis=1), 0.0, atol=1e-13)
    np.testing.assert_allclose(deta.sum(axis=1), 0.0, atol=1e-13)
    # the rule integrates the face's area on the reference element of the face itself
    face = USER_TYPES[face_name].face
    x = np.c_[face.nodes, np.zeros(nf)][None]
    _, dA = face_frame(face, x, face.nodes[:1] * 0 + face.nodes.mean(axis=0))
    assert dA[0, 0] == pytest.approx(1.0)


def test_the_law_constants_are_the_laws(block):
    _, laws, pairs = block
    c = pairs[0].constants
    v = np.array(section_values(c, pairs[0].face))
    head = dict(zip(HEADER, v[:len(HEADER)]))
    assert head["law_per_deck"] == 1000.0  # µm moments in an mm deck
    assert (head["lay_x"], head["lay_y"], head["lay_z"]) == tuple(laws.interactions["ROUGH"].lay_direction)
    assert (head["a_x"], head["a_y"]) == (0.7, 1.0)  # block.yaml's kt_over_kn
    tab = v[len(HEADER) + int(head["n_par"]):][:4 * int(head["n_tab"])].reshape(-1, 4)
    np.testing.assert_array_equal(tab, c.tab)


def test_the_faces_are_joined_node_to_node_with_the_normal_towards_the_slave(block):
    deck, _, pairs = block
    p = pairs[0]
    assert p.user_type == "URCQ8" and p.nodes.shape == (4, 16)
    xyz = deck.coords[deck.node_index(p.nodes.ravel())].reshape(4, 16, 3)
    np.testing.assert_allclose(xyz[:, :8], xyz[:, 8:], atol=1e-12)  # conforming: B facing A
    master = {n for eid, face in deck.surfaces["BASETOP"] for n in deck.connectivity[deck.element_ids == eid][0]}
    assert set(p.nodes[:, :8].ravel()) <= master
    from roughcontact.fe.element import QUAD8

    R, _ = face_frame(QUAD8, xyz[:, :8], np.zeros((1, 2)))
    np.testing.assert_allclose(R[:, 0, 2], np.tile([0.0, 0.0, 1.0], (4, 1)), atol=1e-12)  # base below, block above: n = +z
    assert p.ids.min() > deck.element_ids.max()


def test_the_rewritten_deck(block):
    deck, _, pairs = block
    text = rewrite(read_blocks(EXAMPLES / "block.inp"), pairs, list(deck.nsets), ("provenance",))
    names = [line.split(",")[0].upper() for line in text.splitlines() if line.startswith("*") and not line.startswith("**")]
    assert "*CONTACT PAIR" not in names and "*SURFACE INTERACTION" not in names
    assert "*SURFACE BEHAVIOR" not in names  # the *INCLUDEd table went with its interaction
    assert names.index("*USER ELEMENT") < names.index("*STEP")
    assert names.count("*EL PRINT") == names.count("*END STEP") == 2
    assert f"*DEPVAR\n{NDEPVAR}\n" in text
    assert all(line.count(",") < 16 or line.endswith(",") for line in text.splitlines() if not line.startswith("*"))
    assert text.startswith("** provenance\n")
    # the element rows: id, then 16 nodes over two lines
    rows = text.split("*ELEMENT, TYPE=URCQ8, ELSET=RC_PAIR1\n")[1].split("*MATERIAL")[0].split(",\n")
    first = [int(v) for v in ",".join(rows[:2]).replace("\n", ",").split(",")[:17]]
    assert first == [int(pairs[0].ids[0]), *pairs[0].nodes[0].tolist()]
