"""Zero-thickness interface friction law of section 8: orthotropic (8.1) and isotropic (8.2)
slip-hardening friction, as an incremental update for every integration point of an FE model.

Equation numbers are those of Buczkowski & Kleiber (2009). Where the printed paper is wrong or
ambiguous the corrected form is used and marked "erratum"/"reading" below (tests in
tests/test_friction.py prove each one).

Models
------
Orthotropic hardening (8.1), :class:`OrthotropicHardening`:

* limit surface (91): f = [(t_x/μ_x)² + (t_y/μ_y)²]^{1/2} - p_N ≤ 0, an ellipse in (t_x, t_y)
  with semi-axes μ_x p_N, μ_y p_N;
* axial slip hardening (89)-(90): μ_i = μ_mi [1 - (1 - μ_oi) exp(-n_i κ_i)], i = x, y, with
  κ_i = ∫|du_i^p| the accumulated axial plastic slip (reading, see below); μ_oi is the ratio
  initial/macroscopic coefficient (μ_i = μ_mi μ_oi at κ_i = 0); μ_oi < 1 hardens, = 1 is
  constant friction, > 1 softens;
* non-associated slip potential (98)/(101): g = [(t_x/ν_x)² + (t_y/ν_y)²]^{1/2} - C with
  ν_y/ν_x = (μ_y/μ_x)^k evaluated with the current μ's (k = 1: associated, g = f; k = 0: circle,
  slip coaxial with t_T); Δu_T^p = γ ∂g/∂t (99); no dilatancy, Δu_N^p = 0. Only the ratio
  ν_y/ν_x matters (ν_x, ν_y scale γ only); the code uses ν_x = μ_x^{(1+k)/2} μ_y^{(1-k)/2},
  ν_y = μ_y^{(1+k)/2} μ_x^{(1-k)/2}.

Isotropic hardening (8.2), :class:`IsotropicHardening`: f = |t_T| - μ_F p_N (120),
μ_F = μ_m [1 - (1 - μ_o) exp(-n κ)] (119) with κ = ∫|du_T^p| the accumulated slip length,
circular potential g = |t_T| - C (121): Δu_T^p = γ t_T/|t_T|. The paper's "β" (initial
coefficient ratio) is called ``mu_o`` here (the paper also uses β for the traction angle).

Elastic part (93)-(94): Δt = diag(k_Tx, k_Ty, k_N) Δu^e, k's per unit area: constant inputs or
from the tabulated normal law (next section).

Normal contact, sign convention and reference state (the one place: :func:`normal_law`)
-------------------------------------------------------------------------------------
u_N is the normal *closure* (approach, penetration) of the interface: positive closes it.
The normal traction stored and returned is the contact *pressure* p_N = t_N ≥ 0, positive in
compression (the paper's t_N in (91), (117), (120)). p_N and k_N = dp_N/du_N are taken at the
end of the step, u_N = u_N,n + Δu_N (the total form of (117)), from one of two normal laws:

* constant stiffness (``k_N`` a number): p_N = k_N · max(u_N, 0); u_N = 0 is first touch;
  k_Tx, k_Ty are given constants.
* tabulated statistical law (``k_N`` a :class:`roughcontact.interface.InterfaceLaw`):
  p_N = W(h)/A0 and k_N = K/A0 = -d(W/A0)/dh of the elastic (53), (55)/(95) or elasto-plastic
  (82) model, with u_N = h_ref - h measured from the *reference state* h_ref, the separation
  at which the interface carries the initial pressure p0 (the paper applies an initial load
  first, 9.1): u_N = 0 ↔ p_N = p0 > 0, u_N < 0 unloads towards the light end, open (p_N = 0)
  for u_N ≤ u_open (the table's light-end tail, docs/interface.md); a closure beyond the
  table's heavy end raises ValueError. k_Tx = a_x k_N(u_N), k_Ty = a_y k_N(u_N) with the law's
  factors a = k_T/k_N, also at the end of the step: the trial traction is
  t^tr = t_n + K_T(u_N) Δu_T (incremental (93)) and the consistent tangent carries
  ∂K_T/∂u_N = a d²p_N/du_N² besides ∂p_N/∂u_N = k_N in the friction limit.

For p_N = 0 the contact is open: p_N = 0, t_T = 0, D = 0, plastic slips and hardening frozen
(tangential motion of separated faces is neither elastic nor frictional slip). An engine that
uses the gap g = -u_N (positive open) and a tension-positive normal stress σ_N = -p_N passes
Δu_N = -Δg and uses σ_N = -state[..., T_N] and S·D·S with S = diag(1, 1, -1).

Python interface
----------------
``update(model, state, du, k_N, k_Tx, k_Ty)`` or ``update(model, state, du, law)``
-> :class:`FrictionUpdate` ``(state, D, status)``

* ``state``: float array (..., NSTATE = 9), one row per integration point (or shape (9,)),
  columns (named index constants):

  ====  ============  =====================================================================
  0     ``T_X``       tangential traction t_x                                 [stress]
  1     ``T_Y``       tangential traction t_y                                 [stress]
  2     ``T_N``       normal pressure p_N ≥ 0 (output; recomputed from u_N)   [stress]
  3     ``U_N``       total normal closure u_N (> 0: in contact)              [length]
  4,5   ``UP_X/Y``    total plastic slips u_x^p, u_y^p (signed)               [length]
  6     ``KAPPA_X``   orthotropic: κ_x = ∫|du_x^p|; isotropic: κ = ∫|du_T^p|  [length]
  7     ``KAPPA_Y``   orthotropic: κ_y = ∫|du_y^p|; isotropic: unused (carried) [length]
  8     ``DISSIPATION`` accumulated frictional work ∫ t_T · du_T^p ≥ 0     [stress·length]
  ====  ============  =====================================================================

  :func:`initial_state` builds a virgin state (optionally pre-compressed).
* ``du``: (..., 3) increment of the relative displacement (Δu_Tx, Δu_Ty, Δu_N) [length].
* ``k_N, k_Tx, k_Ty``: stiffnesses per unit area [stress/length], scalars or arrays
  broadcastable to the point shape, finite and > 0; or ``law`` (in place of ``k_N``, without
  k_Tx, k_Ty): an :class:`roughcontact.interface.InterfaceLaw` (tabulated p_N(u_N), k_N(u_N)
  and k_T = a k_N).
* returns the new state (same shape; the tractions are ``state[..., :3]``), the consistent
  (algorithmic) tangent ``D`` (..., 3, 3) with D_ij = ∂(t_x, t_y, p_N)_i/∂(Δu_Tx, Δu_Ty, Δu_N)_j,
  and ``status`` (...,) int8: STICK = 0, SLIP = 1, OPEN = 2.

Units: any consistent set; e.g. stresses in N/mm², lengths in µm, stiffnesses in
N/(mm²·µm) (the project's K/A0); n_x, n_y, n in 1/[length] (275 /mm = 0.275 /µm).

Algorithm
---------
Elastic predictor t^tr = t_n + K_T Δu_T; if f(t^tr, κ_n, p_N,n+1) ≤ 0: stick, D = D^e (94)
(plus ∂K_T/∂u_N Δu_T in the u_N column with a tabulated law).
Otherwise backward Euler (implicit) return mapping: t = t^tr - K_T Δu^p with Δu^p, κ and the
potential ratio all evaluated at the end of the step, so that f(t, κ, p) = 0 holds to machine
precision for any increment size. Writing Δu_i^p = λ w_i t_i (w_x = ρ, w_y = 1/ρ,
ρ = ν_y/ν_x = e^r) gives t_i = t_i^tr/(1 + k_Ti λ w_i) and κ_i = κ_i,n + λ w_i|t_i|, so the
orthotropic update reduces to two scalar equations in (λ, r):
F = f(t, κ, p) = 0 and Φ = r - k ln(μ_y/μ_x) = 0; the isotropic one (w = 1) to one equation in λ.
Both are solved by Newton iterations safeguarded by bisection on proven brackets (the inner
r-equation is bracketed by the range of μ over the admissible κ box, the outer λ-equation by
f(λ = 0) > 0 and f → -p as λ → ∞), stopping when the Newton step is below ``tol`` · λ.
The consistent tangent is the exact linearisation of this algorithm (implicit function theorem
on (F, Φ)). For a vanishing slip increment it equals the continuum tangent (105)/(107)/(123)
(:func:`continuum_tangent`); for finite steps it differs by the curvature terms
(γ ∂²g/∂t² and the evolution of ρ) of the backward-Euler step.

At t_i^tr = 0 (a slip component changing sign) κ_i = κ_i,n + |Δu_i^p| has a kink, felt
through ν_y/ν_x when k ≠ 0: D is then the mean of the two one-sided derivatives.

The batch kernel is numba (``njit(cache=True)``, plain loops, no fastmath); the pure
Python/NumPy/SciPy twin :func:`reference_update` solves the primitive system
(t_x, t_y, γ, κ...) with complex-step Jacobians for testing.

Errata and readings (section 8)
-------------------------------
* (89)-(90), (119): u^p is read as the *accumulated* slip κ (monotone, ≥ 0); with the signed
  plastic displacement μ would soften without bound for negative slip.
* (110): as printed (d_x, d_y signed) it is the hardening modulus only for t_x, t_y ≥ 0; with
  κ accumulated it is H = -Σ_i t_i² μ_i' |d_i| / (μ_i³ S) (|d_i| instead of d_i).
* (126)/(131): the sign is wrong (H = +t_N ∂μ_F/∂u would soften the tangent for a hardening μ);
  with (125) and ∂f/∂μ_F = -t_N, H = -p_N μ_F' for any k_Tx, k_Ty (the k-dependent bracket of
  (126) does not follow from (125)); k_Tx, k_Ty enter only through A (124).
* (115)/(116): μ_α with α the *slip* angle gives the traction magnitude on the limit ellipse only
  for the associated rule (k = 1, α the normal angle); in general |t_T| = p_N μ_β,
  μ_β = (cos²β/μ_x² + sin²β/μ_y²)^{-1/2} (:func:`directional_coefficient_beta`).
* Fig. 18/19 presets (:func:`fig18_preset`): ν_x = ν_y = 0.125 fixes a circular potential
  (k = 0 here); k_N is not given numerically (from (95)); n = 275 1/mm from the 9.2 text;
  k_T/k_N = 0.7 is prescribed there although (96)/Table 3 give 0.79-0.94 for ν = 0.25.
  With equal axial parameters the per-axis hardening (89)-(90) still makes μ_x ≠ μ_y once
  κ_x ≠ κ_y (induced anisotropy).
* (128)/(130): "α ≠ β" in the text contradicts (121)/(130); with a circular potential the slip is
  always coaxial with t_T (α = β), whatever k_Tx/k_Ty.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numba
import numpy as np

from .interface import InterfaceLaw, closure_law, reference_closure_law

__all__ = [
    "NSTATE", "T_X", "T_Y", "T_N", "U_N", "UP_X", "UP_Y", "KAPPA_X", "KAPPA_Y", "KAPPA",
    "DISSIPATION", "STICK", "SLIP", "OPEN",
    "OrthotropicHardening", "IsotropicHardening", "FrictionUpdate",
    "normal_law", "initial_state", "update", "reference_update",
    "limit_function", "hardening_modulus", "continuum_tangent",
    "slip_angle", "traction_angle", "directional_coefficient_115",
    "directional_coefficient_beta", "FIG18_CASES", "fig18_preset",
]

# ---------------------------------------------------------------------------------------------
# state layout
# ---------------------------------------------------------------------------------------------
NSTATE = 9
T_X, T_Y, T_N, U_N, UP_X, UP_Y, KAPPA_X, KAPPA_Y, DISSIPATION = range(NSTATE)
KAPPA = KAPPA_X  # isotropic model: accumulated slip length

STICK, SLIP, OPEN = 0, 1, 2
_FAILED = -1
_BEYOND = -2  # closure beyond the heavy end of a tabulated normal law

_MAXIT = 200


# ---------------------------------------------------------------------------------------------
# models
# ---------------------------------------------------------------------------------------------
def _check_positive(name, value, allow_zero=False):
    v = float(value)
    if not math.isfinite(v) or v < 0.0 or (v == 0.0 and not allow_zero):
        raise ValueError(f"{name} must be finite and {'>= 0' if allow_zero else '> 0'}, got {value!r}")
    return v


@dataclass(frozen=True)
class OrthotropicHardening:
    """Section 8.1 parameters: μ_m (macroscopic coefficients), μ_o (initial/macroscopic ratio),
    n (slip hardening, 1/[length]) per axis, and the potential shape exponent k
    (ν_y/ν_x = (μ_y/μ_x)^k; k = 1 associated, k = 0 circular potential)."""

    mu_m_x: float
    mu_m_y: float
    mu_o_x: float = 1.0
    mu_o_y: float = 1.0
    n_x: float = 0.0
    n_y: float = 0.0
    k: float = 0.0

    def __post_init__(self):
        for name in ("mu_m_x", "mu_m_y", "mu_o_x", "mu_o_y"):
            object.__setattr__(self, name, _check_positive(name, getattr(self, name)))
        for name in ("n_x", "n_y"):
            object.__setattr__(self, name, _check_positive(name, getattr(self, name), True))
        k = float(self.k)
        if not math.isfinite(k):
            raise ValueError(f"k must be finite, got {self.k!r}")
        object.__setattr__(self, "k", k)

    def params(self) -> np.ndarray:
        return np.array([self.mu_m_x, self.mu_m_y, self.mu_o_x, self.mu_o_y,
                         self.n_x, self.n_y, self.k], dtype=np.float64)

    def mu(self, kappa_x, kappa_y):
        """(μ_x, μ_y) of (89)-(90) at accumulated axial slips κ_x, κ_y."""
        return (_mu_np(self.mu_m_x, self.mu_o_x, self.n_x, kappa_x),
                _mu_np(self.mu_m_y, self.mu_o_y, self.n_y, kappa_y))

    def swapped(self) -> "OrthotropicHardening":
        """The same law with x and y exchanged."""
        return OrthotropicHardening(self.mu_m_y, self.mu_m_x, self.mu_o_y, self.mu_o_x,
                                    self.n_y, self.n_x, self.k)


@dataclass(frozen=True)
class IsotropicHardening:
    """Section 8.2 parameters: μ_m, μ_o (the paper's β) and n (1/[length]) of (119)."""

    mu_m: float
    mu_o: float = 1.0
    n: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "mu_m", _check_positive("mu_m", self.mu_m))
        object.__setattr__(self, "mu_o", _check_positive("mu_o", self.mu_o))
        object.__setattr__(self, "n", _check_positive("n", self.n, True))

    def params(self) -> np.ndarray:
        return np.array([self.mu_m, self.mu_o, self.n], dtype=np.float64)

    def mu(self, kappa):
        """μ_F of (119) at the accumulated slip length κ."""
        return _mu_np(self.mu_m, self.mu_o, self.n, kappa)


def _mu_np(mu_m, mu_o, n, kappa):
    return mu_m * (1.0 - (1.0 - mu_o) * np.exp(-n * np.asarray(kappa, dtype=float)))


# ---------------------------------------------------------------------------------------------
# numba building blocks
# ---------------------------------------------------------------------------------------------
@numba.njit(cache=True)
def _normal_law(u_n, k_n, tab, h_ref):
    """THE sign convention (module docstring): u_N = closure (> 0 compresses), p_N ≥ 0 pressure.
    Returns (p_N, dp_N/du_N, d²p_N/du_N², beyond). Empty ``tab``: total form of eq. (117) with
    constant k_N, open for u_N ≤ 0; otherwise the tabulated law (interface.closure_law) with
    u_N measured from the reference separation h_ref."""
    if tab.shape[0] > 0:
        return closure_law(u_n, h_ref, tab)
    if u_n > 0.0:
        return k_n * u_n, k_n, 0.0, False
    return 0.0, 0.0, 0.0, False


@numba.njit(cache=True)
def _hardening(mu_m, mu_o, n, kappa):
    e = math.exp(-n * kappa)
    mu = mu_m * (1.0 - (1.0 - mu_o) * e)  # eq. (89)/(90)/(119)
    dmu = n * mu_m * (1.0 - mu_o) * e  # eq. (111)/(112)/(129)
    return mu, dmu


@numba.njit(cache=True)
def _sign(x):
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return 0.0


# indices into the work vector of _ortho_eval
_E_TX, _E_TY, _E_KX, _E_KY, _E_WX, _E_WY, _E_CX, _E_CY = 0, 1, 2, 3, 4, 5, 6, 7
_E_S, _E_PHI, _E_S_LAM, _E_S_R, _E_S_TTX, _E_S_TTY = 8, 9, 10, 11, 12, 13
_E_PHI_LAM, _E_PHI_R, _E_PHI_TTX, _E_PHI_TTY = 14, 15, 16, 17
_E_TX_LAM, _E_TX_R, _E_TY_LAM, _E_TY_R = 18, 19, 20, 21
_E_S_KTX, _E_S_KTY, _E_PHI_KTX, _E_PHI_KTY, _E_TX_KTX, _E_TY_KTY = 22, 23, 24, 25, 26, 27
_NE = 28


@numba.njit(cache=True)
def _ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, out):
    """Backward-Euler state at (λ, r) and the partial derivatives of F = S - p and
    Φ = r - k ln(μ_y/μ_x) with respect to λ, r, the trial tractions and k_Tx, k_Ty."""
    wx = math.exp(r)
    wy = math.exp(-r)
    cx = 1.0 / (1.0 + ktx * lam * wx)
    cy = 1.0 / (1.0 + kty * lam * wy)
    tx = ttx * cx  # t = t^tr - K_T Δu^p, Δu_i^p = λ w_i t_i: eqs. (93), (99)
    ty = tty * cy
    ax = abs(ttx)
    ay = abs(tty)
    kx = kxn + ax * lam * wx * cx  # κ_i = κ_i,n + |Δu_i^p|
    ky = kyn + ay * lam * wy * cy
    mux, dmux = _hardening(par[0], par[2], par[4], kx)  # eq. (89), (111)
    muy, dmuy = _hardening(par[1], par[3], par[5], ky)  # eq. (90), (112)
    hx = dmux / mux
    hy = dmuy / muy
    ke = par[6]
    # derivatives of c_i, t_i, κ_i
    cx_lam = -ktx * wx * cx * cx
    cx_r = -ktx * lam * wx * cx * cx
    cy_lam = -kty * wy * cy * cy
    cy_r = kty * lam * wy * cy * cy
    tx_lam = ttx * cx_lam
    tx_r = ttx * cx_r
    ty_lam = tty * cy_lam
    ty_r = tty * cy_r
    kx_lam = ax * wx * cx * cx
    kx_r = ax * lam * wx * cx * cx
    kx_ttx = _sign(ttx) * lam * wx * cx
    ky_lam = ay * wy * cy * cy
    ky_r = -ay * lam * wy * cy * cy
    ky_tty = _sign(tty) * lam * wy * cy
    # Φ: potential ratio ν_y/ν_x = (μ_y/μ_x)^k, eq. (98), in logarithms
    phi = r - ke * (math.log(muy) - math.log(mux))
    phi_lam = -ke * (hy * ky_lam - hx * kx_lam)
    phi_r = 1.0 - ke * (hy * ky_r - hx * kx_r)
    phi_ttx = ke * hx * kx_ttx
    phi_tty = -ke * hy * ky_tty
    # limit function, eq. (91); ∂S/∂t_i = c_x, c_y of eq. (106)
    s = math.sqrt((tx / mux) ** 2 + (ty / muy) ** 2)
    gx = tx / (mux * mux * s)
    gy = ty / (muy * muy * s)
    out[_E_TX] = tx
    out[_E_TY] = ty
    out[_E_KX] = kx
    out[_E_KY] = ky
    out[_E_WX] = wx
    out[_E_WY] = wy
    out[_E_CX] = cx
    out[_E_CY] = cy
    out[_E_S] = s
    out[_E_PHI] = phi
    out[_E_S_LAM] = gx * (tx_lam - tx * hx * kx_lam) + gy * (ty_lam - ty * hy * ky_lam)
    out[_E_S_R] = gx * (tx_r - tx * hx * kx_r) + gy * (ty_r - ty * hy * ky_r)
    out[_E_S_TTX] = gx * (cx - tx * hx * kx_ttx)
    out[_E_S_TTY] = gy * (cy - ty * hy * ky_tty)
    out[_E_PHI_LAM] = phi_lam
    out[_E_PHI_R] = phi_r
    out[_E_PHI_TTX] = phi_ttx
    out[_E_PHI_TTY] = phi_tty
    out[_E_TX_LAM] = tx_lam
    out[_E_TX_R] = tx_r
    out[_E_TY_LAM] = ty_lam
    out[_E_TY_R] = ty_r
    # k_T-derivatives at fixed (λ, r, t^tr): needed when k_T follows k_N(u_N)
    cx_k = -lam * wx * cx * cx
    cy_k = -lam * wy * cy * cy
    tx_k = ttx * cx_k
    ty_k = tty * cy_k
    kx_k = ax * lam * wx * cx_k
    ky_k = ay * lam * wy * cy_k
    out[_E_S_KTX] = gx * (tx_k - tx * hx * kx_k)
    out[_E_S_KTY] = gy * (ty_k - ty * hy * ky_k)
    out[_E_PHI_KTX] = ke * hx * kx_k
    out[_E_PHI_KTY] = -ke * hy * ky_k
    out[_E_TX_KTX] = tx_k
    out[_E_TY_KTY] = ty_k


@numba.njit(cache=True)
def _ortho_solve_r(lam, r0, ttx, tty, ktx, kty, kxn, kyn, par, wk, tol):
    """Φ(r; λ) = 0 by bracketed Newton. Bracket: the range of k ln(μ_y/μ_x) over the box
    κ_i ∈ [κ_i,n, κ_i,n + |t_i^tr|/k_Ti] that contains every backward-Euler κ."""
    ke = par[6]
    if ke == 0.0:
        _ortho_eval(lam, 0.0, ttx, tty, ktx, kty, kxn, kyn, par, wk)
        return 0.0, 0
    mxa, _ = _hardening(par[0], par[2], par[4], kxn)
    mxb, _ = _hardening(par[0], par[2], par[4], kxn + abs(ttx) / ktx)
    mya, _ = _hardening(par[1], par[3], par[5], kyn)
    myb, _ = _hardening(par[1], par[3], par[5], kyn + abs(tty) / kty)
    lo_l = math.log(min(mya, myb)) - math.log(max(mxa, mxb))
    hi_l = math.log(max(mya, myb)) - math.log(min(mxa, mxb))
    if ke > 0.0:
        lo = ke * lo_l
        hi = ke * hi_l
    else:
        lo = ke * hi_l
        hi = ke * lo_l
    r = min(max(r0, lo), hi)
    if hi - lo <= 0.0:
        _ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk)
        return r, 0
    for it in range(_MAXIT):
        _ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk)
        phi = wk[_E_PHI]
        if phi == 0.0:
            return r, 0
        if phi < 0.0:
            lo = r
        else:
            hi = r
        dphi = wk[_E_PHI_R]
        newton = False
        rn = 0.5 * (lo + hi)
        if dphi > 0.0:
            cand = r - phi / dphi
            if lo < cand < hi:
                rn = cand
                newton = True
        done = (newton and abs(rn - r) <= tol * (1.0 + abs(rn))) or \
            (hi - lo) <= 4.0 * 2.220446049250313e-16 * (1.0 + abs(rn))
        r = rn
        if done:
            _ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk)
            return r, 0
    return r, 1


@numba.njit(cache=True)
def _begin_update(stiff, s_old, du, s_new, D, tab, h_ref):
    """Shared start of both updates: copy the state, zero D, apply the normal law and the
    tangential stiffnesses at the end of the step; for a closed contact the elastic (trial)
    tangential tractions, eq. (93)-(94). ``stiff`` = (k_Tx, k_Ty, k_N) for the constant law,
    (k_Tx/k_N, k_Ty/k_N, unused) with a table (k_T = a k_N(u_N)).
    Returns (status, p, dp, ttx, tty, ktx, kty, dktx, dkty) with d = d/du_N and status
    OPEN, _BEYOND or STICK (= closed, to be decided)."""
    for j in range(NSTATE):
        s_new[j] = s_old[j]
    for a in range(3):
        for b in range(3):
            D[a, b] = 0.0
    u_n = s_old[U_N] + du[2]
    p, dp, ddp, beyond = _normal_law(u_n, stiff[2], tab, h_ref)
    s_new[U_N] = u_n
    s_new[T_N] = p
    if beyond:
        return _BEYOND, p, dp, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if p <= 0.0:
        s_new[T_X] = 0.0
        s_new[T_Y] = 0.0
        return OPEN, p, dp, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if tab.shape[0] > 0:
        ktx = stiff[0] * dp
        kty = stiff[1] * dp
        dktx = stiff[0] * ddp
        dkty = stiff[1] * ddp
    else:
        ktx = stiff[0]
        kty = stiff[1]
        dktx = 0.0
        dkty = 0.0
    return (STICK, p, dp, s_old[T_X] + ktx * du[0], s_old[T_Y] + kty * du[1],
            ktx, kty, dktx, dkty)


@numba.njit(cache=True)
def _stick(ttx, tty, ktx, kty, dp, dktx, dkty, du, s_new, D):
    """Stick: t = t^tr, D = D^e (94) plus ∂t^tr/∂u_N = ∂K_T/∂u_N Δu_T (zero for constant k_T)."""
    s_new[T_X] = ttx
    s_new[T_Y] = tty
    D[0, 0] = ktx
    D[1, 1] = kty
    D[2, 2] = dp
    if dktx != 0.0 or dkty != 0.0:
        D[0, 2] = dktx * du[0]
        D[1, 2] = dkty * du[1]
    return STICK


@numba.njit(cache=True)
def _assemble_tangent(sens, ktx, kty, dp, dktx, dkty, du, D):
    """D rows t_x, t_y from the sensitivities sens[i, m] = dt_i/dθ_m of the return map to
    θ = (t^tr_x, t^tr_y, p, k_Tx, k_Ty) by the chain rule through t^tr = t_n + K_T(u_N) Δu_T,
    p(u_N), K_T(u_N); row p_N: dp/du_N."""
    for i in range(2):
        D[i, 0] = sens[i, 0] * ktx
        D[i, 1] = sens[i, 1] * kty
        D[i, 2] = sens[i, 2] * dp
        if dktx != 0.0 or dkty != 0.0:
            D[i, 2] += (sens[i, 0] * du[0] + sens[i, 3]) * dktx + (sens[i, 1] * du[1] + sens[i, 4]) * dkty
    D[2, 2] = dp


@numba.njit(cache=True)
def _ortho_point(par, stiff, s_old, du, s_new, D, tol, tab, h_ref):
    """One orthotropic update (section 8.1). Returns STICK/SLIP/OPEN, _FAILED or _BEYOND."""
    status, p, dp, ttx, tty, ktx, kty, dktx, dkty = _begin_update(stiff, s_old, du, s_new, D, tab, h_ref)
    if status != STICK:
        return status
    kxn = s_old[KAPPA_X]
    kyn = s_old[KAPPA_Y]
    mux, _ = _hardening(par[0], par[2], par[4], kxn)
    muy, _ = _hardening(par[1], par[3], par[5], kyn)
    s_tr = math.sqrt((ttx / mux) ** 2 + (tty / muy) ** 2)
    if s_tr - p <= 0.0:  # f ≤ 0, eq. (91): stick
        return _stick(ttx, tty, ktx, kty, dp, dktx, dkty, du, s_new, D)
    # slip: backward-Euler return mapping; ψ(λ) = p/S - 1 increases from ψ(0) < 0 to +∞
    wk = np.empty(_NE)
    r = par[6] * (math.log(muy) - math.log(mux))
    lam = 0.0
    lo = 0.0
    hi = -1.0  # no upper bracket yet
    status = _FAILED
    for it in range(_MAXIT):
        r, fail = _ortho_solve_r(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk, 1e-14)
        if fail:
            break
        s = wk[_E_S]
        psi = p / s - 1.0
        drdl = -wk[_E_PHI_LAM] / wk[_E_PHI_R]
        dpsi = -p / (s * s) * (wk[_E_S_LAM] + wk[_E_S_R] * drdl)
        if psi == 0.0:
            status = SLIP
            break
        if psi < 0.0:
            lo = lam
        else:
            hi = lam
        newton = False
        if dpsi > 0.0:
            cand = lam - psi / dpsi
            if cand > lo and (hi < 0.0 or cand < hi):
                newton = True
        if not newton:
            if hi >= 0.0:
                cand = 0.5 * (lo + hi)
            elif lam == 0.0:
                cand = (s / p - 1.0) / max(ktx * wk[_E_WX], kty * wk[_E_WY])
            else:
                cand = 2.0 * lam
        done = (newton and abs(cand - lam) <= tol * cand) or \
            (hi >= 0.0 and hi - lo <= 4.0 * 2.220446049250313e-16 * hi)
        lam = cand
        if done:
            r, fail = _ortho_solve_r(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk, 1e-14)
            if not fail:
                status = SLIP
            break
    if status == _FAILED:
        return _FAILED
    tx = wk[_E_TX]
    ty = wk[_E_TY]
    dupx = lam * wk[_E_WX] * tx  # Δu^p = γ ∂g/∂t, eq. (99) with (98)/(101), Δu_N^p = 0
    dupy = lam * wk[_E_WY] * ty
    s_new[T_X] = tx
    s_new[T_Y] = ty
    s_new[UP_X] = s_old[UP_X] + dupx
    s_new[UP_Y] = s_old[UP_Y] + dupy
    s_new[KAPPA_X] = wk[_E_KX]
    s_new[KAPPA_Y] = wk[_E_KY]
    s_new[DISSIPATION] = s_old[DISSIPATION] + tx * dupx + ty * dupy
    # consistent tangent: implicit differentiation of (F, Φ) = 0 in (λ, r)
    a11 = wk[_E_S_LAM]
    a12 = wk[_E_S_R]
    a21 = wk[_E_PHI_LAM]
    a22 = wk[_E_PHI_R]
    det = a11 * a22 - a12 * a21
    # right-hand sides: θ = (t^tr_x, t^tr_y, p, k_Tx, k_Ty); F_p = -1, Φ_p = 0
    b1 = (wk[_E_S_TTX], wk[_E_S_TTY], -1.0, wk[_E_S_KTX], wk[_E_S_KTY])
    b2 = (wk[_E_PHI_TTX], wk[_E_PHI_TTY], 0.0, wk[_E_PHI_KTX], wk[_E_PHI_KTY])
    # direct ∂t/∂θ at fixed (λ, r)
    ex = (wk[_E_CX], 0.0, 0.0, wk[_E_TX_KTX], 0.0)
    ey = (0.0, wk[_E_CY], 0.0, 0.0, wk[_E_TY_KTY])
    sens = np.empty((2, 5))
    for m in range(5):
        dlam = -(a22 * b1[m] - a12 * b2[m]) / det
        dr = -(-a21 * b1[m] + a11 * b2[m]) / det
        sens[0, m] = wk[_E_TX_LAM] * dlam + wk[_E_TX_R] * dr + ex[m]
        sens[1, m] = wk[_E_TY_LAM] * dlam + wk[_E_TY_R] * dr + ey[m]
    _assemble_tangent(sens, ktx, kty, dp, dktx, dkty, du, D)
    return SLIP


@numba.njit(cache=True)
def _iso_eval(lam, ttx, tty, ktx, kty, kapn, par):
    cx = 1.0 / (1.0 + ktx * lam)
    cy = 1.0 / (1.0 + kty * lam)
    tx = ttx * cx  # t = t^tr - K_T γ t/|t|, eqs. (93), (99), (121); λ = γ/|t|
    ty = tty * cy
    t = math.sqrt(tx * tx + ty * ty)
    kap = kapn + lam * t  # κ = κ_n + |Δu^p|, eq. (119)
    mu, dmu = _hardening(par[0], par[1], par[2], kap)  # eq. (119), (129)
    t_lam = -(ktx * cx * tx * tx + kty * cy * ty * ty) / t
    kap_lam = t + lam * t_lam
    return tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam


@numba.njit(cache=True)
def _iso_point(par, stiff, s_old, du, s_new, D, tol, tab, h_ref):
    """One isotropic update (section 8.2). Returns STICK/SLIP/OPEN, _FAILED or _BEYOND."""
    status, p, dp, ttx, tty, ktx, kty, dktx, dkty = _begin_update(stiff, s_old, du, s_new, D, tab, h_ref)
    if status != STICK:
        return status
    kapn = s_old[KAPPA]
    mu0, _ = _hardening(par[0], par[1], par[2], kapn)
    if math.sqrt(ttx * ttx + tty * tty) - mu0 * p <= 0.0:  # f ≤ 0, eq. (120): stick
        return _stick(ttx, tty, ktx, kty, dp, dktx, dkty, du, s_new, D)
    lam = 0.0
    lo = 0.0
    hi = -1.0
    status = _FAILED
    for it in range(_MAXIT):
        tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam = _iso_eval(
            lam, ttx, tty, ktx, kty, kapn, par)
        psi = mu * p / t - 1.0
        dpsi = p * (dmu * kap_lam * t - mu * t_lam) / (t * t)
        if psi == 0.0:
            status = SLIP
            break
        if psi < 0.0:
            lo = lam
        else:
            hi = lam
        newton = False
        if dpsi > 0.0:
            cand = lam - psi / dpsi
            if cand > lo and (hi < 0.0 or cand < hi):
                newton = True
        if not newton:
            if hi >= 0.0:
                cand = 0.5 * (lo + hi)
            elif lam == 0.0:
                cand = (t / (mu * p) - 1.0) / max(ktx, kty)
            else:
                cand = 2.0 * lam
        done = (newton and abs(cand - lam) <= tol * cand) or \
            (hi >= 0.0 and hi - lo <= 4.0 * 2.220446049250313e-16 * hi)
        lam = cand
        if done:
            status = SLIP
            break
    if status == _FAILED:
        return _FAILED
    tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam = _iso_eval(
        lam, ttx, tty, ktx, kty, kapn, par)
    dupx = lam * tx  # Δu^p = γ t/|t|, eq. (99) with (121)
    dupy = lam * ty
    s_new[T_X] = tx
    s_new[T_Y] = ty
    s_new[UP_X] = s_old[UP_X] + dupx
    s_new[UP_Y] = s_old[UP_Y] + dupy
    s_new[KAPPA] = kap
    s_new[DISSIPATION] = s_old[DISSIPATION] + tx * dupx + ty * dupy
    # consistent tangent: F = |t| - μ_F p = 0 differentiated in λ and
    # θ = (t^tr_x, t^tr_y, p, k_Tx, k_Ty); ∂|t|/∂k_Ti = -λ c_i t_i²/|t| at fixed λ
    f_lam = t_lam - dmu * p * kap_lam
    fac = 1.0 - dmu * p * lam
    txk = -lam * cx * tx
    tyk = -lam * cy * ty
    b = (tx * cx / t * fac, ty * cy / t * fac, -mu, tx * txk / t * fac, ty * tyk / t * fac)
    ex = (cx, 0.0, 0.0, txk, 0.0)
    ey = (0.0, cy, 0.0, 0.0, tyk)
    tx_lam = -ktx * cx * tx
    ty_lam = -kty * cy * ty
    sens = np.empty((2, 5))
    for m in range(5):
        dlam = -b[m] / f_lam
        sens[0, m] = tx_lam * dlam + ex[m]
        sens[1, m] = ty_lam * dlam + ey[m]
    _assemble_tangent(sens, ktx, kty, dp, dktx, dkty, du, D)
    return SLIP


@numba.njit(cache=True)
def _ortho_kernel(par, stiff, s_old, du, s_new, D, status, tol, tab, h_ref):
    for i in range(s_old.shape[0]):
        status[i] = _ortho_point(par, stiff[i], s_old[i], du[i], s_new[i], D[i], tol, tab, h_ref)


@numba.njit(cache=True)
def _iso_kernel(par, stiff, s_old, du, s_new, D, status, tol, tab, h_ref):
    for i in range(s_old.shape[0]):
        status[i] = _iso_point(par, stiff[i], s_old[i], du[i], s_new[i], D[i], tol, tab, h_ref)


# ---------------------------------------------------------------------------------------------
# Python API
# ---------------------------------------------------------------------------------------------
class FrictionUpdate(NamedTuple):
    """Result of :func:`update`: new state (..., 9), consistent tangent D (..., 3, 3) and
    status (...,) (STICK, SLIP, OPEN)."""

    state: np.ndarray
    D: np.ndarray
    status: np.ndarray

    @property
    def tractions(self) -> np.ndarray:
        """(t_x, t_y, p_N), shape (..., 3)."""
        return self.state[..., :3]


def normal_law(u_n, k_n):
    """Normal pressure p_N ≥ 0 and dp_N/du_N for the total closure u_N (> 0 closes), the
    module's single sign-convention helper (vectorised): ``k_n`` a constant stiffness (open for
    u_N ≤ 0) or an :class:`~roughcontact.interface.InterfaceLaw` (u_N from its reference state;
    open for u_N ≤ law.u_open; ValueError beyond its heavy end)."""
    if isinstance(k_n, InterfaceLaw):
        return k_n.normal(u_n)
    u = np.asarray(u_n, dtype=float)
    k = np.asarray(k_n, dtype=float)
    closed = u > 0.0
    p = np.where(closed, k * u, 0.0)
    dp = np.where(closed, k * np.ones_like(u), 0.0)
    if p.ndim == 0:
        return float(p), float(dp)
    return p, dp


def initial_state(shape=(), *, u_N=0.0, k_N=None):
    """Virgin state(s): zero tractions, slips, hardening and dissipation, normal closure u_N
    (p_N from :func:`normal_law` stored if k_N, a constant or an InterfaceLaw, is given; with a
    law, u_N = 0 is its reference state p_N = p0). ``shape`` is the point shape ((): one point)."""
    shape = (shape,) if isinstance(shape, (int, np.integer)) else tuple(shape)
    s = np.zeros(shape + (NSTATE,))
    s[..., U_N] = u_N
    if k_N is not None:
        s[..., T_N] = normal_law(s[..., U_N], k_N)[0]
    return s


def _as_model(model):
    if isinstance(model, (OrthotropicHardening, IsotropicHardening)):
        return model
    raise TypeError("model must be an OrthotropicHardening or IsotropicHardening instance")


def _stiffness_inputs(k_N, k_Tx, k_Ty):
    """(named per-point stiffness inputs for the kernel, tab, h_ref): (k_Tx, k_Ty, k_N) for the
    constant law, (k_Tx/k_N, k_Ty/k_N, unused) with an InterfaceLaw (see _begin_update)."""
    if isinstance(k_N, InterfaceLaw):
        if k_Tx is not None or k_Ty is not None:
            raise ValueError("with an InterfaceLaw as k_N, k_Tx and k_Ty come from the law "
                             "(k_T = kT_over_kN * k_N(u_N)); do not pass them")
        tab, h_ref, (ax, ay) = k_N.kernel_data()
        return (("kT_over_kN_x", ax), ("kT_over_kN_y", ay), ("unused", 1.0)), tab, h_ref
    if k_Tx is None or k_Ty is None:
        raise ValueError("k_Tx and k_Ty are required with a constant k_N")
    return (("k_Tx", k_Tx), ("k_Ty", k_Ty), ("k_N", k_N)), _NO_TABLE, 0.0


_NO_TABLE = np.empty((0, 4))


def _prepare(state, du, stiffness):
    s = np.asarray(state, dtype=float)
    d = np.asarray(du, dtype=float)
    if s.ndim == 0 or s.shape[-1] != NSTATE:
        raise ValueError(f"state must have shape (..., {NSTATE}), got {s.shape}")
    if d.ndim == 0 or d.shape[-1] != 3:
        raise ValueError(f"du must have shape (..., 3), got {d.shape}")
    try:
        shape = np.broadcast_shapes(s.shape[:-1], d.shape[:-1])
    except ValueError:
        raise ValueError(f"state {s.shape} and du {d.shape} do not broadcast") from None
    stiff = []
    for name, k in stiffness:
        a = np.asarray(k, dtype=float)
        if not np.all(np.isfinite(a) & (a > 0.0)):
            raise ValueError(f"{name} must be finite and > 0")
        try:
            shape = np.broadcast_shapes(shape, a.shape)
        except ValueError:
            raise ValueError(f"{name} of shape {a.shape} does not broadcast to {shape}") from None
        stiff.append(a)
    if not np.all(np.isfinite(s)):
        raise ValueError("state must be finite")
    if not np.all(np.isfinite(d)):
        raise ValueError("du must be finite")
    if np.any(s[..., KAPPA_X] < 0.0) or np.any(s[..., KAPPA_Y] < 0.0):
        raise ValueError("accumulated slips (state[..., 6:8]) must be >= 0")
    n = int(np.prod(shape))
    s2 = np.ascontiguousarray(np.broadcast_to(s, shape + (NSTATE,)).reshape(n, NSTATE))
    d2 = np.ascontiguousarray(np.broadcast_to(d, shape + (3,)).reshape(n, 3))
    st = np.empty((n, 3))
    for j, a in enumerate(stiff):
        st[:, j] = np.broadcast_to(a, shape).reshape(n)
    return shape, s2, d2, st


def update(model, state, du, k_N, k_Tx=None, k_Ty=None, *, tol=1e-12) -> FrictionUpdate:
    """Incremental update of the interface law at many integration points (numba kernel).

    Parameters
    ----------
    model : OrthotropicHardening or IsotropicHardening
    state : (..., 9) array, the state at the start of the increment (see module docstring).
    du : (..., 3) array, increment (Δu_Tx, Δu_Ty, Δu_N) of the relative displacement;
        Δu_N > 0 closes the interface.
    k_N, k_Tx, k_Ty : stiffnesses per unit area, > 0, broadcastable to the point shape;
        or k_N an :class:`~roughcontact.interface.InterfaceLaw` (tabulated p_N(u_N), k_N(u_N),
        k_T = a k_N(u_N); then no k_Tx, k_Ty). See "Normal contact, sign convention and
        reference state" in the module docstring.
    tol : relative Newton step tolerance of the return mapping (0 < tol ≤ 1e-6).

    Returns
    -------
    FrictionUpdate(state, D, status); state and D have the broadcast point shape.

    Raises ValueError for bad input and for closures beyond the heavy end of a tabulated law.
    """
    model = _as_model(model)
    tol = float(tol)
    if not (0.0 < tol <= 1e-6):
        raise ValueError(f"tol must be in (0, 1e-6], got {tol!r}")
    stiffness, tab, h_ref = _stiffness_inputs(k_N, k_Tx, k_Ty)
    shape, s_old, d, st = _prepare(state, du, stiffness)
    n = s_old.shape[0]
    s_new = np.empty_like(s_old)
    D = np.empty((n, 3, 3))
    status = np.empty(n, dtype=np.int8)
    kernel = _ortho_kernel if isinstance(model, OrthotropicHardening) else _iso_kernel
    kernel(model.params(), st, s_old, d, s_new, D, status, tol, tab, h_ref)
    if np.any(status == _BEYOND):
        bad = np.flatnonzero(status == _BEYOND)
        raise ValueError(
            f"u_N = {s_new[bad[0], U_N]:g} at points {bad[:10].tolist()} exceeds the heavy end of "
            f"the tabulated normal law (u_max = {k_N.u_max:g}, p_max = {k_N.table.p_max:g}); "
            "rebuild the table with a larger p_max")
    if np.any(status == _FAILED):
        bad = np.flatnonzero(status == _FAILED)
        raise RuntimeError(f"return mapping did not converge at points {bad[:10].tolist()}")
    return FrictionUpdate(s_new.reshape(shape + (NSTATE,)), D.reshape(shape + (3, 3)),
                          status.reshape(shape))


# ---------------------------------------------------------------------------------------------
# diagnostics: limit function, angles, directional coefficient, continuum tangent
# ---------------------------------------------------------------------------------------------
def limit_function(model, state):
    """f of (91) (orthotropic) or (120) (isotropic) at the state's tractions, pressure and
    hardening variables [stress]; ≤ 0 admissible, = 0 on the limit surface."""
    model = _as_model(model)
    s = np.asarray(state, dtype=float)
    tx, ty, p = s[..., T_X], s[..., T_Y], s[..., T_N]
    if isinstance(model, OrthotropicHardening):
        mux, muy = model.mu(s[..., KAPPA_X], s[..., KAPPA_Y])
        return np.sqrt((tx / mux) ** 2 + (ty / muy) ** 2) - p  # eq. (91)
    return np.hypot(tx, ty) - model.mu(s[..., KAPPA]) * p  # eq. (120)


def slip_angle(du_p):
    """α of (114)/(127): inclination of the plastic slip increment (Δu_x^p, Δu_y^p)."""
    d = np.asarray(du_p, dtype=float)
    return np.arctan2(d[..., 1], d[..., 0])


def traction_angle(t):
    """β of (116)/(130): inclination of the tangential traction (t_x, t_y)."""
    t = np.asarray(t, dtype=float)
    return np.arctan2(t[..., 1], t[..., 0])


def directional_coefficient_115(mu_x, mu_y, alpha):
    """μ_α of (115) as printed: the traction magnitude/p_N on the limit ellipse whose outward
    normal has inclination α (equals the slip angle only for the associated rule k = 1)."""
    c2, s2 = np.cos(alpha) ** 2, np.sin(alpha) ** 2
    return np.sqrt((mu_x ** 4 * c2 + mu_y ** 4 * s2) / (mu_x ** 2 * c2 + mu_y ** 2 * s2))


def directional_coefficient_beta(mu_x, mu_y, beta):
    """|t_T|/p_N on the limit ellipse (91) in the traction direction β (corrected (115)-(116)):
    μ_β = (cos²β/μ_x² + sin²β/μ_y²)^{-1/2}."""
    return 1.0 / np.sqrt(np.cos(beta) ** 2 / mu_x ** 2 + np.sin(beta) ** 2 / mu_y ** 2)


def _gradients(model, s):
    """(c, d, H): ∂f/∂(t_x, t_y, t_N) (106)/(122), slip direction ∂g/∂(t_x, t_y, t_N) up to a
    positive factor, and the corrected hardening modulus H (109)/(110), (125) for one state."""
    tx, ty, p = float(s[T_X]), float(s[T_Y]), float(s[T_N])
    if isinstance(model, OrthotropicHardening):
        mux, muy = (float(v) for v in model.mu(s[KAPPA_X], s[KAPPA_Y]))
        dmux = model.n_x * model.mu_m_x * (1 - model.mu_o_x) * math.exp(-model.n_x * s[KAPPA_X])
        dmuy = model.n_y * model.mu_m_y * (1 - model.mu_o_y) * math.exp(-model.n_y * s[KAPPA_Y])
        S = math.hypot(tx / mux, ty / muy)
        c = np.array([tx / (mux ** 2 * S), ty / (muy ** 2 * S), -1.0])  # eq. (106)
        rho = (muy / mux) ** model.k  # ν_y/ν_x, eq. (98)
        d = np.array([rho * tx, ty / rho, 0.0])  # ∝ (t_x/ν_x², t_y/ν_y²), eq. (106)_4-6
        d /= np.linalg.norm(d)
        # corrected eq. (110): ∂f/∂μ_i μ_i' |d_i| (κ_i accumulated)
        H = -(tx ** 2 * dmux * abs(d[0]) / (mux ** 3 * S) + ty ** 2 * dmuy * abs(d[1]) / (muy ** 3 * S))
        return c, d, H
    mu = float(model.mu(s[KAPPA]))
    dmu = model.n * model.mu_m * (1 - model.mu_o) * math.exp(-model.n * s[KAPPA])
    T = math.hypot(tx, ty)
    c = np.array([tx / T, ty / T, -mu])  # eq. (122)
    d = np.array([tx / T, ty / T, 0.0])  # eq. (122)
    H = -p * dmu  # corrected (125)/(126)/(131): ∂f/∂μ_F = -t_N, |∂g/∂t| = 1
    return c, d, H


def hardening_modulus(model, state):
    """Corrected hardening parameter H of (109)-(110) / (125)-(126) at one state on the limit
    surface, in the paper's sign convention (H ≤ 0 for hardening, 0 for constant μ; the slip
    direction normalised to |∂g/∂t_T| = 1)."""
    model = _as_model(model)
    return _gradients(model, np.asarray(state, dtype=float))[2]


def continuum_tangent(model, state, k_N, k_Tx, k_Ty):
    """Continuum elasto-plastic tangent (105) = (107)/(123) at one sliding state:
    D^ep = D^e - (D^e d)⊗(D^e c)/(c·D^e d - H), with c, d of (106)/(122), corrected H and
    D^e of (94) (k_N = dp_N/du_N). The algorithmic tangent of :func:`update` tends to it as the
    slip increment vanishes."""
    model = _as_model(model)
    s = np.asarray(state, dtype=float)
    c, d, H = _gradients(model, s)
    De = np.diag([float(k_Tx), float(k_Ty), float(k_N)])
    A = c @ De @ d  # eq. (108)/(124)
    return De - np.outer(De @ d, De @ c) / (A - H)  # eq. (105)


# ---------------------------------------------------------------------------------------------
# presets: Fig. 18 / Fig. 19 caption, cases (a)-(c)
# ---------------------------------------------------------------------------------------------
#: Fig. 18/19 cases. ν_x = ν_y = 0.125 for all three: a circular slip potential, i.e. k = 0
#: (only ν_y/ν_x matters). n_x = n_y = 275 1/mm (section 9.2 text). k_N is not given
#: numerically (it comes from (95) for the captions' surface), so stiffnesses are ratios.
FIG18_CASES = {
    "a": dict(mu_m=0.2, mu_o=1.0, kTx_over_kN=0.7, kTy_over_kN=0.7),
    "b": dict(mu_m=0.5, mu_o=0.5, kTx_over_kN=0.7, kTy_over_kN=0.7),
    "c": dict(mu_m=0.5, mu_o=0.5, kTx_over_kN=0.7, kTy_over_kN=1.0),
}
_N_FIG18_PER_MM = 275.0
_LENGTH_PER_MM = {"mm": 1.0, "um": 1e3, "µm": 1e3, "m": 1e-3}


def fig18_preset(case, k_N, length_unit="mm"):
    """Orthotropic model and stiffnesses of Fig. 18/19 case 'a', 'b' or 'c'.

    ``k_N`` is the normal stiffness per unit area (user supplied; the paper gets it from (95)),
    ``length_unit`` the displacement unit used for u ('mm', 'um'/'µm', 'm'): n is converted
    from 275 1/mm. Returns (OrthotropicHardening, dict(k_N=..., k_Tx=..., k_Ty=...))."""
    if case not in FIG18_CASES:
        raise ValueError(f"case must be one of {sorted(FIG18_CASES)}, got {case!r}")
    if length_unit not in _LENGTH_PER_MM:
        raise ValueError(f"length_unit must be one of {sorted(_LENGTH_PER_MM)}")
    k_N = _check_positive("k_N", k_N)
    c = FIG18_CASES[case]
    n = _N_FIG18_PER_MM / _LENGTH_PER_MM[length_unit]
    model = OrthotropicHardening(c["mu_m"], c["mu_m"], c["mu_o"], c["mu_o"], n, n, k=0.0)
    return model, dict(k_N=k_N, k_Tx=c["kTx_over_kN"] * k_N, k_Ty=c["kTy_over_kN"] * k_N)


# ---------------------------------------------------------------------------------------------
# slow reference twin (pure Python / NumPy / SciPy), single point
# ---------------------------------------------------------------------------------------------
def _ref_mu(mu_m, mu_o, n, kappa):
    return mu_m * (1.0 - (1.0 - mu_o) * np.exp(-n * kappa))  # eq. (89)/(90)/(119)


def _ref_residual(model, X, theta, s_old, stiffness, sx, sy):
    """Primitive backward-Euler residual (complex-step capable).
    Orthotropic X = (t_x, t_y, γ, κ_x, κ_y); isotropic X = (t_x, t_y, γ, κ).
    ``stiffness(u_N)`` -> (p_N, k_N, k_Tx, k_Ty) at the end-of-step closure."""
    dux, duy, dun = theta
    p, _, kTx, kTy = stiffness(s_old[U_N] + dun)
    ttx = s_old[T_X] + kTx * dux
    tty = s_old[T_Y] + kTy * duy
    if isinstance(model, OrthotropicHardening):
        tx, ty, gam, kx, ky = X
        mux = _ref_mu(model.mu_m_x, model.mu_o_x, model.n_x, kx)
        muy = _ref_mu(model.mu_m_y, model.mu_o_y, model.n_y, ky)
        k = model.k
        nux = np.exp(0.5 * (1 + k) * np.log(mux) + 0.5 * (1 - k) * np.log(muy))  # ν_y/ν_x = (μ_y/μ_x)^k
        nuy = np.exp(0.5 * (1 + k) * np.log(muy) + 0.5 * (1 - k) * np.log(mux))
        snu = np.sqrt((tx / nux) ** 2 + (ty / nuy) ** 2)
        dx = tx / (nux ** 2 * snu)  # eq. (106)_4
        dy = ty / (nuy ** 2 * snu)  # eq. (106)_5
        smu = np.sqrt((tx / mux) ** 2 + (ty / muy) ** 2)
        return np.array([
            tx - ttx + kTx * gam * dx,  # eq. (93), (99)
            ty - tty + kTy * gam * dy,
            kx - s_old[KAPPA_X] - gam * sx * dx,  # accumulated |Δu_x^p|
            ky - s_old[KAPPA_Y] - gam * sy * dy,
            smu - p,  # eq. (91)
        ])
    tx, ty, gam, kap = X
    mu = _ref_mu(model.mu_m, model.mu_o, model.n, kap)
    t = np.sqrt(tx ** 2 + ty ** 2)
    return np.array([
        tx - ttx + kTx * gam * tx / t,  # eq. (93), (99), (122)
        ty - tty + kTy * gam * ty / t,
        kap - s_old[KAPPA] - gam,
        t - mu * p,  # eq. (120)
    ])


def _bracket_up(psi, guess):
    hi = guess
    while psi(hi) > 0.0:
        hi *= 2.0
    return hi


def _ref_initial_guess(model, s_old, ttx, tty, kTx, kTy, p):
    """Initial guess by nested Brent solves of the reduced (λ, r) equations."""
    from scipy.optimize import brentq

    if isinstance(model, OrthotropicHardening):
        kxn, kyn, k = s_old[KAPPA_X], s_old[KAPPA_Y], model.k

        def state_at(lam, r):
            wx, wy = math.exp(r), math.exp(-r)
            tx, ty = ttx / (1 + kTx * lam * wx), tty / (1 + kTy * lam * wy)
            kx, ky = kxn + lam * wx * abs(tx), kyn + lam * wy * abs(ty)
            mux, muy = model.mu(kx, ky)
            return tx, ty, kx, ky, float(mux), float(muy)

        def r_of(lam):
            if k == 0.0:
                return 0.0

            def phi(r):
                *_, mux, muy = state_at(lam, r)
                return r - k * math.log(muy / mux)

            b = 50.0 * abs(k) + 1.0
            return brentq(phi, -b, b, xtol=1e-15, rtol=1e-15)

        def psi(lam):
            tx, ty, kx, ky, mux, muy = state_at(lam, r_of(lam))
            return math.hypot(tx / mux, ty / muy) - p

        hi = _bracket_up(psi, math.hypot(ttx, tty) / (p * max(kTx, kTy)))
        lam = brentq(psi, 0.0, hi, xtol=1e-300, rtol=1e-15)
        tx, ty, kx, ky, mux, muy = state_at(lam, r_of(lam))
        nux = mux ** (0.5 * (1 + k)) * muy ** (0.5 * (1 - k))
        nuy = muy ** (0.5 * (1 + k)) * mux ** (0.5 * (1 - k))
        snu = math.hypot(tx / nux, ty / nuy)
        gam = lam * snu * nux * nuy  # λ̃ = (γ/S_ν)/(ν_x ν_y)
        return np.array([tx, ty, gam, kx, ky])
    kapn = s_old[KAPPA]

    def state_at(lam):
        tx, ty = ttx / (1 + kTx * lam), tty / (1 + kTy * lam)
        t = math.hypot(tx, ty)
        return tx, ty, t, kapn + lam * t

    def psi(lam):
        tx, ty, t, kap = state_at(lam)
        return t - float(model.mu(kap)) * p

    hi = _bracket_up(psi, math.hypot(ttx, tty) / (p * max(kTx, kTy)))
    lam = brentq(psi, 0.0, hi, xtol=1e-300, rtol=1e-15)
    tx, ty, t, kap = state_at(lam)
    return np.array([tx, ty, lam * t, kap])


def _complex_jacobian(fun, x, h=1e-30):
    x = np.asarray(x, dtype=complex)
    cols = []
    for j in range(x.size):
        xp = x.copy()
        xp[j] += 1j * h
        cols.append(np.imag(fun(xp)) / h)
    return np.array(cols).T


def _ref_stiffness(k_N, k_Tx, k_Ty):
    """u_N -> (p_N, k_N, k_Tx, k_Ty) for the twin, complex-step capable, valid for a closed
    contact: the constant law (p = k_N u_N) or the tabulated one
    (interface.reference_closure_law, k_T = a k_N)."""
    if isinstance(k_N, InterfaceLaw):
        tab, h_ref, (ax, ay) = k_N.kernel_data()

        def stiffness(u):
            p, k = reference_closure_law(u, h_ref, tab)
            return p, k, ax * k, ay * k
        return stiffness
    kN, kTx, kTy = float(k_N), float(k_Tx), float(k_Ty)
    return lambda u: (kN * u, kN, kTx, kTy)


def reference_update(model, state, du, k_N, k_Tx=None, k_Ty=None):
    """Slow single-point twin of :func:`update` (pure Python/NumPy/SciPy), with the same
    stiffness inputs (constants or an InterfaceLaw as ``k_N``).

    Solves the primitive backward-Euler system in (t_x, t_y, γ, κ...) with the potential (98)
    written through ν_x, ν_y explicitly, by Newton with complex-step Jacobians from a nested
    Brent initial guess; the tangent is the implicit-function derivative of that system,
    again by complex steps (the stick tangent: complex steps of the trial tractions).
    Returns (state (9,), D (3, 3), status)."""
    model = _as_model(model)
    s_old = np.asarray(state, dtype=float).copy()
    d = np.asarray(du, dtype=float)
    stiffness = _ref_stiffness(k_N, k_Tx, k_Ty)
    s = s_old.copy()
    D = np.zeros((3, 3))
    u_n = s_old[U_N] + d[2]
    s[U_N] = u_n
    p, kN, kTx, kTy = (float(np.real(v)) for v in stiffness(u_n))
    if p <= 0.0:  # open (constant law: u_N ≤ 0)
        s[T_N] = s[T_X] = s[T_Y] = 0.0
        return s, D, OPEN
    s[T_N] = p
    ttx, tty = s_old[T_X] + kTx * d[0], s_old[T_Y] + kTy * d[1]
    trial = s.copy()
    trial[T_X], trial[T_Y] = ttx, tty
    if limit_function(model, trial) <= 0.0:
        s[T_X], s[T_Y] = ttx, tty

        def trial_tractions(theta):
            pc, _, kx, ky = stiffness(s_old[U_N] + theta[2])
            return np.array([s_old[T_X] + kx * theta[0], s_old[T_Y] + ky * theta[1], pc])
        return s, _complex_jacobian(trial_tractions, d), STICK
    sx, sy = float(np.sign(ttx)), float(np.sign(tty))
    theta0 = d.astype(complex)

    def R(X, theta=theta0):
        return _ref_residual(model, X, theta, s_old, stiffness, sx, sy)

    X = _ref_initial_guess(model, s_old, ttx, tty, kTx, kTy, p)
    for _ in range(20):
        J = _complex_jacobian(R, X)
        step = np.linalg.solve(J, -np.real(R(X.astype(complex))))
        X = X + step
        if np.all(np.abs(step) <= 1e-15 * np.maximum(np.abs(X), 1e-300)):
            break
    J = _complex_jacobian(R, X)
    Rth = _complex_jacobian(lambda th: R(X.astype(complex), th), d)
    dX = -np.linalg.solve(J, Rth)
    D[:2, :] = dX[:2, :]
    D[2, 2] = kN
    tx, ty = X[0], X[1]
    dup = np.array([ttx - tx, tty - ty]) / np.array([kTx, kTy])
    s[T_X], s[T_Y] = tx, ty
    s[UP_X] += dup[0]
    s[UP_Y] += dup[1]
    if isinstance(model, OrthotropicHardening):
        s[KAPPA_X], s[KAPPA_Y] = X[3], X[4]
    else:
        s[KAPPA] = X[3]
    s[DISSIPATION] += tx * dup[0] + ty * dup[1]
    return s, D, SLIP
