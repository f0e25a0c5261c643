"""Element and mesh drawings (roughcontact.paper.drawings, workflow/scripts/drawing.py): what is
drawn is the engine's own element data — labels at element.nodes, the contact face through
element.contact_face, interface pairs i ↔ n + i — so a wrong ordering shows in the picture."""

from __future__ import annotations

import dataclasses
import importlib.util
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from roughcontact.fe.element import HEX20, HEX21, HEX28, QUAD16, Element
from roughcontact.fe.interface_element import INTERFACE18, INTERFACE32
from roughcontact.fe.mesh import box, graded, rigid_base_interface
from roughcontact.paper import drawings, plots

ROOT = Path(__file__).resolve().parents[2]
HEXES = [HEX20, HEX21, HEX28]
INTERFACES = [INTERFACE18, INTERFACE32]


def node_labels(fig) -> dict[int, object]:
    """local index → the Text artist labelling that node (each gid at most once)."""
    out = {}
    for text in fig.axes[0].texts:
        gid = text.get_gid() or ""
        if gid.startswith("node-label:"):
            i = int(gid.split(":")[1])
            assert i not in out, f"node {i} labelled twice"
            out[i] = text
    return out


def artists(fig, gid: str) -> list:
    ax = fig.axes[0]
    return [a for a in list(ax.collections) + list(ax.lines) if a.get_gid() == gid]


def script():
    """workflow/scripts/drawing.py as a module (its snakemake block does not run)."""
    spec = importlib.util.spec_from_file_location("drawing_script", ROOT / "workflow" / "scripts" / "drawing.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# ---------------------------------------------------------------------------------------------
# element figures
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("element", HEXES, ids=lambda e: e.name)
def test_labels_sit_at_the_element_nodes_each_number_once(element):
    fig = drawings.element_figure(element, title="t")
    labels = node_labels(fig)
    assert sorted(labels) == list(range(element.n_nodes))
    assert sorted(int(t.get_text()) for t in labels.values()) == list(range(1, element.n_nodes + 1))
    kinds = drawings.node_kinds(element.nodes)
    for i, text in labels.items():
        assert text.get_text() == str(i + 1)
        node = element.nodes[i]
        offset = np.asarray(text.get_position_3d()) - node
        # outward along the ray from the element centre through the node, by the kind's distance
        assert np.allclose(np.cross(offset, node), 0.0, atol=1e-12)
        assert offset @ node > 0
        assert np.isclose(np.linalg.norm(offset), drawings._LABEL_DISTANCE[kinds[i]])


def test_numbering_offsets_every_label():
    labels = node_labels(drawings.element_figure(HEX21, title="t", numbering=0))
    assert {i: int(t.get_text()) for i, t in labels.items()} == {i: i for i in range(HEX21.n_nodes)}


def test_a_swapped_node_pair_moves_its_labels():
    """Swap nodes 9 and 10 of HEX28 ((c, −1, −1) and (1, −c, −1), on two edges of the contact
    face): the labels follow, and the contact face interpolated through the now stale
    ``contact_face`` order leaves its square."""
    nodes = HEX28.nodes.copy()
    nodes[[9, 10]] = nodes[[10, 9]]
    bad = Element("bad", nodes, HEX28.space, QUAD16, HEX28.contact_face)
    good = node_labels(drawings.element_figure(HEX28, title="t"))
    swapped = node_labels(drawings.element_figure(bad, title="t"))
    assert np.allclose(good[9].get_position_3d(), swapped[10].get_position_3d())
    assert np.allclose(good[10].get_position_3d(), swapped[9].get_position_3d())
    assert np.abs(np.abs(drawings.contact_outline(bad)[:, :2]).max(axis=1) - 1.0).max() > 0.05


@pytest.mark.parametrize("element", HEXES, ids=lambda e: e.name)
def test_node_kinds(element):
    kinds = drawings.node_kinds(element.nodes)
    face = {"hex20": 0, "hex21": 1, "hex28": 4}[element.name]
    assert (kinds.count("corner"), kinds.count("face"), kinds.count("interior")) == (8, face, 0)
    assert kinds.count("edge") == element.n_nodes - 8 - face


@pytest.mark.parametrize("element", HEXES, ids=lambda e: e.name)
def test_edges_are_the_cube_edges_through_every_edge_node(element):
    curves = drawings.edge_curves(element)
    assert len(curves) == 12
    pts = np.vstack(curves)
    for curve in curves:  # straight reference edges: two coordinates fixed at ±1
        assert (np.ptp(curve, axis=0) < 1e-12).sum() == 2
        assert np.allclose(np.abs(curve[0][np.ptp(curve, axis=0) < 1e-12]), 1.0)
    for i, kind in enumerate(drawings.node_kinds(element.nodes)):
        on_curve = np.min(np.linalg.norm(pts - element.nodes[i], axis=1)) < 1e-12
        assert on_curve == (kind in ("corner", "edge")), i


def test_edges_follow_the_interpolation_through_moved_nodes():
    """Edges are x(ξ) = Σ N_a x_a: move one Lobatto node of HEX28 and the edge bends through it."""
    coords = HEX28.nodes.copy()
    coords[9] += (0.0, -0.3, 0.0)  # node 9 = (c, -1, -1) pushed outwards
    curves = drawings.edge_curves(HEX28, coords)
    pts = np.vstack(curves)
    assert np.min(np.linalg.norm(pts - coords[9], axis=1)) < 1e-12
    assert pts[:, 1].min() < -1.2


@pytest.mark.parametrize("element", [HEX21, HEX28], ids=lambda e: e.name)
def test_contact_face_polygon_has_exactly_the_contact_face_nodes(element):
    outline = drawings.contact_outline(element)
    assert np.allclose(outline[:, 2], -1.0)
    on_outline = {i for i in range(element.n_nodes)
                  if np.min(np.linalg.norm(outline - element.nodes[i], axis=1)) < 1e-12}
    face = set(element.contact_face)
    boundary = {i for i in face if np.isclose(np.abs(element.nodes[i, :2]).max(), 1.0)}
    assert on_outline == boundary
    assert face == set(np.flatnonzero(np.isclose(element.nodes[:, 2], -1.0)))
    x, y = outline[:, 0], outline[:, 1]
    assert np.isclose(0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y), 4.0)  # the square, once round
    fig = drawings.element_figure(element, title="t")
    assert len(artists(fig, "contact-face")) == 1


def test_a_permuted_contact_face_scrambles_the_polygon():
    perm = list(HEX21.contact_face)
    perm[4], perm[5] = perm[5], perm[4]
    outline = drawings.contact_outline(dataclasses.replace(HEX21, contact_face=tuple(perm)))
    assert np.abs(np.abs(outline[:, :2]).max(axis=1) - 1.0).max() > 0.05


def test_hex28_marks_c_and_hex21_does_not():
    gids = lambda fig: {t.get_gid() for t in fig.axes[0].texts}
    assert {"c-label", "c-note"} <= gids(drawings.element_figure(HEX28, title="t"))
    assert "c-label" not in gids(drawings.element_figure(HEX21, title="t"))


# ---------------------------------------------------------------------------------------------
# interface figures
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("element", INTERFACES, ids=lambda e: e.name)
def test_interface_labels_pairs_and_lobatto_points(element):
    n = element.face.n_nodes
    fig = drawings.interface_figure(element, title="t")
    labels = node_labels(fig)
    assert sorted(labels) == list(range(2 * n))
    assert sorted(int(t.get_text()) for t in labels.values()) == list(range(1, 2 * n + 1))
    pairs = [a for a in fig.axes[0].lines if (a.get_gid() or "").startswith("pair:")]
    assert len(pairs) == n
    for line in pairs:
        i = int(line.get_gid().split(":")[1])
        xs, ys, zs = line.get_data_3d()
        assert np.allclose(xs, element.face.nodes[i, 0]) and np.allclose(ys, element.face.nodes[i, 1])
        assert zs[0] == 0.0 and zs[1] > 0.0  # side A below, side B above
    for i in range(2 * n):  # label i over node i of its side
        p = np.asarray(labels[i].get_position_3d())
        d = p[:2] - element.nodes[i]
        assert np.allclose(np.cross(np.append(d, 0.0), np.append(element.nodes[i], 0.0)), 0.0, atol=1e-12)
    (points,) = artists(fig, "integration-points")
    xyz = np.column_stack(points._offsets3d)
    assert len(xyz) == n and np.allclose(xyz[:, 2], 0.0)
    dist = np.linalg.norm(xyz[:, None, :2] - element.face.nodes[None], axis=2)
    assert np.all(dist.min(axis=1) < 1e-12) and np.all(dist.min(axis=0) < 1e-12)  # Lobatto points = nodes


def test_interface_gauss_points_lie_between_the_nodes():
    fig = drawings.interface_figure(INTERFACE32, title="t", rule="gauss")
    (points,) = artists(fig, "integration-points")
    xyz = np.column_stack(points._offsets3d)
    assert len(xyz) == 16
    assert np.linalg.norm(xyz[:, None, :2] - QUAD16.nodes[None], axis=2).min() > 0.05


def test_node_table_of_an_interface_pairs_the_sides():
    rows = drawings.node_table(INTERFACE18)
    assert [r["label"] for r in rows] == list(range(1, 19))
    assert [r["side"] for r in rows] == ["A"] * 9 + ["B"] * 9
    assert all(rows[r["facing"] - 1]["facing"] == r["label"] for r in rows)
    assert rows[8]["kind"] == "face" and (rows[8]["xi"], rows[8]["eta"]) == (0.0, 0.0)


def test_node_table_of_hex28():
    rows = drawings.node_table(HEX28)
    assert [r["index"] for r in rows] == list(range(28)) and rows[0]["label"] == 1
    assert np.allclose([[r["xi"], r["eta"], r["zeta"]] for r in rows], HEX28.nodes)


# ---------------------------------------------------------------------------------------------
# meshes
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def small_mesh():
    return rigid_base_interface(box([0.0, 1.0, 2.0], [0.0, 1.0, 2.0], [0.0, 1.0, 2.0], contact_face="bottom",
                                    family="cubic", name="b"))


def test_boundary_edges_of_a_box(small_mesh):
    """2 × 2 × 2 cells: 48 element edges on the surface; 30 on the three faces seen from the
    default view; 18 of those on the box's own edges (the feature edges)."""
    assert len(drawings.boundary_edges(small_mesh)) == 48
    view = drawings._view_vector(20.0, -60.0)
    assert len(drawings.boundary_edges(small_mesh, view)) == 30
    assert len(drawings.boundary_edges(small_mesh, view, max_edges=10)) == 18
    for path in drawings.boundary_edges(small_mesh):  # straight polylines through the mid nodes
        x = small_mesh.points[path]
        assert len(path) in (3, 4) and np.allclose(np.cross(x - x[0], x[-1] - x[0]), 0.0)


def test_mesh_figure_draws_interface_supports_and_loads(small_mesh, tmp_path):
    fig = drawings.mesh_figure(small_mesh, title="t", supports=[("xmin", "symmetry"), ("ymin", "symmetry"),
                                                                 ("base", "rigid base")],
                               loads=[((1.0, 1.0, 2.0), (0.0, 0.0, -1.0), "F")])
    (interface,) = artists(fig, "interface-face")
    assert len(interface.get_paths()) == len(small_mesh.interfaces[0].cells) == 4
    # seen from (+x, −y, +z): ymin faces the viewer (triangles); xmin and the base (z = 0) are
    # turned away (plates behind the body, no triangles floating in front of it)
    assert artists(fig, "support:ymin") and artists(fig, "plate:xmin") and artists(fig, "plate:base")
    assert not artists(fig, "support:xmin") and not artists(fig, "support:base") and artists(fig, "load:0")
    (edges,) = artists(fig, "edges")
    fig.canvas.draw()  # projects the 3D segments
    assert len(edges.get_segments()) == 30
    path = plots.save(fig, tmp_path / "mesh.png")
    assert path.stat().st_size > 10_000


def test_mesh_figure_of_an_elongated_body_keeps_true_proportions():
    mesh = box(graded(0.0, 250.0, 5, 2.0), [0.0, 10.0], graded(0.0, 120.0, 3), name="beam")
    fig = drawings.mesh_figure(mesh, title="t", highlight_interface=False)
    aspect = fig.axes[0].get_box_aspect()
    assert aspect[0] / aspect[2] == pytest.approx((250 + 20) / (120 + 20))
    assert not artists(fig, "interface-face")


# ---------------------------------------------------------------------------------------------
# the workflow script and rules
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name, n", [("hex28", 28), ("interface32", 32), ("hex21", 21), ("interface18", 18)])
def test_script_writes_png_and_node_table(tmp_path, name, n):
    out = {"png": tmp_path / f"{name}.png", "csv": tmp_path / f"{name}.csv"}
    script().run(name, "caption", out, tmp_path / "log")
    assert out["png"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out["png"].stat().st_size > 20_000
    lines = out["csv"].read_text().splitlines()
    assert lines[0].startswith("label,index,") and len(lines) == n + 1
    assert lines[1].startswith("1,0,")


def test_script_refuses_an_unknown_element(tmp_path):
    with pytest.raises(ValueError, match="unknown element"):
        script().draw("hex99", "t")


def test_rules_plan_the_four_drawings(tmp_path):
    """The rules file on its own (a Snakefile that only includes it) plans fig11..fig17."""
    (tmp_path / "src").symlink_to(ROOT / "src")
    (tmp_path / "Snakefile").write_text(f'include: "{ROOT / "workflow" / "rules" / "drawings.smk"}"\n')
    r = subprocess.run([sys.executable, "-m", "snakemake", "-n", "fig11", "fig12", "fig16", "fig17"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr + r.stdout
    for name in ("fig11", "fig12", "fig16", "fig17"):
        assert f"paper_figures/{name}.png" in r.stdout + r.stderr
