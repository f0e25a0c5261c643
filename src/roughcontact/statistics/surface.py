"""Spectral description of a strongly anisotropic rough surface (section 2 of the paper).

All quantities follow Bush, Gibson & Keogh (1979) as used by Buczkowski & Kleiber (2009),
with the corrections listed in docs/errata.md. Lengths are in one consistent unit L
(the paper uses µm): m00 [L²], m20, m02 [–], m40, m04 [L⁻²]; x runs along the grain.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["SpectralMoments", "ProfileDensities", "gaussian_bearing_area"]

_MOMENT_NAMES = ("m00", "m20", "m02", "m40", "m04")
#: derived statistics that must be finite and positive for the moments to be usable
_DERIVED = ("summit_density", "mean_summit_curvature", "summit_height_std", "summit_mean_height")


@dataclass(frozen=True)
class ProfileDensities:
    """Nayak's profile densities (12), per unit length [1/L], along (x) and across (y) the grain."""

    zero_crossings_x: float
    zero_crossings_y: float
    extrema_x: float
    extrema_y: float


@dataclass(frozen=True)
class SpectralMoments:
    """The five spectral moments of a strongly anisotropic surface, eq. (8).

    Validated on construction: every moment finite and positive, and
    μ = 1 − 1/α1 − 1/α2 > 0 (eq. 10; the covariance matrix (8) is positive definite
    only then). A violation raises ``ValueError`` naming the condition and the values.
    """

    m00: float
    m20: float
    m02: float
    m40: float
    m04: float

    def __post_init__(self) -> None:
        for name in _MOMENT_NAMES:
            value = getattr(self, name)
            try:
                fvalue = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"{name} must be a real number, got {value!r}") from None
            if not math.isfinite(fvalue):
                raise ValueError(f"{name} must be finite, got {fvalue!r}")
            if fvalue <= 0.0:
                raise ValueError(f"{name} must be positive, got {fvalue!r}")
            object.__setattr__(self, name, fvalue)
        self._check_representable(("alpha1", "alpha2", "beta1", "beta2"))
        if not self.mu > 0.0:
            raise ValueError(
                "the moments violate mu = 1 - 1/alpha1 - 1/alpha2 > 0 (covariance (8) not "
                f"positive definite): alpha1 = m00*m40/m20^2 = {self.alpha1:.6g}, "
                f"alpha2 = m00*m04/m02^2 = {self.alpha2:.6g}, mu = {self.mu:.6g}"
            )
        self._check_representable(_DERIVED)

    def _check_representable(self, names) -> None:
        """ValueError unless every derived statistic in ``names`` is a finite positive double:
        moments like 1e-300 or 1e300 are valid numbers whose products (m20² in α1, m40 m04 in
        D_sum) under- or overflow, which ended in ZeroDivisionError / OverflowError."""
        for name in names:
            try:
                value = getattr(self, name)
            except (ZeroDivisionError, OverflowError):
                value = math.nan
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(
                    f"{name} of these moments is not a finite positive double ({value!r}): the "
                    "moments under- or overflow in double precision; express them in another "
                    "length unit"
                )

    # -- bandwidth parameters, eqs. (10)-(11) ---------------------------------------------
    @property
    def alpha1(self) -> float:
        """Bandwidth parameter along the grain, α1 = m00 m40 / m20² (11)."""
        return self.m00 * self.m40 / self.m20**2

    @property
    def alpha2(self) -> float:
        """Bandwidth parameter across the grain, α2 = m00 m04 / m02² (11)."""
        return self.m00 * self.m04 / self.m02**2

    @property
    def beta1(self) -> float:
        """β1 = 1/α1 (11)."""
        return self.m20**2 / (self.m00 * self.m40)

    @property
    def beta2(self) -> float:
        """β2 = 1/α2 (11)."""
        return self.m02**2 / (self.m00 * self.m04)

    @property
    def mu(self) -> float:
        """μ = 1 − β1 − β2 (10); the conditional variance of ω1 given the curvatures is 1."""
        return 1.0 - self.beta1 - self.beta2

    @property
    def height_std(self) -> float:
        """Rq = √m00 [L]."""
        return math.sqrt(self.m00)

    # -- summit statistics -----------------------------------------------------------------
    @property
    def summit_density(self) -> float:
        """D_sum = (2π)⁻² (m40 m04/(m20 m02))^{1/2} [1/L²], eq. (17) with the exponent corrected
        from 2 to 1/2 (docs/errata.md, E3)."""
        return math.sqrt(self.m40 * self.m04 / (self.m20 * self.m02)) / (4.0 * math.pi**2)

    @property
    def mean_summit_curvature(self) -> float:
        """κ̄_m = √(π/8)(√m04 + √m40) [1/L], eq. (70): the mean of (|ξ4| + |ξ6|)/2 over summits."""
        return math.sqrt(math.pi / 8.0) * (math.sqrt(self.m04) + math.sqrt(self.m40))

    @property
    def summit_height_std(self) -> float:
        """σ_s = √(m00 [1 − (π/2 − 1)(β1 + β2)]) [L], eqs. (71)–(72) corrected (errata E6).

        Var(ξ1) over summits = m00 μ (1 + (β1 + β2) Var(Rayleigh)/μ), Var(Rayleigh) = 2 − π/2.
        """
        return math.sqrt(self.m00 * (1.0 - (math.pi / 2.0 - 1.0) * (self.beta1 + self.beta2)))

    @property
    def summit_mean_height(self) -> float:
        """δ = (π m00/2)^{1/2}(√β1 + √β2) [L], eq. (73) with the exponent corrected (errata E7):
        the mean summit height above the surface mean plane."""
        return math.sqrt(math.pi * self.m00 / 2.0) * (math.sqrt(self.beta1) + math.sqrt(self.beta2))

    # -- Nayak's profile densities, eq. (12) ----------------------------------------------
    def profile_densities(self) -> ProfileDensities:
        """Zero-crossing and extremum densities of profiles along/across the grain [1/L], eq. (12)
        with the extremum densities corrected to (m40/m20)^{1/2}/π, (m04/m02)^{1/2}/π (errata E5)."""
        return ProfileDensities(
            zero_crossings_x=math.sqrt(self.m20 / self.m00) / math.pi,
            zero_crossings_y=math.sqrt(self.m02 / self.m00) / math.pi,
            extrema_x=math.sqrt(self.m40 / self.m20) / math.pi,
            extrema_y=math.sqrt(self.m04 / self.m02) / math.pi,
        )

    @classmethod
    def from_profile_densities(cls, m00: float, densities: ProfileDensities) -> "SpectralMoments":
        """Invert (12): the moments from the height variance m00 [L²] and the four profile
        densities [1/L]."""
        m20 = m00 * (math.pi * densities.zero_crossings_x) ** 2
        m02 = m00 * (math.pi * densities.zero_crossings_y) ** 2
        m40 = m20 * (math.pi * densities.extrema_x) ** 2
        m04 = m02 * (math.pi * densities.extrema_y) ** 2
        return cls(m00, m20, m02, m40, m04)

    @classmethod
    def from_heights(cls, z, dx, dy=None, **options) -> "SpectralMoments":
        """The moments in the lay frame measured on a height map z[i, j] at x = j·dx, y = i·dy
        [L] (:func:`roughcontact.statistics.measure.measure_heights`, which also reports the lay
        angle, m11, m22 and the estimator; options: estimator, window, detrend, lay_angle_deg)."""
        from .measure import measure_heights

        return measure_heights(z, dx, dy, **options).moments

    @classmethod
    def from_profiles(cls, along, across, dx, dy=None, **options) -> "SpectralMoments":
        """The moments from profiles along the lay (interval dx [L]) and across it (dy)
        (:func:`roughcontact.statistics.measure.measure_profiles`)."""
        from .measure import measure_profiles

        return measure_profiles(along, across, dx, dy, **options)

    def combined_with(self, other: "SpectralMoments") -> "SpectralMoments":
        """Two rough surfaces in contact as one rough surface on a flat: the sum of the
        heights' moments (independent surfaces, same lay frame; Greenwood & Tripp 1970,
        O'Callaghan & Cameron 1976, McCool 1986 section 2)."""
        if not isinstance(other, SpectralMoments):
            raise ValueError(f"other must be a SpectralMoments, got {type(other).__name__}")
        return SpectralMoments(*(getattr(self, n) + getattr(other, n) for n in _MOMENT_NAMES))

    # -- conventions for the separation -----------------------------------------------------
    def l_from_s(self, s):
        """The integration variable l = s/√μ of (23), from s = h/√m00."""
        return np.asarray(s, dtype=float) / math.sqrt(self.mu)

    def s_from_h(self, h):
        """s = h/√m00 (23), from the separation h [L] of the flat from the surface mean plane."""
        return np.asarray(h, dtype=float) / math.sqrt(self.m00)

    # -- the summit pdf ----------------------------------------------------------------------
    def summit_pdf(self, omega1, omega4, omega6):
        """p_sum(ω1, ω4, ω6), eq. (18) normalised over ω1 ∈ ℝ, ω4, ω6 > 0, with the cross terms
        of X paired as the inverse of (8) gives (errata E1, E4):
        X = (ω1 − √β1 ω4 − √β2 ω6)² + μ(ω4² + ω6²). Zero for ω4 ≤ 0 or ω6 ≤ 0."""
        w1, w4, w6 = (np.asarray(w, dtype=float) for w in (omega1, omega4, omega6))
        mu = self.mu
        X = (w1 - math.sqrt(self.beta1) * w4 - math.sqrt(self.beta2) * w6) ** 2 + mu * (
            w4**2 + w6**2
        )
        p = mu**2 / math.sqrt(2.0 * math.pi) * w4 * w6 * np.exp(-0.5 * X)
        return np.where((w4 > 0) & (w6 > 0), p, 0.0)

    def as_dict(self) -> dict[str, float]:
        """The five moments, keyed by the paper's names."""
        return {name: getattr(self, name) for name in _MOMENT_NAMES}

    def summary(self) -> dict[str, float]:
        """Derived statistics, keyed as the CLI prints them."""
        return {
            **self.as_dict(),
            "alpha1": self.alpha1,
            "alpha2": self.alpha2,
            "beta1": self.beta1,
            "beta2": self.beta2,
            "mu": self.mu,
            "summit_density": self.summit_density,
            "mean_summit_curvature": self.mean_summit_curvature,
            "summit_height_std": self.summit_height_std,
            "summit_mean_height": self.summit_mean_height,
        }


def gaussian_bearing_area(s):
    """A_B(s) = ½ erfc(s/√2), eq. (25): the fraction of a Gaussian surface above h = s√m00."""
    from scipy.special import ndtr

    return ndtr(-np.asarray(s, dtype=float))
