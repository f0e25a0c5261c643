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
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..contact.at_pressure import contact_at_pressure
from ..statistics.surface import SpectralMoments

__all__ = ["ModelAtPressures", "model_at_pressures", "ladder_stiffness", "kappa", "seed_mean",
           "holding_ranges", "HoldingRange"]


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
    differences over the (non-uniform) gaps, one-sided at the ends. ln p is nearly linear in ḡ
    (Persson 2007, PRL 99, 125502), so this is accurate to a few % for ladders of factor ≤ 2.5."""
    p = np.asarray(pressure, dtype=float)
    g = np.asarray(mean_gap, dtype=float)
    if p.shape != g.shape or p.ndim != 1 or p.size < 3:
        raise ValueError("pressure and mean_gap must be 1-d arrays of the same length >= 3")
    if np.any(np.diff(g) >= 0):
        raise ValueError("the mean gap must fall as the pressure rises along the ladder")
    return -p * np.gradient(np.log(p), g)


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
    """The contiguous runs of the ladder where the model's area is within ``tolerance`` of the
    BEM's (ratio = A_model/A_BEM); empty if none."""
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
