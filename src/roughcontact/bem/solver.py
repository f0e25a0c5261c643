"""The deterministic contact of a rough surface with a rigid flat, under load control: a thin
wrapper of ContactMechanics (optional extra ``[bem]``).

ContactMechanics (MIT; Pastewka and co-workers) solves the frictionless, non-adhesive contact of
a rigid surface with an elastic half-space of contact modulus E*: the FFT Green's function of
the half-space (Stanley & Kato 1997, J. Tribol. 119, 481) and the constrained conjugate
gradients of Polonsky & Keer (1999, Wear 231, 206), at a prescribed total force. The rough
surface may be either body: the gap depends on the sum of the heights only (the paper's eq. (42)
and section 3: a rough surface on a smooth flat, E* of (42)).

Boundary: ``periodic=True`` (default) — the map is one cell of a periodic surface
(PeriodicFFTElasticHalfSpace); ``periodic=False`` — the map is a finite patch on an unbounded
half-space, loaded nowhere else (FreeFFTElasticHalfSpace: Johnson 1985's point-force Green's
function, convolved by FFT on a grid padded to 2nx × 2ny, Hockney 1969). A measured scan is not
periodic: wrapping it would put steps at its edges.

Plastic cap: ``hardness=H`` bounds the contact pressure by H (a perfectly plastic surface layer;
ContactMechanics' plastic system, Almqvist et al. 2007, Tribol. Int. 40, 574; Weber et al. 2018,
Nat. Commun. 9, 888): points at p = H flow, and the rigid surface sinks into them.

Conventions: heights z[i, j] [L] at x = j·dx, y = i·dy (the library's; ContactMechanics indexes
[x, y], handled here); pressure p = W/A0 in the unit of E*; the contact area is the number of
grid points with compressive force times dx·dy; the mean gap ḡ [L] is the mean over the map of
the distance between the flat and the deformed surface, the BEM's counterpart of the model's
separation h = s√m00 (the asperity model has no bulk deformation; in a periodic cell the
uniform q = 0 displacement is undefined and does not enter ḡ). In the plastic case the points
at the hardness have gap 0: their overlap with the flat is material that has flowed, not a gap.
The normal stiffness per nominal area K/A0 = −dp/dḡ [unit of E* per L] is the central
difference of ḡ over ln p at p·e^(±ε), each side solve warm-started from the solution at p.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..validation import positive
from ..limits import describe

__all__ = ["SKIP_MESSAGE", "BEMNotInstalled", "BEMConvergenceError", "SolverSettings", "LadderResult",
           "BOUNDARIES", "STIFFNESS_STEP", "available", "solve_pressures"]

#: what every user-facing path prints when the extra is missing (one line)
SKIP_MESSAGE = "skipped: [bem] not installed — pip install '.[bem]'"


class BEMNotInstalled(ImportError):
    """The optional extra ``[bem]`` (ContactMechanics) is not installed."""

    def __init__(self, detail: str = ""):
        super().__init__(SKIP_MESSAGE + (f" ({detail})" if detail else ""))


class BEMConvergenceError(RuntimeError):
    """The solver did not reach its tolerances: the result is not returned."""


def _contact_mechanics():
    """The ContactMechanics module, or BEMNotInstalled."""
    try:
        with warnings.catch_warnings():  # NuMPI's notice on import: serial runs need no MPI
            warnings.filterwarnings("ignore", message="Could not import mpi4py")
            import ContactMechanics
            from ContactMechanics.Optimization import constrained_conjugate_gradients
    except ImportError as exc:
        raise BEMNotInstalled(str(exc)) from None
    return ContactMechanics, constrained_conjugate_gradients


def available() -> bool:
    """True where ContactMechanics imports (the extra ``[bem]``)."""
    try:
        _contact_mechanics()
    except BEMNotInstalled:
        return False
    return True


@dataclass(frozen=True)
class SolverSettings:
    """Tolerances of the constrained conjugate gradients (all relative, so that they mean the
    same in any unit system).

    pentol : largest penetration (rms and max) inside the contact and largest change of the
        displacements in the last iteration, as a fraction of the surface's rms height [–];
    forcetol : largest tensile force outside the contact, as a fraction of the mean force per
        grid point p·dx·dy [–];
    thermotol : relative change of the rigid body's position in the last iteration [–];
    maxiter : iterations before BEMConvergenceError.
    """

    pentol: float = 1e-4
    forcetol: float = 1e-3
    thermotol: float = 1e-6
    maxiter: int = 20000

    def __post_init__(self):
        for name in ("pentol", "forcetol", "thermotol"):
            v = positive(name, getattr(self, name))
            if not v < 1.0:
                raise ValueError(f"{name} must be a fraction in (0, 1), got {describe(v)}")
        if isinstance(self.maxiter, bool) or not isinstance(self.maxiter, int) or self.maxiter < 1:
            raise ValueError(f"maxiter must be a positive integer, got {describe(self.maxiter)}")

    def as_dict(self) -> dict:
        return {"pentol": self.pentol, "forcetol": self.forcetol, "thermotol": self.thermotol,
                "maxiter": self.maxiter}


#: the boundary of the elastic problem, as stated in results: periodic cell or finite patch
BOUNDARIES = {True: "periodic", False: "free boundary (padded)"}

#: ε of the stiffness's central difference in ln p (pressures p·e^(±ε)): its truncation error is
#: ε²/6 · (d³ḡ/d ln p³)/(dḡ/d ln p), 1e-4 on Westergaard's wave at p/p* = 0.05 and far less on rough
#: surfaces, whose ḡ is nearly linear in ln p (tests/bem/test_solver.py: ε against ε/2). Below it the
#: pixel-by-pixel growth of the contact (a kink in ḡ(p) per new point) dominates: ~1e-3 on 256² maps.
STIFFNESS_STEP = 0.05


@dataclass(frozen=True)
class LadderResult:
    """The solutions at increasing pressures (arrays over the pressures).

    pressure W/A0 [unit of E*]; area_fraction A/A0 [–] (elastic and plastic contact);
    mean_gap ḡ [L]; iterations [–] and seconds [s] of each pressure's solve (with the stiffness,
    of its two side solves too); max_penetration [L] (the largest overlap left inside the
    elastic contact);
    settings : the tolerances used; pressure_field : the contact pressure [unit of E*] of the
    last solution on the grid, [i, j] as the heights (> 0 in contact);
    periodic : the boundary (:data:`BOUNDARIES`); hardness : the pressure cap H [unit of E*] or
    None (elastic); plastic_area_fraction : the fraction of the map at p = H [–] (None if elastic);
    penetration_residual : the solver's largest penetration inside the contact at convergence,
    over the rms height [–]; force_residual : its largest tensile force outside the contact (and,
    plastic, the largest force above the cap) over the mean force per point p·dx·dy [–];
    stiffness : K/A0 = −dp/dḡ [unit of E* per L] (None unless asked for); stiffness_step : its ε.
    """

    pressure: np.ndarray
    area_fraction: np.ndarray
    mean_gap: np.ndarray
    iterations: np.ndarray
    max_penetration: np.ndarray
    seconds: np.ndarray
    settings: SolverSettings
    pressure_field: np.ndarray = field(repr=False)
    periodic: bool = True
    hardness: float | None = None
    plastic_area_fraction: np.ndarray | None = None
    penetration_residual: np.ndarray | None = None
    force_residual: np.ndarray | None = None
    stiffness: np.ndarray | None = None
    stiffness_step: float | None = None

    @property
    def boundary(self) -> str:
        """'periodic' or 'free boundary (padded)'."""
        return BOUNDARIES[self.periodic]


def _check_map(z):
    z = np.asarray(z, dtype=float)
    if z.ndim != 2 or min(z.shape) < 8 or not np.all(np.isfinite(z)):
        raise ValueError(f"heights must be a finite 2-d map of at least 8 x 8 points, got shape {z.shape}")
    if not np.ptp(z) > 0:
        raise ValueError("heights are constant: a flat on a flat has no contact problem to solve")
    return z


def _check_pressures(pressures):
    p = np.atleast_1d(np.asarray(pressures, dtype=float))
    if p.ndim != 1 or p.size == 0 or not np.all(np.isfinite(p) & (p > 0)) or np.any(np.diff(p) <= 0):
        raise ValueError(f"pressures must be positive, finite and increasing, got {describe(pressures)}")
    return p


class _Problem:
    """One map on one substrate: solve(p, warm) → the state at W/A0 = p."""

    def __init__(self, z, dx, dy, E_star, periodic, hardness, settings):
        CM, self.ccg = _contact_mechanics()
        ny, nx = z.shape
        self.nx, self.ny, self.dx, self.dy = nx, ny, dx, dy
        self.heights = np.ascontiguousarray(z.T)  # ContactMechanics: [x, y]
        self.area0 = nx * dx * ny * dy
        self.rms = float(np.sqrt(np.mean((z - z.mean()) ** 2)))
        half_space = CM.PeriodicFFTElasticHalfSpace if periodic else CM.FreeFFTElasticHalfSpace
        self.substrate = half_space((nx, ny), E_star, (nx * dx, ny * dy))
        self.cap = None if hardness is None else hardness * dx * dy  # the largest force per point
        self.settings = settings

    def solve(self, p: float, warm, rescale: bool = False) -> dict:
        """The converged state at W/A0 = p, from the forces of ``warm`` (a previous state; times
        p/p_warm if ``rescale``) or from scratch.

        The solver's own test of convergence looks inside its contact set only: warm-started
        from a contact of a single point, it has reported success with that one point while the
        flat overlapped the rest of the map (ḡ < 0; 128², a ladder from 1e-2 N/mm²). So the
        complementarity is checked here as well — no overlap outside the contact beyond the
        penetration tolerance — and a state that fails it is solved again from scratch, then
        refused (BEMConvergenceError)."""
        state = self._solve(p, warm, rescale)
        if warm is not None and state["overlap"] > self.settings.pentol:
            cold = self._solve(p, None)
            cold["it"] += state["it"]
            cold["sec"] += state["sec"]
            state = cold
        if state["overlap"] > self.settings.pentol:
            raise BEMConvergenceError(
                f"the BEM reported convergence at W/A0 = {p:g} with the flat overlapping the surface outside "
                f"the contact by {state['overlap']:.3g} rms heights (tolerance {self.settings.pentol:g})")
        return state

    def _solve(self, p: float, warm, rescale: bool = False) -> dict:
        s = self.settings
        nx, ny = self.nx, self.ny
        initial = None
        if warm is not None:
            initial = np.zeros(self.substrate.nb_subdomain_grid_pts)  # 2nx × 2ny when padded
            # ContactMechanics' sign: compressive forces are negative
            initial[:nx, :ny] = -warm["force"] * (p / warm["p"] if rescale else 1.0)
        t0 = time.perf_counter()
        res = self.ccg(self.substrate, self.heights, hardness=self.cap, external_force=p * self.area0,
                       initial_forces=initial, pentol=s.pentol * self.rms, forcetol=s.forcetol * p * self.dx * self.dy,
                       thermotol=s.thermotol, maxiter=s.maxiter)
        seconds = time.perf_counter() - t0
        if not res.success:
            raise BEMConvergenceError(
                f"the BEM did not converge at W/A0 = {p:g} after {res.nit} iterations "
                f"(maxiter {s.maxiter}; {res.message}; {getattr(res, 'maxcv', {})})")
        f = np.asarray(res.jac)  # compressive force per grid point > 0, [x, y] over the map
        gap = np.asarray(res.x)[:nx, :ny] - self.heights - res.offset
        total = float(f.sum())
        # the solver rescales the forces to W each iteration; its last penetration correction
        # moves the total by ~1e-8 relative, far below the area's resolution
        if not math.isclose(total, p * self.area0, rel_tol=1e-4):
            raise BEMConvergenceError(f"total force {total:g} != W = {p * self.area0:g} at W/A0 = {p:g}")
        plastic = np.zeros(f.shape, bool) if self.cap is None else f >= self.cap * (1.0 - 1e-9)
        elastic = (f > 0.0) & ~plastic
        outside = f <= 0.0
        overlap = float(max(0.0, -gap[outside].min())) / self.rms if outside.any() else 0.0
        if self.cap is not None:
            gap = np.maximum(gap, 0.0)  # the overlap at p = H has flowed: gap 0 there
        cv = getattr(res, "maxcv", {})
        return {"p": p, "force": f, "area": float((f > 0.0).mean()), "plastic": float(plastic.mean()),
                "gap": float(gap.mean()), "it": int(res.nit), "sec": seconds, "overlap": overlap,
                "pen": float(max(0.0, -gap[elastic].min())) if elastic.any() else 0.0,
                "pen_res": float(cv.get("max_pen", 0.0)) / self.rms,
                "force_res": float(cv.get("max_pres", 0.0)) / (p * self.dx * self.dy)}


def solve_pressures(z, dx: float, dy: float, E_star: float, pressures, *,
                    settings: SolverSettings = SolverSettings(), progress=None, periodic: bool = True,
                    hardness: float | None = None, stiffness_step: float | None = None) -> LadderResult:
    """Solve the contact of the map z[i, j] [L] (spacings dx, dy [L]) with a rigid flat at each
    nominal pressure of ``pressures`` (increasing; unit of E*), each solution starting from the
    previous one. E_star : contact modulus (42). periodic : the map is a periodic cell (True) or a
    finite patch (False, free boundary). hardness : the pressure cap H [unit of E*], > every
    pressure (None: elastic). stiffness_step : ε > 0 to compute K/A0 = −dp/dḡ at every pressure
    by the central difference p·2ε/(ḡ(p e^−ε) − ḡ(p e^ε)) (two more solves per pressure, warm-
    started from the solution at p; exact where ḡ is linear in ln p, Persson 2007, PRL 99, 125502).
    progress(i, p, result) is called after each pressure. BEMConvergenceError if a solve misses
    its tolerances."""
    _contact_mechanics()
    z = _check_map(z)
    dx, dy, E_star = positive("dx", dx), positive("dy", dy), positive("E_star", E_star)
    p = _check_pressures(pressures)
    if not isinstance(periodic, (bool, np.bool_)):
        raise ValueError(f"periodic must be True or False, got {describe(periodic)}")
    eps = None if stiffness_step is None else positive("stiffness_step", stiffness_step)
    if eps is not None and not eps <= 0.5:
        raise ValueError(f"stiffness_step must be at most 0.5 (a step in ln p), got {describe(eps)}")
    if hardness is not None:
        hardness = positive("hardness", hardness)
        top = p[-1] * math.exp(eps or 0.0)
        if not top < hardness:
            raise ValueError(f"hardness {describe(hardness)} must exceed the largest pressure solved, "
                             f"{top:g} (W/A0 <= H: the whole map at the cap carries at most H)")
    problem = _Problem(z, dx, dy, E_star, bool(periodic), hardness, settings)
    # one increasing ladder through every pressure and its stiffness's side points, each solve
    # warm-started from the previous one's forces scaled to the new load. ContactMechanics bb5a881
    # stalls otherwise: from a *higher* load, or from a load a few % lower, its first iteration
    # rescales the forces to W and the conjugate direction of the next (G/G_old ≫ 1) is lost. The
    # plain ladder (no stiffness) keeps the unscaled start of the workflow's runs.
    sides = (-1.0, 0.0, 1.0) if eps is not None else (0.0,)
    points = sorted((float(pi) * math.exp(k * eps if eps else 0.0), i, k) for i, pi in enumerate(p) for k in sides)
    solved, state, done = {}, None, {i: 0 for i in range(p.size)}
    for load, i, k in points:
        state = problem.solve(load, state, rescale=eps is not None)
        solved[i, k] = state
        done[i] += 1
        if done[i] == len(sides) and progress is not None:
            parts = [solved[i, k] for k in sides]
            progress(i, float(p[i]), {"area_fraction": solved[i, 0.0]["area"], "iterations": sum(s["it"] for s in parts),
                                      "seconds": sum(s["sec"] for s in parts)})
    rows, stiffness = [], []
    for i, pi in enumerate(p):
        row = dict(solved[i, 0.0])
        if eps is not None:
            lo, hi = solved[i, -1.0], solved[i, 1.0]
            stiffness.append(float(pi) * 2.0 * eps / (lo["gap"] - hi["gap"]))
            row["sec"] += lo["sec"] + hi["sec"]
            row["it"] += lo["it"] + hi["it"]
        rows.append(row)
    col = lambda key: np.array([r[key] for r in rows])  # noqa: E731
    return LadderResult(pressure=p, area_fraction=col("area"), mean_gap=col("gap"), iterations=col("it"),
                        max_penetration=col("pen"), seconds=col("sec"), settings=settings,
                        pressure_field=solved[p.size - 1, 0.0]["force"].T / (dx * dy), periodic=bool(periodic), hardness=hardness,
                        plastic_area_fraction=None if hardness is None else col("plastic"),
                        penetration_residual=col("pen_res"), force_residual=col("force_res"),
                        stiffness=np.array(stiffness) if eps is not None else None, stiffness_step=eps)
