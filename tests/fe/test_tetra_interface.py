"""12-node interface elements between the TRI6 faces of two TET10 blocks: the interface patch
tests of issue 31.

Model: two boxes [0, X] × [0, Y] stacked at z = 0 (lower z ∈ [−H1, 0], upper z ∈ [0, H2]), split
into tetrahedra (fe.tetra), joined by INTERFACE12 elements (side A = lower, n = +z), a linear
interface law s = diag(k_t, k_t, k_n) δ, rollers on x = 0 (u_x = 0), y = 0 (u_y = 0) of both
bodies, z = −H1 fixed in z, uniform pressure p on the upper body's top. The exact solution is
uniaxial stress σ_zz = −p in both bodies (same material: the same lateral strain ν p / E, so no
slip) and a uniform closure δ_n = −p / k_n: the law's inverse at p. Every interface point must
show it to 1e-9 relative, for both rules ("gauss": 6 points per triangle, "lobatto": the
mid-side nodes), and the displacement of the top must be the closed form
u_z(H2) = −p/k_n − p (H1 + H2)/E. A rigid motion of both bodies gives zero jumps and no
interface forces.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from roughcontact.fe.assembly import isotropic_elasticity, stiffness, surface_traction
from roughcontact.fe.element import TRI6
from roughcontact.fe.interface_points import interface_forces, interface_points, interface_tangent
from roughcontact.fe.mesh import dofs, interface_between, merge
from roughcontact.fe.quadrature import element_rule, simplex_rule
from roughcontact.fe.tetra import box_tets

X, Y, H1, H2 = 6.0, 4.0, 3.0, 2.5  # mm
E, NU = 210e3, 0.3  # N/mm²
KN, KT = 5e4, 2e4  # N/mm³
P = 80.0  # N/mm²


def two_tet_bodies(n=(3, 2, 2)):
    xe, ye = np.linspace(0.0, X, n[0] + 1), np.linspace(0.0, Y, n[1] + 1)
    lower = box_tets(xe, ye, np.linspace(-H1, 0.0, n[2] + 1), name="lower")
    upper = box_tets(xe, ye, np.linspace(0.0, H2, n[2] + 1), name="upper")
    return interface_between(merge(lower, upper), "lower.zmax", "upper.zmin")


def solve_linear(mesh, rule, pressure=P):
    """u (3N,) of the patch-test problem with the linear law (module docstring)."""
    D = isotropic_elasticity(E, NU)
    K = stiffness(mesh.points, [(b.element, b.cells) for b in mesh.blocks], D,
                  [element_rule(b.element) for b in mesh.blocks])
    pts = interface_points(mesh, rule)
    K = K + interface_tangent(pts, np.broadcast_to(np.diag([KT, KT, KN]), (pts.n_points, 3, 3)))
    top = mesh.face_sets["upper.zmax"]
    f = surface_traction(mesh.points, TRI6, top.face_nodes, (0.0, 0.0, -pressure), simplex_rule("tri6"))
    ns = mesh.node_sets
    fixed = np.unique(np.concatenate([
        dofs(ns["lower.xmin"], [0]), dofs(ns["upper.xmin"], [0]), dofs(ns["lower.ymin"], [1]),
        dofs(ns["upper.ymin"], [1]), dofs(ns["lower.zmin"], [2])]))
    free = np.setdiff1d(np.arange(mesh.n_dofs), fixed)
    u = np.zeros(mesh.n_dofs)
    u[free] = spla.spsolve(sp.csc_matrix(K[free][:, free]), f[free])
    return u, pts


@pytest.mark.parametrize("rule, n_points", [("gauss", 6), ("lobatto", 3)])
def test_uniform_pressure_closure_is_the_laws_inverse(rule, n_points):
    mesh = two_tet_bodies()
    u, pts = solve_linear(mesh, rule)
    n_faces = len(mesh.interfaces[0].cells)
    assert n_faces == 2 * 3 * 2  # two triangles per grid face of the 3 × 2 grid
    jumps = pts.jumps(u)
    closure = -jumps[:, 2]
    assert pts.n_points == (n_faces * n_points if rule == "gauss" else len(np.unique(pts.nodes)))
    assert np.abs(closure - P / KN).max() < 1e-9 * P / KN
    assert np.abs(jumps[:, :2]).max() < 1e-9 * P / KN  # no slip: both bodies expand alike
    assert np.allclose(pts.weights.sum(), X * Y, rtol=1e-13)
    # the settlement of the top: compression of both bodies plus the closure (closed form)
    top = mesh.node_sets["upper.zmax"]
    uz = u.reshape(-1, 3)[top, 2]
    exact = -P / KN - P * (H1 + H2) / E
    assert np.abs(uz - exact).max() < 1e-9 * abs(exact)


def test_interface_forces_balance_the_load():
    mesh = two_tet_bodies()
    u, pts = solve_linear(mesh, "gauss")
    s = pts.jumps(u) @ np.diag([KT, KT, KN])
    f = interface_forces(pts, s).reshape(-1, 3)
    upper = np.unique(np.concatenate([b.cells.ravel() for b in mesh.blocks if b.name.startswith("upper")]))
    # internal forces Bᵀ(w s): on the upper body they carry the whole applied load −p X Y (its
    # bulk forces are self-equilibrated), on the lower body the opposite
    assert f[upper, 2].sum() == pytest.approx(-P * X * Y, rel=1e-12)
    assert f[:, 2].sum() == pytest.approx(0.0, abs=1e-12 * P * X * Y)


@pytest.mark.parametrize("rule", ["gauss", "lobatto"])
def test_rigid_motion_gives_no_interface_tractions(rule):
    mesh = two_tet_bodies()
    pts = interface_points(mesh, rule)
    W = np.array([[0.0, -0.3, 0.2], [0.3, 0.0, -0.1], [-0.2, 0.1, 0.0]])
    R = np.linalg.qr(np.eye(3) + W)[0]  # a finite rotation
    x = mesh.points
    u = (x @ R.T - x + np.array([0.5, -1.0, 2.0])).ravel()
    scale = np.abs(u).max()
    assert np.abs(pts.jumps(u)).max() < 1e-14 * scale
    s = pts.jumps(u) @ np.diag([KT, KT, KN])
    assert np.abs(interface_forces(pts, s)).max() < 1e-14 * scale * KN * X * Y


def test_tilted_interface_frame_and_areas():
    """The frame of a rotated interface: n is the rotated +z, t1 the lay projected, and the
    weights add up to the area (the frames are not hard-wired to the axes)."""
    mesh = two_tet_bodies((2, 2, 1))
    R = np.linalg.qr(np.array([[2.0, 1.0, 0.3], [-0.5, 1.0, 0.2], [0.1, -0.4, 1.0]]))[0]
    R = R * np.sign(np.linalg.det(R))
    turned = type(mesh)(mesh.points @ R.T, mesh.blocks, mesh.node_sets, mesh.face_sets, mesh.interfaces, mesh.name)
    for rule in ("gauss", "lobatto"):
        pts = interface_points(turned, rule, lay=(1.0, 0.0, 0.0))
        assert np.abs(pts.frames[:, 2] - R[:, 2]).max() < 1e-13
        lay = np.array([1.0, 0.0, 0.0]) - R[0, 2] * R[:, 2]
        assert np.abs(pts.frames[:, 0] - lay / np.linalg.norm(lay)).max() < 1e-13
        assert pts.weights.sum() == pytest.approx(X * Y, rel=1e-13)
