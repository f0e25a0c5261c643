"""Interface integration points (roughcontact.fe.interface_points): the interface patch test.

A uniform relative displacement of the two sides must give the same local jump at every point
(the shape functions of a face sum to one and the frames of a flat face are constant), and the
nodal forces of a traction field must be its consistent nodal forces where the rule integrates
N_a·s exactly. Exactness, per direction of a face of degree p (QUAD9: p = 2, QUAD16: p = 3):

* Gauss, p + 1 points, exact to degree 2p + 1: N_a·s exact for s of degree ≤ p + 1;
* Lobatto (the nodes), p + 1 points, exact to degree 2p − 1: N_a·s exact for s of degree ≤ p − 1,
  the resultant ∫s dA for degree ≤ 2p − 1 and the first moments ∫x s dA for degree ≤ 2p − 2.

So a traction of degree p (quadratic on INTERFACE18, cubic on INTERFACE32) separates the two
rules: Gauss gives the consistent nodal forces, Lobatto not (it differs at the 4e-4–6e-3
level), but its resultant and first moments are still exact. The references are
independent of this module: the analytic integrals of the polynomial traction, and
assembly.surface_traction with an 8 × 8 Gauss rule (exact to degree 15) on side B's faces.
"""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact.fe.assembly import surface_traction
from roughcontact.fe.interface_points import interface_forces, interface_points, interface_tangent
from roughcontact.fe.mesh import box, interface_between, merge, rigid_base_interface
from roughcontact.fe.quadrature import tensor_rule

FAMILIES = {"quadratic": 2, "cubic": 3}  # face degree p of the contact face
X, Y = 8.0, 6.0  # contact zone [0, X] × [0, Y] mm (unequal sides: no symmetry hides a swap)
EXACT = tensor_rule("gauss", (8, 8))  # exact for N_a·s up to degree 15 per direction

# Jumps and forces are sums of O(10) products of O(1) numbers: round-off ~1e-15 relative; 1e-12
# is three orders above it and ten below any real error (a missing term is O(1)).
TIGHT = 1e-12


def two_bodies(family: str, n=(4, 3)):
    """Two boxes stacked at z = 0 (lower: transition layer on top; upper: at the bottom), merged
    and joined by interface elements: side A = lower body, n = +z."""
    xe, ye = np.linspace(0.0, X, n[0] + 1), np.linspace(0.0, Y, n[1] + 1)
    lower = box(xe, ye, [-3.0, -1.0, 0.0], contact_face="top", family=family, name="lower")
    upper = box(xe, ye, [0.0, 1.5, 4.0], contact_face="bottom", family=family, name="upper")
    mesh = interface_between(merge(lower, upper), "lower.contact", "upper.contact")
    body_b = np.unique(np.concatenate([b.cells.ravel() for b in mesh.blocks if b.name.startswith("upper")]))
    return mesh, body_b, mesh.face_sets["upper.contact"]


def on_base(family: str, n=(4, 3)):
    """One box on a rigid base: side A = the base nodes, side B = the box's contact face."""
    xe, ye = np.linspace(0.0, X, n[0] + 1), np.linspace(0.0, Y, n[1] + 1)
    mesh = rigid_base_interface(box(xe, ye, [0.0, 2.0, 5.0], contact_face="bottom", family=family))
    body_b = np.setdiff1d(np.arange(mesh.n_nodes), mesh.node_sets["base"])
    return mesh, body_b, mesh.face_sets["contact"]


MESHES = {"two_bodies": two_bodies, "on_base": on_base}
CASES = [(m, f, r) for m in MESHES for f in FAMILIES for r in ("gauss", "lobatto")]


def frame(lay):
    """Rows t1, t2, n of a flat interface with normal +z and t1 along the projected lay."""
    n = np.array([0.0, 0.0, 1.0])
    t1 = np.asarray(lay, dtype=float) - np.dot(lay, n) * n
    t1 /= np.linalg.norm(t1)
    return np.array([t1, np.cross(n, t1), n])


def polynomial_traction(degree: int):
    """A local traction field s(x, y) (n_points, 3) of total degree ``degree`` in x and y per
    component (pure x^degree and y^degree terms included), and its analytic integrals over
    [0, X] × [0, Y]: ∫s, ∫x s, ∫y s."""
    # terms (coefficient, i, j) of x^i y^j per component
    terms = [
        [(0.7, 0, 0), (-0.3, 1, 0), (0.2, 0, 1), (0.05, degree, 0)],
        [(-0.4, 0, 0), (0.1, 1, 1 if degree >= 2 else 0), (-0.02, 0, degree)],
        [(-1.3, 0, 0), (0.25, degree, 0), (-0.15, 0, degree), (0.08, 1, 0)],
    ]

    def s(x):
        return np.stack([sum(c * x[..., 0] ** i * x[..., 1] ** j for c, i, j in comp) for comp in terms], axis=-1)

    def moment(a, b):  # ∫∫ x^a y^b s dA over the rectangle, per component
        return np.array([sum(c * X ** (i + a + 1) / (i + a + 1) * Y ** (j + b + 1) / (j + b + 1) for c, i, j in comp)
                         for comp in terms])

    return s, moment(0, 0), moment(1, 0), moment(0, 1)


@pytest.mark.parametrize("kind, family, rule", CASES)
def test_point_count_weights_and_frames(kind, family, rule):
    mesh, _, faces = MESHES[kind](family)
    pts = interface_points(mesh, rule)
    p = FAMILIES[family]
    n_elements = len(faces)
    side_b = np.unique(mesh.interfaces[0].side("B"))
    expected = side_b.size if rule == "lobatto" else n_elements * (p + 1) ** 2
    assert pts.n_points == expected
    if rule == "lobatto":  # one point per side-B node, sitting on it
        assert np.array_equal(np.sort(pts.nodes), side_b)
        np.testing.assert_allclose(pts.x, mesh.points[pts.nodes], rtol=0, atol=TIGHT * X)
    assert np.all(pts.weights > 0)
    assert abs(pts.weights.sum() - X * Y) <= TIGHT * X * Y
    np.testing.assert_allclose(pts.frames, np.broadcast_to(frame((1, 0, 0)), pts.frames.shape), rtol=0, atol=TIGHT)


@pytest.mark.parametrize("family, n, points", [("quadratic", (4, 4), 81), ("cubic", (3, 3), 100)])
def test_nodal_rule_gives_the_papers_contact_point_counts(family, n, points):
    """Section 9.2: 81 contact points for 4 × 4 quadratic, 100 for 3 × 3 cubic elements."""
    mesh, _, _ = on_base(family, n)
    assert interface_points(mesh, "lobatto").n_points == points
    assert interface_points(mesh, "gauss").n_points == n[0] * n[1] * (FAMILIES[family] + 1) ** 2


@pytest.mark.parametrize("lay", [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.3, -2.0, 0.7)])
@pytest.mark.parametrize("kind, family, rule", CASES)
def test_uniform_jump_is_exact_at_every_point(kind, family, rule, lay):
    """Side B moved rigidly by v relative to side A (both sides also carried by a common
    translation w, which must not matter): every point's jump is R·v, R the local frame."""
    mesh, body_b, _ = MESHES[kind](family)
    pts = interface_points(mesh, rule, lay)
    v, w = np.array([0.013, -0.021, 0.0047]), np.array([-0.5, 0.25, 1.0])
    u = np.tile(w, (mesh.n_nodes, 1))
    u[body_b] += v
    jumps = pts.jumps(u.ravel())
    R = frame(lay)
    np.testing.assert_allclose(jumps, np.broadcast_to(R @ v, jumps.shape), rtol=0, atol=TIGHT * np.linalg.norm(v))
    # a common rigid translation alone gives no jump
    assert np.max(np.abs(pts.jumps(np.tile(w, mesh.n_nodes)))) <= TIGHT * np.linalg.norm(w)


@pytest.mark.parametrize("lay", [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0)])
@pytest.mark.parametrize("kind, family, rule", CASES)
def test_uniform_traction_gives_consistent_nodal_forces(kind, family, rule, lay):
    """A uniform local traction s: the forces on side B are the consistent nodal forces of the
    global traction Rᵀs on B's faces (both rules integrate N_a exactly), side A gets the
    opposite forces, and they sum to Rᵀs × area."""
    mesh, body_b, faces = MESHES[kind](family)
    pts = interface_points(mesh, rule, lay)
    s = np.array([0.3, -0.2, -1.1])
    f = interface_forces(pts, np.tile(s, (pts.n_points, 1))).reshape(-1, 3)
    g = frame(lay).T @ s  # the traction in global components
    ref = surface_traction(mesh.points, faces.face_element, faces.face_nodes, g, rule=EXACT).reshape(-1, 3)
    scale = np.linalg.norm(g) * X * Y
    side_a = np.unique(mesh.interfaces[0].side("A"))
    side_b = np.unique(mesh.interfaces[0].side("B"))
    np.testing.assert_allclose(f[side_b], ref[side_b], rtol=0, atol=TIGHT * scale)
    np.testing.assert_allclose(f[side_a].sum(axis=0), -g * X * Y, rtol=0, atol=TIGHT * scale)
    np.testing.assert_allclose(f[side_b].sum(axis=0), g * X * Y, rtol=0, atol=TIGHT * scale)
    others = np.setdiff1d(np.arange(mesh.n_nodes), np.concatenate([side_a, side_b]))
    assert not np.any(f[others])


@pytest.mark.parametrize("kind, family", [(m, f) for m in MESHES for f in FAMILIES])
def test_polynomial_traction_consistency_by_rule(kind, family):
    """Tractions s(x) evaluated at the points: degree p − 1 gives the consistent nodal forces with
    both rules; degree p with Gauss only, while Lobatto keeps the exact resultant and first
    moments (module docstring)."""
    mesh, _, faces = MESHES[kind](family)
    p = FAMILIES[family]
    side_b = np.unique(mesh.interfaces[0].side("B"))
    worst_lobatto = 0.0
    for degree in (p - 1, p):
        s, total, mx, my = polynomial_traction(degree)
        ref = surface_traction(mesh.points, faces.face_element, faces.face_nodes, s, rule=EXACT).reshape(-1, 3)
        scale = np.max(np.abs(ref))
        for rule in ("gauss", "lobatto"):
            pts = interface_points(mesh, rule)
            f = interface_forces(pts, s(pts.x)).reshape(-1, 3)[side_b]
            x = mesh.points[side_b]
            # resultant and first moments Σ_a x_a f_a = Σ_q w_q x_q s_q: exact for both rules
            np.testing.assert_allclose(f.sum(axis=0), total, rtol=0, atol=TIGHT * np.max(np.abs(total)))
            np.testing.assert_allclose(x[:, 0] @ f, mx, rtol=0, atol=TIGHT * X * np.max(np.abs(total)))
            np.testing.assert_allclose(x[:, 1] @ f, my, rtol=0, atol=TIGHT * X * np.max(np.abs(total)))
            if rule == "gauss" or degree <= p - 1:
                np.testing.assert_allclose(f, ref[side_b], rtol=0, atol=TIGHT * scale)
            else:
                worst_lobatto = np.max(np.abs(f - ref[side_b])) / scale
    # the test distinguishes the rules: Lobatto is not the consistent load at degree p (measured
    # 4e-4 relative for the cubic faces, 6e-3 for the quadratic ones; 1e-6 is far above round-off)
    assert worst_lobatto > 1e-6


@pytest.mark.parametrize("rule", ["gauss", "lobatto"])
def test_interface_tangent_is_the_derivative_of_the_forces(rule):
    """Bᵀ diag(w D) B is the Jacobian of u ↦ Bᵀ(w ⊙ D·B u) (a linear map: exact to round-off),
    with an unsymmetric D per point."""
    mesh, _, _ = two_bodies("quadratic", (2, 2))
    pts = interface_points(mesh, rule)
    rng = np.random.default_rng(7)
    D = rng.normal(size=(pts.n_points, 3, 3))
    u = rng.normal(size=mesh.n_dofs)
    forces = interface_forces(pts, np.einsum("qij,qj->qi", D, pts.jumps(u)))
    K = interface_tangent(pts, D)
    np.testing.assert_allclose(K @ u, forces, rtol=0, atol=TIGHT * np.max(np.abs(forces)))


def test_interface_points_need_interfaces():
    with pytest.raises(ValueError, match="no interface elements"):
        interface_points(box([0, 1], [0, 1], [0, 1]))
    mesh, _, _ = on_base("quadratic", (1, 1))
    with pytest.raises(ValueError, match="rule kind"):
        interface_points(mesh, "simpson")
    with pytest.raises(ValueError, match="lay direction"):
        interface_points(mesh, "gauss", lay=(0.0, 0.0, 1.0))
