"""Material data of the asperity model (sections 5–6 of Buczkowski & Kleiber 2009): the
effective modulus E* (42), the yield coefficient K_Y (63)–(64), Tabor's hardness (68) and
:class:`AsperityMaterial` (E*, Y, H, K_Y, c_h, ω_p/ω_c, K_v). Why K_v defaults to K_Y Y/H
(load continuous at first yield): :mod:`roughcontact.asperity.laws`, "Continuity".
Pure Python, no I/O; stresses in one consistent unit."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..validation import positive

__all__ = [
    "TABOR_RATIO",
    "AsperityMaterial",
    "effective_modulus",
    "yield_coefficient_from_poisson",
    "paper_K_v",
]

#: Tabor's Y/H, eq. (68): Y = 0.354 H.
TABOR_RATIO = 0.354


def effective_modulus(E1: float, nu1: float, E2: float = math.inf, nu2: float = 0.0) -> float:
    """The effective (harmonic, contact) modulus E*, eq. (42): 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2
    [the unit of E1, E2]. The default second body is rigid (E2 = ∞): E* = E1/(1 − ν1²), the
    plane-strain modulus; two equal bodies give half of it. ValueError for E ≤ 0 or ν ∉ (−1, 0.5]."""
    compliance = 0.0
    for name, E, nu in (("1", E1, nu1), ("2", E2, nu2)):
        E, nu = float(E), float(nu)
        if not (E > 0.0) or math.isnan(E):
            raise ValueError(f"E{name} must be positive, got {E!r}")
        if not (-1.0 < nu <= 0.5):
            raise ValueError(f"nu{name} must lie in (-1, 0.5], got {nu!r}")
        if math.isfinite(E):
            compliance += (1.0 - nu * nu) / E  # eq. (42)
    return 1.0 / compliance


def yield_coefficient_from_poisson(nu):
    """Maximum-contact-pressure yield coefficient K_Y = 1.282 + 1.158ν, eq. (64) (CEB [25]).

    The paper's figures use the fixed value K_Y = 1.62, i.e. (64) at ν ≈ 0.2918."""
    return 1.282 + 1.158 * np.asarray(nu, dtype=float)  # eq. (64)


def paper_K_v(nu):
    """The paper's K_v = 0.454 + 0.41ν (von Mises, [60]; the unnumbered equation after (76)).

    Gives a continuous load at ω_c only if K_v H = K_Y Y (see :class:`AsperityMaterial`)."""
    return 0.454 + 0.41 * np.asarray(nu, dtype=float)  # eq. after (76)


@dataclass(frozen=True)
class AsperityMaterial:
    """Material data of the elasto-plastic asperity model (sections 5–6).

    E_star : effective (composite) elastic modulus E* [stress].
    Y : yield strength [stress].
    H : indentation hardness [stress]; ``None`` → Tabor's H = Y/0.354, eq. (68).
    yield_coefficient : K_Y in p_max = K_Y Y at first yield, eq. (63) (the paper's "K";
        1.62 in all figures; :func:`yield_coefficient_from_poisson` gives (64)).
    c_h : hardness coefficient of the fully plastic mean pressure c_h H, eq. (66); 0.967.
    wp_over_wc : ω_p/ω_c (> 1), end of the elasto-plastic transition; 45.
    K_v : coefficient of the mean pressure (2/3) K_v H at ω_c in (75). ``None`` → the value
        that makes the load continuous at ω_c, K_v = K_Y Y/H (= 0.354·1.62 = 0.57348 with
        Tabor's H). Pass ``paper_K_v(nu)`` (0.454 + 0.41ν) for the paper's choice, which makes
        the load jump by :attr:`load_jump_at_yield` (+0.614 % for ν = 0.3).

    All values must be finite and positive (ValueError otherwise). After construction H and
    K_v hold the resolved numbers.
    """

    E_star: float
    Y: float
    H: float | None = None
    yield_coefficient: float = 1.62
    c_h: float = 0.967
    wp_over_wc: float = 45.0
    K_v: float | None = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "E_star", positive("E_star", self.E_star))
        set_(self, "Y", positive("Y (yield strength)", self.Y))
        if self.H is None:
            set_(self, "H", positive("H = Y/0.354 (hardness, eq. 68)", self.Y / TABOR_RATIO))  # eq. (68)
        else:
            set_(self, "H", positive("H (hardness)", self.H))
        set_(self, "yield_coefficient", positive("yield_coefficient", self.yield_coefficient))
        ratio = self.yield_pressure / self.E_star
        if not (math.isfinite(ratio) and 0.0 < ratio * ratio < math.inf):
            # ω_c of (65) scales with (K_Y Y/E*)²; a tiny ψ gives a huge Y (yield-from-psi)
            raise ValueError(
                f"K_Y Y/E* = {ratio!r} (K_Y Y = {self.yield_pressure!r}, E* = {self.E_star!r}): its "
                "square in the critical interference (65) under- or overflows a double; the "
                "plasticity index or yield strength is out of range"
            )
        set_(self, "c_h", positive("c_h", self.c_h))
        r = positive("wp_over_wc", self.wp_over_wc)
        if not r > 1.0:
            raise ValueError(f"wp_over_wc = ω_p/ω_c must exceed 1, got {r!r}")
        set_(self, "wp_over_wc", r)
        if self.K_v is None:
            set_(self, "K_v", self.continuous_K_v)
        else:
            set_(self, "K_v", positive("K_v", self.K_v))

    @classmethod
    def with_paper_K_v(cls, E_star: float, Y: float, poisson: float, **kwargs) -> "AsperityMaterial":
        """The paper's choice K_v = 0.454 + 0.41ν (load discontinuous at ω_c unless ν ≈ 0.2914)."""
        nu = float(poisson)
        if not (-1.0 < nu < 0.5):
            raise ValueError(f"Poisson's ratio must lie in (-1, 0.5), got {nu!r}")
        return cls(E_star, Y, K_v=float(paper_K_v(nu)), **kwargs)

    @property
    def yield_pressure(self) -> float:
        """K_Y Y: the Hertz maximum pressure at first yield, eq. (63) [stress]."""
        return self.yield_coefficient * self.Y  # eq. (63)

    @property
    def continuous_K_v(self) -> float:
        """K_v = K_Y Y/H: the value for which the load is continuous at ω_c (elastic mean
        pressure (2/3) K_Y Y = elasto-plastic (2/3) K_v H, eqs. (62)–(63), (75))."""
        return self.yield_coefficient * self.Y / self.H

    @property
    def load_jump_at_yield(self) -> float:
        """Relative jump W(ω_c⁺)/W(ω_c⁻) − 1 = K_v H/(K_Y Y) − 1 of the load at ω_c."""
        return self.K_v * self.H / self.yield_pressure - 1.0

    @property
    def has_load_jump(self) -> bool:
        """Whether the load jumps at ω_c (|load_jump_at_yield| above rounding, 1e-12)."""
        return abs(self.load_jump_at_yield) > 1e-12

    @property
    def stiffness_ratio_at_yield(self) -> float:
        """dW/dω(ω_c⁺)/dW/dω(ω_c⁻) = [(2/3) K_v H + H(c_h − (2/3)K_v)/ln r]/(K_Y Y), r = ω_p/ω_c
        (independent of the asperity's shape and curvature)."""
        H, r = self.H, self.wp_over_wc
        return ((2.0 / 3.0) * self.K_v * H + H * (self.c_h - (2.0 / 3.0) * self.K_v) / math.log(r)) / (
            self.yield_pressure
        )

    @property
    def stiffness_ratio_at_full_plasticity(self) -> float:
        """dW/dω(ω_p⁺)/dW/dω(ω_p⁻) = 1/(1 + (1 − (2/3) K_v/c_h)/ln r), r = ω_p/ω_c."""
        return 1.0 / (1.0 + (1.0 - (2.0 / 3.0) * self.K_v / self.c_h) / math.log(self.wp_over_wc))
