"""Interface friction law of section 8 (roughcontact.interface.friction): return mapping, consistent
tangent, the paper's identities (89), (115)-(118), (105)/(107)/(123) and the errata.

Units in these tests: stresses N/mm², lengths µm, stiffnesses N/(mm²·µm).
"""

import math

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.interface import friction as fr
from roughcontact.interface.reference import reference_update
from roughcontact.interface import InterfaceLaw, NormalLawTable

KN, KTX, KTY = 100.0, 70.0, 90.0
UN0 = 0.05  # closure -> p_N = 5 N/mm²
P0 = KN * UN0

ORTHO = fr.OrthotropicHardening(0.3, 0.5, mu_o_x=0.6, mu_o_y=0.7, n_x=20.0, n_y=10.0, k=0.5)
ORTHO_K1 = fr.OrthotropicHardening(0.3, 0.5, mu_o_x=0.6, mu_o_y=0.7, n_x=20.0, n_y=10.0, k=1.0)
ORTHO_K0 = fr.OrthotropicHardening(0.3, 0.5, mu_o_x=0.6, mu_o_y=0.7, n_x=20.0, n_y=10.0, k=0.0)
ISO = fr.IsotropicHardening(0.4, mu_o=0.6, n=15.0)
MODELS = {"ortho": ORTHO, "ortho_k1": ORTHO_K1, "iso": ISO}

# elastic-limit tangential displacement (initial μ ~ 0.2-0.35, p = 5): ~0.02 µm
DLIM = 0.3 * 0.6 * P0 / KTX


def upd(model, state, du, kN=KN, kTx=KTX, kTy=KTY):
    return fr.update(model, state, np.asarray(du, float), kN, kTx, kTy)


def fd_tangent(model, state, du, h=1e-7, law=None):
    """Central differences of the updated tractions (constant stiffnesses or ``law``)."""
    def tractions(d):
        return (upd(model, state, d) if law is None else fr.update(model, state, d, law)).tractions

    D = np.zeros((3, 3))
    for j in range(3):
        e = np.zeros(3)
        e[j] = h
        D[:, j] = (tractions(du + e) - tractions(du - e)) / (2 * h)
    return D


def preloaded(model):
    """A hardened state in the (-, +) quadrant, after a slip path."""
    s = fr.initial_state(u_N=UN0, k_N=KN)
    for du in ([0.03, 0.04, 0.0], [-0.08, 0.01, 0.0]):
        s = upd(model, s, du).state
    return s


# ---------------------------------------------------------------------------------------------
# consistent tangent vs finite differences
# ---------------------------------------------------------------------------------------------
SLIP_INCREMENTS = [[0.03, -0.05, 0.001], [-0.06, 0.01, -0.002], [1e-3, 0.07, 0.003],
                   [-2.0, -1.5, 0.0]]  # the last one ~100x the elastic limit
STICK_INCREMENTS = [[0.004, 0.002, 0.0], [-0.003, 0.001, 0.002]]


@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("start", ["virgin", "preloaded"])
def test_tangent_matches_finite_differences_slip(name, start):
    model = MODELS[name]
    s = fr.initial_state(u_N=UN0, k_N=KN) if start == "virgin" else preloaded(model)
    for du in SLIP_INCREMENTS:
        du = np.array(du)
        r = upd(model, s, du)
        assert r.status == fr.SLIP
        err = np.abs(r.D - fd_tangent(model, s, du)).max() / np.abs(r.D).max()
        assert err <= 1e-6, (du, err)
        assert r.D[2, 2] == KN and r.D[2, 0] == 0.0 and r.D[2, 1] == 0.0


@pytest.mark.parametrize("name", list(MODELS))
def test_tangent_matches_finite_differences_stick(name):
    model = MODELS[name]
    for s in (fr.initial_state(u_N=UN0, k_N=KN), preloaded(model)):
        for du in STICK_INCREMENTS:
            du = np.array(du)
            if s[fr.KAPPA_X] > 0:  # unload from the preloaded sliding state
                du = du - np.r_[0.3 * s[fr.T_X] / KTX, 0.3 * s[fr.T_Y] / KTY, 0.0]
            r = upd(model, s, du)
            assert r.status == fr.STICK
            np.testing.assert_array_equal(r.D, np.diag([KTX, KTY, KN]))
            err = np.abs(r.D - fd_tangent(model, s, du)).max() / KN
            assert err <= 1e-6


# ---------------------------------------------------------------------------------------------
# limit surface, dissipation
# ---------------------------------------------------------------------------------------------
def random_path(rng, nsteps, scale):
    ang = rng.uniform(0, 2 * np.pi, nsteps)
    mag = scale * rng.choice([0.3, 1.0, 10.0, 100.0], nsteps)
    dun = rng.uniform(-0.2, 0.2, nsteps) * UN0
    return np.c_[mag * np.cos(ang), mag * np.sin(ang), dun]


@pytest.mark.parametrize("name", list(MODELS) + ["ortho_soft"])
def test_tractions_stay_on_limit_surface(name):
    model = MODELS.get(name) or fr.OrthotropicHardening(0.3, 0.5, 1.5, 1.3, 20.0, 10.0, k=0.5)
    rng = np.random.default_rng(1)
    # 64 independent points, 40 steps each, increments up to 100x the elastic limit
    s = fr.initial_state(64, u_N=UN0, k_N=KN)
    worst = 0.0
    nslip = 0
    for _ in range(40):
        du = random_path(rng, 64, DLIM)
        r = upd(model, s, du)
        f = fr.limit_function(model, r.state)
        slip = r.status == fr.SLIP
        nslip += slip.sum()
        assert np.all(f[r.status == fr.STICK] <= 1e-12 * r.state[r.status == fr.STICK, fr.T_N])
        worst = max(worst, np.abs(f[slip]).max(initial=0.0))
        s = r.state
    assert nslip > 500
    assert worst <= 1e-10
    assert worst <= 1e-14 * 1.3 * P0


@pytest.mark.parametrize("name", list(MODELS))
def test_single_huge_increment_on_surface(name):
    model = MODELS[name]
    s = fr.initial_state(u_N=UN0, k_N=KN)
    for fac in (3.0, 10.0, 100.0, 1e4):
        r = upd(model, s, [fac * DLIM * 0.6, -fac * DLIM * 0.8, 0.0])
        assert r.status == fr.SLIP
        assert abs(fr.limit_function(model, r.state)) <= 1e-10


@pytest.mark.parametrize("name", list(MODELS))
def test_dissipation_nonnegative(name):
    model = MODELS[name]
    rng = np.random.default_rng(2)
    s = fr.initial_state(32, u_N=UN0, k_N=KN)
    for _ in range(30):
        r = upd(model, s, random_path(rng, 32, DLIM))
        dup = r.state[:, fr.UP_X:fr.UP_Y + 1] - s[:, fr.UP_X:fr.UP_Y + 1]
        work = np.einsum("ij,ij->i", r.state[:, :2], dup)  # t_T · Δu_T^p (Table 5's integrand)
        assert np.all(work >= 0.0)
        np.testing.assert_allclose(r.state[:, fr.DISSIPATION] - s[:, fr.DISSIPATION], work,
                                   rtol=1e-12, atol=1e-14 * r.state[:, fr.DISSIPATION].max())
        # accumulated slips grow by |Δu^p| (axial for 8.1, length for 8.2)
        dk = r.state[:, fr.KAPPA_X:fr.KAPPA_Y + 1] - s[:, fr.KAPPA_X:fr.KAPPA_Y + 1]
        expect = np.abs(dup) if name != "iso" else np.c_[np.hypot(*dup.T), 0 * dup[:, 0]]
        np.testing.assert_allclose(dk, expect, rtol=1e-12, atol=1e-14 * r.state[:, fr.KAPPA_X:].max())
        s = r.state


# ---------------------------------------------------------------------------------------------
# flow rule: associated k = 1, isotropic μ, deviation angle (118), (115)
# ---------------------------------------------------------------------------------------------
def slip_and_traction(model, s, du):
    r = upd(model, s, du)
    assert r.status == fr.SLIP
    dup = r.state[fr.UP_X:fr.UP_Y + 1] - s[fr.UP_X:fr.UP_Y + 1]
    return r, dup, r.state[:2]


def test_k1_gives_associated_rule():
    s = preloaded(ORTHO_K1)
    for du in SLIP_INCREMENTS:
        r, dup, t = slip_and_traction(ORTHO_K1, s, np.array(du))
        mux, muy = ORTHO_K1.mu(r.state[fr.KAPPA_X], r.state[fr.KAPPA_Y])
        grad = np.array([t[0] / mux ** 2, t[1] / muy ** 2])  # ∂f/∂t, eq. (106)
        sin = (dup[0] * grad[1] - dup[1] * grad[0]) / (np.linalg.norm(dup) * np.linalg.norm(grad))
        assert abs(sin) <= 1e-12
        assert dup @ grad > 0
    # k = 0.5 is not associated: same check fails clearly
    r, dup, t = slip_and_traction(ORTHO, s, np.array(SLIP_INCREMENTS[0]))
    mux, muy = ORTHO.mu(r.state[fr.KAPPA_X], r.state[fr.KAPPA_Y])
    grad = np.array([t[0] / mux ** 2, t[1] / muy ** 2])
    assert abs(dup[0] * grad[1] - dup[1] * grad[0]) / (np.linalg.norm(dup) * np.linalg.norm(grad)) > 1e-2


def test_isotropic_friction_gives_alpha_equal_beta():
    # 8.1 with μ_x = μ_y (no hardening), any k, anisotropic stiffness
    m = fr.OrthotropicHardening(0.4, 0.4, k=0.7)
    s = fr.initial_state(u_N=UN0, k_N=KN)
    # 8.2 (130): circular potential, α = β whatever k_Tx/k_Ty (the "α ≠ β" remark is wrong)
    for model in (m, ISO):
        for du in SLIP_INCREMENTS:
            r, dup, t = slip_and_traction(model, s, np.array(du))
            da = fr.slip_angle(dup) - fr.traction_angle(t)
            assert abs(math.remainder(da, 2 * math.pi)) <= 1e-12


def test_deviation_angle_eq118():
    """tan β = tan α (ν_y/ν_x)², ν_y/ν_x = (μ_y/μ_x)^k at the end of the step (118)."""
    s = fr.initial_state(u_N=UN0, k_N=KN)
    du = np.array([0.05, 0.05, 0.0])
    devs = {}
    for model in (ORTHO_K0, ORTHO, ORTHO_K1):
        r, dup, t = slip_and_traction(model, s, du)
        mux, muy = model.mu(r.state[fr.KAPPA_X], r.state[fr.KAPPA_Y])
        rho = (muy / mux) ** model.k
        a, b = fr.slip_angle(dup), fr.traction_angle(t)
        assert math.tan(b) == pytest.approx(math.tan(a) * rho ** 2, rel=1e-12)
        devs[model.k] = math.degrees(a - b)
    # circle potential: no deviation; deviation grows with k (μ_y > μ_x: slip turns to x)
    assert abs(devs[0.0]) <= 1e-12
    assert 0 < -devs[0.5] < -devs[1.0]
    assert devs[0.5] == pytest.approx(-12.0, abs=2.0)
    assert devs[1.0] == pytest.approx(-23.0, abs=3.0)


def test_directional_coefficient_eq115():
    """(115)-(116) with α the slip angle puts t on the ellipse only for k = 1; in general the
    magnitude is p μ_β (erratum)."""
    s = fr.initial_state(u_N=UN0, k_N=KN)
    du = np.array([0.03, 0.05, 0.0])
    for model in (ORTHO_K1, ORTHO_K0):
        r, dup, t = slip_and_traction(model, s, du)
        mux, muy = model.mu(r.state[fr.KAPPA_X], r.state[fr.KAPPA_Y])
        ratio = np.linalg.norm(t) / r.state[fr.T_N]
        a, b = fr.slip_angle(dup), fr.traction_angle(t)
        assert ratio == pytest.approx(fr.directional_coefficient_beta(mux, muy, b), rel=1e-13)
        mu115 = fr.directional_coefficient_115(mux, muy, a)
        if model.k == 1.0:
            assert ratio == pytest.approx(mu115, rel=1e-13)
        else:
            assert abs(mu115 / ratio - 1) > 0.05


# ---------------------------------------------------------------------------------------------
# hardening: H = 0 for constant μ, (89)/(119) on monotone paths, continuum tangent (105)/(107)
# ---------------------------------------------------------------------------------------------
def test_constant_mu_gives_zero_H():
    cases = [fr.OrthotropicHardening(0.3, 0.5, k=0.5),  # μ_o = 1
             fr.OrthotropicHardening(0.3, 0.5, 0.6, 0.7, 0.0, 0.0, k=0.5),  # n = 0
             fr.IsotropicHardening(0.4), fr.IsotropicHardening(0.4, 0.6, 0.0)]
    for model in cases:
        r = upd(model, fr.initial_state(u_N=UN0, k_N=KN), [0.05, -0.03, 0.0])
        assert fr.hardening_modulus(model, r.state) == 0.0
        mu = (model.mu_m_x * model.mu_o_x if hasattr(model, "k") else model.mu_m * model.mu_o)
        assert fr.limit_function(model, r.state) == pytest.approx(0.0, abs=1e-14)
        assert mu > 0
    for model in (ORTHO, ISO):
        r = upd(model, fr.initial_state(u_N=UN0, k_N=KN), [0.05, -0.03, 0.0])
        assert fr.hardening_modulus(model, r.state) < 0.0  # paper's sign: H < 0 hardens


@pytest.mark.parametrize("nsteps", [1, 7])
def test_monotone_path_reproduces_eq89(nsteps):
    from scipy.optimize import brentq

    m = ORTHO
    ux_total = 0.4
    s = fr.initial_state(u_N=UN0, k_N=KN)
    for _ in range(nsteps):
        s = upd(m, s, [ux_total / nsteps, 0.0, 0.0]).state

    def eq(up):  # k_Tx (u_x - u^p) = p μ_x(u^p), μ_x from (89)
        return KTX * (ux_total - up) - P0 * m.mu_m_x * (1 - (1 - m.mu_o_x) * math.exp(-m.n_x * up))

    up = brentq(eq, 0.0, ux_total, xtol=1e-16, rtol=1e-15)
    assert s[fr.UP_X] == pytest.approx(up, rel=1e-12)
    assert s[fr.KAPPA_X] == pytest.approx(up, rel=1e-12)
    assert s[fr.T_X] / P0 == pytest.approx(
        m.mu_m_x * (1 - (1 - m.mu_o_x) * math.exp(-m.n_x * up)), rel=1e-12)  # eq. (89)
    assert s[fr.T_Y] == 0.0 and s[fr.UP_Y] == 0.0 and s[fr.KAPPA_Y] == 0.0
    # isotropic model (119) along a 30° straight path with k_Tx = k_Ty
    iso = ISO
    d = np.array([math.cos(0.5236), math.sin(0.5236)])
    s = fr.initial_state(u_N=UN0, k_N=KN)
    for _ in range(nsteps):
        s = upd(iso, s, np.r_[ux_total / nsteps * d, 0.0], kTy=KTX).state
    up = brentq(lambda u: KTX * (ux_total - u) - P0 * iso.mu_m * (1 - (1 - iso.mu_o) * math.exp(-iso.n * u)),
                0.0, ux_total, xtol=1e-16, rtol=1e-15)
    assert s[fr.KAPPA] == pytest.approx(up, rel=1e-12)
    assert np.hypot(s[fr.T_X], s[fr.T_Y]) / P0 == pytest.approx(
        iso.mu_m * (1 - (1 - iso.mu_o) * math.exp(-iso.n * up)), rel=1e-12)  # eq. (119)


@pytest.mark.parametrize("name", list(MODELS))
def test_algorithmic_tangent_tends_to_continuum_105(name):
    """(105)/(107)/(123) with the corrected H is the limit of the consistent tangent for a
    vanishing slip increment; finite steps differ at first order in the increment."""
    model = MODELS[name]
    s = preloaded(model)
    Dc = fr.continuum_tangent(model, s, KN, KTX, KTY)
    diffs = []
    for eps in (1e-2, 1e-4, 1e-6):
        du = np.r_[eps * s[:2] / np.array([KTX, KTY]), 0.0]
        r = upd(model, s, du)
        assert r.status == fr.SLIP
        diffs.append(np.abs(r.D - Dc).max() / np.abs(Dc).max())
    assert diffs[-1] <= 1e-5
    assert 1e-4 < diffs[0] < 0.1
    assert diffs[0] / diffs[1] == pytest.approx(100, rel=0.1)


def paper_107(c, d, H, kN, kTx, kTy):
    """(107)/(123) entry by entry as printed."""
    cx, cy, cz = c
    dx, dy, dz = d
    A = kTx * cx * dx + kTy * cy * dy + kN * cz * dz  # eq. (108)
    M = np.array([
        [kTx * (kN * cz * dz + kTy * cy * dy - H), -kTx * kTy * cy * dx, -kTx * kN * cz * dx],
        [-kTx * kTy * cx * dy, kTy * (kTx * cx * dx + kN * cz * dz - H), -kTy * kN * cz * dy],
        [-kTx * kN * cx * dz, -kTy * kN * cy * dz, kN * (kTx * cx * dx + kTy * cy * dy - H)]])
    return M / (A - H)


def test_printed_107_equals_105():
    for model in (ORTHO, ISO):
        s = preloaded(model)
        c, d, H = fr._gradients(model, s)
        np.testing.assert_allclose(paper_107(c, d, H, KN, KTX, KTY),
                                   fr.continuum_tangent(model, s, KN, KTX, KTY), rtol=1e-13, atol=1e-12)


def test_erratum_110_sign_for_negative_traction():
    """(110) as printed (signed d_x) is the onset tangent only for t_x, t_y ≥ 0."""
    s = preloaded(ORTHO)
    assert s[fr.T_X] < 0 < s[fr.T_Y]
    c, d, H = fr._gradients(ORTHO, s)
    mux, muy = ORTHO.mu(s[fr.KAPPA_X], s[fr.KAPPA_Y])
    dmux = ORTHO.n_x * ORTHO.mu_m_x * (1 - ORTHO.mu_o_x) * math.exp(-ORTHO.n_x * s[fr.KAPPA_X])
    dmuy = ORTHO.n_y * ORTHO.mu_m_y * (1 - ORTHO.mu_o_y) * math.exp(-ORTHO.n_y * s[fr.KAPPA_Y])
    S = math.hypot(s[0] / mux, s[1] / muy)
    H_printed = -(s[0] ** 2 * dmux * d[0] / (mux ** 3 * S) + s[1] ** 2 * dmuy * d[1] / (muy ** 3 * S))
    du = np.r_[1e-7 * s[:2] / np.array([KTX, KTY]), 0.0]
    D_alg = upd(ORTHO, s, du).D
    scale = np.abs(D_alg).max()
    assert np.abs(paper_107(c, d, H, KN, KTX, KTY) - D_alg).max() / scale <= 1e-5
    assert np.abs(paper_107(c, d, H_printed, KN, KTX, KTY) - D_alg).max() / scale > 1e-2


def test_erratum_126_sign():
    """(126)/(131) print H = +t_N μ_F' (...); the consistent onset tangent needs H = -p μ_F'
    (from (125) with ∂f/∂μ_F = -t_N), with no k_T-dependent factor."""
    kty = 3.0 * KTX  # strongly anisotropic tangential stiffness
    s = fr.initial_state(u_N=UN0, k_N=KN)
    for du in ([0.05, 0.03, 0.0], [0.02, 0.05, 0.0]):  # slide into the first quadrant
        s = upd(ISO, s, du, kTy=kty).state
    assert s[fr.T_X] > 0 and s[fr.T_Y] > 0
    c, d, H = fr._gradients(ISO, s)
    p, kap = s[fr.T_N], s[fr.KAPPA]
    dmu = ISO.n * ISO.mu_m * (1 - ISO.mu_o) * math.exp(-ISO.n * kap)
    al = fr.traction_angle(s[:2])  # α = β for the circular potential
    H126 = p * dmu * (KTX * math.cos(al) + kty * math.tan(al) * math.sin(al)) / math.sqrt(
        kty ** 2 * math.tan(al) ** 2 + KTX ** 2)
    assert H == pytest.approx(-p * dmu, rel=1e-15) and H < 0 < H126
    assert abs(-H126 / H - 1) > 0.03  # the k_T-dependent bracket of (126) is not 1
    du = np.r_[1e-7 * s[:2] / np.array([KTX, kty]), 0.0]
    D_alg = upd(ISO, s, du, kTy=kty).D
    scale = np.abs(D_alg).max()
    err = {h: np.abs(paper_107(c, d, h, KN, KTX, kty) - D_alg).max() / scale
           for h in (H, H126, -H126)}
    assert err[H] <= 1e-5
    assert err[H126] > 1e-2
    assert err[-H126] > 20 * err[H], err


# ---------------------------------------------------------------------------------------------
# objectivity, kernel vs reference twin, batching, normal contact, validation, presets
# ---------------------------------------------------------------------------------------------
SWAP = [1, 0, 2, 3, 5, 4, 7, 6, 8]


def test_objectivity_under_xy_swap():
    rng = np.random.default_rng(3)
    m = ORTHO
    ms = m.swapped()
    s = fr.initial_state(16, u_N=UN0, k_N=KN)
    for _ in range(15):
        du = random_path(rng, 16, DLIM)
        r = upd(m, s, du)
        rs = upd(ms, s[:, SWAP], du[:, [1, 0, 2]], kTx=KTY, kTy=KTX)
        np.testing.assert_allclose(rs.state, r.state[:, SWAP], rtol=1e-13, atol=1e-16)
        np.testing.assert_allclose(rs.D, r.D[:, [1, 0, 2]][:, :, [1, 0, 2]], rtol=1e-12, atol=1e-12)
        s = r.state
    swap_iso = [1, 0, 2, 3, 5, 4, 6, 7, 8]  # κ (slot 6) is a scalar in 8.2
    s = fr.initial_state(16, u_N=UN0, k_N=KN)
    for _ in range(15):
        du = random_path(rng, 16, DLIM)
        r = upd(ISO, s, du)
        rs = upd(ISO, s[:, swap_iso], du[:, [1, 0, 2]], kTx=KTY, kTy=KTX)
        np.testing.assert_allclose(rs.state, r.state[:, swap_iso], rtol=1e-13, atol=1e-16)
        np.testing.assert_allclose(rs.D, r.D[:, [1, 0, 2]][:, :, [1, 0, 2]], rtol=1e-12, atol=1e-12)
        s = r.state


def twin_cases():
    rng = np.random.default_rng(4)
    models = [ORTHO, ORTHO_K1, ORTHO_K0, ISO,
              fr.OrthotropicHardening(0.25, 0.6, 0.5, 0.9, 40.0, 5.0, k=2.0),
              fr.OrthotropicHardening(0.3, 0.5, 1.4, 1.2, 20.0, 10.0, k=0.5),  # softening
              fr.IsotropicHardening(0.3, 1.3, 10.0)]
    cases = []
    for i in range(42):
        model = models[i % len(models)]
        s = fr.initial_state(u_N=UN0, k_N=KN)
        for du in random_path(rng, 3, DLIM):
            s = upd(model, s, du).state
        du = random_path(rng, 1, DLIM)[0]
        if i % 14 == 13:
            du[2] = -2 * s[fr.U_N]  # opens
        cases.append((model, s, du))
    return cases


def test_tangent_at_zero_trial_component_is_one_sided_average():
    """t_x^tr = 0 is a kink of κ_x = κ_x,n + |Δu_x^p| (felt through ν_y/ν_x for k ≠ 0): D is
    the mean of the one-sided derivatives, central differences converge to it only as O(h)."""
    s = fr.initial_state(u_N=UN0, k_N=KN)
    du = np.array([0.0, 0.07, 0.003])
    D = upd(ORTHO, s, du).D
    errs = [np.abs(D - fd_tangent(ORTHO, s, du, h)).max() / np.abs(D).max() for h in (1e-5, 1e-7)]
    assert errs[1] < 1e-6 and errs[0] / errs[1] == pytest.approx(100, rel=0.01)


def assert_kernel_matches_twin(model, s, du, *stiffness, d_scale):
    """The numba update equals reference_update (state to 1e-12 per group, D to 1e-12 of
    max(|D|, d_scale)); returns the status."""
    r = fr.update(model, s, du, *stiffness)
    s_ref, D_ref, st = reference_update(model, s, du, *stiffness)
    assert st == r.status
    for sl in (slice(0, 3), slice(3, 4), slice(4, 6), slice(6, 8), slice(8, 9)):
        sc = max(np.abs(s_ref[sl]).max(), 1e-300)
        assert np.abs(r.state[sl] - s_ref[sl]).max() <= 1e-12 * sc, (model, sl)
    assert np.abs(r.D - D_ref).max() <= 1e-12 * max(np.abs(D_ref).max(), d_scale)
    return st


def test_kernel_matches_reference_twin():
    statuses = {assert_kernel_matches_twin(model, s, du, KN, KTX, KTY, d_scale=KN)
                for model, s, du in twin_cases()}
    assert statuses == {fr.STICK, fr.SLIP, fr.OPEN}


def test_batch_equals_pointwise_and_broadcasts():
    rng = np.random.default_rng(5)
    s = fr.initial_state((3, 4), u_N=UN0, k_N=KN)
    du = random_path(rng, 12, DLIM).reshape(3, 4, 3)
    kN = np.linspace(80, 120, 4)
    r = fr.update(ORTHO, s, du, kN, KTX, KTY)
    assert r.state.shape == (3, 4, 9) and r.D.shape == (3, 4, 3, 3) and r.status.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            p = fr.update(ORTHO, s[i, j], du[i, j], kN[j], KTX, KTY)
            assert p.state.shape == (9,) and p.D.shape == (3, 3)
            np.testing.assert_array_equal(p.state, r.state[i, j])
            np.testing.assert_array_equal(p.D, r.D[i, j])


def test_normal_convention_and_open_contact():
    assert fr.normal_law(0.02, KN) == (2.0, KN)  # closure > 0: pressure
    assert fr.normal_law(-0.02, KN) == (0.0, 0.0)  # opening: no pressure
    s = preloaded(ORTHO)
    r = upd(ORTHO, s, [0.01, 0.02, -2 * UN0])
    assert r.status == fr.OPEN
    assert np.all(r.tractions == 0.0) and np.all(r.D == 0.0)
    np.testing.assert_array_equal(r.state[fr.UP_X:], s[fr.UP_X:])  # slips, κ, dissipation frozen
    # re-closing starts from zero tangential traction (stick)
    r2 = upd(ORTHO, r.state, [0.0, 0.0, 2 * UN0])
    assert r2.status == fr.STICK
    assert r2.state[fr.T_N] == pytest.approx(P0) and np.all(r2.state[:2] == 0.0)
    # compression increases the tangential capacity: ∂t_T/∂u_N along t_T in slip
    r3 = upd(ORTHO, s, np.r_[0.02 * s[:2] / np.array([KTX, KTY]), 0.0])
    assert r3.status == fr.SLIP and r3.D[:2, 2] @ s[:2] > 0


def test_input_validation():
    s = fr.initial_state(u_N=UN0, k_N=KN)
    with pytest.raises(ValueError):
        fr.update(ORTHO, s[:8], [0, 0, 0], KN, KTX, KTY)
    with pytest.raises(ValueError):
        fr.update(ORTHO, s, [0, 0], KN, KTX, KTY)
    with pytest.raises(ValueError):
        fr.update(ORTHO, s, [0, np.nan, 0], KN, KTX, KTY)
    with pytest.raises(ValueError):
        fr.update(ORTHO, s, [0, 0, 0], -1.0, KTX, KTY)
    with pytest.raises(ValueError):
        fr.update(ORTHO, np.stack([s, s]), [0, 0, 0], KN, [1.0, 2.0, 3.0], KTY)
    bad = s.copy()
    bad[fr.KAPPA_X] = -1.0
    with pytest.raises(ValueError):
        fr.update(ORTHO, bad, [0, 0, 0], KN, KTX, KTY)
    with pytest.raises(ValueError):
        fr.update(ORTHO, s, [0, 0, 0], KN, KTX, KTY, tol=0.1)
    with pytest.raises(TypeError):
        fr.update("ortho", s, [0, 0, 0], KN, KTX, KTY)
    with pytest.raises(ValueError):
        fr.OrthotropicHardening(0.0, 0.5)
    with pytest.raises(ValueError):
        fr.IsotropicHardening(0.5, mu_o=-0.1)
    with pytest.raises(ValueError):
        fr.OrthotropicHardening(0.3, 0.5, n_x=-1.0)


# ---------------------------------------------------------------------------------------------
# tabulated normal law (interface.InterfaceLaw): p_N(u_N), k_N(u_N) and k_T = a k_N(u_N) at the
# end of the step
# ---------------------------------------------------------------------------------------------
A_X, A_Y = 0.7, 0.9  # k_Tx/k_N (section 9.2's 0.7), k_Ty/k_N


@pytest.fixture(scope="module")
def law():
    """Elastic table of the Table 1 surface (preset "plot": these tests need a smooth law, not
    its accuracy — tests/interface/test_normal_law.py checks that), reference state p0 = P0."""
    surface = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    table = NormalLawTable.build(surface, "elastic", E_star=1.14e5, s_range=(1.5, 4.5), accuracy="plot")
    return InterfaceLaw.from_pressure(table, P0, kT_over_kN=(A_X, A_Y))


def law_scales(law):
    """Elastic-limit tangential displacement at p0 and a closure step that changes p_N by ~40 %."""
    k0 = law.normal(0.0)[1]
    return 0.3 * 0.6 * P0 / (A_X * k0), 0.4 * P0 / k0


def preloaded_law(model, law):
    dlim, dun = law_scales(law)
    s = fr.initial_state(u_N=0.0, k_N=law)
    for du in ([6 * dlim, 8 * dlim, 0.5 * dun], [-16 * dlim, 2 * dlim, -0.3 * dun]):
        s = fr.update(model, s, du, law).state
    return s


@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("start", ["reference", "preloaded"])
def test_table_tangent_matches_finite_differences(name, start, law):
    """Consistent tangent with p_N(u_N), k_N(u_N) and k_T(u_N) from the table, in stick and
    slip, closing and opening increments: ≤ 1e-6 against central differences."""
    model = MODELS[name]
    dlim, dun = law_scales(law)
    s = fr.initial_state(u_N=0.0, k_N=law) if start == "reference" else preloaded_law(model, law)
    t_scale = np.r_[s[:2] / np.array([A_X, A_Y]), 0.0] / law.normal(s[fr.U_N])[1]
    cases = [(fr.SLIP, np.array(du) * [dlim, dlim, dun]) for du in
             ([3.0, -5.0, 0.4], [-6.0, 1.0, -0.3], [0.1, 7.0, 0.2], [-200.0, -150.0, 0.0])]
    cases += [(fr.STICK, np.array([0.2 * dlim, 0.1 * dlim, sign * 0.3 * dun]) - 0.3 * t_scale)
              for sign in (1.0, -1.0)]
    for expected, du in cases:
        r = fr.update(model, s, du, law)
        assert r.status == expected, (du, r.status)
        err = np.abs(r.D - fd_tangent(model, s, du, law=law)).max() / np.abs(r.D).max()
        assert err <= 1e-6, (du, err)
        p, k_N = law.normal(r.state[fr.U_N])
        assert r.state[fr.T_N] == p and r.D[2, 2] == k_N and r.D[2, 0] == r.D[2, 1] == 0.0
        if du[2] != 0.0:  # k_T follows k_N: the tangential tractions depend on u_N
            assert np.abs(r.D[:2, 2]).max() > 1e-3 * np.abs(r.D).max()


def test_table_stick_stiffness_follows_kN(law):
    dlim, dun = law_scales(law)
    s = fr.initial_state(u_N=0.0, k_N=law)
    for du_n in (-0.5 * dun, 0.0, 0.7 * dun):
        r = fr.update(ISO, s, [0.1 * dlim, -0.2 * dlim, du_n], law)
        assert r.status == fr.STICK
        kTx, kTy = law.tangential(du_n)
        assert r.D[0, 0] == kTx and r.D[1, 1] == kTy
        np.testing.assert_allclose(r.state[:2], [kTx * 0.1 * dlim, -kTy * 0.2 * dlim], rtol=1e-15)


@pytest.mark.parametrize("name", list(MODELS))
def test_table_tractions_stay_on_limit_surface(name, law):
    model = MODELS[name]
    dlim, dun = law_scales(law)
    rng = np.random.default_rng(6)
    s = fr.initial_state(64, u_N=0.0, k_N=law)
    nslip = nopen = 0
    for step in range(30):
        du = random_path(rng, 64, dlim)
        # closure steps up to ±dun, kept inside the table's heavy end; 8 points opened once
        du[:, 2] = np.minimum(rng.uniform(-1.0, 1.0, 64) * dun, 0.8 * law.u_max - s[:, fr.U_N])
        if step == 10:
            du[:8, 2] = law.u_open - 0.5 * dun - s[:8, fr.U_N]
        r = fr.update(model, s, du, law)
        f = fr.limit_function(model, r.state)
        stick, slip = r.status == fr.STICK, r.status == fr.SLIP
        nslip += slip.sum()
        nopen += (r.status == fr.OPEN).sum()
        assert np.all(f[stick] <= 1e-12 * r.state[stick, fr.T_N])
        assert np.all(np.abs(f[slip]) <= 1e-13 * r.state[slip, fr.T_N])
        np.testing.assert_array_equal(r.state[:, fr.T_N], law.normal(r.state[:, fr.U_N])[0])
        s = r.state
    assert nslip > 300 and nopen > 0


def test_table_kernel_matches_reference_twin(law):
    dlim, dun = law_scales(law)
    rng = np.random.default_rng(7)
    statuses = set()
    for i, model in enumerate([ORTHO, ORTHO_K1, ORTHO_K0, ISO] * 6):
        s = fr.initial_state(u_N=0.0, k_N=law)
        for du in random_path(rng, 3, dlim):
            du[2] = rng.uniform(-0.5, 0.5) * dun
            s = fr.update(model, s, du, law).state
        du = random_path(rng, 1, dlim)[0]
        du[2] = rng.uniform(-0.5, 0.5) * dun if i % 8 != 7 else law.u_open - s[fr.U_N] - 0.01
        statuses.add(assert_kernel_matches_twin(model, s, du, law, d_scale=1.0))
    assert statuses == {fr.STICK, fr.SLIP, fr.OPEN}


@pytest.mark.parametrize("name", list(MODELS))
def test_utilisation_is_one_on_slip_below_one_in_stick(name):
    """utilisation = (f + p)/p: exactly 1 where the update slipped, < 1 where it stuck, 0 open."""
    model = MODELS[name]
    s = fr.initial_state(3, u_N=UN0, k_N=KN)
    du = np.array([[0.3 * DLIM, 0.0, 0.0], [50 * DLIM, -20 * DLIM, 0.0], [0.0, 0.0, -2 * UN0]])
    r = upd(model, s, du)
    assert list(r.status) == [fr.STICK, fr.SLIP, fr.OPEN]
    u = fr.utilisation(model, r.state)
    assert 0.0 < u[0] < 1.0
    assert u[1] == pytest.approx(1.0, abs=1e-12)
    assert u[2] == 0.0


def test_utilisation_needs_a_friction_limit():
    with pytest.raises(TypeError, match="friction limit"):
        fr.utilisation(fr.Frictionless(), fr.initial_state(u_N=UN0, k_N=KN))


@pytest.mark.parametrize("name", list(MODELS))
def test_overflowing_increments_and_stiffnesses_are_refused(name):
    """Issue #12: Δu_T ≥ 1e160 or k = 1e300 returned a zero traction with a non-finite tangent
    and state; the update now refuses them (ValueError naming the overflow)."""
    model = MODELS[name]
    s = fr.initial_state(u_N=UN0, k_N=KN)
    with pytest.raises(ValueError, match="overflows double precision"):
        upd(model, s, [1e160, 0.0, 0.0])
    with pytest.raises(ValueError, match="overflows double precision"):
        upd(model, s, [DLIM, 0.0, 0.0], kN=1e300, kTx=1e300, kTy=1e300)
    r = upd(model, s, [1e150, 0.0, 0.0])  # huge but representable: slides on the limit surface
    assert np.all(np.isfinite(r.state)) and np.all(np.isfinite(r.D))


@pytest.mark.parametrize("k_N", [-1.0, 0.0, math.nan, math.inf, [1.0, -2.0]])
def test_initial_state_refuses_bad_normal_stiffness(k_N):
    with pytest.raises(ValueError, match="k_N must be finite and > 0"):
        fr.initial_state(2, u_N=UN0, k_N=k_N)
    with pytest.raises(ValueError, match="u_N must be finite"):
        fr.initial_state(u_N=math.nan, k_N=KN)
