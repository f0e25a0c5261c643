"""Plasticity-index closures (closures.py): what each fixes, and that the consistent one makes
(74)/(87) equal the physical first yield (65)."""

import math

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact import asperity as asp
from roughcontact.contact.closures import CLOSURES, resolve_material
from roughcontact.asperity.ellipse import hertz_factors

E_STAR, Y_PRINTED = 1.14e5, 2070.0  # N/mm², captions of Figs 5–8
SURFACES = {m00: SpectralMoments(m00, 8e-5, 8e-4, 1.04e-6, 1.04e-4) for m00 in (0.0625, 0.3125, 0.625)}


@pytest.mark.parametrize("m00, psi_expected", [(0.0625, 0.88), (0.3125, 1.35), (0.625, 1.61)])
def test_material_closure_gives_the_captions_psi(m00, psi_expected):
    """The captions' E*, Y already fix ψ (docs/independent-studies.md: 0.88, 1.35, 1.61, printed to two decimals),
    not the prescribed 0.35 / 0.5."""
    mat = resolve_material(SURFACES[m00], E_star=E_STAR, Y=Y_PRINTED)
    assert mat.Y == Y_PRINTED and mat.H == pytest.approx(Y_PRINTED / 0.354, rel=1e-15)
    assert asp.plasticity_index(SURFACES[m00], mat) == pytest.approx(psi_expected, abs=0.005)
    assert mat.load_jump_at_yield == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("psi", [0.05, 0.35, 0.5, 5.0, 50.0])
def test_yield_from_psi_is_consistent(psi):
    """ψ and E* kept, Y derived: the material's own index is ψ, the load is continuous at ω_c,
    and (74) with this ψ equals (65) at random summits (both ellipse orientations)."""
    surface = SURFACES[0.0625]
    mat = resolve_material(surface, E_star=E_STAR, psi=psi)
    assert mat.E_star == E_STAR and mat.H == pytest.approx(mat.Y / 0.354, rel=1e-15)
    assert asp.plasticity_index(surface, mat) == pytest.approx(psi, rel=1e-14)
    assert mat.load_jump_at_yield == pytest.approx(0.0, abs=1e-15)
    rng = np.random.default_rng(11)
    w4 = rng.rayleigh(size=100) / math.sqrt(surface.mu)
    w6 = rng.rayleigh(size=100) / math.sqrt(surface.mu)
    w4[0], w6[0] = 40.0, 1e-2  # a turned ellipse (ρ > 1)
    rho = asp.curvature_ratio(w4, w6, surface)
    kappa = math.sqrt(surface.mu) * (w4 * math.sqrt(surface.m40) + w6 * math.sqrt(surface.m04)) / 2  # (44)
    wc = asp.critical_interference(kappa, hertz_factors(np.sqrt(rho)), mat)  # (65)
    star = asp.critical_interference_star(w4, w6, surface, psi)  # (74)
    np.testing.assert_allclose(star * math.sqrt(surface.m00 * surface.mu), wc, rtol=1e-13)


@pytest.mark.parametrize("m00", [0.0625, 0.3125, 0.625])
@pytest.mark.parametrize("psi", [0.35, 0.5])
def test_paper_literal_yields_like_psi_but_presses_like_printed_Y(m00, psi):
    """First yield as the prescribed ψ says; pressures from the printed Y: the load of every
    asperity jumps at ω_c by ψ/ψ_physical − 1 (−60 % for ψ = 0.35, m00 = 0.0625)."""
    surface = SURFACES[m00]
    literal = resolve_material(surface, E_star=E_STAR, psi=psi, Y=Y_PRINTED, closure="paper-literal")
    consistent = resolve_material(surface, E_star=E_STAR, psi=psi)
    physical = resolve_material(surface, E_star=E_STAR, Y=Y_PRINTED)
    assert literal.yield_pressure == pytest.approx(consistent.yield_pressure, rel=1e-15)  # same ω_c
    assert literal.H == pytest.approx(physical.H, rel=1e-15)
    assert literal.K_v * literal.H == pytest.approx(1.62 * Y_PRINTED, rel=1e-14)
    psi_phys = asp.plasticity_index(surface, physical)
    assert literal.load_jump_at_yield == pytest.approx(psi / psi_phys - 1.0, rel=1e-12)
    assert literal.load_jump_at_yield < -0.5 if (psi, m00) == (0.35, 0.0625) else literal.load_jump_at_yield < 0


def test_overrides_pass_through():
    mat = resolve_material(SURFACES[0.0625], E_star=E_STAR, psi=0.5, c_h=0.9, wp_over_wc=25.0,
                           yield_coefficient=1.5, H=9000.0)
    assert (mat.c_h, mat.wp_over_wc, mat.yield_coefficient, mat.H) == (0.9, 25.0, 1.5, 9000.0)
    assert asp.plasticity_index(SURFACES[0.0625], mat) == pytest.approx(0.5, rel=1e-14)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        (dict(psi=0.5, Y=2070.0), "closure='paper-literal'"),
        (dict(), "give the plasticity index psi or the yield strength Y"),
        (dict(psi=0.5, closure="gw"), "closure must be one of"),
        (dict(Y=2070.0, closure="yield-from-psi"), "needs psi"),
        (dict(psi=0.5, closure="material"), "does not take psi"),
        (dict(psi=0.5, closure="paper-literal"), "needs the yield strength"),
        (dict(psi=-1.0), "psi must be finite and positive"),
        (dict(Y=0.0), "Y (yield strength) must be finite and positive"),
    ],
)
def test_bad_input(kwargs, fragment):
    with pytest.raises(ValueError) as e:
        resolve_material(SURFACES[0.0625], E_star=E_STAR, **kwargs)
    assert fragment in str(e.value)


def test_every_closure_is_documented():
    import roughcontact.contact.closures as mod

    for name in CLOSURES:
        assert f"``\"{name}\"``" in mod.__doc__


def test_effective_modulus_eq42():
    """(42): two equal bodies give half the plane-strain modulus (Fig. 18: E = 2e5, ν = 0.25 →
    1.0667e5 N/mm²); a rigid base gives the plane-strain modulus itself (section 9.1: E1 =
    1.057e5, ν1 = 0.25 → 1.1275e5, printed 1.127e5)."""
    assert asp.effective_modulus(2e5, 0.25, 2e5, 0.25) == pytest.approx(2e5 / (2 * (1 - 0.0625)), rel=1e-15)
    assert asp.effective_modulus(1.057e5, 0.25) == pytest.approx(1.057e5 / 0.9375, rel=1e-15)
    assert round(asp.effective_modulus(1.057e5, 0.25) / 1e5, 3) == 1.127
    assert asp.effective_modulus(1.0, 0.3, 3.0, 0.2) == pytest.approx(1 / (0.91 + 0.96 / 3), rel=1e-15)
    for bad in (dict(E1=0.0, nu1=0.3), dict(E1=1.0, nu1=0.6), dict(E1=1.0, nu1=0.3, E2=-1.0)):
        with pytest.raises(ValueError):
            asp.effective_modulus(**bad)
