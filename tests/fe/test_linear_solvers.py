"""The kept-factor Krylov strategies (roughcontact.fe.linear_solvers; "sparse-krylov" and
"condensed-krylov" of roughcontact.fe.solver, issue 31): right-preconditioned GMRES against a
direct solve, the refactoring policy, and Newton's answer unchanged — the same iterations per
increment and the same converged state as the direct "sparse" strategy within Newton's own
displacement tolerance — on the block of tests/fe/test_solver.py (frictionless: symmetric
tangent; Coulomb: unsymmetric) and on a frictional plate-on-base deck (benchmarks/fe_large_interface.py).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from roughcontact.fe import solver as solver_module
from roughcontact.fe.interface_points import interface_tangent
from roughcontact.fe import linear_solvers as ls
from roughcontact.fe.linear_solvers import KRYLOV_RTOL, MAX_KRYLOV, ReusedFactor, gmres_right
from roughcontact.fe.solver import NewtonOptions, solve
from roughcontact.interface import friction as fr

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from test_solver import P0, block_model, materials, slipped_state  # noqa: E402,F401  (the fixture)

KRYLOV = ("sparse-krylov", "condensed-krylov")


def _unsymmetric(n, seed):
    """A well-conditioned unsymmetric sparse matrix: a 1-D Laplacian plus a random skew part."""
    rng = np.random.default_rng(seed)
    L = sp.diags([-1.0, 2.5, -1.0], [-1, 0, 1], shape=(n, n))
    R = sp.random(n, n, density=5.0 / n, random_state=seed)
    return (L + 0.3 * (R - R.T)).tocsc(), rng.normal(size=n)


def test_gmres_right_solves_to_the_true_residual():
    """With the exact factor as preconditioner one iteration; with the factor of a perturbed
    matrix a few; the recomputed residual meets KRYLOV_RTOL and x matches a direct solve."""
    A, b = _unsymmetric(400, 1)
    exact = spla.spsolve(A, b)
    x, its = gmres_right(A.__matmul__, spla.splu(A).solve, b, KRYLOV_RTOL, MAX_KRYLOV)
    assert its == 1 and np.linalg.norm(b - A @ x) <= KRYLOV_RTOL * np.linalg.norm(b)
    P = (A + 0.2 * sp.diags(np.random.default_rng(2).uniform(size=400))).tocsc()  # diagonal 8 % off
    x, its = gmres_right(A.__matmul__, spla.splu(P).solve, b, KRYLOV_RTOL, MAX_KRYLOV)
    assert 2 <= its <= MAX_KRYLOV and np.linalg.norm(b - A @ x) <= KRYLOV_RTOL * np.linalg.norm(b)
    # cond(A) ~ 10: the error is within cond·rtol of the solution
    np.testing.assert_allclose(x, exact, rtol=0, atol=1e-8 * np.max(np.abs(exact)))
    assert gmres_right(A.__matmul__, spla.splu(P).solve, b, KRYLOV_RTOL, 1) == (None, 1)  # not met: None
    assert gmres_right(A.__matmul__, spla.splu(P).solve, np.zeros(400), KRYLOV_RTOL, 5)[1] == 0


def test_reused_factor_refactors_when_krylov_fails():
    """The first solve factors; a nearby matrix reuses the factor (GMRES); a far one (the
    preconditioner useless within the iteration limit) refactors and solves directly."""
    A, b = _unsymmetric(300, 3)
    reuse = ReusedFactor(max_iterations=6)
    made = []

    def factorise(M):
        def f():
            made.append(M)
            return spla.splu(M).solve
        return f

    for M in (A, (A + 0.01 * sp.eye(300)).tocsc(), (A + sp.diags(np.linspace(0, 50, 300))).tocsc()):
        x = reuse.solve(M.__matmul__, b, factorise(M))
        assert np.linalg.norm(b - M @ x) <= KRYLOV_RTOL * np.linalg.norm(b)
    s = reuse.stats
    assert (s.factorisations, s.krylov_solves, s.krylov_failures) == (2, 1, 1) and made[-1] is not A


@pytest.mark.parametrize("kind", KRYLOV)
@pytest.mark.parametrize("tangential", ["free", "coulomb"])
def test_krylov_strategies_solve_the_tangent_system(kind, tangential, materials):
    """Against spsolve of K_t du = r, after a first solve with another tangent (so the kept
    factor is a preconditioner of the wrong matrix and GMRES does the work)."""
    model, u, r, resp = slipped_state(materials, tangential)
    free = model.free
    linear = solver_module._linear_solver(model, kind)
    linear(model.points, 0.5 * resp.tangent, r, u[free], 1.0)  # factor kept: another tangent
    du = linear(model.points, resp.tangent, r, u[free], 1.0)
    assert linear.reuse.stats.krylov_solves >= 1
    Kt = (model.stiffness + interface_tangent(model.points, resp.tangent)).tocsr()[free][:, free]
    ref = spla.spsolve(Kt.tocsc(), r)
    # ‖r − K_t du‖ ≤ 1e-12 ‖r‖ and cond(K_t) ≈ 1e3 (tests/fe/test_solver.py): error ≤ 1e-9 of du
    assert np.linalg.norm(r - Kt @ du) <= KRYLOV_RTOL * np.linalg.norm(r)
    np.testing.assert_allclose(du, ref, rtol=0, atol=1e-9 * np.max(np.abs(ref)))


@pytest.mark.parametrize("tangential", ["free", "coulomb"])
def test_newton_answer_unchanged(tangential, materials):
    """The same Newton iterations per increment and the same converged u as the direct solve
    within Newton's displacement tolerance (displacement_rtol = 1e-8 of the displacements)."""
    levels = [P0, 0.5, 1.0, 2.0]
    direct = solve(block_model(materials[tangential], n=(3, 3, 3)), levels, NewtonOptions(linear_solver="sparse"))
    for kind in KRYLOV:
        model = block_model(materials[tangential], n=(3, 3, 3))
        sol = solve(model, levels, NewtonOptions(linear_solver=kind))
        assert [i.iterations for i in sol.increments] == [i.iterations for i in direct.increments]
        scale = np.max(np.abs(direct.final.u))
        for a, b in zip(sol.increments, direct.increments):
            np.testing.assert_allclose(a.u, b.u, rtol=0, atol=1e-8 * scale)
            assert np.array_equal(a.status, b.status)
        stats = solver_module._linear_solver(model, kind).reuse.stats
        assert stats.krylov_solves > stats.factorisations  # the factor was reused


def test_frictional_plate_on_base_deck(tmp_path):
    """The benchmark's deck (4 × 4 in plan) with Coulomb friction: the Krylov strategies give the
    direct strategy's iterations, interface statuses and displacements (within 1e-8 of them)."""
    import fe_large_interface as bench
    from roughcontact.fe.deck_run import run_deck_file

    deck, law = tmp_path / "plate.inp", tmp_path / "LAW.yaml"
    deck.write_text(bench.plate_on_base_deck(4, 1, 1))
    law.write_text(bench.law_yaml(friction=True))
    runs = {kind: run_deck_file(deck, law, options=NewtonOptions(linear_solver=kind))
            for kind in ("sparse", *KRYLOV)}
    ref = runs["sparse"]
    assert any(np.any(inc.status == fr.SLIP) for inc in ref.increments)  # the unsymmetric tangent is met
    scale = max(np.max(np.abs(inc.u)) for inc in ref.increments)
    for kind in KRYLOV:
        assert [i.iterations for i in runs[kind].increments] == [i.iterations for i in ref.increments]
        for a, b in zip(runs[kind].increments, ref.increments):
            assert np.array_equal(a.status, b.status)
            np.testing.assert_allclose(a.u, b.u, rtol=0, atol=1e-8 * scale)


def test_cli_solver_choices_are_the_solvers():
    from roughcontact.cli import fe as cli_fe

    assert cli_fe.LINEAR_SOLVERS == solver_module.LINEAR_SOLVERS


def test_adaptive_budget_weighs_a_factorisation_against_iterations():
    """Budget None: a factorisation that costs ≫ an iteration lets GMRES run up to
    MAX_KRYLOV_CAP iterations (stale beyond half of them); a cheap one keeps the minimum
    MAX_KRYLOV / REFACTOR_AFTER; fixed integers are kept as given."""
    A, b = _unsymmetric(200, 5)

    def factorise(delay):
        def f():
            time.sleep(delay)
            return spla.splu(A).solve
        return f

    slow = ReusedFactor()
    slow.solve(A.__matmul__, b, factorise(0.5))  # 0.5 s against ~1e-4 s per iteration
    assert slow.max_iterations == ls.MAX_KRYLOV_CAP and slow.refactor_after == ls.MAX_KRYLOV_CAP // 2
    fast = ReusedFactor()
    fast.solve(A.__matmul__, b, factorise(0.0))
    assert MAX_KRYLOV <= fast.max_iterations < ls.MAX_KRYLOV_CAP
    assert fast.refactor_after == max(ls.REFACTOR_AFTER, fast.max_iterations // 2)
    fixed = ReusedFactor(refactor_after=3, max_iterations=7)
    fixed.solve(A.__matmul__, b, factorise(0.5))
    assert (fixed.refactor_after, fixed.max_iterations) == (3, 7)


def test_krylov_accepts_the_direct_solves_own_accuracy():
    """The accepted residual is max(rtol, ρ_f): ρ_f the relative residual of the direct solve
    right after the factorisation, recomputed here independently."""
    A, b = _unsymmetric(300, 7)
    reuse = ReusedFactor()
    x = reuse.solve(A.__matmul__, b, lambda: spla.splu(A).solve)
    assert reuse.floor == pytest.approx(np.linalg.norm(b - A @ x) / np.linalg.norm(b), rel=1e-12, abs=0.0)
    assert reuse.floor < 1e-14  # cond(A) ~ 10: the direct solve is accurate to round-off


def test_gmres_restarts_on_the_recomputed_residual():
    """A preconditioner with a tiny error ε = 1e-9 in one solve of three makes the Arnoldi
    estimate drift from the true residual; with restarts (iterative refinement) the recomputed
    residual still meets the target, and x matches the direct solve."""
    A, b = _unsymmetric(300, 9)
    lu = spla.splu(A)
    calls = []

    def noisy(v):
        calls.append(1)
        x = lu.solve(v)
        return x * (1.0 + 1e-9) if len(calls) % 3 == 1 else x
    x, its = gmres_right(A.__matmul__, noisy, b, KRYLOV_RTOL, 30)
    assert x is not None and np.linalg.norm(b - A @ x) <= KRYLOV_RTOL * np.linalg.norm(b)
    np.testing.assert_allclose(x, spla.spsolve(A, b), rtol=0, atol=1e-10 * np.max(np.abs(x)))


BACKENDS = ["superlu", pytest.param("pardiso", marks=pytest.mark.skipif(
    not ls.pardiso_available(), reason="pypardiso (optional) not installed"))]


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("krylov", [False, True])
@pytest.mark.parametrize("tangential", ["free", "coulomb"])
def test_sparse_backends_solve_the_tangent_system(backend, krylov, tangential, materials):
    """Each sparse factorisation, direct or kept for GMRES, against spsolve of K_t du = r on the
    slipped block (Coulomb: the unsymmetric tangent, factored as it is)."""
    model, u, r, resp = slipped_state(materials, tangential)
    free = model.free
    linear = ls.Sparse(model, krylov, backend)
    assert linear.backend == backend
    if krylov:
        linear(model.points, 0.5 * resp.tangent, r, u[free], 1.0)  # the kept factor: another tangent
    du = linear(model.points, resp.tangent, r, u[free], 1.0)
    Kt = (model.stiffness + interface_tangent(model.points, resp.tangent)).tocsr()[free][:, free]
    ref = spla.spsolve(Kt.tocsc(), r)
    if tangential == "coulomb":
        assert not np.allclose(Kt.toarray(), Kt.toarray().T, rtol=1e-9, atol=0.0)  # really unsymmetric
    # cond(K_t) ≈ 1e3 (tests/fe/test_solver.py): 1e-12 of the residual → 1e-9 of du
    np.testing.assert_allclose(du, ref, rtol=0, atol=1e-9 * np.max(np.abs(ref)))


@pytest.mark.skipif(not ls.pardiso_available(), reason="pypardiso (optional) not installed")
def test_pardiso_refuses_a_singular_tangent(materials):
    """No supports and an open interface (zero tangent): K_t singular, LinAlgError (the Newton
    loop's "singular tangent"), not a perturbed-pivot answer."""
    model, u, r, resp = slipped_state(materials, "free")
    free = model.free
    linear = ls.Sparse(model, False, "pardiso")
    with pytest.raises(np.linalg.LinAlgError):
        linear(model.points, 0.0 * resp.tangent, r, u[free], 1.0)


def test_sparse_backend_is_checked():
    with pytest.raises(ValueError, match="backend must be one of"):
        ls.Sparse(None, False, "umfpack")


def test_without_pypardiso_the_sparse_strategies_use_superlu(monkeypatch, materials):
    """The optional package's absent path (pip install without the extra [pardiso]): an import that
    fails gives SuperLU, and the answer is the same."""
    import builtins

    real_import = builtins.__import__

    def no_pardiso(name, *args, **kwargs):
        if name.split(".")[0] == "pypardiso":
            raise ImportError("No module named 'pypardiso'")
        return real_import(name, *args, **kwargs)

    model, u, r, resp = slipped_state(materials, "coulomb")
    monkeypatch.setattr(builtins, "__import__", no_pardiso)
    assert not ls.pardiso_available()
    linear = ls.Sparse(model, False, "auto")
    assert linear.backend == "superlu"
    Kt = (model.stiffness + interface_tangent(model.points, resp.tangent)).tocsr()[model.free][:, model.free]
    ref = spla.spsolve(Kt.tocsc(), r)
    np.testing.assert_allclose(linear(model.points, resp.tangent, r, u[model.free], 1.0), ref, rtol=0,
                               atol=1e-9 * np.max(np.abs(ref)))
