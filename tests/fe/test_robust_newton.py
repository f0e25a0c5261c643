"""Robust Newton (issue 23): a trial iterate past the heavy end of the tabulated law gets the
law's tangent tail instead of a refusal; the table's range is judged on converged states only;
the residual line search.

The model of the issue: a steel block on a larger cast-iron base (C3D20-like quadratic
hexahedra through `box`, `merge`, `interface_between`, benchmarks/block_on_base.py), loaded
from zero with the law seated at 1e-3 N/mm². Before, the engine stopped at its first increment
("no convergence at increment 1 (load level 0.000977): u_N = … exceeds the heavy end of the
tabulated normal law (p_max = 100)") although the solution's largest pressure is ~35 N/mm².
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.fe import solver as solver_module
from roughcontact.fe.contact import statistical_interface
from roughcontact.fe.solver import ConvergenceError, LawRangeError, NewtonOptions, solve
from roughcontact.interface import InterfaceLaw, NormalLawTable
from roughcontact.interface.normal_law import _slope_is_negative

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

import block_on_base as bob  # noqa: E402

SURFACE = SpectralMoments(**bob.MOMENTS)


@pytest.fixture(scope="module")
def law():
    table = NormalLawTable.build(SURFACE, "elastic", E_star=78065.86, pressure_range=(1e-5, 100.0), accuracy="plot")
    return InterfaceLaw.from_pressure(table, 1e-3)


@pytest.fixture(scope="module")
def problem():
    return bob.BlockOnBase(refine=1, increments=4)


@pytest.fixture(scope="module")
def model(problem):
    return bob.engine_model(problem)[1]


# -------------------------------------------------------------------------------------------
# the law's tail
# -------------------------------------------------------------------------------------------
def test_extrapolated_law_equals_the_law_inside_the_table(law):
    ext = law.extrapolated()
    assert ext.extrapolate and not law.extrapolate and ext.extrapolated() is ext
    assert ext.u_max == law.u_max and ext.table is law.table
    u = np.linspace(law.u_open - 0.1, law.u_max, 2001)[:-1]
    p, k = law.normal(u)
    pe, ke = ext.normal(u)
    # the same interpolant on the same intervals: identical to the last bit
    assert np.array_equal(p, pe) and np.array_equal(k, ke)


def test_tail_is_the_tangent_continuation(law):
    """Past u_max: p_N = p_max + k_max (u_N − u_max) to within the interpolation of the tail's
    nodes (measured 0.1 % at 0.1 µm, 7e-6 at 100 µm), C¹ at u_max, monotone (q' proven negative
    on every interval of the extended table)."""
    ext = law.extrapolated()
    tab = ext.kernel_data()[0]
    assert np.all(_slope_is_negative(tab))
    u_max = law.u_max
    p_max, k_max = law.normal(u_max - 1e-12)
    d = np.array([1e-9, 1e-3, 0.1, 1.0, 10.0, 100.0])
    p, k = ext.normal(u_max + d)
    linear = p_max + k_max * d
    assert np.all(np.abs(p / linear - 1.0) < 5e-3)
    assert np.all(k > 0.0) and np.all(np.abs(k / k_max - 1.0) < 0.05)
    assert np.all(np.diff(ext.normal(u_max + np.linspace(0.0, 10.0, 5001))[0]) > 0.0)
    # C¹: the values and slopes either side of u_max agree to the step
    h = 1e-9
    below, above = law.normal(u_max - h), ext.normal(u_max + h)
    assert above[0] - below[0] == pytest.approx(2 * h * k_max, rel=1e-3)
    assert above[1] == pytest.approx(below[1], rel=1e-6)


def test_beyond_the_tail_and_without_it_is_an_error(law):
    with pytest.raises(ValueError, match="heavy end of the table"):
        law.normal(law.u_max + 1e-3)
    ext = law.extrapolated()
    p_end = 1e6 * law.table.p_max
    k_max = law.normal(law.u_max - 1e-12)[1]
    with pytest.raises(ValueError, match="extrapolated tail"):
        ext.normal(law.u_max + 10 * p_end / k_max)


def test_material_extrapolates_trial_states_only_on_request(law):
    mat = statistical_interface(SURFACE, 1e-3, E_star=78065.86, pressure_range=(1e-5, 100.0))
    state = mat.initial_state(2)
    jump = np.array([[0.0, 0.0, -0.5e-3], [0.0, 0.0, -(mat.normal.u_max + 0.2) / 1000.0]])  # mm, closing
    with pytest.raises(ValueError, match="heavy end"):
        mat.respond(state, jump)
    resp = mat.respond(state, jump, extrapolate=True)
    assert np.all(np.isfinite(resp.tractions)) and np.all(np.isfinite(resp.tangent))
    assert mat.beyond_table(resp.state).tolist() == [False, True]
    inside = mat.respond(state[:1], jump[:1])
    assert np.array_equal(inside.tractions, resp.tractions[:1])


# -------------------------------------------------------------------------------------------
# the block on a base, loaded from zero
# -------------------------------------------------------------------------------------------
def test_first_newton_iterate_leaves_the_table(model, problem):
    """The reason of the old failure, shown directly: from the seated state the tangent is the
    soft k_N(p0), and the first Newton step closes the interface far past u_max."""
    mat = model.material
    state = mat.initial_state(model.points.n_points)
    u = np.zeros(model.stiffness.shape[0])
    level = problem.levels[0]
    resp = mat.respond(state, model.points.jumps(u))
    r = (level * model.load - model.stiffness @ u
         - solver_module.interface_forces(model.points, resp.tractions))[model.free]
    u[model.free] += solver_module._linear_solver(model, "auto")(model.points, resp.tangent, r, u[model.free], level)
    closure = mat.closure_mm(mat.respond(state, model.points.jumps(u), extrapolate=True).state) * 1000.0
    assert closure.max() > mat.normal.u_max


@pytest.mark.parametrize("line_search", [True, False])
def test_block_on_base_loaded_from_zero_converges(model, problem, line_search):
    """With the tail (and with or without the line search) every level converges without a
    cut-back, each converged state inside the table, and the interface carries the applied load
    (the force tolerance 1e-9 bounds the equilibrium error; 1e-8 leaves a margin)."""
    sol = solve(model, problem.levels, NewtonOptions(line_search=line_search))
    assert [inc.cutbacks for inc in sol.increments] == [0] * problem.increments
    for k, inc in enumerate(sol.increments):
        assert not model.material.beyond_table(inc.state).any()
        assert sol.equilibrium_error(k) <= 1e-8
    p = -sol.final.tractions[:, 2]
    assert 20.0 < p.max() < 100.0  # the loaded edge, well inside the table (~35 N/mm² here)


def test_line_search_changes_the_path_not_the_answer(model, problem):
    """Same converged displacements with and without the line search (both converge to the
    force tolerance 1e-9; measured 1e-13 relative), and no more iterations with it."""
    on = solve(model, problem.levels, NewtonOptions(line_search=True))
    off = solve(model, problem.levels, NewtonOptions(line_search=False))
    for a, b in zip(on.increments, off.increments):
        np.testing.assert_allclose(a.u, b.u, rtol=0, atol=1e-9 * np.max(np.abs(b.u)))
    assert sum(i.iterations for i in on.increments) <= sum(i.iterations for i in off.increments)


def test_converged_state_beyond_the_table_is_a_clear_error(problem):
    """A load whose solution needs pressures above p_max: the iterations may cross the table's
    end (tail), but the converged state beyond it stops the run with the increment, the level,
    the pressure reached and p_max — a ConvergenceError (the command line's exit 1)."""
    heavy = bob.BlockOnBase(refine=1, increments=4, pressure=150.0)
    model = bob.engine_model(heavy)[1]
    with pytest.raises(LawRangeError) as info:
        solve(model, heavy.levels)
    err = info.value
    assert isinstance(err, ConvergenceError)
    msg = str(err)
    assert f"increment {err.increment}" in msg and "p_max = 100" in msg and "converged beyond" in msg
    assert err.level in heavy.levels
    p_reached = float(msg.split("p_N up to ")[1].split()[0])
    assert p_reached > 100.0


def test_beyond_even_the_tail_cuts_back_as_before(model, problem):
    """Past the tail's end (10⁶ p_max) the trial is still refused: with one iteration per
    attempt and no cut-backs the run fails with a ConvergenceError naming the increment."""
    with pytest.raises(ConvergenceError, match="increment 1"):
        solve(model, problem.levels, NewtonOptions(max_iterations=1, max_cutbacks=0))

