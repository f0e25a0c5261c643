"""Elasto-plastic contact of a rough surface with a rigid flat, per unit nominal area.

Sections 5–7 of Buczkowski & Kleiber (2009), eqs. (78)–(85), with the corrections of
docs/errata.md (E12–E17). Public entry point: :func:`elastoplastic_contact`.

The integrals
-------------
In the polar variables of docs/derivation.md (θ, r, t; ω = t √(m00 μ) the interference,
κ_m = r c(θ), summit measure cos θ sin θ · r³ e^{−r²/2} φ(t + l − r g(θ)) dt dr dθ):

    A/A0 = D_sum ∫∫∫ A_i(ω, κ_m, e) · (measure)          (78)–(81)
    W/A0 = D_sum ∫∫∫ W_i(ω, κ_m, e) · (measure)          (82)–(85)
    K/A0 = D_sum ∫∫∫ dW_i/dω · (measure) [+ jump term]   (replaces (88), errata E17)

with the per-asperity law A_i, W_i, dW_i/dω of :func:`roughcontact.asperity.respond`
(elastic ω ≤ ω_c, elasto-plastic ω_c < ω < ω_p, plastic ω ≥ ω_p). The parts A^e, A^ep, A^p
(and W^e, W^ep, W^p) are the same integrals restricted to one regime — the t-ranges
[0, t_c], (t_c, t_p), [t_p, ∞) of (79)–(81), (83)–(85). The ellipse factors f1, f2, f3 and
K(e)E(e) depend on θ only, so ω_c = K E (K_Y Y/E*)²/κ_m (65) is, in t units,
t_c(θ, r) = tc1(θ)/r with tc1 = ω_c(θ, κ_m = c(θ))/√(m00 μ) computed at the θ-nodes by
:func:`roughcontact.asperity.critical_interference`; t_p = (ω_p/ω_c) t_c.

K = −dW/dh: W(h) = D_sum ∫ W_i(ξ1 − h) p_sum over ξ1 > h; the lower limit contributes
W_i(0) = 0, so −dW/dh = D_sum ∫ dW_i/dω p_sum + (load jumps). With the default continuous
K_v = K_Y Y/H the per-asperity load is continuous and the jump term vanishes. With the
paper's K_v = 0.454 + 0.41ν (``AsperityMaterial.with_paper_K_v``) the load jumps at ω_c by
J = A_i(ω_c)·(2/3)(K_v H − K_Y Y) (errata E15), and −dW/dh gains
(D_sum/√(m00 μ)) ∫∫ J φ(t_c + l − r g) cs r³ e^{−r²/2} dr dθ, the density of summits sitting
exactly at first yield times the jump; it is included in ``stiffness`` (and reported
separately as ``stiffness_jump``), so ``stiffness`` is −dW/dh in both cases.

Integrators
-----------
``method="production"``: numba (quadrature._ep_pairs): θ-nodes of the elastic integrator
(split at the axis turn θ*, the peak of g and the kinks of the Hertz option) carrying f1, f2,
f3, c, g, tc1; r on the partition of the elastic kernel plus the r where t_c and t_p cross
the bulk of the t-mass (and r_c/2, 2 r_c), Gauss–Legendre on each piece. Per r-node the
t-integral is closed-form where the Gaussian window of φ(t − a), a = r g − l, lies in one
regime (elastic: J_{1/2}, J_1, J_{3/2}(a); plastic: J_0, J_1), otherwise the elastic piece
[lo, t_c] (in √t) and the elasto-plastic piece [t_c, t_p] (in ln t near 0) are integrated by
Gauss–Legendre and the plastic tail beyond t_p is closed-form (levels:
quadrature.ELASTOPLASTIC_PRESETS). Parallel over (s, θ-node) pairs.
``method="reference"``: the slow twin (:func:`reference_integrals`) — scipy
``integrate.cubature`` (adaptive Gauss–Kronrod 21) over θ (polynomially mapped to flatten
the end-point singularities) and, nested, over r; the inner t-integral by Gauss–Legendre
in u = √t on the regime pieces, with the law and its regime taken from asperity.respond
itself. Seconds per separation; used by the tests.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from . import ellipse
from .asperity import AsperityMaterial, critical_interference, plasticity_index, respond
from .polar import PolarGeometry
from .quadrature import elastoplastic_settings_for, polar_elastoplastic_integrals, theta_rule
from .surface import SpectralMoments

__all__ = ["ElastoPlasticCurves", "elastoplastic_contact", "reference_integrals"]

HERTZ = ("exact", "paper")
METHODS = ("production", "reference")
#: relative size below which a load jump at ω_c counts as zero (continuous K_v up to rounding)
_JUMP_TOL = 1e-12
_PARTS = ("elastic", "elastoplastic", "plastic")


def _units(length="L", stress="unit of E*"):
    u = {
        "s": "1 (h/sqrt(m00))",
        "area_fraction": "1 (A/A0)",
        "pressure": f"{stress} (W/A0)",
        "stiffness": f"{stress} per {length} (K/A0 = -d(W/A0)/dh)",
        "stiffness_jump": f"{stress} per {length} (load-jump part of K/A0)",
    }
    for p in _PARTS:
        u[f"{p}_area_fraction"] = f"1 (A^{p}/A0)"
        u[f"{p}_pressure"] = f"{stress} (W^{p}/A0)"
    return u


@dataclass(frozen=True)
class ElastoPlasticCurves:
    """Elasto-plastic contact per unit nominal area at the separations ``s`` = h/√m00.

    area_fraction A/A0 [–] (78); pressure W/A0 [unit of E*] (82); stiffness K/A0 = −d(W/A0)/dh
    [unit of E* per length unit of the moments]; the regime parts elastic_*, elastoplastic_*,
    plastic_* (79)–(81), (83)–(85) sum to the totals; stiffness_jump is the part of K due to
    a load jump at ω_c (0 unless K_v ≠ K_Y Y/H). ``psi`` is asperity.plasticity_index.
    """

    s: np.ndarray
    area_fraction: np.ndarray
    pressure: np.ndarray
    stiffness: np.ndarray
    elastic_area_fraction: np.ndarray
    elastoplastic_area_fraction: np.ndarray
    plastic_area_fraction: np.ndarray
    elastic_pressure: np.ndarray
    elastoplastic_pressure: np.ndarray
    plastic_pressure: np.ndarray
    stiffness_jump: np.ndarray
    hertz: str
    method: str
    material: AsperityMaterial
    surface: SpectralMoments
    psi: float
    units: dict = field(default_factory=_units)

    @property
    def mean_real_pressure(self) -> np.ndarray:
        """W/A [unit of E*] (nan where A = 0)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.pressure / self.area_fraction

    @property
    def plastic_area_ratio(self) -> np.ndarray:
        """A^p/A (Fig. 5's ordinate as captioned)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.plastic_area_fraction / self.area_fraction

    @property
    def yielded_area_ratio(self) -> np.ndarray:
        """(A^ep + A^p)/A: the part of the real area past first yield."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return (self.elastoplastic_area_fraction + self.plastic_area_fraction) / self.area_fraction

    FIELDS: ClassVar[tuple[str, ...]] = (
        "area_fraction",
        "pressure",
        "stiffness",
        "elastic_area_fraction",
        "elastoplastic_area_fraction",
        "plastic_area_fraction",
        "elastic_pressure",
        "elastoplastic_pressure",
        "plastic_pressure",
        "stiffness_jump",
    )

    def to_dataset(self):
        """An xarray.Dataset over ``s`` with units, material and surface in the attributes."""
        import xarray as xr

        ds = xr.Dataset(
            {name: ("s", getattr(self, name), {"units": self.units[name]}) for name in self.FIELDS},
            coords={"s": ("s", self.s, {"units": self.units["s"], "long_name": "h/sqrt(m00)"})},
        )
        m = self.material
        ds.attrs.update(
            model="bgk-elastoplastic",
            hertz=self.hertz,
            method=self.method,
            E_star=m.E_star,
            Y=m.Y,
            H=m.H,
            yield_coefficient=m.yield_coefficient,
            c_h=m.c_h,
            wp_over_wc=m.wp_over_wc,
            K_v=m.K_v,
            psi=self.psi,
            **self.surface.as_dict(),
        )
        return ds


# ---------------------------------------------------------------------------------------
# validation
# ---------------------------------------------------------------------------------------
def _check_inputs(surface, s, material, hertz, method) -> np.ndarray:
    if not isinstance(surface, SpectralMoments):
        raise TypeError(f"surface must be a SpectralMoments, got {type(surface).__name__}")
    if not isinstance(material, AsperityMaterial):
        raise TypeError(f"material must be an AsperityMaterial, got {type(material).__name__}")
    if hertz not in HERTZ:
        raise ValueError(f"hertz must be one of {', '.join(HERTZ)}; got {hertz!r}")
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}; got {method!r}")
    try:
        arr = np.atleast_1d(np.asarray(s, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"s must be a 1-D sequence of real separations h/sqrt(m00), got {s!r}") from None
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError("s must be a non-empty 1-D sequence of separations h/sqrt(m00)")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"separations must be finite, got {arr[~np.isfinite(arr)][:3]}")
    return arr


def _material_constants(material: AsperityMaterial):
    """(E*, ω_p/ω_c, c_h H, H(c_h − (2/3)K_v), (2/3) K_v H, with_jump) for the kernels."""
    m = material
    with_jump = abs(m.load_jump_at_yield) > _JUMP_TOL
    return (
        m.E_star,
        m.wp_over_wc,
        m.c_h * m.H,
        m.H * (m.c_h - (2.0 / 3.0) * m.K_v),
        (2.0 / 3.0) * m.K_v * m.H,
        with_jump,
    )


# ---------------------------------------------------------------------------------------
# θ-node data (as contact._theta_nodes, plus f3 and the critical interference)
# ---------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def _theta_nodes(surface: SpectralMoments, hertz: str, accuracy, material: AsperityMaterial):
    """θ-weights (× cos θ sin θ) and per-node g, c, f1, f2, f3, tc1 (the same nodes as
    contact._theta_nodes). tc1 = ω_c(θ, κ_m = c(θ))/√(m00 μ) by asperity.critical_interference."""
    settings = elastoplastic_settings_for(accuracy)
    geom = PolarGeometry(surface)
    theta, w = theta_rule(geom.theta_breaks(hertz), settings)
    lam = np.sqrt(geom.lambda_squared(theta))
    factors = ellipse.hertz_factors(lam, hertz)
    c = geom.c(theta)
    sigma = math.sqrt(surface.m00 * surface.mu)
    wc1 = np.asarray(critical_interference(c, factors, material, hertz=hertz), dtype=float)  # eq. (65)
    nodes = dict(
        g=geom.g(theta),
        c=c,
        f1=np.asarray(factors.f1, float),
        f2=np.asarray(factors.f2, float),
        f3=np.asarray(factors.f3, float),
        tc1=wc1 / sigma,
    )
    return w * np.cos(theta) * np.sin(theta), nodes


def _production(surface, l_values, material, hertz, accuracy) -> np.ndarray:
    """Columns A^e, A^ep, A^p, W^e, W^ep, W^p, K, K_jump per unit nominal area."""
    w_theta, nodes = _theta_nodes(surface, hertz, accuracy, material)
    sigma = math.sqrt(surface.m00 * surface.mu)
    per_node = polar_elastoplastic_integrals(l_values, nodes, sigma, _material_constants(material), accuracy)
    tot = np.einsum("ijq,j->iq", per_node, w_theta) * surface.summit_density
    out = tot.copy()
    out[:, 6] = tot[:, 6] + tot[:, 7]  # K = ∫ dW_i/dω p_sum + jump term
    return out


# ---------------------------------------------------------------------------------------
# the slow twin
# ---------------------------------------------------------------------------------------
_REF_TAIL = 60.0  # e^-60: a wider window than production's e^-50


@functools.lru_cache(maxsize=8)
def _gauss_legendre(n: int):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


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
    y, wy = _gauss_legendre(n_t)
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

    _check_inputs(surface, [s], material, hertz, "reference")
    geom = PolarGeometry(surface)
    mu = surface.mu
    sigma = math.sqrt(surface.m00 * mu)
    l = float(s) / math.sqrt(mu)
    pv = (2.0 / 3.0) * material.K_v * material.H
    with_jump = abs(material.load_jump_at_yield) > _JUMP_TOL
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


# ---------------------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------------------
def elastoplastic_contact(
    surface: SpectralMoments,
    s,
    material: AsperityMaterial,
    *,
    hertz: str = "exact",
    accuracy="table",
    method: str = "production",
) -> ElastoPlasticCurves:
    """Elasto-plastic contact per unit nominal area at separations ``s`` = h/√m00 (23).

    surface   SpectralMoments (lengths in its unit L; D_sum per L²).
    material  AsperityMaterial (E*, Y, H, K_Y, c_h, ω_p/ω_c, K_v; stresses in one unit).
              To prescribe a plasticity index ψ use
              ``AsperityMaterial(E, asperity.yield_strength_for_plasticity_index(ψ, surface, E))``.
    hertz     "exact" | "paper" (ellipse factors as in contact.elastic_contact).
    accuracy  production preset of quadrature.ELASTOPLASTIC_PRESETS ("table", "plot") or a
              QuadratureSettings.
    method    "production" (numba) or "reference" (the scipy slow twin; seconds per point).

    Returns :class:`ElastoPlasticCurves`: A/A0, W/A0 (unit of E*), K/A0 = −d(W/A0)/dh (unit of
    E* per L) and the elastic / elasto-plastic / plastic parts of area and load.
    """
    s_arr = _check_inputs(surface, s, material, hertz, method)
    if method == "production":
        elastoplastic_settings_for(accuracy)  # validates the preset name
        cols = _production(surface, surface.l_from_s(s_arr), material, hertz, accuracy)
    else:
        cols = np.array([reference_integrals(surface, float(x), material, hertz=hertz) for x in s_arr])
    Ae, Aep, Ap, We, Wep, Wp, K, Kj = (np.asarray(cols[:, q], dtype=float) for q in range(8))
    return ElastoPlasticCurves(
        s=s_arr,
        area_fraction=Ae + Aep + Ap,
        pressure=We + Wep + Wp,
        stiffness=K,
        elastic_area_fraction=Ae,
        elastoplastic_area_fraction=Aep,
        plastic_area_fraction=Ap,
        elastic_pressure=We,
        elastoplastic_pressure=Wep,
        plastic_pressure=Wp,
        stiffness_jump=Kj,
        hertz=hertz,
        method=method,
        material=material,
        surface=surface,
        psi=plasticity_index(surface, material),
    )
