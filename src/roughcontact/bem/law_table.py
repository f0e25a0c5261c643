"""The BEM's load ladder of one surface as an interface law, on disk (issue 32, "A law from it").

``roughcontact bem SCAN ... --law-table FILE`` writes the ladder — at increasing nominal
pressures W/A0 the mean gap ḡ, the stiffness K/A0 = −dp/dḡ and the area fraction — with the
scan's measured moments and where it came from; LAW.yaml's ``normal: {table: FILE}``
(:mod:`roughcontact.fe.laws`) and ``roughcontact export --law-table FILE`` read it back and
tabulate p_N(u_N), k_N(u_N) from it with
:meth:`roughcontact.interface.NormalLawTable.from_samples` (docs/own-model.md, "A law from the
BEM").

The file (JSON, one object)::

    {"format": "roughcontact.bem-law-table", "version": 1,
     "length_unit": "um", "stress_unit": null, "E_star": 114000.0, "periodic": true,
     "pressure": [...], "mean_gap": [...], "stiffness": [...], "area_fraction": [...],
     "moments": {"m00": ..., "m20": ..., "m02": ..., "m40": ..., "m04": ..., "unit": "um"},
     "lay_angle_deg": 0.0, "source": {"file": ..., "sha256": ..., "shape": [ny, nx], "dx": ..., "dy": ...},
     "solver": {...}, "stiffness_method": "...", "provenance": {...} or null}

Units: lengths (ḡ, the moments) in ``length_unit`` (m, mm, um, nm); pressures and E* in one
stress unit, named by ``stress_unit`` where it is known (null: the unit E* was given in);
stiffness in that stress unit per ``length_unit``. No ContactMechanics here: the file is read
where the extra ``[bem]`` is not installed.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import limits
from ..files import atomic_path
from ..limits import describe
from ..readers import lengths
from ..statistics.surface import SpectralMoments
from ..validation import positive
from ..write_errors import write_error

__all__ = ["FORMAT", "VERSION", "LENGTH_UNITS", "BEMLawSamples", "write_law_table", "read_law_table",
           "normal_law_table"]

FORMAT = "roughcontact.bem-law-table"
VERSION = 1
#: the length units of a law table (roughcontact.readers.lengths names; those of a law file)
LENGTH_UNITS = ("m", "mm", "um", "nm")
_MOMENTS = ("m00", "m20", "m02", "m40", "m04")
_ARRAYS = ("pressure", "mean_gap", "stiffness", "area_fraction")
_KEYS = ("format", "version", "length_unit", "stress_unit", "E_star", "periodic", *_ARRAYS, "moments",
         "lay_angle_deg", "source", "solver", "stiffness_method", "provenance")
#: longest stress-unit name (a name, not a sentence)
_MAX_NAME = 40


def _array(name, value) -> np.ndarray:
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a list of numbers, got {describe(value)}") from None
    if a.ndim != 1:
        raise ValueError(f"{name} must be a flat list of numbers, got {describe(value)}")
    bad = ~np.isfinite(a)
    if bad.any():
        raise ValueError(f"{name}[{int(np.flatnonzero(bad)[0])}] is not finite")
    a.setflags(write=False)
    return a


def _first(mask) -> int:
    return int(np.flatnonzero(mask)[0])


@dataclass(frozen=True, eq=False)
class BEMLawSamples:
    """The BEM's load ladder of one surface, as a law: arrays over increasing pressure.

    pressure       W/A0, increasing, > 0, in the unit of E_star;
    mean_gap       ḡ [length_unit], strictly decreasing;
    stiffness      K/A0 = −dp/dḡ [unit of E_star per length_unit], > 0;
    area_fraction  A/A0 [–] in [0, 1];
    length_unit    'm', 'mm', 'um', 'nm' (roughcontact.readers.lengths names);
    E_star         the contact modulus used (42) [stress unit];
    periodic       periodic solver (True) or free-boundary (False);
    moments        the scan's measured moments (lay frame), in length_unit;
    lay_angle_deg  the lay angle of the scan (from the map's x axis) [°];
    source         {"file", "sha256", "shape": [ny, nx], "dx", "dy"};
    solver         tolerances / method (JSON-able);
    stiffness_method  how K was obtained (e.g. "central differences, ±2 % in p");
    stress_unit    the name of the stress unit where known (None: the unit E* was given in).

    Validated on construction: ValueError (one line, naming the field) otherwise."""

    pressure: np.ndarray
    mean_gap: np.ndarray
    stiffness: np.ndarray
    area_fraction: np.ndarray
    length_unit: str
    E_star: float
    periodic: bool
    moments: SpectralMoments
    lay_angle_deg: float
    source: dict
    solver: dict
    stiffness_method: str
    stress_unit: str | None = field(default=None)

    def __post_init__(self):
        arrays = {name: _array(name, getattr(self, name)) for name in _ARRAYS}
        n = arrays["pressure"].size
        sizes = {name: a.size for name, a in arrays.items()}
        if len(set(sizes.values())) != 1 or n < 3:
            raise ValueError(f"pressure, mean_gap, stiffness and area_fraction must have one length >= 3, got {sizes}")
        p, g, k, a = (arrays[name] for name in _ARRAYS)
        if not p[0] > 0.0 or np.any(np.diff(p) <= 0.0):
            i = 0 if not p[0] > 0.0 else _first(np.diff(p) <= 0.0) + 1
            raise ValueError(f"pressure must be positive and strictly increasing: pressure[{i}] = {p[i]!r}")
        if np.any(np.diff(g) >= 0.0):
            i = _first(np.diff(g) >= 0.0) + 1
            raise ValueError(f"mean_gap must fall strictly as the pressure rises: mean_gap[{i}] = {g[i]!r} "
                             f">= mean_gap[{i - 1}] = {g[i - 1]!r}")
        if np.any(k <= 0.0):
            i = _first(k <= 0.0)
            raise ValueError(f"stiffness must be positive: stiffness[{i}] = {k[i]!r}")
        if np.any((a < 0.0) | (a > 1.0)):
            i = _first((a < 0.0) | (a > 1.0))
            raise ValueError(f"area_fraction must lie in [0, 1]: area_fraction[{i}] = {a[i]!r}")
        for name, value in arrays.items():
            object.__setattr__(self, name, value)
        if not (isinstance(self.length_unit, str) and self.length_unit in LENGTH_UNITS):
            raise ValueError(f"length_unit must be one of {', '.join(LENGTH_UNITS)}, got {describe(self.length_unit)}")
        if self.stress_unit is not None and not (isinstance(self.stress_unit, str) and 0 < len(self.stress_unit)
                                                 <= _MAX_NAME and self.stress_unit.isprintable()):
            raise ValueError(f"stress_unit must be null or a unit name, got {describe(self.stress_unit)}")
        E = self.E_star
        if isinstance(E, bool) or not isinstance(E, (int, float)) or not (math.isfinite(E) and E > 0):
            raise ValueError(f"E_star must be a positive finite number, got {describe(E)}")
        object.__setattr__(self, "E_star", float(E))
        if not isinstance(self.periodic, bool):
            raise ValueError(f"periodic must be true or false, got {describe(self.periodic)}")
        if not isinstance(self.moments, SpectralMoments):
            raise ValueError(f"moments must be SpectralMoments, got {describe(self.moments)}")
        angle = self.lay_angle_deg
        if isinstance(angle, bool) or not isinstance(angle, (int, float)) or not math.isfinite(angle):
            raise ValueError(f"lay_angle_deg must be a finite number, got {describe(angle)}")
        object.__setattr__(self, "lay_angle_deg", float(angle))
        for name in ("source", "solver"):
            if not isinstance(getattr(self, name), dict):
                raise ValueError(f"{name} must be a mapping, got {describe(getattr(self, name))}")
        if not isinstance(self.stiffness_method, str) or not self.stiffness_method.strip():
            raise ValueError(f"stiffness_method must say how K was obtained, got {describe(self.stiffness_method)}")

    @property
    def n_samples(self) -> int:
        return int(self.pressure.size)


def _jsonable(value):
    """numpy scalars and arrays in the free-form mappings as plain JSON."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"not JSON-able: {type(value).__name__}")


def law_table_dict(samples: BEMLawSamples, provenance: dict | None = None) -> dict:
    """The JSON object of :func:`write_law_table` (module docstring)."""
    if not isinstance(samples, BEMLawSamples):
        raise TypeError(f"samples must be BEMLawSamples, got {type(samples).__name__}")
    if provenance is not None and not isinstance(provenance, dict):
        raise ValueError(f"provenance must be a mapping or None, got {describe(provenance)}")
    return {"format": FORMAT, "version": VERSION, "length_unit": samples.length_unit,
            "stress_unit": samples.stress_unit, "E_star": samples.E_star, "periodic": samples.periodic,
            **{name: getattr(samples, name).tolist() for name in _ARRAYS},
            "moments": {**samples.moments.as_dict(), "unit": samples.length_unit},
            "lay_angle_deg": samples.lay_angle_deg, "source": samples.source, "solver": samples.solver,
            "stiffness_method": samples.stiffness_method, "provenance": provenance}


def write_law_table(path, samples: BEMLawSamples, provenance: dict | None = None) -> None:
    """Write ``samples`` to ``path`` as the JSON of the module docstring, atomically
    (files.atomic_path: nothing under the name if it fails; write_errors.WriteError, one line)."""
    text = json.dumps(law_table_dict(samples, provenance), indent=1, default=_jsonable, allow_nan=False) + "\n"
    path = Path(path)
    with atomic_path(path) as tmp:
        try:
            tmp.write_text(text)
        except OSError as exc:
            raise write_error(path, exc, "BEM law table", needed=len(text)) from None


def _moments(value, unit) -> SpectralMoments:
    if not isinstance(value, dict):
        raise ValueError(f"moments must be a mapping of m00 ... m04 and unit, got {describe(value)}")
    missing = [m for m in (*_MOMENTS, "unit") if m not in value]
    if missing:
        raise ValueError(f"moments lack {', '.join(missing)}")
    if value["unit"] != unit:
        raise ValueError(f"moments.unit {describe(value['unit'])} differs from length_unit {describe(unit)}")
    for m in _MOMENTS:
        v = value[m]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"moments.{m} must be a number, got {describe(v)}")
    return SpectralMoments(**{m: value[m] for m in _MOMENTS})


def read_law_table(path) -> BEMLawSamples:
    """The samples of a law table file (module docstring): a regular UTF-8 JSON file within the
    input limits (roughcontact.limits), validated; every problem one ValueError naming the file."""
    path = Path(path)
    where = f"BEM law table {path}"
    try:
        data = limits.parse_json(limits.read_text(path, "BEM law table"), where)
    except ValueError as exc:  # missing, not a regular file, too large, not UTF-8, not JSON, too deep
        raise ValueError(str(exc)) from None
    try:
        if not isinstance(data, dict):
            raise ValueError(f"must be a JSON object, got {describe(data)}")
        if data.get("format") != FORMAT:
            raise ValueError(f"format must be {FORMAT!r}, got {describe(data.get('format'))} (written by "
                             "`roughcontact bem ... --law-table FILE`)")
        if data.get("version") != VERSION:
            raise ValueError(f"version {describe(data.get('version'))} is not read here (version {VERSION})")
        missing = [k for k in _KEYS if k not in data]
        if missing:
            raise ValueError(f"missing key {describe(missing[0])}")
        extra = [k for k in data if k not in _KEYS]
        if extra:
            raise ValueError(f"unknown key {describe(extra[0])}")
        unit = data["length_unit"]
        if isinstance(unit, str) and unit not in LENGTH_UNITS:
            try:
                unit = lengths.normalise(unit)  # "µm", "micron" → "um"
            except ValueError:
                pass
        if not (isinstance(unit, str) and unit in LENGTH_UNITS):
            raise ValueError(f"length_unit must be one of {', '.join(LENGTH_UNITS)}, got {describe(data['length_unit'])}")
        moments = data["moments"]
        if isinstance(moments, dict) and isinstance(moments.get("unit"), str) and moments["unit"] not in LENGTH_UNITS:
            try:
                moments = {**moments, "unit": lengths.normalise(moments["unit"])}
            except ValueError:
                pass
        if data["provenance"] is not None and not isinstance(data["provenance"], dict):
            raise ValueError(f"provenance must be a mapping or null, got {describe(data['provenance'])}")
        return BEMLawSamples(
            pressure=data["pressure"], mean_gap=data["mean_gap"], stiffness=data["stiffness"],
            area_fraction=data["area_fraction"], length_unit=unit, E_star=data["E_star"],
            periodic=data["periodic"], moments=_moments(moments, unit), lay_angle_deg=data["lay_angle_deg"],
            source=data["source"], solver=data["solver"], stiffness_method=data["stiffness_method"],
            stress_unit=data["stress_unit"])
    except ValueError as exc:
        raise ValueError(f"{where}: {' '.join(str(exc).split())}") from None


def normal_law_table(samples: BEMLawSamples, *, moments: SpectralMoments | None = None, stress_factor: float = 1.0):
    """The interface law of the ladder: :meth:`roughcontact.interface.NormalLawTable.from_samples`
    through (h = ḡ, p, K) at level "bem", lengths in the table's ``length_unit``, pressures, K and
    E* times ``stress_factor`` (another stress unit); surface: ``moments`` (in length_unit) or
    the table's measured ones. ValueError where the samples do not make a monotone law."""
    from ..interface.normal_law import NormalLawTable

    if not isinstance(samples, BEMLawSamples):
        raise TypeError(f"samples must be BEMLawSamples, got {type(samples).__name__}")
    f = positive("stress_factor", stress_factor)
    return NormalLawTable.from_samples(samples.mean_gap, samples.pressure * f, samples.stiffness * f,
                                       surface=samples.moments if moments is None else moments,
                                       E_star=samples.E_star * f, level="bem")
