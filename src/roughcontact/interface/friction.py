"""Zero-thickness interface friction law of section 8: orthotropic (8.1) and isotropic (8.2)
slip-hardening friction, as an incremental update for every integration point of an FE model.

Equation numbers are those of Buczkowski & Kleiber (2009). Where the printed paper is wrong or
ambiguous the corrected form is used and marked "erratum"/"reading" below (tests in
tests/interface/test_friction.py prove each one).

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

Tangential forms (``update(..., tangential=...)``, :data:`TANGENTIAL_FORMS`)
--------------------------------------------------------------------------
With a load-dependent k_T = a k_N(u_N) the incremental law (93) does not say at which u_N the
stiffness is taken, and section 9.2 (the flat punch) does not say either. Three stated
readings of the elastic (trial) tangential traction, n the last converged state:

* ``"incremental-end"`` (default): t^tr = t_n + K_T(u_N,n+1) Δu_T. The return mapping uses
  K_T(u_N,n+1); ∂t^tr/∂u_N = K_T'(u_N,n+1) Δu_T, K_T' = a d²p_N/du_N².
* ``"incremental-start"``: t^tr = t_n + K_T(u_N,n) Δu_T, k_T frozen at the start of the
  increment (the classic explicit treatment of a hypoelastic law): the return mapping uses
  K_T(u_N,n), ∂t^tr/∂u_N = 0. A point open at the start (K_T(u_N,n) = 0) has no tangential
  stiffness for the increment in which it closes (t_T = 0, stick).
* ``"secant"`` (a total elastic law): t^tr = K_T(u_N,n+1) (u^e_T,n + Δu_T) with the elastic
  tangential displacement of the last converged state u^e_T,n = t_n / K_T(u_N,n) (0 where that
  state was open, K_T(u_N,n) = 0); the return mapping uses K_T(u_N,n+1),
  ∂t^tr/∂u_N = K_T'(u_N,n+1) (u^e_T,n + Δu_T). The elastic tangential response is then path
  independent: a stick cycle of Δu_T at varying u_N returns t_T to 0 (to round-off), where the
  incremental forms keep a residual wherever k_T changed along the cycle (hypoelastic drift;
  7-9 % of the peak in tests/interface/test_tangential_forms.py).

For a constant k_T the three coincide (bit for bit: the kernel writes the secant trial as
t_n (K_T/K_T,n) + K_T Δu_T, and K_T/K_T,n = 1 exactly). Why it matters (docs/independent-studies.md, "The punch";
docs/errata.md D3): under the incremental law with 1000 N on the whole punch nothing slips (the
largest |t_T|/(μ p) is 0.98, 0.78, 0.89 in cases a, b, c on the 21-node mesh), while the secant
(total) reading lets it slip; and with k_T frozen at the start the tangential forces reverse on
unloading even without slip (time-integration error).

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
  factors a = k_T/k_N, by default also at the end of the step: the trial traction is
  t^tr = t_n + K_T(u_N) Δu_T (incremental (93); other forms in "Tangential forms") and the
  consistent tangent carries ∂K_T/∂u_N = a d²p_N/du_N² besides ∂p_N/∂u_N = k_N in the
  friction limit.

For p_N = 0 the contact is open: p_N = 0, t_T = 0, D = 0, plastic slips and hardening frozen
(tangential motion of separated faces is neither elastic nor frictional slip). An engine that
uses the gap g = -u_N (positive open) and a tension-positive normal stress σ_N = -p_N passes
Δu_N = -Δg and uses σ_N = -state[..., T_N] and S·D·S with S = diag(1, 1, -1) (:data:`OPENING_SIGN`; the FE
engine, roughcontact.fe.contact, does exactly this).

Models without a friction limit: :class:`Frictionless` (t_T ≡ 0, free sliding) and
:class:`NoSlip` (the elastic law (93)-(94) alone, a stuck interface or tangential springs),
for tangential restraints the paper leaves open (9.1).

Python interface
----------------
``update(model, state, du, k_N, k_Tx, k_Ty)`` or ``update(model, state, du, law)``
(keywords ``tol``, ``tangential``) -> :class:`FrictionUpdate` ``(state, D, status)``

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
Elastic predictor t^tr = t_n + K_T Δu_T (or another tangential form); if
f(t^tr, κ_n, p_N,n+1) ≤ 0: stick, D = D^e (94) (plus ∂K_T/∂u_N e in the u_N column with a
tabulated law, the lever e = Δu_T, 0 or u^e_T,n + Δu_T by form).
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

The batch kernel is numba (:mod:`.kernels`: ``njit(cache=True)``, plain loops, no
fastmath); the pure Python/NumPy/SciPy twin :func:`.reference.reference_update` solves the
primitive system (t_x, t_y, γ, κ...) with complex-step Jacobians for testing.

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
* Fig. 18/19 presets (:func:`roughcontact.examples.section9.fig18_preset`): ν_x = ν_y = 0.125 fixes a circular potential
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

import numpy as np

from ..validation import positive
from .kernels import (  # noqa: F401  (the state layout and status codes are part of this API)
    BEYOND, DISSIPATION, FAILED, FORM_END, FORM_SECANT, FORM_START, KAPPA, KAPPA_X, KAPPA_Y, NSTATE,
    OPEN, SLIP, STICK, T_N, T_X, T_Y, U_N, UP_X, UP_Y, _iso_kernel, _no_limit_kernel, _ortho_kernel,
)
from .normal_law import InterfaceLaw
from ..limits import describe

__all__ = [
    "NSTATE", "T_X", "T_Y", "T_N", "U_N", "UP_X", "UP_Y", "KAPPA_X", "KAPPA_Y", "KAPPA",
    "DISSIPATION", "STICK", "SLIP", "OPEN",
    "OrthotropicHardening", "IsotropicHardening", "Frictionless", "NoSlip", "FrictionUpdate",
    "OPENING_SIGN", "TANGENTIAL_FORMS",
    "normal_law", "initial_state", "update",
    "limit_function", "utilisation", "hardening_modulus", "continuum_tangent",
    "slip_angle", "traction_angle", "directional_coefficient_115",
    "directional_coefficient_beta",
]

#: S = diag(1, 1, −1): an engine's jump (slip_x, slip_y, opening) times S is this module's
#: (Δu_Tx, Δu_Ty, Δu_N closure); (t_x, t_y, p_N) times S is the tension-positive (t_x, t_y, σ_N);
#: the tangent D becomes S D S (module docstring, "Normal contact, sign convention ...").
OPENING_SIGN = np.array([1.0, 1.0, -1.0])

#: the readings of the elastic tangential law (93) with a load-dependent k_T (module docstring,
#: "Tangential forms"); the first is the default
TANGENTIAL_FORMS = ("incremental-end", "incremental-start", "secant")
_FORM_CODES = dict(zip(TANGENTIAL_FORMS, (FORM_END, FORM_START, FORM_SECANT)))


# ---------------------------------------------------------------------------------------------
# models
# ---------------------------------------------------------------------------------------------
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
            object.__setattr__(self, name, positive(name, getattr(self, name)))
        for name in ("n_x", "n_y"):
            object.__setattr__(self, name, positive(name, getattr(self, name), allow_zero=True))
        k = float(self.k)
        if not math.isfinite(k):
            raise ValueError(f"k must be finite, got {describe(self.k)}")
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
        object.__setattr__(self, "mu_m", positive("mu_m", self.mu_m))
        object.__setattr__(self, "mu_o", positive("mu_o", self.mu_o))
        object.__setattr__(self, "n", positive("n", self.n, allow_zero=True))

    def params(self) -> np.ndarray:
        return np.array([self.mu_m, self.mu_o, self.n], dtype=np.float64)

    def mu(self, kappa):
        """μ_F of (119) at the accumulated slip length κ."""
        return _mu_np(self.mu_m, self.mu_o, self.n, kappa)


@dataclass(frozen=True)
class Frictionless:
    """No tangential restraint (free sliding): t_T = 0 at every point, the normal law only.
    Status SLIP where closed (the faces slide freely), OPEN where open."""

    def params(self) -> np.ndarray:
        return np.array([0.0])


@dataclass(frozen=True)
class NoSlip:
    """The elastic tangential law (93)-(94) without a friction limit: t_T = t_T,n + K_T Δu_T at
    every closed point (status STICK), t_T = 0 where open. For a stuck interface, or tangential
    springs k_T = a k_N (e.g. Mindlin's ratio, Table 3) that never slip."""

    def params(self) -> np.ndarray:
        return np.array([1.0])


def _mu_np(mu_m, mu_o, n, kappa):
    return mu_m * (1.0 - (1.0 - mu_o) * np.exp(-n * np.asarray(kappa, dtype=float)))


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
    if not np.all(np.isfinite(np.asarray(u_N, dtype=float))):
        raise ValueError(f"u_N must be finite, got {describe(u_N)}")
    if k_N is not None and not isinstance(k_N, InterfaceLaw):
        k = np.asarray(k_N, dtype=float)
        if not np.all(np.isfinite(k) & (k > 0.0)):
            raise ValueError(f"k_N must be finite and > 0 (or an InterfaceLaw), got {describe(k_N)}")
    s = np.zeros(shape + (NSTATE,))
    s[..., U_N] = u_N
    if k_N is not None:
        s[..., T_N] = normal_law(s[..., U_N], k_N)[0]
    return s


_KERNELS = {OrthotropicHardening: _ortho_kernel, IsotropicHardening: _iso_kernel,
            Frictionless: _no_limit_kernel, NoSlip: _no_limit_kernel}


def _as_model(model):
    if type(model) in _KERNELS:
        return model
    raise TypeError("model must be an OrthotropicHardening, IsotropicHardening, Frictionless or "
                    "NoSlip instance")


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
    # writable C copies: numba types a read-only array (a broadcast view) apart from a writable
    # one, and one signature per kernel keeps its shared on-disk cache safe
    s2 = np.array(np.broadcast_to(s, shape + (NSTATE,)).reshape(n, NSTATE), order="C")
    d2 = np.array(np.broadcast_to(d, shape + (3,)).reshape(n, 3), order="C")
    st = np.empty((n, 3))
    for j, a in enumerate(stiff):
        st[:, j] = np.broadcast_to(a, shape).reshape(n)
    return shape, s2, d2, st


def update(model, state, du, k_N, k_Tx=None, k_Ty=None, *, tol=1e-12,
           tangential="incremental-end") -> FrictionUpdate:
    """Incremental update of the interface law at many integration points (numba kernel).

    Parameters
    ----------
    model : OrthotropicHardening, IsotropicHardening, Frictionless or NoSlip
    state : (..., 9) array, the state at the start of the increment (see module docstring).
    du : (..., 3) array, increment (Δu_Tx, Δu_Ty, Δu_N) of the relative displacement;
        Δu_N > 0 closes the interface.
    k_N, k_Tx, k_Ty : stiffnesses per unit area, > 0, broadcastable to the point shape;
        or k_N an :class:`~roughcontact.interface.InterfaceLaw` (tabulated p_N(u_N), k_N(u_N),
        k_T = a k_N(u_N); then no k_Tx, k_Ty). See "Normal contact, sign convention and
        reference state" in the module docstring.
    tol : relative Newton step tolerance of the return mapping (0 < tol ≤ 1e-6).
    tangential : one of :data:`TANGENTIAL_FORMS`, the reading of (93) with a load-dependent
        k_T (module docstring, "Tangential forms"); all coincide for constant stiffnesses.

    Returns
    -------
    FrictionUpdate(state, D, status); state and D have the broadcast point shape.

    Raises ValueError for bad input, for closures beyond the heavy end of a tabulated law and
    for increments or stiffnesses whose trial tractions overflow (no non-finite state returned).
    """
    model = _as_model(model)
    if not isinstance(tangential, str) or tangential not in _FORM_CODES:
        raise ValueError(f"tangential must be one of {', '.join(TANGENTIAL_FORMS)}, got {describe(tangential)}")
    tol = float(tol)
    if not (0.0 < tol <= 1e-6):
        raise ValueError(f"tol must be in (0, 1e-6], got {describe(tol)}")
    stiffness, tab, h_ref = _stiffness_inputs(k_N, k_Tx, k_Ty)
    shape, s_old, d, st = _prepare(state, du, stiffness)
    n = s_old.shape[0]
    s_new = np.empty_like(s_old)
    D = np.empty((n, 3, 3))
    status = np.empty(n, dtype=np.int8)
    _KERNELS[type(model)](model.params(), st, s_old, d, s_new, D, status, tol, tab, h_ref,
                          np.int64(_FORM_CODES[tangential]))
    if np.any(status == BEYOND):
        bad = np.flatnonzero(status == BEYOND)
        u_bad = max(s_new[bad[0], U_N], s_old[bad[0], U_N])  # start or end of the increment
        raise ValueError(
            f"u_N = {u_bad:g} at points {bad[:10].tolist()} exceeds the heavy end of "
            f"the tabulated normal law (u_max = {k_N.u_max:g}, p_max = {k_N.table.p_max:g}); "
            "rebuild the table with a larger p_max")
    overflow = ~(np.all(np.isfinite(s_new), axis=1) & np.all(np.isfinite(D), axis=(1, 2)))
    if np.any(overflow):
        bad = np.flatnonzero(overflow)
        raise ValueError(
            f"the update overflows double precision at points {bad[:10].tolist()} (stiffness "
            f"{st[bad[0]].tolist()}, increment {d[bad[0]].tolist()}): the trial tractions "
            "k_T·Δu_T, k_N·u_N are not finite; reduce the increment or the stiffness")
    if np.any(status == FAILED):
        bad = np.flatnonzero(status == FAILED)
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


def utilisation(model, state):
    """How much of the friction limit the tangential traction uses [1]: (f + p_N)/p_N of (91)
    (√((t_x/μ_x)² + (t_y/μ_y)²)/p_N) or (120) (|t_T|/(μ p_N)); 1 on the limit surface (slip),
    < 1 inside (stick). Points with p_N ≤ 0 (open) have no limit: they are reported as 0."""
    if not isinstance(model, (OrthotropicHardening, IsotropicHardening)):
        raise TypeError("utilisation needs a friction limit: an OrthotropicHardening or IsotropicHardening model")
    s = np.asarray(state, dtype=float)
    p = s[..., T_N]
    closed = p > 0.0
    ratio = (limit_function(model, s) + p) / np.where(closed, p, 1.0)
    return np.where(closed, ratio, 0.0)


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
