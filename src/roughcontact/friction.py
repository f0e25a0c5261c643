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

Elastic part (93)-(94): Δt = diag(k_Tx, k_Ty, k_N) Δu^e, k's per unit area, constant inputs.

Normal contact and sign convention (the one place: :func:`normal_law`)
----------------------------------------------------------------------
u_N is the normal *closure* (approach, penetration) of the interface: positive closes it.
The normal traction stored and returned is the contact *pressure* p_N = t_N ≥ 0, positive in
compression (the paper's t_N in (91), (117), (120)). With the constant stiffness used here
p_N = k_N · max(u_N, 0) (the total-displacement form of (117); contact for u_N > 0). For
u_N ≤ 0 the contact is open: p_N = 0, t_T = 0, D = 0, plastic slips and hardening frozen
(tangential motion of separated faces is neither elastic nor frictional slip). The
tabulated normal law replaces :func:`normal_law` later. An engine that uses the gap g = -u_N
(positive open) and a tension-positive normal stress σ_N = -p_N passes Δu_N = -Δg and uses
σ_N = -state[..., T_N] and S·D·S with S = diag(1, 1, -1).

Python interface
----------------
``update(model, state, du, k_N, k_Tx, k_Ty)`` -> :class:`FrictionUpdate` ``(state, D, status)``

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
  broadcastable to the point shape, finite and > 0.
* returns the new state (same shape; the tractions are ``state[..., :3]``), the consistent
  (algorithmic) tangent ``D`` (..., 3, 3) with D_ij = ∂(t_x, t_y, p_N)_i/∂(Δu_Tx, Δu_Ty, Δu_N)_j,
  and ``status`` (...,) int8: STICK = 0, SLIP = 1, OPEN = 2.

Units: any consistent set; e.g. stresses in N/mm², lengths in µm, stiffnesses in
N/(mm²·µm) (the project's K/A0); n_x, n_y, n in 1/[length] (275 /mm = 0.275 /µm).

Algorithm
---------
Elastic predictor t^tr = t_n + K_T Δu_T; if f(t^tr, κ_n, p_N,n+1) ≤ 0: stick, D = D^e (94).
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
def _normal_law(u_n, k_n):
    """THE sign convention: u_N = closure (> 0 compresses), p_N ≥ 0 pressure.
    Returns (p_N, dp_N/du_N); total form of eq. (117) with constant k_N; open for u_N ≤ 0."""
    if u_n > 0.0:
        return k_n * u_n, k_n
    return 0.0, 0.0


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
_NE = 22


@numba.njit(cache=True)
def _ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, out):
    """Backward-Euler state at (λ, r) and the partial derivatives of F = S - p and
    Φ = r - k ln(μ_y/μ_x) with respect to λ, r and the trial tractions."""
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
def _begin_update(ktx, kty, kn, s_old, du, s_new, D):
    """Shared start of both updates: copy the state, zero D, apply the normal law; for a
    closed contact return the elastic (trial) tangential tractions, eq. (93)-(94)."""
    for j in range(NSTATE):
        s_new[j] = s_old[j]
    for a in range(3):
        for b in range(3):
            D[a, b] = 0.0
    u_n = s_old[U_N] + du[2]
    p, dp = _normal_law(u_n, kn)
    s_new[U_N] = u_n
    s_new[T_N] = p
    if p <= 0.0:
        s_new[T_X] = 0.0
        s_new[T_Y] = 0.0
        return True, p, dp, 0.0, 0.0
    return False, p, dp, s_old[T_X] + ktx * du[0], s_old[T_Y] + kty * du[1]


@numba.njit(cache=True)
def _ortho_point(par, ktx, kty, kn, s_old, du, s_new, D, tol):
    """One orthotropic update (section 8.1). Returns STICK/SLIP/OPEN or _FAILED."""
    is_open, p, dp, ttx, tty = _begin_update(ktx, kty, kn, s_old, du, s_new, D)
    if is_open:
        return OPEN
    kxn = s_old[KAPPA_X]
    kyn = s_old[KAPPA_Y]
    mux, _ = _hardening(par[0], par[2], par[4], kxn)
    muy, _ = _hardening(par[1], par[3], par[5], kyn)
    s_tr = math.sqrt((ttx / mux) ** 2 + (tty / muy) ** 2)
    if s_tr - p <= 0.0:  # f ≤ 0, eq. (91): stick
        s_new[T_X] = ttx
        s_new[T_Y] = tty
        D[0, 0] = ktx
        D[1, 1] = kty
        D[2, 2] = dp
        return STICK
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
    # right-hand sides: θ = (t^tr_x, t^tr_y, p); F_p = -1, Φ_p = 0
    b1 = (wk[_E_S_TTX], wk[_E_S_TTY], -1.0)
    b2 = (wk[_E_PHI_TTX], wk[_E_PHI_TTY], 0.0)
    dth = (ktx, kty, dp)
    for j in range(3):
        dlam = -(a22 * b1[j] - a12 * b2[j]) / det
        dr = -(-a21 * b1[j] + a11 * b2[j]) / det
        dtx = wk[_E_TX_LAM] * dlam + wk[_E_TX_R] * dr
        dty = wk[_E_TY_LAM] * dlam + wk[_E_TY_R] * dr
        if j == 0:
            dtx += wk[_E_CX]
        elif j == 1:
            dty += wk[_E_CY]
        D[0, j] = dtx * dth[j]
        D[1, j] = dty * dth[j]
    D[2, 2] = dp
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
def _iso_point(par, ktx, kty, kn, s_old, du, s_new, D, tol):
    """One isotropic update (section 8.2). Returns STICK/SLIP/OPEN or _FAILED."""
    is_open, p, dp, ttx, tty = _begin_update(ktx, kty, kn, s_old, du, s_new, D)
    if is_open:
        return OPEN
    kapn = s_old[KAPPA]
    mu0, _ = _hardening(par[0], par[1], par[2], kapn)
    if math.sqrt(ttx * ttx + tty * tty) - mu0 * p <= 0.0:  # f ≤ 0, eq. (120): stick
        s_new[T_X] = ttx
        s_new[T_Y] = tty
        D[0, 0] = ktx
        D[1, 1] = kty
        D[2, 2] = dp
        return STICK
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
    # consistent tangent: F = |t| - μ_F p = 0 differentiated in λ and θ = (t^tr_x, t^tr_y, p)
    f_lam = t_lam - dmu * p * kap_lam
    fac = 1.0 - dmu * p * lam
    b = (tx * cx / t * fac, ty * cy / t * fac, -mu)
    dth = (ktx, kty, dp)
    tx_lam = -ktx * cx * tx
    ty_lam = -kty * cy * ty
    for j in range(3):
        dlam = -b[j] / f_lam
        dtx = tx_lam * dlam
        dty = ty_lam * dlam
        if j == 0:
            dtx += cx
        elif j == 1:
            dty += cy
        D[0, j] = dtx * dth[j]
        D[1, j] = dty * dth[j]
    D[2, 2] = dp
    return SLIP


@numba.njit(cache=True)
def _ortho_kernel(par, stiff, s_old, du, s_new, D, status, tol):
    for i in range(s_old.shape[0]):
        status[i] = _ortho_point(par, stiff[i, 0], stiff[i, 1], stiff[i, 2],
                                 s_old[i], du[i], s_new[i], D[i], tol)


@numba.njit(cache=True)
def _iso_kernel(par, stiff, s_old, du, s_new, D, status, tol):
    for i in range(s_old.shape[0]):
        status[i] = _iso_point(par, stiff[i, 0], stiff[i, 1], stiff[i, 2],
                               s_old[i], du[i], s_new[i], D[i], tol)


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
    """Normal pressure p_N ≥ 0 and dp_N/du_N for the total closure u_N (> 0 closes; ≤ 0 open)
    with a constant stiffness k_N (the module's single sign-convention helper; vectorised)."""
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
    (p_N = k_N u_N stored if k_N is given). ``shape`` is the point shape ((): one point)."""
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


def _prepare(state, du, k_N, k_Tx, k_Ty):
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
    for name, k in (("k_Tx", k_Tx), ("k_Ty", k_Ty), ("k_N", k_N)):
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


def update(model, state, du, k_N, k_Tx, k_Ty, *, tol=1e-12) -> FrictionUpdate:
    """Incremental update of the interface law at many integration points (numba kernel).

    Parameters
    ----------
    model : OrthotropicHardening or IsotropicHardening
    state : (..., 9) array, the state at the start of the increment (see module docstring).
    du : (..., 3) array, increment (Δu_Tx, Δu_Ty, Δu_N) of the relative displacement;
        Δu_N > 0 closes the interface.
    k_N, k_Tx, k_Ty : stiffnesses per unit area, > 0, broadcastable to the point shape.
    tol : relative Newton step tolerance of the return mapping (0 < tol ≤ 1e-6).

    Returns
    -------
    FrictionUpdate(state, D, status); state and D have the broadcast point shape.
    """
    model = _as_model(model)
    tol = float(tol)
    if not (0.0 < tol <= 1e-6):
        raise ValueError(f"tol must be in (0, 1e-6], got {tol!r}")
    shape, s_old, d, st = _prepare(state, du, k_N, k_Tx, k_Ty)
    n = s_old.shape[0]
    s_new = np.empty_like(s_old)
    D = np.empty((n, 3, 3))
    status = np.empty(n, dtype=np.int8)
    kernel = _ortho_kernel if isinstance(model, OrthotropicHardening) else _iso_kernel
    kernel(model.params(), st, s_old, d, s_new, D, status, tol)
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


def _ref_residual(model, X, theta, s_old, kTx, kTy, kN, sx, sy):
    """Primitive backward-Euler residual (complex-step capable).
    Orthotropic X = (t_x, t_y, γ, κ_x, κ_y); isotropic X = (t_x, t_y, γ, κ)."""
    dux, duy, dun = theta
    ttx = s_old[T_X] + kTx * dux
    tty = s_old[T_Y] + kTy * duy
    p = kN * (s_old[U_N] + dun)
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


def reference_update(model, state, du, k_N, k_Tx, k_Ty):
    """Slow single-point twin of :func:`update` (pure Python/NumPy/SciPy).

    Solves the primitive backward-Euler system in (t_x, t_y, γ, κ...) with the potential (98)
    written through ν_x, ν_y explicitly, by Newton with complex-step Jacobians from a nested
    Brent initial guess; the tangent is the implicit-function derivative of that system,
    again by complex steps. Returns (state (9,), D (3, 3), status)."""
    model = _as_model(model)
    s_old = np.asarray(state, dtype=float).copy()
    d = np.asarray(du, dtype=float)
    kTx, kTy, kN = float(k_Tx), float(k_Ty), float(k_N)
    s = s_old.copy()
    D = np.zeros((3, 3))
    u_n = s_old[U_N] + d[2]
    s[U_N] = u_n
    if u_n <= 0.0:
        s[T_N] = s[T_X] = s[T_Y] = 0.0
        return s, D, OPEN
    p = kN * u_n
    s[T_N] = p
    ttx, tty = s_old[T_X] + kTx * d[0], s_old[T_Y] + kTy * d[1]
    trial = s.copy()
    trial[T_X], trial[T_Y] = ttx, tty
    if limit_function(model, trial) <= 0.0:
        s[T_X], s[T_Y] = ttx, tty
        return s, np.diag([kTx, kTy, kN]), STICK
    sx, sy = float(np.sign(ttx)), float(np.sign(tty))
    theta0 = d.astype(complex)

    def R(X, theta=theta0):
        return _ref_residual(model, X, theta, s_old, kTx, kTy, kN, sx, sy)

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
