"""Quadrature rules and the numba kernel for J_ν(a) = E[(Z + a)₊^ν], against closed forms
and mpmath (the kernel's slow twin)."""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.special import ndtr

from roughcontact.quadrature import PRESETS, TanhSinh, normal_moment, settings_for, theta_rule


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


def _J_mpmath(nu, a):
    """J_ν(a) = Γ(ν+1)/√(2π) e^{−a²/4} D_{−ν−1}(−a) at 30 digits (parabolic cylinder D)."""
    with mp.workdps(30):
        a = mp.mpf(a)
        return float(mp.gamma(nu + 1) / mp.sqrt(2 * mp.pi) * mp.exp(-a * a / 4) * mp.pcfd(-nu - 1, -a))


A_VALUES = [-35.0, -10.0, -3.0, -0.5, 0.0, 0.7, 3.0, 9.0, 30.0]


@pytest.mark.mpmath
@pytest.mark.parametrize("preset, tol", [("table", 5e-15), ("plot", 5e-7)])
def test_normal_moments_against_mpmath(preset, tol):
    J = normal_moment(A_VALUES, preset)
    for i, a in enumerate(A_VALUES):
        for k, nu in enumerate((0.5, 1.0, 1.5)):
            assert J[i, k] == pytest.approx(_J_mpmath(nu, a), rel=tol), (a, nu)


def test_first_moment_closed_form():
    # J_1(a) = a Φ(a) + φ(a) (GW's F_1); evaluated where the closed form has no cancellation
    a = np.array([-2.0, -1.0, 0.0, 1.0, 4.0])
    closed = a * ndtr(a) + np.exp(-0.5 * a * a) / math.sqrt(2 * math.pi)
    np.testing.assert_allclose(normal_moment(a)[:, 1], closed, rtol=1e-14)


def test_moments_deep_in_the_tail_underflow_to_zero():
    J = normal_moment([-40.0, -1e3, -1e300])
    assert np.all(np.isfinite(J)) and np.all(J >= 0)
    assert np.all(J[1:] == 0.0) and np.all(J[0] < 1e-300)


def test_normal_moment_rejects_nan():
    with pytest.raises(ValueError, match="finite"):
        normal_moment([0.0, np.nan])


def test_theta_rule_integrates_smooth_functions_with_breakpoints():
    th, w = theta_rule([0.3, 1.0], settings_for("table"))
    assert np.all(np.diff(th) > 0) and th[0] > 0 and th[-1] < math.pi / 2
    assert np.sum(w * np.cos(th) * np.sin(th)) == pytest.approx(0.5, rel=1e-14)
    # |θ − 0.3| has a kink at the breakpoint: still exact to rounding
    exact = (0.3**2 + (math.pi / 2 - 0.3) ** 2) / 2
    assert np.sum(w * np.abs(th - 0.3)) == pytest.approx(exact, rel=1e-14)


def test_presets_resolve_and_unknown_names_fail():
    assert settings_for("table") is PRESETS["table"]
    with pytest.raises(ValueError, match="unknown accuracy preset"):
        settings_for("fastest")
