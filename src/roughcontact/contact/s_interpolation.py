"""Curves over the separation s from a verified Chebyshev interpolant (issue 13).

A contact curve (A/A0, W/A0, K/A0 and their parts against s = h/√m00) is smooth in s, and
ln of a positive quantity is nearly quadratic (the summit heights are Gaussian). When a curve
asks for more separations than an interpolant needs nodes, :func:`interpolated_columns`
evaluates the model at Chebyshev–Lobatto nodes in s on [min s, max s] (8, 16, 32, 64
intervals, nested) and interpolates ln|f| (or f itself where a column changes sign or has
zeros) barycentrically. Each grid is *verified*: the model is evaluated directly at the
N points halfway between the nodes of the N-interval grid (the odd nodes of the 2N grid) and
the interpolant must agree with it there to ``rtol`` (relative to each column, or to 1e-3 of
its total for a part below that: the convention of the presets' bounds); the curve then comes
from the finer 2N grid, and the measured error of the coarser one is reported as the bound.
If that does not happen before the nodes outnumber the requested points, every point is
evaluated directly. Pure numerics: the model enters as a function of an s-array.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

__all__ = ["SInterpolation", "lobatto_nodes", "barycentric", "interpolated_columns", "interpolated_columns_many"]

#: Chebyshev–Lobatto grids tried: 8, 16, 32, 64 intervals
N_START = 8
N_MAX = 64
#: relative floor of a part against its total (the presets' bounds hold parts above 1e-3 of
#: their total to rtol, smaller parts to rtol × 1e-3 of the total)
PART_FLOOR = 1e-3


@dataclass(frozen=True)
class SInterpolation:
    """How a curve was obtained. ``nodes``: model evaluations (0: direct at every point);
    ``intervals``: N of the grid the curve comes from; ``error``: the measured max relative
    error of the N/2 grid's interpolant at the points between its nodes (the bound stated for
    the curve; nan if direct); ``rtol``: the tolerance asked for."""

    method: str  # "chebyshev" | "direct"
    nodes: int
    intervals: int
    error: float
    rtol: float

    def as_attrs(self, prefix: str = "s_interpolation") -> dict:
        return {prefix: self.method, f"{prefix}_nodes": self.nodes, f"{prefix}_intervals": self.intervals,
                f"{prefix}_error": self.error, f"{prefix}_rtol": self.rtol}


def lobatto_nodes(lo: float, hi: float, n: int) -> np.ndarray:
    """The n + 1 Chebyshev–Lobatto points of [lo, hi], from hi down to lo (k = 0 … n)."""
    x = np.cos(math.pi * np.arange(n + 1) / n)
    return 0.5 * (hi + lo) + 0.5 * (hi - lo) * x


def barycentric(nodes: np.ndarray, values: np.ndarray, s: np.ndarray) -> np.ndarray:
    """The polynomial through (nodes, values[k, :]) on Chebyshev–Lobatto nodes at the points s
    (second barycentric form, weights (−1)^k halved at the ends; exact at the nodes)."""
    n = nodes.size - 1
    w = (-1.0) ** np.arange(n + 1)
    w[0] *= 0.5
    w[-1] *= 0.5
    d = s[:, None] - nodes[None, :]
    hit = d == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        c = w[None, :] / d
        out = (c @ values) / c.sum(axis=1)[:, None]
    rows, cols = np.nonzero(hit)
    out[rows] = values[cols]
    return out


def _transform(values: np.ndarray):
    """Per column: ln|f| with its sign where the column has one sign and no zero, else f."""
    sign = np.sign(values)
    logged = np.all(sign == sign[:1], axis=0) & np.all(sign != 0, axis=0)
    t = values.copy()
    t[:, logged] = np.log(np.abs(values[:, logged]))
    return t, logged, sign[0]


def _back(t: np.ndarray, logged, sign) -> np.ndarray:
    out = t.copy()
    out[:, logged] = sign[logged] * np.exp(t[:, logged])
    return out


def _interpolate(nodes, values, s) -> np.ndarray:
    t, logged, sign = _transform(values)
    return _back(barycentric(nodes, t, s), logged, sign)


def _relative_error(approx, exact, totals: Sequence[Sequence[int]]) -> float:
    """max |approx − exact| / max(|exact|, PART_FLOOR |exact total|) over points and columns;
    column q's total is the sum of the columns totals[q] (q alone for a total)."""
    total = np.stack([exact[:, list(group)].sum(axis=1) for group in totals], axis=1)
    scale = np.maximum(np.abs(exact), PART_FLOOR * np.abs(total))
    err = np.abs(approx - exact)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(scale > 0.0, err / scale, np.where(err > 0.0, np.inf, 0.0))
    return float(np.max(rel))


def interpolated_columns(evaluate: Callable[[np.ndarray], np.ndarray], s, rtol: float,
                         totals: Sequence[Sequence[int]], *, min_points: int = 48):
    """The model's columns at the separations ``s`` (shape (len(s), n_columns)) and the
    :class:`SInterpolation` that says how.

    ``evaluate(s_array)`` returns the columns at those separations (finite). With fewer than
    ``min_points`` distinct separations, or when no verified grid is cheaper than the points
    themselves, every point is evaluated directly."""
    cols, how = interpolated_columns_many(lambda x, active: evaluate(x)[:, None, :], s, 1, rtol, totals,
                                          min_points=min_points)
    return cols[:, 0], how[0]


def interpolated_columns_many(evaluate: Callable[[np.ndarray, np.ndarray], np.ndarray], s, n_models: int,
                              rtol: float, totals: Sequence[Sequence[int]], *, min_points: int = 48):
    """:func:`interpolated_columns` for ``n_models`` models sharing their evaluations (e.g. the
    materials of one surface, whose hyperbola integrals are computed once per separation):
    ``evaluate(s_array, models)`` returns (len(s_array), len(models), n_columns) for the model
    indices ``models``. Each model's grid is chosen and verified on its own columns exactly as
    :func:`interpolated_columns` would for it alone (the same nodes, the same check, so the same
    numbers); models still unverified are evaluated on the finer grid. Returns
    (columns (len(s), n_models, n_columns), [SInterpolation per model])."""
    s = np.asarray(s, dtype=float)
    lo, hi = float(s.min()), float(s.max())
    distinct = np.unique(s).size
    everyone = np.arange(n_models)
    if distinct < min_points or hi <= lo:
        return evaluate(s, everyone), [SInterpolation("direct", s.size, 0, math.nan, rtol)] * n_models
    n = N_START
    nodes = lobatto_nodes(lo, hi, n)
    values = evaluate(nodes, everyone)
    spent = n + 1
    result = np.empty((s.size, n_models, values.shape[2]))
    how: list[SInterpolation | None] = [None] * n_models
    active = everyone
    spent_at = np.zeros(n_models, dtype=int)  # evaluations when a model fell back to every point
    while active.size and 2 * n + 1 <= distinct and n <= N_MAX:
        fine = lobatto_nodes(lo, hi, 2 * n)
        between = fine[1::2]
        finite = np.array([np.all(np.isfinite(values[:, k])) for k in active])
        spent_at[active[~finite]] = spent
        active = active[finite]
        if not active.size:
            break
        direct = evaluate(between, active)
        spent += n
        merged = np.empty((2 * n + 1, n_models, values.shape[2]))
        merged[0::2] = values
        merged[1::2][:, active] = direct
        still = []
        for j, k in enumerate(active):
            error = _relative_error(_interpolate(nodes, values[:, k], between), direct[:, j], totals)
            if error <= rtol:
                result[:, k] = _interpolate(fine, merged[:, k], s)
                how[k] = SInterpolation("chebyshev", spent, 2 * n, error, rtol)
            else:
                still.append(k)
        active = np.array(still, dtype=int)
        nodes, values = fine, merged
        n *= 2
    spent_at[active] = spent
    rest = np.array([k for k in everyone if how[k] is None], dtype=int)
    if rest.size:
        result[:, rest] = evaluate(s, rest)
        for k in rest:
            how[k] = SInterpolation("direct", int(spent_at[k]) + s.size, 0, math.nan, rtol)
    return result, how
