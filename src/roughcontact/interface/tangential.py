"""Mindlin's (1949) normal-to-tangential stiffness ratio of an elliptical contact (section 8).

Equation numbers are those of Buczkowski & Kleiber (2009); corrections are in docs/errata.md.

The paper's (96) (with N from (97)) gives k_N/k_T of two bodies with the same elastic constants
for a Hertzian contact ellipse with semi-axes A (along x) and B (along y), the tangential force
(and k_T) along semi-axis B: k_T = k_Ty for B < A (force along the minor axis), k_T = k_Tx of the
turned ellipse for B > A (force along the major axis). The printed (96) is garbled; the form
used here is rebuilt from Mindlin (1949) / Johnson (1985, §7.2) as follows.

Derivation (one body; the second, with the same ν and G, doubles both compliances and leaves
the ratio unchanged). Let a ≥ b be the major/minor semi-axes, e² = 1 - b²/a².

* Tangential: the no-slip traction q = Q/(2πab) (1 - x²/a² - y²/b²)^(-1/2) (Mindlin) in Cerruti's
  surface displacement u = 1/(2πG) ∫∫ q [(1-ν)/s + ν (Δ·ê)²/s³] dA (ê the force direction)
  gives a uniform displacement; with ∫∫ q/s dA = Q K(e)/a and ∫∫ q (Δ·ê)²/s³ dA = Q X/a,

      δ_T = Q/(2π a G) [(1-ν) K(e) + ν X],  X = B(e) (force along the minor axis),
                                            X = D(e) (force along the major axis),

  B(e) = (E - (1-e²)K)/e², D(e) = (K - E)/e² the Jahnke–Emde integrals (B + D = K).
* Normal: the incremental Hertz stiffness equals the flat elliptical punch stiffness,
  δ_N = (1-ν) P K(e)/(2π a G).

Hence (the corrected (96); N(e)/e = 4π(D - B) from (97))

    k_N/k_T = 1 + ν/(1-ν) · B(e)/K(e),    e²  = 1 - B²/A²,  B < A  (k_T = k_Ty),      (96a)
    k_N/k_T = 1 + ν/(1-ν) · D(k1)/K(k1),  k1² = 1 - A²/B²,  B > A  (k_T = k_Tx),      (96b)

equivalently (2-ν)/(2(1-ν)) ∓ ν (D - B)/(2(1-ν)K) = π(2-ν)/(4(1-ν)) · (1/K) ·
[2K/π ∓ ν/(2π²(2-ν)) · N/e]: the bracket multiplies the whole prefactor, and the N term has
the sign "-" for B < A and "+" for B > A (the paper prints the second term outside the
prefactor and with "-" in both branches).

Properties: both branches give (2-ν)/(2(1-ν)) at B = A (B = D = π/4, K = π/2) and join
continuously there; r = B²/A² and 1/r are related by k(r) + k(1/r) = 2 + ν/(1-ν).
Limits (paper's (i)–(iv)): ν = 0 → 1; B/A → 0 → 1; B/A → ∞ → 1/(1-ν); B = A → (2-ν)/(2(1-ν)).
(ii) and (iii) are approached only logarithmically: with L = ln(4/e1), e1 = min(B/A, A/B),
B/K = 1/L · (1 + O(e1² L)), so

    k_N/k_T = 1 + ν/((1-ν) L)            as B/A → 0,
    k_N/k_T = 1/(1-ν) - ν/((1-ν) L)      as B/A → ∞,

e.g. 1.000961 at B²/A² = 1e-300, ν = 1/4.

Table 3 reading: the first column "10.E-03", …, "10.E+03" means B²/A² = 10⁻³, …, 10³ (one
decade per row, "10.E-00" the circle). With this reading (96a)/(96b) reproduce all 21 printed
cells to within one unit of the last printed digit (max relative deviation 5.0e-6;
tests/interface/test_tangential.py; the printed digits in config/paper_values.yaml). Three cells are truncated rather than
rounded (10.E-01: 1.12167 for 1.1216756, 1.36502 for 1.3650268; 10.E+02, ν = 1/4: 1.24413 for
1.2441357); the other 18 are correctly rounded. The readings B²/A² = 10 × 10^k and
B/A = 10^k miss by > 1e-2.

Numerics: the elliptic integrals come from :func:`roughcontact.asperity.ellipse.elliptic_BD` of the
complementary modulus e1 = B/A = sqrt(r) for r ≤ 1 and e1 = A/B = 1/sqrt(r) for r > 1, so that
K = B + D and the ratios B/K, D/K are sums of positive terms (no cancellation) for
r from the smallest subnormal to the largest float.
"""

from __future__ import annotations

import numpy as np

from ..asperity.ellipse import e1_from_lambda, elliptic_BD
from ..statistics.surface import SpectralMoments
from ..validation import instance
from ..limits import describe

__all__ = ["NU_MIN", "NU_MAX", "kn_over_kt", "representative_aspect"]

#: Accepted Poisson's ratio: the physical range of an isotropic elastic half-space,
#: -1 < ν ≤ 1/2 (positive shear and bulk moduli; ν = 1/2 the incompressible limit, which
#: Table 3 tabulates and for which Cerruti's and Boussinesq's solutions still hold).
#: The algebraic formula is finite for every ν < 1, but for ν > 1/2 it describes no material.
NU_MIN = -1.0  # exclusive
NU_MAX = 0.5  # inclusive


def _validate(b2_over_a2, nu) -> tuple[np.ndarray, np.ndarray]:
    try:
        r = np.asarray(b2_over_a2, dtype=float)
        v = np.asarray(nu, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("b2_over_a2 and nu must be real numbers") from None
    if not np.all(np.isfinite(r) & (r > 0.0)):
        bad = r[~(np.isfinite(r) & (r > 0.0))].reshape(-1)[0]
        raise ValueError(f"b2_over_a2 = B^2/A^2 must be finite and > 0, got {describe(float(bad))}")
    ok = (v > NU_MIN) & (v <= NU_MAX)
    if not np.all(ok):
        bad = v[~ok].reshape(-1)[0]
        raise ValueError(
            f"nu must satisfy -1 < nu <= 0.5 (physical Poisson's ratio), got {describe(float(bad))}"
        )
    try:
        r, v = np.broadcast_arrays(r, v)
    except ValueError:
        raise ValueError(
            f"b2_over_a2 (shape {r.shape}) and nu (shape {v.shape}) do not broadcast"
        ) from None
    return r, v


def _b_over_k(r: np.ndarray) -> np.ndarray:
    """X/K of (96a)/(96b) for r = B²/A² (validated, > 0): B(e)/K(e) for r ≤ 1 (e1 = B/A),
    D(k1)/K(k1) for r > 1 (e1 = A/B); K = B + D (eq. 28), no cancellation."""
    small = r <= 1.0
    e1 = np.where(small, np.sqrt(np.where(small, r, 1.0)), 1.0 / np.sqrt(np.where(small, 1.0, r)))
    B, D = elliptic_BD(e1)  # Jahnke–Emde B, D of complementary modulus e1 (ellipse.py)
    return np.where(small, B, D) / (B + D)


def kn_over_kt(b2_over_a2, nu):
    """Mindlin's ratio k_N/k_T of the normal to the initial tangential contact stiffness of two
    bodies with the same elastic constants, corrected eq. (96) with (97).

    Parameters
    ----------
    b2_over_a2 : array_like
        B²/A², the squared ratio of the contact-ellipse semi-axis B along the tangential force
        to the other semi-axis A; finite, > 0 (B < A: force along the minor axis, k_T = k_Ty;
        B > A: along the major axis, k_T = k_Tx). Dimensionless.
    nu : array_like
        Poisson's ratio, -1 < ν ≤ 1/2 (the physical range; see NU_MIN, NU_MAX).
        Broadcast against ``b2_over_a2``.

    Returns
    -------
    float or ndarray
        k_N/k_T = 1 + ν/(1-ν) · B(e)/K(e) (B < A, e² = 1 - B²/A²), or
        1 + ν/(1-ν) · D(k1)/K(k1) (B > A, k1² = 1 - A²/B²). Dimensionless; lies between 1 and
        1/(1-ν); (2-ν)/(2(1-ν)) at B = A. A float for scalar inputs.

    Table 3 of the paper is this function at B²/A² = 10⁻³ … 10³ (its "10.E-03" … "10.E+03")
    and ν = 0, 1/4, 1/2, to one unit of the last printed digit.

    Raises
    ------
    ValueError
        If b2_over_a2 is not finite and positive, ν is outside (-1, 1/2], or the shapes do not
        broadcast.
    """
    r, v = _validate(b2_over_a2, nu)
    scalar = r.ndim == 0
    ratio = _b_over_k(r.reshape(-1)).reshape(r.shape)
    out = 1.0 + v / (1.0 - v) * ratio  # eq. (96), corrected (module docstring)
    return float(out) if scalar else out



def representative_aspect(surface: SpectralMoments) -> float:
    """a_y²/a_x² of the Hertz contact ellipse of a summit whose principal curvatures are the
    surface's rms curvatures √m40 (along x) and √m04 (along y): curvature ratio
    λ² = √(m40/m04) (λ² = ω4√m40/(ω6√m04) of section 3 at ω4 = ω6), e1 = B/A from the exact
    inversion of (27), and the semi-axis along the smaller curvature is the larger one.

    A reading, not the paper's: section 9 takes k_T from (96) without saying for which ellipse;
    this one summit stands for the surface. Feed it to
    :func:`roughcontact.interface.mindlin_kT_over_kN` (with ν) for (k_Tx/k_N, k_Ty/k_N)."""
    instance("surface", surface, SpectralMoments)
    lam2 = (surface.m40 / surface.m04) ** 0.5
    e1 = float(e1_from_lambda(min(lam2, 1.0 / lam2) ** 0.5))
    # the x semi-axis is the major one when x is the direction of smaller curvature (m40 < m04)
    return e1 * e1 if surface.m40 <= surface.m04 else 1.0 / (e1 * e1)
