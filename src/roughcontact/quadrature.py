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


def settings_for(accuracy) -> QuadratureSettings:
    """Resolve an accuracy preset name (or pass a QuadratureSettings through)."""
    if isinstance(accuracy, QuadratureSettings):
        return accuracy
    try:
        return PRESETS[accuracy]
    except KeyError:
        raise ValueError(
            f"unknown accuracy preset {accuracy!r}; choose one of {sorted(PRESETS)}"
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
