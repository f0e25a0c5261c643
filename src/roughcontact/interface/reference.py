"""Slow twins of the interface kernels (:mod:`.kernels`), for the tests: the tabulated normal
law as power-basis polynomials (:func:`reference_closure_law`) and the friction update as the
primitive backward-Euler system (t_x, t_y, γ, κ…) solved with complex-step Jacobians
(:func:`reference_update`), one point at a time, for each tangential form of (93)
(friction.py, "Tangential forms"; written here from their definitions, not from the kernel's
arrangement). Pure Python / NumPy / SciPy.
"""

from __future__ import annotations

import math

import numpy as np

from .friction import TANGENTIAL_FORMS, OrthotropicHardening, _as_model, limit_function
from .kernels import (
    DISSIPATION, KAPPA, KAPPA_X, KAPPA_Y, OPEN, SLIP, STICK, T_N, T_X, T_Y, U_N, UP_X, UP_Y,
)
from .normal_law import InterfaceLaw, _hermite_power_coefficients
from ..limits import describe

__all__ = ["reference_closure_law", "reference_update"]

def reference_closure_law(u_n, h_ref, tab):
    """Slow twin of :func:`closure_law` for one (real or complex) closure u_N: (p_N, k_N), with
    the interval chosen by the real part and q as a power-basis polynomial (Horner), so that
    complex steps give exact derivatives. Raises ValueError beyond the heavy end."""
    tab = np.asarray(tab, dtype=float)
    h = h_ref - u_n
    hr = float(np.real(h))
    if hr < tab[0, 0]:
        raise ValueError(f"h = {describe(hr)} is beyond the heavy end of the table (h_min = {describe(tab[0, 0])})")
    if hr > tab[-1, 0]:
        p_light, d_light = math.exp(tab[-1, 1]), tab[-1, 2]
        z = 1.0 + 0.5 * d_light * (h - tab[-1, 0])
        if np.real(z) <= 0.0:
            return 0.0 * h, 0.0 * h
        return p_light * z * z, -p_light * d_light * z
    i = min(int(np.searchsorted(tab[:, 0], hr, side="right")) - 1, tab.shape[0] - 2)
    width = tab[i + 1, 0] - tab[i, 0]
    coef = _hermite_power_coefficients(tab[i:i + 2])[0]
    t = (h - tab[i, 0]) / width
    q = np.polyval(coef[::-1], t)
    dq = np.polyval(np.polyder(coef[::-1]), t) / width
    p = np.exp(q)
    return p, -p * dq


def _ref_mu(mu_m, mu_o, n, kappa):
    return mu_m * (1.0 - (1.0 - mu_o) * np.exp(-n * kappa))  # eq. (89)/(90)/(119)


def _ref_trial(tangential, s_old, stiffness):
    """θ = (Δu_Tx, Δu_Ty, Δu_N) -> (t^tr_x, t^tr_y, p_N, K_Tx, K_Ty) of the tangential form
    (complex-step capable): the trial tractions and the stiffness the return mapping uses.
    ``stiffness(u_N)`` -> (p_N, k_N, k_Tx, k_Ty); K_T(u_N,n) from the start closure (it raises
    beyond the table); an open start state (K_T(u_N,n) = 0) has t_n = 0 and u^e_T,n = 0."""
    if tangential not in TANGENTIAL_FORMS:
        raise ValueError(f"tangential must be one of {', '.join(TANGENTIAL_FORMS)}, got {describe(tangential)}")
    u0 = s_old[U_N]
    t_n = np.array([s_old[T_X], s_old[T_Y]])
    if tangential != "incremental-end":
        k_n = np.array([float(np.real(k)) for k in stiffness(u0)[2:]])  # K_T(u_N,n)
        t_n = np.where(k_n > 0.0, t_n, 0.0)
        ue_n = np.where(k_n > 0.0, t_n / np.where(k_n > 0.0, k_n, 1.0), 0.0)  # u^e_T,n = t_n/K_T,n

    def trial(theta):
        p, _, kTx, kTy = stiffness(u0 + theta[2])
        k_end = np.array([kTx, kTy])
        du_T = np.asarray(theta[:2])
        if tangential == "incremental-end":  # t^tr = t_n + K_T(u_N,n+1) Δu_T, eq. (93)
            tt, k = t_n + k_end * du_T, k_end
        elif tangential == "incremental-start":  # t^tr = t_n + K_T(u_N,n) Δu_T
            tt, k = t_n + k_n * du_T, k_n + 0.0 * du_T
        else:  # secant: t^tr = K_T(u_N,n+1) (u^e_T,n + Δu_T)
            tt, k = k_end * (ue_n + du_T), k_end
        return tt[0], tt[1], p, k[0], k[1]
    return trial


def _ref_residual(model, X, theta, s_old, trial, sx, sy):
    """Primitive backward-Euler residual (complex-step capable).
    Orthotropic X = (t_x, t_y, γ, κ_x, κ_y); isotropic X = (t_x, t_y, γ, κ).
    ``trial(θ)`` -> (t^tr_x, t^tr_y, p_N, K_Tx, K_Ty) of the tangential form (_ref_trial)."""
    ttx, tty, p, kTx, kTy = trial(theta)
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
    (interface.reference.reference_closure_law, k_T = a k_N)."""
    if isinstance(k_N, InterfaceLaw):
        tab, h_ref, (ax, ay) = k_N.kernel_data()

        def stiffness(u):
            p, k = reference_closure_law(u, h_ref, tab)
            return p, k, ax * k, ay * k
        return stiffness
    kN, kTx, kTy = float(k_N), float(k_Tx), float(k_Ty)
    return lambda u: (kN * u, kN, kTx, kTy)


def reference_update(model, state, du, k_N, k_Tx=None, k_Ty=None, *, tangential="incremental-end"):
    """Slow single-point twin of :func:`update` (pure Python/NumPy/SciPy), with the same
    stiffness inputs (constants or an InterfaceLaw as ``k_N``) and tangential forms.

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
    p, kN = (float(np.real(v)) for v in stiffness(u_n)[:2])
    if p <= 0.0:  # open (constant law: u_N ≤ 0)
        s[T_N] = s[T_X] = s[T_Y] = 0.0
        return s, D, OPEN
    s[T_N] = p
    trial = _ref_trial(tangential, s_old, stiffness)
    ttx, tty, _, kTx, kTy = (float(np.real(v)) for v in trial(d))
    s_tr = s.copy()
    s_tr[T_X], s_tr[T_Y] = ttx, tty
    if limit_function(model, s_tr) <= 0.0:
        s[T_X], s[T_Y] = ttx, tty

        def trial_tractions(theta):
            return np.array(trial(theta)[:3])
        return s, _complex_jacobian(trial_tractions, d), STICK
    sx, sy = float(np.sign(ttx)), float(np.sign(tty))
    theta0 = d.astype(complex)

    def R(X, theta=theta0):
        return _ref_residual(model, X, theta, s_old, trial, sx, sy)

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
