"""The comparison integrators of the speed-against-error benchmark, in the paper's own
Cartesian variables (ω1, ω4, ω6) of (49)–(53) with the normalised summit pdf (18 corrected,
SpectralMoments.summit_pdf; docs/derivation.md):

* :func:`product_rule` — the paper's Gauss–Legendre product rule ("Gauss–Legendre 50-point
  quadrature formula", section 3 after (53)), n points per dimension on a truncated box;
* :func:`naive_tplquad` — what a user would write first: scipy.integrate.tplquad over the
  infinite ranges with the Hertz factors and the per-asperity law evaluated point by point.

Both compute, per unit nominal area, the elastic (A, W, K) of (52), (53), (55) or the
elasto-plastic (A, W, K) of (78), (82) and K = D_sum ∫ dW_i/dω p_sum (errata E17) with the
per-asperity law of asperity.respond. Units as contact.elastic_contact (E* = 1 unless given).

Truncation of the product rule (the paper states none): u = √μ ω4 and v = √μ ω6 are
Rayleigh(1) variables, so ω4, ω6 ∈ [0, √(2T/μ)] keeps all but e^{−T} of their mass; given
(ω4, ω6), ω1 is normal with unit variance about √β1 ω4 + √β2 ω6 ≤ (√β1 + √β2) √(2T/μ), so
ω1 ∈ [l, max(l, that) + √(2T)]. T = 25 (a relative truncation ≈ 1e-11, far below the rule's
own error). The Hertz factors depend on (ω4, ω6) only and are computed once per surface.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from roughcontact import asperity
from roughcontact.asperity import ellipse
from roughcontact.statistics import SpectralMoments

TRUNCATION = 25.0


def _law(kind, omega, kappa, factors, material, E_star):
    """Per-asperity (area, load, dW/dω) at interference ω and mean curvature κ_m."""
    if kind == "elastic":
        root = np.sqrt(omega / kappa)
        return (factors.f1 * math.pi * omega / kappa,  # (46)
                factors.f2 * (4.0 / 3.0) * E_star * omega * root,  # (47)
                2.0 * factors.f2 * E_star * root)  # (54)
    resp = asperity.respond(omega, kappa, factors, material)
    return resp.area, resp.load, resp.stiffness


@functools.lru_cache(maxsize=16)
def _box(surface: SpectralMoments, n: int, hertz: str):
    """Nodes, weights and Hertz factors of the (ω4, ω6) plane."""
    mu = surface.mu
    top = math.sqrt(2.0 * TRUNCATION / mu)
    x, w = np.polynomial.legendre.leggauss(n)
    q, wq = 0.5 * top * (x + 1.0), 0.5 * top * w
    W4, W6 = np.meshgrid(q, q, indexing="ij")
    k4 = W4 * math.sqrt(mu * surface.m40)  # |ξ4|, (13)
    k6 = W6 * math.sqrt(mu * surface.m04)  # |ξ6|
    lam = np.sqrt(np.minimum(k4, k6) / np.maximum(k4, k6))  # (27), the ellipse turns at ρ = 1
    factors = ellipse.hertz_factors(lam.ravel(), hertz)
    factors = ellipse.HertzFactors(*(np.asarray(f).reshape(lam.shape) for f in factors))
    kappa = 0.5 * (k4 + k6)  # κ_m, (43)
    return W4, W6, np.outer(wq, wq), kappa, factors, (x, w), top


def product_rule(surface: SpectralMoments, s: float, *, n: int = 50, kind: str = "elastic", material=None,
                 E_star: float = 1.0, hertz: str = "exact") -> np.ndarray:
    """(A/A0, W/A0, K/A0) at separation s by the n³-point Gauss–Legendre product rule."""
    W4, W6, w46, kappa, factors, (x, w), top = _box(surface, n, hertz)
    mu = surface.mu
    sig = math.sqrt(surface.m00 * mu)
    l = s / math.sqrt(mu)
    mean_max = (math.sqrt(surface.beta1) + math.sqrt(surface.beta2)) * top
    z_top = max(l, mean_max) - l + math.sqrt(2.0 * TRUNCATION)
    z, wz = 0.5 * z_top * (x + 1.0), 0.5 * z_top * w  # ω1 − l
    out = np.zeros(3)
    E = material.E_star if material is not None else E_star
    for zk, wk in zip(z, wz):
        pdf = surface.summit_pdf(l + zk, W4, W6)
        omega = np.full(W4.shape, zk * sig)
        laws = _law(kind, omega, kappa, factors, material, E)
        for q in range(3):
            out[q] += wk * np.sum(w46 * laws[q] * pdf)
    return surface.summit_density * out


def naive_tplquad(surface: SpectralMoments, s: float, *, quantity: str = "area", kind: str = "elastic",
                  material=None, E_star: float = 1.0, hertz: str = "exact") -> float:
    """One of A/A0, W/A0, K/A0 ("area", "load", "stiffness") by scipy.integrate.tplquad over
    ω1 ∈ (l, ∞), ω4, ω6 ∈ (0, ∞) with scipy's default tolerances (epsabs = epsrel = 1.49e-8),
    the Hertz factors and the law point by point."""
    from scipy.integrate import tplquad

    mu = surface.mu
    sig = math.sqrt(surface.m00 * mu)
    l = s / math.sqrt(mu)
    q = ("area", "load", "stiffness").index(quantity)
    E = material.E_star if material is not None else E_star

    def integrand(w6, w4, w1):
        k4, k6 = w4 * math.sqrt(mu * surface.m40), w6 * math.sqrt(mu * surface.m04)
        if k4 <= 0.0 or k6 <= 0.0:
            return 0.0
        f = ellipse.hertz_factors(math.sqrt(min(k4, k6) / max(k4, k6)), hertz)
        law = _law(kind, (w1 - l) * sig, 0.5 * (k4 + k6), f, material, E)[q]
        return float(law * surface.summit_pdf(w1, w4, w6))

    val, _ = tplquad(integrand, l, np.inf, 0.0, np.inf, 0.0, np.inf)
    return surface.summit_density * val
