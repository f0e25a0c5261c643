"""Anchors of the verification gate for what it did not see (issue 29): the elasto-plastic curves
and sweeps against the slow twins, and every published CSV against the result it was written from.

With every output of a finished run scaled by 1.05 the gate stayed green for the elasto-plastic
curves (Figs 5-8 and the stiffness sensitivity: their claims are ratios and orderings, which a
common factor leaves alone), for the sweep ``results/sweeps/m00_psi.nc`` (not read at all) and
for an edited ``paper_figures/*.csv`` (no rule reads a published file back). Here:

* **curves and sweeps** (scene ``curve_anchors``): at a few sample points per curve file, chosen
  in config/config.yaml ``gate_anchors.curves.samples``, the file's totals A/A0, W/A0, K/A0 and
  the regime parts of A and W against the slow twin of the elasto-plastic kernel
  (:func:`roughcontact.integrals.reference_elastoplastic.reference_integrals`, adaptive scipy
  cubature with the law from :func:`roughcontact.asperity.respond`), and the purely elastic
  model's curves against the mpmath integrals
  (:func:`roughcontact.integrals.reference.elastic_reference`). The twin values are computed
  from the configuration alone, never from the file they judge;
* **published CSVs** (scene ``published_csv``): each CSV re-derived from the files it was written
  from and compared with the published one cell by cell (:func:`csv_cell_check`).

Pure functions, no file I/O (the workflow scripts read and write); tolerances are data
(config.yaml ``gate_anchors``).
"""

from __future__ import annotations

import csv
import io as _io
import math
from dataclasses import asdict, dataclass, field
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from ..limits import describe
from .verify import NOT_REPRODUCED, REPRODUCED, Check, numerics_id

__all__ = ["CURVE_SCENE", "CSV_SCENE", "TwinPoint", "sample_points", "twin_values", "curve_anchor_checks",
           "csv_cell_check", "regression_details", "EP_PARTS", "ELASTIC_MODEL"]

CURVE_SCENE, CSV_SCENE = "curve_anchors", "published_csv"
_MOMENTS = ("m00", "m20", "m02", "m40", "m04")
#: the regime parts of A/A0 and W/A0 (contact.elastoplastic.ElastoPlasticCurves), in the twin's order
EP_PARTS = ("elastic_area_fraction", "elastoplastic_area_fraction", "plastic_area_fraction",
            "elastic_pressure", "elastoplastic_pressure", "plastic_pressure")
#: the total each part is measured against (the twin scales its columns by their totals)
_PART_TOTAL = {p: ("area_fraction" if "area" in p else "pressure") for p in EP_PARTS}
#: the purely elastic model beside the elasto-plastic one (contact.sweep, with_elastic)
ELASTIC_MODEL = ("elastic_model_area_fraction", "elastic_model_pressure", "elastic_model_stiffness")


@dataclass(frozen=True)
class TwinPoint:
    """One sample point of a curve file: where it lies in the file (``coords``: dimension →
    coordinate value), the model's parameters there (``params``: the five moments, E_star and psi
    and/or Y, as a sweep combination), the closure and Hertz option, and which variables of the
    file the twin's quantities judge (``variables``: file variable → twin quantity: a total
    "area_fraction", "pressure", "stiffness", a part of :data:`EP_PARTS`, or one of :data:`ELASTIC_MODEL`)."""

    source: str
    coords: dict
    params: dict
    closure: str
    hertz: str
    variables: dict = field(default_factory=dict)

    @property
    def s(self) -> float:
        return float(self.coords["s"])

    @property
    def label(self) -> str:
        return ",".join(f"{k}={_fmt(v)}" for k, v in self.coords.items())

    def to_json(self) -> dict:
        return asdict(self)


def _fmt(v) -> str:
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def _axis(spec) -> np.ndarray:
    """A configured axis: a list or a grid {start, stop, num, spacing} (contact.sweep.axis_values)."""
    from ..contact.sweep import axis_values

    return axis_values(spec)


def _coordinate(name: str, want, axis: np.ndarray | None, where: str):
    """A sample's coordinate: a value of the axis (matched to 1e-9 relative, so that a typo
    fails instead of silently judging a neighbour), or {index: k} of a numeric axis."""
    if want is None:
        raise ValueError(f"{where}: {name} is missing (a value of its axis, or {{index: k}})")
    if isinstance(want, Mapping):
        if axis is None or set(want) != {"index"}:
            raise ValueError(f"{where}: {name} must be a value or {{index: k}} of its axis")
        k = want["index"]
        if isinstance(k, bool) or not isinstance(k, int) or not -axis.size <= k < axis.size:
            raise ValueError(f"{where}: {name} index must be an integer in [0, {axis.size}), got {describe(k)}")
        return float(axis[k])
    if isinstance(want, str):
        return want
    value = float(want)
    if axis is not None and not np.any(np.isclose(axis, value, rtol=1e-9, atol=1e-12)):
        raise ValueError(f"{where}: {name} = {value:g} is not on the configured axis "
                         f"({', '.join(f'{a:.6g}' for a in axis[:8])}{' ...' if axis.size > 8 else ''})")
    return value


def _totals(prefix: str = "") -> dict:
    return {f"{prefix}{q}": q for q in ("area_fraction", "pressure", "stiffness")}


def sample_points(kind: str, name: str, cfg: Mapping[str, Any], samples: Sequence[Mapping[str, Any]],
                  surfaces: Mapping[str, Mapping[str, float]] | None = None) -> list[TwinPoint]:
    """The :class:`TwinPoint` of each configured sample of the curve file ``name``.

    kind     "sweep" (``cfg``: a config.yaml ``sweeps:`` entry; a sample gives every axis and s)
             or the scene kind "elastoplastic_psi" (Fig. 5: psi, s), "stiffness_pressure"
             (Figs 7-8: closure, m00, s) or "stiffness_sensitivity" (variant, s; or psi, s for
             its psi_pressure, psi_stiffness) with the scene's ``cfg``.
    surfaces config.yaml ``surfaces`` (the scenes name theirs)."""
    out = []
    for i, sample in enumerate(samples):
        where = f"gate_anchors.curves.samples.{name}[{i}]"
        sample = dict(sample)
        s = _coordinate("s", sample.pop("s", None), _axis(cfg["s"]), where)
        if kind == "sweep":
            axes = {k: _axis(v) for k, v in cfg["axes"].items()}
            if set(sample) != set(axes):
                raise ValueError(f"{where}: give exactly the sweep's axes {', '.join(axes)} and s")
            coords = {k: _coordinate(k, sample[k], axes[k], where) for k in axes}
            params = {**{k: float(v) for k, v in cfg["fixed"].items()}, **coords}
            variables = {**_totals(), **{p: p for p in EP_PARTS}}
            if cfg.get("with_elastic", True):
                variables.update({e: e for e in ELASTIC_MODEL})
            out.append(TwinPoint(name, {**coords, "s": s}, params, cfg.get("closure"), cfg.get("hertz", "exact"),
                                 variables))
            continue
        base = {k: float(v) for k, v in surfaces[cfg["surface"]].items()}
        E = {"E_star": float(cfg["E_star"])}
        if kind == "elastoplastic_psi":
            _only(sample, {"psi"}, where)
            psi = _coordinate("psi", sample["psi"], np.asarray(cfg["psi"], dtype=float), where)
            out.append(TwinPoint(name, {"psi": psi, "s": s}, {**base, **E, "psi": psi}, cfg["closure"],
                                 cfg.get("hertz", "exact"), {**_totals(), **{p: p for p in EP_PARTS}}))
        elif kind == "stiffness_pressure":
            _only(sample, {"closure", "m00"}, where)
            closure = sample["closure"]
            if closure not in cfg["closures"]:
                raise ValueError(f"{where}: closure {describe(closure)} is not one of the scene's {cfg['closures']}")
            m00 = _coordinate("m00", sample["m00"], np.asarray(cfg["m00"], dtype=float), where)
            inputs = {"material": {"Y": float(cfg["Y"])}, "yield-from-psi": {"psi": float(cfg["psi"])},
                      "paper-literal": {"psi": float(cfg["psi"]), "Y": float(cfg["Y"])}}[closure]
            out.append(TwinPoint(name, {"closure": closure, "m00": m00, "s": s}, {**base, "m00": m00, **E, **inputs},
                                 closure, cfg.get("hertz", "exact"),
                                 {**_totals(), **{p: p for p in EP_PARTS},
                                  **{e: e for e in ELASTIC_MODEL}}))
        elif kind == "stiffness_sensitivity":
            if "variant" in sample:
                _only(sample, {"variant"}, where)
                variant = sample["variant"]
                if variant != "base" and variant not in cfg["variants"]:
                    raise ValueError(f"{where}: variant {describe(variant)} is not one of the scene's "
                                     f"{['base', *cfg['variants']]}")
                factors = {} if variant == "base" else cfg["variants"][variant]
                moments = {k: v * float(factors.get(k, 1.0)) for k, v in base.items()}
                out.append(TwinPoint(name, {"variant": variant, "s": s}, {**moments, **E, "psi": float(cfg["psi"])},
                                     cfg["closure"], cfg.get("hertz", "exact"),
                                     {**_totals(), **{p: p for p in EP_PARTS},
                                      **{e: e for e in ELASTIC_MODEL}}))
            else:
                _only(sample, {"psi"}, where)
                psi = _coordinate("psi", sample["psi"], np.asarray(cfg["psi_values"], dtype=float), where)
                out.append(TwinPoint(name, {"psi": psi, "s": s}, {**base, **E, "psi": psi}, cfg["closure"],
                                     cfg.get("hertz", "exact"), {"psi_pressure": "pressure",
                                                                 "psi_stiffness": "stiffness"}))
        else:
            raise ValueError(f"{where}: no twin for the scene kind {describe(kind)}")
    return out


def _only(sample: Mapping, keys: set, where: str) -> None:
    if set(sample) != keys:
        raise ValueError(f"{where}: give exactly {', '.join(sorted(keys))} and s, got {', '.join(sorted(sample))}")


def twin_values(point: TwinPoint, *, rtol: float, dps: int, ep_twin: Callable | None = None,
                elastic_twin: Callable | None = None) -> dict[str, float]:
    """The slow twins' values of every quantity ``point.variables`` asks for, in the unit system
    of config.yaml ``units`` (A/A0 [1], W/A0 [stress], K/A0 [stress/length]):

    * the elasto-plastic totals and parts: the scipy twin
      (:func:`~roughcontact.integrals.reference_elastoplastic.reference_integrals` at ``rtol``;
      (78)-(85), K = −dW/dh with the load jump), material from the point's closure
      (:func:`roughcontact.contact.resolve_material`, as the sweep resolves it);
    * the purely elastic model (:data:`ELASTIC_MODEL`): the mpmath integrals (52), (53), (55) at ``dps`` digits times E*
      (:func:`~roughcontact.integrals.reference.elastic_reference`).

    ``ep_twin``, ``elastic_twin``: replacements with the same signatures (tests)."""
    from ..contact import resolve_material
    from ..integrals.reference import elastic_reference
    from ..integrals.reference_elastoplastic import reference_integrals
    from ..statistics.surface import SpectralMoments

    ep_twin = ep_twin or reference_integrals
    elastic_twin = elastic_twin or elastic_reference
    p = point.params
    surface = SpectralMoments(*(float(p[m]) for m in _MOMENTS))
    wanted = set(point.variables.values())
    out: dict[str, float] = {}
    if wanted - set(ELASTIC_MODEL):
        material = resolve_material(surface, E_star=float(p["E_star"]), psi=p.get("psi"), Y=p.get("Y"),
                                    closure=point.closure)
        cols = np.asarray(ep_twin(surface, point.s, material, hertz=point.hertz, rtol=rtol), dtype=float)
        out.update({"area_fraction": float(cols[0:3].sum()), "pressure": float(cols[3:6].sum()),
                    "stiffness": float(cols[6]), **{name: float(cols[k]) for k, name in enumerate(EP_PARTS)}})
    if wanted & set(ELASTIC_MODEL):
        ref = elastic_twin(surface, [point.s], hertz=point.hertz, dps=dps, quantities=("area", "load", "stiffness"))
        E = float(p["E_star"])
        out.update({"elastic_model_area_fraction": float(ref["area"][0]),
                    "elastic_model_pressure": E * float(ref["load"][0]),
                    "elastic_model_stiffness": E * float(ref["stiffness"][0])})
    return out


def _select(ds, coords: Mapping[str, Any], variable: str) -> float:
    """The value of ``variable`` at ``coords`` (numeric ones matched to 1e-9 relative)."""
    da = ds[variable]
    for dim, want in coords.items():
        if dim not in da.dims:
            continue
        axis = ds[dim].values
        if isinstance(want, str):
            hits = np.flatnonzero(axis.astype(str) == want)
        else:
            hits = np.flatnonzero(np.isclose(axis.astype(float), float(want), rtol=1e-9, atol=1e-12))
        if hits.size != 1:
            raise ValueError(f"{variable}: {dim} = {_fmt(want)} is not (once) on the file's axis")
        da = da.isel({dim: int(hits[0])})
    return float(da.values)


def curve_anchor_checks(points: Sequence[TwinPoint], twins: Sequence[Mapping[str, float]],
                        data: Mapping[str, Any], files: Mapping[str, str], tolerance: Mapping[str, Any],
                        twin_rtol: float, dps: int) -> list[Check]:
    """One check per (sample point, variable) of the curve files (``data``: source → dataset,
    ``files``: source → its path, for the messages), against the twins' values at the point
    (``twins``, one mapping per point, :func:`twin_values`). Totals: relative error; a part of A
    or W: its difference relative to the twin's total (parts may vanish). ``tolerance``: config
    ``gate_anchors.curves.tolerance`` {rtol, why}."""
    rtol, why = float(tolerance["rtol"]), " ".join(str(tolerance["why"]).split())
    out = []
    for point, twin in zip(points, twins):
        ds = data[point.source]
        for variable, quantity in point.variables.items():
            ref = float(twin[quantity])
            try:
                ours = _select(ds, point.coords, variable)
            except (KeyError, ValueError) as exc:
                ours, missing = math.nan, str(exc)
            else:
                missing = ""
            scale = abs(float(twin[_PART_TOTAL[quantity]])) if quantity in _PART_TOTAL else abs(ref)
            err = (ours - ref) / scale if scale > 0.0 and math.isfinite(ours) else (
                0.0 if ours == ref else math.nan)
            ok = math.isfinite(err) and abs(err) <= rtol
            what = (f"elastic model, mpmath {dps} digits" if quantity in ELASTIC_MODEL
                    else f"slow twin, scipy cubature rtol {twin_rtol:g}")
            rel = " of its total" if quantity in _PART_TOTAL else ""
            detail = (f"{files[point.source]} {variable}[{point.label}] = {ours:.10g} vs {ref:.10g} ({what}): "
                      f"{err:+.2e}{rel} {'≤' if ok else '>'} {rtol:.0e}" if not missing else
                      f"{files[point.source]}: {missing}")
            out.append(Check(id=numerics_id(CURVE_SCENE, point.source, variable, point.label, "point"),
                             kind="numerics", scene=CURVE_SCENE, verdict=REPRODUCED if ok else NOT_REPRODUCED,
                             detail=detail, description=f"a sampled point of {point.source}'s curves against the "
                             f"independent slow twin", model=point.source, quantity=variable, s=point.label,
                             target=ref, value=ours, error=err, tolerance=rtol, tolerance_why=why))
    return out


# ---------------------------------------------------------------------------------------------
# published CSVs
# ---------------------------------------------------------------------------------------------
def _number(text: str):
    try:
        return float(text)
    except ValueError:
        return None


def csv_cell_check(name: str, published: str, derived: str, tolerance: Mapping[str, Any], *,
                   shown: int = 5) -> Check:
    """One check of a published CSV (``name``: its path) against the same CSV re-derived from the
    files it was written from: same header, same rows, every cell equal (numbers within
    ``tolerance['rtol']`` relative, text exactly). The detail names the file and the first
    ``shown`` differing cells (row number, the row's first cell, column, published vs derived)."""
    rtol, why = float(tolerance["rtol"]), " ".join(str(tolerance["why"]).split())
    pub = list(csv.reader(_io.StringIO(published)))
    der = list(csv.reader(_io.StringIO(derived)))
    diffs, worst = [], 0.0
    if not pub or not der or pub[0] != der[0]:
        diffs.append(f"header {describe(','.join(pub[0]) if pub else '')} vs derived "
                     f"{describe(','.join(der[0]) if der else '')}")
        worst = math.inf
    else:
        header = der[0]
        if len(pub) != len(der):
            diffs.append(f"{len(pub) - 1} rows vs {len(der) - 1} derived")
            worst = math.inf
        for i, (a, b) in enumerate(zip(pub[1:], der[1:]), start=2):
            if len(a) != len(b):
                diffs.append(f"line {i}: {len(a)} cells vs {len(b)} derived")
                worst = math.inf
                continue
            for col, x, y in zip(header, a, b):
                if x == y:
                    continue
                fx, fy = _number(x), _number(y)
                if fx is not None and fy is not None and math.isfinite(fx) and math.isfinite(fy):
                    err = abs(fx - fy) / max(abs(fy), 1e-300) if fy != 0.0 else (0.0 if fx == 0.0 else math.inf)
                    if err <= rtol:
                        continue
                    worst = max(worst, err)
                else:
                    worst = math.inf
                row = ",".join(b[:2])
                diffs.append(f"line {i} ({row}), column {describe(col)}: published {describe(x)} vs derived {describe(y)}")
    ok = not diffs
    n_cells = sum(len(r) for r in der[1:])
    detail = (f"{name}: all {n_cells} cells equal the ones re-derived from its result files" if ok else
              f"{name} differs from its result files in {len(diffs)} place(s): " + "; ".join(diffs[:shown])
              + (" ..." if len(diffs) > shown else ""))
    return Check(id=numerics_id(CSV_SCENE, name.rsplit("/", 1)[-1].removesuffix(".csv"), "cells", name, "file"),
                 kind="numerics", scene=CSV_SCENE, verdict=REPRODUCED if ok else NOT_REPRODUCED, detail=detail,
                 description="the published CSV against the files it was written from, cell by cell", model=name,
                 quantity="cells", s=name, target=0.0, value=float(len(diffs)), error=worst, tolerance=rtol,
                 tolerance_why=why)


def regression_details(checks: Sequence[Check], limit: int = 300) -> dict[str, str]:
    """{id: detail} of the regressions among ``checks`` (after verify.apply_expectations), each
    detail on one line cut to ``limit`` characters: the summary's ``regression_details``, which
    the gate prints beside each id (the tampered file and its cell, not only the check's name)."""
    out = {}
    for c in checks:
        if c.status == "regression":
            text = " ".join(str(c.detail).split())
            out[c.id] = text if len(text) <= limit else text[: limit - 1] + "…"
    return out
