"""Form removal before the moments are measured (statistics.measure, ``detrend``): the mean, the
least-squares plane, a polynomial of total degree 2–4, or a sphere (its radius reported), fitted
over the measured points of a height map z[i, j] at x = j·dx, y = i·dy [L]. A sphere's or a
cylinder's curvature left in the map stays in m00 and m20 (the derivative fields are centred, so
a constant curvature leaves m40 and m04 as they are).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["FIT_POINTS", "remove_form"]

#: a form is fitted on at most about this many measured points (a regular subsample of larger maps:
#: the fit's matrix of up to 15 columns then takes ≤ 130 MB on an 8192² map; measured on a 2048²
#: map, the plane from every 4th point differs from all points' by 1.3e-4 Sq, m00 by 5e-9)
FIT_POINTS = 2**20


def _coordinates(shape, dx, dy):
    """x = j dx, y = i dy [L] of every point of a map of ``shape``."""
    ny, nx = shape
    return np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")[::-1]


def _fit_points(ok):
    """Flat indices of the measured points a form is fitted on: all of them, or on a map with
    more than FIT_POINTS a regular subsample of about FIT_POINTS (every k-th in row order)."""
    idx = np.flatnonzero(ok)
    return idx[::-(-idx.size // FIT_POINTS)]


def _poly_form(z, ok, x, y, degree):
    """The least-squares polynomial of total degree ``degree`` in x, y over the measured points
    (:func:`_fit_points`; coordinates centred and scaled to [-1, 1], which keeps the monomials'
    matrix conditioned), evaluated on the whole map."""
    u = (x - x.mean()) / max(np.ptp(x) / 2, 1e-300)
    v = (y - y.mean()) / max(np.ptp(y) / 2, 1e-300)
    terms = [(i, d - i) for d in range(degree + 1) for i in range(d + 1)]
    fit = _fit_points(ok)
    uf, vf = u.ravel()[fit], v.ravel()[fit]
    A = np.column_stack([uf**i * vf**j for i, j in terms])
    coef, *_ = np.linalg.lstsq(A, z.ravel()[fit], rcond=None)
    form = np.zeros(z.shape)
    for c, (i, j) in zip(coef, terms):
        form += c * u**i * v**j
    return form


def _sphere_form(z, ok, x, y):
    """The sphere z = z_c + σ √(R² − (x − x0)² − (y − y0)²) (σ = +1: a cap, −1: a bowl) nearest
    to the measured heights in the least-squares sense (vertical residuals; Gauss–Newton from
    the paraboloid z = c + a x + b y + k (x² + y²), whose R = 1/(2|k|): the sphere's small-slope
    limit), and its parameters. A tilt is the sphere's centre off the map's; a map without
    curvature (|k| ≈ 0, R beyond 1e6 times the map's extent) gets its plane removed instead."""
    from scipy.optimize import least_squares

    fit_at = _fit_points(ok)
    xs, ys, zs = x.ravel()[fit_at], y.ravel()[fit_at], z.ravel()[fit_at]
    xc, yc = xs.mean(), ys.mean()
    extent = math.hypot(np.ptp(xs), np.ptp(ys))
    r2 = (xs - xc) ** 2 + (ys - yc) ** 2
    A = np.column_stack([np.ones_like(xs), xs - xc, ys - yc, r2])
    (c, a, b, k), *_ = np.linalg.lstsq(A, zs, rcond=None)
    if not abs(k) * 2e6 * extent > 1.0:  # R0 = 1/(2|k|) > 1e6 extent: no measurable sphere
        plane = _poly_form(z, ok, x, y, 1)
        return plane, {"removed": "plane", "note": f"no spherical form: the fitted radius exceeds 1e6 times the "
                       f"map's extent ({extent:.3g}); the plane was removed"}
    sign = -1.0 if k > 0 else 1.0  # k < 0: the heights fall away from the centre, a cap
    R0 = 1.0 / (2.0 * abs(k))
    x0, y0 = xc - a / (2.0 * k), yc - b / (2.0 * k)
    z0 = c - k * ((x0 - xc) ** 2 + (y0 - yc) ** 2) - sign * R0  # apex height c' = z0 + σ R0

    def residual(p):
        root = np.sqrt(np.maximum(p[3] ** 2 - (xs - p[0]) ** 2 - (ys - p[1]) ** 2, 0.0))
        return p[2] + sign * root - zs

    fit = least_squares(residual, [x0, y0, z0, R0], x_scale=[extent, extent, R0, R0], method="lm")
    x0, y0, z0, R = fit.x
    reach = np.max((x[ok] - x0) ** 2 + (y[ok] - y0) ** 2)
    if not (np.isfinite(fit.x).all() and R > 0 and R * R > reach):
        raise ValueError(f"the fitted sphere (radius {abs(R):.4g}) does not span the map (its points reach "
                         f"{math.sqrt(reach):.4g} from the centre): use --detrend poly2 or poly3")
    form = z0 + sign * np.sqrt(np.maximum(R * R - (x - x0) ** 2 - (y - y0) ** 2, 0.0))
    return form, {"removed": "sphere", "radius": float(R), "shape": "convex (a cap)" if sign > 0 else "concave (a bowl)",
                  "centre_x": float(x0), "centre_y": float(y0)}


def remove_form(z, dx, dy, how):
    """(z minus its form, what was removed): the form fitted by least squares over the measured
    points (x = j dx, y = i dy) — the mean, the plane, a polynomial of total degree N ("polyN"),
    or a sphere (:func:`_sphere_form`); the dict says which, with the sphere's radius [L] and the
    rms of the removed form about its mean, ``form_rms`` [L]."""
    ok = np.isfinite(z)
    if how == "none":
        return z, {"removed": "nothing", "form_rms": 0.0}
    if how == "mean":
        return z - z[ok].mean(), {"removed": "mean", "form_rms": 0.0}
    x, y = _coordinates(z.shape, dx, dy)
    if how == "sphere":
        form, info = _sphere_form(z, ok, x, y)
    else:
        degree = 1 if how == "plane" else int(how[4:])
        form, info = _poly_form(z, ok, x, y, degree), {"removed": how if degree > 1 else "plane"}
        if degree > 1:
            info["degree"] = degree
    info["form_rms"] = float(np.std(form[ok]))
    return z - form, info
