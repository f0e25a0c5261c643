"""Chebyshev tables of the Gaussian moments J_ν(a), ν = 0, 1/2, 1, 3/2 (built once with mpmath).

    J_ν(a) = ∫₀^∞ t^ν φ(t − a) dt = E[(Z + a)₊^ν] = Γ(ν+1)/√(2π) e^{−a²/4} D_{−ν−1}(−a),

Z ~ N(0, 1), D the parabolic-cylinder function (DLMF 12.5.1 with 12.2.2 as in reference.py);
J_0 = Φ, J_1(a) = aΦ(a) + φ(a), and Greenwood–Williamson's F_ν(d) = J_ν(−d). These are the
inner t-integrals of every summit integral (docs/derivation.md), so the production kernels
(kernels.py) evaluate them in closed form from the tables here instead of integrating in t.

Representation (all four ν share the pieces; the numba evaluator is kernels._moments):

* a ≤ 0, x = −a ∈ [k, k+1), k = 0 … 11: G_ν(x) = J_ν(−x)/φ(x) = ∫₀^∞ t^ν e^{−xt − t²/2} dt
  (smooth, from G_ν(0) to ≈ Γ(ν+1)/x^{ν+1}); J_ν = G_ν(x) φ(x), so the Gaussian factor is
  an exact exp and no digits are lost to cancellation (J_1 = aΦ + φ cancels for a < 0).
* 0 ≤ a < 12, a ∈ [k, k+1): J_ν(a) itself (entire, positive).
* x ≥ 12: x^{ν+1} G_ν(x) as a function of y = 2(12/x)² − 1 (its asymptotic series
  Γ(ν+1) Σ_k (−1)^k (ν+1)_{2k} / (k! 2^k x^{2k}) is a series in 1/x²).
* a ≥ 12: J_ν(a)/a^ν as a function of y = 2(12/a)² − 1 (Σ_k binom(ν, 2k) (2k−1)!! a^{−2k},
  exponentially small corrections ≤ φ(12) ≈ 1e-32).

Each piece is a polynomial of degree 16 in y ∈ [−1, 1] (the piece mapped linearly; in the
tails y above): the Chebyshev series from the values at 40 Chebyshev–Gauss nodes at 40
digits, truncated after 17 terms (the largest dropped coefficient is 3.5e-18 of the piece's
largest value, recorded in the data file), then converted to the monomial basis at 40 digits
and rounded to double. The monomial form is evaluated by Estrin's scheme (2× faster than
Clenshaw's recurrence, whose steps depend on each other); it amplifies rounding by at most
Σ|m_k|/|f| ≤ 3.5. Below a = −38.6 every J_ν < φ(a) underflows double precision and the
evaluator returns exactly 0.

The coefficients are generated data (`_normal_moments_data.py`); regenerate with

    .venv/bin/python -m roughcontact.integrals.normal_moments

tests/integrals/test_normal_moments.py checks the evaluator against mpmath over the whole a-range and
(marked mpmath) that regenerating reproduces the stored table.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

__all__ = ["NU", "WIDTH", "X_SPLIT", "N_COEF", "N_SIDE", "table", "build_table", "mp_moment"]

#: the orders ν of the table columns
NU = (0.0, 0.5, 1.0, 1.5)
#: width of the Chebyshev pieces on |a| < X_SPLIT
WIDTH = 1.0
#: beyond |a| = X_SPLIT the tails in y = 2(X_SPLIT/|a|)² − 1 take over
X_SPLIT = 12.0
#: Chebyshev coefficients per piece (degree 16)
N_COEF = 17
#: pieces per side of a = 0
N_SIDE = round(X_SPLIT / WIDTH)
#: rows: N_SIDE pieces of G_ν(x) (a < 0), N_SIDE of J_ν(a) (a ≥ 0), the negative, the positive tail
N_PIECES = 2 * N_SIDE + 2
_N_SAMPLE = 40  # Chebyshev–Gauss nodes per piece when building

_DATA = Path(__file__).with_name("_normal_moments_data.py")


def mp_moment(nu, a):
    """J_ν(a) at the current mpmath precision (parabolic-cylinder form, DLMF 12.5.1)."""
    import mpmath as mp

    nu, a = mp.mpf(nu), mp.mpf(a)
    return mp.gamma(nu + 1) / mp.sqrt(2 * mp.pi) * mp.exp(-a * a / 4) * mp.pcfd(-nu - 1, -a)


def _mp_scaled(nu, x):
    """G_ν(x) = J_ν(−x)/φ(x) = Γ(ν+1) e^{x²/4} D_{−ν−1}(x) (no underflow for large x)."""
    import mpmath as mp

    nu, x = mp.mpf(nu), mp.mpf(x)
    return mp.gamma(nu + 1) * mp.exp(x * x / 4) * mp.pcfd(-nu - 1, x)


def _piece_function(row: int, nu):
    """The smooth function tabulated in ``row``, as a function of y ∈ [−1, 1]."""
    import mpmath as mp

    X, w = mp.mpf(X_SPLIT), mp.mpf(WIDTH)
    if row < N_SIDE:  # x ∈ [row w, (row + 1) w]
        return lambda y: _mp_scaled(nu, (row + (y + 1) / 2) * w)
    if row < 2 * N_SIDE:
        k = row - N_SIDE
        return lambda y: mp_moment(nu, (k + (y + 1) / 2) * w)
    if row == 2 * N_SIDE:  # x = X/√((y + 1)/2)
        def neg_tail(y):
            x = X / mp.sqrt((y + 1) / 2)
            return x ** (mp.mpf(nu) + 1) * _mp_scaled(nu, x)

        return neg_tail

    def pos_tail(y):
        a = X / mp.sqrt((y + 1) / 2)
        return mp_moment(nu, a) / a ** mp.mpf(nu)

    return pos_tail


def _chebyshev_to_monomial(coef):
    """Σ c_k T_k(y) → Σ m_k y^k (mpmath, exact up to the working precision)."""
    import mpmath as mp

    n = len(coef)
    out = [mp.mpf(0)] * n
    t_prev, t_cur = [mp.mpf(1)], [mp.mpf(0), mp.mpf(1)]  # T_0, T_1 as monomial lists
    for k, c in enumerate(coef):
        t = t_prev if k == 0 else t_cur
        for i, v in enumerate(t):
            out[i] += c * v
        if k >= 1:  # T_{k+1} = 2y T_k − T_{k−1}
            nxt = [mp.mpf(0)] + [2 * v for v in t_cur]
            for i, v in enumerate(t_prev):
                nxt[i] -= v
            t_prev, t_cur = t_cur, nxt
    return out


def build_table(dps: int = 40) -> tuple[np.ndarray, float]:
    """Monomial coefficients in y, shape (N_PIECES, 4, N_COEF), from mpmath at ``dps`` digits
    (the truncated Chebyshev interpolant of each piece, converted exactly).

    Returns the table and the largest dropped Chebyshev coefficient (index ≥ N_COEF of the
    _N_SAMPLE-term series) relative to the largest |value| of its piece."""
    import mpmath as mp

    out = np.empty((N_PIECES, len(NU), N_COEF))
    worst = 0.0
    with mp.workdps(dps):
        n = _N_SAMPLE
        ys = [mp.cos(mp.pi * (k + mp.mpf(1) / 2) / n) for k in range(n)]
        cosines = [[mp.cos(mp.pi * j * (k + mp.mpf(1) / 2) / n) for k in range(n)] for j in range(n)]
        for row in range(N_PIECES):
            for col, nu in enumerate(NU):
                f = _piece_function(row, mp.mpf(nu))
                vals = [f(y) for y in ys]
                coef = [mp.fsum(v * c for v, c in zip(vals, cosines[j])) * 2 / n for j in range(n)]
                coef[0] /= 2
                scale = max(abs(v) for v in vals)
                worst = max(worst, float(max(abs(c) for c in coef[N_COEF:]) / scale))
                out[row, col] = [float(m) for m in _chebyshev_to_monomial(coef[:N_COEF])]
    return out, worst


def _write_data(path: Path = _DATA, dps: int = 40) -> float:
    tab, worst = build_table(dps)
    rows = ",\n".join(
        "    [" + ", ".join("[" + ", ".join(repr(float(c)) for c in tab[r, q]) + "]" for q in range(len(NU))) + "]"
        for r in range(N_PIECES)
    )
    text = (
        '"""Generated by `python -m roughcontact.integrals.normal_moments` (mpmath, dps=%d): monomial\n'
        "coefficients (in y) of the J_ν tables, shape (%d, %d, %d); see normal_moments.py. Do not\n"
        "edit. Largest dropped Chebyshev coefficient relative to its piece: %.1e.\"\"\"\n\n"
        "COEFFICIENTS = [\n%s,\n]\n" % (dps, N_PIECES, len(NU), N_COEF, worst, rows)
    )
    path.write_text(text)
    return worst


def table() -> np.ndarray:
    """The stored monomial coefficients, shape (N_PIECES, 4, N_COEF), C-contiguous float64."""
    from ._normal_moments_data import COEFFICIENTS

    tab = np.ascontiguousarray(np.array(COEFFICIENTS, dtype=float))
    if tab.shape != (N_PIECES, len(NU), N_COEF):
        raise RuntimeError(f"_normal_moments_data.py has shape {tab.shape}; regenerate it")
    return tab


#: −ln of the smallest positive double is 744.4; J_ν(a) < φ(a) vanishes below this a
A_UNDERFLOW = -math.sqrt(2.0 * 745.2)  # ≈ −38.6


if __name__ == "__main__":
    print(f"wrote {_DATA}; largest dropped coefficient {_write_data():.1e}")
