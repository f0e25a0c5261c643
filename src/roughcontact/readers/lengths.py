"""Length units of measured data: their names as instruments and users write them, and the
factors between them (SI: 1 µm = 1e-6 m)."""

from __future__ import annotations

__all__ = ["METRES", "normalise", "factor"]

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
        raise ValueError(f"unknown length unit {unit!r}: use one of {', '.join(METRES)}")
    return key


def factor(from_unit, to_unit) -> float:
    """The number by which a length in ``from_unit`` is multiplied to express it in ``to_unit``."""
    return METRES[normalise(from_unit)] / METRES[normalise(to_unit)]
