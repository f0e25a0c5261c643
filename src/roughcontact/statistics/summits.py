"""Summits of a Gaussian surface: measured on a height map, and expected from its moments with
and without the fourth-order cross moment m22.

The model of the paper keeps five moments and drops m22 = E[z_xy²] (section 2, after eq. (6);
Bush, Gibson & Keogh 1979): the summit density (17), the mean summit curvature (70) and the
summit heights (71)–(73) follow from the pdf (18) of (ξ1, ξ4, ξ6) alone. A real Gaussian surface
has m22 > 0 (an elliptically stretched isotropic one: m22 = √(m40 m04)/3, Nayak 1971). The
expectations below keep it, by the Rice formula for the maxima of a Gaussian field
(Longuet-Higgins 1957; Nayak 1971, eqs. (29)–(35)): in the lay frame (m11 = m31 = m13 = 0) the
gradient (ξ2, ξ3) is independent of (ξ1, ξ4, ξ5, ξ6) and ξ5 of (ξ4, ξ6), so

    D_sum = E[det H · 1{H ≺ 0}] / (2π √(m20 m02)),   H = [[ξ4, ξ5], [ξ5, ξ6]],

and with X = −ξ4, Y = −ξ6 > 0 the expectation over ξ5 ~ N(0, m22) of (XY − ξ5²)·1{ξ5² < XY}
is closed: g(c) = c(2Φ(r) − 1) − m22[(2Φ(r) − 1) − 2rφ(r)], c = XY, r = √(c/m22); g(c) = c when
m22 = 0, which gives back (17). Summit statistics are then g-weighted means over (X, Y), a
bivariate normal (variances m40, m04, covariance m22) on the positive quadrant; the height ξ1
given (X, Y) is normal with the regression mean and variance of the covariance matrix (3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr

from .surface import SpectralMoments

__all__ = ["SummitStatistics", "gaussian_summit_statistics", "map_summits", "measure_summits"]

#: Gauss–Legendre points per axis on [0, _U] in units of √m40, √m04 (the integrand is smooth
#: and below e^-60 of its peak beyond _U = 11; 160 points give 1e-12, tests/statistics/test_summits.py)
_NODES = 160
_U = 11.0


@dataclass(frozen=True)
class SummitStatistics:
    """Summit statistics of a surface [units of the moments' length L].

    density : summits per unit area [1/L²] (17);
    mean_curvature : mean over summits of (|ξ4| + |ξ6|)/2 [1/L] (43), (70);
    mean_height : mean summit height above the mean plane of the heights, δ [L] (73);
    height_std : standard deviation of the summit heights, σ_s [L] (71)–(72);
    count : number of summits found (maps only; 0 for an expectation).
    """

    density: float
    mean_curvature: float
    mean_height: float
    height_std: float
    count: int = 0

    def as_dict(self) -> dict[str, float]:
        return {"density": self.density, "mean_curvature": self.mean_curvature,
                "mean_height": self.mean_height, "height_std": self.height_std}


def gaussian_summit_statistics(moments: SpectralMoments, m22: float = 0.0) -> SummitStatistics:
    """Expected summit statistics of a Gaussian surface with these five moments (lay frame,
    m11 = m31 = m13 = 0) and the cross moment ``m22`` [L⁻²] (0: the paper's model, whose
    closed forms (17), (70), (71)–(73) this reproduces; √(m40 m04)/3: an elliptically stretched
    isotropic surface, Nayak's isotropic results). 0 ≤ m22 < √(m40 m04)."""
    if not isinstance(moments, SpectralMoments):
        raise TypeError(f"moments must be a SpectralMoments, got {type(moments).__name__}")
    m = moments
    m22 = float(m22)
    if not (math.isfinite(m22) and 0.0 <= m22 < math.sqrt(m.m40 * m.m04)):
        raise ValueError(f"m22 must lie in [0, sqrt(m40 m04)) = [0, {math.sqrt(m.m40 * m.m04):.6g}), got {m22!r}")
    t, w = np.polynomial.legendre.leggauss(_NODES)
    u = 0.5 * _U * (t + 1.0)
    w = 0.5 * _U * w
    uu, vv = np.meshgrid(u, u, indexing="ij")
    ww = np.outer(w, w)
    s4, s6 = math.sqrt(m.m40), math.sqrt(m.m04)
    X, Y = s4 * uu, s6 * vv
    rho = m22 / (s4 * s6)
    # bivariate normal density of (X, Y) in the scaled variables (the Jacobian s4 s6 cancels
    # in every ratio below but not in the density itself)
    pdf = np.exp(-(uu**2 - 2 * rho * uu * vv + vv**2) / (2 * (1 - rho**2))) / (
        2 * math.pi * math.sqrt(1 - rho**2))
    c = X * Y
    if m22 > 0.0:
        r = np.sqrt(c / m22)
        erf_r = 2.0 * ndtr(r) - 1.0
        g = c * erf_r - m22 * (erf_r - 2.0 * r * np.exp(-0.5 * r * r) / math.sqrt(2 * math.pi))
    else:
        g = c
    weight = ww * pdf * g
    total = weight.sum()
    density = total / (2 * math.pi * math.sqrt(m.m20 * m.m02))
    curvature = float((weight * 0.5 * (X + Y)).sum() / total)
    # regression of ξ1 on (X, Y): cov(ξ1, X) = m20, cov(ξ1, Y) = m02 (Appendix A, n14, n16)
    cov = np.array([[m.m40, m22], [m22, m.m04]])
    b = np.linalg.solve(cov, np.array([m.m20, m.m02]))
    cond_var = m.m00 - float(b @ np.array([m.m20, m.m02]))
    mean_h = b[0] * X + b[1] * Y
    delta = float((weight * mean_h).sum() / total)
    var = cond_var + float((weight * (mean_h - delta) ** 2).sum() / total)
    return SummitStatistics(density=float(density), mean_curvature=curvature, mean_height=delta,
                            height_std=math.sqrt(var))


def map_summits(z: np.ndarray) -> np.ndarray:
    """Boolean mask of the 8-neighbour summits of a periodic height map (points higher than
    all eight neighbours: the paper's section 1 definition)."""
    mask = np.ones(z.shape, dtype=bool)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di or dj:
                mask &= z > np.roll(z, (di, dj), axis=(0, 1))
    return mask


def measure_summits(z, dx: float, dy: float) -> SummitStatistics:
    """Summit statistics of a periodic height map z[i, j] at x = j·dx, y = i·dy [L]: the
    8-neighbour maxima, their heights above the map's mean, and the curvatures ξ4 = z_xx,
    ξ6 = z_yy there by spectral differentiation (exact for a band-limited periodic map)."""
    z = np.asarray(z, dtype=float)
    if z.ndim != 2 or min(z.shape) < 3 or not np.all(np.isfinite(z)):
        raise ValueError(f"z must be a finite 2-d map of at least 3 x 3 points, got shape {z.shape}")
    for name, d in (("dx", dx), ("dy", dy)):
        if not (math.isfinite(d) and d > 0):
            raise ValueError(f"{name} must be a positive finite length, got {d!r}")
    ny, nx = z.shape
    zf = np.fft.fft2(z - z.mean())
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=dx)[np.newaxis, :]
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=dy)[:, np.newaxis]
    zxx = np.fft.ifft2(-(qx**2) * zf).real
    zyy = np.fft.ifft2(-(qy**2) * zf).real
    mask = map_summits(z)
    n = int(mask.sum())
    if n < 2:
        raise ValueError(f"the map has {n} summit(s): too few for statistics")
    heights = (z - z.mean())[mask]
    kappa = 0.5 * (np.abs(zxx[mask]) + np.abs(zyy[mask]))
    return SummitStatistics(density=n / (nx * dx * ny * dy), mean_curvature=float(kappa.mean()),
                            mean_height=float(heights.mean()), height_std=float(heights.std()), count=n)
