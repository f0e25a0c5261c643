"""Finite elements as data: reference nodes + a polynomial space → shape functions.

An :class:`Element` is defined by its reference nodes (in [-1, 1]^d) and a polynomial space of
the same dimension, spanned by ``basis`` polynomials given as coefficients over monomials
ξ^a η^b ζ^c. The shape functions are the nodal (Lagrange) basis of that space: with the
nodal matrix V_ik = p_k(x_i) (basis polynomial k at node i), N(x) = p(x) V⁻¹, so that
N_j(x_i) = δ_ij and every polynomial of the space is reproduced exactly. Nothing is written out
by hand; a wrong node set or space shows as a singular (or ill-conditioned) V at construction.

The hexahedra of section 9 (Buczkowski & Kleiber 2009, Figs 11, 16; Buczkowski 1998,
Buczkowski & Gabbert 2004) share one construction, a "face layer" space

    P = F_bot(ξ, η)·L0(ζ) ⊕ F_top(ξ, η)·L1(ζ) ⊕ Q1(ξ, η)·B(ζ),
    L0 = (1 − ζ)/2,  L1 = (1 + ζ)/2,  B = 1 − ζ²,

with F_bot, F_top the spaces of the bottom (ζ = −1) and top (ζ = +1) faces and Q1 the bilinears
(the quadratic bubble in ζ along the four vertical edges):

=========  ====================  =============  =====================================
element    F_bot (ζ = −1)        F_top          dimension
=========  ====================  =============  =====================================
HEX20      S2 (serendipity, 8)   S2 (8)         8 + 8 + 4 = 20: the serendipity hex20
HEX21      Q2 (biquadratic, 9)   S2 (8)         9 + 8 + 4 = 21: Fig. 16
HEX28      Q3 (bicubic, 16)      S2 (8)         16 + 8 + 4 = 28: Fig. 11
=========  ====================  =============  =====================================

Properties that follow from the construction (tests/fe/test_element.py checks each):

* the trace on ζ = −1 is F_bot, on ζ = +1 is S2 (so a hex20 fits on top of a transition
  element), and on a lateral face (ξ = ±1 or η = ±1) it is F_bot|edge·L0 ⊕ S2|edge·L1 ⊕
  linear·B, fixed by the nodes on that face (two transition elements side by side conform);
* each space contains the 20-dimensional serendipity space, hence all complete quadratics
  (quadratic patch tests pass on affine meshes, linear ones on distorted meshes — for HEX28
  with curved edges only with more than the default 4×4×3 Gauss points, tests/fe/test_assembly.py;
  the meshes of :mod:`.mesh` are boxes);
* unisolvence: the bottom nodes fix the F_bot part, the top nodes the S2 part, the four
  vertical mid-edge nodes the Q1 part (the 1/√5 nodes of HEX28 are the 4-point Gauss–Lobatto
  abscissae, so nodal integration of the contact face samples at the nodes).

The contact face of a transition element is always its local ζ = −1 face; its face nodes in
the order of the matching 2D element are ``contact_face``. Node order: corners and edges of
HEX20 follow VTK's quadratic hexahedron (type 25); HEX21 adds the face centre as node 20;
HEX28 is listed in :data:`HEX28_NODES` (corners as VTK, then the contact face's edge nodes, the
top-edge and vertical-edge mid-nodes, the contact face's interior nodes).

Quadrilaterals (QUAD8 = S2, QUAD9 = Q2, QUAD16 = Q3 on the Lobatto nodes ±1, ±1/√5) are the
faces and the sides of the zero-thickness interface elements.

Simplices (``domain="simplex"``: the reference cell is the unit simplex x_i ≥ 0, Σ x_i ≤ 1, not
[-1, 1]^d). TET10 is CalculiX's C3D10: corners 1-4 at (0,0,0), (1,0,0), (0,1,0), (0,0,1), mid-edge
nodes 5: 1-2, 6: 2-3, 7: 3-1, 8: 1-4, 9: 2-4, 10: 3-4 (CalculiX manual, section 6.2.2; 0-based
here), with the complete quadratics P2 in (ξ, η, ζ) (10 monomials); TRI6 is its face (corners 1-3,
mid-sides 4: 1-2, 5: 2-3, 6: 3-1) with P2 in (ξ, η). The same Vandermonde construction gives the
familiar shape functions (corner N = λ(2λ − 1), mid-edge N = 4 λ_i λ_j in the barycentric λ).
:data:`TET10_FACES` lists the faces S1-S4 in CalculiX's order, each as TRI6 nodes oriented with
∂x/∂u × ∂x/∂v pointing OUT of the element (CalculiX lists them inward: 1-2-3, 1-4-2, 2-4-3,
3-4-1; the corner order is reversed here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = [
    "Polynomials", "Element", "LOBATTO4", "QUAD8", "QUAD9", "QUAD16", "HEX20", "HEX21", "HEX28",
    "HEX20_NODES", "HEX21_NODES", "HEX28_NODES", "QUAD8_NODES", "QUAD9_NODES", "QUAD16_NODES",
    "ELEMENTS", "P2_2D", "P2_3D", "TRI6", "TET10", "TRI6_NODES", "TET10_NODES", "TET10_FACES",
]

#: the interior 4-point Gauss–Lobatto abscissa, c = 1/√5 (the paper's Fig. 11)
LOBATTO4 = 1.0 / math.sqrt(5.0)


# ---------------------------------------------------------------------------------------------
# polynomials over monomials
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Polynomials:
    """A list of polynomials in d variables: ``coefficients`` (n_poly, n_mono) over the
    monomials ``exponents`` (n_mono, d) (x^exponents summed with the coefficients)."""

    exponents: np.ndarray
    coefficients: np.ndarray

    @property
    def dim(self) -> int:
        return int(self.exponents.shape[1])

    def __len__(self) -> int:
        return int(self.coefficients.shape[0])

    @classmethod
    def monomials(cls, exponents) -> "Polynomials":
        """One polynomial per monomial."""
        e = np.asarray(exponents, dtype=np.int64)
        return cls(e, np.eye(e.shape[0]))

    def monomial_values(self, x) -> np.ndarray:
        """(n_points, n_mono) values of the monomials at points x (n_points, d)."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        return np.prod(x[:, None, :] ** self.exponents[None, :, :], axis=2)

    def monomial_gradients(self, x) -> np.ndarray:
        """(n_points, n_mono, d) derivatives of the monomials at points x."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        e = self.exponents
        out = np.empty((x.shape[0], e.shape[0], self.dim))
        for k in range(self.dim):
            ek = e.copy()
            ek[:, k] = np.maximum(e[:, k] - 1, 0)
            out[:, :, k] = e[None, :, k] * np.prod(x[:, None, :] ** ek[None, :, :], axis=2)
        return out

    def __call__(self, x) -> np.ndarray:
        """(n_points, n_poly) values at points x (n_points, d)."""
        return self.monomial_values(x) @ self.coefficients.T

    def gradient(self, x) -> np.ndarray:
        """(n_points, n_poly, d) gradients at points x."""
        return np.einsum("pmd,km->pkd", self.monomial_gradients(x), self.coefficients)

    def times_zeta(self, zeta_poly) -> "Polynomials":
        """Each 2D polynomial p(ξ, η) times the 1D polynomial q(ζ) = Σ_c zeta_poly[c] ζ^c: a 3D
        list over the monomials ξ^a η^b ζ^c."""
        if self.dim != 2:
            raise ValueError("times_zeta takes a list of 2D polynomials")
        q = np.asarray(zeta_poly, dtype=float)
        exps, cols = [], []
        for c, qc in enumerate(q):
            if qc == 0.0:
                continue
            exps.append(np.column_stack([self.exponents, np.full(len(self.exponents), c)]))
            cols.append(qc * self.coefficients)
        return _combine(np.vstack(exps), np.hstack(cols))


def _combine(exponents, coefficients) -> Polynomials:
    """Polynomials over possibly repeated monomials, with repeats merged."""
    uniq, inverse = np.unique(exponents, axis=0, return_inverse=True)
    c = np.zeros((coefficients.shape[0], uniq.shape[0]))
    np.add.at(c.T, inverse.reshape(-1), coefficients.T)
    return Polynomials(uniq, c)


def direct_sum(*spaces: Polynomials) -> Polynomials:
    """The polynomials of several lists in one list (the span is the sum of the spans)."""
    exps = np.vstack([s.exponents for s in spaces])
    blocks, col = [], 0
    total = exps.shape[0]
    for s in spaces:
        c = np.zeros((len(s), total))
        c[:, col:col + s.exponents.shape[0]] = s.coefficients
        col += s.exponents.shape[0]
        blocks.append(c)
    return _combine(exps, np.vstack(blocks))


def _tensor_2d(p: int) -> Polynomials:
    """Q_p: ξ^a η^b, a, b ≤ p."""
    return Polynomials.monomials([(a, b) for b in range(p + 1) for a in range(p + 1)])


#: the 2D polynomial spaces of the faces
Q1 = _tensor_2d(1)
Q2 = _tensor_2d(2)
Q3 = _tensor_2d(3)
S2 = Polynomials.monomials([(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2), (2, 1), (1, 2)])
#: complete quadratics (total degree ≤ 2) in 2 and 3 variables: the spaces of TRI6 and TET10
P2_2D = Polynomials.monomials([(a, b) for a in range(3) for b in range(3) if a + b <= 2])
P2_3D = Polynomials.monomials([(a, b, c) for a in range(3) for b in range(3) for c in range(3) if a + b + c <= 2])

# ζ-factors of the face layer: L0 = (1 − ζ)/2, L1 = (1 + ζ)/2, B = 1 − ζ² (coefficients of 1, ζ, ζ²)
_L0, _L1, _B = (0.5, -0.5), (0.5, 0.5), (1.0, 0.0, -1.0)


def face_layer_space(bottom: Polynomials, top: Polynomials) -> Polynomials:
    """F_bot·L0 ⊕ F_top·L1 ⊕ Q1·B (module docstring)."""
    return direct_sum(bottom.times_zeta(_L0), top.times_zeta(_L1), Q1.times_zeta(_B))


# ---------------------------------------------------------------------------------------------
# reference nodes
# ---------------------------------------------------------------------------------------------
_CORNERS_2D = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
_MIDS_2D = [(0, -1), (1, 0), (0, 1), (-1, 0)]
_c = LOBATTO4

QUAD8_NODES = np.array(_CORNERS_2D + _MIDS_2D, dtype=float)
QUAD9_NODES = np.array(_CORNERS_2D + _MIDS_2D + [(0, 0)], dtype=float)
#: corners; two nodes per edge in the direction of travel 0→1→2→3→0; interior counter-clockwise
QUAD16_NODES = np.array(
    _CORNERS_2D
    + [(-_c, -1), (_c, -1), (1, -_c), (1, _c), (_c, 1), (-_c, 1), (-1, _c), (-1, -_c)]
    + [(-_c, -_c), (_c, -_c), (_c, _c), (-_c, _c)],
    dtype=float,
)


def _at(z, pts):
    return [(x, y, z) for x, y in pts]


#: VTK quadratic hexahedron: corners (bottom, top), bottom / top edge mid-nodes, vertical mid-nodes
HEX20_NODES = np.array(
    _at(-1, _CORNERS_2D) + _at(1, _CORNERS_2D) + _at(-1, _MIDS_2D) + _at(1, _MIDS_2D)
    + [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
    dtype=float,
)
#: HEX20 + the centre of the contact face ζ = −1 (node 20)
HEX21_NODES = np.vstack([HEX20_NODES, [(0.0, 0.0, -1.0)]])
#: corners 0-7 (as HEX20), contact-face edge nodes 8-15 (QUAD16 order), top-edge mid-nodes 16-19,
#: vertical mid-nodes 20-23, contact-face interior nodes 24-27 (QUAD16 order)
HEX28_NODES = np.vstack([
    HEX20_NODES[:8],
    [(x, y, -1.0) for x, y in QUAD16_NODES[4:12]],
    HEX20_NODES[12:20],
    [(x, y, -1.0) for x, y in QUAD16_NODES[12:16]],
])


# ---------------------------------------------------------------------------------------------
# elements
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Element:
    """A Lagrange element: reference ``nodes`` (n, d) and the polynomial ``space`` they
    interpolate (n polynomials). ``degree`` is the highest power per variable (it sets the
    Gauss rule that integrates a stiffness exactly on affine cells: degree + 1 points per
    direction, :attr:`gauss_counts`; a ``domain="simplex"`` element is on the unit simplex and
takes the simplex rules of :func:`.quadrature.element_rule` instead). ``contact_face`` lists, for a transition element, the local nodes of its
    ζ = −1 face in the order of ``face_element``'s nodes."""

    name: str
    nodes: np.ndarray
    space: Polynomials
    face_element: "Element | None" = None
    contact_face: tuple[int, ...] = ()
    domain: str = "cube"
    _inverse: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        if self.domain not in ("cube", "simplex"):
            raise ValueError(f"{self.name}: domain must be 'cube' or 'simplex', got {self.domain!r}")
        nodes = np.asarray(self.nodes, dtype=float)
        if nodes.ndim != 2 or nodes.shape[1] != self.space.dim or nodes.shape[0] != len(self.space):
            raise ValueError(f"{self.name}: {nodes.shape[0]} nodes in {nodes.shape[1]}D do not fit a "
                             f"{len(self.space)}-dimensional space in {self.space.dim}D")
        V = self.space(nodes)
        cond = np.linalg.cond(V)
        if not cond < 1e8:
            raise ValueError(f"{self.name}: the nodes are not unisolvent for the space (cond(V) = {cond:.3g})")
        object.__setattr__(self, "nodes", nodes)
        object.__setattr__(self, "_inverse", np.linalg.inv(V))

    @property
    def n_nodes(self) -> int:
        return int(self.nodes.shape[0])

    @property
    def dim(self) -> int:
        return int(self.nodes.shape[1])

    @property
    def degree(self) -> tuple[int, ...]:
        """Highest exponent of each variable in the space."""
        used = np.abs(self.space.coefficients).max(axis=0) > 0
        return tuple(int(d) for d in self.space.exponents[used].max(axis=0))

    def shape(self, x) -> np.ndarray:
        """Shape functions N (n_points, n_nodes) at reference points x (n_points, d)."""
        return self.space(x) @ self._inverse

    def shape_gradients(self, x) -> np.ndarray:
        """Reference gradients dN/dξ (n_points, n_nodes, d) at reference points x."""
        return np.einsum("pkd,kn->pnd", self.space.gradient(x), self._inverse)

    @property
    def gauss_counts(self) -> tuple[int, ...]:
        """Gauss points per direction that integrate the stiffness exactly on affine cells
        (degree + 1 in each variable: 3×3×3 for HEX20/HEX21, 4×4×3 for HEX28)."""
        return tuple(d + 1 for d in self.degree)


def _face_nodes(nodes3d, face2d) -> tuple[int, ...]:
    """Local indices of the 3D nodes lying on ζ = −1 at the 2D face nodes' positions."""
    out = []
    for x, y in face2d:
        hit = np.flatnonzero(np.all(np.isclose(nodes3d, (x, y, -1.0), atol=1e-12), axis=1))
        if hit.size != 1:
            raise ValueError(f"no unique node at ({x}, {y}, -1)")
        out.append(int(hit[0]))
    return tuple(out)


QUAD8 = Element("quad8", QUAD8_NODES, S2)
QUAD9 = Element("quad9", QUAD9_NODES, Q2)
QUAD16 = Element("quad16", QUAD16_NODES, Q3)
HEX20 = Element("hex20", HEX20_NODES, face_layer_space(S2, S2), QUAD8, _face_nodes(HEX20_NODES, QUAD8_NODES))
HEX21 = Element("hex21", HEX21_NODES, face_layer_space(Q2, S2), QUAD9, _face_nodes(HEX21_NODES, QUAD9_NODES))
HEX28 = Element("hex28", HEX28_NODES, face_layer_space(Q3, S2), QUAD16, _face_nodes(HEX28_NODES, QUAD16_NODES))


#: CalculiX C3D10 / S6 reference nodes (module docstring)
TRI6_NODES = np.array([(0, 0), (1, 0), (0, 1), (0.5, 0), (0.5, 0.5), (0, 0.5)], dtype=float)
_TET_CORNERS = np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], dtype=float)
_TET_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
TET10_NODES = np.vstack([_TET_CORNERS] + [[(_TET_CORNERS[i] + _TET_CORNERS[j]) / 2] for i, j in _TET_EDGES])


def _tet_faces() -> dict[int, tuple[int, ...]]:
    """{S: TRI6 node list} of the faces S1-S4 (0-based TET10 indices), outward: CalculiX's inward
    corner triples (1-2-3, 1-4-2, 2-4-3, 3-4-1) reversed, mid-side nodes found by position."""
    out = {}
    for s, (a, b, c) in enumerate(((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0)), start=1):
        corners = (a, c, b)
        mids = []
        for i, j in zip(corners, corners[1:] + corners[:1]):
            mid = (TET10_NODES[i] + TET10_NODES[j]) / 2
            mids.append(int(np.flatnonzero(np.all(np.isclose(TET10_NODES, mid), axis=1))[0]))
        out[s] = corners + tuple(mids)
    return out


TRI6 = Element("tri6", TRI6_NODES, P2_2D, domain="simplex")
TET10 = Element("tet10", TET10_NODES, P2_3D, TRI6, domain="simplex")
#: faces S1-S4 of TET10 as TRI6 node lists (0-based), ∂x/∂u × ∂x/∂v outward
TET10_FACES = _tet_faces()

#: every element by name
ELEMENTS = {e.name: e for e in (QUAD8, QUAD9, QUAD16, HEX20, HEX21, HEX28, TRI6, TET10)}
