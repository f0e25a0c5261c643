"""The BEM checked on closed forms, as its authors check it (ContactMechanics' own tests: Hertz,
flat punch, Westergaard), on the grids of the rough-surface runs.

* Hertz, a sphere of radius R on the periodic n × n grid of square pixels (Johnson 1985,
  *Contact Mechanics*, eqs. (4.22)–(4.23)): a = (3WR/4E*)^{1/3}, p0 = 3W/(2πa²);
* Hertz, an elliptic paraboloid on the anisotropic pixels dx × dy of a family's grid, with the
  curvature ratio that makes the contact ellipse span as many pixels along x as along y (exact
  Hertz functions of asperity.ellipse: B/A = e1(λ), A_i = f1 π ω/κ_m (46), W = f2 (4/3) E*
  κ_m^{-1/2} ω^{3/2} (47), p0 = 3W/(2 A_i));
* Westergaard's wavy surface z = h0 cos(2πx/λ) in partial contact (Westergaard 1939; Johnson
  1985, eqs. (13.6)–(13.9)): p̄ = p* sin²(πa/λ) with p* = πE*h0/λ, p_max = 2p̄/sin(πa/λ),
  along x and along y of a family's grid.

Each check returns the computed and the closed-form values of the contact size (the equivalent
radius √(A/π), or the contact fraction 2a/λ) and of the largest pressure; the areas are counts
of pixels with compressive force, as for the rough surfaces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..asperity import ellipse
from .solver import SolverSettings, solve_pressures
from ..limits import describe

__all__ = ["BEMCheck", "hertz_sphere", "hertz_elliptic", "westergaard"]


@dataclass(frozen=True)
class BEMCheck:
    """One closed-form check: ``size`` and ``p_max`` computed and exact, and their ratios."""

    case: str
    n: int
    size: float
    size_exact: float
    p_max: float
    p_max_exact: float
    iterations: int
    pixels_across: float  # the contact's diameter (or width) in pixels

    @property
    def size_ratio(self) -> float:
        return self.size / self.size_exact

    @property
    def p_max_ratio(self) -> float:
        return self.p_max / self.p_max_exact


def _solve(case, z, dx, dy, E_star, p, settings, size, size_exact, p_max_exact, pixels):
    res = solve_pressures(z, dx, dy, E_star, [p], settings=settings)
    field = res.pressure_field
    return BEMCheck(case=case, n=z.shape[0], size=size(res.area_fraction[0]), size_exact=size_exact,
                    p_max=float(field.max()), p_max_exact=p_max_exact, iterations=int(res.iterations[0]),
                    pixels_across=pixels)


def _centred(n, d):
    """Coordinates [L] of n points of spacing d, centred on the cell."""
    return (np.arange(n) - n / 2) * d


def hertz_sphere(n: int, *, radius_fraction: float = 0.125, E_star: float = 1.0,
                 settings: SolverSettings = SolverSettings()) -> BEMCheck:
    """A sphere (R = L) on an n × n periodic cell of side L = 1 with square pixels, loaded so
    that a_Hertz = radius_fraction · L (n·radius_fraction pixels). ``size``: √(A/π) vs a."""
    L, R = 1.0, 1.0
    a = radius_fraction * L
    W = 4.0 * E_star * a**3 / (3.0 * R)  # a = (3WR/4E*)^(1/3)
    d = L / n
    x = _centred(n, d)
    z = -(x[np.newaxis, :] ** 2 + x[:, np.newaxis] ** 2) / (2.0 * R)
    p0 = 3.0 * W / (2.0 * math.pi * a**2)
    return _solve("hertz_sphere", z, d, d, E_star, W / L**2, settings,
                  lambda frac: math.sqrt(frac * L * L / math.pi), a, p0, 2 * a / d)


def hertz_elliptic(n: int, dx_over_dy: float, *, axis_fraction: float = 0.0625, E_star: float = 1.0,
                   settings: SolverSettings = SolverSettings()) -> BEMCheck:
    """An elliptic paraboloid on an n × n cell of pixels dx × dy (dx/dy = ``dx_over_dy`` ≥ 1,
    L_y = 1): curvatures κ_x < κ_y with the ratio λ² = κ_x/κ_y that gives B/A = dy/dx, loaded so
    that the contact ellipse's semi-axes are axis_fraction · (L_x, L_y). ``size``: √(A/π) vs
    √(A_i/π) of (46)."""
    if not dx_over_dy >= 1.0:
        raise ValueError(f"dx_over_dy must be >= 1, got {describe(dx_over_dy)}")
    Ly = 1.0
    Lx = dx_over_dy * Ly
    e1 = 1.0 / dx_over_dy
    lam = float(ellipse.lambda_from_e1(e1))
    kappa_y = 1.0
    kappa_x = lam**2 * kappa_y
    kappa_m = 0.5 * (kappa_x + kappa_y)
    A, B = axis_fraction * Lx, axis_fraction * Ly
    f1, f2 = float(ellipse.f1(e1)), float(ellipse.f2(e1))
    omega = A * B * kappa_m / f1  # π A B = f1 π ω / κ_m (46)
    W = f2 * 4.0 / 3.0 * E_star * kappa_m**-0.5 * omega**1.5  # (47)
    area = math.pi * A * B
    dx, dy = Lx / n, Ly / n
    x, y = _centred(n, dx), _centred(n, dy)
    z = -(kappa_x * x[np.newaxis, :] ** 2 + kappa_y * y[:, np.newaxis] ** 2) / 2.0
    return _solve("hertz_elliptic", z, dx, dy, E_star, W / (Lx * Ly), settings,
                  lambda frac: math.sqrt(frac * Lx * Ly / math.pi), math.sqrt(area / math.pi),
                  3.0 * W / (2.0 * area), 2 * B / dy)


def westergaard(n: int, *, dx: float = 1.0, dy: float = 1.0, axis: str = "x", contact_fraction: float = 0.5,
                E_star: float = 1.0, settings: SolverSettings = SolverSettings()) -> BEMCheck:
    """One wave z = h0 cos(2π x/λ) (or along y) over the n × n cell (λ = n·dx), h0 = λ/100, at
    the mean pressure whose contact width 2a is ``contact_fraction`` of λ. ``size``: the contact
    fraction 2a/λ (the area fraction of the strip)."""
    if axis not in ("x", "y"):
        raise ValueError(f"axis must be 'x' or 'y', got {describe(axis)}")
    if not 0.0 < contact_fraction < 1.0:
        raise ValueError(f"contact_fraction must lie in (0, 1), got {describe(contact_fraction)}")
    lam = n * (dx if axis == "x" else dy)
    h0 = lam / 100.0
    p_star = math.pi * E_star * h0 / lam
    a = 0.5 * contact_fraction * lam
    p_mean = p_star * math.sin(math.pi * a / lam) ** 2
    t = 2 * math.pi * np.arange(n) / n
    wave = h0 * np.cos(t)
    z = np.tile(wave, (n, 1)) if axis == "x" else np.tile(wave[:, np.newaxis], (1, n))
    return _solve(f"westergaard_{axis}", z, dx, dy, E_star, p_mean, settings, lambda frac: frac,
                  contact_fraction, 2.0 * p_mean / math.sin(math.pi * a / lam), contact_fraction * n)
