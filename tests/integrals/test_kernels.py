"""Quadrature rules and the elastic kernel layers against independent slow twins: the tanh-sinh
θ rule against closed forms; the inner r-rule (partition + Gauss–Legendre, J_ν in closed form)
against scipy.integrate.quad; the Chebyshev interpolation in g against the direct θ-sum; the
far tail. (J_ν itself: integrals/test_normal_moments.py; the whole chain against mpmath:
contact/test_elastic.py, integrals/test_reference.py; the elasto-plastic kernel against its
scipy twin: contact/test_elastoplastic.py; no cross-file kernel calls: test_layout.py.)"""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad

from roughcontact import SpectralMoments
from roughcontact.contact.elastic import _theta_nodes
from roughcontact.integrals.production import elastic_inner_integrals, gaussian_moments, polar_elastic_integrals
from roughcontact.integrals.rules import PRESETS, QuadratureSettings, TanhSinh, settings_for, theta_rule

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
ANISO = SpectralMoments(1.0, 0.1, 1.0, 0.03, 300.0)  # m04/m40 = 1e4, g(θ) ∈ [0.07, 0.71]
LOW_BANDWIDTH = SpectralMoments(1.0, 1.0, 1.0, 2.2, 2.2)  # α ≈ 2.2, g(θ) ∈ [2.2, 3.2]


@pytest.mark.parametrize(
    "f, exact",
    [
        (np.sqrt, 2.0 / 3.0),  # derivative singular at 0
        (np.log, -1.0),  # logarithmic singularity
        (lambda y: np.sqrt(y * (1.0 - y)) * np.log(1.0 - y), None),  # both ends
    ],
)
def test_tanh_sinh_on_endpoint_singularities(f, exact):
    y, w = TanhSinh(4).nodes_weights
    if exact is None:  # ∫ √(y(1−y)) ln(1−y) dy = π(1 − 4 ln 2)/16 ... via mpmath
        exact = float(mp.quad(lambda t: mp.sqrt(t * (1 - t)) * mp.log(1 - t), [0, 1]))
    assert np.sum(w * f(y)) == pytest.approx(exact, rel=1e-13)


def test_strong_singularity_needs_a_wider_truncation():
    # ∫ y^{-1/2} = 2: the default rule omits y < 1e-16 (an O(1e-8) piece here); widening
    # the truncation restores it — the default is kept because our integrands are bounded
    f = lambda y: 1.0 / np.sqrt(y)  # noqa: E731
    y, w = TanhSinh(4).nodes_weights
    assert abs(np.sum(w * f(y)) - 2.0) < 1e-7
    y, w = TanhSinh(4, half_width=4.5).nodes_weights
    assert np.sum(w * f(y)) == pytest.approx(2.0, rel=1e-13)


def test_tanh_sinh_nodes_are_interior_and_symmetric():
    y, w = TanhSinh(3).nodes_weights
    assert np.all((y > 0) & (y < 1)) and np.all(w > 0)
    np.testing.assert_allclose(y + y[::-1], 1.0, atol=1e-16)
    assert np.sum(w) == pytest.approx(1.0, rel=1e-14)


def test_theta_rule_integrates_smooth_functions_with_breakpoints():
    th, w = theta_rule([0.3, 1.0], settings_for("table"))
    assert np.all(np.diff(th) > 0) and th[0] > 0 and th[-1] < math.pi / 2
    assert np.sum(w * np.cos(th) * np.sin(th)) == pytest.approx(0.5, rel=1e-14)
    # |θ − 0.3| has a kink at the breakpoint: still exact to rounding
    exact = (0.3**2 + (math.pi / 2 - 0.3) ** 2) / 2
    assert np.sum(w * np.abs(th - 0.3)) == pytest.approx(exact, rel=1e-14)


def test_presets_resolve_and_unknown_names_fail():
    assert settings_for("table") is PRESETS["table"]
    st = QuadratureSettings(3, 5, 4)
    assert (st.r_nodes, st.t_nodes, st.g_tol) == (24, 20, 1e-13)
    with pytest.raises(ValueError, match="unknown accuracy preset"):
        settings_for("fastest")


# --------------------------------------------------------------------------------------
# the inner r-integral against scipy.integrate.quad (J_ν from the tables, checked elsewhere)
# --------------------------------------------------------------------------------------
def _inner_by_quad(g, l):
    """∫₀^∞ r^p e^{−r²/2} J_ν(r g − l) dr for (p, ν) = (2, 1), (5/2, 3/2), (5/2, 1/2), adaptive
    Gauss–Kronrod with the kinks of the integrand's shape (r = l/g, the Gaussian centre
    l g/(1 + g²)) as break points, relative tolerance 2e-14."""
    q = 1.0 + g * g
    centre = max(l * g / q, 0.0)
    top = centre + 14.0 + (math.sqrt(2.0 * (45.0 + 0.5 * l * l / q)) if l > 0 else 0.0)
    pts = sorted({p for p in (l / g, centre, centre + 1.0 / math.sqrt(q)) if 0.0 < p < top})
    out = []
    for p_pow, col in ((2.0, 2), (2.5, 3), (2.5, 1)):
        def f(r, p_pow=p_pow, col=col):
            return r**p_pow * math.exp(-0.5 * r * r) * gaussian_moments(r * g - l)[0, col]

        val, _ = quad(f, 0.0, top, points=pts or None, epsabs=0.0, epsrel=2e-14, limit=400)
        out.append(val)
    return np.array(out)


G_VALUES = [0.07, 0.4, 1.4, 3.0]
L_VALUES = [-3.0, 0.0, 0.5, 2.0, 6.0, 20.0]


@pytest.mark.parametrize("preset, rtol", [("table", 1e-12), ("plot", 1e-8)])
def test_inner_r_rule_matches_scipy_quad(preset, rtol):
    """Measured (g ≤ 3, l ∈ [−3, 20]): table ≤ 1.2e-14, plot ≤ 2.8e-9."""
    g, l = np.meshgrid(G_VALUES, L_VALUES, indexing="ij")
    got = elastic_inner_integrals(g.ravel(), l.ravel(), preset)
    for k, (gk, lk) in enumerate(zip(g.ravel(), l.ravel())):
        np.testing.assert_allclose(got[k], _inner_by_quad(gk, lk), rtol=rtol, err_msg=f"g={gk}, l={lk}")


def test_inner_integrals_are_positive_and_underflow_cleanly():
    I = elastic_inner_integrals([0.4, 0.4, 0.4], [30.0, 60.0, 1e4])
    assert np.all(np.isfinite(I)) and np.all(I >= 0)
    assert np.all(I[0] > 0) and np.all(I[0] < 1e-150) and np.all(I[2] == 0.0)


# --------------------------------------------------------------------------------------
# the θ-sum: Chebyshev interpolation in g against the direct sum over θ-nodes
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize("surface", [TABLE1, ANISO, LOW_BANDWIDTH], ids=["table1", "aniso1e4", "alpha2.2"])
def test_g_interpolation_matches_direct_theta_sum(surface):
    """The interpolation converged (used) and agrees with integrating every θ-node (measured
    ≤ 6e-15 at "table")."""
    w_area, w_load, _, g = _theta_nodes(surface, "exact", "table")
    l = surface.l_from_s(np.array([-1.0, 0.5, 2.0, 5.0, 12.0]))
    fast, used = polar_elastic_integrals(l, w_area, w_load, g, "table", return_used=True)
    slow = polar_elastic_integrals(l, w_area, w_load, g, "table", interpolate=False)
    assert np.all(used)
    np.testing.assert_allclose(fast, slow, rtol=1e-12)


def test_far_tail_is_zero_or_tiny_never_nan():
    w_area, w_load, _, g = _theta_nodes(TABLE1, "exact", "table")
    l = TABLE1.l_from_s(np.array([30.0, 60.0, 1e3]))
    out = polar_elastic_integrals(l, w_area, w_load, g, "table")
    assert np.all(np.isfinite(out)) and np.all(out >= 0)
    assert np.all(out[0] > 0) and np.all(out[0] < 1e-150) and np.all(out[2] == 0.0)


def test_threads_and_serial_give_the_same_numbers():
    """Many separations run split over threads, few serially: the same per-separation sums."""
    w_area, w_load, _, g = _theta_nodes(TABLE1, "exact", "plot")
    l = TABLE1.l_from_s(np.linspace(-1.0, 6.0, 24))
    batch = polar_elastic_integrals(l, w_area, w_load, g, "plot")
    single = np.array([polar_elastic_integrals([x], w_area, w_load, g, "plot")[0] for x in l])
    np.testing.assert_array_equal(batch, single)


# --------------------------------------------------------------------------------------
# numba's on-disk cache (docs/performance.md): one signature per kernel (no cross-file calls:
# tests/test_layout.py)
# --------------------------------------------------------------------------------------
def _dispatchers(module):
    import numba.core.registry

    return {k: v for k, v in vars(module).items() if isinstance(v, numba.core.registry.CPUDispatcher)}


def test_every_kernel_has_one_signature_after_varied_calls():
    """Concurrent processes sharing numba's cache are safe only while each kernel has one key
    (two keys written at once can be given the same data file): feed the public API lists,
    scalars, float32 and non-contiguous arrays, one and many separations, every preset — each
    kernel must still have compiled exactly one signature."""
    import roughcontact.integrals.kernels as K
    import roughcontact.integrals.production as Q
    from roughcontact import asperity as asp
    from roughcontact.contact import bearing_area, elastic_contact
    from roughcontact.contact.elastoplastic import elastoplastic_contact

    s32 = np.linspace(0.0, 3.0, 10, dtype=np.float32)
    for acc in ("table", "plot"):
        elastic_contact(TABLE1, [1.0], 1.0, accuracy=acc)
        elastic_contact(TABLE1, s32[::2], 1.0, accuracy=acc, hertz="paper")
        elastic_contact(TABLE1, np.linspace(0, 3, 12), 1.0, accuracy=acc)
        elastic_contact(TABLE1, 2.0, 1.0, model="gw", accuracy=acc)
        bearing_area(TABLE1, s32, accuracy=acc)
        mat = asp.AsperityMaterial(1.0, 1e-3)
        elastoplastic_contact(TABLE1, [1.0], mat, accuracy=acc)
        elastoplastic_contact(TABLE1, s32[::3], asp.AsperityMaterial.with_paper_K_v(1.0, 1e-3, 0.3), accuracy=acc)
    Q.normal_moment(3)
    Q.gaussian_moments([1, 2])
    Q.elastic_inner_integrals(np.float32(0.5), [1, 2])
    Q.asperity_law([1e-3], 2.0, 1.0, 1.0, 1.0, 1e-3, 1.0, 45.0, 1.0, 0.3)
    many = {k: len(d.signatures) for k, d in _dispatchers(K).items() if len(d.signatures) > 1}
    assert not many, many
