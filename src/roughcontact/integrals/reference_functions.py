"""mpmath special functions of the reference integrator (:mod:`.reference`), independent of
the double-precision ones it checks: J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt (the GW F_ν(−a)), the
complete elliptic integrals in Carlson form, the exact inversion of (27) λ²(e1), the paper's
(33) and polynomials (36)–(39), and the Hertz factors f1, f2 of (46)–(47)
(Buczkowski & Kleiber 2009). It does not use :mod:`roughcontact.asperity.ellipse`.
"""

from __future__ import annotations

import functools
import math

import mpmath as mp
import numpy as np

from .normal_moments import mp_moment

__all__ = [
    "HERTZ_MODES",
    "normal_moment",
    "normal_moments_reference",
    "exact_e1",
    "paper_e1",
    "paper_clip_lambda",
    "hertz_factors",
    "exact_lambda_squared",
]

#: "exact": exact Hertz (27) inverted exactly; "paper": (33) clipped + (36)–(39);
#: "circle": f1 = f2 = 1 (a spherical asperity of curvature κm = r c(θ); for checks only).
HERTZ_MODES = ("exact", "paper", "circle")
# (33): e1 = 0.4777 λ/(1 − 1.3211 λ); e1 reaches 1 at λ = 1/(0.4777 + 1.3211) = 0.5559.
_P33_A = "0.4777"
_P33_B = "1.3211"
# (36)–(37) and (38)–(39) with a2 = 0.1077812 (Abramowitz & Stegun 17.3.36; the paper prints
# 0.10778112).
_AS_K = ("1.3862944", "0.1119723", "0.0725296", "0.5", "0.1213478", "0.0288729")
_AS_E = ("1", "0.4630151", "0.1077812", "0", "0.2452727", "0.0412496")
#: guard digits for the elliptic functions (the Carlson form B = R_F − R_D/3 cancels like
#: ln(4/e1) as e1 → 0, i.e. ≤ 3 digits at the smallest e1 tanh-sinh reaches)
_ELLIPTIC_GUARD_DPS = 15


# ---------------------------------------------------------------------------------------
# J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt (the Greenwood–Williamson F_ν(−a))
# ---------------------------------------------------------------------------------------
def _phi(a):
    return mp.exp(-a * a / 2) / mp.sqrt(2 * mp.pi)


def _Phi(a):
    return mp.erfc(-a / mp.sqrt(2)) / 2


def _J_integer(n: int, a):
    """J_n(a) for integer n ≥ 0: J_0 = Φ, J_1 = aΦ + φ, J_{k+1} = a J_k + k J_{k−1}.

    For a < 0 the recurrence cancels (J_n ~ n! φ(a)/|a|^{n+1} while its terms are
    ~ |a|^{n−1} φ(a)): about 2n log10|a| digits, supplied as guard bits."""
    a = mp.mpf(a)
    extra = 10
    if a < 0:
        extra += int(2 * n * math.log2(1.0 + float(-a))) + 4
    with mp.extraprec(extra):
        Phi = _Phi(a)
        if n == 0:
            return +Phi
        j_prev, j = Phi, a * Phi + _phi(a)
        for k in range(1, n):
            j_prev, j = j, a * j + k * j_prev
    return +j


def normal_moment(nu, a):
    """J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt at the current mpmath precision.

    Integer ν: the elementary forms (J_0 = Φ(a), J_1 = aΦ(a) + φ(a), recurrence);
    otherwise Γ(ν+1)/√(2π) e^{−a²/4} D_{−ν−1}(−a) with mpmath.pcfd(n, z) = D_n(z)."""
    a = mp.mpf(a)
    nu = mp.mpf(nu)
    if nu == int(nu) and nu >= 0:
        return _J_integer(int(nu), a)
    return mp_moment(nu, a)


def normal_moments_reference(a_values, dps: int = 20) -> np.ndarray:
    """Floats (J_{1/2}, J_1, J_{3/2})(a) as an (n, 3) array — the GW functions F_ν(d) = J_ν(−d)
    (contact.elastic passes a = −d)."""
    a_arr = np.atleast_1d(np.asarray(a_values, dtype=float))
    out = np.empty((a_arr.size, 3))
    with mp.workdps(dps):
        half = mp.mpf(1) / 2
        for i, a in enumerate(a_arr):
            for j, nu in enumerate((half, 1, 3 * half)):
                out[i, j] = float(normal_moment(nu, a))
    return out


# ---------------------------------------------------------------------------------------
# Hertz functions of one asperity, (27), (33), (36)–(39), (46)–(47)
# ---------------------------------------------------------------------------------------
def _carlson(m1):
    """K, E, D = (K − E)/m, B = K − D at complementary parameter m1 = e1² = 1 − m, from
    K = R_F(0, m1, 1), D = R_D(0, m1, 1)/3 (Jahnke–Emde; no cancellation in m)."""
    K = mp.elliprf(0, m1, 1)
    D = mp.elliprd(0, m1, 1) / 3
    B = K - D
    E = B + m1 * D
    return K, E, D, B


def exact_lambda_squared(e1):
    """λ² = b²/a² of (27) for e1 = B/A: λ² = (K − E)(1 − m)/(E − (1 − m)K) = m1 D(m)/B(m)."""
    e1 = mp.mpf(e1)
    with mp.extradps(_ELLIPTIC_GUARD_DPS):
        m1 = e1 * e1
        _, _, D, B = _carlson(m1)
        return +(m1 * D / B)


def exact_e1(lam2):
    """Exact inversion of (27): the e1 = B/A ∈ (0, 1] with λ²(e1) = ``lam2`` ∈ (0, 1].

    Solved for x = ln e1 with mpmath.findroot (bracketing Anderson–Björck) on
    ln λ²(e^x) − ln λ² = 0, which is monotone; the bracket is [x_lo, ln λ]
    (λ ≥ e1 because D ≥ B)."""
    lam2 = mp.mpf(lam2)
    if lam2 >= 1:
        return mp.mpf(1)
    if lam2 <= 0:
        return mp.mpf(0)
    with mp.extradps(_ELLIPTIC_GUARD_DPS):
        target = mp.log(lam2)

        def F(x):
            m1 = mp.exp(2 * x)
            _, _, D, B = _carlson(m1)
            return mp.log(m1 * D / B) - target

        x_hi = target / 2
        if F(x_hi) <= 0:  # only at λ² → 1 within rounding
            return mp.exp(x_hi)
        # small-e1 form (32): λ² ≈ e1² (ln(4/e1) − 1), so e1 ≈ λ/√(ln(4/λ)); step down from there
        x_lo = x_hi - mp.log(1 + mp.log(4 / mp.sqrt(lam2))) / 2 - mp.mpf("0.5")
        while F(x_lo) >= 0:
            x_lo -= 1
        tol = mp.eps * 2**10
        x = mp.findroot(F, (x_lo, x_hi), solver="anderson", tol=tol, verify=False)
        return +mp.exp(x)


@functools.lru_cache(maxsize=64)
def _mp_constants(strings: tuple, prec: int) -> tuple:
    """Decimal constants as mpf at one precision (string parsing is slow in mpmath)."""
    with mp.workprec(prec):
        return tuple(mp.mpf(c) for c in strings)


def paper_clip_lambda():
    """λ = 1/(0.4777 + 1.3211) where (33) reaches e1 = 1 (the paper's clip point)."""
    a, b = _mp_constants((_P33_A, _P33_B), mp.mp.prec)
    return 1 / (a + b)


def paper_e1(lam):
    """(33) as the paper used it: e1 = 0.4777 λ/(1 − 1.3211 λ), clipped to ≤ 1; e1 = 1 (a
    circle) from the clip point λ = 1/(0.4777 + 1.3211) on, including the pole at 1/1.3211."""
    lam = mp.mpf(lam)
    a, b = _mp_constants((_P33_A, _P33_B), mp.mp.prec)
    if lam * (a + b) >= 1:
        return mp.mpf(1)
    return a * lam / (1 - b * lam)


def _as_poly(coef, m1):
    """(36) / (38): (a0 + a1 m1 + a2 m1²) + (b0 + b1 m1 + b2 m1²) ln(1/m1)."""
    a0, a1, a2, b0, b1, b2 = _mp_constants(coef, mp.mp.prec)
    if m1 == 1:
        return a0 + a1 + a2
    return (a0 + a1 * m1 + a2 * m1 * m1) + (b0 + b1 * m1 + b2 * m1 * m1) * mp.log(1 / m1)


def hertz_factors(lam2, hertz: str = "exact"):
    """(e1, f1, f2) at λ² ∈ (0, 1], (46)–(47): f1 = E/(K e1), f2 = π√E/(2 K^{3/2} e1).

    "exact": e1 from the exact inversion of (27), K, E exact (Carlson forms);
    "paper": e1 from (33) clipped, K, E from the polynomials (36)–(39) in m1 = e1²;
    "circle": e1 = f1 = f2 = 1."""
    lam2 = mp.mpf(lam2)
    if hertz == "circle":
        return mp.mpf(1), mp.mpf(1), mp.mpf(1)
    if hertz == "exact":
        e1 = exact_e1(lam2)
        with mp.extradps(_ELLIPTIC_GUARD_DPS):
            K, E, _, _ = _carlson(e1 * e1)
            f1 = E / (K * e1)
            f2 = mp.pi * mp.sqrt(E) / (2 * K**1.5 * e1)
        return e1, +f1, +f2
    if hertz == "paper":
        e1 = paper_e1(mp.sqrt(lam2))
        m1 = e1 * e1
        K, E = _as_poly(_AS_K, m1), _as_poly(_AS_E, m1)
        return e1, E / (K * e1), mp.pi * mp.sqrt(E) / (2 * K**1.5 * e1)
    raise ValueError(f"hertz must be one of {', '.join(HERTZ_MODES)}; got {hertz!r}")
