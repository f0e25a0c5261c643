"""Quadrature rules and the numba production kernels: the only place integration rules live.

The integrals are those of docs/derivation.md in polar form: an outer θ-integral whose
nodes carry the precomputed ellipse data, a middle r-integral and an inner t-integral
(the interference) against the Gaussian φ(t + l − r g(θ)). Every rule is a tanh-sinh
(double-exponential) rule on a finite window: it converges exponentially even with the
endpoint singularities of the integrand (t^{1/2} at t = 0, r^{5/2} at r = 0, the
logarithmic singularities of the Hertz factors at θ → 0, π/2). The windows are cut where
the Gaussian factors fall below e^{−TAIL} of their peak (TAIL = 50, i.e. < 2e-22).

Kernels are plain loops over arrays (fastmath off); the Python API in contact.py validates
inputs. Each kernel has a slow twin: the mpmath integrator in reference.py.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

__all__ = [
    "TanhSinh",
    "QuadratureSettings",
    "PRESETS",
    "settings_for",
    "theta_rule",
    "normal_moment",
    "polar_elastic_integrals",
    "ELASTOPLASTIC_PRESETS",
    "elastoplastic_settings_for",
    "asperity_law",
    "polar_elastoplastic_integrals",
]

#: -ln of the relative size at which Gaussian tails are cut (e^-50 ≈ 2e-22).
TAIL = 50.0
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)
#: below this a, J_ν(a) ≤ φ(a) < 1e-323 is zero in double precision
_A_UNDERFLOW = -38.6


@dataclass(frozen=True)
class TanhSinh:
    """Tanh-sinh rule on [0, 1]: nodes y_k = (1 + tanh(π/2 sinh(kh)))/2, |kh| ≤ half_width.

    Both y and 1 − y are formed without cancellation (y = expit(π sinh(kh))), so an
    integrand singular at either end point is evaluated at its true distance from it. The
    default half_width 3.1 keeps every node representable at both ends (1 − y ≥ 1e-16) and
    symmetric; it omits the end intervals y < 1e-16, which is harmless for bounded
    integrands (all of ours) but not for strong singularities such as y^{-1/2}
    (widen half_width for those).
    """

    level: int  # step h = 2^-level
    half_width: float = 3.1

    @property
    def nodes_weights(self) -> tuple[np.ndarray, np.ndarray]:
        h = 2.0**-self.level
        n = int(math.floor(self.half_width / h))
        k = np.arange(-n, n + 1) * h
        u = 0.5 * math.pi * np.sinh(k)
        y = 1.0 / (1.0 + np.exp(-2.0 * u))  # (1 + tanh u)/2
        w = h * 0.5 * math.pi * np.cosh(k) / np.cosh(u) ** 2 * 0.5
        return y, w


@dataclass(frozen=True)
class QuadratureSettings:
    """Levels of the tanh-sinh rules in θ (per sub-interval), r and t."""

    theta_level: int
    r_level: int
    t_level: int

    def rules(self):
        return tuple(TanhSinh(lv).nodes_weights for lv in (self.theta_level, self.r_level, self.t_level))


#: Named accuracy presets (levels of the θ, r, t rules). Measured against levels (5, 5, 5)
#: and (6, 6, 6) for s ∈ [−1, 30] on the Table 1 and Table 2 surfaces (tests/test_contact.py):
#: "table" ≤ 1e-14 relative (~30 ms per separation on one core); "plot" ≤ 3e-6 (≤ 1e-7 for
#: s ≤ 7; ~10 ms).
PRESETS: dict[str, QuadratureSettings] = {
    "table": QuadratureSettings(theta_level=4, r_level=4, t_level=4),
    "plot": QuadratureSettings(theta_level=3, r_level=4, t_level=3),
}


def settings_for(accuracy, presets: dict[str, QuadratureSettings] | None = None) -> QuadratureSettings:
    """Resolve an accuracy preset name of ``presets`` (default: the elastic PRESETS), or pass a
    QuadratureSettings through."""
    if isinstance(accuracy, QuadratureSettings):
        return accuracy
    presets = PRESETS if presets is None else presets
    try:
        return presets[accuracy]
    except (KeyError, TypeError):
        raise ValueError(
            f"unknown accuracy preset {accuracy!r}; choose one of {sorted(presets)}"
        ) from None


# ---------------------------------------------------------------------------------------
# numba kernels
# ---------------------------------------------------------------------------------------
@numba.njit(cache=True)
def _t_window(a):
    """Window [lo, hi] of t ≥ 0 outside which φ(t − a) is below e^{−TAIL} of its maximum."""
    span = math.sqrt(2.0 * TAIL)
    if a > 0.0:
        return max(0.0, a - span), a + span
    # maximum at t = 0: exp(−(t − a)²/2)/exp(−a²/2) = exp(−|a| t − t²/2) = e^{−TAIL}
    # at t = −|a| + √(a² + 2 TAIL), i.e. a + √(a² + 2 TAIL) since a ≤ 0
    return 0.0, a + math.sqrt(a * a + 2.0 * TAIL)


@numba.njit(cache=True)
def _normal_moments_on(lo, hi, a, y_t, w_t):
    """Tanh-sinh sums of t^ν φ(t − a) over [lo, hi] for ν = 1/2, 1, 3/2."""
    width = hi - lo
    j_half = 0.0
    j_one = 0.0
    j_three_half = 0.0
    for k in range(y_t.shape[0]):
        t = lo + width * y_t[k]
        d = t - a
        wphi = width * w_t[k] * _INV_SQRT_2PI * math.exp(-0.5 * d * d)
        sq = math.sqrt(t)
        j_half += wphi * sq
        j_one += wphi * t
        j_three_half += wphi * t * sq
    return j_half, j_one, j_three_half


@numba.njit(cache=True)
def _normal_moments(a, y_t, w_t):
    """(J_{1/2}, J_1, J_{3/2}) at a, with J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt = E[(Z + a)₊^ν].

    For a > 0 the window is split at the peak t = a so that neither piece holds an
    interior bump (tanh-sinh spends its nodes near the ends of an interval)."""
    if a < _A_UNDERFLOW:  # J_ν(a) < φ(a) underflows: exactly zero
        return 0.0, 0.0, 0.0
    lo, hi = _t_window(a)
    if a > lo:
        h1, o1, t1 = _normal_moments_on(lo, a, a, y_t, w_t)
        h2, o2, t2 = _normal_moments_on(a, hi, a, y_t, w_t)
        return h1 + h2, o1 + o2, t1 + t2
    return _normal_moments_on(lo, hi, a, y_t, w_t)


@numba.njit(cache=True)
def _normal_moments_array(a_values, y_t, w_t, out):
    for i in range(a_values.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = _normal_moments(a_values[i], y_t, w_t)


@numba.njit(cache=True)
def _r_window(g, l):
    """Window (lo, peak, hi) of r > 0 holding the mass of r^k e^{−r²/2} J_ν(r g − l).

    The log-integrand is −r²/2 − (r g − l)²/2 (+ slowly varying terms) below r = l/g and
    −r²/2 above it: its peak is near r* = l g/(1 + g²) with curvature 1 + g² below.
    """
    q = 1.0 + g * g
    span = math.sqrt(2.0 * TAIL)
    rstar = l * g / q if l > 0.0 else 0.0
    lo = max(0.0, rstar - span / math.sqrt(q) - 1.0)
    return lo, rstar, rstar + span


@numba.njit(cache=True)
def _r_sums(lo, hi, g, l, y_r, w_r, y_t, w_t):
    """∫_lo^hi r² e^{−r²/2} (J_1, r^{1/2} J_{3/2}, r^{1/2} J_{1/2})(r g − l) dr."""
    width = hi - lo
    acc_a = 0.0
    acc_w = 0.0
    acc_k = 0.0
    for k in range(y_r.shape[0]):
        r = lo + width * y_r[k]
        j_half, j_one, j_three_half = _normal_moments(r * g - l, y_t, w_t)
        base = width * w_r[k] * r * r * math.exp(-0.5 * r * r)
        sr = math.sqrt(r)
        acc_a += base * j_one
        acc_w += base * sr * j_three_half
        acc_k += base * sr * j_half
    return acc_a, acc_w, acc_k


@numba.njit(cache=True, parallel=True)
def _polar_elastic_kernel(l_values, w_area, w_load, g, y_r, w_r, y_t, w_t, out):
    """out[i] = (I_area, I_load, I_stiffness) at l_values[i] (docs/derivation.md):

    I_area  = Σ_θ w_area  ∫ r² e^{−r²/2} J_1(r g − l) dr
    I_load  = Σ_θ w_load  ∫ r^{5/2} e^{−r²/2} J_{3/2}(r g − l) dr
    I_stiff = Σ_θ w_load  ∫ r^{5/2} e^{−r²/2} J_{1/2}(r g − l) dr

    The r-window is split at the peak r* (as the t-window at t = a) so that no piece
    holds an interior bump.
    """
    for i in numba.prange(l_values.shape[0]):
        l = l_values[i]
        area = 0.0
        load = 0.0
        stiff = 0.0
        for j in range(g.shape[0]):
            lo, peak, hi = _r_window(g[j], l)
            if peak > lo:
                a1, w1, k1 = _r_sums(lo, peak, g[j], l, y_r, w_r, y_t, w_t)
                a2, w2, k2 = _r_sums(peak, hi, g[j], l, y_r, w_r, y_t, w_t)
                acc_a, acc_w, acc_k = a1 + a2, w1 + w2, k1 + k2
            else:
                acc_a, acc_w, acc_k = _r_sums(lo, hi, g[j], l, y_r, w_r, y_t, w_t)
            area += w_area[j] * acc_a
            load += w_load[j] * acc_w
            stiff += w_load[j] * acc_k
        out[i, 0] = area
        out[i, 1] = load
        out[i, 2] = stiff


# ---------------------------------------------------------------------------------------
# Python API (inputs validated here, not in the kernels)
# ---------------------------------------------------------------------------------------
def theta_rule(breakpoints, settings: QuadratureSettings) -> tuple[np.ndarray, np.ndarray]:
    """Composite tanh-sinh nodes and weights on (0, π/2), split at ``breakpoints``
    (where the integrand is not smooth: the axis turn θ*, the clip of eq. (33))."""
    y, w = TanhSinh(settings.theta_level).nodes_weights
    edges = np.unique(np.concatenate(([0.0], np.asarray(breakpoints, float), [0.5 * math.pi])))
    nodes, weights = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        nodes.append(a + (b - a) * y)
        weights.append((b - a) * w)
    return np.concatenate(nodes), np.concatenate(weights)


def normal_moment(a, accuracy="table") -> np.ndarray:
    """J_ν(a) = E[(Z + a)₊^ν] for ν = 1/2, 1, 3/2 (columns), Z ~ N(0, 1). GW's F_ν(d) = J_ν(−d)."""
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(a, dtype=float)))
    if not np.all(np.isfinite(a)):
        raise ValueError("normal_moment: arguments must be finite")
    _, _, (y_t, w_t) = settings_for(accuracy).rules()
    out = np.empty((a.shape[0], 3))
    _normal_moments_array(a, y_t, w_t, out)
    return out


def polar_elastic_integrals(l_values, w_area, w_load, g, accuracy="table") -> np.ndarray:
    """The dimensionless (θ, r, t) integrals at each l; columns (area, load, stiffness).

    ``w_area``, ``w_load``, ``g`` are per θ-node: θ-weight × cos θ sin θ × f1/c (resp. f2/√c)
    and g(θ) (see contact.py for how they are built)."""
    l_values = np.ascontiguousarray(np.atleast_1d(np.asarray(l_values, dtype=float)))
    if not np.all(np.isfinite(l_values)):
        raise ValueError("separations must be finite")
    _, (y_r, w_r), (y_t, w_t) = settings_for(accuracy).rules()
    out = np.empty((l_values.shape[0], 3))
    _polar_elastic_kernel(
        l_values,
        np.ascontiguousarray(w_area, dtype=float),
        np.ascontiguousarray(w_load, dtype=float),
        np.ascontiguousarray(g, dtype=float),
        y_r,
        w_r,
        y_t,
        w_t,
        out,
    )
    return out


# ---------------------------------------------------------------------------------------
# elasto-plastic kernels (sections 5–7, eqs. (78)–(85); Python API in elastoplastic.py)
# ---------------------------------------------------------------------------------------
# Per-asperity laws. Each mirrors one branch of asperity.respond line by line (same
# formulas, same order of operations); tests/test_elastoplastic.py compares them with
# asperity.respond at many points in every regime. Dimensional: ω, 1/κ in L, E*, H in
# stress; returns (area [L²], load [stress·L²], dW/dω [stress·L]).
@numba.njit(cache=True)
def _asperity_elastic(omega, kappa, f1, f2, E_star):
    """asperity.respond, elastic branch: (46), (47) and dW/dω of (47) (= (54))."""
    root = math.sqrt(omega / kappa)
    A = f1 * math.pi * omega / kappa  # eq. (46)
    W = f2 * (4.0 / 3.0) * E_star * omega * root  # eq. (47)
    S = 2.0 * f2 * E_star * root  # eq. (54)
    return A, W, S


@numba.njit(cache=True)
def _asperity_elastoplastic(omega, kappa, f1, f3, wc, ratio, cH, dp, ln_r):
    """asperity.respond, elasto-plastic branch ω_c < ω < ω_p: (76), (75), (77) and dW/dω.

    ratio = ω_p/ω_c, cH = c_h H, dp = H (c_h − (2/3) K_v), ln_r = ln(ω_p/ω_c)."""
    d = 2.0 * f3 - f1
    t = omega / wc  # ω/ω_c
    x = (t - 1.0) / (ratio - 1.0)  # (ω − ω_c)/(ω_p − ω_c)
    g = x * x * (3.0 - 2.0 * x)  # blend, asperity.blend
    dg = 6.0 * x * (1.0 - x)
    bracket = f1 + d * g
    A = bracket * math.pi * omega / kappa  # eq. (76)
    p = cH - dp * math.log(ratio / t) / ln_r  # eq. (75)
    W = A * p  # eq. (77)
    dA = (bracket + d * dg * t / (ratio - 1.0)) * math.pi / kappa
    S = dA * p + (bracket * math.pi / kappa) * dp / ln_r
    return A, W, S


@numba.njit(cache=True)
def _asperity_plastic(omega, kappa, f3, cH):
    """asperity.respond, plastic branch ω ≥ ω_p: (61), (67) and d(67)/dω."""
    A = 2.0 * f3 * math.pi * omega / kappa  # eq. (61)
    W = A * cH  # eq. (67)
    S = 2.0 * f3 * math.pi * cH / kappa
    return A, W, S


@numba.njit(cache=True)
def _asperity_law_array(omega, kappa, f1, f2, f3, wc, E_star, ratio, cH, dp, ln_r, out):
    """The three branches dispatched as asperity.respond does (elastic ω ≤ ω_c, plastic
    ω ≥ ω_p, elasto-plastic between); out[i] = (A, W, dW/dω, regime). For the tests."""
    for i in range(omega.shape[0]):
        w = omega[i]
        if w <= wc[i]:
            A, W, S = _asperity_elastic(w, kappa[i], f1[i], f2[i], E_star)
            reg = 0.0
        elif w >= ratio * wc[i]:
            A, W, S = _asperity_plastic(w, kappa[i], f3[i], cH)
            reg = 2.0
        else:
            A, W, S = _asperity_elastoplastic(w, kappa[i], f1[i], f3[i], wc[i], ratio, cH, dp, ln_r)
            reg = 1.0
        out[i, 0] = A
        out[i, 1] = W
        out[i, 2] = S
        out[i, 3] = reg


@numba.njit(cache=True)
def _ep_piece(lo, hi, a, regime, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t):
    """∫_lo^hi (A, W, dW/dω)(σ t) φ(t − a) dt for one regime (0, 1, 2) on [lo, hi].

    The regime is fixed by the caller's breakpoints, not re-decided per node, so a node
    that rounds onto t_c or t_p still uses the law of its piece."""
    width = hi - lo
    acc_a = 0.0
    acc_w = 0.0
    acc_s = 0.0
    for k in range(y_t.shape[0]):
        t = lo + width * y_t[k]
        d = t - a
        wphi = width * w_t[k] * _INV_SQRT_2PI * math.exp(-0.5 * d * d)
        omega = sigma * t
        if regime == 0:
            A, W, S = _asperity_elastic(omega, kappa, f1, f2, E_star)
        elif regime == 1:
            A, W, S = _asperity_elastoplastic(omega, kappa, f1, f3, wc, ratio, cH, dp, ln_r)
        else:
            A, W, S = _asperity_plastic(omega, kappa, f3, cH)
        acc_a += wphi * A
        acc_w += wphi * W
        acc_s += wphi * S
    return acc_a, acc_w, acc_s


@numba.njit(cache=True)
def _ep_piece_split(lo, hi, a, regime, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t):
    """_ep_piece, split at the Gaussian peak t = a when it lies inside (lo, hi)."""
    if lo < a and a < hi:
        a1, w1, s1 = _ep_piece(lo, a, a, regime, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t)
        a2, w2, s2 = _ep_piece(a, hi, a, regime, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t)
        return a1 + a2, w1 + w2, s1 + s2
    return _ep_piece(lo, hi, a, regime, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t)


@numba.njit(cache=True)
def _ep_t_integral(a, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t, acc, weight):
    """Add weight × ∫₀^∞ law(σ t) φ(t − a) dt to acc[0:7] = (A^e, A^ep, A^p, W^e, W^ep, W^p, S).

    The t-axis is cut at t_c = ω_c/σ and t_p = (ω_p/ω_c) t_c; each regime piece is
    intersected with the Gaussian window of φ(t − a) (empty pieces skipped) and split at
    its peak."""
    if a < _A_UNDERFLOW:
        return
    lo, hi = _t_window(a)
    tc = wc / sigma
    tp = ratio * tc
    e_hi = min(hi, tc)
    if lo < e_hi:
        A, W, S = _ep_piece_split(lo, e_hi, a, 0, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t)
        acc[0] += weight * A
        acc[3] += weight * W
        acc[6] += weight * S
    ep_lo = max(lo, tc)
    ep_hi = min(hi, tp)
    if ep_lo < ep_hi:
        A, W, S = _ep_piece_split(ep_lo, ep_hi, a, 1, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t)
        acc[1] += weight * A
        acc[4] += weight * W
        acc[6] += weight * S
    p_lo = max(lo, tp)
    if p_lo < hi:
        A, W, S = _ep_piece_split(p_lo, hi, a, 2, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t)
        acc[2] += weight * A
        acc[5] += weight * W
        acc[6] += weight * S


@numba.njit(cache=True)
def _ep_r_sums(lo, hi, l, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, ln_r, pv, with_jump,
               y_r, w_r, y_t, w_t, acc):
    """acc[0:8] += ∫_lo^hi r³ e^{−r²/2} (t-integrals of _ep_t_integral, jump term) dr.

    acc[7] is the Leibniz term of a load jump J at ω_c (zero for the continuous K_v):
    (1/σ) J φ(t_c + l − r g), J = A^e(ω_c)·(2/3) K_v H − W^e(ω_c) (pv = (2/3) K_v H)."""
    width = hi - lo
    for k in range(y_r.shape[0]):
        r = lo + width * y_r[k]
        wr = width * w_r[k] * r * r * r * math.exp(-0.5 * r * r)
        if wr == 0.0:
            continue
        a = r * g - l
        kappa = r * c  # κ_m = r c(θ), eq. (44)
        wc = sigma * tc1 / r  # ω_c = ω_c(θ, κ_m = c)/r, eq. (65)
        _ep_t_integral(a, sigma, kappa, wc, f1, f2, f3, E_star, ratio, cH, dp, ln_r, y_t, w_t, acc, wr)
        if with_jump:
            d = wc / sigma - a
            Ae, We, _ = _asperity_elastic(wc, kappa, f1, f2, E_star)
            acc[7] += wr * (Ae * pv - We) * _INV_SQRT_2PI * math.exp(-0.5 * d * d) / sigma


@numba.njit(cache=True, parallel=True)
def _polar_elastoplastic_kernel(l_values, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, pv,
                                with_jump, y_r, w_r, y_t, w_t, out):
    """out[i, j, :] = the (r, t)-integrals at l_values[i] and θ-node j (not yet θ-weighted):

    ∫ dr r³ e^{−r²/2} ∫ dt φ(t + l − r g_j) × (A^e, A^ep, A^p, W^e, W^ep, W^p, dW/dω, ·)
    with the per-asperity laws at ω = σ t, κ_m = r c_j, ω_c = σ tc1_j/r; the 8th column is
    the load-jump term (see _ep_r_sums). Parallel over (l, θ-node) pairs."""
    n_theta = g.shape[0]
    ln_r = math.log(ratio)
    for ij in numba.prange(l_values.shape[0] * n_theta):
        i = ij // n_theta
        j = ij - i * n_theta
        l = l_values[i]
        acc = np.zeros(8)
        lo, peak, hi = _r_window(g[j], l)
        if peak > lo:
            _ep_r_sums(lo, peak, l, g[j], c[j], f1[j], f2[j], f3[j], tc1[j], sigma, E_star, ratio, cH, dp,
                       ln_r, pv, with_jump, y_r, w_r, y_t, w_t, acc)
            _ep_r_sums(peak, hi, l, g[j], c[j], f1[j], f2[j], f3[j], tc1[j], sigma, E_star, ratio, cH, dp,
                       ln_r, pv, with_jump, y_r, w_r, y_t, w_t, acc)
        else:
            _ep_r_sums(lo, hi, l, g[j], c[j], f1[j], f2[j], f3[j], tc1[j], sigma, E_star, ratio, cH, dp,
                       ln_r, pv, with_jump, y_r, w_r, y_t, w_t, acc)
        for q in range(8):
            out[i, j, q] = acc[q]


def asperity_law(omega, kappa, f1, f2, f3, wc, E_star, ratio, cH, dp) -> np.ndarray:
    """The numba per-asperity law at arrays of points; columns (A, W, dW/dω, regime).
    Mirrors asperity.respond (used by the tests to compare the two)."""
    arrs = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (omega, kappa, f1, f2, f3, wc)))
    flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrs]
    out = np.empty((flat[0].shape[0], 4))
    _asperity_law_array(*flat, float(E_star), float(ratio), float(cH), float(dp), math.log(ratio), out)
    return out


def polar_elastoplastic_integrals(l_values, nodes, sigma, material_constants, accuracy="table") -> np.ndarray:
    """Per (l, θ-node) (r, t)-integrals of the elasto-plastic laws; shape (n_l, n_θ, 8).

    ``nodes``: dict of per-θ-node arrays g, c, f1, f2, f3, tc1 (tc1 = ω_c(θ, κ_m = c(θ))/σ);
    ``material_constants``: (E*, ω_p/ω_c, c_h H, H (c_h − (2/3) K_v), (2/3) K_v H, with_jump).
    Columns: A^e, A^ep, A^p, W^e, W^ep, W^p, dW/dω, load-jump term (elastoplastic.py
    applies the θ-weights and D_sum)."""
    l_values = np.ascontiguousarray(np.atleast_1d(np.asarray(l_values, dtype=float)))
    if not np.all(np.isfinite(l_values)):
        raise ValueError("separations must be finite")
    _, (y_r, w_r), (y_t, w_t) = elastoplastic_settings_for(accuracy).rules()
    arr = {k: np.ascontiguousarray(nodes[k], dtype=float) for k in ("g", "c", "f1", "f2", "f3", "tc1")}
    E_star, ratio, cH, dp, pv, with_jump = material_constants
    out = np.empty((l_values.shape[0], arr["g"].shape[0], 8))
    _polar_elastoplastic_kernel(
        l_values, arr["g"], arr["c"], arr["f1"], arr["f2"], arr["f3"], arr["tc1"], float(sigma),
        float(E_star), float(ratio), float(cH), float(dp), float(pv), bool(with_jump),
        y_r, w_r, y_t, w_t, out,
    )
    return out


#: Presets of the elasto-plastic kernel. The regime parts (A^e, A^ep, A^p, ...) need a finer
#: r-rule than the elastic totals: where t_c = tc1/r sweeps the Gaussian window the part
#: integrands have a knee at small r (r ~ tc1 at high ψ). Measured against levels (6, 6, 6)
#: and the scipy twin (tests/test_elastoplastic.py): "table" ≤ 1e-12 relative on totals and
#: parts above 1e-3 of their total; "plot" ≤ 1e-8.
ELASTOPLASTIC_PRESETS: dict[str, QuadratureSettings] = {
    "table": QuadratureSettings(theta_level=4, r_level=5, t_level=4),
    "plot": QuadratureSettings(theta_level=3, r_level=4, t_level=3),
}


def elastoplastic_settings_for(accuracy) -> QuadratureSettings:
    """Resolve an elasto-plastic accuracy preset name (or pass a QuadratureSettings through)."""
    return settings_for(accuracy, ELASTOPLASTIC_PRESETS)
