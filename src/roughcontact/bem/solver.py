"""The deterministic elastic contact of a periodic rough surface with a rigid flat, under load
control: a thin wrapper of ContactMechanics (optional extra ``[bem]``).

ContactMechanics (MIT; Pastewka and co-workers) solves the frictionless, non-adhesive contact of
a rigid surface with an elastic half-space of contact modulus E* on a periodic grid: the FFT
Green's function of the half-space (Stanley & Kato 1997, J. Tribol. 119, 481) and the
constrained conjugate gradients of Polonsky & Keer (1999, Wear 231, 206), at a prescribed total
force. The rough surface may be either body: the gap depends on the sum of the heights only
(the paper's eq. (42) and section 3: a rough surface on a smooth flat, E* of (42)).

Conventions: heights z[i, j] [L] at x = j·dx, y = i·dy (the library's; ContactMechanics indexes
[x, y], handled here); pressure p = W/A0 in the unit of E*; the contact area is the number of
grid points with compressive force times dx·dy; the mean gap ḡ [L] is the mean over the cell
of the distance between the flat and the deformed surface, the BEM's counterpart of the
model's separation h = s√m00 (the asperity model has no bulk deformation; in a periodic cell
the uniform q = 0 displacement is undefined and does not enter ḡ).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..validation import positive
from ..limits import describe

__all__ = ["SKIP_MESSAGE", "BEMNotInstalled", "BEMConvergenceError", "SolverSettings", "LadderResult",
           "available", "solve_pressures"]

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


@dataclass(frozen=True)
class LadderResult:
    """The solutions at increasing pressures (arrays over the pressures).

    pressure W/A0 [unit of E*]; area_fraction A/A0 [–]; mean_gap ḡ [L]; iterations [–];
    max_penetration [L] (the largest overlap left inside the contact); seconds [s] of each solve;
    settings : the tolerances used; pressure_field : the contact pressure [unit of E*] of the
    last solution on the grid, [i, j] as the heights (> 0 in contact).
    """

    pressure: np.ndarray
    area_fraction: np.ndarray
    mean_gap: np.ndarray
    iterations: np.ndarray
    max_penetration: np.ndarray
    seconds: np.ndarray
    settings: SolverSettings
    pressure_field: np.ndarray = field(repr=False)


def _check_map(z):
    z = np.asarray(z, dtype=float)
    if z.ndim != 2 or min(z.shape) < 8 or not np.all(np.isfinite(z)):
        raise ValueError(f"heights must be a finite 2-d map of at least 8 x 8 points, got shape {z.shape}")
    if not np.ptp(z) > 0:
        raise ValueError("heights are constant: a flat on a flat has no contact problem to solve")
    return z


def solve_pressures(z, dx: float, dy: float, E_star: float, pressures, *,
                    settings: SolverSettings = SolverSettings(), progress=None) -> LadderResult:
    """Solve the contact of the periodic map z[i, j] [L] (spacings dx, dy [L]) with a rigid
    flat at each nominal pressure of ``pressures`` (increasing; unit of E*), each solution
    starting from the previous one. E_star : contact modulus (42). progress(i, p, result) is
    called after each solve. BEMConvergenceError if a solve misses its tolerances."""
    _, ccg = _contact_mechanics()
    from ContactMechanics import PeriodicFFTElasticHalfSpace

    z = _check_map(z)
    dx, dy, E_star = positive("dx", dx), positive("dy", dy), positive("E_star", E_star)
    p = np.atleast_1d(np.asarray(pressures, dtype=float))
    if p.ndim != 1 or p.size == 0 or not np.all(np.isfinite(p) & (p > 0)) or np.any(np.diff(p) <= 0):
        raise ValueError(f"pressures must be positive, finite and increasing, got {describe(pressures)}")
    ny, nx = z.shape
    heights = np.ascontiguousarray(z.T)  # ContactMechanics: [x, y]
    area0 = nx * dx * ny * dy
    rms = float(np.sqrt(np.mean((z - z.mean()) ** 2)))
    substrate = PeriodicFFTElasticHalfSpace((nx, ny), E_star, (nx * dx, ny * dy))
    out = {k: [] for k in ("area", "gap", "it", "pen", "sec")}
    forces = None
    field_ = np.zeros((ny, nx))
    for i, pi in enumerate(p):
        t0 = time.perf_counter()
        res = ccg(substrate, heights, external_force=pi * area0, initial_forces=forces,
                  pentol=settings.pentol * rms, forcetol=settings.forcetol * pi * dx * dy,
                  thermotol=settings.thermotol, maxiter=settings.maxiter)
        seconds = time.perf_counter() - t0
        if not res.success:
            raise BEMConvergenceError(
                f"the BEM did not converge at W/A0 = {pi:g} after {res.nit} iterations "
                f"(maxiter {settings.maxiter}; {res.message}; {getattr(res, 'maxcv', {})})")
        f = np.asarray(res.jac)  # compressive force per grid point > 0
        gap = np.asarray(res.x) - heights - res.offset
        total = float(f.sum())
        # the solver rescales the forces to W each iteration; its last penetration correction
        # moves the total by ~1e-8 relative, far below the area's resolution
        if not math.isclose(total, pi * area0, rel_tol=1e-4):
            raise BEMConvergenceError(f"total force {total:g} != W = {pi * area0:g} at W/A0 = {pi:g}")
        in_contact = f > 0.0
        out["area"].append(float(in_contact.mean()))
        out["gap"].append(float(gap.mean()))
        out["it"].append(int(res.nit))
        out["pen"].append(float(max(0.0, -gap[in_contact].min())) if in_contact.any() else 0.0)
        out["sec"].append(seconds)
        field_ = f.T / (dx * dy)
        forces = -f  # ContactMechanics' sign: compressive forces are negative
        if progress is not None:
            progress(i, float(pi), {"area_fraction": out["area"][-1], "iterations": out["it"][-1],
                                    "seconds": seconds})
    return LadderResult(pressure=p, area_fraction=np.array(out["area"]), mean_gap=np.array(out["gap"]),
                        iterations=np.array(out["it"]), max_penetration=np.array(out["pen"]),
                        seconds=np.array(out["sec"]), settings=settings, pressure_field=field_)
