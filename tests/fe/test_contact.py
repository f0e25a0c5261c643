"""The interface material of the FE engine (roughcontact.fe.contact): the library's law in the
engine's units and sign convention.

References, none taken from the module under test:
* roughcontact.interface.friction.update called directly with the conversion written out here
  (the engine's jump (slip t1, slip t2, opening) [mm] → the law's (Δu_Tx, Δu_Ty, Δu_N closure)
  in law units: × length_per_mm, opening → −closure; tractions (t_x, t_y, p_N) → (t_x, t_y, σ_N
  = −p_N); tangent S D S × length_per_mm, S = diag(1, 1, −1));
* closed forms of the constant-stiffness law (σ_N = −k_N·max(closure, 0), t_T = k_T·slip);
* central finite differences of the tractions for the tangent.
"""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.fe.contact import MICROMETRES_PER_MM, InterfaceMaterial, statistical_interface
from roughcontact.interface import InterfaceLaw
from roughcontact.interface import friction as fr

SURFACE = SpectralMoments(m00=0.625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)  # µm units
E_STAR = 1.127e5  # N/mm², section 9.1
P0 = 0.05  # N/mm², seating pressure of the law's reference state

MODELS = {
    "frictionless": fr.Frictionless(),
    "noslip": fr.NoSlip(),
    "coulomb": fr.IsotropicHardening(mu_m=0.3),
    "isotropic_hardening": fr.IsotropicHardening(mu_m=0.4, mu_o=0.5, n=0.8),  # n in 1/µm
    "orthotropic": fr.OrthotropicHardening(0.3, 0.5, 0.6, 0.8, 0.5, 0.3, k=0.5),
}


@pytest.fixture(scope="module")
def law() -> InterfaceLaw:
    return statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="free").normal


def material(kind: str, normal, law_=None) -> InterfaceMaterial:
    """A material of friction model ``kind`` with the statistical law (µm units, lengths ×1000)
    or a constant k_N (then in N/mm³, length_per_mm = 1, pre-compressed by 1e-3 mm)."""
    if normal == "law":
        return InterfaceMaterial(law_, MODELS[kind])
    return InterfaceMaterial(2.0e3, MODELS[kind], k_T=(1.5e3, 0.9e3), length_per_mm=1.0, closure0=1e-3)


def committed_states(mat: InterfaceMaterial, rng, n: int) -> np.ndarray:
    """Non-virgin committed states: one random increment from the initial state (some points
    slipped, with hardening and dissipation), all still closed. Jumps in mm of order 1e-4
    (0.1 µm: a fraction of the law's closure range)."""
    d = rng.normal(scale=[2e-4, 2e-4, 3e-5], size=(n, 3)) - [0.0, 0.0, 2e-5]  # net closure
    return mat.respond(mat.initial_state(n), d).state


def law_update(mat: InterfaceMaterial, committed, d_jump):
    """friction.update with the engine → law conversion written out (module docstring)."""
    L = mat.length_per_mm
    du = np.column_stack([d_jump[:, 0], d_jump[:, 1], -d_jump[:, 2]]) * L
    if isinstance(mat.normal, InterfaceLaw):
        return fr.update(mat.model, committed, du, mat.normal)
    return fr.update(mat.model, committed, du, mat.normal, *mat.k_T)


CASES = [(k, n) for k in MODELS for n in ("law", "constant")]


@pytest.mark.parametrize("kind, normal", CASES)
def test_respond_is_the_library_law_in_engine_units(kind, normal, law):
    mat = material(kind, normal, law)
    rng = np.random.default_rng(11)
    committed = committed_states(mat, rng, 64)
    d_jump = rng.normal(scale=[3e-4, 3e-4, 2e-5], size=(64, 3))
    resp = mat.respond(committed, d_jump)
    ref = law_update(mat, committed, d_jump)
    S = np.array([1.0, 1.0, -1.0])
    # the same arithmetic up to the order of two exact operations (a sign, ×1000): bitwise or
    # within one rounding, 1e-14 relative
    scale_t = np.max(np.abs(ref.state[:, :3]))
    np.testing.assert_allclose(resp.tractions, ref.state[:, :3] * S, rtol=0, atol=1e-14 * scale_t)
    D_ref = ref.D * np.outer(S, S) * mat.length_per_mm
    np.testing.assert_allclose(resp.tangent, D_ref, rtol=0, atol=1e-14 * np.max(np.abs(D_ref)))
    np.testing.assert_allclose(resp.state, ref.state, rtol=1e-14, atol=1e-14 * np.max(np.abs(ref.state)))
    assert np.array_equal(resp.status, ref.status)
    np.testing.assert_allclose(mat.closure_mm(resp.state), ref.state[:, fr.U_N] / mat.length_per_mm, rtol=1e-15)
    # the cases exercise what they claim: friction models with a limit have slipping points
    if kind in ("coulomb", "isotropic_hardening", "orthotropic"):
        assert np.any(resp.status == fr.SLIP) and np.any(resp.status == fr.STICK)


def test_constant_stiffness_closed_form():
    """σ_N = −k_N·(closure0 − opening) while closed, 0 (OPEN, zero tangent) once the opening
    exceeds the pre-compression; t_T = k_T·slip without a friction limit."""
    k_N, k_T, c = 2.0e3, (1.5e3, 0.9e3), 1e-3  # N/mm³, mm
    mat = InterfaceMaterial(k_N, fr.NoSlip(), k_T=k_T, length_per_mm=1.0, closure0=c)
    state = mat.initial_state(4)
    np.testing.assert_allclose(state[:, fr.T_N], k_N * c, rtol=1e-15)
    d = np.array([[1e-4, -2e-4, 0.0], [0.0, 0.0, 0.4e-3], [3e-5, 1e-5, -0.5e-3], [1e-4, 1e-4, 1.2e-3]])
    r = mat.respond(state, d)
    np.testing.assert_allclose(r.tractions[:3, 2], -k_N * (c - d[:3, 2]), rtol=1e-14)
    np.testing.assert_allclose(r.tractions[:3, :2], d[:3, :2] * k_T, rtol=1e-14)
    np.testing.assert_array_equal(r.tangent[:3], np.broadcast_to(np.diag([*k_T, k_N]), (3, 3, 3)))
    assert r.status[3] == fr.OPEN and not np.any(r.tractions[3]) and not np.any(r.tangent[3])
    np.testing.assert_allclose(mat.closure_mm(r.state), c - d[:, 2], rtol=1e-14)


def test_statistical_law_reference_state_and_units(law):
    """u = 0 carries the seating pressure p0; an approach of x mm is a closure of 1000·x µm of the
    law (σ_N = −p_N(1000 x)); the tangent is dp_N/du_N [N/(mm²·µm)] × 1000 [N/mm³]."""
    mat = InterfaceMaterial(law, fr.Frictionless())
    assert mat.length_per_mm == MICROMETRES_PER_MM == 1000.0
    state = mat.initial_state(3)
    np.testing.assert_allclose(-mat.respond(state, np.zeros((3, 3))).tractions[:, 2], P0, rtol=1e-12)
    approach = np.array([1e-4, 3e-4, -1e-4])  # mm (negative: unloading, still closed)
    r = mat.respond(state, np.column_stack([np.zeros(3), np.zeros(3), -approach]))
    p, k = law.normal(1000.0 * approach)
    np.testing.assert_allclose(-r.tractions[:, 2], p, rtol=1e-14)
    np.testing.assert_allclose(r.tangent[:, 2, 2], 1000.0 * k, rtol=1e-14)


@pytest.mark.parametrize("kind, normal", CASES)
def test_tangent_is_the_derivative_of_the_tractions(kind, normal, law):
    """Central differences of tractions(d_jump) in each of the three jump directions. Points
    near a regime boundary (stick/slip, or an orthotropic slip component changing sign, where D
    is a one-sided mean) are excluded by checking that ± h give the same status."""
    mat = material(kind, normal, law)
    rng = np.random.default_rng(5)
    committed = committed_states(mat, rng, 48)
    d = rng.normal(scale=[3e-4, 3e-4, 2e-5], size=(48, 3))
    resp = mat.respond(committed, d)
    h = 1e-9  # mm = 1e-6 µm: truncation (h/0.1 µm)² ~ 1e-10, round-off ε·|t|/(h·|D|) ~ 1e-9
    fd = np.empty_like(resp.tangent)
    same = np.ones(len(d), dtype=bool)
    for j in range(3):
        e = np.zeros(3)
        e[j] = h
        plus, minus = mat.respond(committed, d + e), mat.respond(committed, d - e)
        fd[:, :, j] = (plus.tractions - minus.tractions) / (2 * h)
        same &= (plus.status == resp.status) & (minus.status == resp.status)
    assert same.sum() >= 40  # the exclusion is rare, the check is not vacuous
    scale = np.max(np.abs(resp.tangent[same]), axis=(1, 2))[:, None, None]
    err = np.abs(fd[same] - resp.tangent[same]) / scale
    # 1e-6: the FD errors above are ≤ 1e-8 (measured worst 4e-10 over all cases); a missing term
    # of the consistent tangent (e.g. ∂K_T/∂u_N·Δu_T, or the return-mapping curvature) is ≥ 1e-3 of |D|
    assert err.max() <= 1e-6


def test_material_validation(law):
    with pytest.raises(ValueError, match="do not pass k_T"):
        InterfaceMaterial(law, fr.NoSlip(), k_T=(1.0, 1.0))
    with pytest.raises(ValueError, match="needs k_T"):
        InterfaceMaterial(1e3, fr.NoSlip())
    with pytest.raises(ValueError, match="needs k_T"):
        InterfaceMaterial(1e3, fr.NoSlip(), k_T=(1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="k_N"):
        InterfaceMaterial(-1e3, fr.NoSlip(), k_T=(1.0, 1.0))
    with pytest.raises(ValueError, match="k_Ty"):
        InterfaceMaterial(1e3, fr.NoSlip(), k_T=(1.0, 0.0))
    with pytest.raises(ValueError, match="length_per_mm"):
        InterfaceMaterial(law, fr.NoSlip(), length_per_mm=0.0)
    for bad in ("coulomb", None, fr.IsotropicHardening):  # a string, nothing, the class itself
        with pytest.raises(TypeError, match="model must be"):
            InterfaceMaterial(law, bad)


def test_statistical_interface_choices(law):
    mat = statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="coulomb", mu=0.25)
    assert mat.model == fr.IsotropicHardening(mu_m=0.25) and isinstance(mat.normal, InterfaceLaw)
    assert isinstance(statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="stick").model, fr.NoSlip)
    with pytest.raises(ValueError, match="tangential must be"):
        statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="sticky")
    with pytest.raises(ValueError, match="mu is only used"):
        statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="free", mu=0.3)
    with pytest.raises(ValueError, match="mu"):
        statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="coulomb")
    with pytest.raises(ValueError, match="exactly one of E_star"):
        statistical_interface(SURFACE, P0)


@pytest.mark.parametrize("form", fr.TANGENTIAL_FORMS)
def test_tangential_form_is_passed_to_the_law(form, law):
    """InterfaceMaterial.tangential_form reaches friction.update(..., tangential=form) (the
    conversion written out as in law_update); with the statistical law the forms differ."""
    mat = InterfaceMaterial(law, MODELS["coulomb"], tangential_form=form)
    rng = np.random.default_rng(12)
    committed = committed_states(mat, rng, 32)
    d = rng.normal(scale=[3e-4, 3e-4, 2e-5], size=(32, 3))
    resp = mat.respond(committed, d)
    du = np.column_stack([d[:, 0], d[:, 1], -d[:, 2]]) * mat.length_per_mm
    ref = fr.update(mat.model, committed, du, law, tangential=form)
    np.testing.assert_array_equal(resp.state, ref.state)  # the same call: bitwise
    np.testing.assert_array_equal(resp.tangent, ref.D * np.outer(fr.OPENING_SIGN, fr.OPENING_SIGN) * 1000.0)
    other = fr.update(mat.model, committed, du, law,
                      tangential="secant" if form != "secant" else "incremental-end")
    # not vacuous: another form differs by ~9 % of |t_T| here (measured 7-9 %)
    assert np.abs(other.state[:, :2] - ref.state[:, :2]).max() > 1e-2 * np.abs(ref.state[:, :2]).max()


def test_tangential_form_default_validation_and_statistical_interface(law):
    assert InterfaceMaterial(law, fr.NoSlip()).tangential_form == "incremental-end"
    with pytest.raises(ValueError, match="tangential_form must be one of"):
        InterfaceMaterial(law, fr.NoSlip(), tangential_form="total")
    mat = statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="stick", tangential_form="secant")
    assert mat.tangential_form == "secant" and isinstance(mat.model, fr.NoSlip)
    with pytest.raises(ValueError, match="tangential_form must be one of"):
        statistical_interface(SURFACE, P0, E_star=E_STAR, tangential_form="hypoelastic")
