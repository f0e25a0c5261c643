"""Figs 1 and 2 of the paper, drawn from the library: what they show, computed.

* :func:`fig1_profile` — a synthetic anisotropic Gaussian surface with the moments of a
  configured surface (:func:`roughcontact.statistics.synthetic.synthetic_surface`), one
  profile across the lay, the surface's mean plane (z = 0), the mean plane of the summits
  at the model's δ (73) and the summits the generated map actually has (8-neighbour maxima),
  whose mean height is an independent check of δ.
* :func:`fig2_asperity` — one elliptic-paraboloid asperity (19) with summit curvatures
  ξ4 = ω4 √(m40 μ), ξ6 = ω6 √(m04 μ) (13), the geometric ellipse a, b cut by the plane at
  the interference ω = ξ1 − h (20)–(21), and the Hertz contact ellipse A, B of (26)–(27)
  (e1 = B/A from :func:`roughcontact.asperity.ellipse.e1_from_lambda`).

Lengths in the moments' unit L. Pure numpy; no plotting, no I/O.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..asperity import ellipse
from ..statistics.summits import map_summits as summits
from ..statistics.surface import SpectralMoments
from ..statistics.synthetic import grid_moments, synthetic_surface

__all__ = ["SurfaceProfile", "AsperityGeometry", "summits", "fig1_profile", "fig2_asperity"]


@dataclass(frozen=True)
class SurfaceProfile:
    """Fig. 1's data: the profile z(y) [L] at y [L] across the lay, the mean planes."""

    y: np.ndarray
    z: np.ndarray
    summit_y: np.ndarray          # the map's summits within ``band`` of the profile line
    summit_z: np.ndarray
    band: float                   # half-width of that band [L]
    map_summits: int              # number of summits of the whole map
    delta: float                  # δ of eq. (73) [L]
    map_summit_mean: float        # mean height of every summit of the map [L]
    map_summit_density: float     # summits per unit area of the map [1/L²]
    model_summit_density: float   # D_sum of eq. (17) [1/L²]
    map_m00: float                # the map's height variance [L²]
    grid_m00: float               # its expectation on the grid (statistics.synthetic.grid_moments)
    flat: float                   # height h = s √m00 of the smooth flat drawn [L]
    sigma_s: float                # summit-height standard deviation, eqs. (71)-(72) [L]
    patch: np.ndarray             # the map around the profile: its rows, as many columns [L]
    patch_extent: tuple           # (x0, x1, y0, y1) of the patch [L]


def fig1_profile(moments: SpectralMoments, *, n: int, dx: float, seed: int, profile_length: float,
                 separation: float, band_points: int = 3) -> SurfaceProfile:
    """A seeded n × n map with spacing ``dx`` [L] (x along the lay), its summits, and the
    profile across the lay (along y) through the map's middle column, ``profile_length`` [L]
    long, with the summits within ``band_points`` columns of it; the smooth flat at
    separation s = h/√m00 = ``separation``."""
    if not (profile_length > 0 and profile_length <= n * dx):
        raise ValueError(f"profile_length must be in (0, n*dx = {n * dx:g}], got {profile_length!r}")
    z = synthetic_surface(moments, (n, n), dx, seed=seed)  # z[i, j]: y = i dx, x = j dx
    peaks = summits(z)
    column = n // 2
    rows = int(round(profile_length / dx)) + 1
    y = np.arange(rows) * dx
    near_i, near_j = np.nonzero(peaks[:rows, column - band_points:column + band_points + 1])
    half = min(rows // 2, column)
    patch = z[:rows, column - half:column + half + 1]
    return SurfaceProfile(
        y=y, z=z[:rows, column], summit_y=near_i * dx, summit_z=z[near_i, near_j + column - band_points],
        band=band_points * dx, map_summits=int(peaks.sum()),
        delta=moments.summit_mean_height, map_summit_mean=float(z[peaks].mean()),
        map_summit_density=float(peaks.sum() / (n * dx) ** 2), model_summit_density=moments.summit_density,
        map_m00=float(z.var()), grid_m00=grid_moments(moments, (n, n), dx)["m00"],
        flat=separation * math.sqrt(moments.m00), sigma_s=moments.summit_height_std,
        patch=patch, patch_extent=((column - half) * dx, (column + half) * dx, 0.0, (rows - 1) * dx),
    )


@dataclass(frozen=True)
class AsperityGeometry:
    """Fig. 2's data: the asperity's curvatures [1/L], the interference ω [L], the geometric
    ellipse a (along x), b (along y) and the contact ellipse A (along x), B (along y) [L];
    e1 = min(A, B)/max(A, B)."""

    xi4: float
    xi6: float
    interference: float
    a: float
    b: float
    A: float
    B: float
    e1: float

    def height(self, x, y):
        """The paraboloid (19) relative to its summit: z − ξ1 = −(ξ4 x² + ξ6 y²)/2 [L]."""
        return -0.5 * (self.xi4 * np.asarray(x) ** 2 + self.xi6 * np.asarray(y) ** 2)


def fig2_asperity(moments: SpectralMoments, *, omega4: float, omega6: float, interference: float) -> AsperityGeometry:
    """One asperity of the surface ``moments`` with standardised curvatures ω4, ω6 (13) at
    interference ω [L]: a² = 2ω/ξ4, b² = 2ω/ξ6 (20), λ = b/a, e1 = B/A from (27), and
    A² (1/a² + e1²/b²) = 1 from (26)."""
    if not (omega4 > 0 and omega6 > 0 and interference > 0):
        raise ValueError("omega4, omega6 and interference must be positive")
    mu = moments.mu
    xi4, xi6 = omega4 * math.sqrt(moments.m40 * mu), omega6 * math.sqrt(moments.m04 * mu)  # eq. (13)
    a, b = math.sqrt(2 * interference / xi4), math.sqrt(2 * interference / xi6)  # eq. (20)
    lam = min(a, b) / max(a, b)
    e1 = float(ellipse.e1_from_lambda(lam))  # eq. (27), exact inversion
    big, small = max(a, b), min(a, b)
    A = 1.0 / math.sqrt(1.0 / big**2 + e1**2 / small**2)  # eq. (26) with B = e1 A
    B = e1 * A
    if a < b:  # the major axes follow the smaller curvature
        A, B = B, A
    return AsperityGeometry(xi4=xi4, xi6=xi6, interference=interference, a=a, b=b, A=A, B=B, e1=e1)
