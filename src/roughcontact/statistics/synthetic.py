"""Seeded, periodic synthetic Gaussian surfaces with a prescribed anisotropic spectrum.

Convention (docs/fe-export.md, "Moments"): wavenumbers are angular, q = 2π/λ [rad/L], and the
power spectral density Φ(q_x, q_y) [L⁴] is normalised so that

    m_pq = ∫∫ q_x^p q_y^q Φ(q) d²q,   m00 = Var z,  m20 = Var ∂z/∂x,  m40 = Var ∂²z/∂x², ...

(Longuet-Higgins 1957; Nayak 1971, eqs. (1)–(3); the paper's eq. (8) uses the same moments).

The spectrum is separable in the lay frame (x' along the lay, y' across it),
Φ(q') = m00 f₁(q'_x) f₂(q'_y), with each factor f a unit-mass even density whose second moment
⟨q²⟩ = m20/m00 (m02/m00) and whose bandwidth α = ⟨q⁴⟩/⟨q²⟩² = m00 m40/m20² (m00 m04/m02²),
eq. (11), are those prescribed:

* α ≥ 3: the generalised Gaussian f ∝ exp(−|q/c|ⁿ), n ≤ 2, with
  α(n) = Γ(5/n) Γ(1/n) / Γ(3/n)² and ⟨q²⟩ = c² Γ(3/n)/Γ(1/n);
* 1 < α < 3: f ∝ |q|ᵏ exp(−q²/(2s²)), k = (3 − α)/(α − 1) ≥ 0, with ⟨q²⟩ = (k + 1) s² and
  ⟨q⁴⟩ = (k + 1)(k + 3) s⁴ (Gaussian moments, Abramowitz & Stegun 6.1.1).

Then m11 = m31 = m13 = 0 and m22 = m20 m02/m00 in the lay frame.

The heights are Gaussian white noise filtered in Fourier space (e.g. Hu & Tonder 1992;
Persson et al. 2005, J. Phys.: Condens. Matter 17 R1, appendix): with N = nx·ny points and
Δq_x = 2π/(nx dx), Δq_y = 2π/(ny dy), the filter |H_k|² = N Φ(q_k) Δq_x Δq_y gives
E[z²] = Σ_k Φ(q_k) Δq_x Δq_y, the grid's quadrature of m00. The surface is periodic over
nx·dx × ny·dy; it reproduces the prescribed moments only where the grid resolves the spectrum
(Δq small against its width, the Nyquist wavenumber π/dx far in its tail): check with
:func:`grid_moments`.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import gammaln

from .surface import SpectralMoments

__all__ = ["synthetic_surface", "lay_frame_spectrum", "grid_moments", "window_moments", "dropout_mask"]


def _gg_alpha(n: float) -> float:
    """α of the generalised Gaussian exp(−|q/c|ⁿ): Γ(5/n)Γ(1/n)/Γ(3/n)²."""
    return math.exp(gammaln(5.0 / n) + gammaln(1.0 / n) - 2.0 * gammaln(3.0 / n))


def _density_1d(q, q2: float, alpha: float):
    """The unit-mass even density f(q) [L] with ⟨q²⟩ = q2 [L⁻²] and ⟨q⁴⟩/⟨q²⟩² = alpha."""
    q = np.abs(np.asarray(q, dtype=float))
    if alpha >= 3.0:
        n = 2.0 if alpha == 3.0 else brentq(lambda t: _gg_alpha(t) - alpha, 0.05, 2.0, xtol=1e-14)
        c = math.sqrt(q2 * math.exp(gammaln(1.0 / n) - gammaln(3.0 / n)))
        # ∫ exp(−|q/c|ⁿ) dq = 2 c Γ(1 + 1/n)
        return np.exp(-((q / c) ** n)) / (2.0 * c * math.exp(gammaln(1.0 + 1.0 / n)))
    k = (3.0 - alpha) / (alpha - 1.0)
    s = math.sqrt(q2 / (k + 1.0))
    # ∫ |q|^k exp(−q²/2s²) dq = s^{k+1} 2^{(k+1)/2} Γ((k+1)/2)
    norm = s ** (k + 1.0) * math.exp(0.5 * (k + 1.0) * math.log(2.0) + gammaln(0.5 * (k + 1.0)))
    return q**k * np.exp(-0.5 * (q / s) ** 2) / norm


def lay_frame_spectrum(moments: SpectralMoments, qx, qy, lay_angle_deg: float = 0.0):
    """Φ(q_x, q_y) [L⁴] of the separable spectrum with the five prescribed moments, in the map's
    frame whose x axis makes ``lay_angle_deg`` [deg] with the lay (counter-clockwise from the
    map's x axis to the lay). qx, qy: angular wavenumbers [rad/L], broadcast together."""
    if not math.isfinite(lay_angle_deg):
        raise ValueError(f"lay_angle_deg must be finite, got {lay_angle_deg!r}")
    t = math.radians(lay_angle_deg)
    qx, qy = np.broadcast_arrays(np.asarray(qx, dtype=float), np.asarray(qy, dtype=float))
    q_along = math.cos(t) * qx + math.sin(t) * qy
    q_across = -math.sin(t) * qx + math.cos(t) * qy
    m = moments
    return (
        m.m00
        * _density_1d(q_along, m.m20 / m.m00, m.alpha1)
        * _density_1d(q_across, m.m02 / m.m00, m.alpha2)
    )


def _grid_wavenumbers(shape: tuple[int, int], dx: float, dy: float):
    ny, nx = shape
    qx = 2.0 * np.pi * np.fft.fftfreq(nx, d=dx)
    qy = 2.0 * np.pi * np.fft.fftfreq(ny, d=dy)
    return qx[np.newaxis, :], qy[:, np.newaxis]


def _check_grid(shape, dx, dy):
    if len(shape) != 2 or any(int(n) != n or n < 4 for n in shape):
        raise ValueError(f"shape must be two integers >= 4 (ny, nx), got {shape!r}")
    for name, d in (("dx", dx), ("dy", dy)):
        if not (isinstance(d, (int, float)) and math.isfinite(d) and d > 0):
            raise ValueError(f"{name} must be a positive finite length, got {d!r}")


def grid_moments(
    moments: SpectralMoments, shape: tuple[int, int], dx: float, dy: float | None = None,
    lay_angle_deg: float = 0.0,
) -> dict[str, float]:
    """The expected moments of :func:`synthetic_surface` on this grid, in the lay frame: the
    quadrature Σ_k q^p q^q Φ(q_k) Δq_x Δq_y of the prescribed spectrum over the grid's
    wavenumbers (rotated into the lay frame). Equal to ``moments`` when the grid resolves Φ."""
    dy = dx if dy is None else dy
    _check_grid(shape, dx, dy)
    qx, qy = _grid_wavenumbers(shape, dx, dy)
    w = lay_frame_spectrum(moments, qx, qy, lay_angle_deg) * (2 * np.pi) ** 2 / (
        shape[1] * dx * shape[0] * dy
    )
    t = math.radians(lay_angle_deg)
    qa = math.cos(t) * qx + math.sin(t) * qy
    qc = -math.sin(t) * qx + math.cos(t) * qy
    return {
        "m00": float(w.sum()),
        "m20": float((qa**2 * w).sum()),
        "m02": float((qc**2 * w).sum()),
        "m40": float((qa**4 * w).sum()),
        "m04": float((qc**4 * w).sum()),
        "m22": float((qa**2 * qc**2 * w).sum()),
    }


def synthetic_surface(
    moments: SpectralMoments,
    shape: tuple[int, int],
    dx: float,
    dy: float | None = None,
    *,
    seed: int,
    lay_angle_deg: float = 0.0,
) -> np.ndarray:
    """A periodic Gaussian height map with the prescribed spectral moments.

    Parameters
    ----------
    moments : the five moments m00 [L²], m20, m02 [–], m40, m04 [L⁻²] in the lay frame
        (x' along the lay), angular wavenumbers (module docstring).
    shape : (ny, nx), the number of rows (y) and columns (x), each >= 4.
    dx, dy : sampling intervals [L] along the map's x and y (dy defaults to dx).
    seed : seed of numpy's default generator (PCG64); equal seeds give equal maps.
    lay_angle_deg : the angle [deg] from the map's x axis to the lay, counter-clockwise.

    Returns
    -------
    z : float array of shape (ny, nx) [L]; z[i, j] is the height at x = j·dx, y = i·dy.

    The q = 0 Fourier term is set to zero, so z has zero mean exactly (:func:`grid_moments`
    keeps that term, Φ(0)Δq_xΔq_y, negligible on a grid that resolves Φ). On the Nyquist
    rows/columns the filter uses the mean of Φ(q) and Φ(−q) folded onto the grid, so that it is
    Hermitian-symmetric and z is real without discarding an imaginary part.
    """
    if not isinstance(moments, SpectralMoments):
        raise ValueError(f"moments must be a SpectralMoments, got {type(moments).__name__}")
    dy = dx if dy is None else dy
    _check_grid(shape, dx, dy)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"seed must be an integer, got {seed!r}")
    ny, nx = int(shape[0]), int(shape[1])
    qx, qy = _grid_wavenumbers((ny, nx), dx, dy)
    dqx, dqy = 2.0 * np.pi / (nx * dx), 2.0 * np.pi / (ny * dy)
    phi = lay_frame_spectrum(moments, qx, qy, lay_angle_deg)
    phi = 0.5 * (phi + np.roll(phi[::-1, ::-1], 1, axis=(0, 1)))  # Φ at the grid's −k
    filt = np.sqrt(nx * ny * phi * dqx * dqy)
    filt[0, 0] = 0.0
    noise = np.random.default_rng(seed).standard_normal((ny, nx))
    return np.fft.ifft2(filt * np.fft.fft2(noise)).real


def _spectral_derivative(Z, qx, qy, p: int, q: int) -> np.ndarray:
    """∂^p_x ∂^q_y of the trigonometric interpolant with Fourier coefficients Z (numpy's FFT
    layout; the Nyquist wavenumbers set to 0, where the real derivative is not defined)."""
    return np.fft.ifft2((1j * qx) ** p * (1j * qy) ** q * Z).real


def window_moments(parent, dx: float, dy: float | None = None, *, rows: slice, cols: slice, mask=None) -> dict:
    """The exact moments of a window ``parent[rows, cols]`` of a periodic map (e.g.
    :func:`synthetic_surface`), the reference for estimators of a measured window's moments.

    The derivative fields z_x … z_yy of the whole periodic map come from its Fourier series
    (exact for its trigonometric interpolant) and are cropped to the window; then, over the
    window's points (those where ``mask``, a boolean array of the window's shape, is True):
    m00 = the mean square of the heights about their least-squares plane (Sq²); the lay angle θ
    from the slopes' covariances (m11 = 0 in the lay frame, m20 ≤ m02; Longuet-Higgins 1957);
    and the nine moments in the lay frame as covariances, about their window means, of the
    rotated fields z_a = c z_x + s z_y, z_aa = c² z_xx + 2cs z_xy + s² z_yy, … (angular
    wavenumbers, L = the unit of dx). Returns the nine moments and ``lay_angle_deg`` (in (−90, 90])."""
    dy = dx if dy is None else dy
    z = np.asarray(parent, dtype=float)
    _check_grid(z.shape, dx, dy)
    qx, qy = _grid_wavenumbers(z.shape, dx, dy)
    qx, qy = qx.copy(), qy.copy()
    if z.shape[1] % 2 == 0:
        qx[0, z.shape[1] // 2] = 0.0
    if z.shape[0] % 2 == 0:
        qy[z.shape[0] // 2, 0] = 0.0
    Z = np.fft.fft2(z)
    d = {k: _spectral_derivative(Z, qx, qy, p, q)[rows, cols]
         for k, (p, q) in {"zx": (1, 0), "zy": (0, 1), "zxx": (2, 0), "zxy": (1, 1), "zyy": (0, 2)}.items()}
    h = z[rows, cols]
    keep = np.ones(h.shape, dtype=bool) if mask is None else np.asarray(mask, dtype=bool)
    ny, nx = h.shape
    y, x = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    A = np.column_stack([np.ones(int(keep.sum())), x[keep], y[keep]])
    coef, *_ = np.linalg.lstsq(A, h[keep], rcond=None)
    m00 = float(np.mean((h[keep] - A @ coef) ** 2))
    g = {k: v[keep] - v[keep].mean() for k, v in d.items()}
    m20, m02, m11 = (float(np.mean(a * b)) for a, b in ((g["zx"], g["zx"]), (g["zy"], g["zy"]), (g["zx"], g["zy"])))
    theta = 0.5 * math.atan2(2.0 * m11, m20 - m02) + 0.5 * math.pi  # perpendicular to the steepest
    theta = theta - math.pi if theta > 0.5 * math.pi else theta
    c, s = math.cos(theta), math.sin(theta)
    za, zc = c * g["zx"] + s * g["zy"], -s * g["zx"] + c * g["zy"]
    zaa = c * c * g["zxx"] + 2 * c * s * g["zxy"] + s * s * g["zyy"]
    zcc = s * s * g["zxx"] - 2 * c * s * g["zxy"] + c * c * g["zyy"]
    zac = -c * s * g["zxx"] + (c * c - s * s) * g["zxy"] + c * s * g["zyy"]
    pairs = {"m20": (za, za), "m02": (zc, zc), "m11": (za, zc), "m40": (zaa, zaa), "m04": (zcc, zcc),
             "m22": (zac, zac), "m31": (zaa, zac), "m13": (zcc, zac)}
    return {"m00": m00, **{k: float(np.mean(a * b)) for k, (a, b) in pairs.items()},
            "lay_angle_deg": math.degrees(theta)}


def dropout_mask(shape: tuple[int, int], *, seed: int, patches: int = 40, radius=(2.0, 8.0),
                 single: float = 0.01) -> np.ndarray:
    """A boolean mask (True = not measured) of optical-instrument-like dropouts: ``patches`` discs
    of radii uniform in ``radius`` [samples] at random centres, and a fraction ``single`` of
    isolated points; to test estimators on maps with missing data (set them to NaN)."""
    _check_grid(shape, 1.0, 1.0)
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:shape[0], 0:shape[1]]
    hole = rng.random(shape) < single
    for _ in range(int(patches)):
        cy, cx, r = rng.integers(0, shape[0]), rng.integers(0, shape[1]), rng.uniform(*radius)
        hole |= (yy - cy) ** 2 + (xx - cx) ** 2 < r * r
    return hole
