"""The polar form of the summit integrals (docs/derivation.md), shared by every integrator.

With u = √μ ω4 = r cos θ and v = √μ ω6 = r sin θ (independent Rayleigh variables), and
t = ω1 − l, the summit pdf (18, corrected) becomes

    p_sum dω1 dω4 dω6 = cos θ sin θ · r³ e^{−r²/2} · φ(t + l − r g(θ)) dt dr dθ.

This module owns the θ-dependent geometry (g, c, curvature ratio) and the dimensional
prefactors of (52), (53), (55) and (24); it does no integration.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..asperity import ellipse
from ..statistics.surface import SpectralMoments

__all__ = ["PolarGeometry", "ElasticPrefactors"]


@dataclass(frozen=True)
class PolarGeometry:
    """θ-dependent factors of the integrand for one surface.

    ``g(θ)``: mean of ω1 per unit r; ``c(θ)`` [1/L]: κ_m = r c(θ) (eq. 44);
    ``curvature_ratio(θ)`` = |ξ4|/|ξ6| (its min with the inverse is λ² of eq. 27);
    ``theta_circle``: θ where the two curvatures are equal (λ = 1, the ellipse turns).
    """

    surface: SpectralMoments

    @property
    def theta_circle(self) -> float:
        return math.atan(math.sqrt(self.surface.m40 / self.surface.m04))

    @property
    def theta_peak(self) -> float:
        """θ where g(θ) is largest (tan θ = √(β2/β1)): for large separations the integrand
        concentrates there, in a peak of width ~1/l."""
        return math.atan2(math.sqrt(self.surface.beta2), math.sqrt(self.surface.beta1))

    def theta_at_lambda(self, lam: float) -> tuple[float, float]:
        """The two θ in (0, π/2) where λ = min(ρ, 1/ρ)^{1/2} equals ``lam`` ∈ (0, 1]
        (ρ = lam² on the far side of θ*, ρ = 1/lam² on the near side)."""
        k = math.sqrt(self.surface.m40 / self.surface.m04)  # ρ = k cot θ
        return math.atan(k * lam**2), math.atan(k / lam**2)

    def theta_breaks(self, hertz: str) -> list[float]:
        """θ where an integrand of this surface is not smooth or is peaked, for splitting the
        θ-integral: the axis turn θ*, the peak of g, and the kinks of the Hertz option."""
        breaks = [self.theta_circle, self.theta_peak]
        for lam in ellipse.kinks(hertz):
            if lam < 1.0:
                breaks.extend(self.theta_at_lambda(lam))
        return breaks

    def g(self, theta):
        s = self.surface
        return (math.sqrt(s.beta1) * np.cos(theta) + math.sqrt(s.beta2) * np.sin(theta)) / math.sqrt(
            s.mu
        )

    def c(self, theta):
        s = self.surface
        return 0.5 * (math.sqrt(s.m40) * np.cos(theta) + math.sqrt(s.m04) * np.sin(theta))

    def curvature_ratio(self, theta):
        s = self.surface
        return math.sqrt(s.m40) * np.cos(theta) / (math.sqrt(s.m04) * np.sin(theta))

    def lambda_squared(self, theta):
        """λ² = smaller/larger principal curvature ∈ (0, 1] (27); the ellipse turns at θ*."""
        rho = self.curvature_ratio(theta)
        return np.minimum(rho, 1.0 / rho)


@dataclass(frozen=True)
class ElasticPrefactors:
    """Dimensional prefactors multiplying the dimensionless (θ, r, t) integrals.

    area      π D_sum √(m00 μ)                      (52)  → A/A0 [–]
    load      (4/3) D_sum (m00 μ)^{3/4}              (53)  → W/(A0 E*) [–]
    stiffness 2 D_sum (m00 μ)^{1/4}                  (55)  → K/(A0 E*) [1/L]
    bearing   2π D_sum √(m00 μ) (m40 m04)^{−1/4}     (24)  → A_G [–]
    """

    area: float
    load: float
    stiffness: float
    bearing: float

    @classmethod
    def of(cls, surface: SpectralMoments) -> "ElasticPrefactors":
        D = surface.summit_density
        sig = surface.m00 * surface.mu  # variance of the summit height scale √(m00 μ)
        return cls(
            area=math.pi * D * math.sqrt(sig),
            load=4.0 / 3.0 * D * sig**0.75,
            stiffness=2.0 * D * sig**0.25,
            bearing=2.0 * math.pi * D * math.sqrt(sig) * (surface.m40 * surface.m04) ** -0.25,
        )
