"""Structured box meshes, transition layers, interfaces (roughcontact.fe.mesh)."""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact.fe.element import HEX20, HEX20_NODES, HEX21, HEX28, QUAD8, QUAD9, QUAD16, Element
from roughcontact.fe.interface_element import INTERFACE18, INTERFACE32, face_frame
from roughcontact.fe.mesh import (
    LATERAL28, Mesh, box, dofs, graded, interface_between, local_face, merge, rigid_base_interface,
)
from roughcontact.fe.quadrature import tensor_rule

CASES = [(None, "quadratic"), ("bottom", "quadratic"), ("bottom", "cubic"),
         ("top", "quadratic"), ("top", "cubic")]
OUTWARD = {"xmin": (-1, 0, 0), "xmax": (1, 0, 0), "ymin": (0, -1, 0), "ymax": (0, 1, 0),
           "zmin": (0, 0, -1), "zmax": (0, 0, 1)}


def small_box(contact, family, n=(2, 3, 3)):
    """A box with unequal, graded edges so that no symmetry hides an indexing error."""
    z = graded(0.0, 4.0, n[2], 0.3 if contact == "bottom" else 3.0)  # small cells at the contact face
    return box(graded(-1.0, 2.0, n[0], 2.0), graded(0.0, 1.5, n[1], 0.5), z,
               contact_face=contact, family=family, name="b")


def hex20_count(nx, ny, nz):
    """Nodes of an nx × ny × nz hex20 grid: the (2nx+1)(2ny+1)(2nz+1) lattice of corners and
    midpoints minus the face centres and cell centres that hex20 has no node at."""
    lattice = (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1)
    face_centres = nx * ny * (nz + 1) + nx * (ny + 1) * nz + (nx + 1) * ny * nz
    return lattice - face_centres - nx * ny * nz


def expected_count(nx, ny, nz, contact, family):
    """hex20 grid plus the transition layer's extra contact-face nodes: HEX21 one face centre per
    cell; HEX28 two Lobatto nodes per contact-face edge instead of one mid-node, and four
    interior nodes per cell."""
    n = hex20_count(nx, ny, nz)
    if contact is None:
        return n
    if family == "quadratic":
        return n + nx * ny
    return n + (nx * (ny + 1) + (nx + 1) * ny) + 4 * nx * ny


# ---------------------------------------------------------------------------------------------
# graded
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("n, ratio", [(1, 1.0), (5, 1.0), (6, 0.2), (4, 7.0)])
def test_graded_sizes_geometric_ends_exact(n, ratio):
    e = graded(-3.0, 10.0, n, ratio)
    h = np.diff(e)
    assert e.size == n + 1 and e[0] == -3.0 and e[-1] == 10.0
    assert np.all(h > 0) and np.isclose(h[-1] / h[0], ratio, rtol=1e-12)
    if n > 2:
        assert np.allclose(h[1:] / h[:-1], ratio ** (1 / (n - 1)), rtol=1e-12)


@pytest.mark.parametrize("args", [(0, 1, 0), (0, 1, 2.5), (1, 0, 3), (0, 1, 3, -1.0), (0, 1, 1, 2.0),
                                  (0, np.inf, 2)])
def test_graded_rejects_bad_input(args):
    with pytest.raises(ValueError):
        graded(*args)


# ---------------------------------------------------------------------------------------------
# one box
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("contact, family", CASES)
@pytest.mark.parametrize("n", [(1, 1, 1), (2, 3, 3), (3, 1, 2)])
def test_node_count_matches_formula(contact, family, n):
    m = box(*(np.arange(k + 1.0) for k in n), contact_face=contact, family=family)
    assert m.n_nodes == expected_count(*n, contact, family)
    assert m.n_dofs == 3 * m.n_nodes
    assert sum(len(b.cells) for b in m.blocks) == np.prod(n)


def test_block_elements():
    assert [(b.name, b.element) for b in small_box(None, "cubic").blocks] == [("bulk", HEX20)]
    assert [b.element for b in small_box("bottom", "quadratic").blocks] == [HEX20, HEX21]
    assert [b.element for b in small_box("top", "cubic").blocks] == [HEX20, HEX28]
    one_layer = box([0, 1], [0, 1], [0, 1], contact_face="bottom", family="cubic")
    assert [b.element for b in one_layer.blocks] == [HEX28]


def trilinear(corners, xi):
    """The trilinear map of 8 corners (n, 8, 3) (VTK order) at reference points xi (p, 3)."""
    s = HEX20_NODES[:8]
    N = np.prod(1 + xi[:, None, :] * s[None, :, :], axis=2) / 8  # (p, 8)
    return np.einsum("pa,cak->cpk", N, corners)


@pytest.mark.parametrize("contact, family", CASES)
def test_nodes_are_the_trilinear_map_of_the_corners(contact, family):
    m = small_box(contact, family)
    for b in m.blocks:
        x = m.points[b.cells]
        assert np.allclose(x, trilinear(x[:, :8], b.element.nodes), rtol=0, atol=1e-12)


@pytest.mark.parametrize("contact, family", CASES)
def test_jacobian_positive_at_every_node(contact, family):
    m = small_box(contact, family)
    for b in m.blocks:
        G = b.element.shape_gradients(b.element.nodes)  # (p, a, 3)
        J = np.einsum("pad,cak->cpdk", G, m.points[b.cells])
        assert np.all(np.linalg.det(J) > 0)


@pytest.mark.parametrize("family", ["quadratic", "cubic"])
def test_top_transition_layer_is_turned_over(family):
    """For "top", local ζ = −1 is the top face and det J > 0 at the element centre."""
    m = small_box("top", family)
    t = m.blocks[-1]
    G = t.element.shape_gradients(np.zeros((1, 3)))
    J = np.einsum("pad,cak->cpdk", G, m.points[t.cells])
    assert np.all(np.linalg.det(J) > 0)
    assert np.all(m.points[t.cells[:, list(t.element.contact_face)], 2] == 4.0)


@pytest.mark.parametrize("contact, family", CASES)
def test_volume_no_duplicates_every_node_used(contact, family):
    m = small_box(contact, family)
    assert np.unique(m.points, axis=0).shape[0] == m.n_nodes
    used = np.unique(np.concatenate([b.cells.ravel() for b in m.blocks]))
    assert np.array_equal(used, np.arange(m.n_nodes))
    vol = 0.0
    for b in m.blocks:
        rule = tensor_rule("gauss", (4, 4, 4))
        J = np.einsum("pad,cak->cpdk", b.element.shape_gradients(rule.points), m.points[b.cells])
        vol += np.sum(np.linalg.det(J) * rule.weights)
    assert np.isclose(vol, 3.0 * 1.5 * 4.0, rtol=1e-12)


@pytest.mark.parametrize("contact, family", CASES)
def test_node_sets_are_exactly_the_nodes_on_each_face(contact, family):
    m = small_box(contact, family)
    lo, hi = m.points.min(axis=0), m.points.max(axis=0)
    for name, direction in OUTWARD.items():
        axis = int(np.flatnonzero(direction)[0])
        value = (hi if sum(direction) > 0 else lo)[axis]
        assert np.array_equal(m.node_sets[name], np.flatnonzero(m.points[:, axis] == value)), name
    if contact:
        assert np.array_equal(m.node_sets["contact"], m.node_sets["zmin" if contact == "bottom" else "zmax"])
    else:
        assert "contact" not in m.node_sets and "contact" not in m.face_sets


def face_area_and_normal(m, fs):
    rule = tensor_rule("gauss", (5, 5))
    R, dA = face_frame(fs.face_element, m.points[fs.face_nodes], rule.points, lay=(1.0, 1.0, 1.0))
    return np.sum(dA * rule.weights), R[..., 2, :]


@pytest.mark.parametrize("contact, family", CASES)
def test_face_sets_tile_the_box_faces_with_outward_normals(contact, family):
    m = small_box(contact, family)
    size = np.ptp(m.points, axis=0)
    for name, direction in OUTWARD.items():
        parts = [m.face_sets[k] for k in (name, name + ".transition") if k in m.face_sets]
        area = 0.0
        for fs in parts:
            a, n = face_area_and_normal(m, fs)
            area += a
            assert np.allclose(n, direction, atol=1e-12), name
            assert set(np.unique(fs.face_nodes)) <= set(m.node_sets[name])
            cells = m.blocks[fs.block_index].cells[fs.cell_indices]
            assert all(set(f) <= set(c) for f, c in zip(fs.face_nodes, cells))
        axis = int(np.flatnonzero(direction)[0])
        assert np.isclose(area, np.prod(np.delete(size, axis)), rtol=1e-12), name
    if contact:
        fs = m.face_sets["contact"]
        assert fs.face_element is {"quadratic": QUAD9, "cubic": QUAD16}[family]
        assert np.array_equal(np.unique(fs.face_nodes), m.node_sets["contact"])


@pytest.mark.parametrize("element", [HEX20, HEX21, HEX28])
@pytest.mark.parametrize("axis, side", [(a, s) for a in range(3) for s in (-1, 1)])
def test_local_face_element_interpolates_the_trace(element, axis, side):
    """On each face, the element's shape functions are the face element's (others vanish)."""
    face, idx = local_face(element, axis, side)
    expected = {(HEX28, 2, -1): QUAD16, (HEX21, 2, -1): QUAD9}.get((element, axis, side))
    expected = expected or (LATERAL28 if element is HEX28 and axis < 2 else QUAD8)
    assert face is expected
    uv = np.random.default_rng(1).uniform(-1, 1, (7, 2))
    Nf = face.shape(uv)
    x = Nf @ element.nodes[list(idx)]  # the face map is affine in the reference cube
    assert np.allclose(x[:, axis], side)
    N = element.shape(x)
    assert np.allclose(N[:, list(idx)], Nf, atol=1e-12)
    assert np.allclose(np.delete(N, list(idx), axis=1), 0.0, atol=1e-12)


def test_box_rejects_bad_input():
    for kwargs in ({"contact_face": "left"}, {"contact_face": "bottom", "family": "linear"}):
        with pytest.raises(ValueError):
            box([0, 1], [0, 1], [0, 1], **kwargs)
    with pytest.raises(ValueError):
        box([0, 1, 1], [0, 1], [0, 1])
    with pytest.raises(ValueError):
        box([0], [0, 1], [0, 1])


# ---------------------------------------------------------------------------------------------
# interfaces
# ---------------------------------------------------------------------------------------------
def interface_normals(m, block):
    """Side A's unit normals (n_cells, n_points, 3) and side A/B coordinates."""
    face = block.element.face
    xa, xb = m.points[block.side("A")], m.points[block.side("B")]
    R, _ = face_frame(face, xa, tensor_rule("gauss", (3, 3)).points)
    return R[..., 2, :], xa, xb


@pytest.mark.parametrize("contact, family, normal", [
    ("bottom", "quadratic", 1), ("bottom", "cubic", 1), ("top", "quadratic", -1), ("top", "cubic", -1)])
def test_rigid_base_interface_normals_point_into_the_body(contact, family, normal):
    body = small_box(contact, family)
    m = rigid_base_interface(body)
    (block,) = m.interfaces
    assert block.element is {"quadratic": INTERFACE18, "cubic": INTERFACE32}[family]
    n, xa, xb = interface_normals(m, block)
    assert np.allclose(n, (0, 0, normal), atol=1e-12)
    assert np.array_equal(xa, xb)
    assert np.array_equal(m.points[: body.n_nodes], body.points)
    base = m.node_sets["base"]
    assert np.array_equal(base, np.arange(body.n_nodes, m.n_nodes))
    assert np.array_equal(np.unique(block.side("A")), base)
    assert np.array_equal(np.unique(block.side("B")), body.node_sets["contact"])
    if contact == "bottom":  # side B is then exactly the elements' contact_face order
        t = body.blocks[-1]
        assert np.array_equal(block.side("B"), t.cells[:, list(t.element.contact_face)])
    with pytest.raises(ValueError):
        rigid_base_interface(m)  # the interface exists already
    with pytest.raises(ValueError):
        rigid_base_interface(body, face_set="zmax" if contact == "bottom" else "zmin")  # quad8: no interface


@pytest.mark.parametrize("family, n, contact_points", [("quadratic", 4, 81), ("cubic", 3, 100)])
def test_quarter_punch_contact_point_counts(family, n, contact_points):
    """docs/independent-studies.md, "Contact points": 81 = 9 × 9 nodes of 4 × 4 quadratic, 100 = 10 × 10 of 3 × 3 cubic."""
    punch = box(graded(0, 10, n), graded(0, 10, n), graded(0, 10, 3, 3.0), contact_face="bottom",
                family=family)
    s = rigid_base_interface(punch).summary()
    assert s["interface_elements"] == {"interface": n * n}
    assert s["interface_nodes"] == {"interface": contact_points}
    assert s["interface_points"] == {"interface": n * n * (3 if family == "quadratic" else 4) ** 2}
    assert s["nodes"] == punch.n_nodes + contact_points and s["dofs"] == 3 * s["nodes"]


def two_bodies(family, shift=0.0, upper_n=2):
    """A foundation (contact on top) and a punch above it sharing the contact zone x, y ∈ [0, 2]."""
    xy = np.array([0.0, 1.0, 2.0, 3.5, 6.0])
    lower = box(xy, xy, graded(-5, 0, 3, 0.3), contact_face="top", family=family, name="foundation")
    upper = box(np.linspace(0, 2, upper_n + 1) + shift, xy[:3], graded(0, 2, 2, 3.0),
                contact_face="bottom", family=family, name="punch")
    return merge(lower, upper), lower, upper


def test_merge_renumbers_and_prefixes():
    m, lower, upper = two_bodies("quadratic")
    assert m.n_nodes == lower.n_nodes + upper.n_nodes
    assert np.array_equal(m.points[lower.n_nodes:], upper.points)
    assert [b.name for b in m.blocks] == ["foundation.bulk", "foundation.transition",
                                          "punch.bulk", "punch.transition"]
    assert np.array_equal(m.node_sets["punch.zmax"], upper.node_sets["zmax"] + lower.n_nodes)
    fs = m.face_sets["punch.contact"]
    assert np.array_equal(m.points[fs.face_nodes], upper.points[upper.face_sets["contact"].face_nodes])
    assert np.array_equal(m.blocks[fs.block_index].cells[fs.cell_indices][:, 0],
                          upper.blocks[-1].cells[:, 0] + lower.n_nodes)
    with pytest.raises(ValueError):
        merge(lower, lower)


@pytest.mark.parametrize("family", ["quadratic", "cubic"])
def test_interface_between_pairs_coincide(family):
    m, lower, upper = two_bodies(family)
    # the foundation's contact zone is the part of its top face under the punch
    top = m.face_sets["foundation.contact"]
    centre = m.points[top.face_nodes].mean(axis=1)
    under = np.flatnonzero((centre[:, 0] < 2) & (centre[:, 1] < 2))
    zone = type(top)(top.block_index, top.cell_indices[under], top.face_nodes[under], top.face_element)
    m = Mesh(m.points, m.blocks, m.node_sets, {**m.face_sets, "zone": zone}, m.interfaces, m.name)
    out = interface_between(m, "zone", "punch.contact")
    (block,) = out.interfaces
    assert len(block.cells) == 4
    n, xa, xb = interface_normals(out, block)
    assert np.array_equal(xa, xb)
    assert np.allclose(n, (0, 0, 1), atol=1e-12)  # from the foundation (A) up into the punch (B)
    assert np.all(block.side("A") < lower.n_nodes) and np.all(block.side("B") >= lower.n_nodes)
    # side A may be larger: the whole top face gives the same elements (A's other faces stay free)
    whole = interface_between(m, "foundation.contact", "punch.contact").interfaces[0]
    assert np.array_equal(whole.cells, block.cells)


@pytest.mark.parametrize("shift, upper_n", [(0.25, 2), (0.0, 4)])
def test_interface_between_rejects_non_matching_meshes(shift, upper_n):
    m, _, _ = two_bodies("quadratic", shift=shift, upper_n=upper_n)
    top = m.face_sets["foundation.contact"]
    centre = m.points[top.face_nodes].mean(axis=1)
    under = np.flatnonzero((centre[:, 0] < 2) & (centre[:, 1] < 2))
    zone = type(top)(top.block_index, top.cell_indices[under], top.face_nodes[under], top.face_element)
    m = Mesh(m.points, m.blocks, m.node_sets, {**m.face_sets, "zone": zone}, m.interfaces, m.name)
    with pytest.raises(ValueError):
        interface_between(m, "zone", "punch.contact")


def centred_punch(family, x=(2.0, 3.5), y=(1.0, 2.0, 3.5)):
    """A foundation (contact on top, 4 × 4 faces) and a smaller punch on the middle of it whose
    x/y edges are some of the foundation's: the punch does not touch the foundation's edges."""
    xy = np.array([0.0, 1.0, 2.0, 3.5, 6.0])
    lower = box(xy, xy, graded(-5, 0, 2, 0.3), contact_face="top", family=family, name="foundation")
    upper = box(x, y, graded(0, 2, 2, 3.0), contact_face="bottom", family=family, name="punch")
    return merge(lower, upper), lower


@pytest.mark.parametrize("family", ["quadratic", "cubic"])
def test_interface_between_pairs_a_partial_interface(family):
    """Side A (the whole top face, 16 faces) is larger than B (2 faces in the middle): each B
    face gets the A face at its place, node by node; A's other 14 faces stay free."""
    m, lower = centred_punch(family)
    out = interface_between(m, "foundation.contact", "punch.contact")
    (block,) = out.interfaces
    assert len(block.cells) == 2 and block.element is {"quadratic": INTERFACE18, "cubic": INTERFACE32}[family]
    n, xa, xb = interface_normals(out, block)
    assert np.array_equal(xa, xb) and np.allclose(n, (0, 0, 1), atol=1e-12)
    assert np.all(block.side("A") < lower.n_nodes) and np.all(block.side("B") >= lower.n_nodes)
    assert set(np.unique(block.side("B"))) == set(np.unique(m.face_sets["punch.contact"].face_nodes))
    top = m.face_sets["foundation.contact"].face_nodes
    assert all(any(np.array_equal(a, f) for f in top) for a in block.side("A"))  # A's faces as they are
    x = m.points[block.side("A")]
    assert np.allclose(x[..., 0].min(), 2.0) and np.allclose(x[..., 0].max(), 3.5)
    assert np.allclose(x[..., 1].min(), 1.0) and np.allclose(x[..., 1].max(), 3.5)


@pytest.mark.parametrize("x, y, match", [
    ((2.0, 3.0), (1.0, 2.0), "coincident"),  # an edge of B at x = 3 between A's nodes: no partner
    ((2.0, 3.5, 6.5), (1.0, 2.0), "coincident"),  # B's last face sticks out beyond A
    ((0.0, 2.0), (1.0, 2.0), "coincide one to one"),  # B's 9 nodes sit on A's nodes, its face does not
])
def test_interface_between_rejects_a_b_face_without_partner(x, y, match):
    m, _ = centred_punch("quadratic", x, y)
    with pytest.raises(ValueError, match=match):
        interface_between(m, "foundation.contact", "punch.contact")


def test_interface_between_rejects_b_larger_than_a_and_other_misuse():
    m, _ = centred_punch("quadratic")
    with pytest.raises(ValueError, match="face type or count"):  # B's 2 faces cannot hold A's 16
        interface_between(m, "punch.contact", "foundation.contact")
    with pytest.raises(ValueError, match="distinct nodes"):  # one body against itself
        interface_between(m, "foundation.contact", "foundation.contact")
    with pytest.raises(ValueError, match="face type"):  # quad9 against quad16
        mixed = merge(box([0.0, 1.0], [0.0, 1.0], [-1.0, 0.0], contact_face="top", name="f"),
                      box([0.0, 1.0], [0.0, 1.0], [0.0, 1.0], contact_face="bottom", family="cubic", name="p"))
        interface_between(mixed, "f.contact", "p.contact")
    with pytest.raises(ValueError, match="no face set"):
        interface_between(m, "foundation.contact", "nothing")


def test_mesh_validates_cells():
    m = box([0, 1], [0, 1], [0, 1])
    with pytest.raises(ValueError):
        Mesh(m.points[:5], m.blocks)
    assert isinstance(LATERAL28, Element) and LATERAL28.n_nodes == 9


def test_dofs_are_node_major_three_per_node():
    np.testing.assert_array_equal(dofs([0, 5], (0, 2)), [0, 2, 15, 17])
    np.testing.assert_array_equal(dofs(np.array([4]), (1,)), [13])
