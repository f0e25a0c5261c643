"""TET10/TRI6 (CalculiX C3D10 and its faces) and the simplex rules: exactness against the closed
form ∫ x^a y^b z^c over the unit simplex = a! b! c! / (a + b + c + d)!, partition of unity, the
Kronecker property, the barycentric closed forms of the shape functions, and patch tests on a
small tetrahedral mesh (a cube split into 6 tetrahedra, distorted): a linear displacement field
gives its constant strain exactly, a rigid rotation (linearised) zero stress, and the volume."""

from __future__ import annotations

import itertools
from math import factorial

import numpy as np
import pytest

from roughcontact.fe.assembly import isotropic_elasticity, stiffness, strain_stress, block_geometry
from roughcontact.fe.element import TET10, TET10_FACES, TET10_NODES, TRI6
from roughcontact.fe.quadrature import collapsed_rule, element_rule, simplex_rule
from roughcontact.fe.tetra import hex_to_tets

TIGHT = 1e-12  # sums of O(10) products of O(1) numbers


def simplex_integral(exps) -> float:
    """∫ Π x_k^e_k over the unit simplex (Dirichlet's formula)."""
    return np.prod([factorial(e) for e in exps]) / factorial(sum(exps) + len(exps))


@pytest.mark.parametrize("name, dim, degree", [("tet4", 3, 2), ("tri6", 2, 4), ("tri_midedge", 2, 2)])
def test_simplex_rules_exact_to_their_degree(name, dim, degree):
    rule = simplex_rule(name)
    for exps in itertools.product(range(degree + 1), repeat=dim):
        if sum(exps) <= degree:
            value = rule.weights @ np.prod(rule.points ** np.array(exps), axis=1)
            # tri6's tabulated constants have 15 digits (Dunavant 1985)
            assert value == pytest.approx(simplex_integral(exps), rel=1e-13, abs=1e-15), exps
    # and not beyond: a monomial of degree + 1 (or + 2 for the odd-symmetric tri6) is missed
    exps = (degree + 1,) + (0,) * (dim - 1)
    assert rule.weights @ rule.points[:, 0] ** (degree + 1) != pytest.approx(simplex_integral(exps), rel=1e-6)


@pytest.mark.parametrize("dim, n", [(2, 3), (3, 3), (3, 4)])
def test_collapsed_rule_exact_to_2n_minus_dim(dim, n):
    rule = collapsed_rule(dim, n)
    for exps in itertools.product(range(2 * n - dim + 1), repeat=dim):
        if sum(exps) <= 2 * n - dim:
            value = rule.weights @ np.prod(rule.points ** np.array(exps), axis=1)
            assert value == pytest.approx(simplex_integral(exps), rel=1e-13), exps


@pytest.mark.parametrize("element", [TET10, TRI6])
def test_partition_of_unity_and_kronecker(element):
    x = collapsed_rule(element.dim, 4).points
    assert np.abs(element.shape(x).sum(axis=1) - 1.0).max() < TIGHT
    assert np.abs(element.shape_gradients(x).sum(axis=1)).max() < 1e-11
    assert np.abs(element.shape(element.nodes) - np.eye(element.n_nodes)).max() < TIGHT


def test_tet10_matches_barycentric_closed_form():
    x = collapsed_rule(3, 3).points
    lam = np.column_stack([1.0 - x.sum(axis=1), x])  # λ_1..λ_4 of corners 1-4
    ref = [lam[:, i] * (2 * lam[:, i] - 1) for i in range(4)]
    ref += [4 * lam[:, i] * lam[:, j] for i, j in ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))]
    assert np.abs(TET10.shape(x) - np.column_stack(ref)).max() < TIGHT


def test_faces_are_calculix_faces_outward():
    # CalculiX manual, C3D10: S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1 (1-based corners)
    calculix = {1: {1, 2, 3}, 2: {1, 4, 2}, 3: {2, 4, 3}, 4: {3, 4, 1}}
    centre = TET10_NODES[:4].mean(axis=0)
    for s, face in TET10_FACES.items():
        assert {i + 1 for i in face[:3]} == calculix[s]
        x = TET10_NODES[list(face)]
        assert np.allclose(TRI6.shape(TRI6.nodes) @ x, x)
        n = np.cross(x[1] - x[0], x[2] - x[0])
        assert n @ (x[:3].mean(axis=0) - centre) > 0  # outward
        assert np.allclose(x[3:], (x[:3] + np.roll(x[:3], -1, axis=0)) / 2)  # mids in TRI6 order


def small_mesh():
    """A distorted 2 × 1 × 1 hexahedral grid split into 12 tetrahedra (straight edges)."""
    xs = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1.2, 0], [2, 1, 0],
                   [0, 0, 1], [1.1, 0, 1], [2, 0, 1.1], [0, 1, 1], [1, 1, 0.9], [2, 1.1, 1]], dtype=float)
    hexes = np.array([[0, 1, 4, 3, 6, 7, 10, 9], [1, 2, 5, 4, 7, 8, 11, 10]])
    return hex_to_tets(xs, hexes)


def test_volume_and_linear_patch():
    points, cells = small_mesh()
    assert cells.shape == (12, 10)
    G, dV = block_geometry(TET10, points[cells], element_rule(TET10))
    # volume of the two distorted hexahedra by the divergence theorem on their trilinear faces is
    # awkward; the straight-edged tets' volumes are exact: Σ |det(edges)| / 6 over the corners
    corners = points[cells[:, :4]]
    vol = np.abs(np.linalg.det(corners[:, 1:] - corners[:, :1])) / 6.0
    assert np.abs(dV.sum(axis=1) - vol).max() < TIGHT
    # a linear field u = A x + c: constant strain sym(A) at every point, and K u = 0 at interior…
    A = np.array([[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [0.0, 7e-4, 4e-3]])
    u = (points @ A.T + np.array([0.1, -0.2, 0.3])).ravel()
    D = isotropic_elasticity(210e3, 0.3)
    strain, stress = strain_stress(points, TET10, cells, u, D, element_rule(TET10).points)
    eps = 0.5 * (A + A.T)
    ref = np.array([eps[0, 0], eps[1, 1], eps[2, 2], 2 * eps[1, 2], 2 * eps[0, 2], 2 * eps[0, 1]])
    assert np.abs(strain - ref).max() < 1e-15 * 1e3
    # … and the nodal forces K u are those of the constant stress on the boundary: they sum to
    # zero, and their moment too (equilibrium of a self-equilibrated field)
    K = stiffness(points, [(TET10, cells)], D, element_rule(TET10))
    f = (K @ u).reshape(-1, 3)
    scale = np.abs(f).max()
    assert np.abs(f.sum(axis=0)).max() < 1e-12 * scale
    assert np.abs(np.cross(points, f).sum(axis=0)).max() < 1e-12 * scale


def test_rigid_rotation_gives_zero_stress():
    points, cells = small_mesh()
    W = np.array([[0.0, -1.0, 0.5], [1.0, 0.0, -2.0], [-0.5, 2.0, 0.0]]) * 1e-3  # skew: linearised rotation
    u = (points @ W.T + np.array([1.0, 2.0, 3.0])).ravel()
    D = isotropic_elasticity(210e3, 0.3)
    _, stress = strain_stress(points, TET10, cells, u, D, collapsed_rule(3, 3).points)
    # round-off: E × |u| / h × 1e-15 per term (the 3 mm translation dominates, h ≥ 0.5 mm), with
    # a margin of ten terms; a real strain of the rotation's size would give ~E × 1e-3 = 210
    assert np.abs(stress).max() < 1e-14 * 210e3 * 3.0 / 0.5
    K = stiffness(points, [(TET10, cells)], D, element_rule(TET10))
    assert np.abs(K @ u).max() < 1e-12 * abs(K).max()
