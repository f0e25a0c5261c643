"""The numba production kernels of the summit integrals (elastic and elasto-plastic).

The integrals are those of docs/derivation.md in polar form, θ outside, r in the middle and
the interference t inside, against the Gaussian φ(t + l − r g(θ)). What makes them fast
(docs/performance.md has the measurements):

* t in closed form. Elastic summits need only J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt, ν = 1/2, 1, 3/2,
  evaluated from the Chebyshev tables of normal_moments.py (≤ 7e-16 relative, exact zero
  below a ≈ −38.6) instead of ~200 tanh-sinh nodes per (θ, r) node. Plastic summits need
  J_0, J_1 at a shifted argument; only the finite elastic and elasto-plastic t-pieces of a
  summit that straddles first yield are integrated numerically (Gauss–Legendre).
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
elasto-plastic kernel against the scipy twin elastoplastic.reference_integrals
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


@numba.njit(cache=True)
def _t_rule_row(lo, hi, a, log_span):
    """Which t-rule a piece [lo, hi] gets (rows of the (3, n) node arrays: n, n/2, n/4 nodes):
    by the variation of ln φ(t − a) across it, (hi − lo)·max(1, |a − t_mid|), and the span of
    ln t if integrated in ln t. Short pieces (high ψ: t_c ≪ 1) are nearly polynomial;
    tests/contact/test_elastoplastic.py checks every preset against finer settings and the twin."""
    length = hi - lo
    c = max(length * max(1.0, abs(a - 0.5 * (lo + hi))), log_span)
    if c <= 0.1:
        return 2
    if c <= 0.75:
        return 1
    return 0


@numba.njit(cache=True)
def _t_window(a):
    """[lo, hi] of t ≥ 0 outside which φ(t − a) is below e^{−TAIL} of its maximum."""
    if a > 0.0:
        return max(0.0, a - _SPAN), a + _SPAN
    # maximum at t = 0: exp(−(t − a)²/2)/exp(−a²/2) = exp(−|a| t − t²/2) = e^{−TAIL}
    # at t = −|a| + √(a² + 2 TAIL), i.e. a + √(a² + 2 TAIL) since a ≤ 0
    return 0.0, a + math.sqrt(a * a + 2.0 * TAIL)


@numba.njit(cache=True)
def _t_elastic_piece(lo, hi, a, e, yt, wt, in_sqrt):
    """e^{e} ∫_lo^hi (t^{1/2}, t, t^{3/2}) φ(t − a) dt (Gauss–Legendre; in u = √t if in_sqrt;
    the rule of _t_rule_row)."""
    row = _t_rule_row(lo, hi, a, 0.0)
    y = yt[row]
    w = wt[row]
    m_h = 0.0
    m_1 = 0.0
    m_3 = 0.0
    if in_sqrt:
        u0 = math.sqrt(lo)
        du = math.sqrt(hi) - u0
        for k in range(y.shape[0]):
            if w[k] == 0.0:
                break
            u = u0 + du * y[k]
            t = u * u
            d = t - a
            f = 2.0 * du * w[k] * u * _INV_SQRT_2PI * math.exp(e - 0.5 * d * d)  # dt = 2u du
            m_h += f * u
            m_1 += f * t
            m_3 += f * t * u
    else:
        width = hi - lo
        for k in range(y.shape[0]):
            if w[k] == 0.0:
                break
            t = lo + width * y[k]
            d = t - a
            f = width * w[k] * _INV_SQRT_2PI * math.exp(e - 0.5 * d * d)
            st = math.sqrt(t)
            m_h += f * st
            m_1 += f * t
            m_3 += f * t * st
    return m_h, m_1, m_3


@numba.njit(cache=True)
def _t_elastic(lo, hi, a, e, y, w):
    """_t_elastic_piece on [lo, hi], split at the peak t = a if inside; a piece that starts
    near t = 0 (lo < hi/2) in u = √t (t^{1/2} is not smooth at 0: in t the short rules would
    converge like ((1 + √(lo/hi))/(1 − √(lo/hi)))^{−2n} only)."""
    if lo < a < hi:
        h1, o1, t1 = _t_elastic_piece(lo, a, a, e, y, w, lo < 0.5 * a)
        h2, o2, t2 = _t_elastic_piece(a, hi, a, e, y, w, a < 0.5 * hi)
        return h1 + h2, o1 + o2, t1 + t2
    return _t_elastic_piece(lo, hi, a, e, y, w, lo < 0.5 * hi)


@numba.njit(cache=True)
def _t_ep_piece(lo, hi, a, e, yt, wt, in_log, sigma, kappa, f1, f3, wc, ratio, cH, dp, ln_r):
    """e^{e} ∫_lo^hi (A, W, dW/dω)(σ t) φ(t − a) dt with the elasto-plastic law (76), (77), and
    at the same nodes e^{e} ∫_lo^hi (t^{1/2}, t, t^{3/2}) φ(t − a) dt (for the complement of
    the elastic part); Gauss–Legendre in t, or in ln t when ``in_log`` (the law holds ln t: a
    piece reaching towards t = 0, up to t_p/t_c = 45, would converge only algebraically in
    t); the rule of _t_rule_row."""
    acc_a = 0.0
    acc_w = 0.0
    acc_s = 0.0
    m_h = 0.0
    m_1 = 0.0
    m_3 = 0.0
    span = math.log(hi / lo) if in_log else hi - lo
    row = _t_rule_row(lo, hi, a, span if in_log else 0.0)
    y = yt[row]
    w = wt[row]
    ln_top = math.log(ratio * wc / (sigma * lo)) if in_log else 0.0  # ln(ω_p/ω) at t = lo
    for k in range(y.shape[0]):
        if w[k] == 0.0:
            break
        if in_log:
            t = lo * math.exp(span * y[k])
            jac = span * t
            ln_q = ln_top - span * y[k]
        else:
            t = lo + span * y[k]
            jac = span
            ln_q = math.log(ratio / (sigma * t / wc))
        d = t - a
        f = jac * w[k] * _INV_SQRT_2PI * math.exp(e - 0.5 * d * d)
        A, W, S = _asperity_elastoplastic(sigma * t, kappa, f1, f3, wc, ratio, cH, dp, ln_r, ln_q)
        acc_a += f * A
        acc_w += f * W
        acc_s += f * S
        st = math.sqrt(t)
        m_h += f * st
        m_1 += f * t
        m_3 += f * t * st
    return acc_a, acc_w, acc_s, m_h, m_1, m_3


@numba.njit(cache=True)
def _t_ep(lo, hi, a, e, y, w, sigma, kappa, f1, f3, wc, ratio, cH, dp, ln_r):
    """_t_ep_piece on [lo, hi] (lo ≥ t_c > 0), split at the peak t = a if inside; in ln t
    where a piece starts near 0 relative to its length (lo < hi/2)."""
    if lo < a < hi:
        a1, w1, s1, h1, o1, t1 = _t_ep_piece(lo, a, a, e, y, w, lo < 0.5 * a, sigma, kappa, f1, f3, wc, ratio, cH,
                                             dp, ln_r)
        a2, w2, s2, h2, o2, t2 = _t_ep_piece(a, hi, a, e, y, w, a < 0.5 * hi, sigma, kappa, f1, f3, wc, ratio, cH,
                                             dp, ln_r)
        return a1 + a2, w1 + w2, s1 + s2, h1 + h2, o1 + o2, t1 + t2
    return _t_ep_piece(lo, hi, a, e, y, w, lo < 0.5 * hi, sigma, kappa, f1, f3, wc, ratio, cH, dp, ln_r)


@numba.njit(cache=True)
def _ep_r_piece(lo, hi, in_sqrt, l, g, c, f1, f2, f3, tc1, S, sigma, E_star, ratio, cH, dp, ln_r, pv,
                with_jump, y_r, w_r, y_t, w_t, jt, acc):
    """acc[0:8] += e^{S} ∫_lo^hi r³ e^{−r²/2} (t-integrals) dr, columns (A^e, A^ep, A^p, W^e,
    W^ep, W^p, dW/dω, load-jump term).

    Per r: a = r g − l, κ_m = r c (44), ω_c = σ tc1/r (65), t_c = tc1/r, t_p = (ω_p/ω_c) t_c.
    A summit whose Gaussian t-window lies below t_c is elastic: σ-powers of (46), (47), (54)
    times J_1, J_{3/2}, J_{1/2}(a) in closed form; above t_p plastic: (61), (67) with
    ∫_{t_p}^∞ (1, t) φ(t − a) dt = (J_0(a − t_p), t_p J_0(a − t_p) + J_1(a − t_p)), also
    closed. Only the elastic piece [lo, t_c] and the elasto-plastic piece [t_c, t_p] of a
    straddling window are integrated numerically. The jump term: (1/σ) J φ(t_c − a) with
    J = A^e(ω_c)·(2/3) K_v H − W^e(ω_c) (pv = (2/3) K_v H)."""
    s15 = sigma * math.sqrt(sigma)
    ss = math.sqrt(sigma)
    for k in range(y_r.shape[0]):
        if in_sqrt:
            u0 = math.sqrt(lo)
            du = math.sqrt(hi) - u0
            u = u0 + du * y_r[k]
            r = u * u
            wr = 2.0 * du * w_r[k] * u * r * r * r
        else:
            r = lo + (hi - lo) * y_r[k]
            wr = (hi - lo) * w_r[k] * r * r * r
        if wr == 0.0:
            continue
        e = S - 0.5 * r * r
        a = r * g - l
        kappa = r * c  # κ_m = r c(θ), eq. (44)
        tc = tc1 / r
        wc = sigma * tc  # ω_c = ω_c(θ, κ_m = c)/r, eq. (65)
        tp = ratio * tc
        t_lo, t_hi = _t_window(a)
        rk = math.sqrt(kappa)
        ce_a = f1 * math.pi * sigma / kappa  # (46) per unit t
        ce_w = f2 * (4.0 / 3.0) * E_star * s15 / rk  # (47) per unit t^{3/2}
        ce_s = 2.0 * f2 * E_star * ss / rk  # (54) per unit t^{1/2}
        cp_a = 2.0 * f3 * math.pi * sigma / kappa  # (61) per unit t
        cp_s = 2.0 * f3 * math.pi * cH / kappa  # d(67)/dω
        if tc >= t_hi:
            _, jh, j1, j3 = _moments(a, e, jt)
            acc[0] += wr * ce_a * j1
            acc[3] += wr * ce_w * j3
            acc[6] += wr * ce_s * jh
        elif tp <= t_lo:
            j0, _, j1, _ = _moments(a, e, jt)
            acc[2] += wr * cp_a * j1
            acc[5] += wr * cp_a * cH * j1
            acc[6] += wr * cp_s * j0
        else:
            ep_lo = max(t_lo, tc)
            ep_hi = min(t_hi, tp)
            mh = m1 = m3 = 0.0
            if ep_lo < ep_hi:
                A, W, Sd, mh, m1, m3 = _t_ep(ep_lo, ep_hi, a, e, y_t, w_t, sigma, kappa, f1, f3, wc, ratio, cH, dp,
                                             ln_r)
                acc[1] += wr * A
                acc[4] += wr * W
                acc[6] += wr * Sd
            if tc > t_lo:
                if tp >= t_hi and tc >= 0.5 * (a + math.sqrt(a * a + 4.0)):
                    # the window above t_c is all elasto-plastic and t_c lies above the mode of
                    # t φ(t − a) (the elastic part is a large share, so the difference does not
                    # cancel): the closed form minus the t^ν-integrals at the nodes of that piece
                    _, jh, j1, j3 = _moments(a, e, jt)
                    mh, m1, m3 = jh - mh, j1 - m1, j3 - m3
                else:
                    mh, m1, m3 = _t_elastic(t_lo, tc, a, e, y_t, w_t)
                acc[0] += wr * ce_a * m1
                acc[3] += wr * ce_w * m3
                acc[6] += wr * ce_s * mh
            if tp < t_hi:
                j0, _, j1, _ = _moments(a - tp, e, jt)
                p1 = tp * j0 + j1
                acc[2] += wr * cp_a * p1
                acc[5] += wr * cp_a * cH * p1
                acc[6] += wr * cp_s * j0
        if with_jump:
            d = tc - a
            Ae, We, _ = _asperity_elastic(wc, kappa, f1, f2, E_star)
            acc[7] += wr * (Ae * pv - We) * _INV_SQRT_2PI * math.exp(e - 0.5 * d * d) / sigma


@numba.njit(cache=True)
def _regime_crossing(g, l, tau):
    """The r > 0 where a regime boundary t = τ/r (τ = t_c1 or (ω_p/ω_c) t_c1) meets the bulk
    of the t-mass, the mode t_m(a) = (a + √(a² + 4))/2 of t φ(t − a), a = r g − l: the
    regime parts change fastest there. τ/r falls and t_m(r g − l) rises with r: bisection
    in ln r."""
    lo = -60.0
    hi = math.log(max(1.0, abs(l) / g) + 2.0 * math.sqrt(tau) + 2.0 * tau + 10.0)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        r = math.exp(mid)
        a = r * g - l
        if tau / r > 0.5 * (a + math.sqrt(a * a + 4.0)):
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-6:
            break
    return math.exp(0.5 * (lo + hi))


@numba.njit(cache=True)
def _ep_theta_node(l, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, ln_r, pv, with_jump,
                   y_r, w_r, y_t, w_t, jt, cuts, acc):
    """acc[0:8] = the (r, t)-integrals at one θ-node (unscaled). The r-partition is the
    elastic one (_r_cuts) plus the r where t_c and t_p cross the bulk of the t-mass
    (_regime_crossing)."""
    n, S, sqrt0 = _r_cuts(g, l, cuts)
    r_c = _regime_crossing(g, l, tc1)
    r_p = _regime_crossing(g, l, ratio * tc1)
    for extra in (0.5 * r_c, r_c, 2.0 * r_c, r_p):
        if cuts[0] < extra < cuts[n - 1]:
            p = n
            while cuts[p - 1] > extra:
                cuts[p] = cuts[p - 1]
                p -= 1
            cuts[p] = extra
            n += 1
    for q in range(8):
        acc[q] = 0.0
    for p in range(n - 1):
        lo = cuts[p]
        hi = cuts[p + 1]
        if hi > lo:
            in_sqrt = lo < 0.1 * hi and (lo > 0.0 or sqrt0)
            _ep_r_piece(lo, hi, in_sqrt, l, g, c, f1, f2, f3, tc1, S, sigma, E_star, ratio, cH, dp, ln_r, pv,
                        with_jump, y_r, w_r, y_t, w_t, jt, acc)
    f = math.exp(-S)
    for q in range(8):
        acc[q] *= f


@numba.njit(cache=True)
def _ep_pairs(pairs, l_values, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, pv, with_jump,
              y_r, w_r, y_t, w_t, jt, out):
    """out[i, j, :] for the (l, θ-node) pairs ij = i·n_θ + j in ``pairs``."""
    n_theta = g.shape[0]
    ln_r = math.log(ratio)
    cuts = np.empty(12)
    acc = np.empty(8)
    for ij in pairs:
        i = ij // n_theta
        j = ij - i * n_theta
        _ep_theta_node(l_values[i], g[j], c[j], f1[j], f2[j], f3[j], tc1[j], sigma, E_star, ratio, cH, dp, ln_r,
                       pv, with_jump, y_r, w_r, y_t, w_t, jt, cuts, acc)
        for q in range(8):
            out[i, j, q] = acc[q]


@numba.njit(cache=True, parallel=True)
def _ep_pairs_parallel(n_blocks, l_values, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, pv, with_jump,
                       y_r, w_r, y_t, w_t, jt, out):
    """_ep_pairs over all (l, θ-node) pairs, interleaved over ``n_blocks`` blocks (the cost
    of a pair varies along θ)."""
    n = l_values.shape[0] * g.shape[0]
    for b in numba.prange(n_blocks):
        pairs = np.arange(b, n, n_blocks)
        _ep_pairs(pairs, l_values, g, c, f1, f2, f3, tc1, sigma, E_star, ratio, cH, dp, pv, with_jump,
                  y_r, w_r, y_t, w_t, jt, out)
