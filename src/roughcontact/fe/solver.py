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
Non-convergence (iteration limit, a non-finite residual, a singular tangent, or a trial closure
beyond even the extrapolated tail of a tabulated law) halves the step back to the last converged
state (the step doubles again after every converged sub-step); after ``max_cutbacks`` halvings
:class:`ConvergenceError` names the increment, the load level and the residual. Never a silently
wrong answer: every converged increment records its residual history and the equilibrium error
(applied load vs integrated interface pressure).

The law's range. Trial states (the iterations) see the tabulated law continued past its heavy
end by its tangent (``InterfaceMaterial.respond(..., extrapolate=True)``,
:meth:`~roughcontact.interface.InterfaceLaw.extrapolated`): from a soft seated state the first
Newton step of a stiffening law overshoots far past the table, and refusing that iterate stopped
a block on a base loaded from zero at its first increment (issue 23). The range is judged on
the converged state: a converged state past the heavy end raises :class:`LawRangeError` (a
ConvergenceError) naming the increment, the level, the pressure reached and p_max.

Line search (``line_search``, on by default). The full Newton step is taken when it does not
increase ‖r‖; otherwise the step is shortened by the minimiser of the quadratic through
‖r‖²(0), its slope −2‖r‖²(0) along the Newton direction and ‖r‖²(α) (within [α/10, α/2]) until
‖r(α)‖ ≤ (1 − 10⁻⁴ α) ‖r(0)‖, at most 8 times (then the best step is taken). A step into the
region past even the tail counts as an infinite residual. It changes the path, not the
converged answer (tests: the beam's and punch's results unchanged to 1e-13).

Linear solves (``linear_solver``): ``"condensed"`` condenses the bulk onto the interface dofs I:
one SuperLU factorisation of K + αP_I with the bulk dofs first (nested dissection by the node
coordinates, :mod:`.ordering`) and I last gives the dense Schur complement
S = K_II − K_IR K_RR⁻¹ K_RI from its trailing factor blocks; each iteration then factors the dense
(S + K_int) (Cholesky when the interface tangent is symmetric, LU otherwise) and does two sparse
solves (:class:`.linear_solvers.Condensed`). ``"sparse"`` refactors the whole sparse tangent
every iteration (SuperLU in the same nested-dissection order). ``"condensed-krylov"`` and
``"sparse-krylov"`` keep the factor (dense S + K_int, or sparse K_t) of an earlier iteration and
reuse it as the right preconditioner of GMRES on the current tangent, refactoring only when GMRES
has cost about as much as a factorisation (the budget weighs the timed factorisation against a
timed GMRES iteration: tens of iterations on small models, hundreds on large ones) or fails
(:mod:`.linear_solvers`: the unsymmetric friction tangent is solved by GMRES as it is, and
factored as it is — LU — when it is refactored; the accepted residual ‖r − K_t du‖ ≤
max(1e-12, ρ_f) ‖r‖ with ρ_f the direct solve's own residual after the last factorisation,
below Newton's force tolerance, so the iterations and the answer are the direct solve's). The
sparse factorisation is Intel MKL PARDISO when the optional extra [pardiso] is installed
(:mod:`.pardiso`; Cholesky of a symmetric tangent, LU of an unsymmetric one; METIS ordering; a
factor of the 209 k-dof plate on a base in 53 CPU s and 3.9 GB against more than 240 CPU s and
8.5 GB with SuperLU; the kept factor of "sparse-krylov" in single precision, 14 s and 1.3 GB,
GMRES restoring the double-precision residual), else SuperLU. ``"auto"`` (default) is "condensed-krylov" up to AUTO_CONDENSED_MAX = 3000
interface dofs and "sparse-krylov" beyond: condensing costs a dense S of 8 n_I² bytes and n_I³/3 per dense
refactoring, the sparse strategy a factorisation of the whole sparse tangent per refactoring
(docs/performance.md, "Large contact interfaces" and "Large contact interfaces (issue 31)": a
block on a base, 61.6 k dofs and 2166 interface dofs, 35 s "condensed-krylov" against 164 s
"sparse-krylov"; a plate on a base with full-face contact, 22.6 k dofs and 6534 interface
dofs, 32 s "sparse-krylov" against 120-190 s).
The Newton loop runs with ``blas_threads`` BLAS threads (1: on these dense systems a second
thread costs more than it gains, and on a loaded machine far more). ``make bench-fe`` measures
the strategies and the engine against CalculiX (docs/performance.md, "FE engine";
environment-notes.md records the choice of solver).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
import scipy.sparse as sp

from ..interface import friction
from . import assembly
from .contact import InterfaceMaterial
from .linear_solvers import Condensed, Sparse
from .interface_points import InterfacePoints, interface_forces, interface_points
from ..limits import describe

__all__ = ["ContactModel", "NewtonOptions", "Increment", "Solution", "ConvergenceError", "LawRangeError", "solve",
           "Stepping", "IncrementLimitError"]

#: the round-off floor of a residual r = F − K u − f: this many ulps of |K| |u|
_ROUNDOFF = 1e3 * np.finfo(float).eps
#: a Newton correction this many times the displacements so far (or 1 m) is a singular tangent
_DIVERGED = 1e6
_DIVERGED_FLOOR = 1e3  # mm
#: step-length reductions of the line search before the shortest step is taken as it is
_BACKTRACKS = 8
#: the linear strategies; "auto" takes "condensed-krylov" up to this many interface dofs,
#: "sparse-krylov" beyond (module docstring, "Linear solves")
LINEAR_SOLVERS = ("auto", "condensed", "sparse", "condensed-krylov", "sparse-krylov")
AUTO_CONDENSED_MAX = 3000


class ConvergenceError(RuntimeError):
    """Newton did not converge at an increment even after the allowed cut-backs."""

    def __init__(self, increment: int, level: float, residual: float, reason: str):
        self.increment, self.level, self.residual, self.reason = increment, level, residual, reason
        super().__init__(f"no convergence at increment {increment} (load level {level:.6g}): "
                         f"{reason}; residual {residual:.3e} N after the allowed cut-backs")


class LawRangeError(ConvergenceError):
    """A converged state lies past the heavy end of the tabulated interface law: the answer
    would rest on the law's extrapolated tail (trial states only), not on the statistical model.
    A :class:`ConvergenceError` (no valid state at that increment) with its own message."""

    def __init__(self, increment: int, level: float, residual: float, reason: str):
        RuntimeError.__init__(self, f"increment {increment} (load level {level:.6g}) converged beyond the "
                                    f"tabulated interface law: {reason}")
        self.increment, self.level, self.residual, self.reason = increment, level, residual, reason


@dataclass(frozen=True)
class NewtonOptions:
    """Convergence criteria and limits (module docstring)."""

    max_iterations: int = 30
    force_rtol: float = 1e-9
    force_atol: float = 1e-9
    displacement_rtol: float = 1e-8
    displacement_atol: float = 1e-12
    max_cutbacks: int = 6
    linear_solver: str = "auto"
    blas_threads: int | None = 1
    line_search: bool = True

    def __post_init__(self):
        if self.linear_solver not in LINEAR_SOLVERS:
            raise ValueError(f"linear_solver must be one of {', '.join(map(repr, LINEAR_SOLVERS))}, "
                             f"got {describe(self.linear_solver)}")
        if self.blas_threads is not None and not (isinstance(self.blas_threads, int) and self.blas_threads >= 1):
            raise ValueError(f"blas_threads must be a positive integer or None, got {describe(self.blas_threads)}")
        if not (self.max_iterations >= 1 and self.max_cutbacks >= 0):
            raise ValueError("max_iterations must be >= 1 and max_cutbacks >= 0")
        for name in ("force_rtol", "force_atol", "displacement_rtol", "displacement_atol"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} must be positive")


@dataclass(frozen=True, eq=False)
class ContactModel:
    """The discrete problem: bulk stiffness K (3N × 3N) [N/mm], interface points, interface
    material, supported dofs (u = 0), the load pattern F (3N,) [N per unit load level] and a
    dead load F₀ (3N,) [N] present at every level (None: zero); optionally the node
    ``coordinates`` (N, 3) [mm], which give the linear solvers a fill-reducing ordering
    (:mod:`.ordering`; :meth:`assemble` passes the mesh's)."""

    stiffness: sp.csr_matrix
    points: InterfacePoints
    material: InterfaceMaterial
    fixed: np.ndarray
    load: np.ndarray
    dead_load: np.ndarray | None = None
    _cache: dict = field(default_factory=dict, repr=False)
    coordinates: np.ndarray | None = field(default=None, repr=False)

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
        if self.coordinates is not None:
            x = np.asarray(self.coordinates, dtype=float)
            if x.shape != (n // 3, 3) or not np.all(np.isfinite(x)):
                raise ValueError(f"coordinates must be finite node positions of shape ({n // 3}, 3)")
            object.__setattr__(self, "coordinates", x)

    @classmethod
    def assemble(cls, mesh, elasticity, material: InterfaceMaterial, fixed, load, *, dead_load=None,
                 rule: str = "lobatto", lay=(1.0, 0.0, 0.0)) -> "ContactModel":
        """From a :class:`~.mesh.Mesh`: ``elasticity`` a 6×6 Voigt matrix for every block or a
        dict block name → matrix [N/mm²] (:func:`.assembly.isotropic_elasticity`), interface
        points of ``rule`` with t1 along ``lay``."""
        blocks = [(b.element, b.cells) for b in mesh.blocks]
        D = [elasticity[b.name] for b in mesh.blocks] if isinstance(elasticity, dict) else elasticity
        K = assembly.stiffness(mesh.points, blocks, D)
        return cls(K, interface_points(mesh, rule, lay), material, fixed, load, dead_load, coordinates=mesh.points)

    def with_material(self, material: InterfaceMaterial) -> "ContactModel":
        """The same bodies, supports and loads with another interface material, sharing this
        model's factorised bulk (the linear solvers depend on K, B, the supports and loads only)."""
        return ContactModel(self.stiffness, self.points, material, self.fixed, self.load, self.dead_load,
                            self._cache, self.coordinates)

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
def interface_dofs(model: ContactModel) -> int:
    """The number of free dofs the interface touches (both sides): the size of the condensed
    dense system."""
    return int(np.count_nonzero(np.diff(model.points.B[:, model.free].tocsc().indptr) > 0))


def linear_strategy(model: ContactModel, kind: str = "auto") -> str:
    """The linear strategy ``kind`` resolves to: "auto" is "condensed-krylov" while the interface
    has at most AUTO_CONDENSED_MAX interface dofs, else "sparse-krylov" (module docstring)."""
    if kind != "auto":
        return kind
    return "condensed-krylov" if interface_dofs(model) <= AUTO_CONDENSED_MAX else "sparse-krylov"


def _linear_solver(model: ContactModel, kind: str):
    kind = linear_strategy(model, kind)
    key = ("linear", kind)
    if key not in model._cache:
        model._cache[key] = (Condensed if kind.startswith("condensed") else Sparse)(model, kind.endswith("krylov"))
    return model._cache[key]


# ---------------------------------------------------------------------------------------------
# Newton
# ---------------------------------------------------------------------------------------------
def _newton(model, solver, opts, level, u_n, state_n, guess):
    """Newton iterations at one load level from the committed (u_n, state_n), starting at
    ``guess``. Returns (u, response, residuals) or raises _Failed."""
    free, points, material = model.free, model.points, model.material
    jumps_n = points.jumps(u_n)
    f_ext = model.dead_load + level * model.load

    def evaluate(u):
        """(law response, free residual, its norm, interface forces); the response of a trial
        state past the heavy end of a tabulated law comes from its extrapolated tail."""
        resp = material.respond(state_n, points.jumps(u) - jumps_n, extrapolate=True)
        f_int_iface = interface_forces(points, resp.tractions)
        r = (f_ext - model.stiffness @ u - f_int_iface)[free]
        return resp, r, float(np.linalg.norm(r)), f_int_iface

    u = guess.copy()
    try:
        resp, r, norm, f_int_iface = evaluate(u)
    except ValueError as exc:  # beyond even the extrapolated tail of a tabulated law (or overflow)
        raise _Failed(math.inf, str(exc)) from None
    residuals, last_du, last_status = [], None, None
    for it in range(opts.max_iterations + 1):
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
        last_status = resp.status
        u, du, (resp, r, norm, f_int_iface) = _line_search(evaluate, u, free, du, norm, opts.line_search)
        last_du = du


def _line_search(evaluate, u, free, du, norm0, enabled):
    """The Newton step u + α du (module docstring, "Line search"): α = 1 unless the residual
    norm grows; then backtracking on φ(α) = ‖r(u + α du)‖² with the minimiser of the quadratic
    through φ(0), φ'(0) = −2φ(0) (the Newton direction) and φ(α), kept within [α/10, α/2], until
    ‖r‖ ≤ (1 − 10⁻⁴ α) ‖r(0)‖; after _BACKTRACKS reductions the best step tried is taken.
    Returns (u, α du, evaluation)."""
    trial = u.copy()
    alpha, best = 1.0, None
    phi0 = norm0 ** 2
    for k in range(_BACKTRACKS + 1):
        trial[free] = u[free] + alpha * du
        try:
            ev = evaluate(trial)
        except ValueError:  # past even the extrapolated tail: the step is far too long
            ev = None
        norm = ev[2] if ev is not None else math.inf
        if ev is not None and (best is None or norm < best[1][2]):
            best = (alpha, ev)
        if not enabled or norm <= (1.0 if k == 0 else 1.0 - 1e-4 * alpha) * norm0:
            break
        phi = norm ** 2
        ratio = phi0 * alpha / (phi - phi0 + 2.0 * phi0 * alpha) if math.isfinite(phi) else 0.0
        alpha *= min(max(ratio, 0.1), 0.5)
    else:  # no step met the criterion: the best one tried
        ev = None
    if ev is None:
        if best is None:
            raise _Failed(norm0, "every step length leads past the extrapolated tail of the interface law")
        alpha, ev = best
        trial[free] = u[free] + alpha * du
    return trial, alpha * du, ev


def _check_range(material: InterfaceMaterial, resp, increment: int, level: float, residual: float):
    """LawRangeError when a converged state lies past the heavy end of the tabulated law (the
    iterations may cross it: they see the law's extrapolated tail)."""
    beyond = material.beyond_table(resp.state)
    if beyond.any():
        bad = np.flatnonzero(beyond)
        law = material.normal_of(bad[0]) if hasattr(material, "normal_of") else material.normal  # a deck's laws
        raise LawRangeError(increment, level, residual, (
            f"p_N up to {np.max(resp.state[bad, friction.T_N]):.6g} at {bad.size} interface points "
            f"(first {bad[:10].tolist()}), u_N up to {np.max(resp.state[bad, friction.U_N]):.6g} "
            f"> u_max = {law.u_max:.6g} (p_max = {law.table.p_max:.6g}) in the law's length unit; "
            "rebuild the table with a larger p_max (pressure_range)"))


#: what a ConvergenceError's reason says when a cut-back would fall below Stepping.smallest
BELOW_SMALLEST = "; a further cut-back would fall below the smallest step"


class IncrementLimitError(ConvergenceError):
    """A level not reached within its :attr:`Stepping.max_increments` converged sub-steps."""


@dataclass(frozen=True)
class Stepping:
    """How :func:`solve` reaches one load level from the previous one (λ units, like the levels).

    ``first``: the first sub-step (None: the whole way); after every converged sub-step the
    step doubles, capped at ``largest`` (None: no cap) and landing exactly on the level; a
    failed sub-step is halved, down to ``smallest`` (None: at most ``max_cutbacks`` halvings;
    a halving below it raises ConvergenceError naming it). ``record``: every converged
    sub-step is an :class:`Increment` of the solution (else only the level's last);
    ``max_increments``: the most converged sub-steps the level may take (None: no limit;
    more raise :class:`IncrementLimitError`). The default reaches the level as before."""

    first: float | None = None
    largest: float | None = None
    smallest: float | None = None
    record: bool = False
    max_increments: int | None = None


_WHOLE = Stepping()


class _Failed(Exception):
    def __init__(self, residual, reason):
        self.residual, self.reason = residual, reason


def solve(model: ContactModel, levels: Sequence[float], options: NewtonOptions | None = None,
          progress: Callable[[int, int, Increment], None] | None = None,
          stepping: Sequence[Stepping] | None = None) -> Solution:
    """Load the model through ``levels`` (load levels λ, in the unit of the load pattern, e.g.
    N), each reached from the previous converged state (the first from u = 0 and the
    material's initial state), level k as ``stepping[k]`` says (:class:`Stepping`; default:
    in one step, cut back when Newton fails). ``progress(k, n, increment)`` is called after
    every recorded increment (k the level, 1-based)."""
    opts = options or NewtonOptions()
    if opts.blas_threads is None:
        return _solve(model, levels, opts, progress, stepping)
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=opts.blas_threads, user_api="blas"):
        return _solve(model, levels, opts, progress, stepping)


def _solve(model, levels, opts, progress, stepping=None) -> Solution:
    levels = [float(x) for x in levels]
    if not levels or not all(math.isfinite(x) for x in levels):
        raise ValueError("levels must be a non-empty sequence of finite load levels")
    stepping = [_WHOLE] * len(levels) if stepping is None else list(stepping)
    if len(stepping) != len(levels):
        raise ValueError(f"stepping: {len(stepping)} entries for {len(levels)} levels")
    solver = _linear_solver(model, opts.linear_solver)
    u = np.zeros(model.stiffness.shape[0])
    state = model.material.initial_state(model.points.n_points)
    previous = 0.0
    rate = None
    out = []
    for k, target in enumerate(levels):
        t0, spec, done = time.perf_counter(), stepping[k], 0
        level, step, cutbacks, iterations = previous, target - previous, 0, 0
        if spec.first is not None:
            step = math.copysign(spec.first, step)
        while True:
            # the last sub-step lands exactly on the target (halved steps sum to it up to rounding)
            trial = target if abs(target - level) <= abs(step) * (1.0 + 1e-9) else level + step
            # predictor: the last converged step's displacement rate (secant), else u_n
            guess = u if rate is None else u + rate * (trial - level)
            try:
                u_new, resp, residuals = _newton(model, solver, opts, trial, u, state, guess)
            except _Failed as fail:
                cutbacks += 1
                if spec.smallest is None and cutbacks > opts.max_cutbacks:
                    raise ConvergenceError(k + 1, trial, fail.residual, fail.reason) from None
                if spec.smallest is not None and abs(step) * 0.5 < spec.smallest:
                    raise ConvergenceError(k + 1, trial, fail.residual, f"{fail.reason}{BELOW_SMALLEST} "
                                           f"{spec.smallest:.6g} (to {abs(step) * 0.5:.6g})") from None
                step *= 0.5
                continue
            _check_range(model.material, resp, k + 1, trial, residuals[-1])
            rate = (u_new - u) / (trial - level) if trial != level else None
            u, state, level = u_new, resp.state, trial
            iterations += len(residuals) - 1
            step *= 2.0  # a cut-back step grows back after every converged sub-step
            if spec.largest is not None:
                step = math.copysign(min(abs(step), spec.largest), step)
            done += 1
            if level == target:
                break
            if spec.record:
                inc = Increment(level, u.copy(), state.copy(), resp.tractions.copy(), resp.status.copy(),
                                iterations, tuple(residuals), cutbacks, time.perf_counter() - t0)
                out.append(inc)
                t0, cutbacks, iterations = time.perf_counter(), 0, 0
                if progress is not None:
                    progress(k + 1, len(levels), inc)
            if spec.max_increments is not None and done >= spec.max_increments:
                raise IncrementLimitError(k + 1, level, residuals[-1], f"{done} increments reached level "
                                          f"{level:.6g} of {target:.6g}: more than the {spec.max_increments} allowed")
        inc = Increment(level, u.copy(), state.copy(), resp.tractions.copy(), resp.status.copy(),
                        iterations, tuple(residuals), cutbacks, time.perf_counter() - t0)
        out.append(inc)
        previous = target
        if progress is not None:
            progress(k + 1, len(levels), inc)
    return Solution(model, tuple(out))
