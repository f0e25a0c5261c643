"""Plasticity-index closures: how a material for the elasto-plastic model is fixed (sections 5–7).

E*, the yield strength Y and the five moments already determine the plasticity index ψ
(:func:`roughcontact.asperity.plasticity_index`), yet the paper's Figs 5–8 prescribe
ψ = 0.35 / 0.5 *and* print E* = 1.14e5 N/mm², Y = 2070 N/mm² (for which ψ = 0.88, 1.35, 1.61 at
m00 = 0.0625, 0.3125, 0.625). Something has to give; a *closure* says what. Three are offered:

``"material"`` (physical)
    E* and Y (hence H = Y/0.354, eq. (68), unless given) are the material; ψ is an output.
    Use it for a real material.

``"yield-from-psi"`` (consistent, prescribed ψ; the default when ψ is given)
    ψ and E* are kept; the yield strength is derived from ψ so that the physical first-yield
    interference (65) equals the dimensionless ω_c* of (74)/(87) exactly:
    Y = (2/π) E* √(σ_s κ̄_m)/(K_Y ψ) (:func:`~roughcontact.asperity.yield_strength_for_plasticity_index`),
    and H = Y/0.354 (68). Every asperity's load is continuous at ω_c and ω_p.
    Figs 5–8 are drawn with this closure.

``"paper-literal"`` (inconsistent, for comparison only)
    What the paper's equations do when read literally: first yield from the prescribed ψ
    (ω_c* of (74), i.e. the Y of ``"yield-from-psi"``), but the elasto-plastic and plastic
    pressures from the printed Y (H = Y/0.354, K_v = 0.354·K_Y so that K_v H = K_Y Y_printed).
    The mean pressure then jumps at ω_c by the factor Y_printed/Y_ψ = ψ/ψ_physical, e.g. −60 %
    for ψ = 0.35 on the m00 = 0.0625 surface (ψ_physical = 0.88): the load of each asperity
    *drops* at first yield, and −dW/dh carries the (negative) jump term. Offered to show how
    far the figures move under the paper's reading (docs/errata.md E16), never as physics.

Which ψ makes (74)/(87) exact: ψ = (2/π)(E*/(K_Y Y))√(σ_s κ̄_m) (CEB-type; GW's (69) differs
by the constant factor (2/π)H/(K_Y Y) = 1.110 with Tabor's H) — tests/asperity/test_laws.py
``test_74_equals_65_with_consistent_psi`` and tests/contact/test_closures.py prove it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..asperity import TABOR_RATIO, AsperityMaterial, yield_strength_for_plasticity_index
from ..statistics.surface import SpectralMoments
from ..validation import positive

__all__ = ["Closure", "CLOSURES", "DEFAULTS", "default_closure", "resolve_material", "check_hardness"]


@dataclass(frozen=True)
class Closure:
    """A named way of fixing the material: which inputs it takes and what it means."""

    name: str
    needs_psi: bool
    needs_yield_strength: bool
    summary: str


CLOSURES: dict[str, Closure] = {
    c.name: c
    for c in (
        Closure("material", False, True, "E*, Y given (H = Y/0.354); psi is computed (physical)"),
        Closure(
            "yield-from-psi", True, False,
            "psi, E* given; Y derived from psi so that (74) = (65); H = Y/0.354 (consistent)",
        ),
        Closure(
            "paper-literal", True, True,
            "first yield from psi, pressures from the printed Y: load jumps at omega_c (inconsistent)",
        ),
    )
}

#: The captions' constants of Figs 5–8 (K = 1.62, c_h = 0.967, ω_p/ω_c = 45); H by Tabor (68).
DEFAULTS = {"yield_coefficient": 1.62, "c_h": 0.967, "wp_over_wc": 45.0}


def default_closure(psi, Y) -> str:
    """The closure implied by what is given: Y alone → "material", ψ alone → "yield-from-psi".
    Both need an explicit closure ("paper-literal")."""
    if psi is not None and Y is not None:
        raise ValueError(
            "both psi and the yield strength given: choose closure='paper-literal' explicitly "
            "(the material and psi are then inconsistent), or give only one of them"
        )
    if psi is None and Y is None:
        raise ValueError("give the plasticity index psi or the yield strength Y")
    return "material" if Y is not None else "yield-from-psi"


def check_hardness(H, Y, E_star, how: str = "") -> None:
    """ValueError unless a given hardness H lies strictly between the yield strength Y and E*
    (all in one stress unit; ``H=None``, Tabor's default, passes).

    Why: H is the mean pressure of a fully plastic indentation, H ≈ 2.8 Y (Tabor, *The Hardness
    of Metals*, 1951; eq. (68) of the paper, H = Y/0.354); the mean pressure already reaches
    1.1 Y at first yield (Johnson, *Contact Mechanics*, 1985, §6.2), so H ≤ Y is no metal's
    hardness. A Hertz mean pressure p_m = (2/3)p_0 = (4E*/3π)(a/R) (Johnson 1985, §4.2) equal
    to E* needs a/R = 3π/4 > 1, no small-strain asperity contact (the model's, sections 5–6);
    real materials have H/E* below ~0.1, diamond included. So H ≥ E* is unphysical here."""
    if H is None:
        return
    h = positive("H (hardness)", H)
    y, e = float(Y), float(E_star)
    if not (math.isfinite(y) and math.isfinite(e)):
        return  # AsperityMaterial reports a non-finite Y or E*
    if not y < h < e:
        ylabel = f"Y {how} = {y:.6g}" if how else f"Y = {y:.6g}"
        raise ValueError(f"hardness H = {h:.6g} must lie between the yield strength and E*: {ylabel}, "
                         f"E* = {e:.6g} (Tabor's H = Y/0.354 = {y / TABOR_RATIO:.6g}, eq. 68)")


def resolve_material(
    surface: SpectralMoments,
    *,
    E_star: float,
    psi: float | None = None,
    Y: float | None = None,
    closure: str | None = None,
    H: float | None = None,
    yield_coefficient: float = DEFAULTS["yield_coefficient"],
    c_h: float = DEFAULTS["c_h"],
    wp_over_wc: float = DEFAULTS["wp_over_wc"],
    K_v: float | None = None,
) -> AsperityMaterial:
    """The :class:`AsperityMaterial` of a closure (module docstring) for ``surface``.

    E_star, Y, H in one stress unit; ``psi`` dimensionless; ``closure`` one of CLOSURES (None →
    :func:`default_closure`). H defaults to Tabor's Y/0.354 (68) of the closure's Y (of the
    printed Y for "paper-literal"); K_v defaults to the continuous K_Y Y/H (to 0.354 K_Y for
    "paper-literal"). A given H must lie strictly between the closure's Y and E*
    (:func:`check_hardness`). Raises ValueError naming what is missing, extra or invalid.
    """
    if not isinstance(surface, SpectralMoments):
        raise TypeError(f"surface must be a SpectralMoments, got {type(surface).__name__}")
    name = default_closure(psi, Y) if closure is None else closure
    try:
        spec = CLOSURES[name]
    except KeyError:
        raise ValueError(f"closure must be one of {', '.join(CLOSURES)}; got {name!r}") from None
    if spec.needs_psi != (psi is not None):
        raise ValueError(f"closure {name!r} {'needs' if spec.needs_psi else 'does not take'} psi")
    if spec.needs_yield_strength != (Y is not None):
        raise ValueError(
            f"closure {name!r} {'needs' if spec.needs_yield_strength else 'does not take'} the yield strength Y"
        )
    # before Y is derived from it: K_Y = 0 divides by zero in the yield-from-psi closure
    yield_coefficient = positive("yield_coefficient K_Y (p_max = K_Y Y at first yield, eq. 63)", yield_coefficient)
    common = dict(yield_coefficient=yield_coefficient, c_h=c_h, wp_over_wc=wp_over_wc)
    if name == "material":
        check_hardness(H, Y, E_star)
        return AsperityMaterial(E_star, Y, H=H, K_v=K_v, **common)
    # Y that makes plasticity_index(surface, material) equal psi at fixed E*, K_Y
    y_psi = yield_strength_for_plasticity_index(psi, surface, E_star, yield_coefficient)
    if name == "yield-from-psi":
        check_hardness(H, y_psi, E_star, "derived from psi")
        return AsperityMaterial(E_star, y_psi, H=H, K_v=K_v, **common)
    check_hardness(H, Y, E_star)
    # paper-literal: first yield at K_Y Y_psi, pressures from the printed Y
    h_printed = H if H is not None else AsperityMaterial(E_star, Y).H  # eq. (68)
    kv = K_v if K_v is not None else TABOR_RATIO * yield_coefficient
    return AsperityMaterial(E_star, y_psi, H=h_printed, K_v=kv, **common)

