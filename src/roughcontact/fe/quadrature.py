"""Tensor-product integration rules on [-1, 1]^d: Gauss–Legendre and Gauss–Lobatto.

Gauss–Legendre with n points integrates polynomials of degree 2n − 1 exactly; Gauss–Lobatto
with n points (end points included) degree 2n − 3. The n-point Lobatto abscissae are the nodes
of the interface elements' faces (n = 3: 0, ±1; n = 4: ±1, ±1/√5), so a Lobatto rule on an
interface element samples the law at its nodes ("nodal integration", docs/fe.md).
"""

from __future__ import annotations

import functools
import itertools
from typing import NamedTuple

import numpy as np
from numpy.polynomial import legendre

from ..limits import describe

__all__ = ["Rule", "gauss_legendre", "gauss_lobatto", "tensor_rule", "RULES"]


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
