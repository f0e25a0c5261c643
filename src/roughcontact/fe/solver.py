"""Incremental loading with full Newton iterations for a linear-elastic bulk in contact through
zero-thickness interface elements (section 9 of Buczkowski & Kleiber 2009: penalty contact whose
penalty is the physical interface stiffness, active set per point, 16 increments).

Equations (dof vector u [mm], free dofs f, supports u = 0 on ``fixed``):

    r(u) = F₀ + λ·F − K u − Bᵀ(w ⊙ s(δ(u)))  = 0  on f,     δ = B u,

with F the load pattern [N per unit of λ], F₀ a constant (dead) load present at every level
(e.g. a seating pressure; zero by default), K the bulk stiffness [N/mm], B the jump operator and
s the interface tractions from :class:`~.contact.InterfaceMaterial` (the library's law). Each
load level λ_k is reached from the last converged state by Newton's method with the consistent
tangent K + Bᵀ diag(w D) B; the law's state is committed only at convergence.

Convergence (all three, checked after every iteration):
* force:        ‖r_f‖₂ ≤ force_rtol·max(‖λF_f‖₂, ‖interface forces‖₂) + force_atol + 1000 ε ‖|K| |u|‖₂
                [N] (the last term is the round-off floor of K u: a soft interface lets a body
                move far as a rigid body, K u ≈ 0 while |K| |u| is large);
* increment:    ‖Δu‖_∞ ≤ displacement_rtol·‖u − u_n‖_∞ + displacement_atol [mm] (last correction);
* active set:   no interface point changed status (stick / slip / open) in the last iteration.
Non-convergence (iteration limit, a non-finite residual, a singular tangent or a closure beyond
the heavy end of a tabulated law) halves the step back to the last converged state (the step
doubles again after every converged sub-step); after ``max_cutbacks`` halvings
:class:`ConvergenceError` names the increment, the load level and the residual. Never a silently
wrong answer: every converged increment records its residual history and the equilibrium error
(applied load vs integrated interface pressure).

Linear solves: ``"condensed"`` (default) factors the bulk once, condenses it onto the interface
dofs (dense Schur complement S = K_II − K_IR K_RR⁻¹ K_RI) and per iteration solves the dense
(S + K_int) system (Cholesky when the interface tangent is symmetric) plus one or two sparse
back-substitutions; ``"sparse"`` refactors the whole sparse tangent (SuperLU, ordering of
Aᵀ + A) every iteration. The Newton loop runs with ``blas_threads`` BLAS threads (1: on
these dense systems of a few hundred to a few thousand unknowns a second thread costs more
than it gains, and on a loaded machine far more). ``make bench-fe`` measures both strategies
(results/benchmarks/fe_linear_solvers.md; environment-notes.md records the choice).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..interface import friction
from . import assembly
from .contact import InterfaceMaterial
from .interface_points import InterfacePoints, interface_forces, interface_points, interface_tangent

__all__ = ["ContactModel", "NewtonOptions", "Increment", "Solution", "ConvergenceError", "solve"]

#: the round-off floor of a residual r = F − K u − f: this many ulps of |K| |u|
_ROUNDOFF = 1e3 * np.finfo(float).eps
#: a Newton correction this many times the displacements so far (or 1 m) is a singular tangent
_DIVERGED = 1e6
_DIVERGED_FLOOR = 1e3  # mm


class ConvergenceError(RuntimeError):
    """Newton did not converge at an increment even after the allowed cut-backs."""

    def __init__(self, increment: int, level: float, residual: float, reason: str):
        self.increment, self.level, self.residual, self.reason = increment, level, residual, reason
        super().__init__(f"no convergence at increment {increment} (load level {level:.6g}): "
                         f"{reason}; residual {residual:.3e} N after the allowed cut-backs")


@dataclass(frozen=True)
class NewtonOptions:
    """Convergence criteria and limits (module docstring)."""

    max_iterations: int = 30
    force_rtol: float = 1e-9
    force_atol: float = 1e-9
    displacement_rtol: float = 1e-8
    displacement_atol: float = 1e-12
    max_cutbacks: int = 6
    linear_solver: str = "condensed"
    blas_threads: int | None = 1

    def __post_init__(self):
        if self.linear_solver not in ("condensed", "sparse"):
            raise ValueError(f"linear_solver must be 'condensed' or 'sparse', got {self.linear_solver!r}")
        if self.blas_threads is not None and not (isinstance(self.blas_threads, int) and self.blas_threads >= 1):
            raise ValueError(f"blas_threads must be a positive integer or None, got {self.blas_threads!r}")
        if not (self.max_iterations >= 1 and self.max_cutbacks >= 0):
            raise ValueError("max_iterations must be >= 1 and max_cutbacks >= 0")
        for name in ("force_rtol", "force_atol", "displacement_rtol", "displacement_atol"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} must be positive")


@dataclass(frozen=True, eq=False)
class ContactModel:
    """The discrete problem: bulk stiffness K (3N × 3N) [N/mm], interface points, interface
    material, supported dofs (u = 0), the load pattern F (3N,) [N per unit load level] and a
    dead load F₀ (3N,) [N] present at every level (None: zero)."""

    stiffness: sp.csr_matrix
    points: InterfacePoints
    material: InterfaceMaterial
    fixed: np.ndarray
    load: np.ndarray
    dead_load: np.ndarray | None = None
    _cache: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        n = self.stiffness.shape[0]
        fixed = np.asarray(self.fixed)
        if fixed.size and not np.issubdtype(fixed.dtype, np.integer):
            raise TypeError(f"fixed must be integer dof indices, got an array of {fixed.dtype}")
        fixed = np.unique(fixed.astype(np.int64))
        if fixed.size and (fixed[0] < 0 or fixed[-1] >= n):
            raise ValueError("fixed dofs out of range")
        load = np.asarray(self.load, dtype=float)
        dead = np.zeros(n) if self.dead_load is None else np.asarray(self.dead_load, dtype=float)
        for name, vec in (("load pattern", load), ("dead load", dead)):
            if vec.shape != (n,) or not np.all(np.isfinite(vec)):
                raise ValueError(f"the {name} must be a finite vector of length {n}")
        object.__setattr__(self, "dead_load", dead)
        if self.points.B.shape[1] != n:
            raise ValueError("the interface points belong to another mesh")
        object.__setattr__(self, "fixed", fixed)
        object.__setattr__(self, "load", load)

    @classmethod
    def assemble(cls, mesh, elasticity, material: InterfaceMaterial, fixed, load, *, dead_load=None,
                 rule: str = "lobatto", lay=(1.0, 0.0, 0.0)) -> "ContactModel":
        """From a :class:`~.mesh.Mesh`: ``elasticity`` a 6×6 Voigt matrix for every block or a
        dict block name → matrix [N/mm²] (:func:`.assembly.isotropic_elasticity`), interface
        points of ``rule`` with t1 along ``lay``."""
        blocks = [(b.element, b.cells) for b in mesh.blocks]
        D = [elasticity[b.name] for b in mesh.blocks] if isinstance(elasticity, dict) else elasticity
        K = assembly.stiffness(mesh.points, blocks, D)
        return cls(K, interface_points(mesh, rule, lay), material, fixed, load, dead_load)

    def with_material(self, material: InterfaceMaterial) -> "ContactModel":
        """The same bodies, supports and loads with another interface material, sharing this
        model's factorised bulk (the linear solvers depend on K, B, the supports and loads only)."""
        return ContactModel(self.stiffness, self.points, material, self.fixed, self.load, self.dead_load,
                            self._cache)

    @property
    def free(self) -> np.ndarray:
        if "free" not in self._cache:
            mask = np.ones(self.stiffness.shape[0], dtype=bool)
            mask[self.fixed] = False
            self._cache["free"] = np.flatnonzero(mask)
        return self._cache["free"]

    @property
    def abs_stiffness(self) -> sp.csr_matrix:
        """|K| entrywise (the scale of the round-off of K u)."""
        if "abs" not in self._cache:
            self._cache["abs"] = abs(self.stiffness).tocsr()
        return self._cache["abs"]

    @property
    def n_dofs(self) -> int:
        """Unknowns (free dofs)."""
        return int(self.free.size)


@dataclass(frozen=True, eq=False)
class Increment:
    """A converged load level: u (3N,) [mm], interface states (n, 9), tractions (n, 3)
    [N/mm²] (t_x, t_y, σ_N), status (n,), Newton iterations spent on it (all sub-steps),
    the residual history of its last sub-step [N], cut-backs used, wall time [s]."""

    level: float
    u: np.ndarray
    state: np.ndarray
    tractions: np.ndarray
    status: np.ndarray
    iterations: int
    residuals: tuple[float, ...]
    cutbacks: int
    seconds: float


@dataclass(frozen=True, eq=False)
class Solution:
    """The converged increments (the first is the first requested level) and the model."""

    model: ContactModel
    increments: tuple[Increment, ...]

    @property
    def final(self) -> Increment:
        return self.increments[-1]

    def interface_pressure_resultant(self, k: int = -1) -> float:
        """Σ_q w_q p_N,q [N]: the integrated interface pressure of increment k."""
        inc = self.increments[k]
        return float(np.sum(-inc.tractions[:, 2] * self.model.points.weights))

    def applied_normal_load(self, k: int = -1, normal=(0.0, 0.0, 1.0)) -> float:
        """−(F₀ + λF)·n summed over all nodes [N]: the applied load pressing along −n."""
        inc = self.increments[k]
        F = (self.model.dead_load + inc.level * self.model.load).reshape(-1, 3)
        return float(-F.sum(axis=0) @ np.asarray(normal, dtype=float))

    def point_fields(self, k: int = -1, reference: int | None = None) -> dict[str, np.ndarray]:
        """Per interface point of increment k, for files (VTU, netCDF): ``traction`` (n, 3)
        [N/mm²] (t_x, t_y, σ_N), ``p_N`` [N/mm²], ``closure_mm`` (from the law's reference
        state, or from increment ``reference``), ``plastic_slip_mm`` (n, 2), ``status``
        (0 stick, 1 slip, 2 open)."""
        inc, material = self.increments[k], self.model.material
        closure = material.closure_mm(inc.state)
        if reference is not None:
            closure = closure - material.closure_mm(self.increments[reference].state)
        return {
            "traction": inc.tractions.copy(),
            "p_N": -inc.tractions[:, 2],
            "closure_mm": closure,
            "plastic_slip_mm": inc.state[:, [friction.UP_X, friction.UP_Y]] / material.length_per_mm,
            "status": inc.status.astype(np.int32),
        }

    def equilibrium_error(self, k: int = -1, normal=(0.0, 0.0, 1.0)) -> float:
        """|integrated interface pressure − applied load| / applied load of increment k."""
        applied = self.applied_normal_load(k, normal)
        return abs(self.interface_pressure_resultant(k) - applied) / abs(applied)


# ---------------------------------------------------------------------------------------------
# linear solvers
# ---------------------------------------------------------------------------------------------
def _splu(A, symmetric: bool):
    """SuperLU with a fill-reducing ordering of Aᵀ + A (3× less fill than COLAMD on the
    beam's stiffness matrices, environment-notes.md); diagonal pivoting when A is symmetric."""
    return spla.splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A", options=dict(SymmetricMode=symmetric))


def _symmetric(D) -> bool:
    return bool(np.allclose(D, np.swapaxes(D, -1, -2), rtol=1e-12, atol=0.0))


class _Sparse:
    """The full tangent, refactored every iteration."""

    def __init__(self, model: ContactModel):
        free = model.free
        self.K = model.stiffness[free][:, free].tocsc()
        self.B = model.points.B[:, free].tocsr()

    def __call__(self, points, D, r, u, level):
        Kt = self.K + interface_tangent(_restricted(points, self.B), D)
        return _splu(Kt, _symmetric(D)).solve(r)


class _Condensed:
    """The bulk factored once and condensed onto the interface dofs (module docstring). The
    dense system is solved by Cholesky when the interface tangent is symmetric (no friction
    or associated slip), by LU otherwise. X = K_RR⁻¹K_RI is kept when it fits in
    ``keep_bytes``; then no iteration needs a sparse solve: the bulk rows R carry no interface
    term, so their residual r_R = F₀_R + λF_R − K_RR u_R − K_RI u_I is linear and
    K_RR⁻¹ r_R = a₀ + λa₁ − u_R − X u_I with a₀ = K_RR⁻¹F₀_R, a₁ = K_RR⁻¹F_R computed once."""

    keep_bytes = 256 * 2**20

    def __init__(self, model: ContactModel):
        free = model.free
        K = model.stiffness[free][:, free].tocsr()
        B = model.points.B[:, free].tocsc()
        on_interface = np.diff(B.indptr) > 0
        self.I = np.flatnonzero(on_interface)
        self.R = np.flatnonzero(~on_interface)
        self.B_I = B[:, self.I].tocsr()
        self.K_RR = _splu(K[self.R][:, self.R], True)
        K_RI = K[self.R][:, self.I].tocsc()
        self.K_IR = K[self.I][:, self.R].tocsr()
        keep = 8 * self.R.size * self.I.size <= self.keep_bytes
        X = np.empty((self.R.size, self.I.size)) if keep else None
        S = K[self.I][:, self.I].toarray()
        for j0 in range(0, self.I.size, 256):  # K_RR⁻¹ K_RI in column blocks (bounded memory)
            block = self.K_RR.solve(K_RI[:, j0:j0 + 256].toarray())
            S[:, j0:j0 + 256] -= self.K_IR @ block
            if keep:
                X[:, j0:j0 + 256] = block
        self.S = 0.5 * (S + S.T)  # symmetric up to round-off: make it exactly so
        self.X, self.K_RI = X, K_RI
        self.a0 = self.K_RR.solve(model.dead_load[free][self.R])
        self.a1 = self.K_RR.solve(model.load[free][self.R])
        self.n = free.size

    def __call__(self, points, D, r, u, level):
        if self.X is not None:
            y = self.a0 + level * self.a1 - u[self.R] - self.X @ u[self.I]  # = K_RR⁻¹ r_R (class docstring)
        else:
            y = self.K_RR.solve(r[self.R])
        A = self.S + interface_tangent(_restricted(points, self.B_I), D).toarray()
        b = r[self.I] - self.K_IR @ y
        du_I = la.solve(A, b, assume_a="pos" if _symmetric(D) else "gen", check_finite=True)
        du = np.empty(self.n)
        du[self.I] = du_I
        du[self.R] = y - (self.X @ du_I if self.X is not None else self.K_RR.solve(self.K_RI @ du_I))
        return du


def _restricted(points: InterfacePoints, B) -> InterfacePoints:
    """The same points with the jump operator restricted to some dofs."""
    return InterfacePoints(B, points.weights, points.x, points.frames, points.element, points.block,
                           points.nodes, points.rule)


def _linear_solver(model: ContactModel, kind: str):
    key = ("linear", kind)
    if key not in model._cache:
        model._cache[key] = (_Condensed if kind == "condensed" else _Sparse)(model)
    return model._cache[key]


# ---------------------------------------------------------------------------------------------
# Newton
# ---------------------------------------------------------------------------------------------
def _newton(model, solver, opts, level, u_n, state_n, guess):
    """Newton iterations at one load level from the committed (u_n, state_n), starting at
    ``guess``. Returns (u, response, residuals) or raises _Failed."""
    free, points, material = model.free, model.points, model.material
    jumps_n = points.jumps(u_n)
    u = guess.copy()
    f_ext = model.dead_load + level * model.load
    residuals, last_du, last_status = [], None, None
    for it in range(opts.max_iterations + 1):
        try:
            resp = material.respond(state_n, points.jumps(u) - jumps_n)
        except ValueError as exc:  # beyond the heavy end of a tabulated law
            raise _Failed(residuals[-1] if residuals else math.inf, str(exc)) from None
        f_int_iface = interface_forces(points, resp.tractions)
        r = (f_ext - model.stiffness @ u - f_int_iface)[free]
        norm = float(np.linalg.norm(r))
        residuals.append(norm)
        if not math.isfinite(norm):
            raise _Failed(norm, "non-finite residual")
        # plus the round-off floor of K u: ε·(|K| |u|) can exceed the forces themselves when a soft
        # interface lets the body move far as a rigid body (K u ≈ 0 but |K| |u| large)
        floor = _ROUNDOFF * np.linalg.norm((model.abs_stiffness @ np.abs(u))[free])
        tol_f = opts.force_rtol * max(np.linalg.norm(f_ext[free]), np.linalg.norm(f_int_iface[free])) + opts.force_atol + floor
        settled = it == 0 or (
            np.max(np.abs(last_du)) <= opts.displacement_rtol * np.max(np.abs(u - u_n)) + opts.displacement_atol
            and np.array_equal(resp.status, last_status))
        if norm <= tol_f and settled:
            return u, resp, residuals
        if it == opts.max_iterations:
            raise _Failed(norm, f"{opts.max_iterations} iterations without convergence")
        try:
            du = solver(points, resp.tangent, r, u[free], level)
        except (np.linalg.LinAlgError, RuntimeError) as exc:  # dense LinAlgError, SuperLU "singular"
            raise _Failed(norm, f"singular tangent ({exc})") from None
        if not np.all(np.isfinite(du)) or np.max(np.abs(du)) > _DIVERGED * max(np.max(np.abs(u)), _DIVERGED_FLOOR):
            raise _Failed(norm, "singular tangent (the Newton step diverged)")
        u[free] += du
        last_du, last_status = du, resp.status


class _Failed(Exception):
    def __init__(self, residual, reason):
        self.residual, self.reason = residual, reason


def solve(model: ContactModel, levels: Sequence[float], options: NewtonOptions | None = None,
          progress: Callable[[int, int, Increment], None] | None = None) -> Solution:
    """Load the model through ``levels`` (load levels λ, in the unit of the load pattern, e.g.
    N), each reached from the previous converged state (the first from u = 0 and the
    material's initial state). ``progress(k, n, increment)`` is called after every level."""
    opts = options or NewtonOptions()
    if opts.blas_threads is None:
        return _solve(model, levels, opts, progress)
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=opts.blas_threads, user_api="blas"):
        return _solve(model, levels, opts, progress)


def _solve(model, levels, opts, progress) -> Solution:
    levels = [float(x) for x in levels]
    if not levels or not all(math.isfinite(x) for x in levels):
        raise ValueError("levels must be a non-empty sequence of finite load levels")
    solver = _linear_solver(model, opts.linear_solver)
    u = np.zeros(model.stiffness.shape[0])
    state = model.material.initial_state(model.points.n_points)
    previous = 0.0
    rate = None
    out = []
    for k, target in enumerate(levels):
        t0 = time.perf_counter()
        level, step, cutbacks, iterations = previous, target - previous, 0, 0
        while True:
            # the last sub-step lands exactly on the target (halved steps sum to it up to rounding)
            trial = target if abs(target - level) <= abs(step) * (1.0 + 1e-9) else level + step
            # predictor: the last converged step's displacement rate (secant), else u_n
            guess = u if rate is None else u + rate * (trial - level)
            try:
                u_new, resp, residuals = _newton(model, solver, opts, trial, u, state, guess)
            except _Failed as fail:
                cutbacks += 1
                if cutbacks > opts.max_cutbacks:
                    raise ConvergenceError(k + 1, trial, fail.residual, fail.reason) from None
                step *= 0.5
                continue
            rate = (u_new - u) / (trial - level) if trial != level else None
            u, state, level = u_new, resp.state, trial
            iterations += len(residuals) - 1
            step *= 2.0  # a cut-back step grows back after every converged sub-step
            if level == target:
                break
        inc = Increment(level, u.copy(), state.copy(), resp.tractions.copy(), resp.status.copy(),
                        iterations, tuple(residuals), cutbacks, time.perf_counter() - t0)
        out.append(inc)
        previous = target
        if progress is not None:
            progress(k + 1, len(levels), inc)
    return Solution(model, tuple(out))
