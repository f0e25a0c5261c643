"""Tangential forms of the elastic law (93) with a load-dependent k_T = a k_N(u_N)
(roughcontact.interface.friction, "Tangential forms"): "incremental-end" (default),
"incremental-start" and "secant".

References, none taken from the kernel under test: the slow twin reference_update (the forms
written from their definitions, complex-step tangents); central differences of the kernel's
tractions; hand computations with InterfaceLaw.tangential; the constant-stiffness law (the
three forms must coincide bit for bit).

Units: stresses N/mm², lengths µm, stiffnesses N/(mm²·µm).
"""

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.interface import InterfaceLaw, NormalLawTable
from roughcontact.interface import friction as fr
from roughcontact.interface.reference import reference_update

FORMS = fr.TANGENTIAL_FORMS
KN, KTX, KTY = 100.0, 70.0, 90.0
UN0 = 0.05  # closure -> p_N = 5 N/mm² (constant law)
P0 = KN * UN0
A_X, A_Y = 0.7, 0.9  # k_Tx/k_N (section 9.2's 0.7), k_Ty/k_N
ORTHO = fr.OrthotropicHardening(0.3, 0.5, mu_o_x=0.6, mu_o_y=0.7, n_x=20.0, n_y=10.0, k=0.5)
ISO = fr.IsotropicHardening(0.4, mu_o=0.6, n=15.0)
MODELS = {"ortho": ORTHO, "iso": ISO}


@pytest.fixture(scope="module")
def law():
    """Elastic table of the Table 1 surface (preset "plot": a smooth law is what matters here),
    reference state p0 = P0 (as tests/interface/test_friction.py)."""
    surface = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    table = NormalLawTable.build(surface, "elastic", E_star=1.14e5, s_range=(1.5, 4.5), accuracy="plot")
    return InterfaceLaw.from_pressure(table, P0, kT_over_kN=(A_X, A_Y))


def setup(kind, law):
    """(stiffness args of update, initial state, elastic-limit slip dlim, closure step dun)."""
    if kind == "law":
        k0 = law.normal(0.0)[1]
        return (law,), fr.initial_state(u_N=0.0, k_N=law), 0.3 * 0.6 * P0 / (A_X * k0), 0.4 * P0 / k0
    return (KN, KTX, KTY), fr.initial_state(u_N=UN0, k_N=KN), 0.3 * 0.6 * P0 / KTX, 0.4 * UN0


def random_path(rng, n, dlim, dun):
    ang = rng.uniform(0, 2 * np.pi, n)
    mag = dlim * rng.choice([0.3, 1.0, 3.0, 10.0], n)
    return np.c_[mag * np.cos(ang), mag * np.sin(ang), rng.uniform(-0.5, 0.5, n) * dun]


def cases(form, model, kind, law, seed):
    """(state, du) pairs: a random 3-step history under ``form``, then a slip increment
    (4-10 dlim) or a stick one (unload half of the elastic slip, |Δu_N| ≤ 0.2 dun)."""
    stiff, s0, dlim, dun = setup(kind, law)
    rng = np.random.default_rng(seed)
    out = []
    for i in range(8):
        s = s0
        for du in random_path(rng, 3, dlim, dun):
            s = fr.update(model, s, du, *stiff, tangential=form).state
        if i % 2:
            ang = rng.uniform(0, 2 * np.pi)
            du = np.r_[rng.uniform(4, 10) * dlim * np.array([np.cos(ang), np.sin(ang)]), rng.uniform(-0.3, 0.3) * dun]
        else:
            k_T = law.tangential(s[fr.U_N]) if kind == "law" else (KTX, KTY)
            du = np.r_[-0.5 * s[:2] / np.asarray(k_T), rng.uniform(-0.2, 0.2) * dun]
        out.append((s, du))
    return out


def twin_errors(model, s, du, stiff, form):
    """(status, state error, D error) of the kernel against reference_update: the state per
    group (tractions, u_N, slips, κ, dissipation) relative to the group's size, D relative to
    max(|D_ref|, k_N at p0)."""
    r = fr.update(model, s, du, *stiff, tangential=form)
    s_ref, D_ref, st = reference_update(model, s, du, *stiff, tangential=form)
    assert st == r.status
    err_s = 0.0
    for sl in (slice(0, 3), slice(3, 4), slice(4, 6), slice(6, 8), slice(8, 9)):
        sc = max(np.abs(s_ref[sl]).max(), 1e-300)
        err_s = max(err_s, np.abs(r.state[sl] - s_ref[sl]).max() / sc)
    err_D = np.abs(r.D - D_ref).max() / max(np.abs(D_ref).max(), 50.0)
    return st, err_s, err_D


@pytest.mark.parametrize("kind", ["constant", "law"])
@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("form", FORMS)
def test_kernel_matches_reference_twin(form, name, kind, law):
    """The numba update equals the twin in stick and slip, tangents included. 1e-12: the
    tolerance of test_friction's kernel-vs-twin tests (two independent solvers converged to
    ~1e-15; measured ≤ 1e-15 for every form)."""
    statuses = set()
    stiff = setup(kind, law)[0]
    for s, du in cases(form, MODELS[name], kind, law, seed=10):
        st, err_s, err_D = twin_errors(MODELS[name], s, du, stiff, form)
        assert err_s <= 1e-12 and err_D <= 1e-12, (du, st, err_s, err_D)
        statuses.add(st)
    assert statuses == {fr.STICK, fr.SLIP}


def fd_tangent(model, s, du, stiff, form, h=1e-7):
    """Central differences of the kernel's tractions w.r.t. du (all three columns) and whether
    ± h kept the status."""
    D = np.zeros((3, 3))
    same = True
    st = fr.update(model, s, du, *stiff, tangential=form).status
    for j in range(3):
        e = np.zeros(3)
        e[j] = h
        plus = fr.update(model, s, du + e, *stiff, tangential=form)
        minus = fr.update(model, s, du - e, *stiff, tangential=form)
        D[:, j] = (plus.tractions - minus.tractions) / (2 * h)
        same &= bool(plus.status == st == minus.status)
    return D, same


@pytest.mark.parametrize("kind", ["constant", "law"])
@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("form", FORMS)
def test_consistent_tangent_matches_finite_differences(form, name, kind, law):
    """D of every form = ∂(t_x, t_y, p_N)/∂(Δu_Tx, Δu_Ty, Δu_N), the u_N column included.
    1e-6 as in test_friction: FD truncation (h/0.01 µm)² ~ 1e-10 plus round-off ε|t|/(h|D|) ~ 1e-9
    (measured ≤ 5e-10 for every form); a missing or wrong lever term ∂K_T/∂u_N e is ≥ 1e-3 of
    |D| (checked below)."""
    model = MODELS[name]
    stiff = setup(kind, law)[0]
    n_checked = 0
    for s, du in cases(form, model, kind, law, seed=20):
        r = fr.update(model, s, du, *stiff, tangential=form)
        D_fd, same = fd_tangent(model, s, du, stiff, form)
        if not same:  # a regime boundary within ± h: D is one-sided there
            continue
        n_checked += 1
        assert np.abs(r.D - D_fd).max() / np.abs(r.D).max() <= 1e-6, (du, r.status)
        if kind == "law" and form != "incremental-start" and r.status == fr.STICK:
            # the lever term ∂K_T/∂u_N e is really there (not vacuous)
            assert np.abs(r.D[:2, 2]).max() > 1e-3 * np.abs(r.D).max()
        if form == "incremental-start" and r.status == fr.STICK:
            assert np.all(r.D[:2, 2] == 0.0)  # k_T frozen at u_N,n: ∂t^tr/∂u_N = 0
    assert n_checked >= 6


def test_constant_stiffness_forms_identical():
    """With constant k_T the three forms give the same states, tangents and statuses bit for bit
    along a random path with stick, slip, opening and re-closing."""
    rng = np.random.default_rng(30)
    stiff, _, dlim, dun = setup("constant", None)
    for model in (ORTHO, ISO, fr.NoSlip()):
        states = {f: fr.initial_state(64, u_N=UN0, k_N=KN) for f in FORMS}
        seen = set()
        for _ in range(25):
            du = random_path(rng, 64, dlim, 3 * dun)  # |Δu_N| ≤ 0.03 µm vs u_N,0 = 0.05: some open
            res = {f: fr.update(model, states[f], du, *stiff, tangential=f) for f in FORMS}
            for f in FORMS[1:]:
                np.testing.assert_array_equal(res[f].state, res[FORMS[0]].state)
                np.testing.assert_array_equal(res[f].D, res[FORMS[0]].D)
                np.testing.assert_array_equal(res[f].status, res[FORMS[0]].status)
            seen |= set(res[FORMS[0]].status.tolist())
            states = {f: res[f].state for f in FORMS}
        assert fr.OPEN in seen and fr.STICK in seen


def test_table_forms_agree_without_normal_motion(law):
    """With Δu_N = 0, K_T(u_N,n+1) = K_T(u_N,n): the tractions of the three forms agree bit for
    bit, but their u_N columns differ (each form is a different function of Δu_N)."""
    stiff, s0, dlim, dun = setup("law", law)
    s = s0
    for du in ([3 * dlim, -2 * dlim, 0.4 * dun], [-dlim, 0.5 * dlim, -0.2 * dun]):
        s = fr.update(ISO, s, du, law).state
    for du in ([0.2 * dlim, 0.1 * dlim, 0.0], [8 * dlim, 3 * dlim, 0.0]):  # stick, slip
        res = {f: fr.update(ISO, s, du, law, tangential=f) for f in FORMS}
        for f in FORMS[1:]:
            np.testing.assert_array_equal(res[f].state, res[FORMS[0]].state)
            np.testing.assert_array_equal(res[f].D[:, :2], res[FORMS[0]].D[:, :2])
        cols = [res[f].D[:2, 2] for f in FORMS]
        assert not np.allclose(cols[0], cols[1]) and not np.allclose(cols[0], cols[2])


def stick_cycle(law, form, model=fr.NoSlip()):
    """Tangential slip out and back (Σ Δu_T = 0) while u_N goes up and down: the tangential
    tractions after every step and the statuses."""
    _, s, dlim, dun = setup("law", law)
    d = np.array([0.4, -0.3]) * dlim
    steps = [np.r_[d, 0.5 * dun], np.r_[d, -0.3 * dun], np.r_[d, 0.6 * dun],
             np.r_[-d, -0.7 * dun], np.r_[-d, 0.4 * dun], np.r_[-d, -0.2 * dun]]
    ts, sts = [], []
    for du in steps:
        r = fr.update(model, s, du, law, tangential=form)
        s = r.state
        ts.append(s[:2].copy())
        sts.append(int(r.status))
    return np.array(ts), sts


def test_secant_is_path_independent(law):
    """A stick cycle of Δu_T at varying u_N returns t_T to 0 with the secant form (to round-off:
    measured 1.6e-16 of the peak, bound 1e-14 for a few roundings of t_n K/K_n); the
    incremental forms keep a hypoelastic residual (measured: end 6.9 %, start 8.7 % of the
    peak), far above any round-off (bound 1e-2)."""
    res = {}
    for f in FORMS:
        for model in (fr.NoSlip(), fr.IsotropicHardening(5.0)):  # μ = 5: nothing slips
            ts, sts = stick_cycle(law, f, model)
            assert set(sts) == {fr.STICK}
            res[f, type(model)] = np.abs(ts[-1]).max() / np.abs(ts).max()
    for model in (fr.NoSlip, fr.IsotropicHardening):
        assert res["secant", model] <= 1e-14
        assert res["incremental-end", model] > 1e-2
        assert res["incremental-start", model] > 1e-2


def test_incremental_path_independent_with_constant_stiffness():
    """The residual of the incremental form comes from the varying k_T: with a constant one the
    same cycle returns to 0 up to round-off."""
    _, s, dlim, dun = setup("constant", None)
    d = np.array([0.4, -0.3]) * dlim
    peak = 0.0
    for sign, dn in ((1, 0.5), (1, -0.3), (1, 0.6), (-1, -0.7), (-1, 0.4), (-1, -0.2)):
        s = fr.update(fr.NoSlip(), s, np.r_[sign * d, dn * dun], KN, KTX, KTY).state
        peak = max(peak, np.abs(s[:2]).max())
    assert np.abs(s[:2]).max() <= 1e-14 * peak  # a few roundings of t_n + k_T Δu_T


def test_incremental_start_uses_start_stiffness(law):
    """t^tr = t_n + K_T(u_N,n) Δu_T by hand (InterfaceLaw.tangential at the start closure); stick:
    D = diag(K_T(u_N,n), k_N(u_N,n+1)) with a zero u_N column; slip: the return mapping
    t = t^tr − K_T(u_N,n) Δu^p (eq. (93), (99)) uses the same start stiffness."""
    _, s, dlim, dun = setup("law", law)
    s = fr.update(ISO, s, [3 * dlim, -2 * dlim, 0.3 * dun], law, tangential="incremental-start").state
    k0 = np.asarray(law.tangential(s[fr.U_N]))
    for du, status in (([-0.3 * dlim, 0.2 * dlim, 0.25 * dun], fr.STICK),
                       ([6 * dlim, 4 * dlim, -0.25 * dun], fr.SLIP)):
        du = np.array(du)
        r = fr.update(ISO, s, du, law, tangential="incremental-start")
        assert r.status == status
        t_tr = s[:2] + k0 * du[:2]
        if status == fr.STICK:
            np.testing.assert_allclose(r.state[:2], t_tr, rtol=1e-15)  # one rounding
            k_N1 = law.normal(s[fr.U_N] + du[2])[1]
            np.testing.assert_array_equal(r.D, np.diag([k0[0], k0[1], k_N1]))
            # the end form uses K_T(u_N,n+1) instead: a clearly different traction
            r_end = fr.update(ISO, s, du, law)
            assert np.abs(r_end.state[:2] - t_tr).max() > 1e-2 * np.abs(t_tr).max()
        else:
            dup = r.state[fr.UP_X:fr.UP_Y + 1] - s[fr.UP_X:fr.UP_Y + 1]
            # 1e-13: the twin-level consistency of t, Δu^p (rounding of the return mapping)
            np.testing.assert_allclose(r.state[:2] + k0 * dup, t_tr, rtol=1e-13)


def test_open_start_state_that_closes(law):
    """A point open at the start of the increment (t_n = 0, K_T(u_N,n) = 0) that closes:
    end and secant (u^e_T,n = 0) give t = K_T(u_N,n+1) Δu_T bit for bit; start gives no
    tangential stiffness for this increment (t_T = 0, stick); the twin agrees for all three."""
    _, s, dlim, dun = setup("law", law)
    s = fr.update(ISO, s, [2 * dlim, dlim, law.u_open - 0.5 * dun], law).state
    assert s[fr.T_N] == 0.0 and np.all(s[:2] == 0.0) and law.normal(s[fr.U_N])[1] == 0.0
    du = np.array([0.3 * dlim, -0.2 * dlim, -s[fr.U_N] + 0.1 * dun])  # closes to u_N = 0.1 dun
    res = {f: fr.update(ISO, s, du, law, tangential=f) for f in FORMS}
    k1 = np.asarray(law.tangential(s[fr.U_N] + du[2]))
    np.testing.assert_array_equal(res["secant"].state, res["incremental-end"].state)
    np.testing.assert_array_equal(res["secant"].D, res["incremental-end"].D)
    np.testing.assert_allclose(res["secant"].state[:2], k1 * du[:2], rtol=1e-15)
    start = res["incremental-start"]
    assert start.status == fr.STICK and np.all(start.state[:2] == 0.0) and np.all(start.D[:2] == 0.0)
    for f in FORMS:
        st, err_s, err_D = twin_errors(ISO, s, du, (law,), f)
        assert st == fr.STICK and err_s <= 1e-12 and err_D <= 1e-12  # as the twin test above


def test_start_state_beyond_the_table(law):
    """start and secant need K_T(u_N,n): a start closure beyond the heavy end raises ValueError
    (the end form never evaluates it)."""
    _, s, _, _ = setup("law", law)
    s = s.copy()
    s[fr.U_N] = law.u_max + 0.05
    du = [0.0, 0.0, -0.1]
    assert fr.update(ISO, s, du, law).status == fr.STICK
    for f in ("incremental-start", "secant"):
        with pytest.raises(ValueError, match="heavy end"):
            fr.update(ISO, s, du, law, tangential=f)


def test_bad_tangential_form():
    s = fr.initial_state(u_N=UN0, k_N=KN)
    for bad in ("total", "secant ", None, 2):
        with pytest.raises(ValueError, match="incremental-end, incremental-start, secant"):
            fr.update(ISO, s, [0.0, 0.0, 0.0], KN, KTX, KTY, tangential=bad)
    with pytest.raises(ValueError, match="tangential must be one of"):
        reference_update(ISO, s, [0.0, 0.0, 0.0], KN, KTX, KTY, tangential="total")
    assert FORMS == ("incremental-end", "incremental-start", "secant")


def test_interface_kernels_keep_one_signature(law):
    """numba's shared cache is safe with one key per kernel (tests/integrals/test_kernels.py):
    the form enters as an int64 whatever the caller passes, tables and constants alike."""
    import numba.core.registry

    from roughcontact.interface import kernels as K

    s = fr.initial_state(2, u_N=UN0, k_N=KN)
    for model in (ORTHO, ISO, fr.NoSlip()):
        for f in FORMS:
            fr.update(model, s, [[1e-3, 0.0, 0.0], [0.5, 0.2, 0.0]], KN, KTX, KTY, tangential=f)
            fr.update(model, fr.initial_state(u_N=0.0, k_N=law), [1e-3, 0.0, 0.0], law, tangential=f)
    disp = {k: v for k, v in vars(K).items() if isinstance(v, numba.core.registry.CPUDispatcher)}
    many = {k: len(d.signatures) for k, d in disp.items() if len(d.signatures) > 1}
    assert not many, many
