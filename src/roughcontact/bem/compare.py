"""The statistical model at the BEM's loads, seed statistics, and where the model holds.

Compared at equal nominal pressure W/A0 (load control: the quantity that does not depend on how
the separation is defined):

* A/A0 — the model's (52) with exact Hertz functions at the separation that gives W/A0 (53)
  (contact.at_pressure) against the BEM's pixel count;
* the separation — the model's s = h/√m00 against the BEM's mean gap ḡ/√m00 (solver module);
* κ = A E* h′/W — the slope of the area-load relation, h′ = √(m20 + m02) the rms gradient
  (Bush, Gibson & Thomas 1975; Persson 2001; Hyun et al. 2004 find κ ≈ 2 in BEM for
  isotropic surfaces, against √(2π) of the asperity theories at vanishing load);
* K/A0 = −d(W/A0)/dh — the model's (55) against −dp/dḡ of the BEM's load ladder (second-order
  differences of ln p over ḡ, numpy.gradient).

The BEM's own discretisation error is estimated from the same surface on grids refined by a
constant factor (:func:`richardson`: Richardson extrapolation with the observed order, Roache
1998, "Verification and Validation in Computational Science and Engineering", ch. 5).
:func:`holding_ranges` also states where the model's gap and stiffness are within a tolerance
of the BEM's (``ratio`` = model/BEM of any quantity).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..asperity import AsperityMaterial
from ..asperity.laws import yield_strength_for_plasticity_index
from ..contact.at_pressure import contact_at_pressure
from ..statistics.surface import SpectralMoments

__all__ = ["ModelAtPressures", "model_at_pressures", "ladder_stiffness", "kappa", "seed_mean",
           "holding_ranges", "HoldingRange", "Extrapolation", "richardson", "plastic_material"]


@dataclass(frozen=True)
class ModelAtPressures:
    """The model (BGK, exact Hertz) at the pressures: A/A0 [–], s [–], K/A0 [unit of E*/L],
    and the model-validity warnings raised on the way (messages)."""

    pressure: np.ndarray
    area_fraction: np.ndarray
    s: np.ndarray
    stiffness: np.ndarray
    warnings: tuple[str, ...]


def model_at_pressures(moments: SpectralMoments, pressures, E_star: float) -> ModelAtPressures:
    """The model at W/A0 = ``pressures`` [unit of E*]; results outside the model's range of
    validity are kept (they are what is being compared) and their warnings recorded."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = contact_at_pressure(moments, pressures, E_star=E_star, model="bgk", hertz="exact", validity="warn")
    return ModelAtPressures(pressure=np.asarray(r.pressure_target), area_fraction=np.asarray(r.area_fraction),
                            s=np.asarray(r.s), stiffness=np.asarray(r.stiffness), warnings=r.warnings)


def ladder_stiffness(pressure, mean_gap) -> np.ndarray:
    """K/A0 = −dp/dḡ [unit of p per unit of ḡ] along a load ladder: −p · d ln p/dḡ by second-order
    differences over the (non-uniform) gaps, second-order one-sided at the ends (numpy.gradient,
    edge_order=2). ln p is nearly linear in ḡ (Persson 2007, PRL 99, 125502), so this is accurate
    to a few % for ladders of factor ≤ 2.5 (the ends less so than the interior)."""
    p = np.asarray(pressure, dtype=float)
    g = np.asarray(mean_gap, dtype=float)
    if p.shape != g.shape or p.ndim != 1 or p.size < 3:
        raise ValueError("pressure and mean_gap must be 1-d arrays of the same length >= 3")
    if np.any(np.diff(g) >= 0):
        raise ValueError("the mean gap must fall as the pressure rises along the ladder")
    return -p * np.gradient(np.log(p), g, edge_order=2)


def plastic_material(moments: SpectralMoments, E_star: float, psi: float, yield_coefficient: float = 1.62
                     ) -> AsperityMaterial:
    """The material whose plasticity index (asperity.laws.plasticity_index) on ``moments`` is ψ:
    Y from ψ at K_Y = ``yield_coefficient`` (the closure of Figs 5–8), Tabor's H = Y/0.354 (68),
    the paper's c_h = 0.967 and ω_p/ω_c = 45. The BEM's cap for it is c_h H, the mean pressure
    (66) of a fully plastic contact (paper.bem_plastic)."""
    Y = yield_strength_for_plasticity_index(psi, moments, E_star, yield_coefficient)
    return AsperityMaterial(E_star, Y, yield_coefficient=yield_coefficient)


def kappa(area_fraction, pressure, E_star: float, moments: SpectralMoments):
    """κ = (A/A0) E* h′/(W/A0) [–], h′ = √(m20 + m02) the rms gradient of the surface."""
    h_prime = math.sqrt(moments.m20 + moments.m02)
    return np.asarray(area_fraction, dtype=float) * E_star * h_prime / np.asarray(pressure, dtype=float)


def seed_mean(values, axis: int = 0):
    """(mean, standard error of the mean) over realisations along ``axis`` (sem = 0 for one)."""
    v = np.asarray(values, dtype=float)
    n = v.shape[axis]
    sem = v.std(axis=axis, ddof=1) / math.sqrt(n) if n > 1 else np.zeros_like(v.mean(axis=axis))
    return v.mean(axis=axis), sem


@dataclass(frozen=True)
class HoldingRange:
    """A contiguous run of ladder pressures at which |A_model/A_BEM − 1| ≤ tolerance.

    p_low, p_high : its first and last pressure [unit of E*]; area_low, area_high : the BEM's
    A/A0 there [–]; worst : the largest |ratio − 1| inside [–]."""

    tolerance: float
    p_low: float
    p_high: float
    area_low: float
    area_high: float
    worst: float


def holding_ranges(pressure, ratio, bem_area, tolerance: float) -> list[HoldingRange]:
    """The contiguous runs of the ladder where the model is within ``tolerance`` of the BEM
    (ratio = model/BEM: A_model/A_BEM, or of the gap or stiffness; ``bem_area`` the BEM's A/A0
    there, to say where on the area scale the run lies); empty if none."""
    p, r, a = (np.asarray(x, dtype=float) for x in (pressure, ratio, bem_area))
    ok = np.abs(r - 1.0) <= tolerance
    out, i = [], 0
    while i < p.size:
        if ok[i]:
            j = i
            while j + 1 < p.size and ok[j + 1]:
                j += 1
            out.append(HoldingRange(tolerance, float(p[i]), float(p[j]), float(a[i]), float(a[j]),
                                    float(np.max(np.abs(r[i:j + 1] - 1.0)))))
            i = j + 1
        else:
            i += 1
    return out


@dataclass(frozen=True)
class Extrapolation:
    """The continuum estimate of a quantity from three grids refined by a constant factor r
    (arrays over the pressures, in the quantity's unit).

    value : the estimate — Richardson's where ``extrapolated``, else the finest grid's value;
    finest : the finest grid's value; order : the observed order p (nan where the three values
    are not monotone); extrapolated : where the convergence is monotone with p ≥ min_order;
    error : the finest grid's estimated relative discretisation error |finest − value|/|value|
    where extrapolated, else the last refinement's change |finest − medium|/|finest| (a bound
    that assumes nothing about the order)."""

    value: np.ndarray
    finest: np.ndarray
    order: np.ndarray
    extrapolated: np.ndarray
    error: np.ndarray


def richardson(coarse, medium, fine, ratio: float = 2.0, min_order: float = 0.5) -> Extrapolation:
    """Richardson extrapolation with the observed order of f on grids h, h/r, h/r² (Roache 1998,
    ch. 5; Celik et al. 2008, J. Fluids Eng. 130, 078001): p = ln((f1 − f2)/(f2 − f3))/ln r and f∞ = f3 + (f3 − f2)/(r^p − 1),
    element-wise over the pressures. Where f1 − f2 and f2 − f3 differ in sign (oscillatory or
    converged to round-off) or p < ``min_order`` (the correction would exceed the last change
    many times over), no extrapolation: the finest value, flagged."""
    f1, f2, f3 = (np.atleast_1d(np.asarray(x, dtype=float)) for x in (coarse, medium, fine))
    if not f1.shape == f2.shape == f3.shape:
        raise ValueError(f"the three grids' values must have one shape, got {f1.shape}, {f2.shape}, {f3.shape}")
    if not (np.all(np.isfinite(f1)) and np.all(np.isfinite(f2)) and np.all(np.isfinite(f3))):
        raise ValueError("the three grids' values must be finite")
    ratio, min_order = float(ratio), float(min_order)
    if not ratio > 1.0 or not min_order > 0.0:
        raise ValueError(f"ratio must exceed 1 and min_order be positive, got {ratio!r}, {min_order!r}")
    d12, d23 = f1 - f2, f2 - f3
    with np.errstate(divide="ignore", invalid="ignore"):
        order = np.where(d12 * d23 > 0, np.log(d12 / d23) / math.log(ratio), np.nan)
        ok = np.isfinite(order) & (order >= min_order)
        value = np.where(ok, f3 + (f3 - f2) / (ratio ** np.where(ok, order, 1.0) - 1.0), f3)
        error = np.where(ok, np.abs(f3 - value) / np.abs(value), np.abs(d23) / np.abs(f3))
    return Extrapolation(value=value, finest=f3, order=order, extrapolated=ok, error=error)
