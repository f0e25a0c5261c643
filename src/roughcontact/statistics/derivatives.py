"""Derivative fields of a sampled height map with missing points: finite differences whose
stencils adapt to the map's edges and to dropouts.

A first derivative at a measured point is Σ_j w_j z(x + o_j h)/h over stencil nodes o_j (integer
offsets, times the sampling interval h and a ``step`` for coarser scales), with the weights that
make it exact for polynomials of degree n − 1 on those n nodes (the Vandermonde conditions
Σ_j w_j o_j^k = δ_k1, k = 0 … n − 1; Fornberg 1988, Math. Comp. 51, 699):

* where the 2r + 1 points −r … r around the point are all measured, the central stencil of
  order 2r (``order`` = 2, 4, 6, 8; transfer function q (1 − c (qh)^{2r}), e.g. (qh)⁶/140 for
  order 6);
* where a dropout or the map's edge interrupts it, the 2r + 3 measured points nearest to the point
  (within 2r + 2 samples along the line): an off-centre stencil one order higher, because its
  error constant is larger than the central one's and in a rotated frame its error leaks into
  the small along-lay moments;
* where fewer are measured, the point is left out (NaN): its derivative is not estimated.

Off-centre stencils amplify wavenumbers near the Nyquist limit (their transfer function is not
bounded by the central one's): on a map that does not resolve its spectrum they can dominate the
curvature moments. ``off_centre=False`` keeps only the central stencils (:mod:`.measure` compares
the two and falls back to it, with a warning, when they disagree; the coarser scales use it).

Second derivatives are the first-derivative stencil applied twice (z_xx = D_x D_x z,
z_xy = D_y D_x z), so that the three second derivatives share one transfer function per axis and a
directional curvature c² z_xx + 2cs z_xy + s² z_yy of a wave across the lay cancels as the exact one
does (a compact z_xx stencil beside a product z_xy stencil does not cancel: the old estimator's
m40 error at oblique lays).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

__all__ = ["ORDERS", "stencil_weights", "first_derivative", "derivative_fields"]

#: accuracy orders of the central stencils
ORDERS = (2, 4, 6, 8)


def stencil_weights(offsets) -> np.ndarray:
    """Weights w_j with Σ_j w_j f(o_j h) = h f'(0) exactly for polynomials of degree < n on the
    n distinct integer ``offsets`` o_j (the Vandermonde conditions of the module docstring)."""
    o = np.asarray(offsets, dtype=float)
    if o.ndim != 1 or o.size < 2 or np.unique(o).size != o.size:
        raise ValueError(f"offsets must be at least two distinct numbers, got {offsets!r}")
    A = np.vander(o, o.size, increasing=True).T  # row k: o_j^k
    b = np.zeros(o.size)
    b[1] = 1.0
    return np.linalg.solve(A, b)


@lru_cache(maxsize=65536)
def _nodes(code: int, r: int) -> tuple[tuple[int, ...], tuple[float, ...]] | None:
    """Off-centre stencil nodes and weights for the pattern ``code`` (bit o + W set where
    offset o is measured, W = 2r + 2): the 2r + 3 measured offsets nearest to 0, or None where
    fewer are measured."""
    W = 2 * r + 2
    measured = [o for o in range(-W, W + 1) if code >> (o + W) & 1]
    n = 2 * r + 3
    if len(measured) < n:
        return None
    nodes = sorted(sorted(measured, key=lambda o: (abs(o), o))[:n])
    return tuple(nodes), tuple(stencil_weights(nodes))


def first_derivative(z, h: float, axis: int, *, order: int = 6, step: int = 1,
                     off_centre: bool = True) -> np.ndarray:
    """∂z/∂(axis) [unit of z per unit of h] at every measured (finite) point of the 2-d array z
    sampled at interval h along ``axis``, with the stencils of the module docstring at spacing
    step·h (step > 1: the derivative the map has when sampled at step·h, from all its points).
    NaN where z is NaN or too few points are measured around the point; with
    ``off_centre=False`` also where the central stencil does not fit."""
    if order not in ORDERS:
        raise ValueError(f"order must be one of {ORDERS}, got {order!r}")
    r, W = order // 2, order + 2
    zz = np.moveaxis(np.asarray(z, dtype=float), axis, -1)
    n = zz.shape[-1]
    pad = W * step
    values = np.full(zz.shape[:-1] + (n + 2 * pad,), np.nan)
    values[..., pad:pad + n] = zz
    # the central stencil everywhere at once (NaN wherever one of its nodes is missing)
    central = stencil_weights(range(-r, r + 1))
    out = np.zeros(zz.shape)
    for o, w in zip(range(-r, r + 1), central):
        if o:
            out += w * values[..., pad + o * step:pad + o * step + n]
    out /= h * step
    out[~np.isfinite(zz)] = np.nan  # only the measured points have a derivative
    if off_centre:
        _off_centre(out, values, np.isfinite(zz) & np.isnan(out), r, W, pad, step, h)
    return np.moveaxis(out, -1, axis)


def _off_centre(out, values, where, r, W, pad, step, h) -> None:
    """Fill ``out`` at the points ``where`` (measured, central stencil incomplete) with the
    off-centre stencils of the module docstring: each point's measured pattern within ±W
    samples (one bit per offset) selects its nodes and weights."""
    idx = np.nonzero(where)
    if idx[0].size == 0:
        return
    lead, pos = idx[:-1], idx[-1] + pad
    measured = np.isfinite(values)
    code = np.zeros(pos.size, dtype=np.int64)
    for o in range(-W, W + 1):
        code |= measured[lead + (pos + o * step,)].astype(np.int64) << (o + W)
    codes, inverse = np.unique(code, return_inverse=True)
    width = 2 * r + 3
    offsets = np.zeros((codes.size, width), dtype=np.int64)
    weights = np.zeros((codes.size, width))
    usable = np.zeros(codes.size, dtype=bool)
    for k, c in enumerate(codes):
        found = _nodes(int(c), r)
        if found is not None:
            nodes, w = found
            offsets[k, :len(nodes)], weights[k, :len(w)] = nodes, w
            usable[k] = True
    acc = np.zeros(pos.size)
    for j in range(width):
        node = values[lead + (pos + offsets[inverse, j] * step,)]
        acc += weights[inverse, j] * np.where(np.isfinite(node), node, 0.0)  # padding nodes have weight 0
    acc[~usable[inverse]] = np.nan
    out[idx] = acc / (h * step)


def derivative_fields(z, dx: float, dy: float, *, order: int = 6, step: int = 1,
                      off_centre: bool = True) -> dict[str, np.ndarray]:
    """z_x, z_y, z_xx, z_xy, z_yy of a map z[i, j] at x = j·dx, y = i·dy (NaN = not measured;
    module docstring), at spacing step·dx, step·dy."""
    options = {"order": order, "step": step, "off_centre": off_centre}
    zx = first_derivative(z, dx, 1, **options)
    zy = first_derivative(z, dy, 0, **options)
    return {
        "zx": zx, "zy": zy,
        "zxx": first_derivative(zx, dx, 1, **options),
        "zxy": first_derivative(zx, dy, 0, **options),
        "zyy": first_derivative(zy, dy, 0, **options),
    }
