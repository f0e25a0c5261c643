"""Gauss–Legendre / Gauss–Lobatto rules: exactness degree, node sets, tensor products."""

from __future__ import annotations

import math

import numpy as np
import pytest

from roughcontact.fe.element import QUAD9_NODES, QUAD16_NODES
from roughcontact.fe.quadrature import gauss_legendre, gauss_lobatto, tensor_rule

# Exact integrals of (x + A)^k, k <= 14, are sums of terms up to 1.3^15 ≈ 50 and the rules sum
# n <= 7 such terms: round-off is ≲ 50 · 1e-16 · a few ≈ 2e-14, so 1e-13 separates "exact" from
# "not exact". Beyond the exactness degree the error is checked against the classical error
# constant (it is 2e-4 … 1.3, far above 1e-13).
EXACT = 1e-13
A = 0.3  # shift: (x + A)^k has odd and even parts, so symmetry does not make a rule look exact


def _integral(k: int) -> float:
    """∫_{-1}^{1} (x + A)^k dx."""
    return ((1 + A) ** (k + 1) - (A - 1) ** (k + 1)) / (k + 1)


def _error(rule, k: int) -> float:
    """∫ (x + A)^k − rule((x + A)^k)."""
    x, w = rule.points[:, 0], rule.weights
    return _integral(k) - w @ (x + A) ** k


@pytest.mark.parametrize("n", range(1, 8))
def test_gauss_exact_to_2n_minus_1(n):
    rule = gauss_legendre(n)
    assert max(abs(_error(rule, k)) for k in range(2 * n)) < EXACT
    # and not beyond: for a polynomial of degree 2n with leading coefficient 1 the error is the
    # Gauss error constant 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2) (Abramowitz & Stegun 25.4.29)
    f = math.factorial
    constant = 2 ** (2 * n + 1) * f(n) ** 4 / ((2 * n + 1) * f(2 * n) ** 2)
    assert abs(_error(rule, 2 * n) - constant) < EXACT


@pytest.mark.parametrize("n", range(2, 8))
def test_lobatto_exact_to_2n_minus_3(n):
    rule = gauss_lobatto(n)
    assert rule.points[0, 0] == -1.0 and rule.points[-1, 0] == 1.0  # end points included
    assert max(abs(_error(rule, k)) for k in range(2 * n - 2)) < EXACT
    # not beyond: degree 2n − 2 has the Lobatto error constant
    # −n (n−1)³ 2^(2n−1) ((n−2)!)⁴ / ((2n−1) ((2n−2)!)²) (A & S 25.4.32)
    f = math.factorial
    constant = -n * (n - 1) ** 3 * 2 ** (2 * n - 1) * f(n - 2) ** 4 / ((2 * n - 1) * f(2 * n - 2) ** 2)
    assert abs(_error(rule, 2 * n - 2) - constant) < EXACT


def test_lobatto_nodes_are_the_face_abscissae():
    # QUAD9 nodes at 0, ±1; QUAD16 nodes at ±1, ±1/√5 (the paper's Fig. 11); values written
    # here independently of the code under test. 1e-15: one rounding of legroots / sqrt.
    assert np.allclose(gauss_lobatto(3).points[:, 0], [-1.0, 0.0, 1.0], rtol=0, atol=1e-15)
    c = 1 / math.sqrt(5)
    assert np.allclose(gauss_lobatto(4).points[:, 0], [-1.0, -c, c, 1.0], rtol=0, atol=1e-15)
    assert np.allclose(gauss_lobatto(4).weights, [1 / 6, 5 / 6, 5 / 6, 1 / 6], rtol=0, atol=1e-15)
    for n, nodes in ((3, QUAD9_NODES), (4, QUAD16_NODES)):
        abscissae = np.unique(np.round(nodes, 14))
        assert np.allclose(abscissae, gauss_lobatto(n).points[:, 0], rtol=0, atol=1e-14)


@pytest.mark.parametrize("kind, counts", [("gauss", (3,)), ("gauss", (2, 3)), ("gauss", (4, 4, 3)),
                                          ("lobatto", (3, 3)), ("lobatto", (4, 2, 3))])
def test_tensor_rule(kind, counts):
    rule = tensor_rule(kind, counts)
    d = len(counts)
    assert rule.points.shape == (math.prod(counts), d)
    assert abs(rule.weights.sum() - 2.0 ** d) < EXACT * 2 ** d  # the volume of [-1, 1]^d
    # first coordinate varies fastest
    one = (gauss_legendre if kind == "gauss" else gauss_lobatto)(counts[0]).points[:, 0]
    assert np.array_equal(rule.points[: counts[0], 0], one)
    # a product of per-direction monomials at the highest exact degree of each direction
    top = [2 * n - 1 if kind == "gauss" else 2 * n - 3 for n in counts]
    exact = math.prod(_integral(k) for k in top)
    assert abs(rule.weights @ np.prod((rule.points + A) ** top, axis=1) - exact) < EXACT * 10


def test_invalid_counts():
    with pytest.raises(ValueError):
        gauss_legendre(0)
    with pytest.raises(ValueError):
        gauss_lobatto(1)
    with pytest.raises(ValueError):
        tensor_rule("newton", (2, 2))
