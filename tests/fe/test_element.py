"""Shape functions of HEX20, HEX21, HEX28, QUAD8, QUAD9, QUAD16: partition of unity, nodality,
polynomial reproduction, gradients, the closed-form hex20, conformity between neighbours.

Expected values are written here independently of element.py (monomial lists, closed forms,
node positions); nothing is taken from the code under test except the node coordinates being
interpolated.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from roughcontact.fe.element import HEX20, HEX21, HEX28, QUAD8, QUAD9, QUAD16

ALL = [HEX20, HEX21, HEX28, QUAD8, QUAD9, QUAD16]
HEXES = [HEX20, HEX21, HEX28]
IDS = [e.name for e in ALL]

# Shape functions are O(1) (|N| < ~3 for the cubic ones) computed by one small solve and a
# matrix product: round-off is ~1e-14; 1e-12 leaves margin for the cond(V) ~ 1e2 of the nodal
# matrices without letting any real error (>= 1e-3 for a wrong node or term) through.
TOL = 1e-12

def _random_points(dim: int, n: int = 50, seed: int = 2009) -> np.ndarray:
    """n uniform points in [-1, 1]^dim (seeded: the same points whichever tests run)."""
    return np.random.default_rng(seed).uniform(-1, 1, size=(n, dim))


def _monomial(exps):
    return lambda x: np.prod(x ** np.asarray(exps), axis=1)


# ------------------------------------------------------------------------------------------
# the spaces, written out independently of element.py
# ------------------------------------------------------------------------------------------
Q1_2D = [(a, b) for a in range(2) for b in range(2)]
S2_2D = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2), (2, 1), (1, 2)]
Q2_2D = [(a, b) for a in range(3) for b in range(3)]
Q3_2D = [(a, b) for a in range(4) for b in range(4)]
#: 3D serendipity: complete quadratics + ξηζ + ξ²η, ξ²ζ, η²ξ, η²ζ, ζ²ξ, ζ²η + ξ²ηζ, ξη²ζ, ξηζ²
SERENDIPITY_3D = (
    [e for e in itertools.product(range(3), repeat=3) if sum(e) <= 2]
    + [(1, 1, 1), (2, 1, 0), (2, 0, 1), (1, 2, 0), (0, 2, 1), (1, 0, 2), (0, 1, 2),
       (2, 1, 1), (1, 2, 1), (1, 1, 2)]
)
COMPLETE_QUADRATIC_3D = [e for e in itertools.product(range(3), repeat=3) if sum(e) <= 2]
BOTTOM_FACE = {"hex20": S2_2D, "hex21": Q2_2D, "hex28": Q3_2D}


def _face_layer_functions(bottom):
    """The spanning functions F_bot·(1−ζ) , S2·(1+ζ), Q1·(1−ζ²) of a hexahedron (docstring of
    element.py), as callables."""
    funcs = []
    for (a, b), zeta in itertools.chain(((e, lambda z: 1 - z) for e in bottom),
                                        ((e, lambda z: 1 + z) for e in S2_2D),
                                        ((e, lambda z: 1 - z * z) for e in Q1_2D)):
        funcs.append(lambda x, a=a, b=b, zeta=zeta: x[:, 0] ** a * x[:, 1] ** b * zeta(x[:, 2]))
    return funcs


def _space_functions(element):
    if element.dim == 2:
        return [_monomial(e) for e in {"quad8": S2_2D, "quad9": Q2_2D, "quad16": Q3_2D}[element.name]]
    return _face_layer_functions(BOTTOM_FACE[element.name])


def _interpolation_error(element, f) -> float:
    x = _random_points(element.dim)
    return float(np.max(np.abs(element.shape(x) @ f(element.nodes) - f(x))))


# ------------------------------------------------------------------------------------------
# basic properties
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("element", ALL, ids=IDS)
def test_sizes(element):
    expected = {"hex20": 20, "hex21": 21, "hex28": 28, "quad8": 8, "quad9": 9, "quad16": 16}
    assert element.n_nodes == expected[element.name]
    assert len(np.unique(np.round(element.nodes, 12), axis=0)) == element.n_nodes  # distinct nodes
    assert np.all(np.abs(element.nodes) <= 1.0)


@pytest.mark.parametrize("element", ALL, ids=IDS)
def test_partition_of_unity(element):
    x = _random_points(element.dim)
    assert np.max(np.abs(element.shape(x).sum(axis=1) - 1.0)) < TOL
    assert np.max(np.abs(element.shape_gradients(x).sum(axis=1))) < TOL


@pytest.mark.parametrize("element", ALL, ids=IDS)
def test_kronecker_delta(element):
    assert np.max(np.abs(element.shape(element.nodes) - np.eye(element.n_nodes))) < TOL


@pytest.mark.parametrize("element", ALL, ids=IDS)
def test_reproduces_its_space(element):
    funcs = _space_functions(element)
    assert len(funcs) == element.n_nodes  # the space has exactly one function per node
    assert max(_interpolation_error(element, f) for f in funcs) < TOL


@pytest.mark.parametrize("element", HEXES, ids=[e.name for e in HEXES])
def test_hexahedra_contain_serendipity(element):
    # every complete quadratic and the 20 serendipity monomials (so the quadratic patch test
    # can pass on affine meshes)
    assert len(SERENDIPITY_3D) == 20 and len(COMPLETE_QUADRATIC_3D) == 10
    assert set(COMPLETE_QUADRATIC_3D) <= set(SERENDIPITY_3D)
    assert max(_interpolation_error(element, _monomial(e)) for e in SERENDIPITY_3D) < TOL


@pytest.mark.parametrize("element, outside", [(HEX20, (2, 2, 0)), (HEX21, (2, 2, 1)), (HEX28, (3, 0, 1)),
                                              (QUAD8, (2, 2)), (QUAD9, (3, 0))],
                         ids=["hex20", "hex21", "hex28", "quad8", "quad9"])
def test_does_not_reproduce_outside_its_space(element, outside):
    # the reproduction tests above are not vacuous: a monomial outside the space fails clearly
    assert _interpolation_error(element, _monomial(outside)) > 1e-3


@pytest.mark.parametrize("element", ALL, ids=IDS)
def test_gradients_against_finite_differences(element):
    # central differences of a polynomial: truncation h²/6 |f'''| ≲ 1e-10·30, round-off
    # eps |N| / h ≈ 1e-11; 1e-8 is well above both and far below any real error
    h = 1e-5
    x = _random_points(element.dim, 20) * 0.99
    grad = element.shape_gradients(x)
    for k in range(element.dim):
        e = np.zeros(element.dim)
        e[k] = h
        fd = (element.shape(x + e) - element.shape(x - e)) / (2 * h)
        assert np.max(np.abs(grad[:, :, k] - fd)) < 1e-8


def _hex20_closed_form(x):
    """The textbook serendipity hex20 (e.g. Zienkiewicz & Taylor), at HEX20's nodes."""
    out = np.empty((len(x), 20))
    for a, (xi, eta, zeta) in enumerate(HEX20.nodes):
        s, t, u = 1 + x[:, 0] * xi, 1 + x[:, 1] * eta, 1 + x[:, 2] * zeta
        if xi != 0 and eta != 0 and zeta != 0:
            out[:, a] = s * t * u * (x[:, 0] * xi + x[:, 1] * eta + x[:, 2] * zeta - 2) / 8
        elif xi == 0:
            out[:, a] = (1 - x[:, 0] ** 2) * t * u / 4
        elif eta == 0:
            out[:, a] = s * (1 - x[:, 1] ** 2) * u / 4
        else:
            out[:, a] = s * t * (1 - x[:, 2] ** 2) / 4
    return out


def test_hex20_is_the_closed_form_serendipity():
    x = np.vstack([_random_points(3), HEX20.nodes])
    assert np.max(np.abs(HEX20.shape(x) - _hex20_closed_form(x))) < TOL


def test_hex20_node_order_is_vtk():
    # VTK_QUADRATIC_HEXAHEDRON (type 25): corners bottom then top counter-clockwise, the mid-edge
    # nodes of edges (0,1), (1,2), (2,3), (3,0), (4,5), (5,6), (6,7), (7,4), (0,4), (1,5), (2,6), (3,7)
    corners = np.array([(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                        (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)], dtype=float)
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    expected = np.vstack([corners, [(corners[i] + corners[j]) / 2 for i, j in edges]])
    assert np.array_equal(HEX20.nodes, expected)
    assert np.array_equal(HEX21.nodes[:20], expected) and np.array_equal(HEX21.nodes[20], [0, 0, -1])


def test_hex28_contact_face_nodes_are_lobatto():
    # the ζ = −1 face carries 16 nodes at ξ, η ∈ {±1, ±1/√5} (4-point Gauss–Lobatto abscissae)
    c = 1 / math.sqrt(5)
    face = HEX28.nodes[np.isclose(HEX28.nodes[:, 2], -1.0, rtol=0, atol=1e-15)]
    expected = {(x, y) for x in (-1, -c, c, 1) for y in (-1, -c, c, 1)}
    assert len(face) == 16
    assert all(min(math.dist(p[:2], q) for q in expected) < 1e-15 for p in face)
    # the rest are the hex20 top-face and vertical mid-edge nodes
    rest = HEX28.nodes[~np.isclose(HEX28.nodes[:, 2], -1.0, rtol=0, atol=1e-15)]
    assert {tuple(p) for p in rest} == {tuple(p) for p in HEX20.nodes if p[2] != -1}


# ------------------------------------------------------------------------------------------
# conformity
# ------------------------------------------------------------------------------------------
def _face_param(axis: int, value: float, st: np.ndarray) -> np.ndarray:
    """Reference points of the face {x_axis = value}, the other two coordinates from st (n, 2)."""
    x = np.insert(st, axis, value, axis=1)
    return x


def _check_shared_face(A, axis_a, value_a, B, axis_b, value_b):
    """A's face {x_axis_a = value_a} glued to B's face {x_axis_b = value_b} with the same
    in-face coordinates (both faces use the two remaining coordinates in increasing axis order).
    The nodes of A and B on the face must coincide, their shape functions agree on the face,
    and every other node's function vanish there. Returns the worst discrepancy."""
    st = _random_points(2, 40, seed=1)
    NA, NB = A.shape(_face_param(axis_a, value_a, st)), B.shape(_face_param(axis_b, value_b, st))
    on_a = np.flatnonzero(np.isclose(A.nodes[:, axis_a], value_a, rtol=0, atol=1e-15))
    on_b = np.flatnonzero(np.isclose(B.nodes[:, axis_b], value_b, rtol=0, atol=1e-15))
    pos_a = np.delete(A.nodes[on_a], axis_a, axis=1)
    pos_b = np.delete(B.nodes[on_b], axis_b, axis=1)
    assert len(on_a) == len(on_b)
    # match each node of A on the face to the node of B at the same in-face position
    dist = np.linalg.norm(pos_a[:, None, :] - pos_b[None, :, :], axis=2)
    match = on_b[np.argmin(dist, axis=1)]
    assert np.max(np.min(dist, axis=1)) < 1e-15 and len(set(match)) == len(on_a)
    err = np.max(np.abs(NA[:, on_a] - NB[:, match]))
    err = max(err, np.max(np.abs(np.delete(NA, on_a, axis=1))), np.max(np.abs(np.delete(NB, on_b, axis=1))))
    return err


@pytest.mark.parametrize("element", HEXES, ids=[e.name for e in HEXES])
def test_hex20_stacked_on_top(element):
    # (a) the top face ζ = +1 of a (transition) element equals the bottom face of a hex20 above
    assert _check_shared_face(element, 2, 1.0, HEX20, 2, -1.0) < TOL


@pytest.mark.parametrize("element", HEXES, ids=[e.name for e in HEXES])
@pytest.mark.parametrize("axis", [0, 1], ids=["xi", "eta"])
def test_side_by_side(element, axis):
    # (b) two transition elements side by side (and (d) two hex20): the +1 face of one on the
    # −1 face of its neighbour in ξ and in η
    assert _check_shared_face(element, axis, 1.0, element, axis, -1.0) < TOL


def test_hex21_beside_hex20():
    # HEX21's lateral faces carry the same 8 nodes as a hex20's (Q2 and S2 agree on an edge)
    assert _check_shared_face(HEX21, 0, 1.0, HEX20, 0, -1.0) < TOL


@pytest.mark.parametrize("element, face", [(HEX20, QUAD8), (HEX21, QUAD9), (HEX28, QUAD16)],
                         ids=["hex20-quad8", "hex21-quad9", "hex28-quad16"])
def test_contact_face_trace(element, face):
    # (c) on ζ = −1 the contact_face nodes' functions are the face element's, the others vanish
    assert element.face_element is face
    st = _random_points(2)
    N = element.shape(_face_param(2, -1.0, st))
    idx = list(element.contact_face)
    assert np.array_equal(element.nodes[idx, :2], face.nodes) and np.all(element.nodes[idx, 2] == -1)
    assert np.max(np.abs(N[:, idx] - face.shape(st))) < TOL
    assert np.max(np.abs(np.delete(N, idx, axis=1))) < TOL
