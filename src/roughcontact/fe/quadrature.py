"""Tensor-product integration rules on [-1, 1]^d: Gauss–Legendre and Gauss–Lobatto.

Gauss–Legendre with n points integrates polynomials of degree 2n − 1 exactly; Gauss–Lobatto
with n points (end points included) degree 2n − 3. The n-point Lobatto abscissae are the nodes
of the interface elements' faces (n = 3: 0, ±1; n = 4: ±1, ±1/√5), so a Lobatto rule on an
interface element samples the law at its nodes ("nodal integration", docs/fe.md).

Simplex rules on the unit triangle (area 1/2) and the unit tetrahedron (volume 1/6), weights
summing to those measures (:func:`simplex_rule`):

* ``tet4``  4 points, degree 2 (Hammer, Marlowe & Stroud 1956; Keast 1986, rule 2): the
  points a, a, a / b, a, a ... with a = (5 − √5)/20, b = (5 + 3√5)/20, weights 1/24. It
  integrates the stiffness of an affine quadratic tetrahedron (∇N·∇N of degree 2) exactly.
* ``tri6``  6 points, degree 4, positive weights (Dunavant 1985, degree-4 rule; Strang & Fix
  1973): N_a × a quadratic traction exactly on flat TRI6 faces.
* ``tri_midedge``  the three edge mid-points, weights 1/6 each, degree 2 (Strang & Fix 1973):
  the nodal rule of the 6-node triangle, whose corner weights ∫N_corner dA vanish.
* :func:`collapsed_rule`: Stroud's conical product (Duffy) rule, n^d Gauss–Legendre points on
  the cube mapped onto the simplex with the Jacobian in the weights (Stroud 1971, ch. 2.7),
  exact to degree 2n − d; used as an independent reference in the tests.
"""

from __future__ import annotations

import functools
import itertools
import math
from typing import NamedTuple

import numpy as np
from numpy.polynomial import legendre

from ..limits import describe

__all__ = ["Rule", "gauss_legendre", "gauss_lobatto", "tensor_rule", "RULES", "simplex_rule",
           "collapsed_rule", "element_rule", "SIMPLEX_RULES"]


class Rule(NamedTuple):
    """Points (n, d) and weights (n,) of an integration rule on [-1, 1]^d (read-only arrays:
    the rules are cached)."""

    points: np.ndarray
    weights: np.ndarray


def _frozen(points, weights) -> Rule:
    points, weights = np.array(points, dtype=float), np.array(weights, dtype=float)
    points.flags.writeable = weights.flags.writeable = False
    return Rule(points, weights)


@functools.lru_cache(maxsize=None)
def gauss_legendre(n: int) -> Rule:
    """n-point Gauss–Legendre rule on [-1, 1] (points (n, 1))."""
    if n < 1:
        raise ValueError(f"a Gauss rule needs n >= 1 points, got {n}")
    x, w = legendre.leggauss(n)
    return _frozen(x[:, None], w)


@functools.lru_cache(maxsize=None)
def gauss_lobatto(n: int) -> Rule:
    """n-point Gauss–Lobatto rule on [-1, 1] (end points included; points (n, 1)): the interior
    points are the roots of P'_{n−1}, the weights 2/(n(n−1) P_{n−1}(x)²)."""
    if n < 2:
        raise ValueError(f"a Lobatto rule needs n >= 2 points, got {n}")
    c = np.zeros(n)
    c[-1] = 1.0  # P_{n-1}
    interior = np.sort(legendre.legroots(legendre.legder(c))) if n > 2 else np.empty(0)
    x = np.concatenate([[-1.0], interior, [1.0]])
    w = 2.0 / (n * (n - 1) * legendre.legval(x, c) ** 2)
    return _frozen(x[:, None], w)


RULES = {"gauss": gauss_legendre, "lobatto": gauss_lobatto}


def tensor_rule(kind: str, counts) -> Rule:
    """Tensor product of 1D rules of ``kind`` ("gauss" | "lobatto") with ``counts`` points per
    direction (a sequence of ints); the first coordinate varies fastest."""
    return _tensor_rule(kind, tuple(int(n) for n in counts))


@functools.lru_cache(maxsize=None)
def _tensor_rule(kind: str, counts: tuple[int, ...]) -> Rule:
    try:
        one = RULES[kind]
    except KeyError:
        raise ValueError(f"rule kind must be one of {sorted(RULES)}, got {describe(kind)}") from None
    rules = [one(int(n)) for n in counts]
    pts = np.array([p[::-1] for p in itertools.product(*[r.points[:, 0] for r in reversed(rules)])])
    wts = np.array([np.prod(w[::-1]) for w in itertools.product(*[r.weights for r in reversed(rules)])])
    return _frozen(pts.reshape(-1, len(counts)), wts)


def _orbit(weight: float, *bary) -> tuple[list, list]:
    """The distinct permutations of barycentric coordinates ``bary`` (summing to 1) as Cartesian
    points (the last d of the d + 1 coordinates), each with ``weight``."""
    pts = sorted(set(itertools.permutations(bary)))
    return [p[1:] for p in pts], [weight] * len(pts)


def _tet4() -> Rule:
    a, b = (5.0 - math.sqrt(5.0)) / 20.0, (5.0 + 3.0 * math.sqrt(5.0)) / 20.0
    return _frozen(*_orbit(1.0 / 24.0, b, a, a, a))


def _tri6() -> Rule:
    # Dunavant (1985), degree 4: two orbits of 3 points (weights for area 1, halved here)
    p1, w1 = _orbit(0.223381589678011 / 2.0, 1.0 - 2.0 * 0.445948490915965, 0.445948490915965, 0.445948490915965)
    p2, w2 = _orbit(0.109951743655322 / 2.0, 1.0 - 2.0 * 0.091576213509771, 0.091576213509771, 0.091576213509771)
    return _frozen(p1 + p2, w1 + w2)


def _tri_midedge() -> Rule:
    return _frozen([(0.5, 0.0), (0.5, 0.5), (0.0, 0.5)], [1.0 / 6.0] * 3)


SIMPLEX_RULES = {"tet4": _tet4, "tri6": _tri6, "tri_midedge": _tri_midedge}


@functools.lru_cache(maxsize=None)
def simplex_rule(name: str) -> Rule:
    """A rule on the unit simplex by name (module docstring): "tet4", "tri6", "tri_midedge"."""
    try:
        return SIMPLEX_RULES[name]()
    except KeyError:
        raise ValueError(f"simplex rule must be one of {sorted(SIMPLEX_RULES)}, got {describe(name)}") from None


@functools.lru_cache(maxsize=None)
def collapsed_rule(dim: int, n: int) -> Rule:
    """Stroud's conical product rule on the unit simplex of dimension ``dim`` (2 or 3) with n
    Gauss–Legendre points per direction: x1 = s1, x2 = (1 − s1) s2, x3 = (1 − s1)(1 − s2) s3
    for s in [0, 1]^dim, weight × (1 − s1)^(dim−1) (1 − s2)^(dim−2)."""
    if dim not in (2, 3):
        raise ValueError(f"collapsed_rule: dim must be 2 or 3, got {describe(dim)}")
    cube = tensor_rule("gauss", (n,) * dim)
    s = (cube.points + 1.0) / 2.0
    w = cube.weights / 2.0 ** dim
    x = np.empty_like(s)
    rest = np.ones(len(s))
    for k in range(dim):
        x[:, k] = rest * s[:, k]
        w = w * (1.0 - s[:, k]) ** (dim - 1 - k)
        rest = rest * (1.0 - s[:, k])
    return _frozen(x, w)


def element_rule(element) -> Rule:
    """The default bulk or face rule of an element: Gauss–Legendre with degree + 1 points per
    direction on the cube; on the simplex "tet4" (3D) or "tri6" (2D). Exact for the stiffness of
    affine cells and for N_a × a linear traction on flat faces."""
    if getattr(element, "domain", "cube") == "simplex":
        return simplex_rule("tet4" if element.dim == 3 else "tri6")
    return tensor_rule("gauss", tuple(d + 1 for d in element.degree))
