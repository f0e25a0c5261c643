"""The five moments and their length unit from a file or a mapping: what
``roughcontact moments SCAN --json > surface.json`` writes, what ``--moments surface.json`` and the
input files (sweep configurations, FE interface laws) read.

Accepted: a mapping with the five moments m00, m20, m02, m40, m04 at its top level or under
``moments``, and the length unit as ``unit`` (``"um"``) or, as the command line's JSON writes it,
``units: {m00: "um^2", ...}``. Moments in L²/–/L⁻² convert between units as m00·f², m40·f⁻²
(f = the size of the old unit in the new one). Each moment must be a JSON number (not ``true``,
which Python would read as 1, nor a string). Files are read through :mod:`roughcontact.limits`
(a regular file within the size limit, JSON nesting bounded)."""

from __future__ import annotations

import numbers
from pathlib import Path

from .. import limits
from ..statistics.surface import SpectralMoments
from . import lengths

__all__ = ["load_moments", "moments_from_mapping", "moments_in_unit", "read_json"]

_FIVE = ("m00", "m20", "m02", "m40", "m04")


def moments_from_mapping(mapping, *, where: str = "moments") -> tuple[SpectralMoments, str | None]:
    """(SpectralMoments, unit or None) from a mapping (module docstring); ValueError naming
    ``where`` for missing or inconsistent entries."""
    if not isinstance(mapping, dict):
        raise ValueError(f"{where}: expected a mapping with m00, m20, m02, m40, m04, got {type(mapping).__name__}")
    source = mapping if all(k in mapping for k in _FIVE) else mapping.get("moments", {})
    if not isinstance(source, dict) or not all(k in source for k in _FIVE):
        missing = [k for k in _FIVE if not isinstance(source, dict) or k not in source]
        raise ValueError(f"{where}: the moments {', '.join(missing)} are missing")
    for k in _FIVE:
        value = source[k]
        # bool is an int in Python: `true` would silently be m00 = 1
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise ValueError(f"{where}: {k} must be a number, got {limits.describe(value)}")
    unit = source.get("unit", mapping.get("unit"))
    units = source.get("units", mapping.get("units"))
    if unit is None and isinstance(units, dict) and isinstance(units.get("m00"), str):
        text = units["m00"].strip()
        if text.endswith("^2") or text.endswith("2"):
            unit = text[:-2] if text.endswith("^2") else text[:-1]
    if unit is not None:
        try:
            unit = lengths.normalise(unit)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
    try:
        moments = SpectralMoments(*(source[k] for k in _FIVE))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    return moments, unit


def read_json(path, what: str = "file"):
    """The content of a JSON file; ValueError (one line) if it is missing, not a regular file,
    beyond the size limit, not UTF-8, not JSON or nested deeper than the nesting limit
    (limits.read_text, limits.parse_json)."""
    if not Path(path).exists():
        raise ValueError(f"no such {what}: {path}")
    text = limits.read_text(path, what)
    try:
        return limits.parse_json(text, str(path))
    except limits.InputLimitError:
        raise
    except ValueError as exc:  # a syntax error or NaN: say which file is not JSON
        raise ValueError(str(exc).replace(f"{path}: not JSON (", f"{path}: not a JSON file (", 1)) from None


def load_moments(path) -> tuple[SpectralMoments, str | None]:
    """(SpectralMoments, unit or None) from a JSON file (module docstring)."""
    return moments_from_mapping(read_json(path, "moments file"), where=str(path))


def moments_in_unit(moments: SpectralMoments, unit_from: str, unit_to: str) -> SpectralMoments:
    """The same surface's moments expressed in ``unit_to`` (m00·f², m20, m02, m40·f⁻², m04·f⁻²)."""
    f = lengths.factor(unit_from, unit_to)
    return SpectralMoments(moments.m00 * f * f, moments.m20, moments.m02, moments.m40 / (f * f),
                           moments.m04 / (f * f))
