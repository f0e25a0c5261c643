"""The numba production kernels of the summit integrals (elastic and elasto-plastic).

The integrals are those of docs/derivation.md in polar form, θ outside, r in the middle and
the interference t inside, against the Gaussian φ(t + l − r g(θ)). What makes them fast
(docs/performance.md has the measurements):

* t in closed form. Elastic summits need only J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt, ν = 1/2, 1, 3/2,
  evaluated from the Chebyshev tables of normal_moments.py (≤ 7e-16 relative, exact zero
  below a ≈ −38.6) instead of ~200 tanh-sinh nodes per (θ, r) node.
* r on a partition that follows the integrand: for l > 0 the factor e^{−r²/2} φ(r g − l)
  is a Gaussian of width 1/√(1 + g²) centred near r = l g/(1 + g²) while a = r g − l < 0,
  and beyond r = l/g (a > 0) J_ν is algebraic and e^{−r²/2} sets the decay; the pieces are
  cut at the modes of both parts, at l/g and inside the long right tail, each piece a
  Gauss–Legendre rule (in u = √r next to r = 0, where r^{5/2} is not smooth). Everything is
  scaled by e^{S}, S = l²/(2(1 + g²)), so nothing underflows before the final product.
* (elastic) θ only through g(θ): the inner r-integrals are computed at Chebyshev–Lobatto
  nodes in g (9, then 17, 33, 65 if needed: nested) and ln of the scaled integrals is
  interpolated; the θ-sum then costs one short Clenshaw series per θ-node. If the series has
  not converged to the preset's tolerance at 65 nodes, every θ-node is integrated directly.
* (elasto-plastic) the τ = r t route: the law depends on τ = r t alone (times powers of r), so
  each column is ∫ F(τ) G_k(τ) dτ with G_k the summit measure on the hyperbola r t = τ, computed
  once per separation on a grid in (g, ln τ) and interpolated; each θ-node integrates its
  regime pieces in ln τ against it (section "The elasto-plastic integrals" below).

θ is a composite tanh-sinh rule (split at the axis turn θ*, the peak of g and the Hertz
kinks): it converges exponentially despite the logarithmic end-point singularities of the
Hertz factors at θ → 0, π/2.

Kernels are plain loops over arrays (fastmath off, cache=True); the Python API
(:mod:`.production`, then :mod:`roughcontact.contact`) validates inputs. All kernels that call
each other live in this one file: numba's on-disk cache is invalidated when a kernel's *own*
file changes, not when a callee's file does (tests/integrals/test_kernels.py enforces "no
cross-file kernel calls" and one signature per kernel). That is why this module is longer than
the others. Slow twins: the J_ν tables against mpmath
(tests/integrals/test_normal_moments.py); the r-rule against scipy.integrate.quad and the
g-interpolation against the direct θ-sum (tests/integrals/test_kernels.py); the whole elastic chain
against the mpmath integrator in reference.py (tests/contact/test_elastic.py, test_reference.py); the
hyperbola integrals against scipy.integrate.quad, their closed form at τ = 0 against mpmath, the
grid against direct evaluation, the θ-levels against finer ones (tests/integrals/test_ep_kernel.py);
the elasto-plastic kernel against the scipy twin elastoplastic.reference_integrals
(tests/contact/test_elastoplastic.py).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from . import normal_moments

#: −ln of the relative size at which Gaussian tails are cut (e^-40 ≈ 4e-18).
TAIL = 40.0
_SPAN = math.sqrt(2.0 * TAIL)
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)
_SPLITTER = 134217729.0  # 2^27 + 1 (Veltkamp split of a double into two 26-bit halves)
_EXP_UNDERFLOW = 745.2  # exp(−745.2) < the smallest subnormal double
#: powers (p, ν) used to place the r-breakpoints: the middle of the (2, 1), (5/2, 3/2),
#: (5/2, 1/2) of the area, load and stiffness integrands
_P_MODE = 2.5
_NU_MODE = 1.0
#: Chebyshev–Lobatto grids in g: 8, 16, 32, 64 intervals (nested)
_N_G_START = 8
_N_G_MAX = 64
_N_SIDE = normal_moments.N_SIDE
_X_SPLIT = normal_moments.X_SPLIT
assert normal_moments.WIDTH == 1.0 and normal_moments.NU == (0.0, 0.5, 1.0, 1.5)
assert normal_moments.N_COEF == 17  # _estrin17


@numba.njit(cache=True)
def _estrin17(p, y, y2, y4, y8, y16):
    """Σ_{k=0}^{16} p[k] y^k by Estrin's scheme (depth 5 instead of Horner's 16)."""
    q0 = p[0] + p[1] * y
    q1 = p[2] + p[3] * y
    q2 = p[4] + p[5] * y
    q3 = p[6] + p[7] * y
    q4 = p[8] + p[9] * y
    q5 = p[10] + p[11] * y
    q6 = p[12] + p[13] * y
    q7 = p[14] + p[15] * y
    r0 = (q0 + q1 * y2) + (q2 + q3 * y2) * y4
    r1 = (q4 + q5 * y2) + (q6 + q7 * y2) * y4
    return r0 + r1 * y8 + p[16] * y16


@numba.njit(cache=True)
def _poly4(c, row, y):
    """The four polynomials (ν = 0, 1/2, 1, 3/2) of table row ``row`` at y ∈ [−1, 1]."""
    cr = c[row]
    y2 = y * y
    y4 = y2 * y2
    y8 = y4 * y4
    y16 = y8 * y8
    return (_estrin17(cr[0], y, y2, y4, y8, y16), _estrin17(cr[1], y, y2, y4, y8, y16),
            _estrin17(cr[2], y, y2, y4, y8, y16), _estrin17(cr[3], y, y2, y4, y8, y16))


@numba.njit(cache=True)
def _moments(a, e, c):
    """(J_0, J_{1/2}, J_1, J_{3/2})(a) · e^{e} (normal_moments.py: a < 0 tabulates
    G_ν = J_ν/φ, so the Gaussian factor and e^{e} are one exact exp, which underflows to 0
    cleanly; e lets the kernels carry a scale without over- or underflow)."""
    if a < 0.0:
        x = -a
        if x > 1e150 or 0.5 * x * x - e > _EXP_UNDERFLOW:  # the product underflows: exactly 0
            return 0.0, 0.0, 0.0, 0.0
        if x < _X_SPLIT:
            k = int(x)
            g0, g1, g2, g3 = _poly4(c, k, 2.0 * (x - k) - 1.0)
        else:
            v = _X_SPLIT / x
            t0, t1, t2, t3 = _poly4(c, 2 * _N_SIDE, 2.0 * v * v - 1.0)
            ix = 1.0 / x
            sx = math.sqrt(ix)
            g0 = t0 * ix
            g1 = t1 * ix * sx
            g2 = t2 * ix * ix
            g3 = t3 * ix * ix * sx
        # x² = p + err exactly (Veltkamp/Dekker split): exp(−x²/2) to ≤ 1 ulp for |a| ≤ 38
        # (exp(−0.5·fl(x²)) alone would lose up to x²·1e-16 ≈ 8e-14 at a = −38)
        c_ = _SPLITTER * x
        hi = c_ - (c_ - x)
        lo = x - hi
        p = x * x
        err = ((hi * hi - p) + 2.0 * hi * lo) + lo * lo
        f = math.exp(e - 0.5 * p) * (1.0 - 0.5 * err) * _INV_SQRT_2PI
        return g0 * f, g1 * f, g2 * f, g3 * f
    f = math.exp(e)
    if a < _X_SPLIT:
        k = int(a)
        j0, j1, j2, j3 = _poly4(c, _N_SIDE + k, 2.0 * (a - k) - 1.0)
        return j0 * f, j1 * f, j2 * f, j3 * f
    v = _X_SPLIT / a
    t0, t1, t2, t3 = _poly4(c, 2 * _N_SIDE + 1, 2.0 * v * v - 1.0)
    sa = math.sqrt(a)
    return t0 * f, t1 * sa * f, t2 * a * f, t3 * a * sa * f


@numba.njit(cache=True)
def _moments_array(a_values, c, out):
    for i in range(a_values.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = _moments(a_values[i], 0.0, c)


# ---------------------------------------------------------------------------------------
# the r-partition (shared by the elastic and elasto-plastic kernels)
# ---------------------------------------------------------------------------------------
@numba.njit(cache=True)
def _mode_above(g, l):
    """The mode r_B > max(l/g, 0) of r^p (r g − l)^ν e^{−r²/2} (p, ν = _P_MODE, _NU_MODE):
    the root of −r + p/r + ν g/(r g − l) (decreasing from +∞ to −∞), safeguarded Newton."""
    b = l / g if l > 0.0 else 0.0
    lo = b
    # f(hi) < 0: with d = r − b ≥ √(p + ν) + 2 ≈ 3.87, −r + p/r + ν/d ≤ −3.87 + 0.65 + 0.26
    hi = b + math.sqrt(_P_MODE + _NU_MODE) + 2.0
    r = 0.5 * (lo + hi)
    for _ in range(60):
        a = r * g - l
        f = -r + _P_MODE / r + _NU_MODE * g / a
        if f > 0.0:
            lo = r
        else:
            hi = r
        df = -1.0 - _P_MODE / (r * r) - _NU_MODE * g * g / (a * a)
        rn = r - f / df
        if not (lo < rn < hi):
            rn = 0.5 * (lo + hi)
        if abs(rn - r) <= 1e-12 * r:
            return rn
        r = rn
    return r


@numba.njit(cache=True)
def _r_cuts(g, l, cuts):
    """Break points of the r-integral of r^p e^{−r²/2} J_ν(r g − l); returns (n, S, sqrt0).

    cuts[0:n] increasing. With q = 1 + g², for l > 0 the integrand is e^{−S} times a Gaussian
    of width 1/√q centred near r_g = l g/q while a = r g − l < 0 (S = l²/(2q)); its mode r_A
    (with the power r^p) and the window r_A ± (√(2 TAIL) + 1)/√q are break points. If l/g
    (a = 0) lies inside, the algebraic part beyond it has its own mode r_B and decays like
    e^{−r²/2}: break points l/g, r_B, √(r_B² + 8) (decay e^{−4}) and the end √(2(TAIL + S)) + 1.
    For l ≤ 0 only the algebraic part exists (from r = 0). ``sqrt0``: the integrand is not
    negligible at r = 0 (then the first piece is integrated in u = √r)."""
    q = 1.0 + g * g
    if l > 0.0:
        S = 0.5 * l * l / q
        sig = 1.0 / math.sqrt(q)
        b = l / g
        r_a = min((l * g + math.sqrt(l * l * g * g + 4.0 * _P_MODE * q)) / (2.0 * q), b)
        lo = max(0.0, r_a - (_SPAN + 1.0) * sig)
        sqrt0 = 0.5 * q * r_a * r_a < 10.0
        cuts[0] = lo
        n = 1
        if r_a > lo:
            cuts[n] = r_a
            n += 1
        top = r_a + (_SPAN + 1.0) * sig
        if b >= top:  # the algebraic part lies beyond the Gaussian window: negligible
            cuts[n] = top
            return n + 1, S, sqrt0
        if b > cuts[n - 1]:
            cuts[n] = b
            n += 1
    else:
        S = 0.0
        sqrt0 = True
        cuts[0] = 0.0
        n = 1
    r_b = _mode_above(g, l)
    hi = max(r_b, math.sqrt(2.0 * (TAIL + S))) + 1.0
    if r_b > cuts[n - 1]:
        cuts[n] = r_b
        n += 1
    r1 = math.sqrt(r_b * r_b + 8.0)
    if r1 < hi:
        cuts[n] = r1
        n += 1
    cuts[n] = hi
    return n + 1, S, sqrt0


# ---------------------------------------------------------------------------------------
# elastic kernels
# ---------------------------------------------------------------------------------------
@numba.njit(cache=True)
def _elastic_piece(lo, hi, g, l, S, y, w, jt, in_sqrt):
    """e^{S} ∫_lo^hi r² e^{−r²/2} (J_1, r^{1/2} J_{3/2}, r^{1/2} J_{1/2})(r g − l) dr
    (Gauss–Legendre in r, or in u = √r when ``in_sqrt``)."""
    acc_a = 0.0
    acc_w = 0.0
    acc_k = 0.0
    if in_sqrt:
        u0 = math.sqrt(lo)
        du = math.sqrt(hi) - u0
        for k in range(y.shape[0]):
            u = u0 + du * y[k]
            r = u * u
            _, jh, j1, j3 = _moments(r * g - l, S - 0.5 * r * r, jt)
            base = 2.0 * du * w[k] * u * r * r  # dr = 2u du
            acc_a += base * j1
            acc_w += base * u * j3
            acc_k += base * u * jh
    else:
        width = hi - lo
        for k in range(y.shape[0]):
            r = lo + width * y[k]
            _, jh, j1, j3 = _moments(r * g - l, S - 0.5 * r * r, jt)
            base = width * w[k] * r * r
            sr = math.sqrt(r)
            acc_a += base * j1
            acc_w += base * sr * j3
            acc_k += base * sr * jh
    return acc_a, acc_w, acc_k


@numba.njit(cache=True)
def _elastic_inner(g, l, y, w, jt, cuts):
    """(I_area, I_load, I_stiffness)·e^{S} and S for one g (docs/derivation.md):
    I_area = ∫ r² e^{−r²/2} J_1(r g − l) dr, I_load = ∫ r^{5/2} e^{−r²/2} J_{3/2}(…) dr,
    I_stiffness = ∫ r^{5/2} e^{−r²/2} J_{1/2}(…) dr, on the partition of _r_cuts."""
    n, S, sqrt0 = _r_cuts(g, l, cuts)
    acc_a = 0.0
    acc_w = 0.0
    acc_k = 0.0
    for p in range(n - 1):
        lo = cuts[p]
        hi = cuts[p + 1]
        if hi > lo:
            in_sqrt = lo < 0.1 * hi and (lo > 0.0 or sqrt0)
            a, b, k = _elastic_piece(lo, hi, g, l, S, y, w, jt, in_sqrt)
            acc_a += a
            acc_w += b
            acc_k += k
    return acc_a, acc_w, acc_k, S


@numba.njit(cache=True)
def _scale_of(g, l):
    """S = l²/(2(1 + g²)) for l > 0, else 0 (the scale of _r_cuts)."""
    return 0.5 * l * l / (1.0 + g * g) if l > 0.0 else 0.0


@numba.njit(cache=True)
def _elastic_direct(l, w_area, w_load, g, y, w, jt, cuts):
    """The θ-sum with the inner integrals at every θ-node."""
    area = 0.0
    load = 0.0
    stiff = 0.0
    for j in range(g.shape[0]):
        a, b, k, S = _elastic_inner(g[j], l, y, w, jt, cuts)
        f = math.exp(-S)
        area += w_area[j] * a * f
        load += w_load[j] * b * f
        stiff += w_load[j] * k * f
    return area, load, stiff


@numba.njit(cache=True)
def _elastic_interpolated(l, w_area, w_load, g, xg, g_mid, g_half, y, w, tol, cosm, jt, cuts, vals, coef):
    """The θ-sum with ln(e^{S} I_q)(g) interpolated at Chebyshev–Lobatto nodes in g.

    vals[m] holds the values at node m of the finest grid (_N_G_MAX intervals); grids of 8, 16,
    32, 64 intervals nest. Converged when the last three coefficients of every series are
    ≤ tol. Returns (area, load, stiffness, ok); ok False: not converged or a value ≤ 0."""
    n_max = _N_G_MAX
    N = _N_G_START
    stride = n_max // N
    first = True
    while True:
        for k in range(N + 1):
            if not first and k % 2 == 0:
                continue  # on the previous grid
            m = k * stride
            gk = g_mid + g_half * cosm[m]
            a, b, kk, _ = _elastic_inner(gk, l, y, w, jt, cuts)
            if not (a > 0.0 and b > 0.0 and kk > 0.0 and a < math.inf and b < math.inf and kk < math.inf):
                return 0.0, 0.0, 0.0, False
            vals[m, 0] = math.log(a)
            vals[m, 1] = math.log(b)
            vals[m, 2] = math.log(kk)
        first = False
        err = 0.0
        for j in range(N + 1):
            for q in range(3):
                s = 0.0
                for k in range(N + 1):
                    f = vals[k * stride, q]
                    if k == 0 or k == N:
                        f *= 0.5
                    s += f * cosm[(j * k * stride) % (2 * n_max)]
                s *= 2.0 / N
                if j == 0 or j == N:
                    s *= 0.5
                coef[j, q] = s
                if j >= N - 2:
                    err = max(err, abs(s))
        if err <= tol:
            break
        if N == n_max:
            return 0.0, 0.0, 0.0, False
        N *= 2
        stride //= 2
    area = 0.0
    load = 0.0
    stiff = 0.0
    for j in range(g.shape[0]):
        x = xg[j]
        x2 = 2.0 * x
        b0 = b1 = b2 = 0.0
        c0 = c1 = c2 = 0.0
        for i in range(N, 0, -1):
            t = coef[i, 0] + x2 * b0 - c0
            c0 = b0
            b0 = t
            t = coef[i, 1] + x2 * b1 - c1
            c1 = b1
            b1 = t
            t = coef[i, 2] + x2 * b2 - c2
            c2 = b2
            b2 = t
        S = _scale_of(g[j], l)
        area += w_area[j] * math.exp(coef[0, 0] + x * b0 - c0 - S)
        load += w_load[j] * math.exp(coef[0, 1] + x * b1 - c1 - S)
        stiff += w_load[j] * math.exp(coef[0, 2] + x * b2 - c2 - S)
    return area, load, stiff, True


@numba.njit(cache=True)
def _elastic_rows(rows, l_values, w_area, w_load, g, y, w, tol, interpolate, jt, out, used):
    """out[i] = (I_area, I_load, I_stiff) for i in ``rows``; used[i] = 1 if interpolated in g."""
    n_max = _N_G_MAX
    cosm = np.empty(2 * n_max)
    for m in range(2 * n_max):
        cosm[m] = math.cos(math.pi * m / n_max)
    g_lo = g.min()
    g_hi = g.max()
    g_mid = 0.5 * (g_hi + g_lo)
    g_half = 0.5 * (g_hi - g_lo)
    xg = np.empty(g.shape[0])
    for j in range(g.shape[0]):
        xg[j] = min(1.0, max(-1.0, (g[j] - g_mid) / g_half)) if g_half > 0.0 else 0.0
    cuts = np.empty(8)
    vals = np.empty((n_max + 1, 3))
    coef = np.empty((n_max + 1, 3))
    for i in rows:
        l = l_values[i]
        ok = False
        if interpolate and g_half > 1e-12 * g_mid:
            a, b, k, ok = _elastic_interpolated(l, w_area, w_load, g, xg, g_mid, g_half, y, w, tol, cosm, jt,
                                                cuts, vals, coef)
        if not ok:
            a, b, k = _elastic_direct(l, w_area, w_load, g, y, w, jt, cuts)
        out[i, 0] = a
        out[i, 1] = b
        out[i, 2] = k
        used[i] = 1 if ok else 0


@numba.njit(cache=True, parallel=True)
def _elastic_rows_parallel(n_blocks, l_values, w_area, w_load, g, y, w, tol, interpolate, jt, out, used):
    """_elastic_rows over all separations, split into ``n_blocks`` contiguous blocks."""
    n = l_values.shape[0]
    for b in numba.prange(n_blocks):
        rows = np.arange(b * n // n_blocks, (b + 1) * n // n_blocks)
        _elastic_rows(rows, l_values, w_area, w_load, g, y, w, tol, interpolate, jt, out, used)


@numba.njit(cache=True)
def _elastic_inner_array(g, l, y, w, jt, out):
    cuts = np.empty(8)
    for i in range(g.shape[0]):
        a, b, k, S = _elastic_inner(g[i], l[i], y, w, jt, cuts)
        f = math.exp(-S)
        out[i, 0] = a * f
        out[i, 1] = b * f
        out[i, 2] = k * f


# ---------------------------------------------------------------------------------------
# elasto-plastic kernels (sections 5–7, eqs. (78)–(85); Python API in elastoplastic.py)
# ---------------------------------------------------------------------------------------
# Per-asperity laws. Each mirrors one branch of asperity.respond line by line (same
# formulas, same order of operations); tests/contact/test_elastoplastic.py compares them with
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
def _asperity_elastoplastic(omega, kappa, f1, f3, wc, ratio, cH, dp, ln_r, ln_q):
    """asperity.respond, elasto-plastic branch ω_c < ω < ω_p: (76), (75), (77) and dW/dω.

    ratio = ω_p/ω_c, cH = c_h H, dp = H (c_h − (2/3) K_v), ln_r = ln(ω_p/ω_c), ln_q = ln(ω_p/ω)
    (the caller's: the t-rule in ln t has it without a log)."""
    d = 2.0 * f3 - f1
    t = omega / wc  # ω/ω_c
    x = (t - 1.0) / (ratio - 1.0)  # (ω − ω_c)/(ω_p − ω_c)
    g = x * x * (3.0 - 2.0 * x)  # blend, asperity.blend
    dg = 6.0 * x * (1.0 - x)
    bracket = f1 + d * g
    A = bracket * math.pi * omega / kappa  # eq. (76)
    p = cH - dp * ln_q / ln_r  # eq. (75)
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
            A, W, S = _asperity_elastoplastic(w, kappa[i], f1[i], f3[i], wc[i], ratio, cH, dp, ln_r,
                                              math.log(ratio / (w / wc[i])))
            reg = 1.0
        out[i, 0] = A
        out[i, 1] = W
        out[i, 2] = S
        out[i, 3] = reg



# ---------------------------------------------------------------------------------------
# The elasto-plastic integrals by the τ = r t route (docs/performance.md, issue 24)
# ---------------------------------------------------------------------------------------
# Per θ-node the summit measure is r³ e^{−r²/2} φ(t − r g + l) dt dr (docs/derivation.md) and
# the law of an asperity with interference ω = σ t and curvature κ_m = r c depends on r only
# through powers once written in τ = r t: A, W ∝ τ-law/r², dW/dω ∝ τ-law/r (the regimes are
# τ < t_c1, t_c1 < τ < (ω_p/ω_c) t_c1, τ beyond). With t = τ/r,
#
#     column = ∫_0^∞ F(τ) G_k(τ) dτ,   G_k(τ) = ∫_0^∞ r^k e^{−r²/2} φ(τ/r + l − g r) dr,
#
# k = 0 for A, W and k = 1 for dW/dω (and the load-jump term, G_1(t_c1)), F the law at
# (ω, κ) = (σ τ, c). G_k depends on θ through g only, and on τ smoothly: it is computed once per
# separation on a grid — Chebyshev–Lobatto nodes in g over the θ-nodes' range times panels in
# s = ln τ — and ln G_k is interpolated there; every θ-node then integrates its regime pieces
# in s (Gauss–Legendre) against the interpolant, with the law evaluated at those nodes only.
_HYP_KP = 0.5  # the power of r whose integrand places the window (between G_0's r⁰ and G_1's r¹)
_HYP_LEVEL = TAIL + 6.0  # the window of the r-integrand: e^{−46} of its maximum
_GRID_BELOW = 10.0  # the s-grid starts this far below ln τ of the mass (and of the smallest t_c1)
_GRID_MAX_PANELS = 48
_GRID_MAX_NG = 32  # Chebyshev intervals in g (nested 4, 8, 16, 32)
_GRID_NG_START = 4
_PART_FLOOR = 1e-3  # the presets' convention: parts relative to max(|part|, 1e-3 |total|)
_UNDERFLOW_SHIFT = 800.0  # e^{−800} times any column's scale (≤ e^{40}) is below the smallest double


@numba.njit(cache=True)
def _hyp_log_integrand(u, tau, g, l):
    """H(u) = ln of r^{3/2} e^{−r²/2 − z²/2}, r = e^u, z = τ/r + l − g r (the integrand of
    G_{1/2} in u = ln r: r^{1/2}·r from dr = r du)."""
    r = math.exp(u)
    z = tau / r + l - g * r
    return (_HYP_KP + 1.0) * u - 0.5 * r * r - 0.5 * z * z


@numba.njit(cache=True)
def _hyp_slope(r, tau, g, l):
    """(dH/du, d²H/du²) at r = e^u. dH/du = P(r)/r², P = −q r⁴ + l g r³ + (3/2) r² + l τ r + τ²
    (q = 1 + g²): one positive root for l ≥ 0 and at most three for l < 0 (Descartes)."""
    q = 1.0 + g * g
    r2 = r * r
    P = ((-q * r + l * g) * r + (_HYP_KP + 1.0)) * r2 + l * tau * r + tau * tau
    dP = ((-4.0 * q * r + 3.0 * l * g) * r + 2.0 * (_HYP_KP + 1.0)) * r + l * tau
    h1 = P / r2
    return h1, dP / r - 2.0 * h1


@numba.njit(cache=True)
def _hyp_mode(tau, g, l, u, lo, hi):
    """A root of dH/du in [lo, hi] (positive at lo, negative at hi): Newton from u, bisection
    when a step leaves the bracket."""
    for _ in range(100):
        h1, h2 = _hyp_slope(math.exp(u), tau, g, l)
        if h1 > 0.0:
            lo = u
        else:
            hi = u
        un = u - h1 / h2 if h2 < 0.0 else 0.5 * (lo + hi)
        if not (lo < un < hi):
            un = 0.5 * (lo + hi)
        if abs(un - u) < 1e-10 or hi - lo < 1e-10:
            return un
        u = un
    return u


@numba.njit(cache=True)
def _hyp_edge(tau, g, l, um, level, direction, width):
    """u beyond the maximum um (direction ±1) where H = level (to ±0.5): a bracket from the
    Laplace guess um ± √(2·46)·width, then Newton safeguarded by bisection (H is monotone
    outside the outermost maximum)."""
    near = um
    far = um + direction * width * math.sqrt(2.0 * _HYP_LEVEL)
    step = width
    for _ in range(60):
        if _hyp_log_integrand(far, tau, g, l) < level:
            break
        near = far
        far = far + direction * step * 4.0
        step *= 2.0
    u = far
    for _ in range(60):
        f = _hyp_log_integrand(u, tau, g, l) - level
        if abs(f) < 0.5:
            return u
        if f > 0.0:
            near = u
        else:
            far = u
        h1, _ = _hyp_slope(math.exp(u), tau, g, l)
        un = u - f / h1 if h1 != 0.0 else 0.5 * (near + far)
        if not (min(near, far) < un < max(near, far)):
            un = 0.5 * (near + far)
        u = un
    return u


@numba.njit(cache=True)
def _hyperbola_moments(tau, g, l, h0, cw):
    """(ln G_0, ln G_1)(τ) for τ > 0: G_k = ∫_0^∞ r^k e^{−r²/2} φ(τ/r + l − g r) dr, the mass
    of the summit measure on the hyperbola r t = τ.

    In u = ln r the integrand decays double-exponentially at both ends (τ/r for r → 0,
    e^{−r²/2} for r → ∞) and is analytic: the trapezoidal rule converges exponentially, and it
    does not care that the integrand can have two maxima (the φ-peak z = 0 at small r and the
    r-bump, for l < 0) or a long shoulder between them. H = A + B with A = (3/2)u − r²/2
    (maximum at r_A = √(3/2)) and B = −z²/2 (maximum at z = 0, r_z); dH/du = A' + B' has the
    sign of both outside [u_A, u_z], so every maximum lies between and is found by Newton from
    either end. Window: where H ≥ H_max − 46; step min(h0, cw × the narrowest Laplace width
    (maxima, φ-peak)). Logs returned: no under- or overflow for any l."""
    rA = math.sqrt(_HYP_KP + 1.0)
    uA = math.log(rA)
    if l >= 0.0:
        rz = (l + math.sqrt(l * l + 4.0 * g * tau)) / (2.0 * g)
    else:  # the same root without cancellation
        rz = 2.0 * tau / (-l + math.sqrt(l * l + 4.0 * g * tau))
    uz = math.log(rz)
    lo = min(uA, uz) - 1e-9
    hi = max(uA, uz) + 1e-9
    m1 = _hyp_mode(tau, g, l, uA, lo, hi)
    m2 = _hyp_mode(tau, g, l, uz, lo, hi)
    H1 = _hyp_log_integrand(m1, tau, g, l)
    H2 = _hyp_log_integrand(m2, tau, g, l)
    Hmax = max(H1, H2)
    level = Hmax - _HYP_LEVEL
    if abs(m1 - m2) < 1e-7 or H2 < level:
        m2 = m1
    if H1 < level:
        m1 = m2
    ml = min(m1, m2)
    mr = max(m1, m2)
    _, h2 = _hyp_slope(math.exp(ml), tau, g, l)
    wl = 1.0 / math.sqrt(max(-h2, 1e-12))
    _, h2 = _hyp_slope(math.exp(mr), tau, g, l)
    wr = 1.0 / math.sqrt(max(-h2, 1e-12))
    ulo = _hyp_edge(tau, g, l, ml, level, -1.0, wl)
    uhi = _hyp_edge(tau, g, l, mr, level, 1.0, wr)
    wmin = min(wl, wr)
    if ulo < uz < uhi:
        wmin = min(wmin, 1.0 / (tau / rz + g * rz))  # the φ-peak: z changes by 1 over this
    h = min(h0, cw * wmin)
    n = int((uhi - ulo) / h) + 1
    h = (uhi - ulo) / n
    # r and √r by products (one exp per node), refreshed every 32 nodes
    q = math.exp(h)
    sq = math.exp(0.5 * h)
    g0 = 0.0
    g1 = 0.0
    r = 0.0
    sr = 0.0
    for k in range(n + 1):
        u = ulo + h * k
        if k % 32 == 0:
            r = math.exp(u)
            sr = math.exp(0.5 * u)
        z = tau / r + l - g * r
        e = math.exp((_HYP_KP + 1.0) * u - 0.5 * r * r - 0.5 * z * z - Hmax)
        if k == 0 or k == n:
            e *= 0.5
        g0 += e / sr  # r·e^{…}: r^{3/2}/r^{1/2}
        g1 += e * sr
        r *= q
        sr *= sq
    base = Hmax + math.log(h * _INV_SQRT_2PI)
    return base + math.log(g0), base + math.log(g1)


@numba.njit(cache=True)
def _hyperbola_moments_array(tau, g, l, h0, cw, out):
    """_hyperbola_moments at arrays of (τ, g, l); out[i] = (ln G_0, ln G_1). For the tests."""
    for i in range(tau.shape[0]):
        out[i, 0], out[i, 1] = _hyperbola_moments(tau[i], g[i], l[i], h0, cw)


@numba.njit(cache=True)
def _cheb_coefficients(vals, n, out):
    """Chebyshev coefficients out[0..n] of the interpolant through vals[k] at x_k = cos(πk/n)
    (n divides 32: the cosines come from one table of cos(πm/32))."""
    table = np.empty(64)
    cd = math.cos(math.pi / 32.0)
    sd = math.sin(math.pi / 32.0)
    c = 1.0
    s = 0.0
    for m in range(64):  # cos(πm/32) by rotation (error ≤ 64 ulp)
        table[m] = c
        c, s = c * cd - s * sd, s * cd + c * sd
    f = 32 // n
    for j in range(n + 1):
        s = 0.0
        for k in range(n + 1):
            v = vals[k]
            if k == 0 or k == n:
                v *= 0.5
            s += v * table[((j * k) % (2 * n)) * f]
        s *= 2.0 / n
        if j == 0 or j == n:
            s *= 0.5
        out[j] = s


@numba.njit(cache=True)
def _clenshaw(c, n, x):
    """Σ_{j=0}^{n} c[j] T_j(x)."""
    b0 = 0.0
    b1 = 0.0
    x2 = 2.0 * x
    for i in range(n, 0, -1):
        t = c[i] + x2 * b0 - b1
        b1 = b0
        b0 = t
    return c[0] + x * b0 - b1


@numba.njit(cache=True)
def _ellipse_tau_max(g, l, T):
    """max r t over the quadrant's part of the ellipse {r² + (t + l − g r)² ≤ 2(S + T)}
    (S = l²/(2(1 + g²)) for l > 0, the minimum of the quadratic form there): beyond it the
    summit measure is below e^{−T} of its maximum. Parametrised r = ρ cos φ,
    t + l − g r = ρ sin φ; scanned in φ."""
    S = 0.5 * l * l / (1.0 + g * g) if l > 0.0 else 0.0
    rho = math.sqrt(2.0 * (S + T))
    best = 0.0
    for k in range(129):
        ph = -0.5 * math.pi + math.pi * k / 128.0
        r = rho * math.cos(ph)
        t = rho * (math.sin(ph) + g * math.cos(ph)) - l
        if r > 0.0 and t > 0.0 and r * t > best:
            best = r * t
    return best


@numba.njit(cache=True)
def _tau_of_mass(g, l):
    """τ = r t at the maximum of r^{5/2} t e^{−(r² + (t + l − g r)²)/2} (concave in (r, t):
    Newton), the bulk of the elasto-plastic τ-integrands; the τ-pieces are split there."""
    q = 1.0 + g * g
    r = 1.5
    t = max(1.0, 1.5 * g - l)
    for _ in range(60):
        d = t + l - g * r
        fr = 2.5 / r - r + g * d
        ft = 1.0 / t - d
        frr = -2.5 / (r * r) - q
        ftt = -1.0 / (t * t) - 1.0
        det = frr * ftt - g * g
        dr = -(ftt * fr - g * ft) / det
        dt = -(frr * ft - g * fr) / det
        lam = 1.0
        while r + lam * dr <= 0.0 or t + lam * dt <= 0.0:
            lam *= 0.5
        r += lam * dr
        t += lam * dt
        if abs(dr) < 1e-12 * r and abs(dt) < 1e-12 * t:
            break
    return r * t


@numba.njit(cache=True)
def _log_normal_moments(x, jt):
    """(ln J_0(x), ln J_1(x)) from the normal-moment tables (_moments; for x < 0 scaled by
    e^{x²/2}, so nothing underflows or cancels: J_1 = x Φ + φ loses digits for x ≪ 0)."""
    e = 0.5 * x * x if x < 0.0 else 0.0
    j0, _, j1, _ = _moments(x, e, jt)
    return math.log(j0) - e, math.log(j1) - e


@numba.njit(cache=True)
def _hyperbola_at_zero(g, l, jt):
    """(ln G_0, ln G_1) at τ = 0 in closed form: ∫_0^∞ r^k e^{−(q r² − 2 l g r + l²)/2} dr/√(2π),
    q = 1 + g², x = l g/√q: G_0 = e^{−l²/(2q)} J_0(x)/√q, G_1 = e^{−l²/(2q)} J_1(x)/q (J_ν the
    normal moments: no cancellation, no underflow)."""
    q = 1.0 + g * g
    sq = math.sqrt(q)
    x = l * g / sq
    base = -0.5 * l * l / q
    lj0, lj1 = _log_normal_moments(x, jt)
    return base + lj0 - math.log(sq), base + lj1 - math.log(q)


@numba.njit(cache=True)
def _hyperbola_at_zero_array(g, l, jt, out):
    """_hyperbola_at_zero at arrays; out[i] = (ln G_0, ln G_1). For the tests."""
    for i in range(g.shape[0]):
        out[i, 0], out[i, 1] = _hyperbola_at_zero(g[i], l[i], jt)


@numba.njit(cache=True)
def _below_params(c, n, width, ln_zero, s_lo):
    """The model of one G_k below the grid (τ < τ_lo = e^{s_lo}) from its panel-0 Chebyshev
    series c (degree n, panel width ``width``): (scale, a, b, kind).

    kind 0 — the expansion at small τ, G(τ) = G(0)(1 + τ(a ln τ + b)) (the τ/r term shifts φ by
    O(τ ln τ)), matched to ln G and d ln G/ds at s_lo; used while G(τ_lo) < 2 G(0), the
    expansion's range. kind 1 — a power law G = G(τ_lo)(τ/τ_lo)^a (b = s_lo), matched to the
    same slope, where G still grows much below the grid (heavy loads: the mass sits at large τ,
    and what lies below τ_lo is negligible)."""
    ln_lo = _clenshaw(c, n, -1.0)
    slope = _cheb_slope_left(c, n) * 2.0 / width
    if ln_lo - ln_zero < math.log(2.0):
        ratio = math.exp(ln_lo - ln_zero)
        y = ratio - 1.0
        e = math.exp(-s_lo)
        a = (ratio * slope - y) * e
        return math.exp(ln_zero), a, y * e - a * s_lo, 0
    return math.exp(ln_lo), max(slope, 0.0), s_lo, 1


@numba.njit(cache=True)
def _below_value(tau, s, scale, a, b, kind):
    """G(τ) of the model of _below_params (s = ln τ)."""
    if kind == 0:
        return scale * (1.0 + tau * (a * s + b))
    return scale * math.exp(a * (s - b))


@numba.njit(cache=True)
def _below_integral(nu, scale, a, b, kind, tb):
    """∫_0^tb τ^ν G(τ) dτ with G the model of _below_params."""
    if tb <= 0.0:
        return 0.0
    n1 = nu + 1.0
    if kind == 0:
        n2 = nu + 2.0
        return scale * (tb ** n1 / n1 + a * tb ** n2 * (math.log(tb) / n2 - 1.0 / (n2 * n2)) + b * tb ** n2 / n2)
    return scale * math.exp((n1 + a) * math.log(tb) - a * b) / (n1 + a)


@numba.njit(cache=True)
def _cheb_slope_left(c, n):
    """d/dx Σ c[j] T_j(x) at x = −1: Σ c[j] (−1)^{j+1} j²."""
    s = 0.0
    for j in range(1, n + 1):
        s += c[j] * (j * j if j % 2 == 1 else -j * j)
    return s


@numba.njit(cache=True)
def _panel_values(l, g, a, b, d, step, h0, cw, shift, out):
    """out[k, q] = ln G_q at the Lobatto points s_k = (a + b)/2 + (b − a)/2 cos(πk/d), for
    k = 0, step, 2·step, … (step 2: the points of degree d/2, which nest); plus ``shift`` (the
    separation's scale l²/(2(1 + g_hi²)): the largest values are O(1), nothing underflows)."""
    for k in range(0, d + 1, step):
        s = 0.5 * (a + b) + 0.5 * (b - a) * math.cos(math.pi * k / d)
        v0, v1 = _hyperbola_moments(math.exp(s), g, l, h0, cw)
        out[k, 0] = v0 + shift
        out[k, 1] = v1 + shift


@numba.njit(cache=True)
def _panel_tail(vals, n, step, tmp, coef):
    """Largest of the last three Chebyshev coefficients of ln G_0, ln G_1 on one panel from the
    n + 1 values vals[0], vals[step], … (degree n)."""
    e = 0.0
    for q in range(2):
        for k in range(n + 1):
            tmp[k] = vals[k * step, q]
        _cheb_coefficients(tmp, n, coef)
        for j in range(n - 2, n + 1):
            e = max(e, abs(coef[j]))
    return e


@numba.njit(cache=True)
def _grid_panels(l, g_hi, g_lo, s_lo, s_mid, s_hi, width, d, tol, h0, cw, shift, edges, degree, vals, info):
    """Panels of the s-grid, tested at both ends of the g-range: from panels of ``width`` below
    s_mid and width/2 above (where ln G bends), each first at degree d/2, raised to d (the
    points nest) and bisected while the last three Chebyshev coefficients of ln G_k exceed
    ``tol``. Returns (P, ok); edges[0..P], degree[p] (d/2 or d); the values at g_hi, g_lo go to
    vals[0] and vals[_GRID_MAX_NG]; info[0] += hyperbola integrals computed."""
    stack_a = np.empty(4 * _GRID_MAX_PANELS)
    stack_b = np.empty(4 * _GRID_MAX_PANELS)
    top = 0
    s_mid = min(max(s_mid, s_lo), s_hi)
    n_hi = int(math.ceil((s_hi - s_mid) / (0.5 * width)))
    for i in range(n_hi - 1, -1, -1):
        stack_a[top] = s_mid + (s_hi - s_mid) * i / n_hi
        stack_b[top] = s_mid + (s_hi - s_mid) * (i + 1) / n_hi
        top += 1
    n_lo = int(math.ceil((s_mid - s_lo) / width))
    for i in range(n_lo - 1, -1, -1):
        stack_a[top] = s_lo + (s_mid - s_lo) * i / n_lo
        stack_b[top] = s_lo + (s_mid - s_lo) * (i + 1) / n_lo
        top += 1
    vh = np.empty((d + 1, 2))
    vl = np.empty((d + 1, 2))
    tmp = np.empty(d + 1)
    coef = np.empty(d + 1)
    half = d // 2
    # the steps as int64 variables, not literals: a literal argument compiles a signature of its
    # own (Literal[int](2)), and one kernel must keep one key in numba's shared cache
    one = np.int64(1)
    two = np.int64(2)
    P = 0
    ok = True
    edges[0] = s_lo
    while top > 0:
        top -= 1
        a = stack_a[top]
        b = stack_b[top]
        _panel_values(l, g_hi, a, b, d, two, h0, cw, shift, vh)
        _panel_values(l, g_lo, a, b, d, two, h0, cw, shift, vl)
        info[0] += 2 * (half + 1)
        n = half
        if max(_panel_tail(vh, half, two, tmp, coef), _panel_tail(vl, half, two, tmp, coef)) > tol:
            for k in range(1, d, 2):  # the odd points: degree d
                s = 0.5 * (a + b) + 0.5 * (b - a) * math.cos(math.pi * k / d)
                v0, v1 = _hyperbola_moments(math.exp(s), g_hi, l, h0, cw)
                vh[k, 0] = v0 + shift
                vh[k, 1] = v1 + shift
                v0, v1 = _hyperbola_moments(math.exp(s), g_lo, l, h0, cw)
                vl[k, 0] = v0 + shift
                vl[k, 1] = v1 + shift
            info[0] += 2 * half
            n = d
            if max(_panel_tail(vh, d, one, tmp, coef), _panel_tail(vl, d, one, tmp, coef)) > tol:
                if P + top + 2 <= _GRID_MAX_PANELS:
                    m = 0.5 * (a + b)
                    stack_a[top] = m
                    stack_b[top] = b
                    stack_a[top + 1] = a
                    stack_b[top + 1] = m
                    top += 2
                    continue
                ok = False
        vals[0, P] = vh
        vals[_GRID_MAX_NG, P] = vl
        degree[P] = n
        P += 1
        edges[P] = b
    return P, ok


@numba.njit(cache=True)
def _grid_fill(l, g_lo, g_hi, rows, stride, edges, degree, P, d, h0, cw, shift, vals):
    """vals[m] (m = i·stride: the Lobatto point cos(πm/_GRID_MAX_NG) of [g_lo, g_hi]) for
    the grid rows i in ``rows``, each panel at its degree."""
    gm = 0.5 * (g_hi + g_lo)
    gh = 0.5 * (g_hi - g_lo)
    for i in rows:
        m = i * stride
        g = gm + gh * math.cos(math.pi * m / _GRID_MAX_NG)
        for p in range(P):
            _panel_values(l, g, edges[p], edges[p + 1], d, d // degree[p], h0, cw, shift, vals[m, p])


@numba.njit(cache=True)
def _grid_g_error(vals, ng, stride, P, d, degree):
    """The largest of the last three Chebyshev coefficients in g of ln G_q over the s-points
    where ln G_q (at g_hi) is within e^{−50} of its largest value (nothing else matters)."""
    tmp = np.empty(_GRID_MAX_NG + 1)
    out = np.empty(_GRID_MAX_NG + 1)
    err = 0.0
    for q in range(2):
        top = -1e300
        for p in range(P):
            for k in range(0, d + 1, d // degree[p]):
                top = max(top, vals[0, p, k, q])
        for p in range(P):
            for k in range(0, d + 1, d // degree[p]):
                if vals[0, p, k, q] < top - 50.0:
                    continue
                for i in range(ng + 1):
                    tmp[i] = vals[i * stride, p, k, q]
                _cheb_coefficients(tmp, ng, out)
                for i in range(max(0, ng - 2), ng + 1):
                    err = max(err, abs(out[i]))
    return err


@numba.njit(cache=True)
def _grid_coefficients(l, g_lo, g_hi, vals, ng, stride, P, d, degree, edges, yt, wt, jt, shift, coef, tot_coef):
    """coef[i, p, j, q]: 2-D Chebyshev coefficients (i in g, j ≤ degree[p] in s) of ln G_q on
    panel p; tot_coef[k, i]: Chebyshev coefficients in g of ln of the totals ∫_0^∞ τ^ν G_q dτ,
    (ν, q) = (1, 0), (3/2, 0), (1/2, 1), (0, 1) — the elastic law over every τ (θ-nodes in one
    regime, and the complement of a large elastic part). The totals: in s on each panel
    (Gauss–Legendre) plus the part below the grid by the small-τ model (_below_params, closed
    form)."""
    tmp = np.empty(max(_GRID_MAX_NG, d) + 1)
    out = np.empty(max(_GRID_MAX_NG, d) + 1)
    tot = np.empty((4, _GRID_MAX_NG + 1))
    for i in range(ng + 1):
        for p in range(P):
            n = degree[p]
            st = d // n
            for q in range(2):
                for k in range(n + 1):
                    tmp[k] = vals[i * stride, p, k * st, q]
                _cheb_coefficients(tmp, n, out)
                for j in range(n + 1):
                    coef[i, p, j, q] = out[j]  # the s-coefficients at g-node i, for now
        m0 = m1 = m2 = m3 = 0.0
        for p in range(P):
            n = degree[p]
            span = edges[p + 1] - edges[p]
            for k in range(yt.shape[0]):
                x = 2.0 * yt[k] - 1.0
                for j in range(n + 1):
                    tmp[j] = coef[i, p, j, 0]
                G0 = math.exp(_clenshaw(tmp, n, x))
                for j in range(n + 1):
                    tmp[j] = coef[i, p, j, 1]
                G1 = math.exp(_clenshaw(tmp, n, x))
                tau = math.exp(edges[p] + span * yt[k])
                sq = math.sqrt(tau)
                wk = span * wt[k] * tau  # dτ = τ ds
                m0 += wk * tau * G0
                m1 += wk * tau * sq * G0
                m2 += wk * sq * G1
                m3 += wk * G1
        n = degree[0]
        g = 0.5 * (g_hi + g_lo) + 0.5 * (g_hi - g_lo) * math.cos(math.pi * i * stride / _GRID_MAX_NG)
        z0, z1 = _hyperbola_at_zero(g, l, jt)
        z0 += shift
        z1 += shift
        for j in range(n + 1):
            tmp[j] = coef[i, 0, j, 0]
            out[j] = coef[i, 0, j, 1]
        w0 = edges[1] - edges[0]
        sc0, a0, b0, k0 = _below_params(tmp, n, w0, z0, edges[0])
        sc1, a1, b1, k1 = _below_params(out, n, w0, z1, edges[0])
        tb = math.exp(edges[0])
        # (floored at 1e-300: a g-node whose values underflow contributes nothing, and no −inf
        # enters the interpolation)
        tot[0, i] = math.log(max(m0 + _below_integral(1.0, sc0, a0, b0, k0, tb), 1e-300))
        tot[1, i] = math.log(max(m1 + _below_integral(1.5, sc0, a0, b0, k0, tb), 1e-300))
        tot[2, i] = math.log(max(m2 + _below_integral(0.5, sc1, a1, b1, k1, tb), 1e-300))
        tot[3, i] = math.log(max(m3 + _below_integral(0.0, sc1, a1, b1, k1, tb), 1e-300))
    for k in range(4):
        _cheb_coefficients(tot[k], ng, tot_coef[k])
    for p in range(P):
        for j in range(degree[p] + 1):
            for q in range(2):
                for i in range(ng + 1):
                    tmp[i] = coef[i, p, j, q]
                _cheb_coefficients(tmp, ng, out)
                for i in range(ng + 1):
                    coef[i, p, j, q] = out[i]


@numba.njit(cache=True)
def _ep_node(l, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, ln_r, pv, with_jump,
             g_lo, g_hi, ng, edges, degree, P, coef, tot_coef, yt, wt, jt, shift, cg, cs, c1, acc):
    """acc[0:8] = (A^e, A^ep, A^p, W^e, W^ep, W^p, dW/dω, load-jump term) at one θ-node, per unit
    θ-weight (elastoplastic.py applies the weights and D_sum).

    Each column is ∫ F(τ) G_k(τ) dτ over its regime's τ-range, F the per-asperity law at
    (ω, κ_m) = (σ τ, c) (the r-powers are in G_k): (46), (47), (54) below t_c1; (76), (75),
    (77) between; (61), (67) above (ω_p/ω_c) t_c1. In s = ln τ, Gauss–Legendre on each piece,
    split at the bulk of the τ-mass (and 4 below it); below the grid G = G(0)(1 + τ(a ln τ + b))
    (_below_params), against which the power laws integrate in closed form. A θ-node whose
    τ-range is all elastic takes the totals (interpolated in g); a large elastic part is the
    total minus the rest (no cancellation: it is the larger share)."""
    x_g = (2.0 * g - g_lo - g_hi) / (g_hi - g_lo) if g_hi > g_lo else 0.0
    x_g = min(1.0, max(-1.0, x_g))
    for q in range(8):
        acc[q] = 0.0
    s_lo = edges[0]
    s_hi = edges[P]
    s_c = math.log(tc1)  # t_c = t_c1/r: in τ = r t the boundary is τ = t_c1, eq. (65)
    s_p = s_c + ln_r
    # the law per unit G at τ = 1 (power laws below the grid, totals)
    Ae1, We1, Se1 = _asperity_elastic(sigma, c, f1, f2, E_star)
    Ap1, Wp1, Sp1 = _asperity_plastic(sigma, c, f3, cH)
    if s_c >= s_hi:  # all elastic: the totals
        acc[0] = Ae1 * math.exp(_clenshaw(tot_coef[0], ng, x_g))
        acc[3] = We1 * math.exp(_clenshaw(tot_coef[1], ng, x_g))
        acc[6] = Se1 * math.exp(_clenshaw(tot_coef[2], ng, x_g))
        return
    for p in range(P):
        for j in range(degree[p] + 1):
            for q in range(2):
                for i in range(ng + 1):
                    cs[i] = coef[i, p, j, q]
                cg[p, j, q] = _clenshaw(cs, ng, x_g)
    s_m = math.log(_tau_of_mass(g, l))
    complement = s_c >= s_m  # the elastic part is the larger share: total minus the rest
    rest_a = rest_w = rest_s = 0.0  # the elastic law's moments above t_c1 (for the complement)
    # below the grid (τ < τ_lo): the model of _below_params
    n = degree[0]
    for j in range(n + 1):
        cs[j] = cg[0, j, 0]
    z0, z1 = _hyperbola_at_zero(g, l, jt)
    z0 += shift
    z1 += shift
    for j in range(n + 1):
        c1[j] = cg[0, j, 1]
    sc0, a0_, b0_, k0 = _below_params(cs, n, edges[1] - edges[0], z0, s_lo)
    sc1, a1_, b1_, k1 = _below_params(c1, n, edges[1] - edges[0], z1, s_lo)
    for kind in range(3):  # 0 elastic, 1 elasto-plastic, 2 plastic
        if kind == 0:
            if complement:
                continue
            a0, b0 = -1e300, min(s_c, s_hi)
        elif kind == 1:
            a0, b0 = s_c, min(s_p, s_hi)
        else:
            a0, b0 = s_p, s_hi
        if b0 <= a0:
            continue
        if kind != 1 and a0 < s_lo:  # below the grid: the power laws against the model, closed form
            tb = math.exp(min(b0, s_lo))
            if kind == 0:
                acc[0] += Ae1 * _below_integral(1.0, sc0, a0_, b0_, k0, tb)
                acc[3] += We1 * _below_integral(1.5, sc0, a0_, b0_, k0, tb)
                acc[6] += Se1 * _below_integral(0.5, sc1, a1_, b1_, k1, tb)
            else:
                ta = math.exp(a0)
                ma = _below_integral(1.0, sc0, a0_, b0_, k0, tb) - _below_integral(1.0, sc0, a0_, b0_, k0, ta)
                acc[2] += Ap1 * ma
                acc[6] += Sp1 * (_below_integral(0.0, sc1, a1_, b1_, k1, tb) - _below_integral(0.0, sc1, a1_, b1_, k1, ta))
                rest_a += ma
                rest_w += _below_integral(1.5, sc0, a0_, b0_, k0, tb) - _below_integral(1.5, sc0, a0_, b0_, k0, ta)
                rest_s += _below_integral(0.5, sc1, a1_, b1_, k1, tb) - _below_integral(0.5, sc1, a1_, b1_, k1, ta)
            a0 = s_lo
            if b0 <= a0:
                continue
        # sub-pieces: split at the bulk s_m and 4 below it
        cut1 = s_m - 4.0
        cut2 = s_m
        for sub in range(3):
            a = a0 if sub == 0 else max(a0, cut1 if sub == 1 else cut2)
            b = b0 if sub == 2 else min(b0, cut1 if sub == 0 else cut2)
            if b <= a:
                continue
            span = b - a
            p = 0
            for k in range(yt.shape[0]):
                s = a + span * yt[k]
                tau = math.exp(s)
                if s < s_lo:  # an elasto-plastic piece below the grid (t_c1 < τ_lo): the model
                    G0 = _below_value(tau, s, sc0, a0_, b0_, k0)
                    G1 = _below_value(tau, s, sc1, a1_, b1_, k1)
                else:
                    while p < P - 1 and s > edges[p + 1]:
                        p += 1
                    x = (2.0 * s - edges[p] - edges[p + 1]) / (edges[p + 1] - edges[p])
                    n = degree[p]
                    for j in range(n + 1):
                        cs[j] = cg[p, j, 0]
                    G0 = math.exp(_clenshaw(cs, n, x))
                    for j in range(n + 1):
                        cs[j] = cg[p, j, 1]
                    G1 = math.exp(_clenshaw(cs, n, x))
                wk = span * wt[k] * tau  # dτ = τ ds
                if kind == 0:
                    A, W, Sd = _asperity_elastic(sigma * tau, c, f1, f2, E_star)
                    acc[0] += wk * A * G0
                    acc[3] += wk * W * G0
                    acc[6] += wk * Sd * G1
                    continue
                if kind == 1:  # ln(ω_p/ω) = ln(ω_p/ω_c) − (s − s_c): no log per node
                    A, W, Sd = _asperity_elastoplastic(sigma * tau, c, f1, f3, sigma * tc1, ratio, cH, dp, ln_r,
                                                       ln_r - (s - s_c))
                    acc[1] += wk * A * G0
                    acc[4] += wk * W * G0
                else:
                    A, W, Sd = _asperity_plastic(sigma * tau, c, f3, cH)
                    acc[2] += wk * A * G0
                    acc[5] += wk * W * G0
                acc[6] += wk * Sd * G1
                st = math.sqrt(tau)
                rest_a += wk * tau * G0
                rest_w += wk * tau * st * G0
                rest_s += wk * st * G1
    if complement:
        acc[0] = Ae1 * (math.exp(_clenshaw(tot_coef[0], ng, x_g)) - rest_a)
        acc[3] = We1 * (math.exp(_clenshaw(tot_coef[1], ng, x_g)) - rest_w)
        acc[6] += Se1 * (math.exp(_clenshaw(tot_coef[2], ng, x_g)) - rest_s)
    if with_jump and s_c < s_hi:
        # −dW/dh gains the load jump J = A_i(ω_c)·(2/3) K_v H − W_i(ω_c) times the density at
        # t = t_c (errata E17): in τ, J(r = 1)·G_1(t_c1)/σ
        if s_c < s_lo:
            G1 = _below_value(tc1, s_c, sc1, a1_, b1_, k1)
        else:
            p = 0
            while p < P - 1 and s_c > edges[p + 1]:
                p += 1
            n = degree[p]
            for j in range(n + 1):
                cs[j] = cg[p, j, 1]
            G1 = math.exp(_clenshaw(cs, n, (2.0 * s_c - edges[p] - edges[p + 1]) / (edges[p + 1] - edges[p])))
        Ae, We, _ = _asperity_elastic(sigma * tc1, c, f1, f2, E_star)
        acc[7] = (Ae * pv - We) * G1 / sigma


@numba.njit(cache=True)
def _grid_ng_start(g_lo, g_hi, tol):
    """The first g-grid (intervals, a power of 2 in [4, 32]): ln G_k depends on g like
    ln(1 + g²) (the Gaussian's width 1/√(1 + g²)), singular at g = ±i, so Chebyshev
    coefficients fall like ρ^{−n}, ρ the Bernstein parameter of ±i for [g_lo, g_hi]; n with
    ρ^{−n} ≤ tol, two more for safety. (The grid is still checked and doubled if needed;
    starting here keeps the result independent of how many threads compute it.)"""
    if not g_hi > g_lo * (1.0 + 1e-12):
        return 1
    w = (1j - 0.5 * (g_hi + g_lo)) / (0.5 * (g_hi - g_lo))
    z = w + np.sqrt(w * w - 1.0)
    rho = max(abs(z), 1.0 / abs(z))
    n = math.log(1.0 / tol) / math.log(max(rho, 1.0001)) + 2.0
    ng = _GRID_NG_START
    while ng < n and ng < _GRID_MAX_NG:
        ng *= 2
    return ng


@numba.njit(cache=True)
def _ep_grid_panels(l, g_lo, g_hi, d, width, tol, h0, cw, shift, edges, degree, vals, info):
    """The s-panels of the grid for one separation (_grid_panels on [s_lo, s_hi]: from ln τ of
    the ellipse e^{−40} down to 10 below the bulk of the mass; below, the small-τ model — the
    grid depends on the surface and l only, not on the material, so materials share it).
    Returns P; info[1] = 0 if the panels' tolerance was not reached."""
    t_hi = max(_ellipse_tau_max(g_hi, l, TAIL), _ellipse_tau_max(g_lo, l, TAIL))
    s_hi = math.log(t_hi)
    s_mass = math.log(_tau_of_mass(0.5 * (g_lo + g_hi), l))
    s_lo = s_mass - _GRID_BELOW
    s_lo = min(max(s_lo, s_hi - 40.0), s_hi - 8.0)
    P, ok = _grid_panels(l, g_hi, g_lo, s_lo, s_mass - 4.0, s_hi, width, d, tol, h0, cw, shift, edges, degree, vals,
                         info)
    if not ok:
        info[1] = 0.0
    return P


@numba.njit(cache=True)
def _ep_grid_rows(ng, first, rows):
    """The interior g-rows of the ng-interval grid not on the previous (ng/2) grid; their count."""
    n = 0
    for i in range(1, ng):
        if first or i % 2 == 1:
            rows[n] = i
            n += 1
    return n


@numba.njit(cache=True)
def _ep_grid_next(ng, vals, P, d, degree, tol, info):
    """After the ng-grid's rows are in: 0 if the g-coefficients converged (or nothing to
    refine), else the next ng (info[1] = 0 if ng is already the largest)."""
    if ng == 1 or _grid_g_error(vals, ng, _GRID_MAX_NG // ng, P, d, degree) <= tol:
        return 0
    if ng == _GRID_MAX_NG:
        info[1] = 0.0
        return 0
    return 2 * ng


@numba.njit(cache=True)
def _ep_grid(l, g_lo, g_hi, d, width, tol, h0, cw, shift, yt, wt, jt, edges, degree, vals, coef,
             tot_coef, info):
    """The grid of ln G_k for one separation (serial): panels in s, then g-nodes doubled
    (nested Lobatto: 4, 8, 16, 32 intervals) until the g-coefficients converge; coefficients
    and totals. Returns (P, ng); info[0] += hyperbola integrals computed; info[1] = 0 if a
    tolerance was not reached (panels or g)."""
    P = _ep_grid_panels(l, g_lo, g_hi, d, width, tol, h0, cw, shift, edges, degree, vals, info)
    ng = _grid_ng_start(g_lo, g_hi, tol)
    rows = np.empty(_GRID_MAX_NG + 1, dtype=np.int64)
    first = True
    while True:
        n_rows = _ep_grid_rows(ng, first, rows)
        first = False
        _grid_fill(l, g_lo, g_hi, rows[:n_rows], _GRID_MAX_NG // ng, edges, degree, P, d, h0, cw, shift, vals)
        for p in range(P):
            info[0] += n_rows * (degree[p] + 1)
        nxt = _ep_grid_next(ng, vals, P, d, degree, tol, info)
        if nxt == 0:
            break
        ng = nxt
    _grid_coefficients(l, g_lo, g_hi, vals, ng, _GRID_MAX_NG // ng, P, d, degree, edges, yt, wt, jt, shift, coef,
                       tot_coef)
    return P, ng


@numba.njit(cache=True)
def _ep_grid_values(l, g_lo, g_hi, d, width, tol, h0, cw, yt, wt, jt, tau, g, out, info):
    """Build one separation's grid and evaluate ln G_0, ln G_1 from it at (τ[i], g[i]) (inside
    the g-range; below the grid by the model of _below_params); out[i] = (ln G_0, ln G_1).
    info = (hyperbola integrals computed, grid converged, panels, g-intervals, s at the grid's
    start). For the tests."""
    vals = np.empty((_GRID_MAX_NG + 1, _GRID_MAX_PANELS, d + 1, 2))
    coef = np.empty((_GRID_MAX_NG + 1, _GRID_MAX_PANELS, d + 1, 2))
    edges = np.empty(_GRID_MAX_PANELS + 1)
    degree = np.empty(_GRID_MAX_PANELS, dtype=np.int64)
    tot_coef = np.empty((4, _GRID_MAX_NG + 1))
    info[0] = 0.0
    info[1] = 1.0
    P, ng = _ep_grid(l, g_lo, g_hi, d, width, tol, h0, cw, 0.0, yt, wt, jt, edges, degree, vals, coef,
                     tot_coef, info)
    info[2] = P
    info[3] = ng
    info[4] = edges[0]
    cs = np.empty(max(d, ng) + 1)
    c = np.empty((2, d + 1))
    for i in range(tau.shape[0]):
        x_g = (2.0 * g[i] - g_lo - g_hi) / (g_hi - g_lo) if g_hi > g_lo else 0.0
        s = math.log(tau[i])
        p = 0
        while p < P - 1 and s > edges[p + 1]:
            p += 1
        n = degree[p] if s >= edges[0] else degree[0]
        pp = p if s >= edges[0] else 0
        for q in range(2):
            for j in range(n + 1):
                for k in range(ng + 1):
                    cs[k] = coef[k, pp, j, q]
                c[q, j] = _clenshaw(cs, ng, x_g)
        if s >= edges[0]:
            x = (2.0 * s - edges[p] - edges[p + 1]) / (edges[p + 1] - edges[p])
            out[i, 0] = _clenshaw(c[0], n, x)
            out[i, 1] = _clenshaw(c[1], n, x)
        else:
            z0, z1 = _hyperbola_at_zero(g[i], l, jt)
            for q in range(2):
                sc, a, b, kind = _below_params(c[q], n, edges[1] - edges[0], z0 if q == 0 else z1, edges[0])
                out[i, q] = math.log(_below_value(tau[i], s, sc, a, b, kind))


@numba.njit(cache=True)
def _ep_level_error(s_new, s_old):
    """max over the columns of |s_new − s_old| relative to max(|column|, 1e-3 |its total|)
    (the presets' convention for parts)."""
    e = 0.0
    for q in range(8):
        if q < 3:
            tot = s_new[0] + s_new[1] + s_new[2]
        elif q < 6:
            tot = s_new[3] + s_new[4] + s_new[5]
        else:
            tot = s_new[6]
        scale = max(abs(s_new[q]), _PART_FLOOR * abs(tot))
        diff = abs(s_new[q] - s_old[q])
        if scale > 0.0:
            e = max(e, diff / scale)
        elif diff > 0.0:
            e = math.inf
    return e


@numba.njit(cache=True)
def _ep_level_sum(m, n_levels, w_levels, node, cur, prev, e_prev):
    """cur = the level-m θ-sum (prev keeps level m − 1's); returns (estimate, e_m): the change
    e_m from level m − 1 and the estimate e_m·min(1, e_m/e_{m−1}) (inf at m = 0)."""
    n = n_levels[m]
    for q in range(8):
        prev[q] = cur[q]
        s = 0.0
        for j in range(n):
            s += w_levels[m, j] * node[j, q]
        cur[q] = s
    if m == 0:
        return math.inf, math.inf
    e = _ep_level_error(cur, prev)
    return (e * min(1.0, e / e_prev) if 0.0 < e_prev < math.inf else e), e


@numba.njit(cache=True)
def _ep_nodes(js, l, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, pv, with_jump, g_lo, g_hi, ng, edges,
              degree, P, d, coef, tot_coef, yt, wt, jt, shift, node):
    """node[j] = _ep_node at the θ-nodes j in ``js`` (one material)."""
    ln_r = math.log(ratio)
    cg = np.empty((P, d + 1, 2))
    cs = np.empty(max(d, ng) + 1)
    c1 = np.empty(d + 1)
    acc = np.empty(8)
    for j in js:
        _ep_node(l, g[j], c[j], f1[j], f2[j], f3[j], tc1[j], sigma, E_star, ratio, cH, dp, ln_r, pv, with_jump,
                 g_lo, g_hi, ng, edges, degree, P, coef, tot_coef, yt, wt, jt, shift, cg, cs, c1, acc)
        for q in range(8):
            node[j, q] = acc[q]


@numba.njit(cache=True)
def _ep_materials_done(shift, cur, est, m_used, n_levels, out, info):
    """out[k] = cur[k]·e^{−shift} and info[k, 2:] for every material k."""
    scale = math.exp(-shift)
    for k in range(cur.shape[0]):
        for q in range(8):
            out[k, q] = cur[k, q] * scale
        info[k, 2] = m_used[k]
        info[k, 3] = est[k] if n_levels.shape[0] > 1 else math.nan


@numba.njit(cache=True)
def _ep_separation(l, g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star, ratio, cH, dp, pv, with_jump,
                   d, width, tol, h0, cw, theta_tol, yt, wt, jt, work_vals, work_coef, out, info):
    """out[k, 0:8] = the θ-sums at one separation for each material k (serial); info[k] =
    (hyperbola integrals computed, 1 if the grid reached its tolerance, θ-level index used,
    estimated θ-error). tc1[k] and the constants E_star[k], ratio[k], cH[k], dp[k], pv[k],
    with_jump[k] are the material's; the grid of the hyperbola integrals is the surface's and
    the separation's, built once for all materials.

    θ-nodes are ordered by the tanh-sinh level they first appear in; n_levels[m] of them make
    level m, whose weights are w_levels[m] (× cos θ sin θ). Levels are added until the estimate
    e_m·min(1, e_m/e_{m−1}) ≤ theta_tol, e_m = the change from level m − 1 (tanh-sinh levels
    nest: the coarser sum costs nothing); with one level only, that one."""
    n_mat = tc1.shape[0]
    n_all = n_levels[n_levels.shape[0] - 1]
    g_lo = g.min()
    g_hi = g.max()
    edges = np.empty(_GRID_MAX_PANELS + 1)
    degree = np.empty(_GRID_MAX_PANELS, dtype=np.int64)
    tot_coef = np.empty((4, _GRID_MAX_NG + 1))
    grid_info = np.zeros(2)
    grid_info[1] = 1.0
    shift = 0.5 * l * l / (1.0 + g_hi * g_hi) if l > 0.0 else 0.0  # ln G ≤ −shift + O(1): scaled out
    cur = np.zeros((n_mat, 8))
    est = np.full(n_mat, math.inf)
    m_used = np.zeros(n_mat, dtype=np.int64)
    if shift <= _UNDERFLOW_SHIFT:  # else every column underflows: exactly 0
        P, ng = _ep_grid(l, g_lo, g_hi, d, width, tol, h0, cw, shift, yt, wt, jt, edges, degree, work_vals,
                         work_coef, tot_coef, grid_info)
        node = np.empty((n_all, 8))
        prev = np.zeros(8)
        for k in range(n_mat):
            e_prev = math.inf
            done = 0
            for m in range(n_levels.shape[0]):
                _ep_nodes(np.arange(done, n_levels[m]), l, g, c, f1, f2, f3, tc1[k], sigma, E_star[k], ratio[k],
                          cH[k], dp[k], pv[k], with_jump[k], g_lo, g_hi, ng, edges, degree, P, d, work_coef,
                          tot_coef, yt, wt, jt, shift, node)
                done = n_levels[m]
                est[k], e_prev = _ep_level_sum(m, n_levels, w_levels, node, cur[k], prev, e_prev)
                m_used[k] = m
                if est[k] <= theta_tol:
                    break
    for k in range(n_mat):
        info[k, 0] = grid_info[0]
        info[k, 1] = grid_info[1]
    _ep_materials_done(shift, cur, est, m_used, n_levels, out, info)


@numba.njit(cache=True)
def _ep_rows(rows, l_values, g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star, ratio, cH, dp, pv,
             with_jump, d, width, tol, h0, cw, theta_tol, yt, wt, jt, out, info):
    """_ep_separation for the separations in ``rows`` (one work grid reused); out[i, k, :]."""
    work_vals = np.empty((_GRID_MAX_NG + 1, _GRID_MAX_PANELS, d + 1, 2))
    work_coef = np.empty((_GRID_MAX_NG + 1, _GRID_MAX_PANELS, d + 1, 2))
    for i in rows:
        _ep_separation(l_values[i], g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star, ratio, cH, dp, pv,
                       with_jump, d, width, tol, h0, cw, theta_tol, yt, wt, jt, work_vals, work_coef, out[i], info[i])


@numba.njit(cache=True, parallel=True)
def _ep_rows_parallel(n_blocks, l_values, g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star, ratio, cH,
                      dp, pv, with_jump, d, width, tol, h0, cw, theta_tol, yt, wt, jt, out, info):
    """_ep_rows over all separations, interleaved over ``n_blocks`` blocks."""
    n = l_values.shape[0]
    for b in numba.prange(n_blocks):
        _ep_rows(np.arange(b, n, n_blocks), l_values, g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star,
                 ratio, cH, dp, pv, with_jump, d, width, tol, h0, cw, theta_tol, yt, wt, jt, out, info)


# ---------------------------------------------------------------------------------------
# The summit table (issue 33): the elasto-plastic columns as Gaussian convolutions
# ---------------------------------------------------------------------------------------
# With y = g r − t (t = the interference in σ units, r the curvature radius variable) the
# Gaussian φ(t + l − g r) of the summit measure is φ(l − y), so every column is
#
#     column(l) = ∫ φ(l − y) ρ(y) dy,   ρ(y) = Σ_θ w_θ ∫_{r ≥ max(0, y/g)} law(σ t, r c) r³ e^{−r²/2} dr,
#
# t = g r − y: ρ depends on the material and the surface, not on the separation
# (integrals.summit_table tabulates it once and makes every separation one quadrature).
# Per (y, θ) the r-integral runs in w = √(r − r0), r0 = max(0, y/g) (t ∝ w² at r0 for y > 0,
# r ∝ w² at r = 0 for y < 0: the t^{1/2}, t^{3/2}, r^{5/2} end-point powers become analytic),
# split at the regime boundaries τ = r t = t_c1, (ω_p/ω_c) t_c1, graded geometrically from
# w = √(|y|/g) (the distance of the branch point of √t next to the corner r = t = 0) and cut
# into pieces of at most ``dr_max`` in r; Gauss–Legendre on each piece.
_ST_TAIL = 55.0  # the r-range ends where e^{−r²/2} fell by e^{−55} from r0
_ST_MAX_PIECES = 96


@numba.njit(cache=True)
def _st_r_of_tau(y, g, tau):
    """The r > 0 with r (g r − y) = τ (τ > 0), without cancellation."""
    D = math.sqrt(y * y + 4.0 * g * tau)
    return (y + D) / (2.0 * g) if y >= 0.0 else 2.0 * tau / (D - y)


@numba.njit(cache=True)
def _st_node(y, S, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, ln_r, pv, with_jump, yq, wq, dr_max,
             edges, acc):
    """acc[0:8] = ρ at one (y, θ-node) per unit θ-weight, scaled by e^{S}: A^e, A^ep, A^p, W^e,
    W^ep, W^p, dW/dω (eqs. (46), (47), (54); (76), (75), (77); (61), (67) by regime) and the
    load-jump density (errata E17) J/σ · r e^{−r²/2}/(g + t_c1/r²) at r(τ = t_c1)."""
    for q in range(8):
        acc[q] = 0.0
    r0 = y / g if y > 0.0 else 0.0
    t0 = -y if y < 0.0 else 0.0  # t at r = r0
    r_end = math.sqrt(r0 * r0 + 2.0 * _ST_TAIL)
    w_end = math.sqrt(r_end - r0)
    rc = _st_r_of_tau(y, g, tc1)
    rp = _st_r_of_tau(y, g, ratio * tc1)
    wc = math.sqrt(min(rc, r_end) - r0)
    wp = math.sqrt(min(rp, r_end) - r0)
    # breakpoints in w: 0, the geometric grading, the regime boundaries, w_end
    n = 0
    edges[n] = 0.0
    n += 1
    d = math.sqrt(abs(y) / g)
    if d > 1e-4 * w_end:
        x = d
        while x < w_end and n < _ST_MAX_PIECES // 2:
            edges[n] = x
            n += 1
            x *= 3.0
    for b in (wc, wp, w_end):
        if b > 0.0:
            edges[n] = b
            n += 1
    edges[:n].sort()
    for i in range(n - 1):
        a = edges[i]
        b = edges[i + 1]
        if b <= a * (1.0 + 1e-15):
            continue
        m = int(math.ceil((b * b - a * a) / dr_max))
        m = max(1, m)
        h = (b - a) / m
        mid = 0.5 * (a + b)
        kind = 0 if mid <= wc else (1 if mid <= wp else 2)
        for j in range(m):
            lo = a + j * h
            for k in range(yq.shape[0]):
                w = lo + h * yq[k]
                r = r0 + w * w
                t = g * w * w + t0
                e = math.exp(S - 0.5 * r * r) * r * r * r * h * wq[k] * 2.0 * w
                if kind == 0:
                    A, W, Sd = _asperity_elastic(sigma * t, r * c, f1, f2, E_star)
                    acc[0] += A * e
                    acc[3] += W * e
                elif kind == 1:
                    A, W, Sd = _asperity_elastoplastic(sigma * t, r * c, f1, f3, sigma * tc1 / r, ratio, cH, dp,
                                                       ln_r, math.log(ratio * tc1 / (r * t)))
                    acc[1] += A * e
                    acc[4] += W * e
                else:
                    A, W, Sd = _asperity_plastic(sigma * t, r * c, f3, cH)
                    acc[2] += A * e
                    acc[5] += W * e
                acc[6] += Sd * e
    if with_jump:
        Ae, We, _ = _asperity_elastic(sigma * tc1, c, f1, f2, E_star)
        acc[7] = (Ae * pv - We) / sigma * rc * math.exp(S - 0.5 * rc * rc) / (g + tc1 / (rc * rc))


@numba.njit(cache=True)
def _st_rho(i, y_values, g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star, ratio, cH, dp, pv, with_jump,
            g_max, yq, wq, dr_max, theta_tol, out, info):
    """out[i] = ln ρ(y_i) (8 columns; −745 where a column is 0), θ-levels added until the
    estimated θ-error e·min(1, e/e_prev) ≤ theta_tol; info[i] = (level used, estimate)."""
    y = y_values[i]
    S = 0.5 * y * y / (g_max * g_max) if y > 0.0 else 0.0  # ρ ≤ e^{−S}·O(1): scaled out
    ln_r = math.log(ratio)
    n_all = n_levels[n_levels.shape[0] - 1]
    node = np.empty((n_all, 8))
    acc = np.empty(8)
    edges = np.empty(_ST_MAX_PIECES)
    cur = np.zeros(8)
    prev = np.zeros(8)
    done = 0
    e_prev = math.inf
    est = math.inf
    used = 0
    for m in range(n_levels.shape[0]):
        for j in range(done, n_levels[m]):
            _st_node(y, S, g[j], c[j], f1[j], f2[j], f3[j], tc1[j], sigma, E_star, ratio, cH, dp, ln_r, pv,
                     with_jump, yq, wq, dr_max, edges, acc)
            for q in range(8):
                node[j, q] = acc[q]
        done = n_levels[m]
        est, e_prev = _ep_level_sum(m, n_levels, w_levels, node, cur, prev, e_prev)
        used = m
        if est <= theta_tol:
            break
    for q in range(8):
        out[i, q] = (math.log(cur[q]) if cur[q] > 0.0 else -745.0) - S
    info[i, 0] = used
    info[i, 1] = est


@numba.njit(cache=True, parallel=True)
def _st_rho_array(y_values, g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star, ratio, cH, dp, pv,
                  with_jump, g_max, yq, wq, dr_max, theta_tol, out, info):
    """_st_rho at every y (threads over y)."""
    for i in numba.prange(y_values.shape[0]):
        _st_rho(np.int64(i), y_values, g, c, f1, f2, f3, tc1, w_levels, n_levels, sigma, E_star, ratio, cH, dp, pv,
                with_jump, g_max, yq, wq, dr_max, theta_tol, out, info)


@numba.njit(cache=True)
def _st_columns(l_values, y, log_scale, weights, out):
    """out[i] = Σ_j exp(log_scale_j − (l_i − y_j)²/2) weights[j]: the convolution (1) of
    integrals.summit_table at every separation. One thread: ~1 µs per (l, 100 nodes), less
    than waking a thread pool on a loaded machine."""
    n_q = weights.shape[1]
    for i in range(l_values.shape[0]):
        l = l_values[i]
        acc = np.zeros(n_q)
        for j in range(y.shape[0]):
            d = l - y[j]
            x = log_scale[j] - 0.5 * d * d
            if x > -745.0:
                e = math.exp(x)
                for q in range(n_q):
                    acc[q] += e * weights[j, q]
        for q in range(n_q):
            out[i, q] = acc[q]


# ---------------------------------------------------------------------------------------
# The shared summit table (issue 33): one build for every material of a surface
# ---------------------------------------------------------------------------------------
# Eq. (65) makes t_c1(θ) = β T(θ): β = (K_Y Y/E*)² is the only material factor (T = t_c1 of a
# reference material, β relative to it). In u = τ/T(θ), v = ln u, every piece of the law of
# _st_node is a material-free density of v times a function of u and the material constants:
#   (46), (47), (54) below u = β:  πσ·f1/c t r², (4/3)E* σ^{3/2}·f2/√c t^{3/2} r^{5/2}, 2E* σ^{1/2}·f2/√c t^{1/2} r^{5/2};
#   (61), (67), d(67)/dω above u = Rβ (R = ω_p/ω_c): 2πσ·f3/c t r², c_h H times it, 2π c_h H·f3/c r²;
#   (76), (75), (77) between: the bracket f1 + (2f3 − f1)G = (1 − G) f1 + 2G f3 with G, dG/dx and
#   the pressure (75) functions of x = (u/β − 1)/(R − 1) and ln(Rβ/u) = ln(Rβ) − v only;
#   the load jump (errata E17) at u = β: π (2/3)K_v H·f1/c r² − (4/3)E* σ^{1/2} β^{1/2}·f2 √T/√c r²
#   (a θ-sum at v = ln β itself),
# each (with the measure r³ e^{−r²/2} dr folded in, dr = τ/(g r + t) dv) summed over θ at fixed v:
#   D_q(y, v) = Σ_θ w_θ h_q(θ) m_q(r, t) e^{−r²/2} τ/(g r + t),   r (g r − y) = τ = e^v T(θ), t = τ/r,
# q = 0 … 6: f1/c t r², f3/c t r², f2/√c t^{3/2} r^{5/2}, f2/√c t^{1/2} r^{5/2}, f1/c r², f3/c r², f2 √T/√c r².
# Per y, ln D_q is interpolated on panels of v (Chebyshev–Lobatto, bisected to the tolerance);
# each material's ρ(y) is then the cumulative integrals of D at ln β and ln(Rβ) and a Gauss–
# Legendre integral over [ln β, ln Rβ] — no r-quadrature per material.
_SH_Q = 7
_SH_DEG = 16
_SH_MAX_PANELS = 192
_SH_MAX_DEPTH = 7  # bisections of a v-panel
_SH_BELOW = 20.0  # v_lo below the bulk: the lowest power of the lower tail is u^{3/2} (S^e, y > 0): e^{−30}
_SH_SPREAD = 20.0  # a panel's ln D may vary by this much: 20 Gauss–Legendre nodes integrate e^{ax}, |a| ≤ 10, to ~1e-17
_SH_WIDTH = 4.0


@numba.njit(cache=True)
def _sh_node(y, S, ev, g, h1, h3, h2, h2t, T, acc):
    """acc[0:7] = the seven densities D_q at one (y, v, θ-node), per unit θ-weight, scaled by e^S
    (ev = e^v: τ = e^v T(θ))."""
    tau = ev * T
    r = _st_r_of_tau(y, g, tau)
    t = tau / r
    e = math.exp(S - 0.5 * r * r) * tau / (g * r + t)
    r2 = r * r * e
    st = math.sqrt(tau)  # (r t)^{1/2}
    a = t * r2
    acc[0] = h1 * a
    acc[1] = h3 * a
    acc[2] = h2 * a * st
    acc[3] = h2 * r2 * st
    acc[4] = h1 * r2
    acc[5] = h3 * r2
    acc[6] = h2t * r2


@numba.njit(cache=True)
def _sh_density(y, S, v, g, h1, h3, h2, h2t, T, w_levels, n_levels, theta_tol, floor, node, acc, cur, out):
    """out[0:7] = D_q(y, v): θ-levels added until the estimated θ-error (per density, relative
    to max(D_q, floor_q)) ≤ theta_tol; returns (estimate, θ-nodes used)."""
    ev = math.exp(v)
    done = 0
    e_prev = math.inf
    est = math.inf
    for m in range(n_levels.shape[0]):
        for j in range(done, n_levels[m]):
            _sh_node(y, S, ev, g[j], h1[j], h3[j], h2[j], h2t[j], T[j], acc)
            for q in range(_SH_Q):
                node[j, q] = acc[q]
        done = n_levels[m]
        e = 0.0
        for q in range(_SH_Q):
            s = 0.0
            for j in range(done):
                s += w_levels[m, j] * node[j, q]
            if m > 0:
                scale = max(s, floor[q])
                d = abs(s - cur[q])
                if scale > 0.0:
                    e = max(e, d / scale)
                elif d > 0.0:
                    e = math.inf
            cur[q] = s
        if m > 0:
            est = e * min(1.0, e / e_prev) if 0.0 < e_prev < math.inf else e
            e_prev = e
            if est <= theta_tol:
                break
    for q in range(_SH_Q):
        out[q] = cur[q]
    return est, done


@numba.njit(cache=True)
def _sh_panel_integral(C, p, lo, hi, a, b, xg, wg, out):
    """out[q] = ∫_a^b e^{ln D_q} dv, q = 0 … 5, on [a, b] ⊂ panel p = [lo, hi] (Gauss–Legendre on
    the interpolant). (The columns are a loop, not an argument: a literal column number would
    give the kernel one signature per column, tests/integrals/test_kernels.py.)"""
    n = C.shape[2] - 1
    h = b - a
    for q in range(6):
        out[q] = 0.0
    for k in range(xg.shape[0]):
        x = (2.0 * (a + h * xg[k]) - lo - hi) / (hi - lo)
        for q in range(6):
            out[q] += wg[k] * math.exp(_clenshaw(C[p, q], n, x))
    for q in range(6):
        out[q] *= h


@numba.njit(cache=True)
def _sh_cumulative(vs, P, lo, hi, C, cum, xg, wg, out):
    """out[q] = ∫_{−∞}^{vs} D_q dv, q = 0 … 5 (panels sorted and contiguous; below them the
    power-law tail cum[0], above them the total)."""
    if vs <= lo[0]:
        for q in range(6):
            out[q] = cum[0, q] * math.exp(min(0.0, vs - lo[0]))  # the tail, at slope ≥ 1 (an upper bound)
        return
    if vs >= hi[P - 1]:
        for q in range(6):
            out[q] = cum[P, q]
        return
    p = 0
    while hi[p] < vs:
        p += 1
    _sh_panel_integral(C, p, lo[p], hi[p], lo[p], vs, xg, wg, out)
    for q in range(6):
        out[q] += cum[p, q]


@numba.njit(cache=True)
def _sh_material(P, lo, hi, C, cum, xg, wg, vb, lnR, sigma, E_star, cH, dp, col):
    """col[0:7] = ρ of one material (β = e^{vb}, R = e^{lnR}) at this y from the panels: the columns of
    _st_node (A^e, A^ep, A^p, W^e, W^ep, W^p, dW/dω), eqs. (46), (47), (54); (76), (75), (77);
    (61), (67); col[7] = 0 (the load jump is _sh_rho's)."""
    vr = vb + lnR
    R = math.exp(lnR)
    pi = math.pi
    n = C.shape[2] - 1
    cb = np.empty(6)
    cr = np.empty(6)
    _sh_cumulative(vb, P, lo, hi, C, cum, xg, wg, cb)
    _sh_cumulative(vr, P, lo, hi, C, cum, xg, wg, cr)
    col[0] = pi * sigma * cb[0]
    col[3] = (4.0 / 3.0) * E_star * sigma * math.sqrt(sigma) * cb[2]
    se = 2.0 * E_star * math.sqrt(sigma) * cb[3]
    col[2] = 2.0 * pi * sigma * (cum[P, 1] - cr[1])
    col[5] = cH * col[2]
    sp = 2.0 * pi * cH * (cum[P, 5] - cr[5])
    a_ep = 0.0
    w_ep = 0.0
    s_ep = 0.0
    va = max(vb, lo[0])
    vz = min(vr, hi[P - 1])
    if vz > va:
        for p in range(P):
            a = max(va, lo[p])
            b = min(vz, hi[p])
            if b <= a:
                continue
            h = b - a
            for k in range(xg.shape[0]):
                v = a + h * xg[k]
                x = (2.0 * v - lo[p] - hi[p]) / (hi[p] - lo[p])
                d1 = math.exp(_clenshaw(C[p, 0], n, x))
                d3 = math.exp(_clenshaw(C[p, 1], n, x))
                k1 = math.exp(_clenshaw(C[p, 4], n, x))
                k3 = math.exp(_clenshaw(C[p, 5], n, x))
                ub = math.exp(v - vb)  # ω/ω_c = u/β
                xx = (ub - 1.0) / (R - 1.0)
                G = xx * xx * (3.0 - 2.0 * xx)  # blend, asperity.blend
                dg = 6.0 * xx * (1.0 - xx)
                pr = cH - dp * (vr - v) / lnR  # eq. (75), ln(ω_p/ω) = ln(Rβ) − v
                A = (1.0 - G) * d1 + 2.0 * G * d3  # eq. (76) per πσ
                kb = (1.0 - G) * k1 + 2.0 * G * k3
                wk = wg[k] * h
                a_ep += wk * A
                w_ep += wk * A * pr
                s_ep += wk * ((kb + dg * (2.0 * k3 - k1) * ub / (R - 1.0)) * pr + kb * dp / lnR)
    col[1] = pi * sigma * a_ep
    col[4] = pi * sigma * w_ep
    col[6] = se + pi * s_ep + sp
    col[7] = 0.0  # the load jump: _sh_rho (a θ-sum at v = ln β)


@numba.njit(cache=True)
def _sh_panel_fit(L, C, p, gmax):
    """Chebyshev coefficients of ln D (L: (deg+1, 7) at the Lobatto nodes) into C[p]; returns the
    panel's error: the largest last-two-coefficient tail per density (relieved where the panel's
    D_q is below 1e-3 of its largest), inf where ln D varies by more than _SH_SPREAD (steep panel)
    or a significant density is 0 at a node."""
    err = 0.0
    vals = np.empty(_SH_DEG + 1)
    for q in range(_SH_Q):
        lmax = -math.inf
        lmin = math.inf
        for k in range(_SH_DEG + 1):
            lmax = max(lmax, L[k, q])
            lmin = min(lmin, L[k, q])
            vals[k] = L[k, q]
        _cheb_coefficients(vals, vals.shape[0] - 1, C[p, q])
        if gmax[q] <= 0.0 or lmax < math.log(gmax[q]) - 39.0:  # negligible: e^{−39} of its largest
            continue
        if lmin < -700.0 or lmax - lmin > _SH_SPREAD:
            return math.inf
        tail = max(abs(C[p, q, _SH_DEG]), abs(C[p, q, _SH_DEG - 1]))
        relief = max(1.0, 1e-3 * gmax[q] / math.exp(lmax))
        err = max(err, tail / relief)
    return err


@numba.njit(cache=True)
def _sh_rho(i, y_values, g, h1, h3, h2, h2t, lnT, w_levels, n_levels, g_max, theta_tol, v_tol, xg, wg, lnb, lnR,
            sigma, E_star, cH, dp, pv, with_jump, layout, out, info):
    """out[i, k] = ln ρ of material k at y_i (8 columns, −745 − S where a column is 0; the
    columns of _st_rho) from one set of v-panels of the densities D_q; info[i] = (largest
    θ-error estimate, v-nodes, largest accepted v-tail, panels, θ-node evaluations).
    ``layout``: [count, widths of the panels from the top down] of the previous (neighbouring)
    y, the initial panels here (then _SH_WIDTH), overwritten with this y's accepted panels."""
    y = y_values[i]
    S = 0.5 * y * y / (g_max * g_max) if y > 0.0 else 0.0
    n_all = n_levels[n_levels.shape[0] - 1]
    T = np.exp(lnT)
    v_lo = math.inf
    v_hi = -math.inf
    v_mid = 0.0
    for j in range(n_all):  # the range of v: the bulk (r² = r0² + 3) − _SH_BELOW … the r-range's end
        r0 = y / g[j] if y > 0.0 else 0.0
        rb = math.sqrt(r0 * r0 + 3.0)
        re = math.sqrt(r0 * r0 + 2.0 * _ST_TAIL)
        tb = g[j] * 3.0 / (rb + r0) if y > 0.0 else g[j] * rb - y
        te = g[j] * 2.0 * _ST_TAIL / (re + r0) if y > 0.0 else g[j] * re - y
        vb_ = math.log(rb * tb) - lnT[j]
        v_lo = min(v_lo, vb_)
        v_hi = max(v_hi, math.log(re * te) - lnT[j])
        v_mid += vb_ / n_all
    v_lo -= _SH_BELOW
    node = np.empty((n_all, _SH_Q))
    acc = np.empty(_SH_Q)
    cur = np.empty(_SH_Q)
    dens = np.empty(_SH_Q)
    floor = np.zeros(_SH_Q)
    gmax = np.zeros(_SH_Q)
    # the densities' scale at the bulk: the θ-error's floor (1e-4 of it) and the panels' relief
    worst_theta = 0.0
    n_eval = 0
    n_theta = 0
    for vp in (v_mid - 1.0, v_mid + 1.0):
        e, _ = _sh_density(y, S, vp, g, h1, h3, h2, h2t, T, w_levels, n_levels, theta_tol, floor, node, acc, cur,
                           dens)
        n_eval += 1
        for q in range(_SH_Q):
            gmax[q] = max(gmax[q], dens[q])
    for q in range(_SH_Q):
        floor[q] = 1e-4 * gmax[q]  # a tenth of the panels' relief (1e-3): θ-noise below their tolerance
    lo = np.empty(_SH_MAX_PANELS)
    hi = np.empty(_SH_MAX_PANELS)
    depth = np.zeros(_SH_MAX_PANELS, dtype=np.int64)
    ok = np.zeros(_SH_MAX_PANELS, dtype=np.bool_)
    C = np.empty((_SH_MAX_PANELS, _SH_Q, _SH_DEG + 1))
    L = np.empty((_SH_DEG + 1, _SH_Q))
    # initial panels from the top down: the neighbour's accepted ones, else widths 1, 1, 2 (the
    # e^{−r²/2} end of the range, where ln D falls like −e^v), then _SH_WIDTH (measured: wider
    # ones below the bulk are bisected back)
    n_prev = int(layout[0])
    P = 0
    b = v_hi
    while b > v_lo:
        if P < n_prev:
            w = layout[1 + P]
        else:
            w = 1.0 if (n_prev == 0 and P < 2) else (2.0 if (n_prev == 0 and P == 2) else _SH_WIDTH)
        a = b - w
        if a - v_lo < 0.5 * w:
            a = v_lo
        if P == _SH_MAX_PANELS // 2 - 1:  # room for bisections: the last initial panel reaches v_lo
            a = v_lo
        lo[P] = a
        hi[P] = b
        P += 1
        b = a
    worst_v = 0.0
    changed = True
    while changed:
        changed = False
        p = 0
        while p < P:
            if ok[p]:
                p += 1
                continue
            a = lo[p]
            b = hi[p]
            for k in range(_SH_DEG + 1):
                v = 0.5 * (a + b) + 0.5 * (b - a) * math.cos(math.pi * k / _SH_DEG)
                e, used = _sh_density(y, S, v, g, h1, h3, h2, h2t, T, w_levels, n_levels, theta_tol, floor, node,
                                      acc, cur, dens)
                n_eval += 1
                n_theta += used
                if e < math.inf:
                    worst_theta = max(worst_theta, e)
                for q in range(_SH_Q):
                    gmax[q] = max(gmax[q], dens[q])
                    L[k, q] = math.log(dens[q]) if dens[q] > 0.0 else -745.0
            err = _sh_panel_fit(L, C, np.int64(p), gmax)  # int64: p starts as the literal 0
            if err <= v_tol or depth[p] >= _SH_MAX_DEPTH or P >= _SH_MAX_PANELS:
                ok[p] = True
                if err < math.inf:
                    worst_v = max(worst_v, err)
                else:
                    worst_v = math.inf
                p += 1
            else:
                c = 0.5 * (a + b)
                hi[p] = c
                depth[p] += 1
                lo[P] = c
                hi[P] = b
                depth[P] = depth[p]
                ok[P] = False
                P += 1
                changed = True
    # panels in order, their integrals and the cumulative sums
    order = np.argsort(lo[:P])
    lo_s = lo[:P][order].copy()
    hi_s = hi[:P][order].copy()
    layout[0] = P
    for k in range(P):
        layout[1 + k] = hi_s[P - 1 - k] - lo_s[P - 1 - k]
    Cs = np.empty((P, _SH_Q, _SH_DEG + 1))
    for k in range(P):
        Cs[k] = C[order[k]]
    cum = np.zeros((P + 1, _SH_Q))
    part = np.empty(6)
    # below v_lo: the power-law tail D(v_lo)/(d ln D/dv) (≤ e^{−30} of the bulk: a second-order correction)
    deg = Cs.shape[2] - 1
    dv = 0.5 * (hi_s[0] - lo_s[0]) * (1.0 - math.cos(math.pi / deg))
    for q in range(6):
        l0 = _clenshaw(Cs[0, q], deg, -1.0)
        l1 = _clenshaw(Cs[0, q], deg, -1.0 + (1.0 - math.cos(math.pi / deg)))
        slope = max((l1 - l0) / dv, 1.0)
        cum[0, q] = math.exp(l0) / slope
    for k in range(P):
        _sh_panel_integral(Cs, k, lo_s[k], hi_s[k], lo_s[k], hi_s[k], xg, wg, part)
        for q in range(6):
            cum[k + 1, q] = cum[k, q] + part[q]
    col = np.empty(8)
    zero = np.zeros(_SH_Q)
    for k in range(lnb.shape[0]):
        _sh_material(P, lo_s, hi_s, Cs, cum, xg, wg, lnb[k], lnR[k], sigma, E_star[k], cH[k], dp[k], col)
        if with_jump[k]:  # errata E17 at u = β, directly (no panel reaches every y's first yield)
            _sh_density(y, S, lnb[k], g, h1, h3, h2, h2t, T, w_levels, n_levels, theta_tol, zero, node, acc, cur, dens)
            col[7] = math.pi * pv[k] * dens[4] \
                - (4.0 / 3.0) * E_star[k] * math.sqrt(sigma) * math.exp(0.5 * lnb[k]) * dens[6]
        for q in range(8):
            out[i, k, q] = (math.log(col[q]) if col[q] > 0.0 else -745.0) - S
    info[i, 0] = worst_theta
    info[i, 1] = n_eval
    info[i, 2] = worst_v
    info[i, 3] = P
    info[i, 4] = n_theta


@numba.njit(cache=True, parallel=True)
def _sh_rho_array(n_blocks, y_values, g, h1, h3, h2, h2t, lnT, w_levels, n_levels, g_max, theta_tol, v_tol, xg, wg,
                  lnb, lnR, sigma, E_star, cH, dp, pv, with_jump, out, info):
    """_sh_rho at every y: threads over ``n_blocks`` contiguous blocks of y (neighbours in a block
    start from each other's v-panels: the Lobatto nodes of a y-panel are consecutive). The caller
    gives n_blocks (summit_table: min(n, 4 × threads)): numba's thread count read inside a kernel
    is a dynamic global, which kept numba from caching it (~4.6 s of compilation per process)."""
    n = y_values.shape[0]
    for b in numba.prange(n_blocks):
        layout = np.zeros(_SH_MAX_PANELS + 1)
        for i in range(b * n // n_blocks, (b + 1) * n // n_blocks):
            _sh_rho(np.int64(i), y_values, g, h1, h3, h2, h2t, lnT, w_levels, n_levels, g_max, theta_tol, v_tol, xg,
                    wg, lnb, lnR, sigma, E_star, cH, dp, pv, with_jump, layout, out, info)
