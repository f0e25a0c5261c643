"""The slow twin of the elasto-plastic production kernel (:mod:`.kernels`, ``_ep_pairs``).

Same integrals as :mod:`roughcontact.contact.elastoplastic` (sections 5–7 of Buczkowski &
Kleiber 2009, (78)–(85), K = −dW/dh replacing (88)), computed independently: scipy
``integrate.cubature`` (adaptive Gauss–Kronrod 21) over θ (polynomially mapped to flatten the
end-point singularities of the Hertz factors) and, nested, over r; the inner t-integral by
Gauss–Legendre in u = √t on the regime pieces, with the law and its regime taken from
:func:`roughcontact.asperity.respond` itself (not from the kernels' copy of it). Seconds per
separation; used by the tests and the workflow's ``ep_numerics`` check points.
"""

from __future__ import annotations

import math

import numpy as np

from ..asperity import AsperityMaterial, critical_interference, ellipse, respond
from ..statistics.surface import SpectralMoments
from ..validation import choice, instance, separations
from .polar import PolarGeometry
from .rules import gauss_legendre

__all__ = ["reference_integrals"]

_REF_TAIL = 60.0  # e^-60: a wider window than production's e^-50


def _ref_r_batch(r, l, g, c, factors, wc1, sigma, material, hertz, n_t, pv, with_jump):
    """Integrand of the r-integral at an array of r: shape (n_r, 8), columns as
    :func:`reference_integrals`. For each r the t-axis (the window of φ(t − a), a = r g − l,
    cut at e^{−60}) is cut at t_c, t_p and a into four pieces (some empty), each on an
    n_t-node Gauss–Legendre rule in u = √t; the
    law and its regime come from asperity.respond."""
    r = np.asarray(r, dtype=float)
    a = r * g - l
    kappa = r * c
    wc = wc1 / r
    span = math.sqrt(2.0 * _REF_TAIL)
    lo = np.where(a > 0.0, np.maximum(0.0, a - span), 0.0)
    hi = np.where(a > 0.0, a + span, a + np.sqrt(a * a + 2.0 * _REF_TAIL))
    tc = wc / sigma
    tp = material.wp_over_wc * tc
    edges = np.sort(
        np.column_stack([lo, np.clip(tc, lo, hi), np.clip(tp, lo, hi), np.clip(a, lo, hi), hi]), axis=1
    )
    y, wy = gauss_legendre(n_t)
    # every piece in u = √t: the elastic law's t^{1/2}, t^{3/2} are then analytic even on a
    # piece that starts just to the right of t = 0 (e.g. at a small peak a > 0)
    u0, u1 = np.sqrt(edges[:, :-1, None]), np.sqrt(edges[:, 1:, None])  # (n_r, 4, 1)
    u = u0 + (u1 - u0) * y
    t = u * u
    w = 2.0 * u * (u1 - u0) * wy
    w = w * np.exp(-0.5 * (t - a[:, None, None]) ** 2) / math.sqrt(2.0 * math.pi)
    resp = respond(sigma * t, kappa[:, None, None], factors, material, hertz=hertz)
    out = np.zeros((r.shape[0], 8))
    for k in range(3):
        sel = resp.regime == k
        out[:, k] = np.sum(np.where(sel, w * resp.area, 0.0), axis=(1, 2))
        out[:, 3 + k] = np.sum(np.where(sel, w * resp.load, 0.0), axis=(1, 2))
    out[:, 6] = np.sum(w * resp.stiffness, axis=(1, 2))
    if with_jump:
        # elastic side of ω_c, evaluated at ω_c/2 (safely elastic: respond re-derives ω_c and
        # may round it below ours) and scaled by the exact powers of (46), (47)
        half = respond(0.5 * wc, kappa, factors, material, hertz=hertz)
        jump = 2.0 * half.area * pv - 2.0**1.5 * half.load  # A(ω_c)·(2/3)K_v H − W(ω_c)
        d = tc - a
        out[:, 7] = jump * np.exp(-0.5 * d * d) / math.sqrt(2.0 * math.pi) / sigma
    return out * (r**3 * np.exp(-0.5 * r * r))[:, None]


def reference_integrals(
    surface: SpectralMoments,
    s: float,
    material: AsperityMaterial,
    *,
    hertz: str = "exact",
    rtol: float = 1e-10,
    n_t: int = 40,
) -> np.ndarray:
    """The slow twin at one separation s: (A^e, A^ep, A^p, W^e, W^ep, W^p, K, K_jump)/A0
    (K includes K_jump).

    scipy.integrate.cubature (adaptive Gauss–Kronrod 21, elementwise tolerance) over θ (split
    at θ*, the peak of g and the Hertz kinks) and, nested, over r (the window of the Gaussian
    factors, e^{−60}, split at its peak), inner t by Gauss–Legendre on the regime pieces with
    asperity.respond as the law (:func:`_ref_r_batch`). Each column is scaled by its total
    (from a pass at rtol 1e-4) and asked for ``rtol``; parts below 1e-4 of their total get an
    absolute accuracy of ``rtol``·1e-4 of it. Slow: seconds per point."""
    from scipy.integrate import cubature

    instance("surface", surface, SpectralMoments)
    instance("material", material, AsperityMaterial)
    choice("hertz", hertz, ("exact", "paper"))
    s = float(separations([s])[0])
    geom = PolarGeometry(surface)
    mu = surface.mu
    sigma = math.sqrt(surface.m00 * mu)
    l = float(s) / math.sqrt(mu)
    pv = (2.0 / 3.0) * material.K_v * material.H
    with_jump = material.has_load_jump
    span = math.sqrt(2.0 * _REF_TAIL)
    breaks = sorted(b for b in geom.theta_breaks(hertz) if 0.0 < b < 0.5 * math.pi)
    edges = [0.0, *breaks, 0.5 * math.pi]

    def theta_batch(th, proj, tol, atol):
        out = np.empty((th.shape[0], proj.shape[0]))
        for i, theta in enumerate(th[:, 0]):
            lam = math.sqrt(float(geom.lambda_squared(theta)))
            factors = ellipse.hertz_factors(lam, hertz)
            g, c = float(geom.g(theta)), float(geom.c(theta))
            wc1 = float(critical_interference(c, factors, material, hertz=hertz))  # eq. (65), r = 1
            q = 1.0 + g * g
            rstar = l * g / q if l > 0.0 else 0.0
            lo, hi = max(0.0, rstar - span / math.sqrt(q) - 1.0), rstar + span
            cuts = [lo, rstar, hi] if lo < rstar < hi else [lo, hi]
            val = np.zeros(proj.shape[0])
            for x0, x1 in zip(cuts[:-1], cuts[1:]):
                res = cubature(
                    lambda rr: _ref_r_batch(rr[:, 0], l, g, c, factors, wc1, sigma, material, hertz, n_t, pv,
                                            with_jump) @ proj.T,
                    [x0], [x1], rtol=0.1 * tol, atol=1e-3 * atol,
                )
                val += res.estimate
            out[i] = math.cos(theta) * math.sin(theta) * val
        return out

    def mapped_theta_batch(v, x0, x1, proj, tol, atol):
        # θ = x0 + (x1 − x0)·S(v), S(v) = 10v³ − 15v⁴ + 6v⁵: the Jacobian 30v²(1 − v)² flattens
        # the algebraic/logarithmic end-point singularities of the Hertz factors at θ → 0, π/2
        vv = v[:, 0]
        theta = x0 + (x1 - x0) * vv**3 * (10.0 - 15.0 * vv + 6.0 * vv * vv)
        jac = (x1 - x0) * 30.0 * vv * vv * (1.0 - vv) ** 2
        return theta_batch(theta[:, None], proj, tol, atol) * jac[:, None]

    def run(proj, tol, atol):
        total = np.zeros(proj.shape[0])
        for x0, x1 in zip(edges[:-1], edges[1:]):
            res = cubature(mapped_theta_batch, [0.0], [1.0], rtol=tol, atol=atol, args=(x0, x1, proj, tol, atol))
            total += res.estimate
        return total * surface.summit_density

    # pass 1: the three totals (all positive) to 1e-4, to scale the columns of pass 2
    totals_proj = np.zeros((3, 8))
    totals_proj[0, 0:3] = totals_proj[1, 3:6] = 1.0
    totals_proj[2, 6] = 1.0
    area, load, stiff = run(totals_proj, 1e-4, 0.0)
    scale = np.array([area, area, area, load, load, load, stiff, stiff]) / surface.summit_density
    scale[~(scale > 0.0)] = 1.0
    fine = run(np.diag(1.0 / scale), rtol, 1e-4 * rtol) * scale
    fine[6] += fine[7]
    return fine
