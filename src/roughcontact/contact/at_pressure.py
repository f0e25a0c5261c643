"""Contact at a prescribed nominal pressure (load control) instead of a separation.

The models give A/A0, W/A0 and K/A0 as functions of the separation s = h/√m00 (23); here the
separation is solved from W(s)/A0 = p for each prescribed pressure p: safeguarded Newton on
ln W with the exact slope d ln W/ds = −√m00 K/W (K/A0 = −d(W/A0)/dh, (55) elastic, −dW/dh
elasto-plastic), bracketed by bisection. W decreases strictly with s where K > 0, so the root
is unique. Then every field is evaluated once more at the solved separations.

Python warnings raised during the computation (e.g. the model-validity warnings of the contact
package) are recorded in the result (``warnings``, one message each) and re-emitted to the
caller, so that a command-line or batch user sees them in the output.
"""

from __future__ import annotations

import warnings as _warnings
from dataclasses import dataclass

import numpy as np

from ..asperity import AsperityMaterial
from ..statistics.surface import SpectralMoments
from ..validation import instance, positive
from .elastic import S_MAX_RATIO, ContactCurves, elastic_contact
from .elastoplastic import ElastoPlasticCurves, elastoplastic_contact
from .validity import relay_warnings
from ..limits import describe

__all__ = ["ContactAtPressure", "contact_at_pressure"]

#: Newton stops when |ln W − ln p| is below this (relative pressure error)
DEFAULT_RTOL = 1e-10
_MAX_STEP = 3.0  # in s: the largest Newton step (ln W is near-quadratic in s)
_MAX_ITER = 200


@dataclass(frozen=True)
class ContactAtPressure:
    """Contact at the prescribed pressures.

    pressure_target : the prescribed W/A0 [unit of E*]; h : the solved separations [L, the
    moments' length unit]; curves : every field at them (s = h/√m00, A/A0, W/A0 (= the target
    to rtol), K/A0, elasto-plastic parts) as :class:`ContactCurves` or
    :class:`ElastoPlasticCurves`; warnings : messages of the warnings raised on the way.
    """

    pressure_target: np.ndarray
    h: np.ndarray
    curves: ContactCurves | ElastoPlasticCurves
    warnings: tuple[str, ...]

    @property
    def s(self) -> np.ndarray:
        return self.curves.s

    @property
    def area_fraction(self) -> np.ndarray:
        return self.curves.area_fraction

    @property
    def stiffness(self) -> np.ndarray:
        return self.curves.stiffness


def _pressures(p) -> np.ndarray:
    try:
        a = np.atleast_1d(np.asarray(p, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"pressure must be real numbers, got {describe(p)}") from None
    if a.ndim != 1 or a.size == 0:
        raise ValueError(f"pressure must be one number or a 1-d sequence, got shape {a.shape}")
    if not np.all(np.isfinite(a) & (a > 0.0)):
        raise ValueError(f"pressure must be positive and finite, got {a[~(np.isfinite(a) & (a > 0))][:3]}")
    return a


def contact_at_pressure(surface: SpectralMoments, p, *, E_star=None, material=None, model="bgk",
                        hertz="exact", accuracy="table", rtol=DEFAULT_RTOL,
                        validity="refuse") -> ContactAtPressure:
    """Contact at nominal pressures p = W/A0 [unit of E*].

    Give ``E_star`` for the elastic model (``model`` "bgk" or "gw", eqs. (52), (53), (55)) or
    ``material`` (:class:`~roughcontact.asperity.AsperityMaterial`) for the elasto-plastic one
    ((78)–(85)). rtol: relative tolerance on W/A0 = p (default 1e-10; the production
    integrators are accurate to ~1e-13). ValueError when a pressure cannot be reached within
    s ∈ [−S_MAX, S_MAX] (37) or the pressure is not monotone there. validity: what to do where the
    solution lies outside the model's range (contact.validity; the Newton iterates are not judged,
    only the separations found).
    """
    instance("surface", surface, SpectralMoments)
    if (E_star is None) == (material is None):
        raise ValueError("give exactly one of E_star (elastic) and material (elasto-plastic)")
    if material is not None:
        instance("material", material, AsperityMaterial)
    else:
        E_star = positive("E_star", E_star)
    rtol = float(rtol)
    if not (1e-14 <= rtol <= 1e-2):
        raise ValueError(f"rtol must lie in [1e-14, 1e-2], got {describe(rtol)}")
    target = _pressures(p)

    def evaluate(s, validity="off"):
        if material is None:
            return elastic_contact(surface, s, E_star, model=model, hertz=hertz, accuracy=accuracy,
                                   validity=validity)
        return elastoplastic_contact(surface, s, material, hertz=hertz, accuracy=accuracy, validity=validity)

    with _warnings.catch_warnings(record=True) as caught:
        _warnings.simplefilter("always")
        s = _solve(evaluate, target, surface.height_std, rtol)
        curves = evaluate(s, validity)
    return ContactAtPressure(pressure_target=target, h=s * surface.height_std, curves=curves,
                             warnings=tuple(relay_warnings(caught)))


def _solve(evaluate, target, sigma, rtol) -> np.ndarray:
    """s with W(s)/A0 = target, all pressures at once (vectorised Newton with brackets)."""
    log_t = np.log(target)
    s = np.zeros_like(target)
    lo = np.full_like(target, -S_MAX_RATIO)
    hi = np.full_like(target, S_MAX_RATIO)
    done = np.zeros(target.size, dtype=bool)
    for _ in range(_MAX_ITER):
        c = evaluate(s)
        W, K = np.asarray(c.pressure, dtype=float), np.asarray(c.stiffness, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.log(W) - log_t
            slope = -sigma * K / W  # d ln W / ds
        done |= np.abs(r) <= rtol
        if done.all():
            return s
        # W decreases with s: residual > 0 means s is too small
        lo = np.where(~done & (r > 0), s, lo)
        hi = np.where(~done & (r <= 0), s, hi)
        ok = np.isfinite(r) & np.isfinite(slope) & (slope < 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.clip(-r / slope, -_MAX_STEP, _MAX_STEP)
        new = np.where(ok, s + step, 0.5 * (lo + hi))
        bad = ~((lo < new) & (new < hi))
        new = np.where(bad, 0.5 * (lo + hi), new)
        s = np.where(done, s, new)
        stuck = ~done & (hi - lo < 1e-15 * max(1.0, float(np.max(np.abs(s)))))
        if stuck.any() or (~done & ((lo >= S_MAX_RATIO * (1 - 1e-12)) | (hi <= -S_MAX_RATIO * (1 - 1e-12)))).any():
            i = int(np.flatnonzero(stuck | ~done)[0])
            raise ValueError(f"no separation gives the pressure {target[i]:g} within s in "
                             f"[{-S_MAX_RATIO:g}, {S_MAX_RATIO:g}] (W/A0 is not monotone there or "
                             "the pressure is beyond the model's range)")
    i = int(np.flatnonzero(~done)[0])
    raise ValueError(f"the separation for the pressure {target[i]:g} did not converge in "
                     f"{_MAX_ITER} iterations (last s = {s[i]:g})")
