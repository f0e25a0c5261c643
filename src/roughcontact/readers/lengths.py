"""Length units of measured data: their names as instruments and users write them, and the
factors between them (SI: 1 µm = 1e-6 m)."""

from __future__ import annotations

import math

from .. import limits

__all__ = ["METRES", "normalise", "factor", "PLAUSIBLE", "in_metres", "likely_unit"]

#: metres per unit, keyed by the canonical (UDUNITS) name
METRES = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "nm": 1e-9, "pm": 1e-12, "angstrom": 1e-10,
          "in": 0.0254, "mil": 2.54e-5}
_ALIASES = {
    "meter": "m", "metre": "m", "meters": "m", "metres": "m",
    "millimeter": "mm", "millimetre": "mm", "millimeters": "mm", "millimetres": "mm",
    "µm": "um", "μm": "um", "micron": "um", "microns": "um", "micrometer": "um", "micrometre": "um",
    "micrometers": "um", "micrometres": "um", "mum": "um",
    "nanometer": "nm", "nanometre": "nm", "nanometers": "nm", "nanometres": "nm",
    "picometer": "pm", "picometre": "pm", "å": "angstrom", "ang": "angstrom",
    "inch": "in", "inches": "in", "thou": "mil",
}


def normalise(unit) -> str:
    """The canonical name of a length unit ("µm", "micron", "um" → "um"); ValueError naming
    the known ones for anything else."""
    text = str(unit).strip()
    key = _ALIASES.get(text.lower(), text.lower()) if text not in METRES else text
    if key not in METRES:
        raise ValueError(f"unknown length unit {limits.describe(unit)}: use one of {', '.join(METRES)}")
    return key


def factor(from_unit, to_unit) -> float:
    """The number by which a length in ``from_unit`` is multiplied to express it in ``to_unit``."""
    return METRES[normalise(from_unit)] / METRES[normalise(to_unit)]


#: the range, in metres, of what topography instruments measure (an order of magnitude beyond each
#: end): the sampling interval from an AFM's ~1 nm pixel to large-area profilometry's ~1 mm, the
#: rms height from ~0.1 nm (the noise floor of optical and stylus instruments) to ~1 mm. A value
#: outside is a unit mistake, not a surface (metres read as µm: 10⁶ too small). "typical": the
#: middle, in log, that :func:`likely_unit` aims for.
PLAUSIBLE = {"sampling interval": (1e-10, 1e-2, 1e-6), "rms height": (1e-11, 1e-2, 1e-7)}


def in_metres(value: float) -> str:
    """A length in metres as a short text in the nearest of pm, nm, um, mm, m ("1.25 pm")."""
    for unit in ("m", "mm", "um", "nm", "pm"):
        if abs(value) >= 0.0999 * METRES[unit] or unit == "pm":  # 0.1 nm, not 100 pm (rounding)
            return f"{value / METRES[unit]:.3g} {unit}"


def likely_unit(value: float, unit: str, quantity: str) -> str | None:
    """None if ``value`` in ``unit`` is a plausible ``quantity`` ("sampling interval" or "rms
    height", :data:`PLAUSIBLE`), else the common unit (m, mm, um, nm) in which the number would be
    plausible and nearest the typical value."""
    low, high, typical = PLAUSIBLE[quantity]
    metres = abs(value) * METRES[normalise(unit)]
    if not metres > 0 or low <= metres <= high:
        return None
    candidates = [u for u in ("m", "mm", "um", "nm") if low <= abs(value) * METRES[u] <= high]
    return min(candidates, key=lambda u: abs(math.log10(abs(value) * METRES[u] / typical)), default=None)
