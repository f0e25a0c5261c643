"""MKL PARDISO through ctypes (roughcontact.fe.pardiso) and the single-precision kept factor of
the "sparse-krylov" strategy (roughcontact.fe.linear_solvers, issue 31): solves against scipy's
direct solve, the single-precision factor's own accuracy (float32 round-off times the
condition), the errors, and GMRES reaching the double-precision residual with it — also on a
nearly singular system, where the residual's round-off floor is the target.

Skipped without the optional extra [pardiso] (the absent path: tests/fe/test_linear_solvers.py,
``test_without_pypardiso_the_sparse_strategies_use_superlu``)."""

from __future__ import annotations

import gc

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from roughcontact.fe import linear_solvers as ls

pytestmark = pytest.mark.skipif(not ls.pardiso_available(), reason="pypardiso (optional) not installed")


def _spd(n, seed, shift=10.0):
    """A sparse symmetric positive definite matrix (random pattern, dominant diagonal)."""
    R = sp.random(n, n, density=4.0 / n, random_state=seed)
    return (R + R.T + sp.diags(np.full(n, shift) + np.abs(R).sum(axis=1).A1 * 2.0)).tocsr()


@pytest.mark.parametrize("symmetric", [True, False])
def test_double_precision_solves_to_round_off(symmetric):
    from roughcontact.fe.pardiso import PardisoFactor

    A = _spd(600, 1)
    if not symmetric:
        A = (A + 0.4 * sp.random(600, 600, density=0.01, random_state=2)).tocsr()
    b = np.random.default_rng(3).normal(size=600)
    f = PardisoFactor(A, symmetric)
    x = f(b)
    ref = spla.spsolve(A.tocsc(), b)
    assert x.dtype == np.float64
    assert np.linalg.norm(b - A @ x) <= 1e-14 * np.linalg.norm(b)
    np.testing.assert_allclose(x, ref, rtol=0, atol=1e-13 * np.max(np.abs(ref)))
    assert f.factor_bytes > 0 and f.perturbed_pivots == 0


def test_single_precision_is_an_approximate_inverse():
    """float32: the residual of the single-precision solve is ~ε₃₂ · cond (cond ≈ 3 here), half
    the factor's memory of the double one; as the preconditioner of GMRES, the double residual."""
    from roughcontact.fe.pardiso import PardisoFactor

    A = _spd(800, 4)
    b = np.random.default_rng(5).normal(size=800)
    single, double = PardisoFactor(A, True, single=True), PardisoFactor(A, True)
    rel = np.linalg.norm(b - A @ single(b)) / np.linalg.norm(b)
    eps32 = float(np.finfo(np.float32).eps)
    assert eps32 / 100 < rel < 100 * eps32
    assert single.factor_bytes < 0.75 * double.factor_bytes
    x, its = ls.gmres_right(A.__matmul__, single, b, ls.KRYLOV_RTOL, 30)
    assert x is not None and its <= 4  # each iteration gains ~7 digits
    assert np.linalg.norm(b - A @ x) <= ls.KRYLOV_RTOL * np.linalg.norm(b)


def test_errors_are_one_line_linalg_errors():
    from roughcontact.fe.pardiso import PardisoFactor

    A = _spd(200, 6)
    indefinite = (A - sp.diags(np.full(200, 1e3))).tocsr()
    with pytest.raises(np.linalg.LinAlgError, match=r"PARDISO: error -4 \(zero pivot"):
        PardisoFactor(indefinite, True)  # Cholesky of an indefinite matrix
    with pytest.raises(ValueError, match="a vector of 200 values expected"):
        PardisoFactor(A, True)(np.ones(3))
    with pytest.raises(ValueError, match="square non-empty"):
        PardisoFactor(sp.csr_matrix((3, 4)), False)


def test_factor_memory_is_released():
    """Many large factors one after the other (each dropped): memory does not accumulate (phase −1
    on collection: the handle is released, not leaked)."""
    import resource

    from roughcontact.fe.pardiso import PardisoFactor

    m = 120  # a 2-D Laplacian on an m × m grid (nested dissection keeps its factor sparse)
    T = sp.diags([-np.ones(m - 1), np.full(m, 2.0), -np.ones(m - 1)], [-1, 0, 1])
    A = (sp.kron(T, sp.eye(m)) + sp.kron(sp.eye(m), T) + 1e-3 * sp.eye(m * m)).tocsr()
    b = np.ones(m * m)
    PardisoFactor(A, False)(b)
    gc.collect()
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    for _ in range(8):
        PardisoFactor(A, False)(b)
        gc.collect()
    grown_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    one_kb = PardisoFactor(A, False).factor_bytes / 1024
    assert grown_kb < 2 * one_kb + 20_000


def test_reused_factor_single_precision_path():
    """ReusedFactor(approximate=True): the fresh single-precision factor is a preconditioner
    (GMRES to KRYLOV_RTOL right after the factorisation, no direct solve); a useless approximate
    factor is replaced by an exact one (``exact_fallbacks``) and the answer is still exact."""
    from roughcontact.fe.pardiso import PardisoFactor

    A = _spd(500, 8)
    b = np.random.default_rng(9).normal(size=500)
    reuse = ls.ReusedFactor(approximate=True)
    x = reuse.solve(A.__matmul__, b, lambda single=False: PardisoFactor(A, True, single=single))
    s = reuse.stats
    assert (s.factorisations, s.direct_solves, s.krylov_solves, s.exact_fallbacks) == (1, 0, 1, 0)
    assert np.linalg.norm(b - A @ x) <= ls.KRYLOV_RTOL * np.linalg.norm(b) and reuse.floor == 0.0

    bad = ls.ReusedFactor(approximate=True)
    exact = spla.splu(A.tocsc()).solve
    x = bad.solve(A.__matmul__, b, lambda single=False: np.zeros_like if single else exact)  # breaks down
    assert (bad.stats.exact_fallbacks, bad.stats.factorisations, bad.stats.direct_solves) == (1, 2, 1)
    np.testing.assert_allclose(x, spla.spsolve(A.tocsc(), b), rtol=1e-12, atol=0)


def test_gmres_accepts_the_round_off_floor_of_a_nearly_singular_system():
    """A spring chain pinned by a spring 1e-12 of the others (cond ~1e13, like the first,
    softly seated tangent of a floating plate): 1e-14 relative residual is unattainable in
    double precision; with |A| the answer at ≤ ROUNDOFF_RESIDUAL ε ‖|A||x|‖ is accepted (and it
    is the direct solve's to cond · ε), without it GMRES gives up. A singular A (ROUNDOFF_CAP)
    is never accepted."""
    n = 400
    main = np.full(n, 2.0)
    main[0] = 1.0 + 1e-12
    main[-1] = 1.0
    A = sp.diags([-np.ones(n - 1), main, -np.ones(n - 1)], [-1, 0, 1]).tocsc()
    b = np.random.default_rng(11).normal(size=n)
    b -= b.mean()
    b[0] += 1e-6  # a little of the soft mode: x ~ 1e6, the floor ~1e-9 of ‖b‖ (the plate's: 1.6e-11)
    P = spla.splu(A).solve
    x, _ = ls.gmres_right(A.__matmul__, P, b, 1e-16, 40, lambda v: abs(A) @ v)
    assert x is not None
    floor = ls.ROUNDOFF_RESIDUAL * np.finfo(float).eps * np.linalg.norm(abs(A) @ np.abs(x))
    assert np.linalg.norm(b - A @ x) <= floor
    assert ls.gmres_right(A.__matmul__, P, b, 1e-16, 40)[0] is None
    singular = sp.diags([-np.ones(n - 1), np.r_[1.0, np.full(n - 2, 2.0), 1.0], -np.ones(n - 1)], [-1, 0, 1]).tocsc()
    c = np.r_[1.0, np.zeros(n - 1)]  # not in the range (its sum is not 0)
    perturbed = spla.splu((singular + sp.diags(np.full(n, 1e-13))).tocsc()).solve
    assert ls.gmres_right(singular.__matmul__, perturbed, c, 1e-12, 40, lambda v: abs(singular) @ v)[0] is None
