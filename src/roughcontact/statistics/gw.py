"""McCool's equivalent Greenwood–Williamson model of an anisotropic surface.

McCool, J.I. (1986) "Comparison of models for the contact of rough surfaces",
Wear 107:37–60: the anisotropic surface is replaced by an isotropic one with the geometric
means m2 = √(m20 m02), m4 = √(m40 m04); summits are spheres of one radius R with
Gaussian heights (std σs) about a summit mean plane ys above the surface mean plane.
These are the "GW" columns of the paper's Tables 1–2 (reference [48] there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .surface import SpectralMoments

__all__ = ["EquivalentGW"]


@dataclass(frozen=True)
class EquivalentGW:
    """Parameters of the equivalent isotropic GW surface (McCool 1986, lengths in L)."""

    surface: SpectralMoments

    @property
    def m2(self) -> float:
        return math.sqrt(self.surface.m20 * self.surface.m02)

    @property
    def m4(self) -> float:
        return math.sqrt(self.surface.m40 * self.surface.m04)

    @property
    def alpha(self) -> float:
        """Bandwidth α = m0 m4/m2² of the equivalent surface."""
        return self.surface.m00 * self.m4 / self.m2**2

    @property
    def summit_density(self) -> float:
        """η = m4/(6π√3 m2) [1/L²] (Nayak 1971 for isotropic surfaces)."""
        return self.m4 / (6.0 * math.pi * math.sqrt(3.0) * self.m2)

    @property
    def summit_radius(self) -> float:
        """R = 0.375 √(π/m4) [L], the mean summit radius (McCool 1986)."""
        return 0.375 * math.sqrt(math.pi / self.m4)

    @property
    def summit_height_std(self) -> float:
        """σs = √(1 − 0.8968/α) √m0 [L] (McCool 1986)."""
        if self.alpha <= 0.8968:
            raise ValueError(f"equivalent GW needs alpha > 0.8968, got {self.alpha:.6g}")
        return math.sqrt(1.0 - 0.8968 / self.alpha) * math.sqrt(self.surface.m00)

    @property
    def summit_mean_height(self) -> float:
        """ys = 4 √(m0/(π α)) [L], summit mean plane above the surface mean plane."""
        return 4.0 * math.sqrt(self.surface.m00 / (math.pi * self.alpha))

    def standardised_separation(self, s):
        """d = (h − ys)/σs with h = s √m0."""
        s = np.asarray(s, dtype=float)
        return (s * math.sqrt(self.surface.m00) - self.summit_mean_height) / self.summit_height_std

    def per_unit_area(self, moments_at_minus_d):
        """A/A0, W/(A0 E*), K/(A0 E*) from F_ν(d) = J_ν(−d) given as columns (ν = 1/2, 1, 3/2).

        GW (1966): A/A0 = π η R σs F1, W/A0 = (4/3) η E* √R σs^{3/2} F_{3/2},
        K/A0 = −d(W/A0)/dh = 2 η E* √R σs^{1/2} F_{1/2}."""
        F = np.asarray(moments_at_minus_d, dtype=float)
        eta, R, sig = self.summit_density, self.summit_radius, self.summit_height_std
        area = math.pi * eta * R * sig * F[:, 1]
        load = 4.0 / 3.0 * eta * math.sqrt(R) * sig**1.5 * F[:, 2]
        stiffness = 2.0 * eta * math.sqrt(R) * math.sqrt(sig) * F[:, 0]
        return area, load, stiffness
