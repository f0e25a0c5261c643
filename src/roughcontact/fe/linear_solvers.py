"""A kept factorisation reused as the preconditioner of a Krylov solve (the ``"krylov"`` and
``"condensed-krylov"`` strategies of :mod:`.solver`, issue 31 "Large interfaces").

Newton's tangent A_k = K + Bᵀ diag(w D_k) B changes from one iteration to the next only through
the interface part, and slowly once the active set settles. Instead of factoring every A_k, a
factorisation P = A_j of an earlier tangent is kept and A_k x = b is solved by GMRES with P as
the *right* preconditioner (Saad, *Iterative Methods for Sparse Linear Systems*, 2nd ed. 2003,
alg. 9.5): x = P⁻¹ y with y minimising the **true** residual ‖b − A_k P⁻¹ y‖₂ over the Krylov
space of A_k P⁻¹ — so the stopping test below is on the residual of the system Newton needs,
not on a preconditioned one.

The friction tangent is unsymmetric (non-associated slip, :func:`.interface_points.interface_tangent`):
GMRES needs no symmetry, and the kept factor is whatever the direct path made of the tangent it
factored (Cholesky or diagonal-pivot LU when that tangent was symmetric, partial-pivot LU when
not); a symmetric P of an unsymmetric A_k (or the reverse) is just a preconditioner of lower
quality, paid for in iterations.

Accuracy (the Newton answer must not change): the solve is accepted when

    ‖b − A_k x‖₂ ≤ KRYLOV_RTOL · ‖b‖₂,   KRYLOV_RTOL = 1e-12,

checked on the explicitly recomputed residual (not the Arnoldi estimate). An inexact Newton step
with forcing term η leaves a residual η‖r‖ + O(‖du‖²) (Dembo, Eisenstat & Steihaug, SIAM J.
Numer. Anal. 19, 1982); with η = 1e-12, far below Newton's force tolerance 1e-9 relative, the
iterations and the converged state are those of the direct solve to within the Newton tolerances
(tests/fe/test_linear_solvers.py), and du itself is within cond(A_k)·1e-12 of the direct
solve's (a backward-stable direct solve is within cond(A_k)·ε). Otherwise — GMRES above
MAX_KRYLOV iterations, a breakdown or a non-finite vector — the current tangent is factored at
once and solved directly (the answer of the direct strategy); a solve that took more than REFACTOR_AFTER iterations marks the kept factor
stale, so the next solve refactors. The cost is then a factorisation per change of the active
set or of the law's stiffness large enough to matter, plus one multiply by A_k and two
triangular solves per GMRES iteration.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from . import ordering
from .interface_points import InterfacePoints, interface_tangent

__all__ = ["KRYLOV_RTOL", "REFACTOR_AFTER", "MAX_KRYLOV", "KrylovStats", "ReusedFactor", "gmres_right", "Sparse",
           "Condensed"]

#: accepted relative true residual ‖b − A x‖/‖b‖ of a Krylov solve (module docstring)
KRYLOV_RTOL = 1e-12
#: a solve that needed more GMRES iterations than this refactors at the next solve
REFACTOR_AFTER = 12
#: GMRES iterations before giving up: the current tangent is factored and solved directly
MAX_KRYLOV = 40


def gmres_right(matvec: Callable, precondition: Callable, b: np.ndarray, rtol: float,
                max_iterations: int) -> tuple[np.ndarray | None, int]:
    """Right-preconditioned GMRES from x₀ = 0 without restarts (Saad 2003, alg. 9.5; modified
    Gram–Schmidt, applied twice; Givens rotations): (x, iterations) with ‖b − A x‖₂ ≤ rtol ‖b‖₂
    on the recomputed residual, or (None, iterations) when that is not reached within
    ``max_iterations`` or the vectors turn non-finite. ``matvec(v)`` = A v, ``precondition(v)``
    = P⁻¹ v."""
    beta = float(np.linalg.norm(b))
    if beta == 0.0:
        return np.zeros_like(b), 0
    target = rtol * beta
    V = np.empty((max_iterations + 1, b.size))
    H = np.zeros((max_iterations + 1, max_iterations))
    cs, sn = np.zeros(max_iterations), np.zeros(max_iterations)
    g = np.zeros(max_iterations + 1)
    V[0], g[0] = b / beta, beta
    Z = []
    for j in range(max_iterations):
        z = precondition(V[j])
        Z.append(z)
        w = matvec(z)
        for _ in range(2):  # reorthogonalised modified Gram–Schmidt
            for i in range(j + 1):
                h = float(V[i] @ w)
                H[i, j] += h
                w -= h * V[i]
        w_norm = float(np.linalg.norm(w))
        H[j + 1, j] = w_norm
        if not (math.isfinite(w_norm) and np.all(np.isfinite(H[:j + 1, j]))):
            return None, j + 1
        for i in range(j):  # the earlier rotations on the new column
            H[i, j], H[i + 1, j] = cs[i] * H[i, j] + sn[i] * H[i + 1, j], -sn[i] * H[i, j] + cs[i] * H[i + 1, j]
        rho = math.hypot(H[j, j], H[j + 1, j])
        if rho == 0.0:
            return None, j + 1
        cs[j], sn[j] = H[j, j] / rho, H[j + 1, j] / rho
        H[j, j], H[j + 1, j] = rho, 0.0
        g[j + 1], g[j] = -sn[j] * g[j], cs[j] * g[j]
        # w_norm = 0: the Krylov space holds the solution (a "lucky" breakdown)
        if abs(g[j + 1]) <= 0.5 * target or j + 1 == max_iterations or w_norm == 0.0:
            y = la.solve_triangular(H[:j + 1, :j + 1], g[:j + 1])
            x = np.asarray(Z).T @ y
            if np.all(np.isfinite(x)) and np.linalg.norm(b - matvec(x)) <= target:
                return x, j + 1
            return None, j + 1  # the estimate met, not the recomputed residual (round-off): give up
        V[j + 1] = w / w_norm
    return None, max_iterations


@dataclass
class KrylovStats:
    """What a :class:`ReusedFactor` did: factorisations, direct solves (right after a
    factorisation), Krylov solves accepted and their GMRES iterations, Krylov solves given up."""

    factorisations: int = 0
    direct_solves: int = 0
    krylov_solves: int = 0
    krylov_iterations: int = 0
    krylov_failures: int = 0


class ReusedFactor:
    """x = A⁻¹ b for a sequence of slowly changing A (module docstring): GMRES preconditioned by
    the kept factor while it converges within MAX_KRYLOV iterations, else a new factorisation."""

    def __init__(self, rtol: float = KRYLOV_RTOL, refactor_after: int = REFACTOR_AFTER,
                 max_iterations: int = MAX_KRYLOV):
        self.rtol, self.refactor_after, self.max_iterations = rtol, refactor_after, max_iterations
        self.factor: Callable | None = None
        self.stale = False
        self.stats = KrylovStats()

    def solve(self, matvec: Callable, b: np.ndarray, factorise: Callable[[], Callable]) -> np.ndarray:
        """``matvec(v)`` = A v of the current A; ``factorise()`` factors the current A and returns
        its solve (v ↦ A⁻¹ v); it may raise (a singular A) as the direct strategies do."""
        if self.factor is not None and not self.stale:
            x, its = gmres_right(matvec, self.factor, b, self.rtol, self.max_iterations)
            if x is not None:
                self.stats.krylov_solves += 1
                self.stats.krylov_iterations += its
                self.stale = its > self.refactor_after
                return x
            self.stats.krylov_failures += 1
        self.factor = None  # free the old factor before the new one is made (peak memory)
        self.factor = factorise()
        self.stale = False
        self.stats.factorisations += 1
        self.stats.direct_solves += 1
        return self.factor(b)


# ---------------------------------------------------------------------------------------------
# the strategies of roughcontact.fe.solver (its module docstring, "Linear solves"); ``model`` a
# solver.ContactModel
# ---------------------------------------------------------------------------------------------
def _symmetric(D) -> bool:
    return bool(np.allclose(D, np.swapaxes(D, -1, -2), rtol=1e-12, atol=0.0))


def _dense_factor(A, symmetric: bool):
    """The solve b ↦ A⁻¹ b of a dense A that may be overwritten: Cholesky when symmetric
    (LinAlgError when not positive definite), else LU (LinAlgError on a zero pivot); no condition
    estimate (half the time of scipy.linalg.solve on 2000 unknowns: the Newton loop checks its steps)."""
    if symmetric:
        c = la.cho_factor(A, overwrite_a=True, check_finite=False)
        return lambda b: la.cho_solve(c, b, check_finite=False)
    with warnings.catch_warnings():  # a zero pivot is raised just below, not warned about
        warnings.simplefilter("ignore", la.LinAlgWarning)
        lu, piv = la.lu_factor(A, overwrite_a=True, check_finite=False)
    if not np.all(np.diagonal(lu)):
        raise np.linalg.LinAlgError("singular matrix (a zero pivot)")
    return lambda b: la.lu_solve((lu, piv), b, check_finite=False)


def _dense_solve(A, b, symmetric: bool):
    """A x = b for a dense A that may be overwritten (:func:`_dense_factor`)."""
    return _dense_factor(A, symmetric)(b)


def _ordered(model, K, dofs) -> np.ndarray:
    """A fill-reducing order of ``dofs`` (indices of the free dofs): nested dissection by the
    node coordinates when the model has them, else reverse Cuthill–McKee (:mod:`.ordering`)."""
    return ordering.dof_order(K, dofs, model.free // 3, model.coordinates)


class Sparse:
    """The full tangent, refactored every iteration (SuperLU in a nested-dissection order;
    diagonal pivoting when the tangent is symmetric); with ``krylov`` its factor is kept and
    reused as the preconditioner of GMRES (:mod:`.linear_solvers`)."""

    def __init__(self, model, krylov: bool = False):
        self.reuse = ReusedFactor() if krylov else None
        free = model.free
        K = model.stiffness[free][:, free].tocsr()
        self.order = _ordered(model, K, np.arange(free.size))
        self.K = K[self.order][:, self.order].tocsc()
        self.B = model.points.B[:, free[self.order]].tocsr()

    def __call__(self, points, D, r, u, level):
        Kt = (self.K + interface_tangent(_restricted(points, self.B), D)).tocsc()
        symmetric = _symmetric(D)

        def factorise():
            return spla.splu(Kt, permc_spec="NATURAL", options=dict(SymmetricMode=symmetric),
                             **({"diag_pivot_thresh": 0.0} if symmetric else {})).solve
        du = np.empty(r.size)
        b = r[self.order]
        du[self.order] = factorise()(b) if self.reuse is None else self.reuse.solve(Kt.__matmul__, b, factorise)
        return du


class Condensed:
    """The bulk condensed onto the interface dofs I (:mod:`.solver`, "Linear solves").

    Set-up, once: the free dofs are ordered bulk R first (nested dissection), I last, and
    M = K + α P_I (α the mean diagonal of K_II, P_I the identity on I) is factored by SuperLU
    in that order without pivoting (M is symmetric positive definite). With I last, the
    trailing blocks of the factors give the Schur complement directly:
    L_II U_II = S + αI, S = K_II − K_IR K_RR⁻¹ K_RI — one sparse factorisation instead of a
    solve for every interface dof (4× less time on 16 k dofs, and the factor of the
    interior is the same work).

    Per iteration, with K_t,II = Bᵀ diag(w D) B on I: x = M⁻¹ r gives the condensed right-hand
    side b_I = (S + αI) x_I = r_I − K_IR K_RR⁻¹ r_R; the dense (S + K_t,II) du_I = b_I (Cholesky
    when the interface tangent is symmetric, LU otherwise); then
    du = x + M⁻¹ [0; (S + αI)(du_I − x_I)] (its R part is K_RR⁻¹(r_R − K_RI du_I)). Two sparse
    solves and one dense factorisation of n_I unknowns; with ``krylov`` the dense factor is kept
    and reused as the preconditioner of GMRES on (S + K_t,II) (:mod:`.linear_solvers`)."""

    def __init__(self, model, krylov: bool = False):
        self.reuse = ReusedFactor() if krylov else None
        free = model.free
        K = model.stiffness[free][:, free].tocsr()
        B = model.points.B[:, free].tocsc()
        on_interface = np.diff(B.indptr) > 0
        I, R = np.flatnonzero(on_interface), np.flatnonzero(~on_interface)
        self.order = np.concatenate([_ordered(model, K, R), I])
        self.n_R, self.n = R.size, free.size
        self.B_I = B[:, I].tocsr()
        alpha = float(np.mean(K.diagonal()[I])) if I.size else 1.0
        M = K[self.order][:, self.order] + sp.diags(np.r_[np.zeros(R.size), np.full(I.size, alpha)])
        self.lu = spla.splu(M.tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0.0,
                            options=dict(SymmetricMode=True))
        identity = np.arange(self.n)
        if not (np.array_equal(self.lu.perm_c, identity) and np.array_equal(self.lu.perm_r, identity)):
            raise RuntimeError("SuperLU reordered the condensed system; use linear_solver='sparse'")
        L_II = self.lu.L[R.size:, R.size:].toarray()  # one factor at a time: bounded memory
        S_alpha = L_II @ self.lu.U[R.size:, R.size:].toarray()
        del L_II
        self.S_alpha = 0.5 * (S_alpha + S_alpha.T)  # symmetric up to round-off: make it exactly so
        self.S = self.S_alpha - alpha * np.eye(I.size)

    def __call__(self, points, D, r, u, level):
        x = self.lu.solve(r[self.order])
        x_I = x[self.n_R:]
        A = self.S + interface_tangent(_restricted(points, self.B_I), D).toarray()
        b_I, symmetric = self.S_alpha @ x_I, _symmetric(D)
        du_I = (_dense_solve(A, b_I, symmetric) if self.reuse is None else
                self.reuse.solve(A.__matmul__, b_I, lambda: _dense_factor(A.copy(), symmetric)))
        correction = np.zeros(self.n)
        correction[self.n_R:] = self.S_alpha @ (du_I - x_I)
        du = np.empty(self.n)
        du[self.order] = x + self.lu.solve(correction)
        return du


def _restricted(points: InterfacePoints, B) -> InterfacePoints:
    """The same points with the jump operator restricted to some dofs."""
    return InterfacePoints(B, points.weights, points.x, points.frames, points.element, points.block,
                           points.nodes, points.rule)
