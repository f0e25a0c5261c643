"""The elasto-plastic kernel's layers against independent slow twins (issue 24, the τ = r t
route, docs/performance.md): the hyperbola integrals G_k(τ) against scipy.integrate.quad, their
closed form at τ = 0 against quad and mpmath, the interpolation grid against direct
evaluation, the nested θ-levels against a fixed finer level, threads against serial. (The whole
kernel against the scipy twin of the summit integrals: tests/contact/test_elastoplastic.py.)"""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad

from roughcontact import SpectralMoments
from roughcontact.asperity import AsperityMaterial, yield_strength_for_plasticity_index
from roughcontact.contact import elastoplastic as EP
from roughcontact.integrals.production import (
    hyperbola_grid_values,
    hyperbola_moments,
    hyperbola_moments_at_zero,
    polar_elastoplastic_integrals,
)
from roughcontact.integrals.rules import (
    ELASTOPLASTIC_PRESETS,
    ElastoPlasticSettings,
    QuadratureSettings,
    elastoplastic_settings_for,
    nested_theta_rule,
    theta_rule,
)

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
ANISO = SpectralMoments(1.0, 0.1, 1.0, 0.03, 300.0)


def _by_quad(tau, g, l, k):
    """G_k(τ) = ∫_0^∞ r^k e^{−r²/2} φ(τ/r + l − g r) dr by adaptive Gauss–Kronrod in u = ln r on
    400 equal pieces of [ln τ − 14, 3.6] (every feature — the τ/r wall, the φ-peak, the
    r-bump — is wider than a piece), relative tolerance 1e-13."""
    def f(u):
        r = math.exp(u)
        z = tau / r + l - g * r
        return r ** (k + 1) * math.exp(-0.5 * r * r - 0.5 * z * z) / math.sqrt(2.0 * math.pi)

    edges = np.linspace(math.log(tau) - 14.0, 3.6, 401)
    return sum(quad(f, a, b, epsabs=0.0, epsrel=1e-13)[0] for a, b in zip(edges[:-1], edges[1:]))


#: (τ, g, l): light and heavy loads, the bimodal l < 0 cases (a φ-peak at r ≈ τ/|l| and the
#: r-bump), tiny and large τ, g from the anisotropic surface (0.07) to α ≈ 2.2 (3.2)
CASES = [(tau, g, l) for tau in (1e-6, 1e-3, 0.05, 0.7, 4.0, 25.0) for g in (0.07, 0.45, 3.2)
         for l in (-3.0, -1.0, 0.0, 1.5, 6.0)]


@pytest.mark.parametrize("preset, tol", [("table", 1e-12), ("plot", 1e-8)])
def test_hyperbola_moments_match_scipy_quad(preset, tol):
    """Measured (these 90 cases): table ≤ 4e-15, plot ≤ 3e-11 relative (absolute in ln G)."""
    tau, g, l = (np.array(v) for v in zip(*CASES))
    got = hyperbola_moments(tau, g, l, preset)
    for i, (t, gg, ll) in enumerate(CASES):
        for k in (0, 1):
            ref = _by_quad(t, gg, ll, k)
            if ref < 1e-280:
                continue
            assert abs(got[i, k] - math.log(ref)) <= tol, (t, gg, ll, k)


def test_hyperbola_moments_at_zero_closed_form():
    """G_k(0) = ∫ r^k e^{−r²/2} φ(l − g r) dr: against quad where it is a normal double, against
    mpmath where it underflows (the kernel returns logs)."""
    for g, l in ((0.45, 1.5), (3.2, -3.0), (0.07, 6.0), (1.0, 0.0)):
        got = hyperbola_moments_at_zero(g, l)[0]
        for k in (0, 1):
            def f(r, k=k):
                return r**k * math.exp(-0.5 * r * r) * math.exp(-0.5 * (l - g * r) ** 2) / math.sqrt(2 * math.pi)
            ref, _ = quad(f, 0.0, 40.0, epsabs=0.0, epsrel=2e-14, limit=200)
            assert got[k] == pytest.approx(math.log(ref), abs=1e-13)
    # where it underflows (the kernel returns logs: erfc, then the asymptotic series of J_ν):
    # against mpmath's ncdf/npdf at 50 digits, G_0 = e^{−l²/2q} Φ(x)/√q, G_1 = e^{−l²/2q}
    # (x Φ(x) + φ(x))/q, x = l g/√q (the quadrature of the line above, reduced by hand)
    with mp.workdps(50):
        for g, l in ((0.45, -120.0), (3.2, 50.0), (0.07, 400.0), (1.0, -40.0)):
            got = hyperbola_moments_at_zero(g, l)[0]
            q = 1 + g * g
            x = mp.mpf(l) * g / mp.sqrt(q)
            base = -mp.mpf(l) ** 2 / (2 * q)
            ref0 = base + mp.log(mp.ncdf(x) / mp.sqrt(q))
            ref1 = base + mp.log((x * mp.ncdf(x) + mp.npdf(x)) / q)
            assert got[0] == pytest.approx(float(ref0), rel=1e-14)
            assert got[1] == pytest.approx(float(ref1), rel=1e-14)


@pytest.mark.parametrize("l", [-1.2, 0.0, 1.3, 6.0])
@pytest.mark.parametrize("surface", ["table1", "aniso"])
def test_grid_interpolates_the_hyperbola_moments(surface, l):
    """ln G_k from the grid against direct evaluation at points between the grid's nodes, over
    the surface's g-range and τ from far below the grid (its small-τ model) to its top.
    Measured on the grid ≤ 3e-12 (table), ≤ 4e-9 (plot); below it (≥ 10 below ln τ of the
    bulk, where τ^{ν+1} weighs it by ≤ e^{−10}) ≤ 2e-8."""
    g_lo, g_hi = (0.3505, 0.4951) if surface == "table1" else (0.0715, 0.7124)
    rng = np.random.default_rng(3)
    g = rng.uniform(g_lo, g_hi, 80)
    tau = np.exp(rng.uniform(-16.0, 3.0, 80))
    direct = hyperbola_moments(tau, g, l, "table")
    keep = direct[:, 0] > direct[:, 0].max() - 30.0  # what the integrals can see
    for preset, tol in (("table", 3e-11), ("plot", 3e-8)):
        got, info = hyperbola_grid_values(l, (g_lo, g_hi), tau, g, preset)
        assert info[1] == 1.0
        on = keep & (np.log(tau) >= info[4])
        below = keep & (np.log(tau) < info[4])
        assert on.sum() > 30 and below.sum() > 5
        np.testing.assert_allclose(got[on], direct[on], rtol=0, atol=tol, err_msg=preset)
        np.testing.assert_allclose(got[below], direct[below], rtol=0, atol=1e-6, err_msg=preset)


def test_nested_theta_rules_are_the_single_level_rules():
    th, counts, w = nested_theta_rule([0.3, 1.0], (2, 4))
    assert list(counts) == [75, 147, 297]
    for m, level in enumerate((2, 3, 4)):
        t_single, w_single = theta_rule([0.3, 1.0], QuadratureSettings(level, 1, 1))
        order = np.argsort(th[:counts[m]])
        np.testing.assert_allclose(th[:counts[m]][order], np.sort(t_single), rtol=0, atol=1e-15)
        np.testing.assert_allclose(w[m, :counts[m]][order], w_single[np.argsort(t_single)], rtol=1e-14)
        assert np.all(w[m, counts[m]:] == 0.0)
    with pytest.raises(ValueError, match="theta levels"):
        nested_theta_rule([], (3, 2))


def _material(psi, surface=TABLE1):
    return AsperityMaterial(1.14e5, yield_strength_for_plasticity_index(psi, surface, 1.14e5))


@pytest.mark.parametrize("psi", [0.35, 5.0])
def test_adaptive_theta_level_keeps_its_estimate(psi):
    """The presets add θ-levels until e·min(1, e/e_prev) ≤ theta_tol; the sum they stop at is
    within that of a fixed level two finer (measured: the estimate is 10²–10⁶ × pessimistic)."""
    s = np.array([0.0, 2.0, 4.0])
    mat = _material(psi)
    for preset in ("plot", "table"):
        st = ELASTOPLASTIC_PRESETS[preset]
        got, info = EP._production(TABLE1, TABLE1.l_from_s(s), mat, "exact", preset, return_info=True)
        used = st.theta_levels[0] + info[:, 2].astype(int)
        for i in range(s.size):
            finer = ElastoPlasticSettings(**{**st.__dict__, "theta_levels": (used[i] + 2, used[i] + 2)})
            ref = EP._production(TABLE1, TABLE1.l_from_s(s[i:i + 1]), mat, "exact", finer)[0]
            tot = np.array([ref[:3].sum()] * 3 + [ref[3:6].sum()] * 3 + [ref[6], ref[6]])
            err = np.abs(got[i] - ref) / np.maximum(np.abs(ref), 1e-3 * np.abs(tot))
            assert np.nanmax(err[:7]) <= max(info[i, 3], 1e-15) * 10 + st.theta_tol, (preset, s[i])


def test_threads_and_serial_give_the_same_numbers():
    """Separations split over the threads, one at a time, one thread for all: the same numbers
    to the last bit (the grid sizes and θ-levels do not depend on who computes them)."""
    import numba

    mat = _material(1.0)
    nodes = EP._theta_nodes(TABLE1, "exact", "plot", mat)
    sigma = math.sqrt(TABLE1.m00 * TABLE1.mu)
    mc = EP._material_constants(mat)
    l = TABLE1.l_from_s(np.linspace(-0.5, 4.0, 5))
    batch = polar_elastoplastic_integrals(l, nodes, sigma, mc, "plot")
    single = np.array([polar_elastoplastic_integrals([x], nodes, sigma, mc, "plot")[0] for x in l])
    threads = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        serial = polar_elastoplastic_integrals(l, nodes, sigma, mc, "plot")
    finally:
        numba.set_num_threads(threads)
    np.testing.assert_array_equal(batch, single)
    np.testing.assert_array_equal(batch, serial)


def test_settings_from_quadrature_levels():
    st = elastoplastic_settings_for(QuadratureSettings(3, 5, 4))
    assert st.theta_levels == (3, 3) and st.tau_nodes == 20 and st.grid_tol == 1e-13
    assert elastoplastic_settings_for("plot") is ELASTOPLASTIC_PRESETS["plot"]
    with pytest.raises(ValueError, match="unknown accuracy preset"):
        elastoplastic_settings_for("fastest")
