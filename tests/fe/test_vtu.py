"""VTU export (roughcontact.fe.vtu): round trips through meshio, cell mapping, atomic writes."""

from __future__ import annotations

import os

import meshio
import numpy as np
import pytest

from roughcontact.fe.element import HEX20_NODES
from roughcontact.fe.mesh import box, graded, rigid_base_interface
from roughcontact.fe.vtu import hex20_view, write_interfaces, write_mesh, write_points

A = np.array([[0.1, -0.2, 0.3], [0.05, 0.4, -0.1], [-0.3, 0.2, 0.25]])


def body(contact=None, family="quadratic", n=(3, 2, 2)):
    return box(graded(0, 6, n[0], 2.0), graded(0, 2, n[1]), graded(0, 3, n[2], 0.5),
               contact_face=contact, family=family, name="b")


def linear_field(x):
    return x @ A.T + (1.0, -2.0, 0.5)


def cells_of(m, kind):
    return [c.data for c in m.cells if c.type == kind]


def trilinear(corners, xi):
    s = HEX20_NODES[:8]  # VTK corner order
    N = np.prod(1 + xi[:, None, :] * s[None, :, :], axis=2) / 8
    return np.einsum("pa,cak->cpk", N, corners)


def test_hex20_round_trip(tmp_path):
    mesh = body()
    u = linear_field(mesh.points)
    tag = np.arange(mesh.n_nodes, dtype=np.int32)
    out = write_mesh(tmp_path / "m.vtu", mesh, point_data={"u": u, "tag": tag},
                     cell_data={"layer": [np.arange(len(mesh.blocks[0].cells), dtype=float)]})
    back = meshio.read(out)
    assert np.array_equal(back.points, mesh.points)
    (cells,) = cells_of(back, "hexahedron20")
    assert np.array_equal(cells, mesh.blocks[0].cells)
    assert np.array_equal(back.point_data["u"], u)
    assert np.array_equal(back.point_data["tag"], tag)
    assert np.array_equal(back.cell_data["layer"][0], np.arange(len(cells)))


@pytest.mark.parametrize("family", ["quadratic", "cubic"])
@pytest.mark.parametrize("contact", ["bottom", "top"])
def test_transition_layers_as_conforming_hex20(tmp_path, family, contact):
    """HEX21 → its nodes 0–19; HEX28 → hex20 with one extra point per contact-face edge, at
    the edge midpoint, shared by the cells on both sides, carrying the interpolated data."""
    mesh = body(contact, family)
    u = linear_field(mesh.points)
    data = {"u": u, "status": np.ones(mesh.n_nodes, np.int64)}
    back = meshio.read(write_mesh(tmp_path / "t.vtu", mesh, point_data=data))
    nx, ny = 3, 2
    extra = 0 if family == "quadratic" else nx * (ny + 1) + (nx + 1) * ny
    assert len(back.points) == mesh.n_nodes + extra
    assert np.array_equal(back.points[: mesh.n_nodes], mesh.points)
    (cells,) = cells_of(back, "hexahedron20")  # meshio reads consecutive blocks of one type as one
    bulk, transition = cells[: len(mesh.blocks[0].cells)], cells[len(mesh.blocks[0].cells):]
    assert np.array_equal(bulk, mesh.blocks[0].cells)
    if family == "quadratic":
        assert np.array_equal(transition, mesh.blocks[1].cells[:, :20])
    # every exported cell is a geometrically correct VTK quadratic hexahedron (det J > 0 given)
    for cells in (bulk, transition):
        x = back.points[cells]
        assert np.allclose(x, trilinear(x[:, :8], HEX20_NODES), rtol=0, atol=1e-12)
    # a linear field is interpolated exactly at the extra points; integer data stays integer
    assert np.allclose(back.point_data["u"], linear_field(back.points), rtol=0, atol=1e-12)
    assert back.point_data["status"].dtype.kind == "i" and np.all(back.point_data["status"] == 1)
    # conforming: each extra point is used by all cells around its edge (1 on the boundary, 2 inside)
    uses = np.bincount(transition.ravel(), minlength=len(back.points))[mesh.n_nodes:]
    assert uses.sum() == 4 * nx * ny * (family == "cubic") and set(uses) <= {1, 2}


def test_hex20_view_without_extra_points():
    cells, ids, w = hex20_view(body("bottom", "quadratic"))
    assert len(ids) == 0 and len(w) == 0 and all(c.shape[1] == 20 for c in cells)


@pytest.mark.parametrize("family, kind, per_element", [("quadratic", "quad9", 1), ("cubic", "quad", 9)])
def test_interface_faces(tmp_path, family, kind, per_element):
    mesh = rigid_base_interface(body("bottom", family))
    (block,) = mesh.interfaces
    u = linear_field(mesh.points)
    back = meshio.read(write_interfaces(tmp_path / "i.vtu", mesh, point_data={"u": u}))
    (cells,) = cells_of(back, kind)
    assert len(cells) == per_element * len(block.cells)
    assert np.array_equal(np.unique(cells), np.unique(block.side("B")))
    assert np.array_equal(back.point_data["u"], u)
    assert np.array_equal(back.cell_data["element"][0], np.repeat(np.arange(len(block.cells)), per_element))
    # the (sub-)quads' corners tile the contact face 6 × 2 mm², counter-clockwise seen from +z
    # (side B's order: its normal points from the base into the body)
    xy = back.points[cells[:, :4], :2]
    x, y, x1, y1 = xy[..., 0], xy[..., 1], np.roll(xy[..., 0], -1, axis=1), np.roll(xy[..., 1], -1, axis=1)
    signed = 0.5 * np.sum(x * y1 - x1 * y, axis=1)  # shoelace
    assert np.all(signed > 0) and np.isclose(signed.sum(), 12.0)


def test_points_round_trip(tmp_path):
    rng = np.random.default_rng(0)
    xyz = rng.uniform(size=(50, 3))
    data = {"traction": rng.normal(size=(50, 3)), "gap": rng.normal(size=50),
            "status": rng.integers(0, 3, size=50).astype(np.int32)}
    back = meshio.read(write_points(tmp_path / "p.vtu", xyz, data))
    assert np.array_equal(back.points, xyz)
    (cells,) = cells_of(back, "vertex")
    assert np.array_equal(cells.ravel(), np.arange(50))
    for name, v in data.items():
        assert np.array_equal(back.point_data[name], v) and back.point_data[name].dtype == v.dtype


def test_atomic_write_keeps_umask_and_leaves_no_temporaries(tmp_path):
    old = os.umask(0o027)
    try:
        target = tmp_path / "p.vtu"
        target.write_text("old")
        write_points(target, np.zeros((2, 3)), {"gap": np.zeros(2)})
        assert target.stat().st_mode & 0o777 == 0o640
        assert meshio.read(target).points.shape == (2, 3)
        with pytest.raises(ValueError):
            write_points(tmp_path / "bad.vtu", np.zeros((2, 3)), {"gap": np.zeros(3)})
        with pytest.raises(ValueError):
            write_mesh(tmp_path / "bad.vtu", body(), point_data={"u": np.zeros((3, 3))})
        assert sorted(p.name for p in tmp_path.iterdir()) == ["p.vtu"]
    finally:
        os.umask(old)


def test_write_interfaces_needs_interfaces(tmp_path):
    with pytest.raises(ValueError):
        write_interfaces(tmp_path / "i.vtu", body())
