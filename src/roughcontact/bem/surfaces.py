"""Periodic Gaussian surfaces with exactly five prescribed spectral moments, for the BEM.

The spectrum is a band-limited power law, elliptically stretched (issue 21): on the lattice of
integer wave vectors k = (k_x, k_y) of a periodic L_x × L_y cell, the physical wave vector is
q = 2π(k_x/L_x, k_y/L_y) and the per-mode variance is

    ⟨z_k²⟩ ∝ |k|^(−2(1+H)) w(|k|),   w = ramp(|k| − k_low + ½) · ramp(k_high + ½ − |k|),

with ramp(t) = min(max(t, 0), 1) (one lattice unit wide, so that the moments vary continuously
with the cut-offs) and Hurst exponent H (0.8: Persson et al. 2005, J. Phys.: Condens. Matter 17
R1, section 2). The spectrum is isotropic in k and stretched in q by the cell's aspect L_x/L_y.

Each mode has a deterministic amplitude c_k and a random phase φ_k (the sum of the paper's
Appendix A, z = Σ c_k cos(q_k·x + φ_k)), so every realisation has the same moments
m_pq = ½ Σ c_k² q_x^p q_y^q exactly (Appendix A), to round-off, whatever the seed. Then:

* α = m00 m40/m20² = m00 m04/m02² depends on the k-lattice only (the square lattice is symmetric
  in k_x ↔ k_y, so α1 = α2 exactly): k_low is solved for the target α (k_high fixed);
* the scale of c_k gives m00, L_x gives m20, L_y gives m02; m40 and m04 follow from α.

So the five target moments are met exactly only when α1 = α2 (the paper's Table 1 and 2 surfaces
have it); other moments raise ``ValueError``. m22 = √(m40 m04)/3 up to the lattice's departure
from isotropy (the model of the paper neglects m22; statistics.summits keeps it).

The surface is a trigonometric polynomial fixed by (moments, H, k_high, seed): sampled on an
n × n grid (n > 2 k_high + 2, every mode below Nyquist) it is the same surface at every n, with
n/k_high pixels per shortest wavelength along both axes (pixels of dx = L_x/n by dy = L_y/n).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..statistics.surface import SpectralMoments
from ..validation import positive
from ..limits import describe

__all__ = ["BandLimitedSurface"]

#: relative mismatch of α1 and α2 tolerated (the paper's surfaces have α1 = α2 to their digits)
ALPHA_MATCH_RTOL = 1e-9


def _lattice(k_high: float):
    """(k_x, k_y) of the half-plane of modes with |k| < k_high + ½ (k_y > 0, or k_y = 0 and
    k_x > 0), in a fixed order (by k_y, then k_x) that does not depend on the grid."""
    K = int(math.ceil(k_high + 0.5))
    ky, kx = np.meshgrid(np.arange(0, K + 1), np.arange(-K, K + 1), indexing="ij")
    kx, ky = kx.ravel(), ky.ravel()
    keep = ((ky > 0) | ((ky == 0) & (kx > 0))) & (np.hypot(kx, ky) < k_high + 0.5)
    return kx[keep].astype(float), ky[keep].astype(float)


def _weights(kx, ky, k_low: float, k_high: float, hurst: float):
    """Per-mode variance up to a constant: |k|^(−2(1+H)) times the ramps at both cut-offs."""
    k = np.hypot(kx, ky)
    ramp = np.clip(k - k_low + 0.5, 0.0, 1.0) * np.clip(k_high + 0.5 - k, 0.0, 1.0)
    return ramp * k ** (-2.0 * (1.0 + hurst))


def _alpha(kx, ky, k_low, k_high, hurst) -> float:
    p = _weights(kx, ky, k_low, k_high, hurst)
    return float(p.sum() * (p * kx**4).sum() / (p * kx**2).sum() ** 2)


@dataclass(frozen=True)
class BandLimitedSurface:
    """A band-limited, elliptically stretched power-law spectrum with exactly the five moments.

    moments : the targets (lay frame, x along the grain) [L², –, –, L⁻², L⁻²];
    hurst : Hurst exponent H [–]; k_low, k_high : cut-offs in lattice units [–] (k_low solved);
    lengths : the periodic cell (L_x, L_y) [L]; kx, ky, amplitude : the half-plane modes and
    their amplitudes c_k [L] (z = Σ c_k cos(q_k·x + φ_k)).
    Build it with :meth:`design`.
    """

    moments: SpectralMoments
    hurst: float
    k_low: float
    k_high: float
    lengths: tuple[float, float]
    kx: np.ndarray
    ky: np.ndarray
    amplitude: np.ndarray

    @classmethod
    def design(cls, moments: SpectralMoments, *, hurst: float = 0.8, k_high: float = 32.0) -> "BandLimitedSurface":
        """The surface with the five ``moments``, Hurst exponent ``hurst`` (0 < H < 1) and the
        shortest wavelength L/k_high (k_high ≥ 4 lattice units). ValueError when α1 ≠ α2 or α is
        outside what the band [1, k_high − 1] can give."""
        if not isinstance(moments, SpectralMoments):
            raise TypeError(f"moments must be a SpectralMoments, got {type(moments).__name__}")
        hurst = positive("hurst", hurst)
        if not hurst < 1.0:
            raise ValueError(f"hurst must lie in (0, 1), got {describe(hurst)}")
        k_high = positive("k_high", k_high)
        if k_high < 4.0:
            raise ValueError(f"k_high must be >= 4 lattice units, got {describe(k_high)}")
        a1, a2 = moments.alpha1, moments.alpha2
        if abs(a1 - a2) > ALPHA_MATCH_RTOL * max(a1, a2):
            raise ValueError(
                f"an elliptically stretched isotropic spectrum has alpha1 = alpha2; these moments have "
                f"alpha1 = {a1:.10g}, alpha2 = {a2:.10g} (m00 m40/m20^2 and m00 m04/m02^2)")
        kx, ky = _lattice(k_high)
        lo, hi = 1.0, k_high - 1.0
        a_lo, a_hi = (_alpha(kx, ky, k, k_high, hurst) for k in (lo, hi))
        if not a_hi < a1 < a_lo:
            raise ValueError(f"alpha = {a1:.6g} is outside ({a_hi:.4g}, {a_lo:.4g}), the range of a band "
                             f"[k_low, {k_high:g}] with 1 <= k_low <= {hi:g} and H = {hurst:g}; change k_high")
        k_low = brentq(lambda k: _alpha(kx, ky, k, k_high, hurst) - a1, lo, hi, xtol=1e-14, rtol=1e-15)
        p = _weights(kx, ky, k_low, k_high, hurst)
        keep = p > 0.0
        kx, ky, p = kx[keep], ky[keep], p[keep]
        c2 = p * (moments.m00 / (0.5 * p.sum()))  # m00 = ½ Σ c_k²
        Lx = 2 * math.pi * math.sqrt(0.5 * (c2 * kx**2).sum() / moments.m20)
        Ly = 2 * math.pi * math.sqrt(0.5 * (c2 * ky**2).sum() / moments.m02)
        return cls(moments=moments, hurst=hurst, k_low=float(k_low), k_high=k_high, lengths=(Lx, Ly),
                   kx=kx, ky=ky, amplitude=np.sqrt(c2))

    @property
    def area(self) -> float:
        """The nominal area of the cell, A0 = L_x L_y [L²]."""
        return self.lengths[0] * self.lengths[1]

    def min_points(self) -> int:
        """The smallest grid n that holds every mode below Nyquist (n/2 > max |k|)."""
        return 2 * int(max(np.abs(self.kx).max(), self.ky.max())) + 2

    def spacing(self, n: int) -> tuple[float, float]:
        """(dx, dy) [L] of an n × n grid."""
        return self.lengths[0] / n, self.lengths[1] / n

    def pixels_per_shortest_wavelength(self, n: int) -> float:
        """n / k_high: the grid points per shortest wavelength, along x and along y."""
        return n / self.k_high

    def grid_moments(self) -> dict[str, float]:
        """m00, m20, m02, m40, m04, m22 (and m11 = 0) of every realisation: ½ Σ c_k² q_x^p q_y^q."""
        qx = 2 * math.pi * self.kx / self.lengths[0]
        qy = 2 * math.pi * self.ky / self.lengths[1]
        c2 = 0.5 * self.amplitude**2
        return {"m00": float(c2.sum()), "m20": float((c2 * qx**2).sum()), "m02": float((c2 * qy**2).sum()),
                "m11": float((c2 * qx * qy).sum()), "m40": float((c2 * qx**4).sum()),
                "m04": float((c2 * qy**4).sum()), "m22": float((c2 * qx**2 * qy**2).sum())}

    def phases(self, seed: int) -> np.ndarray:
        """The random phases φ_k ∈ [0, 2π) of realisation ``seed`` (numpy's PCG64), one per mode
        in the lattice's fixed order: the same surface on every grid."""
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise ValueError(f"seed must be a non-negative integer, got {describe(seed)}")
        return np.random.default_rng(int(seed)).uniform(0.0, 2 * math.pi, self.kx.size)

    def heights(self, n: int, seed: int) -> np.ndarray:
        """The realisation ``seed`` on an n × n grid: z[i, j] [L] at x = j·dx, y = i·dy, zero mean."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < self.min_points():
            raise ValueError(f"n must be an integer >= {self.min_points()} (every mode below Nyquist), got {describe(n)}")
        n = int(n)
        coef = 0.5 * self.amplitude * np.exp(1j * self.phases(seed)) * (n * n)
        F = np.zeros((n, n), dtype=complex)
        ix, iy = self.kx.astype(int), self.ky.astype(int)
        F[iy % n, ix % n] = coef
        F[(-iy) % n, (-ix) % n] = np.conj(coef)
        return np.fft.ifft2(F).real
