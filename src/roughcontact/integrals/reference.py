"""High-precision (mpmath) reference values of the elastic summit integrals.

This is the slow, independent twin of the numba kernels in kernels.py: it evaluates the
dimensionless double integrals of docs/derivation.md (the polar form of (49), (52), (53), (55)
and (24)) to ≥ 15 significant digits at ``dps=20``, with its own mpmath elliptic functions and
its own inversion of (27) (:mod:`.reference_functions`; it does not use
roughcontact.asperity.ellipse).

The integrals, with cs = cos θ sin θ, J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt = E[(Z + a)₊^ν] and
l = s/√μ (23), are

    area       ∫ dθ cs f1(θ)/c(θ)  ∫ dr r²      e^{−r²/2} J_1(r g(θ) − l)        (52)
    load       ∫ dθ cs f2(θ)/√c(θ) ∫ dr r^{5/2} e^{−r²/2} J_{3/2}(r g(θ) − l)    (53)
    stiffness  ∫ dθ cs f2(θ)/√c(θ) ∫ dr r^{5/2} e^{−r²/2} J_{1/2}(r g(θ) − l)    (55)
    bearing    ∫ dθ √cs            ∫ dr r²      e^{−r²/2} J_1(r g(θ) − l)        (22)/(24)
    count      ∫ dθ cs             ∫ dr r³      e^{−r²/2} J_0(r g(θ) − l)        (49)/(50)

(θ ∈ (0, π/2), r > 0). ``count`` is P(l) of (49), the fraction of summits above l (= 1 at
l → −∞). c(θ) = (√m40 cos θ + √m04 sin θ)/2 carries units 1/L, so the area integral carries
units L (through 1/c), load and stiffness L^{1/2} (1/√c); bearing and count are
dimensionless. The dimensional prefactors (polar.ElasticPrefactors, units L^{−1}, L^{−1/2})
are NOT applied by :func:`elastic_integrals`; :func:`elastic_reference` applies them.

How the inner integral is done
------------------------------
The inner (r, t) integral for one θ,

    I_{p,ν}(θ; l) = ∫₀^∞ dr r^p e^{−r²/2} J_ν(r g − l)
                  = (2π)^{−1/2} ∫∫_{r,t>0} r^p t^ν exp(−[r² + (t + l − r g)²]/2) dt dr,

is evaluated in polar coordinates of the (r, t) quarter plane, r = ρ cos ψ, t = ρ sin ψ.
For every quantity n = p + ν + 1 is an INTEGER (4, 5, 4, 4, 4), so the ρ-integral is
elementary:

    I_{p,ν} = ∫₀^{π/2} dψ cos^p ψ sin^ν ψ A^{−(n+1)/2} exp(−l² cos²ψ/(2A)) J_n(−b),
    d = sin ψ − g cos ψ,  A = cos²ψ + d²,  b = l d/√A,

with J_0 = Φ, J_1(a) = aΦ(a) + φ(a), J_{k+1} = a J_k + k J_{k−1} (integration by parts),
evaluated with enough guard digits for the cancellation at a < 0. This is ~8× faster than
integrating J_ν(r g − l) = Γ(ν+1)/√(2π) e^{−a²/4} D_{−ν−1}(−a) (mpmath.pcfd) over r, and the
two agree to ~1e-18 (tests/integrals/test_reference.py); ``inner="r"`` selects the literal r-form of
docs/derivation.md with the parabolic-cylinder J_ν, for cross-checks.

Quadrature
----------
θ: tanh-sinh (mpmath's nodes), split at θ* = atan(√(m40/m04)) (λ = 1, where the ellipse
turns and f1, f2 are not smooth) and, for ``hertz="paper"``, at the two θ where
λ = 1/(0.4777 + 1.3211) (the clip of (33)). ψ: tanh-sinh split at the mode of the (r, t)
integrand (r near l g/(1 + g²), the Gaussian peak; t near the mode of t^ν φ(t − a)).
Both use a vector-valued driver (all quantities share the nodes) with a RELATIVE stopping
rule 10^−dps (mpmath.quad's is absolute, which loses digits for the tiny integrals at large
s) and a more conservative error extrapolation than mpmath's.
The inner integral depends on θ only through g(θ): by default it is computed at 17 or 33
(up to 129 if needed) Chebyshev–Lobatto nodes in g ∈ [g_min, g_max] and ln I is
interpolated; ``interpolate=False`` gives the plain nested quadrature (same values).

Accuracy (relative, against dps=30, Tables 1–2 surfaces and an α1 ≠ α2 surface, both Hertz
modes, s = 0, 1, 2.5, 5, all four quantities): dps=20 ≤ 7e-22, dps=12 ≤ 1e-13; the
returned error estimates bounded every measured error. Cost per separation (all requested
quantities together, ~2 cores shared): ≈0.2–0.8 s at dps=12, ≈0.5–2 s at dps=20; the first
call per surface and precision with ``hertz="exact"`` adds 2–6 s for the exact inversions
of (27) at the θ nodes (memoised).
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import mpmath as mp
import mpmath.libmp as L
import numpy as np
from mpmath.calculus.quadrature import TanhSinh

from ..statistics.surface import SpectralMoments
from .polar import ElasticPrefactors
from .reference_functions import HERTZ_MODES, hertz_factors, normal_moment, paper_clip_lambda

__all__ = [
    "QUANTITIES",
    "ReferenceValue",
    "inner_integral",
    "elastic_integrals",
    "elastic_reference",
]

#: quantity → (p, ν, θ-weight): the powers of r and t in the integrand (see module docstring).
_SPEC = {
    "area": (2, 1, "f1/c"),
    "load": (mp.mpf(5) / 2, mp.mpf(3) / 2, "f2/sqrt(c)"),
    "stiffness": (mp.mpf(5) / 2, mp.mpf(1) / 2, "f2/sqrt(c)"),
    "bearing": (2, 1, "sqrt(cs)"),
    "count": (3, 0, "1"),
}
QUANTITIES = tuple(_SPEC)
#: mpmath's tanh-sinh rule (nodes cached per degree and precision)
_TANH_SINH = TanhSinh(mp.mp)


@dataclass(frozen=True)
class ReferenceValue:
    """One reference integral: ``value`` (mpmath mpf) and ``error``, an estimate of its
    absolute error: the θ tanh-sinh estimate + (largest relative inner estimate + Chebyshev
    interpolation estimate + 10·10^−dps rounding) × |value|. Tanh-sinh estimates are
    extrapolations, not bounds (all measured errors were below them). ``seconds``: wall
    time of the elastic_integrals call that produced it (shared by its quantities)."""

    value: mp.mpf
    error: mp.mpf
    dps: int
    seconds: float = 0.0

    def __float__(self) -> float:
        return float(self.value)

    @property
    def relative_error(self) -> float:
        return float(self.error / abs(self.value)) if self.value else float(self.error)


# ---------------------------------------------------------------------------------------
# vector-valued tanh-sinh (mpmath's nodes, relative stopping rule)
# ---------------------------------------------------------------------------------------
def _tanh_sinh(f, points, ncomp: int, rel_tol, maxdegree: int):
    """∫ f over the intervals of ``points`` for an f returning ``ncomp`` mpf values.

    mpmath's tanh-sinh rule (TanhSinh.get_nodes on [−1, 1], cached there; each degree halves
    the step and re-uses the previous sum) mapped linearly to each interval without caching
    the mapped nodes. Per interval the degree rises until, for every component, the
    Borwein–Bailey–Girgensohn extrapolated error (as in mpmath's estimate_error) is
    ≤ rel_tol × |value| — a RELATIVE criterion, unlike mpmath.quad's absolute eps, so tiny
    integrals (large separations) keep their significant digits.

    Returns (values, errors): lists of mpf; errors are absolute estimates."""
    rule = _TANH_SINH
    prec = mp.mp.prec
    total = [mp.mpf(0)] * ncomp
    total_err = [mp.mpf(0)] * ncomp
    for a, b in zip(points[:-1], points[1:]):
        if a == b:
            continue
        C, D = (b - a) / 2, (b + a) / 2
        history: list[list] = []
        err = [mp.mpf(0)] * ncomp
        for degree in range(1, maxdegree + 1):
            nodes = rule.get_nodes(-1, 1, degree, prec)
            h = mp.ldexp(1, -degree)
            ws, fs = [], []
            for x, w in nodes:
                ws.append(w)
                fs.append(f(D + C * x))
            hC = h * C
            new = [hC * mp.fdot(ws, [fx[i] for fx in fs]) for i in range(ncomp)]
            if history:  # the previous degree's nodes are half of this degree's
                new = [n + v / 2 for n, v in zip(new, history[-1])]
            history.append(new)
            if degree == 1:
                continue
            done = True
            for i in range(ncomp):
                err[i] = _ts_error([r[i] for r in history])
                if err[i] > rel_tol * abs(history[-1][i]):
                    done = False
            if done:
                break
        for i in range(ncomp):
            total[i] += history[-1][i]
            total_err[i] += err[i]
    return total, total_err


def _ts_error(results):
    """mpmath's TanhSinh error extrapolation (estimate_error) for one component, made
    relative to the value (so it does not bottom out at an absolute floor for tiny
    integrals): with D1, D2 the log10 relative changes over the last one and two degrees,
    the error is ~ 10^{max(D1²/D2, 1.5 D1)} (mpmath uses 2 D1: each degree doubling the
    digits; 1.5 is more conservative)."""
    r = results[-1]
    if len(results) == 2:
        return abs(r - results[0])
    if r == results[-2] == results[-3]:
        return mp.mpf(0)
    scale = abs(r)
    if scale == 0:
        return max(abs(results[-2]), abs(results[-3]))
    d1 = abs(r - results[-2]) / scale
    d2 = abs(r - results[-3]) / scale
    floor = -mp.mp.dps - 5
    if d1 == 0:
        return scale * mp.power(10, floor)
    D1 = mp.log10(d1)
    if d2 == 0 or d2 <= d1:
        return scale * d1
    D2 = mp.log10(d2)
    if D1 >= 0:
        return scale * d1
    # mpmath caps the extrapolation at 2·D1 (digits exactly doubling); convergence is not
    # always that clean (seen: a degree-4 result 5e-18 off with 2·D1 = −21), so cap at 1.5·D1
    D4 = min(mp.mpf(0), max(D1**2 / D2, 3 * D1 / 2, floor)) if D2 < 0 else D1
    return scale * mp.power(10, D4)


def _default_maxdegree(dps: int) -> int:
    """mpmath's own guess for the working precision, plus one level."""
    return max(6, _TANH_SINH.guess_degree(mp.mp.prec) + 1)


# ---------------------------------------------------------------------------------------
# θ-geometry (docs/derivation.md, (43)–(44), (27)) with memoised Hertz factors
# ---------------------------------------------------------------------------------------
class _ThetaFactors:
    """θ-dependent factors for one surface and Hertz mode, memoised per (θ, precision):
    the θ nodes are the same for every quantity and every separation."""

    def __init__(self, surface: SpectralMoments, hertz: str):
        self.surface = surface
        self.hertz = hertz
        self._cache: dict = {}

    def constants(self):
        """(moments, √β1, √β2, √μ, √m40, √m04) as mpf at the current precision, (10)–(11)."""
        key = ("constants", mp.mp.prec)
        hit = self._cache.get(key)
        if hit is None:
            m = {k: mp.mpf(v) for k, v in self.surface.as_dict().items()}
            beta1 = m["m20"] ** 2 / (m["m00"] * m["m40"])  # (11)
            beta2 = m["m02"] ** 2 / (m["m00"] * m["m04"])
            mu = 1 - beta1 - beta2  # (10)
            hit = self._cache[key] = (m, mp.sqrt(beta1), mp.sqrt(beta2), mp.sqrt(mu),
                                      mp.sqrt(m["m40"]), mp.sqrt(m["m04"]))
        return hit

    def breakpoints(self):
        """θ split points in (0, π/2): θ* (ρ = 1) and, for "paper", the clip of (33)."""
        _, _, _, _, s40, s04 = self.constants()
        k = s40 / s04  # ρ = k cot θ
        pts = [mp.atan(k)]
        if self.hertz == "paper":
            lam_c2 = paper_clip_lambda() ** 2
            pts += [mp.atan(k * lam_c2), mp.atan(k / lam_c2)]
        return sorted(pts)

    def __call__(self, theta):
        """dict of g, and the θ-weights "f1/c" = cs f1/c, "f2/sqrt(c)" = cs f2/√c,
        "sqrt(cs)" = √cs, "1" = cs; None at rounded end points (cos θ or sin θ ≤ 0)."""
        key = (theta, mp.mp.prec)
        hit = self._cache.get(key)
        if hit is not None:
            return hit
        _, sb1, sb2, smu, s40, s04 = self.constants()
        co, si = mp.cos_sin(theta)
        if co <= 0 or si <= 0:
            return None
        cs = co * si
        g = (sb1 * co + sb2 * si) / smu  # mean of ω1 per unit r
        c = (s40 * co + s04 * si) / 2  # κm = r c(θ), (43)–(44)
        rho = s40 * co / (s04 * si)  # |ξ4|/|ξ6|
        lam2 = min(rho, 1 / rho)  # (27): the ellipse turns at ρ = 1
        _, f1, f2 = hertz_factors(lam2, self.hertz)
        out = {"g": g, "f1/c": cs * f1 / c, "f2/sqrt(c)": cs * f2 / mp.sqrt(c),
               "sqrt(cs)": mp.sqrt(cs), "1": cs}
        if len(self._cache) > 100_000:
            self._cache.clear()
        self._cache[key] = out
        return out


@functools.lru_cache(maxsize=32)
def _theta_factors(surface: SpectralMoments, hertz: str) -> _ThetaFactors:
    return _ThetaFactors(surface, hertz)


# ---------------------------------------------------------------------------------------
# the inner (r, t) integral for one θ
# ---------------------------------------------------------------------------------------
def _psi_split(p, nu, g, l):
    """ψ at the approximate mode of r^p t^ν exp(−[r² + (t + l − r g)²]/2): r0 maximises
    r^p e^{−r²/2 − (rg − l)²/2} (the Gaussian peak near l g/(1 + g²) for l > 0), t0 maximises
    t^ν φ(t − a0), a0 = r0 g − l."""
    if l > 0:
        r0 = (l * g + mp.sqrt(l * l * g * g + 4 * p * (1 + g * g))) / (2 * (1 + g * g))
    else:
        r0 = mp.sqrt(p)
    a0 = r0 * g - l
    t0 = (a0 + mp.sqrt(a0 * a0 + 4 * nu)) / 2 if nu > 0 else max(a0, mp.mpf(0))
    if t0 <= 0:
        t0 = 1 / (1 + abs(a0))  # ν = 0 with a0 ≤ 0: the Φ tail has scale 1/|a0|
    return mp.atan2(t0, r0)


def _pow(x, p):
    """x^p for p ∈ {0, 1/2, 1, 3/2, 2, 5/2, 3, ...} without a log/exp."""
    k = int(p)
    y = x**k if k else mp.mpf(1)
    return y * mp.sqrt(x) if p != k else y


def _psi_integrand(spec, g, l, nmax, wp):
    """The ψ-integrand of the (ρ, ψ) form for all (2p, 2ν, n) in ``spec``:

        cos^p ψ sin^ν ψ A^{−(n+1)/2} exp(−l² cos²ψ/(2A)) J_n(a),
        d = sin ψ − g cos ψ, A = cos²ψ + d², a = −l d/√A,

    with J_0..J_nmax from J_0 = Φ, J_1 = aΦ + φ, J_{k+1} = a J_k + k J_{k−1} at 2 n log2|a|
    guard bits for a < 0 (where the recurrence cancels). Written with mpmath's low-level
    libmp functions on raw mpf tuples (≈3× faster than mpf objects; this is the hot loop)."""
    rnd = L.round_nearest
    mul, add, sub, div = L.mpf_mul, L.mpf_add, L.mpf_sub, L.mpf_div
    g_, l_ = g._mpf_, l._mpf_
    half_l2 = L.mpf_shift(mul(l_, l_, wp, rnd), -1)
    zero = mp.mpf(0)
    make = mp.mp.make_mpf
    consts: dict = {}

    def constants(ep):  # 1/√2, 1/√(2π) at ≥ ep bits
        key = max(ep, wp + 128)
        c = consts.get(key)
        if c is None:
            two = L.from_int(2)
            c = consts[key] = (
                div(L.fone, L.mpf_sqrt(two, key + 10, rnd), key, rnd),
                div(L.fone, L.mpf_sqrt(mul(two, L.mpf_pi(key + 10), key + 10, rnd), key + 10, rnd), key, rnd),
            )
        return c

    def powh(x, sqx, twice):  # x^{twice/2}, None for x^0
        k, odd = divmod(twice, 2)
        y = None
        for _ in range(k):
            y = x if y is None else mul(y, x, wp, rnd)
        if odd:
            y = sqx if y is None else mul(y, sqx, wp, rnd)
        return y

    def h(psi):
        co, si = L.mpf_cos_sin(psi._mpf_, wp, rnd)
        if L.mpf_sign(co) <= 0 or L.mpf_sign(si) <= 0:
            return [zero] * len(spec)
        d = sub(si, mul(g_, co, wp, rnd), wp, rnd)
        co2 = mul(co, co, wp, rnd)
        A = add(co2, mul(d, d, wp, rnd), wp, rnd)
        inv_sqA = div(L.fone, L.mpf_sqrt(A, wp, rnd), wp, rnd)
        a = L.mpf_neg(mul(mul(l_, d, wp, rnd), inv_sqA, wp, rnd))  # J_n(−b), b = l d/√A
        af = L.to_float(a)
        ep = wp + 10 + (int(2 * nmax * math.log2(1.0 - af)) + 4 if af < 0 else 0)
        inv_sqrt2, inv_sqrt2pi = constants(ep)
        Phi = L.mpf_shift(L.mpf_erfc(L.mpf_neg(mul(a, inv_sqrt2, ep, rnd)), ep, rnd), -1)
        phi = mul(L.mpf_exp(L.mpf_neg(L.mpf_shift(mul(a, a, ep, rnd), -1)), ep, rnd), inv_sqrt2pi, ep, rnd)
        J = [Phi, add(mul(a, Phi, ep, rnd), phi, ep, rnd)]
        for k in range(1, nmax):
            J.append(add(mul(a, J[k], ep, rnd), L.mpf_mul_int(J[k - 1], k, ep, rnd), ep, rnd))
        common = L.mpf_exp(L.mpf_neg(div(mul(half_l2, co2, wp, rnd), A, wp, rnd)), wp, rnd)
        sq_co, sq_si = L.mpf_sqrt(co, wp, rnd), L.mpf_sqrt(si, wp, rnd)
        out = []
        for tp, tnu, n in spec:
            v = mul(common, J[n], wp, rnd)
            v = mul(v, L.mpf_pow_int(inv_sqA, n + 1, wp, rnd), wp, rnd)  # A^{−(n+1)/2}
            for f in (powh(co, sq_co, tp), powh(si, sq_si, tnu)):
                if f is not None:
                    v = mul(v, f, wp, rnd)
            out.append(make(v))
        return out

    return h


def _inner_psi(pairs, g, l, rel_tol, maxdegree, alternate=False):
    """I_{p,ν}(θ; l) for every (p, ν) in ``pairs`` via the polar (ρ, ψ) form with the
    elementary ρ-integral (module docstring); one ψ-node serves all pairs."""
    ns = [int(p + nu + 1) for p, nu in pairs]
    if any(n != p + nu + 1 for n, (p, nu) in zip(ns, pairs)):
        raise ValueError("the (rho, psi) form needs p + nu integer")
    for p, nu in pairs:
        if 2 * p != int(2 * p) or 2 * nu != int(2 * nu):
            raise ValueError("p and nu must be multiples of 1/2")
    nmax = max(ns)
    # (2p, 2ν, n) per pair: powers assembled from co, √co, si, √si and 1/√A
    spec = [(int(2 * p), int(2 * nu), n) for (p, nu), n in zip(pairs, ns)]
    h = _psi_integrand(spec, g, l, nmax, mp.mp.prec)
    # split at the (r, t) mode of the middle pair; "alternate" adds the other modes and midpoints
    p_mid = max(p for p, _ in pairs)
    nu_mid = (min(nu for _, nu in pairs) + max(nu for _, nu in pairs)) / 2
    psi0 = _psi_split(p_mid, nu_mid, g, l)
    half_pi = mp.pi / 2
    pts = [mp.mpf(0), psi0, half_pi]
    if alternate:
        pts = sorted({mp.mpf(0), half_pi, psi0 / 2, (psi0 + half_pi) / 2,
                      *(_psi_split(p, nu, g, l) for p, nu in pairs)})
    return _tanh_sinh(h, pts, len(pairs), rel_tol, maxdegree)


def _inner_r(pairs, g, l, rel_tol, maxdegree, alternate=False):
    """I_{p,ν}(θ; l) literally: ∫ dr r^p e^{−r²/2} J_ν(r g − l) with J_ν from
    :func:`normal_moment` (pcfd), r on [0, r_peak, r_peak + 12] (r_peak ≈ max(l g/(1 + g²), 1),
    the peak of the Gaussian factor; 12 beyond it the Gaussian factors have fallen by ≥ e^{−72})."""
    r_peak = max(l * g / (1 + g * g), mp.mpf(1))

    def f(r):
        e = mp.exp(-r * r / 2)
        return [_pow(r, p) * e * normal_moment(nu, r * g - l) for p, nu in pairs]

    pts = [mp.mpf(0), r_peak, r_peak + 12]
    if alternate:
        pts = [mp.mpf(0), r_peak / 2, r_peak, r_peak + 3, r_peak + 14]
    return _tanh_sinh(f, pts, len(pairs), rel_tol, maxdegree)


def inner_integral(quantity: str, g, l, dps: int = 20, inner: str = "psi", alternate: bool = False):
    """I_{p,ν}(θ; l) = ∫₀^∞ dr r^p e^{−r²/2} J_ν(r g − l) for one θ (given through g(θ)),
    (p, ν) of ``quantity``; ``inner`` = "psi" (default) or "r". Returns (value, abs. error)."""
    p, nu, _ = _SPEC[quantity]
    with mp.workdps(dps):
        tol = mp.mpf(10) ** -dps
        md = _default_maxdegree(dps)
        with mp.extraprec(10):
            fn = _inner_psi if inner == "psi" else _inner_r
            (v,), (e,) = fn([(p, nu)], mp.mpf(g), mp.mpf(l), tol, md, alternate)
        return +v, +e


# ---------------------------------------------------------------------------------------
# public: the dimensionless double integrals
# ---------------------------------------------------------------------------------------
class _ChebyshevLogInterpolant:
    """ln I_{p,ν}(g; l) on [g_min, g_max] by Chebyshev–Lobatto interpolation.

    The inner integral depends on θ only through g(θ), and is an entire, positive function of
    g; its logarithm is nearly polynomial (≈ −l²/(2(1 + g²)) + smooth terms at large l).
    The node count N doubles (16, 32, 64, 128; Lobatto nodes nest, so values are reused)
    until the last three Chebyshev coefficients of every ln I are ≤ rel_tol; their sum is
    the interpolation error estimate (a relative error of I)."""

    def __init__(self, evaluate, ncomp, g_min, g_max, rel_tol, n_start=16, n_max=128):
        self.mid, self.half = (g_max + g_min) / 2, (g_max - g_min) / 2
        self.inner_error = mp.mpf(0)  # largest relative error estimate of the node values
        values: dict = {}  # k/N as a Fraction-like key (k, N) reduced → list of ln I
        N = n_start
        while True:
            f = []
            for k in range(N + 1):
                key = _reduced(k, N)
                if key not in values:
                    g = self.mid + self.half * mp.cospi(mp.mpf(k) / N)
                    vals, errs = evaluate(g)
                    for v, e in zip(vals, errs):
                        if v <= 0:
                            raise FloatingPointError(f"inner integral not positive at g={g}: {v}")
                        self.inner_error = max(self.inner_error, e / v)
                    values[key] = [mp.log(v) for v in vals]
                f.append(values[key])
            self.coef = [_chebyshev_lobatto_coefficients([fk[i] for fk in f]) for i in range(ncomp)]
            self.interp_error = max(sum(abs(c) for c in cs[-3:]) for cs in self.coef)
            self.n = N
            if self.interp_error <= rel_tol or N >= n_max:
                break
            N *= 2

    def __call__(self, g):
        x = (g - self.mid) / self.half
        x = max(min(x, mp.mpf(1)), mp.mpf(-1))
        return [mp.exp(_clenshaw(cs, x)) for cs in self.coef]


def _reduced(k, N):
    d = math.gcd(k, N)
    return (k // d, N // d)


def _chebyshev_lobatto_coefficients(f):
    """c_j of p(x) = Σ c_j T_j(x) interpolating f_k at x_k = cos(πk/N), k = 0..N."""
    N = len(f) - 1
    cos_table = [mp.cospi(mp.mpf(m) / N) for m in range(2 * N)]
    fw = [fk / 2 if k in (0, N) else fk for k, fk in enumerate(f)]
    coef = []
    for j in range(N + 1):
        c = mp.fsum(fw[k] * cos_table[(j * k) % (2 * N)] for k in range(N + 1)) * 2 / N
        coef.append(c / 2 if j in (0, N) else c)
    return coef


def _clenshaw(coef, x):
    b1 = b2 = mp.mpf(0)
    for c in reversed(coef[1:]):
        b1, b2 = c + 2 * x * b1 - b2, b1
    return coef[0] + x * b1 - b2


def elastic_integrals(
    surface: SpectralMoments,
    l,
    hertz: str = "exact",
    dps: int = 20,
    quantities=("area", "load", "stiffness"),
    *,
    interpolate: bool = True,
    inner: str = "psi",
    alternate: bool = False,
    maxdegree: int | None = None,
) -> dict[str, ReferenceValue]:
    """The dimensionless integrals of docs/derivation.md at l = s/√μ (23), without prefactors.

    ``quantities`` ⊆ {"area", "load", "stiffness", "bearing", "count"} (module docstring; the
    values carry units L (area) or L^{1/2} (load, stiffness) through 1/c, 1/√c; bearing and
    count are dimensionless).
    ``hertz``: "exact" | "paper" | "circle". ``dps``: working digits; every quadrature and
    the interpolation stop at a relative error estimate 10^−dps. Measured (vs dps=30):
    dps=20 → ~1e-21, dps=12 → ~1e-13 relative.

    θ: tanh-sinh, split at θ* (and at the clip of (33) for "paper"). The inner integral
    depends on θ only through g(θ); with ``interpolate=True`` (default) it is computed at
    17–129 Chebyshev nodes in g and ln I interpolated (error included in the estimate);
    ``interpolate=False`` runs the plain nested quadrature (an inner tanh-sinh per θ node,
    ~6× slower; the two agree to the working precision). ``inner`` ("psi" | "r": the
    elementary (ρ, ψ) form or the literal r-integral with pcfd J_ν), ``alternate`` (more
    split points) and ``maxdegree`` (tanh-sinh levels) exist for cross-checks.

    All quantities share the nodes: asking for several costs little more than one.
    ``ReferenceValue.seconds`` is the wall time of the whole call.
    """
    if not isinstance(surface, SpectralMoments):
        raise TypeError(f"surface must be a SpectralMoments, got {type(surface).__name__}")
    if hertz not in HERTZ_MODES:
        raise ValueError(f"hertz must be one of {', '.join(HERTZ_MODES)}; got {hertz!r}")
    if isinstance(quantities, str):
        quantities = (quantities,)
    quantities = tuple(quantities)
    for q in quantities:
        if q not in _SPEC:
            raise ValueError(f"unknown quantity {q!r}; choose from {', '.join(QUANTITIES)}")
    if inner not in ("psi", "r"):
        raise ValueError(f"inner must be 'psi' or 'r', got {inner!r}")
    inner_fn = _inner_psi if inner == "psi" else _inner_r
    factors = _theta_factors(surface, hertz)
    pairs = sorted({_SPEC[q][:2] for q in quantities})
    t_start = time.perf_counter()

    with mp.workdps(dps):
        rel_tol = mp.mpf(10) ** -dps
        md = maxdegree or _default_maxdegree(dps)
        with mp.extraprec(10):  # guard bits for the sums
            l_mp = mp.mpf(l)
            th_pts = [mp.mpf(0)] + factors.breakpoints() + [mp.pi / 2]
            if alternate:
                th_pts = sorted(th_pts + [(a + b) / 2 for a, b in zip(th_pts[:-1], th_pts[1:])])
            worst_inner = [mp.mpf(0)]

            def inner_at(g):
                return inner_fn(pairs, g, l_mp, rel_tol, md, alternate)

            if interpolate:
                _, sb1, sb2, smu, _, _ = factors.constants()
                g_end = sorted([sb1 / smu, sb2 / smu])  # g(0), g(π/2)
                g_top = mp.sqrt(sb1**2 + sb2**2) / smu  # max of g at tan θ = √(β2/β1)
                interp = _ChebyshevLogInterpolant(inner_at, len(pairs), g_end[0], g_top, rel_tol)
                worst_inner[0] = interp.inner_error + interp.interp_error

            def F(theta):
                fac = factors(theta)
                if fac is None:
                    return [mp.mpf(0)] * len(quantities)
                if interpolate:
                    vals = interp(fac["g"])
                else:
                    vals, errs = inner_at(fac["g"])
                    for v, e in zip(vals, errs):
                        if v and e / abs(v) > worst_inner[0]:
                            worst_inner[0] = e / abs(v)
                by_pair = dict(zip(pairs, vals))
                return [fac[_SPEC[q][2]] * by_pair[_SPEC[q][:2]] for q in quantities]

            values, errors = _tanh_sinh(F, th_pts, len(quantities), rel_tol, md)
        seconds = time.perf_counter() - t_start
        rounding = 10 * rel_tol  # evaluation at dps digits (not in the tanh-sinh estimates)
        return {
            q: ReferenceValue(+v, +(e + (worst_inner[0] + rounding) * abs(v)), dps, seconds)
            for q, v, e in zip(quantities, values, errors)
        }


def elastic_reference(surface: SpectralMoments, s_values, hertz: str = "exact", dps: int = 20,
                      quantities=("area", "load", "stiffness", "bearing")) -> dict[str, np.ndarray]:
    """Floats at separations s = h/√m00: "area" A/A0, "load" W/(A0 E*), "stiffness"
    K/(A0 E*) [1/L], "bearing" A_G — the integrals times polar.ElasticPrefactors (52), (53),
    (55), (24); "count" (if asked) is P(l) of (49) (no prefactor)."""
    s_arr = np.atleast_1d(np.asarray(s_values, dtype=float))
    pre = ElasticPrefactors.of(surface)
    scale = {"area": pre.area, "load": pre.load, "stiffness": pre.stiffness,
             "bearing": pre.bearing, "count": 1.0}
    out = {q: np.empty(s_arr.size) for q in quantities}
    for i, l in enumerate(surface.l_from_s(s_arr)):
        vals = elastic_integrals(surface, float(l), hertz=hertz, dps=dps, quantities=quantities)
        for q in quantities:
            out[q][i] = scale[q] * float(vals[q].value)
    return out
