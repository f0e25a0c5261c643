"""Hertz contact ellipse of one elliptic-paraboloid asperity (section 3 and 5 of the paper).

Equation numbers are those of Buczkowski & Kleiber (2009); corrections are in docs/errata.md.

Convention (this module owns it)
--------------------------------
The contact ellipse is parameterised by the *complementary modulus*

    e1 = B/A = sqrt(1 - e²) ∈ (0, 1]                                          eq. (30)

(B ≤ A the semi-axes of the contact ellipse, e its eccentricity), with m = e² = 1 - e1²
(eq. (40)) and m1 = e1² (eq. (41)). Everything is computed from e1 so that no cancellation
occurs as e → 1 (e1 → 0). All quantities are dimensionless.

The complete elliptic integrals are built from the Jahnke–Emde integrals (Δ = sqrt(1 - m sin²φ))

    B(m) = ∫₀^{π/2} cos²φ/Δ dφ = m1 R_D(0, 1, m1)/3,
    D(m) = ∫₀^{π/2} sin²φ/Δ dφ = R_D(0, m1, 1)/3,

(Carlson's symmetric R_D, DLMF 19.25.1), so that

    K = B + D (eq. 28),  E = B + m1 D (eq. 48),  K - E = m D,  E - m1 K = m B.

Both forms are sums of positive terms; none cancels. The alternative B = K - D loses a factor
≈ ln(4/e1) in relative precision as e1 → 0, and B = (E - m1 K)/m loses 1/m as e1 → 1
(checked against mpmath; see tests/asperity/test_ellipse.py), so the m1 R_D(0, 1, m1) form is used.
For e1 < 1e-8 (where m1 = e1² would underflow for e1 ≲ 1e-154) the two-term asymptotic
expansions in m1 with L = ln(4/e1) are used (DLMF 19.12.1-2):

    D = (L - 1) + m1 (3L/4 - 1),   B = 1 + m1 (3/4 - L/2),   neglected terms O(m1² L).

λ² = κ_small/κ_large ∈ (0, 1] is the ratio of the smaller to the larger principal curvature of
the summit (= b²/a² of the geometric ellipse, b ≤ a). Summits with λ > 1 (the ellipse turns,
the major axis swaps direction) are handled everywhere by λ → 1/λ.

Two "hertz" options exist:

* ``"exact"``: λ ↔ e1 from the exact Hertz relation (27), K, E exact.
* ``"paper"``: the paper's numerics — e1 from the fitted inversion (33), clipped to e1 ≤ 1
  (for λ ≥ PAPER_LAMBDA_CLIP, including beyond the pole PAPER_LAMBDA_POLE, the ellipse is
  taken as a circle, e1 = 1), and K, E from the Abramowitz–Stegun polynomials (36)–(39) with
  the A&S value a2 = 0.1077812 in (39) (the paper misprints 0.10778112). f3, f4 are computed
  from the exact B, D, K, E of that e1 (the paper's section 5 has no separate recipe).

The module is pure numpy/scipy, vectorised over arrays, and does no I/O.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy.special import elliprd

__all__ = [
    "PAPER_LAMBDA_CLIP",
    "PAPER_LAMBDA_POLE",
    "PRINTED_E_A2",
    "AS_K_COEFFS",
    "AS_E_COEFFS",
    "AS_K_BOUND",
    "AS_E_BOUND",
    "HertzFactors",
    "eccentricity",
    "elliptic_BD",
    "elliptic_KE",
    "lambda_squared",
    "lambda_from_e1",
    "lambda_squared_small_e1",
    "e1_from_lambda",
    "e1_from_lambda_paper_raw",
    "f1",
    "f2",
    "f3",
    "f4",
    "hertz_factors",
    "kinks",
    "fig4_curves",
]

# --- constants of the paper's numerics -----------------------------------------------------

#: Coefficients of the fitted inversion (33): e1 = P33_A λ / (1 - P33_C λ).
P33_A = 0.4777
P33_C = 1.3211
#: λ where (33) has its pole (1 - 1.3211 λ = 0), ≈ 0.75694.
PAPER_LAMBDA_POLE = 1.0 / P33_C
#: λ where (33) reaches e1 = 1 (0.4777 λ = 1 - 1.3211 λ), ≈ 0.55593; clipped to a circle beyond.
PAPER_LAMBDA_CLIP = 1.0 / (P33_A + P33_C)

#: A&S 17.3.34 (the paper's (36)–(37)): (a0, a1, a2), (b0, b1, b2); |ε| ≤ 3e-5.
AS_K_COEFFS = ((1.3862944, 0.1119723, 0.0725296), (0.5, 0.1213478, 0.0288729))
AS_K_BOUND = 3e-5
#: A&S 17.3.36 (the paper's (38)–(39)): (1, a1, a2), (0, b1, b2); |ε| ≤ 4e-5.
AS_E_COEFFS = ((1.0, 0.4630151, 0.1077812), (0.0, 0.2452727, 0.0412496))
AS_E_BOUND = 4e-5
#: a2 of (39) as printed in the paper (misprint of A&S 0.1077812).
PRINTED_E_A2 = 0.10778112

_LN4 = math.log(4.0)
_SERIES_E1 = 1e-8  # below this e1, use the asymptotic expansions (m1 < 1e-16)
_TINY = np.finfo(float).smallest_subnormal


# --- helpers -------------------------------------------------------------------------------


def _as_e1(e1) -> tuple[np.ndarray, bool]:
    arr = np.asarray(e1, dtype=float)
    if np.any((arr < 0.0) | (arr > 1.0)):
        raise ValueError("e1 = B/A must lie in [0, 1]")
    return arr, arr.ndim == 0


def _out(x, scalar: bool):
    return float(x) if scalar else x


def eccentricity(e1):
    """Eccentricity e = sqrt(1 - e1²) of the contact ellipse from e1 = B/A, eq. (30).

    Computed as sqrt((1 - e1)(1 + e1)), accurate for e1 → 1 (e → 0). Dimensionless.
    """
    a, scalar = _as_e1(e1)
    return _out(np.sqrt((1.0 - a) * (1.0 + a)), scalar)


def _bd(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Jahnke–Emde B, D for an array a = e1 ∈ [0, 1] (no validation)."""
    B = np.empty_like(a)
    D = np.empty_like(a)
    small = a < _SERIES_E1
    big = ~small
    if np.any(big):
        m1 = a[big] * a[big]
        D[big] = elliprd(0.0, m1, 1.0) / 3.0  # D = R_D(0, m1, 1)/3 (DLMF 19.25.1)
        B[big] = m1 * elliprd(0.0, 1.0, m1) / 3.0  # mB = E - m1 K = m m1 R_D(0, 1, m1)/3
    if np.any(small):
        s = a[small]
        zero = s == 0.0
        with np.errstate(divide="ignore", under="ignore"):
            L = np.where(zero, np.inf, _LN4 - np.log(np.where(zero, 1.0, s)))  # ln(4/e1), cf. (31)
            m1 = s * s
            mL = np.where(zero, 0.0, m1 * np.where(zero, 0.0, L))
        # asymptotic expansions of D and B for m1 → 0 (DLMF 19.12.1-2; (31) is the K one)
        D[small] = (L - 1.0) + (0.75 * mL - m1)
        B[small] = 1.0 + (0.75 * m1 - 0.5 * mL)
    return B, D


# --- elliptic integrals --------------------------------------------------------------------


def elliptic_BD(e1):
    """Jahnke–Emde integrals (B(m), D(m)), m = 1 - e1², of the modulus e = sqrt(1 - e1²).

    B = ∫cos²φ/Δ dφ, D = ∫sin²φ/Δ dφ over (0, π/2), Δ = sqrt(1 - m sin²φ); dimensionless.
    K = B + D (eq. 28), E = B + e1² D (eq. 48). B(0) = D(0) = π/4; as e1 → 0, B → 1 and
    D ≈ ln(4/e1) - 1. e1 = 0 gives (1, inf).
    """
    a, scalar = _as_e1(e1)
    B, D = _bd(a.reshape(-1))
    return _out(B.reshape(a.shape), scalar), _out(D.reshape(a.shape), scalar)


def _ke_paper(a: np.ndarray, a2_printed: bool = False) -> tuple[np.ndarray, np.ndarray]:
    with np.errstate(under="ignore"):
        m1 = a * a  # eq. (41)
    with np.errstate(divide="ignore"):
        ln_1_m1 = -2.0 * np.log(a)  # ln(1/m1), no underflow of m1 for tiny e1
    (ka0, ka1, ka2), (kb0, kb1, kb2) = AS_K_COEFFS
    (ea0, ea1, ea2), (_, eb1, eb2) = AS_E_COEFFS
    if a2_printed:
        ea2 = PRINTED_E_A2  # the paper's misprint in (39)
    with np.errstate(under="ignore", invalid="ignore"):
        K = (ka0 + ka1 * m1 + ka2 * m1 * m1) + (kb0 + kb1 * m1 + kb2 * m1 * m1) * ln_1_m1  # eq. (36)-(37)
        E = (ea0 + ea1 * m1 + ea2 * m1 * m1) + np.where(
            a == 0.0, 0.0, (eb1 * m1 + eb2 * m1 * m1) * ln_1_m1
        )  # eq. (38)-(39)
    return K, E


def elliptic_KE(e1, method: str = "exact", a2_printed: bool = False):
    """Complete elliptic integrals (K(e), E(e)) of the first and second kind, eqs. (28), (48).

    The argument is e1 = sqrt(1 - e²) (the complementary modulus, eq. 30); dimensionless.
    method="exact": K = B + D, E = B + e1² D (cancellation-free, ≈ 1e-16 relative).
    method="paper": the Abramowitz–Stegun polynomials (36)–(39) in m1 = e1², |ε| ≤ 3e-5 (K),
    4e-5 (E); ``a2_printed=True`` uses the paper's misprinted a2 = 0.10778112 in (39).
    """
    a, scalar = _as_e1(e1)
    if method == "exact":
        B, D = _bd(a.reshape(-1))
        B, D = B.reshape(a.shape), D.reshape(a.shape)
        K = B + D  # eq. (28): K = B + D
        with np.errstate(invalid="ignore", under="ignore"):
            E = np.where(a == 0.0, 1.0, B + a * a * D)  # eq. (48): E = B + (1 - m) D
    elif method == "paper":
        K, E = _ke_paper(a, a2_printed)
    else:
        raise ValueError(f"method must be 'exact' or 'paper', not {method!r}")
    return _out(K, scalar), _out(E, scalar)


# --- curvature ratio λ ↔ e1 ----------------------------------------------------------------


def lambda_squared(e1):
    """λ² = b²/a² = smaller/larger principal curvature, exact Hertz relation, eq. (27).

    (27) rewritten with Jahnke–Emde integrals: λ² = (1 - m) D/B = e1² D/B ∈ [0, 1];
    monotone increasing in e1, λ²(1) = 1. Dimensionless. (Underflows to 0 for e1 ≲ 1e-155;
    use :func:`lambda_from_e1` for λ itself.)
    """
    a, scalar = _as_e1(e1)
    B, D = _bd(a.reshape(-1))
    with np.errstate(invalid="ignore", under="ignore"):
        lam2 = np.where(a.reshape(-1) == 0.0, 0.0, a.reshape(-1) ** 2 * (D / B))  # eq. (27)
    return _out(lam2.reshape(a.shape), scalar)


def _lam_of(a: np.ndarray) -> np.ndarray:
    B, D = _bd(a)
    with np.errstate(invalid="ignore"):
        return np.where(a == 0.0, 0.0, a * np.sqrt(D / B))  # sqrt of eq. (27)


def lambda_from_e1(e1):
    """λ = e1 sqrt(D/B), the square root of (27), without underflow for tiny e1 (down to
    subnormal e1). Dimensionless, in [0, 1]."""
    a, scalar = _as_e1(e1)
    return _out(_lam_of(a.reshape(-1)).reshape(a.shape), scalar)


def lambda_squared_small_e1(e1):
    """The paper's small-e1 approximation of (27), eq. (32): λ² = e1² [ln(4/e1) - 1].

    Obtained from the expansion (31) of K; relative error ≈ e1² ln(4/e1)/2 against (27).
    """
    a, scalar = _as_e1(e1)
    with np.errstate(divide="ignore", invalid="ignore", under="ignore"):
        lam2 = np.where(a == 0.0, 0.0, a * a * (_LN4 - np.log(a) - 1.0))  # eq. (32)
    return _out(lam2, scalar)


def _dlog_lambda_dlog_e1(a: np.ndarray) -> np.ndarray:
    """d ln λ / d ln e1 from (27): 1 - (B² - m1 D²)/(2 m B D) ∈ (1/2, 1); → 3/4 as e1 → 1."""
    B, D = _bd(a)
    m = (1.0 - a) * (1.0 + a)
    m1 = a * a
    with np.errstate(divide="ignore", invalid="ignore"):
        g = 1.0 - (B * B - m1 * D * D) / (2.0 * m * B * D)
    return np.where(m < 1e-8, 0.75, g)


def _invert_exact(t: np.ndarray) -> np.ndarray:
    """Solve λ(e1) = t for e1, t ∈ [0, 1], monotone (27); safeguarded Newton in ln e1."""
    out = np.empty_like(t)
    out[t == 0.0] = 0.0
    out[t == 1.0] = 1.0
    idx = np.flatnonzero((t > 0.0) & (t < 1.0))
    if idx.size == 0:
        return out
    tt = t[idx]
    with np.errstate(under="ignore"):
        lo = np.maximum(tt**1.5 * math.exp(-2.0), _TINY)  # λ(lo) < t (D/B < e⁴/t there)
    hi = tt.copy()  # D ≥ B ⇒ e1 ≤ λ
    # start: Johnson-like λ^{4/3} near the circle, (32) inverted once for small λ
    with np.errstate(under="ignore"):
        y = np.where(
            tt > 0.2, tt ** (4.0 / 3.0), tt / np.sqrt(np.log(4.0 / tt) - 1.0 + 0.5 * np.log(np.log(4.0 / tt)))
        )
    y = np.clip(y, lo, hi)
    active = np.ones(tt.size, dtype=bool)
    for _ in range(200):
        ia = np.flatnonzero(active)
        if ia.size == 0:
            break
        ya = y[ia]
        r = np.log(_lam_of(ya) / tt[ia])  # residual in ln λ
        hi[ia] = np.where(r > 0, ya, hi[ia])
        lo[ia] = np.where(r < 0, ya, lo[ia])
        step = -r / _dlog_lambda_dlog_e1(ya)
        ynew = ya * np.exp(step)
        bad = ~((ynew > lo[ia]) & (ynew < hi[ia])) & (r != 0)
        ynew = np.where(bad, np.sqrt(lo[ia]) * np.sqrt(hi[ia]), ynew)  # geometric bisection
        y[ia] = np.where(r == 0, ya, ynew)
        done = (r == 0) | (~bad & (np.abs(step) < 1e-10)) | (hi[ia] <= lo[ia] * (1 + 4e-16))
        active[ia[done]] = False
    out[idx] = y
    return out


def _as_lambda(lam) -> tuple[np.ndarray, bool]:
    arr = np.asarray(lam, dtype=float)
    if np.any(~(arr >= 0.0)):
        raise ValueError("λ must be ≥ 0 (and not NaN)")
    return arr, arr.ndim == 0


def _paper_clipped(t: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore", invalid="ignore"):
        raw = P33_A * t / (1.0 - P33_C * t)  # eq. (33)
    return np.where(t >= PAPER_LAMBDA_CLIP, 1.0, np.minimum(raw, 1.0))


def e1_from_lambda(lam, method: str = "exact"):
    """e1 = B/A of the contact ellipse for the curvature ratio λ (λ² = κ_small/κ_large).

    λ > 1 (the ellipse turns) is replaced by 1/λ. method="exact": inversion of (27) to
    ≈1e-16 relative (monotone; λ = 1 → 1, λ → 0 → 0; works down to λ ≈ 1e-300).
    method="paper": the fit (33), e1 = 0.4777 λ/(1 - 1.3211 λ), clipped to e1 ≤ 1, and
    e1 = 1 (circle) for λ ≥ PAPER_LAMBDA_CLIP ≈ 0.5559 (which includes the pole 0.7569).
    """
    arr, scalar = _as_lambda(lam)
    with np.errstate(divide="ignore"):
        t = np.where(arr > 1.0, 1.0 / arr, arr).reshape(-1)
    if method == "exact":
        e = _invert_exact(t)
    elif method == "paper":
        e = _paper_clipped(t)
    else:
        raise ValueError(f"method must be 'exact' or 'paper', not {method!r}")
    return _out(e.reshape(arr.shape), scalar)


def e1_from_lambda_paper_raw(lam):
    """The paper's fit (33) exactly as printed, e1 = 0.4777 λ/(1 - 1.3211 λ), unclipped and
    without the λ → 1/λ turn (for demonstrating its range problems: e1 > 1 for
    λ > PAPER_LAMBDA_CLIP). Raises ValueError at/beyond the pole λ ≥ PAPER_LAMBDA_POLE."""
    arr, scalar = _as_lambda(lam)
    if np.any(P33_C * arr >= 1.0):
        raise ValueError(f"eq. (33) has a pole at λ = {PAPER_LAMBDA_POLE:.6g}; λ ≥ pole is invalid")
    return _out(P33_A * arr / (1.0 - P33_C * arr), scalar)  # eq. (33)


# --- Hertz factors -------------------------------------------------------------------------


def f1(e1, method: str = "exact"):
    """Area factor f1 = E/(K e1) of (46): A_i = f1 π ω/κ_m. Dimensionless, 1 at e1 = 1,
    ≈ 1/(e1 ln(4/e1)) as e1 → 0 (inf at e1 = 0). method: "exact" or "paper" (A&S K, E)."""
    a, scalar = _as_e1(e1)
    K, E = elliptic_KE(a, method)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        v = np.where(a == 0.0, np.inf, E / (K * a))  # eq. (46); inf only for e1 ≲ 1e-306
    return _out(v, scalar)


def f2(e1, method: str = "exact"):
    """Load factor f2 = π sqrt(E)/(2 K^{3/2} e1) of (47): W_i = f2 (4/3) E* κ_m^{-1/2} ω^{3/2}.
    Dimensionless, 1 at e1 = 1, inf at e1 = 0. method: "exact" or "paper"."""
    a, scalar = _as_e1(e1)
    K, E = elliptic_KE(a, method)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        v = np.where(a == 0.0, np.inf, math.pi * np.sqrt(E) / (2.0 * K * np.sqrt(K) * a))  # eq. (47)
    return _out(v, scalar)


def f3(e1):
    """Plastic-area factor of (58), eq. (59) rearranged without cancellation:
    f3 = E e²/(2 e1 (E - K(1 - e²))) = E/(2 e1 B). Dimensionless, 1 at e = 0, inf at e1 = 0."""
    a, scalar = _as_e1(e1)
    B, D = _bd(a.reshape(-1))
    B, D = B.reshape(a.shape), D.reshape(a.shape)
    with np.errstate(divide="ignore", invalid="ignore", under="ignore", over="ignore"):
        E = B + a * a * D  # eq. (48)
        v = np.where(a == 0.0, np.inf, E / (2.0 * a * B))  # eq. (59): E - (1-e²)K = e² B
    return _out(v, scalar)


def f4(e1):
    """Factor of (58), eq. (60) rearranged without cancellation:
    f4 = 2(E - (1 - e²)K)/(K e²) = 2B/K. Dimensionless, 1 at e = 0, → 0 as e1 → 0."""
    a, scalar = _as_e1(e1)
    B, D = _bd(a.reshape(-1))
    B, D = B.reshape(a.shape), D.reshape(a.shape)
    v = 2.0 * B / (B + D)  # eq. (60): E - (1-e²)K = e² B, K = B + D
    return _out(v, scalar)


class HertzFactors(NamedTuple):
    """Hertz data of one asperity for a curvature ratio λ (all dimensionless)."""

    e1: np.ndarray | float  #: B/A of the contact ellipse, eq. (30)
    f1: np.ndarray | float  #: area factor, eq. (46)
    f2: np.ndarray | float  #: load factor, eq. (47)
    f3: np.ndarray | float  #: plastic-area factor, eq. (59)
    f4: np.ndarray | float  #: eq. (60)
    K: np.ndarray | float  #: K(e), eq. (28) (or (36) for hertz="paper")
    E: np.ndarray | float  #: E(e), eq. (48) (or (38) for hertz="paper")


def hertz_factors(lam, hertz: str = "exact") -> HertzFactors:
    """e1, f1, f2, f3, f4, K, E for curvature ratio λ = sqrt(κ_small/κ_large) (λ > 1 → 1/λ).

    hertz="exact": e1 from the inversion of (27), exact K, E.
    hertz="paper": e1 from (33) clipped to ≤ 1 (circle for λ ≥ PAPER_LAMBDA_CLIP), K, E and
    hence f1, f2 from the polynomials (36)–(39); f3, f4 are the exact functions of that e1.
    """
    if hertz not in ("exact", "paper"):
        raise ValueError(f"hertz must be 'exact' or 'paper', not {hertz!r}")
    e = e1_from_lambda(lam, method=hertz)
    K, E = elliptic_KE(e, method=hertz)
    return HertzFactors(e, f1(e, hertz), f2(e, hertz), f3(e), f4(e), K, E)


def kinks(hertz: str = "exact") -> tuple[float, ...]:
    """λ ∈ (0, 1] at which the hertz factors (as functions of λ, with λ > 1 → 1/λ) are not
    smooth; integrators split the θ-integral there. exact: λ = 1 (the axis turn);
    paper: also the clip point of (33), PAPER_LAMBDA_CLIP ≈ 0.5559."""
    if hertz == "exact":
        return (1.0,)
    if hertz == "paper":
        return (PAPER_LAMBDA_CLIP, 1.0)
    raise ValueError(f"hertz must be 'exact' or 'paper', not {hertz!r}")


def fig4_curves(e, hertz: str = "exact"):
    """(f1, f2) of (46)–(47) as functions of the eccentricity e ∈ [0, 1) (the paper's Fig. 4).
    hertz="exact": exact K, E; hertz="paper": A&S polynomials (36)–(39)."""
    ea = np.asarray(e, dtype=float)
    if np.any((ea < 0.0) | (ea >= 1.0)):
        raise ValueError("e must lie in [0, 1)")
    if hertz not in ("exact", "paper"):
        raise ValueError(f"hertz must be 'exact' or 'paper', not {hertz!r}")
    e1 = np.sqrt((1.0 - ea) * (1.0 + ea))  # eq. (30)
    out1, out2 = f1(e1, hertz), f2(e1, hertz)
    if ea.ndim == 0:
        return float(out1), float(out2)
    return out1, out2
