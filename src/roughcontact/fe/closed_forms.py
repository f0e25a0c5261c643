"""Closed-form solutions the FE engine is checked against (tests/fe/test_checks.py).

Beam on a Winkler foundation (Hetényi 1946, "Beams on Elastic Foundation", finite beams)
-----------------------------------------------------------------------------------------
An Euler–Bernoulli beam of length L and bending stiffness EI [N·mm²] rests on a Winkler
foundation of modulus k_b [N/mm per mm of beam length = N/mm²]: the foundation pushes back with
k_b·w per unit length, w the deflection (positive in the direction of the load). A point load P
[N] at mid-length, both ends free:

    EI w'''' + k_b w = P δ(x),     w''(±L/2) = w'''(±L/2) = 0,

x measured from the load. With λ = (k_b/(4EI))^{1/4} [1/mm] and ξ = λx', x' = L/2 − |x| the
distance from the nearer free end, the homogeneous solutions are cosh ξ cos ξ, cosh ξ sin ξ,
sinh ξ cos ξ, sinh ξ sin ξ; their second and third derivatives at ξ = 0 are (0, 0), (0, 2),
(0, −2), (2, 0), so the free-end conditions leave

    w = A cosh ξ cos ξ + B (cosh ξ sin ξ + sinh ξ cos ξ).

Symmetry (w' = 0 at the load) and the shear jump EI[w''']₀ = P (w'''(0⁺) = P/(2EI)) fix A and B;
with c = λL/2 this is Hetényi's formula for a central load:

    w(x) = P λ / (k_b (sinh λL + sin λL)) · [ 2 cosh ξ cos ξ · cosh c cos c
           + (cosh ξ sin ξ + sinh ξ cos ξ) · (cosh c sin c − sinh c cos c) ].

(The general formula for a load at distances a, b from the ends reduces to this
for a = b = L/2: its common factor (sinh λL − sin λL) cancels against
sinh²λL − sin²λL.) Limits: λL → 0 gives the rigid beam w = P/(k_b L); λL → ∞ the infinite beam
w = (Pλ/(2k_b)) e^{−λ|x|}(cos λ|x| + sin λ|x|). tests/fe/test_checks.py verifies the formula
against an independent numerical solution of the boundary-value problem (scipy's solve_bvp)
and both limits.
"""

from __future__ import annotations

import numpy as np

from ..validation import positive

__all__ = ["winkler_lambda", "hetenyi_finite_beam", "hetenyi_infinite_beam"]


def winkler_lambda(EI: float, k_b: float) -> float:
    """λ = (k_b/(4 EI))^{1/4} [1/length] of a beam (EI [force·length²]) on a Winkler foundation
    of modulus k_b [force/length²]."""
    return (positive("k_b", k_b) / (4.0 * positive("EI", EI))) ** 0.25


def hetenyi_finite_beam(P: float, L: float, EI: float, k_b: float, x):
    """Deflection w(x) [length] of a free–free Euler–Bernoulli beam of length L on a Winkler
    foundation k_b under a point load P at mid-length (module docstring); x measured from the
    load, |x| ≤ L/2 (vectorised). Positive w is in the direction of P. Units: any consistent
    set, e.g. N, mm: P [N], L [mm], EI [N·mm²], k_b [N/mm²] → w [mm]."""
    L = positive("L", L)
    lam = winkler_lambda(EI, k_b)
    x = np.asarray(x, dtype=float)
    if np.any(np.abs(x) > L / 2.0 * (1.0 + 1e-12)):
        raise ValueError("x must lie on the beam, |x| <= L/2")
    xe = lam * (L / 2.0 - np.abs(x))  # ξ = λ × distance from the nearer free end
    c = lam * L / 2.0
    lL = lam * L
    A = np.cosh(c) * np.cos(c)
    Bc = np.cosh(c) * np.sin(c) - np.sinh(c) * np.cos(c)
    bracket = 2.0 * np.cosh(xe) * np.cos(xe) * A + (np.cosh(xe) * np.sin(xe) + np.sinh(xe) * np.cos(xe)) * Bc
    w = P * lam / (k_b * (np.sinh(lL) + np.sin(lL))) * bracket
    return float(w) if w.ndim == 0 else w


def hetenyi_infinite_beam(P: float, EI: float, k_b: float, x):
    """Deflection of an infinite beam on a Winkler foundation under a point load P at x = 0:
    w = (Pλ/(2k_b)) e^{−λ|x|}(cos λ|x| + sin λ|x|) (Hetényi 1946)."""
    lam = winkler_lambda(EI, k_b)
    s = lam * np.abs(np.asarray(x, dtype=float))
    w = P * lam / (2.0 * k_b) * np.exp(-s) * (np.cos(s) + np.sin(s))
    return float(w) if w.ndim == 0 else w
