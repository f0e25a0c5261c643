"""Missing data in a measured height map (NaN: the instrument's dropouts): how much is missing,
and filling it by a stated method.

Optical instruments lose points on steep slopes, dark or specular spots and at the edge of the
field; the derivative estimator of :mod:`.derivatives` works around them, the periodogram needs a
complete map. ``fill="harmonic"`` replaces every missing point by the solution of Laplace's
equation ∇²z = 0 (the 5-point stencil) with the measured points as boundary values and zero
normal slope at the map's edges — the smoothest surface through the hole's rim (as Gwyddion's
"Laplace interpolation"). A harmonic patch has no curvature of its own (z_xx = −z_yy), so the
curvature moments of a filled map are biased low by about the missing fraction: prefer the
estimator's own handling (``fill="none"``) for m40, m04.
"""

from __future__ import annotations

import numpy as np

__all__ = ["FILLS", "MAX_MISSING", "missing_fraction", "fill_harmonic"]

FILLS = ("none", "harmonic")
#: a map with more than this fraction missing is refused: its moments would describe the
#: rims of the holes more than the surface
MAX_MISSING = 0.5


def missing_fraction(z) -> float:
    """The fraction of the map's points that are not finite."""
    z = np.asarray(z, dtype=float)
    return float(np.mean(~np.isfinite(z))) if z.size else 1.0


def fill_harmonic(z) -> np.ndarray:
    """A copy of the 2-d map z with every NaN replaced by the harmonic interpolant of the
    measured points (module docstring): a sparse 5-point Laplace system in the missing points."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    z = np.array(z, dtype=float)
    hole = ~np.isfinite(z)
    n = int(hole.sum())
    if n == 0:
        return z
    if n == z.size:
        raise ValueError("the map has no measured point to fill from")
    index = -np.ones(z.shape, dtype=np.int64)
    index[hole] = np.arange(n)
    iy, ix = np.nonzero(hole)
    rows, cols, vals = [], [], []
    rhs = np.zeros(n)
    diag = np.zeros(n)
    for di, dj in ((-1, 0), (1, 0), (0, -1), (0, 1)):
        ny_, nx_ = iy + di, ix + dj
        inside = (ny_ >= 0) & (ny_ < z.shape[0]) & (nx_ >= 0) & (nx_ < z.shape[1])
        diag[inside] += 1.0  # a neighbour outside the map: zero normal slope (no term)
        k = np.nonzero(inside)[0]
        neighbour = index[ny_[k], nx_[k]]
        unknown = neighbour >= 0
        rows.append(k[unknown])
        cols.append(neighbour[unknown])
        vals.append(-np.ones(int(unknown.sum())))
        rhs[k[~unknown]] += z[ny_[k[~unknown]], nx_[k[~unknown]]]
    rows.append(np.arange(n))
    cols.append(np.arange(n))
    vals.append(diag)
    A = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)).tocsr()
    z[hole] = spsolve(A, rhs)
    return z
