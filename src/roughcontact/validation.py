"""Input checks shared by every layer: one message per kind of bad input (ValueError or
TypeError naming the argument and the condition). No physics, no imports from the package."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["positive", "integer", "choice", "instance", "separations"]


def positive(name: str, value, *, allow_zero: bool = False) -> float:
    """``value`` as a float that is finite and > 0 (or ≥ 0 with ``allow_zero``)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v) or v < 0.0 or (v == 0.0 and not allow_zero):
        raise ValueError(f"{name} must be finite and {'>= 0' if allow_zero else 'positive'}, got {value!r}")
    return v


def integer(name: str, value, minimum: int, maximum: int) -> int:
    """``value`` as an int in [minimum, maximum] (an integral number, not a bool or a float)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer in [{minimum}, {maximum}], got {value!r}")
    if not minimum <= int(value) <= maximum:
        raise ValueError(f"{name} must lie in [{minimum}, {maximum}], got {value!r}")
    return int(value)


def choice(name: str, value, choices) -> None:
    """ValueError unless ``value`` is one of ``choices``."""
    if value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(map(str, choices))}; got {value!r}")


def instance(name: str, value, cls) -> None:
    """TypeError unless ``value`` is an instance of ``cls``."""
    if not isinstance(value, cls):
        raise TypeError(f"{name} must be a {cls.__name__}, got {type(value).__name__}")


def separations(s) -> np.ndarray:
    """Separations s = h/√m00 as a non-empty, finite 1-D float array."""
    try:
        arr = np.atleast_1d(np.asarray(s, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"s must be a 1-D sequence of real separations h/sqrt(m00), got {s!r}") from None
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError("s must be a non-empty 1-D sequence of separations h/sqrt(m00)")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"separations must be finite, got {arr[~np.isfinite(arr)][:3]}")
    return arr
