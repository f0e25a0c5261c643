"""The quarter model of example 9.2: punch on foundation (roughcontact.examples.punch_geometry), as
the engine meshes its deck (roughcontact.examples.punch.punch_mesh: the deck reader)."""

from __future__ import annotations

from dataclasses import asdict

import numpy as np
import pytest

from roughcontact.fe.element import HEX20, HEX21, HEX28
from roughcontact.fe.interface_element import INTERFACE18, INTERFACE32, face_frame
from roughcontact.fe.interface_points import interface_points
from roughcontact.examples.punch import PunchSpec, punch_deck, summary
from roughcontact.examples.punch import punch_mesh as _punch_mesh
from roughcontact.examples.punch_geometry import BASE, SYMMETRY_X, SYMMETRY_Y, PunchGeometry, figure_annotations
from roughcontact.fe.deck import read_deck
from roughcontact.fe.quadrature import tensor_rule

FAMILIES = [("quadratic", 81), ("cubic", 100)]


@pytest.fixture(scope="module", params=FAMILIES, ids=[f for f, _ in FAMILIES])
def case(request):
    """(family, paper's contact points, geometry, mesh) with the default geometry."""
    family, points = request.param
    g = PunchGeometry(family=family)
    return family, points, g, punch_mesh(g)


def punch_mesh(g):
    return _punch_mesh(PunchSpec(geometry=g))


def body_nodes(mesh, body):
    """Sorted node indices of the cells of ``body`` ("foundation" | "punch"): the engine's
    points of the deck's node set <BODY>NODES and those made on its contact face."""
    return np.unique(np.concatenate([mesh.node_sets[f"{body.upper()}NODES"]]
                                    + [i.side("A" if body == "foundation" else "B").ravel() for i in mesh.interfaces]))


def patch_faces(g):
    """The patch's top faces (QUAD8, outward) of the punch deck: the elements of LOADPATCH."""
    from roughcontact.fe.element import QUAD8
    from roughcontact.fe.mesh import local_face

    deck = read_deck("punch.inp", punch_deck(PunchSpec(geometry=g)))
    conn = deck.connectivity[np.searchsorted(deck.element_ids, deck.elsets["LOADPATCH"])]
    nodes = deck.coords[deck.node_index(conn)]
    _, idx = local_face(HEX20, 2, 1)
    return QUAD8, nodes[:, list(idx)]


# ---------------------------------------------------------------------------------------------
# the interface: the paper's contact points
# ---------------------------------------------------------------------------------------------
def test_contact_points_are_the_papers(case):
    family, points, g, m = case
    ip = interface_points(m, "lobatto")
    assert ip.n_points == points  # Figs 18 (81) and 19 (100)
    s = summary(m)
    assert s["contact_points"] == points and s["interface_elements"] == g.n_punch ** 2
    assert s["dofs"] == 3 * s["nodes"] == m.n_dofs
    assert m.interfaces[0].name == "0:ROUGH"
    assert m.interfaces[0].element is {"quadratic": INTERFACE18, "cubic": INTERFACE32}[family]
    assert np.isclose(ip.weights.sum(), 100.0, rtol=1e-12)  # the quarter punch's face, 10 × 10 mm
    assert np.allclose(ip.frames[:, 2], (0.0, 0.0, 1.0), atol=1e-12)  # from the foundation up
    assert np.allclose(ip.x[:, 2], 0.0, atol=1e-12)
    assert np.allclose(ip.x[:, :2].min(axis=0), 0.0, atol=1e-12) and np.allclose(ip.x[:, :2].max(axis=0), 10.0)


def test_interface_sides_and_node_matching_grid(case):
    _, _, g, m = case
    block = m.interfaces[0]
    foundation, punch = body_nodes(m, "foundation"), body_nodes(m, "punch")
    assert np.intersect1d(foundation, punch).size == 0
    assert np.all(np.isin(block.side("A"), foundation)) and np.all(np.isin(block.side("B"), punch))
    # the deck's nodes coincide bitwise; the nodes the reader makes on each face (from each body's
    # own element geometry) to rounding; the interface uses side A's geometry only
    np.testing.assert_allclose(m.points[block.side("A")], m.points[block.side("B")], rtol=0, atol=1e-13)
    # the foundation's top grid under the punch is the punch's bottom grid, node for node
    w = g.punch_half_width
    top = foundation[(m.points[foundation, 2] == 0.0) & np.all(m.points[foundation, :2] <= w, axis=1)]
    bottom = punch[m.points[punch, 2] == 0.0]
    as_set = lambda idx: {tuple(p) for p in np.round(m.points[idx], 9)}  # noqa: E731  (made nodes: to rounding)
    assert as_set(top) == as_set(bottom) and len(top) == len(bottom) == np.unique(block.side("B")).size
    assert np.array_equal(g.foundation_xy_edges()[:g.n_punch + 1], g.punch_edges())


# ---------------------------------------------------------------------------------------------
# the two bodies
# ---------------------------------------------------------------------------------------------
def test_blocks_jacobians_volumes_and_no_duplicates(case):
    family, _, g, m = case
    transition = {"quadratic": HEX21, "cubic": HEX28}[family]
    assert [(b.name, b.element) for b in m.blocks] == [("STEEL/hex20", HEX20), ("STEEL/" + transition.name, transition)]
    rule = tensor_rule("gauss", (3, 3, 3))
    volume = {"foundation": 0.0, "punch": 0.0}
    punch = set(body_nodes(m, "punch").tolist())
    for b in m.blocks:
        for xi in (b.element.nodes, rule.points):  # at every node and Gauss point
            J = np.einsum("pad,cak->cpdk", b.element.shape_gradients(xi), m.points[b.cells])
            assert np.all(np.linalg.det(J) > 0), b.name
        in_punch = np.array([c[0] in punch for c in b.cells])
        v = np.sum(np.linalg.det(J) * rule.weights, axis=1)
        volume["punch"] += v[in_punch].sum()
        volume["foundation"] += v[~in_punch].sum()
    assert volume["foundation"] == pytest.approx(50.0 ** 3, rel=1e-12)
    assert volume["punch"] == pytest.approx(10.0 ** 3, rel=1e-12)
    for body in ("foundation", "punch"):
        nodes = body_nodes(m, body)
        assert np.unique(m.points[nodes], axis=0).shape[0] == nodes.size, body


def test_node_sets_for_supports(case):
    _, _, g, m = case
    for name, axis in ((SYMMETRY_X, 0), (SYMMETRY_Y, 1)):
        both = np.concatenate([body_nodes(m, "foundation"), body_nodes(m, "punch")])
        on_plane = both[m.points[both, axis] == 0.0]
        assert np.array_equal(m.node_sets[name], np.sort(on_plane)), name
    assert np.allclose(m.points[m.node_sets[BASE], 2], -g.foundation_depth)
    assert m.node_sets[BASE].size == (2 * (g.n_punch + g.n_outer) + 1) ** 2 - (g.n_punch + g.n_outer) ** 2


def test_load_patch_faces(case):
    _, _, g, m = case
    face, nodes = patch_faces(g)
    rule = tensor_rule("gauss", (5, 5))
    R, dA = face_frame(face, nodes, rule.points)
    assert float(np.sum(dA * rule.weights)) == pytest.approx((g.load_patch / 2.0) ** 2, rel=1e-12)
    assert np.allclose(R[..., 2, :], (0.0, 0.0, 1.0), atol=1e-12)
    assert np.all(nodes[..., 2] == g.punch_height) and nodes[..., :2].max() == pytest.approx(g.load_patch / 2.0)
    # default reading: the quarter's corner element (the 2 × 2 central elements of the whole punch)
    assert len(nodes) == 1 and g.load_patch == pytest.approx(2.0 * g.punch_half_width / g.n_punch)


# ---------------------------------------------------------------------------------------------
# grading and the load patch's edge
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("family", ["quadratic", "cubic"])
def test_foundation_grows_outward_and_downward(family):
    g = PunchGeometry(family=family)
    xy, z = g.foundation_xy_edges(), g.foundation_z_edges()
    outer, depth = np.diff(xy[g.n_punch:]), -np.diff(z[::-1])  # away from the punch
    assert np.all(np.diff(outer) > 0) and np.all(np.diff(depth) > 0)
    # None ratios: the first element as large as the punch's element next to it
    assert outer[0] == pytest.approx(np.diff(g.punch_edges())[-1], rel=1e-9)
    assert depth[0] == pytest.approx(g.punch_height / g.n_punch_z, rel=1e-9)
    assert xy[-1] == 50.0 and z[0] == -50.0 and z[-1] == 0.0
    h = PunchGeometry(family=family, outer_ratio=3.0, depth_ratio=5.0)
    outer, depth = np.diff(h.foundation_xy_edges()[h.n_punch:]), -np.diff(h.foundation_z_edges()[::-1])
    assert outer[-1] / outer[0] == pytest.approx(3.0) and depth[-1] / depth[0] == pytest.approx(5.0)
    many = PunchGeometry(family=family, n_outer=20, n_depth=30)  # more than fit at the punch's size
    assert np.allclose(np.diff(many.foundation_xy_edges()[many.n_punch:]), 2.0)


@pytest.mark.parametrize("family, load_patch", [("quadratic", 3.0), ("cubic", 10.0), ("quadratic", 20.0),
                                                ("cubic", 20.0 / 3.0)])
def test_load_patch_edge_is_inserted_keeping_the_contact_points(family, load_patch):
    g = PunchGeometry(family=family, load_patch=load_patch)
    edges = g.punch_edges()
    assert edges.size == g.n_punch + 1 and np.any(edges == load_patch / 2.0)
    m = punch_mesh(g)
    assert summary(m)["contact_points"] == dict(FAMILIES)[family]
    face, nodes = patch_faces(g)
    rule = tensor_rule("gauss", (5, 5))
    assert float(np.sum(face_frame(face, nodes, rule.points)[1] * rule.weights)) == pytest.approx(
        (load_patch / 2.0) ** 2, rel=1e-12)
    assert interface_points(m, "lobatto").weights.sum() == pytest.approx(100.0, rel=1e-12)


@pytest.mark.parametrize("kwargs", [
    dict(family="linear"), dict(n_punch=0), dict(n_punch=2.5), dict(n_punch_z=True), dict(n_outer=0),
    dict(n_depth=-1), dict(outer_ratio=0.0), dict(depth_ratio=np.inf), dict(punch_half_width=-1.0),
    dict(foundation_half_width=10.0), dict(foundation_depth=0.0), dict(load_patch=0.0), dict(load_patch=21.0),
    dict(load_patch="big"), dict(n_punch=1, load_patch=5.0), dict(n_outer=1, outer_ratio=2.0),
    dict(n_depth=1, depth_ratio=0.5),
])
def test_bad_geometry_is_refused(kwargs):
    with pytest.raises(ValueError):
        PunchGeometry(**kwargs)


def test_geometry_states_its_numbers_and_round_trips():
    g = PunchGeometry(family="cubic")
    assert (g.n_punch, g.n_punch_z, g.load_patch) == (3, 3, pytest.approx(20.0 / 3.0))
    assert PunchGeometry(**asdict(g)) == g  # a workflow's dict of fields rebuilds the same mesh


# ---------------------------------------------------------------------------------------------
# Figs 14 and 15
# ---------------------------------------------------------------------------------------------
def test_figures_14_15_draw(case, tmp_path):
    """The quarter model with supports, load arrows, the interface shaded, and the exploded
    detail of the contact zone with the interface nodes (81 / 100)."""
    from roughcontact.paper import drawings, plots

    family, points, g, m = case
    fig = drawings.mesh_figure(m, title=family, **figure_annotations(g))
    main, detail = fig.axes
    gids = lambda ax: [a.get_gid() for a in list(ax.collections) + list(ax.lines)]  # noqa: E731
    assert {f"plate:{SYMMETRY_X}", f"plate:{SYMMETRY_Y}", f"plate:{BASE}", "interface-face",
            "transition-layer", "detail-box", "load:4"} <= set(gids(main))
    assert not [k for k in gids(detail) if k and k.startswith(("plate:", "support:"))]  # supports: left only
    (nodes,) = [a for a in detail.collections if a.get_gid() == "interface-nodes"]
    assert len(nodes.get_offsets()) == points
    labels = fig.legends[0].get_texts()
    assert len({t.get_text() for t in labels}) == len(labels)  # one entry per label over both panels
    path = plots.save(fig, tmp_path / f"fig_{family}.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 50_000


@pytest.mark.parametrize("length, n, first", [(40.0, 6, 5.0 / 3.0), (100.0, 8, 2.5), (55.0, 3, 5.0), (30.0, 2, 10.0)])
def test_first_size_ratio_fills_the_length(length, n, first):
    """The grading ratio: n sizes first·q^i fill ``length`` (the geometric sum, to rounding) and
    q is the positive root np.roots finds (to its LAPACK accuracy); found in plain floats, so the
    shipped decks do not depend on the BLAS build (tests/examples/test_shipped.py)."""
    from roughcontact.examples.punch_geometry import _first_size_ratio

    q = _first_size_ratio(length, n, first) ** (1.0 / (n - 1))
    assert sum(first * q**i for i in range(n)) == pytest.approx(length, rel=1e-13)
    roots = np.roots(np.r_[np.full(n - 1, first), first - length])
    assert q == pytest.approx(max(r.real for r in roots if abs(r.imag) < 1e-9 and r.real > 0), rel=1e-12)
