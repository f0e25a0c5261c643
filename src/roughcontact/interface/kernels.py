"""The numba kernels of the interface law (section 8 of Buczkowski & Kleiber 2009): the
tabulated normal law p_N(u_N) (:func:`closure_law`, tables of :mod:`.normal_law`) and the
friction return mapping with its consistent tangent (``_ortho_kernel``, ``_iso_kernel``;
the algorithm and the errata are in :mod:`.friction`'s docstring, which is the Python API).

Plain loops, ``njit(cache=True)``, no fastmath. The friction kernels call
:func:`closure_law`, so both live in this one file (numba's on-disk cache is invalidated only
when a kernel's own file changes; tests/test_layout.py checks that no kernel calls
a kernel of another file). Slow twins: :mod:`.reference`.

State layout (one row per integration point; the friction module re-exports the names)
-------------------------------------------------------------------------------------
T_X, T_Y tangential tractions; T_N pressure p_N ≥ 0; U_N closure u_N (> 0 closes); UP_X,
UP_Y plastic slips; KAPPA_X, KAPPA_Y accumulated axial slips (isotropic: KAPPA = KAPPA_X the
slip length); DISSIPATION ∫ t_T·du_T^p. Status codes STICK, SLIP, OPEN; internal failure codes.

Tangential forms (the last argument ``form`` of the batch kernels, an int64; friction.py's
TANGENTIAL_FORMS): FORM_END = 0 "incremental-end" t^tr = t_n + K_T(u_N,n+1) Δu_T;
FORM_START = 1 "incremental-start" t^tr = t_n + K_T(u_N,n) Δu_T; FORM_SECANT = 2 "secant"
t^tr = K_T(u_N,n+1) (u^e_T,n + Δu_T), u^e_T,n = t_n / K_T(u_N,n) (0 where K_T(u_N,n) = 0).
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = [
    "NSTATE", "T_X", "T_Y", "T_N", "U_N", "UP_X", "UP_Y", "KAPPA_X", "KAPPA_Y", "KAPPA",
    "DISSIPATION", "STICK", "SLIP", "OPEN", "FAILED", "BEYOND", "closure_law",
    "FORM_END", "FORM_START", "FORM_SECANT",
]

NSTATE = 9
T_X, T_Y, T_N, U_N, UP_X, UP_Y, KAPPA_X, KAPPA_Y, DISSIPATION = range(NSTATE)
KAPPA = KAPPA_X  # isotropic model: accumulated slip length
STICK, SLIP, OPEN = 0, 1, 2
FORM_END, FORM_START, FORM_SECANT = 0, 1, 2  # tangential forms of (93), module docstring
FAILED = -1
BEYOND = -2  # closure beyond the heavy end of a tabulated normal law
_MAXIT = 200


# ---------------------------------------------------------------------------------------------
# the tabulated normal law (normal_law.NormalLawTable.kernel_table)
# ---------------------------------------------------------------------------------------------
@numba.njit(cache=True)
def closure_law(u_n, h_ref, tab):
    """Tabulated normal law at the closure u_N [L] = h_ref − h (friction.py's convention).

    ``tab``: (n, 4) rows (h, q, q', q'') with h ascending, q = ln(W/A0) (see module doc).
    Returns (p_N, dp_N/du_N, d²p_N/du_N², beyond): p_N [unit of E*], k_N = dp_N/du_N
    [unit of E*/L], its derivative [unit of E*/L²]; ``beyond`` is True (and the values are 0)
    when h < h_min, i.e. beyond the heavy end of the table. Light-end tail and open contact as
    in the module docstring."""
    n = tab.shape[0]
    h = h_ref - u_n
    if h < tab[0, 0]:
        return 0.0, 0.0, 0.0, True
    h_light = tab[n - 1, 0]
    if h > h_light:
        # C¹ quadratic tail p = p_light z² down to open contact at z = 0
        d_light = tab[n - 1, 2]
        z = 1.0 + 0.5 * d_light * (h - h_light)
        if z <= 0.0:
            return 0.0, 0.0, 0.0, False
        p_light = math.exp(tab[n - 1, 1])
        return p_light * z * z, -p_light * d_light * z, 0.5 * p_light * d_light * d_light, False
    lo = 0
    hi = n - 1
    while hi - lo > 1:  # bisection for tab[lo, 0] <= h <= tab[lo + 1, 0]
        mid = (lo + hi) // 2
        if tab[mid, 0] <= h:
            lo = mid
        else:
            hi = mid
    width = tab[lo + 1, 0] - tab[lo, 0]
    t = (h - tab[lo, 0]) / width
    t2 = t * t
    t3 = t2 * t
    # quintic Hermite basis: G0 (value at 1; H0 = 1 − G0), H1/G1 (slopes), H2/G2 (curvatures)
    g0 = t3 * (10.0 - 15.0 * t + 6.0 * t2)
    h1 = t - t3 * (6.0 - 8.0 * t + 3.0 * t2)
    g1 = -t3 * (4.0 - 7.0 * t + 3.0 * t2)
    h2 = 0.5 * t2 * (1.0 - 3.0 * t + 3.0 * t2 - t3)
    g2 = 0.5 * t3 * (1.0 - 2.0 * t + t2)
    dg0 = 30.0 * t2 * (1.0 - 2.0 * t + t2)
    dh1 = 1.0 - t2 * (18.0 - 32.0 * t + 15.0 * t2)
    dg1 = -t2 * (12.0 - 28.0 * t + 15.0 * t2)
    dh2 = 0.5 * t * (2.0 - 9.0 * t + 12.0 * t2 - 5.0 * t3)
    dg2 = 0.5 * t2 * (3.0 - 8.0 * t + 5.0 * t2)
    ddg0 = 60.0 * t * (1.0 - 3.0 * t + 2.0 * t2)
    ddh1 = -t * (36.0 - 96.0 * t + 60.0 * t2)
    ddg1 = -t * (24.0 - 84.0 * t + 60.0 * t2)
    ddh2 = 1.0 - 9.0 * t + 18.0 * t2 - 10.0 * t3
    ddg2 = t * (3.0 - 12.0 * t + 10.0 * t2)
    jump = tab[lo + 1, 1] - tab[lo, 1]
    s0 = width * tab[lo, 2]
    s1 = width * tab[lo + 1, 2]
    c0 = width * width * tab[lo, 3]
    c1 = width * width * tab[lo + 1, 3]
    q = tab[lo, 1] + jump * g0 + s0 * h1 + s1 * g1 + c0 * h2 + c1 * g2
    dq = (jump * dg0 + s0 * dh1 + s1 * dg1 + c0 * dh2 + c1 * dg2) / width
    ddq = (jump * ddg0 + s0 * ddh1 + s1 * ddg1 + c0 * ddh2 + c1 * ddg2) / (width * width)
    p = math.exp(q)
    # u = h_ref − h: dp/du = −p q', d²p/du² = p (q'² + q'')
    return p, -p * dq, p * (dq * dq + ddq), False


@numba.njit(cache=True)
def _closure_law_array(u_n, h_ref, tab, p, k, dk, beyond):
    for i in range(u_n.shape[0]):
        p[i], k[i], dk[i], beyond[i] = closure_law(u_n[i], h_ref, tab)


# ---------------------------------------------------------------------------------------------
# numba building blocks
# ---------------------------------------------------------------------------------------------
@numba.njit(cache=True)
def _normal_law(u_n, k_n, tab, h_ref):
    """THE sign convention (module docstring): u_N = closure (> 0 compresses), p_N ≥ 0 pressure.
    Returns (p_N, dp_N/du_N, d²p_N/du_N², beyond). Empty ``tab``: total form of eq. (117) with
    constant k_N, open for u_N ≤ 0; otherwise the tabulated law (closure_law) with
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
def _begin_update(stiff, s_old, du, s_new, D, tab, h_ref, form):
    """Shared start of both updates: copy the state, zero D, apply the normal law at the end of
    the step; for a closed contact the trial tangential tractions of the tangential ``form``
    (module docstring), eq. (93)-(94). ``stiff`` = (k_Tx, k_Ty, k_N) for the constant law,
    (k_Tx/k_N, k_Ty/k_N, unused) with a table (k_T = a k_N(u_N)).
    Returns (status, p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy): k_T the stiffness of the
    return mapping, dk_T = dk_T/du_N its u_N-dependence and lv = e the lever, ∂t^tr/∂u_N = dk_T e
    (e = Δu_T end, u^e_T,n + Δu_T secant; dk_T = 0 start); status OPEN, BEYOND (the end, or
    for start/secant the start, of the step beyond the table) or STICK (= closed, to decide)."""
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
        return BEYOND, p, dp, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if p <= 0.0:
        s_new[T_X] = 0.0
        s_new[T_Y] = 0.0
        return OPEN, p, dp, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    tnx = s_old[T_X]
    tny = s_old[T_Y]
    if tab.shape[0] > 0:
        ktx = stiff[0] * dp
        kty = stiff[1] * dp
        dktx = stiff[0] * ddp
        dkty = stiff[1] * ddp
        ktx0 = ktx
        kty0 = kty
        if form != FORM_END:  # K_T(u_N,n) = a k_N(u_N,n) at the start of the step
            _, dp0, _, beyond0 = _normal_law(s_old[U_N], stiff[2], tab, h_ref)
            if beyond0:
                return BEYOND, p, dp, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
            ktx0 = stiff[0] * dp0
            kty0 = stiff[1] * dp0
            if dp0 <= 0.0:  # the start state was open: K_T,n = 0 and t_n = 0 (u^e_T,n = 0)
                tnx = 0.0
                tny = 0.0
    else:  # constant k_T: K_T(u_N,n) = K_T(u_N,n+1), all forms reduce to the end form bitwise
        ktx = stiff[0]
        kty = stiff[1]
        dktx = 0.0
        dkty = 0.0
        ktx0 = ktx
        kty0 = kty
    if form == FORM_START:  # k_T frozen at u_N,n: ∂t^tr/∂u_N = 0, return mapping with K_T(u_N,n)
        return STICK, p, dp, tnx + ktx0 * du[0], tny + kty0 * du[1], ktx0, kty0, 0.0, 0.0, 0.0, 0.0
    if form == FORM_SECANT:  # t^tr = K_T(u_N,n+1)(t_n/K_T(u_N,n) + Δu_T), written t_n (K/K_n) + K Δu_T
        ttx = ktx * du[0]
        tty = kty * du[1]
        lvx = du[0]
        lvy = du[1]
        if ktx0 > 0.0:
            ttx += tnx * (ktx / ktx0)
            lvx += tnx / ktx0
        if kty0 > 0.0:
            tty += tny * (kty / kty0)
            lvy += tny / kty0
        return STICK, p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy
    return STICK, p, dp, tnx + ktx * du[0], tny + kty * du[1], ktx, kty, dktx, dkty, du[0], du[1]


@numba.njit(cache=True)
def _stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, D):
    """Stick: t = t^tr, D = D^e (94) plus ∂t^tr/∂u_N = ∂K_T/∂u_N e (lever e of _begin_update;
    zero for constant k_T and for the start form)."""
    s_new[T_X] = ttx
    s_new[T_Y] = tty
    D[0, 0] = ktx
    D[1, 1] = kty
    D[2, 2] = dp
    if dktx != 0.0 or dkty != 0.0:
        D[0, 2] = dktx * lvx
        D[1, 2] = dkty * lvy
    return STICK


@numba.njit(cache=True)
def _assemble_tangent(sens, ktx, kty, dp, dktx, dkty, lvx, lvy, D):
    """D rows t_x, t_y from the sensitivities sens[i, m] = dt_i/dθ_m of the return map to
    θ = (t^tr_x, t^tr_y, p, k_Tx, k_Ty) by the chain rule through ∂t^tr/∂Δu_T = K_T,
    ∂t^tr/∂u_N = ∂K_T/∂u_N e (lever e of _begin_update), p(u_N), K_T(u_N); row p_N: dp/du_N."""
    for i in range(2):
        D[i, 0] = sens[i, 0] * ktx
        D[i, 1] = sens[i, 1] * kty
        D[i, 2] = sens[i, 2] * dp
        if dktx != 0.0 or dkty != 0.0:
            D[i, 2] += (sens[i, 0] * lvx + sens[i, 3]) * dktx + (sens[i, 1] * lvy + sens[i, 4]) * dkty
    D[2, 2] = dp


@numba.njit(cache=True)
def _safeguarded_step(lam, psi, dpsi, lo, hi, first, tol):
    """One step of the bracketed Newton iteration for the plastic multiplier λ ≥ 0 of both
    return mappings, on ψ(λ) increasing from ψ(0) < 0 (hi < 0: no upper bracket yet): update
    the bracket, take the Newton step when it stays inside, else bisect, else ``first`` (the
    first guess, used at λ = 0) or 2λ. Returns (λ_new, lo, hi, done)."""
    if psi < 0.0:
        lo = lam
    else:
        hi = lam
    newton = False
    cand = 0.0
    if dpsi > 0.0:
        cand = lam - psi / dpsi
        if cand > lo and (hi < 0.0 or cand < hi):
            newton = True
    if not newton:
        if hi >= 0.0:
            cand = 0.5 * (lo + hi)
        elif lam == 0.0:
            cand = first
        else:
            cand = 2.0 * lam
    done = (newton and abs(cand - lam) <= tol * cand) or \
        (hi >= 0.0 and hi - lo <= 4.0 * 2.220446049250313e-16 * hi)
    return cand, lo, hi, done


@numba.njit(cache=True)
def _ortho_point(par, stiff, s_old, du, s_new, D, tol, tab, h_ref, form):
    """One orthotropic update (section 8.1). Returns STICK/SLIP/OPEN, FAILED or BEYOND."""
    status, p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy = _begin_update(
        stiff, s_old, du, s_new, D, tab, h_ref, form)
    if status != STICK:
        return status
    kxn = s_old[KAPPA_X]
    kyn = s_old[KAPPA_Y]
    mux, _ = _hardening(par[0], par[2], par[4], kxn)
    muy, _ = _hardening(par[1], par[3], par[5], kyn)
    s_tr = math.sqrt((ttx / mux) ** 2 + (tty / muy) ** 2)
    if s_tr - p <= 0.0:  # f ≤ 0, eq. (91): stick
        return _stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, D)
    # slip: backward-Euler return mapping; ψ(λ) = p/S - 1 increases from ψ(0) < 0 to +∞
    wk = np.empty(_NE)
    r = par[6] * (math.log(muy) - math.log(mux))
    lam = 0.0
    lo = 0.0
    hi = -1.0  # no upper bracket yet
    status = FAILED
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
        first = (s / p - 1.0) / max(ktx * wk[_E_WX], kty * wk[_E_WY]) if lam == 0.0 else 0.0
        lam, lo, hi, done = _safeguarded_step(lam, psi, dpsi, lo, hi, first, tol)
        if done:
            r, fail = _ortho_solve_r(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk, 1e-14)
            if not fail:
                status = SLIP
            break
    if status == FAILED:
        return FAILED
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
    _assemble_tangent(sens, ktx, kty, dp, dktx, dkty, lvx, lvy, D)
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
def _iso_point(par, stiff, s_old, du, s_new, D, tol, tab, h_ref, form):
    """One isotropic update (section 8.2). Returns STICK/SLIP/OPEN, FAILED or BEYOND."""
    status, p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy = _begin_update(
        stiff, s_old, du, s_new, D, tab, h_ref, form)
    if status != STICK:
        return status
    kapn = s_old[KAPPA]
    mu0, _ = _hardening(par[0], par[1], par[2], kapn)
    if math.sqrt(ttx * ttx + tty * tty) - mu0 * p <= 0.0:  # f ≤ 0, eq. (120): stick
        return _stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, D)
    lam = 0.0
    lo = 0.0
    hi = -1.0
    status = FAILED
    for it in range(_MAXIT):
        tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam = _iso_eval(
            lam, ttx, tty, ktx, kty, kapn, par)
        psi = mu * p / t - 1.0
        dpsi = p * (dmu * kap_lam * t - mu * t_lam) / (t * t)
        if psi == 0.0:
            status = SLIP
            break
        first = (t / (mu * p) - 1.0) / max(ktx, kty) if lam == 0.0 else 0.0
        lam, lo, hi, done = _safeguarded_step(lam, psi, dpsi, lo, hi, first, tol)
        if done:
            status = SLIP
            break
    if status == FAILED:
        return FAILED
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
    _assemble_tangent(sens, ktx, kty, dp, dktx, dkty, lvx, lvy, D)
    return SLIP


@numba.njit(cache=True)
def _ortho_kernel(par, stiff, s_old, du, s_new, D, status, tol, tab, h_ref, form):
    for i in range(s_old.shape[0]):
        status[i] = _ortho_point(par, stiff[i], s_old[i], du[i], s_new[i], D[i], tol, tab, h_ref, form)


@numba.njit(cache=True)
def _iso_kernel(par, stiff, s_old, du, s_new, D, status, tol, tab, h_ref, form):
    for i in range(s_old.shape[0]):
        status[i] = _iso_point(par, stiff[i], s_old[i], du[i], s_new[i], D[i], tol, tab, h_ref, form)


@numba.njit(cache=True)
def _no_limit_point(par, stiff, s_old, du, s_new, D, tab, h_ref, form):
    """No friction limit: par[0] = 0 frictionless (t_T = 0, D = diag(0, 0, k_N)); par[0] = 1
    no slip (the elastic law (93)-(94) alone: the stick branch at every closed point)."""
    status, p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy = _begin_update(
        stiff, s_old, du, s_new, D, tab, h_ref, form)
    if status != STICK:
        return status
    if par[0] == 0.0:
        s_new[T_X] = 0.0
        s_new[T_Y] = 0.0
        D[2, 2] = dp
        return SLIP
    return _stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, D)


@numba.njit(cache=True)
def _no_limit_kernel(par, stiff, s_old, du, s_new, D, status, tol, tab, h_ref, form):
    for i in range(s_old.shape[0]):
        status[i] = _no_limit_point(par, stiff[i], s_old[i], du[i], s_new[i], D[i], tab, h_ref, form)
