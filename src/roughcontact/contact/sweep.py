"""Parameter sweeps of the elasto-plastic contact model as labelled xarray Datasets.

A sweep is the outer product of named parameter axes (any of the five moments, the plasticity
index ``psi``, the yield strength ``Y``, ``E_star`` and the material constants ``c_h``,
``wp_over_wc``, ``yield_coefficient``) times a vector of separations ``s`` = h/√m00. For every
combination the material is fixed by a plasticity-index closure (roughcontact.contact.closures) and
:func:`roughcontact.contact.elastoplastic.elastoplastic_contact` evaluates A, W, K and their elastic /
elasto-plastic / plastic parts over all ``s`` in one call; optionally the purely elastic model
(:func:`roughcontact.contact.elastic_contact`) is added for comparison.

Combinations are validated before anything is computed (every surface must have μ > 0, every
material must be valid), so a sweep never fails half-way on bad input. Pure library code: no
file I/O; ``progress`` receives (done, total) after each combination. Splitting a sweep into
jobs (:func:`split`) and joining the pieces (:func:`combine`) is exact: the pieces are the same
computations as the whole.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace
from typing import Callable, Mapping, Sequence

import numpy as np

from ..statistics.surface import SpectralMoments
from ..validation import choice
from .closures import CLOSURES, DEFAULTS, default_closure, resolve_material
from .validity import VALIDITY_MODES
from .units import PARAMETER_LONG_NAMES, attrs, check_units, parameter_units
from ..limits import describe

__all__ = [
    "SweepSpec", "SWEEPABLE", "run_sweep", "split", "combine", "chunk_count", "parameter_units",
    "axis_values", "spec_from_config",
]

_MOMENTS = ("m00", "m20", "m02", "m40", "m04")
_MATERIAL = ("psi", "Y", "E_star", "c_h", "wp_over_wc", "yield_coefficient")
#: Parameters a sweep axis (or a fixed value) may name.
SWEEPABLE = _MOMENTS + _MATERIAL

_ELASTIC_FIELDS = ("area_fraction", "pressure", "stiffness")
#: axes a sweep may interpolate (outermost first), and from how many values on
INTERPOLABLE = ("m00", "psi")
AXIS_MIN_POINTS = 17
#: tolerance of an axis' check at the points between its nodes: a fifth of the preset's bound
#: (integrals.rules.ELASTOPLASTIC_PRESETS: "plot" 1e-8, "table" 1e-11) — above the quadrature's
#: own variation from one value to the next (the θ-levels and regime pieces a point needs change
#: in steps of its accuracy), which the check sees too; with s's tenth and the quadrature's own
#: error the sum stays within the bound
AXIS_RTOL = {"plot": 2e-9, "table": 2e-12}
AXIS_RTOL_OTHER = 2e-9


@dataclass(frozen=True)
class SweepSpec:
    """What a sweep computes.

    axes     ordered {parameter: values}; the Dataset's dimensions are these, then ``s``.
    s        separations h/√m00 (1-D, finite).
    fixed    values of the parameters that are not swept (the moments, E_star, psi or Y, ...).
    closure  plasticity-index closure name (None: the one psi / Y imply, closures.default_closure).
    hertz    "exact" | "paper"; accuracy: production preset ("table", "plot").
    with_elastic  also evaluate the purely elastic model (variables ``elastic_model_*``).
    validity "warn" (default): a grid whose heavy corner passes A/A0 = 1 (the paper's Figs 5–8
             plot such loads) warns there (contact.validity.ModelValidityWarning, naming s and
             A/A0) instead of losing the whole grid; "refuse" raises as the contact API does.
    interpolate_s each elasto-plastic curve from a verified Chebyshev interpolant in s when it
             has ≥ 48 separations (elastoplastic_contact; the measured bound is in the
             Dataset's attributes ``s_interpolation_*``).
    interpolate_axes  axes among "m00", "psi" whose values (≥ AXIS_MIN_POINTS of them,
             positive) come from a verified Chebyshev interpolant in ln(value), as s does:
             the model at Lobatto nodes, checked at the points between them to the s
             tolerance, the measured error in the attributes ``<axis>_interpolation_*``;
             where the check fails up to the finest grid cheaper than the values, every value
             is computed ("direct"). Off by default (()): measured on the Table 1 slopes at
             "plot", m00 over a factor 2 verifies with 17 nodes (error 1e-10) and over a factor
             10 with 33, but m00 over 0.02 … 1 and ψ over 0.2 … 5 do not verify (the yield
             onset makes the fields steep in ln ψ), and the failed checks cost up to 1.7× the
             direct values; worth it for dense axes over narrow ranges.
    units    {"length": ..., "stress": ...} of the inputs, UDUNITS strings (stored as the variables' units;
             None: the dimensional variables get no units attribute).
    route    production route of contact.elastoplastic (ROUTES): "auto" (default), "tau" or
             "table". "auto" applies elastoplastic_contact's rule per surface (the materials of
             one surface — every ψ, Y, E*, … of the grid at fixed moments — are one call): a
             surface whose τ-route cost reaches the table build (measured break-even: ≥ 11
             materials of an s-interpolated curve at "plot") takes the table route, with one
             shared build per surface (summit_table.build_tables; a 10⁶-point sweep 49 s at load
             4.7–4.9 on 2 cores: benchmarks/ep_cost.py); fewer, or a cached table, as that rule says. "tau":
             per separation; "table": always the summit tables. The route each curve took is
             in the Dataset's attribute ``route_used`` ("tau", "table" or "mixed").
    """

    axes: Mapping[str, Sequence[float]]
    s: Sequence[float]
    fixed: Mapping[str, float] = field(default_factory=dict)
    closure: str | None = None
    hertz: str = "exact"
    accuracy: str = "plot"
    with_elastic: bool = True
    validity: str = "warn"
    interpolate_s: bool = True
    interpolate_axes: Sequence[str] = ()
    units: Mapping[str, str] | None = None
    route: str = "auto"

    def __post_init__(self) -> None:
        axes = {str(k): np.atleast_1d(np.asarray(v, dtype=float)) for k, v in dict(self.axes).items()}
        fixed = {str(k): float(v) for k, v in dict(self.fixed).items()}
        for name in [*axes, *fixed]:
            if name not in SWEEPABLE:
                raise ValueError(f"unknown sweep parameter {describe(name)}; choose from {', '.join(SWEEPABLE)}")
        both = set(axes) & set(fixed)
        if both:
            raise ValueError(f"parameters both swept and fixed: {', '.join(sorted(both))}")
        for name, v in axes.items():
            if v.ndim != 1 or v.size == 0 or not np.all(np.isfinite(v)):
                raise ValueError(f"sweep axis {describe(name)} must be a non-empty 1-D list of finite numbers")
            if np.unique(v).size != v.size:
                raise ValueError(f"sweep axis {describe(name)} has repeated values")
        given = set(axes) | set(fixed)
        missing = [m for m in (*_MOMENTS, "E_star") if m not in given]
        if missing:
            raise ValueError(f"sweep needs values for {', '.join(missing)} (as an axis or fixed)")
        if self.closure is None:
            # the closure the given psi / Y imply (both given: must be explicit)
            closure = default_closure(1.0 if "psi" in given else None, 1.0 if "Y" in given else None)
            object.__setattr__(self, "closure", closure)
        elif self.closure not in CLOSURES:
            raise ValueError(f"closure must be one of {', '.join(CLOSURES)}; got {describe(self.closure)}")
        choice("validity", self.validity, VALIDITY_MODES)
        from .elastoplastic import ROUTES

        choice("route", self.route, ROUTES)
        for name in self.interpolate_axes:
            choice("interpolate_axes", name, INTERPOLABLE)
        object.__setattr__(self, "interpolate_axes", tuple(self.interpolate_axes))
        s = np.atleast_1d(np.asarray(self.s, dtype=float))
        if s.ndim != 1 or s.size == 0 or not np.all(np.isfinite(s)):
            raise ValueError("s must be a non-empty 1-D list of finite separations h/sqrt(m00)")
        object.__setattr__(self, "axes", axes)
        object.__setattr__(self, "fixed", fixed)
        object.__setattr__(self, "s", s)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(v.size for v in self.axes.values()) + (self.s.size,)

    @property
    def points(self) -> int:
        """Number of (parameters, s) points."""
        return int(np.prod(self.shape))

    def combinations(self):
        """(index tuple, {parameter: value}) for every combination of the axes, in C order."""
        names = list(self.axes)
        for idx in itertools.product(*(range(v.size) for v in self.axes.values())):
            yield idx, {**self.fixed, **{n: float(self.axes[n][i]) for n, i in zip(names, idx)}}


def _surface_and_material(spec: SweepSpec, params: Mapping[str, float]):
    surface = SpectralMoments(*(params[m] for m in _MOMENTS))
    material = resolve_material(
        surface,
        E_star=params["E_star"],
        psi=params.get("psi"),
        Y=params.get("Y"),
        closure=spec.closure,
        yield_coefficient=params.get("yield_coefficient", DEFAULTS["yield_coefficient"]),
        c_h=params.get("c_h", DEFAULTS["c_h"]),
        wp_over_wc=params.get("wp_over_wc", DEFAULTS["wp_over_wc"]),
    )
    return surface, material


def _validate(spec: SweepSpec) -> list:
    """Build every (surface, material) first: a bad combination fails before any integral."""
    out = []
    for idx, params in spec.combinations():
        try:
            out.append((idx, *_surface_and_material(spec, params)))
        except (ValueError, TypeError) as exc:
            raise ValueError(f"sweep combination {params}: {exc}") from None
    return out


class _Progress:
    """progress(done, total) after every combination computed directly (an interpolated axis
    computes its nodes, not its values: the count then ends at total with ``finish``)."""

    def __init__(self, callback, total):
        self.callback, self.total, self.done = callback, total, 0

    def add(self, n):
        self.done = min(self.total, self.done + n)
        if self.callback is not None:
            for k in range(self.done - n + 1, self.done + 1):
                self.callback(k, self.total)

    def finish(self):
        if self.done < self.total:
            self.add(self.total - self.done)


def _ep_block(spec: SweepSpec, counter: _Progress):
    """The elasto-plastic fields over the sweep, shape (*spec.shape, len(FIELDS)), and the
    records of how ({"s": [...], "m00": [...], "psi": [...]}, SInterpolation attributes)."""
    for axis in INTERPOLABLE:
        values = spec.axes.get(axis)
        if axis in spec.interpolate_axes and values is not None and values.size >= AXIS_MIN_POINTS \
                and np.all(values > 0):
            return _interpolated_block(spec, axis, counter)
    return _direct_block(spec, counter)


def _direct_block(spec: SweepSpec, counter: _Progress):
    """Every combination computed; the materials of one surface in one call
    (elastoplastic_contact_many: the hyperbola integrals are the surface's, computed once)."""
    from .elastoplastic import ElastoPlasticCurves, elastoplastic_contact_many

    jobs = _validate(spec)
    out = np.empty(spec.shape + (len(ElastoPlasticCurves.FIELDS),))
    records = {"s": [], "m00": [], "psi": [], "route": []}
    by_surface: dict = {}
    for idx, surface, material in jobs:
        by_surface.setdefault(surface, []).append((idx, material))
    for surface, members in by_surface.items():
        curves = elastoplastic_contact_many(surface, spec.s, [m for _, m in members], hertz=spec.hertz,
                                            accuracy=spec.accuracy, validity=spec.validity,
                                            interpolate_s=spec.interpolate_s, route=spec.route)
        for (idx, _), ep in zip(members, curves):
            out[idx] = np.stack([getattr(ep, f) for f in ElastoPlasticCurves.FIELDS], axis=-1)
            records["s"].append(ep.interpolation.as_attrs())
            records["route"].append(ep.route)
        counter.add(len(members))
    return out, records


def _interpolated_block(spec: SweepSpec, axis: str, counter: _Progress):
    """The block with ``axis`` interpolated (contact.s_interpolation in ln(value)): the block of
    the remaining axes at Chebyshev–Lobatto nodes, checked between them."""
    from .elastoplastic import ElastoPlasticCurves
    from .s_interpolation import interpolated_columns

    pos = list(spec.axes).index(axis)
    n_fields = len(ElastoPlasticCurves.FIELDS)
    records = {"s": [], "m00": [], "psi": [], "route": []}
    rest = None
    values = spec.axes[axis]
    exact = dict(zip(np.log(values).tolist(), values.tolist()))  # exp(ln v) need not be v

    def evaluate(x):
        nonlocal rest
        sub = replace(spec, axes={**spec.axes, axis: np.array([exact.get(v, np.exp(v)) for v in x.tolist()])},
                      interpolate_axes=tuple(a for a in spec.interpolate_axes if a != axis))
        block, recs = _ep_block(sub, _Progress(None, sub.points))
        for k, v in recs.items():
            records[k].extend(v)
        moved = np.moveaxis(block, pos, 0)
        rest = moved.shape[1:]
        return moved.reshape(x.size, -1)

    # the fields' totals (area, pressure, stiffness) for the parts' floor, per flattened column
    group = {f: ((0,) if "area" in f else (1,) if "pressure" in f else (2,))
             for f in ElastoPlasticCurves.FIELDS}
    group = [group[f] for f in ElastoPlasticCurves.FIELDS]
    n_rest = int(np.prod(spec.shape)) // spec.axes[axis].size
    totals = [tuple(r * n_fields + g for g in group[q]) for r in range(n_rest) for q in range(n_fields)]
    rtol = AXIS_RTOL.get(spec.accuracy, AXIS_RTOL_OTHER) if isinstance(spec.accuracy, str) else AXIS_RTOL_OTHER
    cols, how = interpolated_columns(evaluate, np.log(values), rtol, totals, min_points=AXIS_MIN_POINTS)
    records[axis].append(how.as_attrs(f"{axis}_interpolation"))
    counter.add(spec.points // spec.s.size)
    block = np.moveaxis(cols.reshape((values.size, *rest)), 0, pos)
    return block, records


def _axis_attrs(axis: str, records) -> dict:
    """An interpolated axis over the blocks it was interpolated in: "chebyshev", "direct" or
    "mixed"; the largest measured error; its tolerance; the values computed in all."""
    p = f"{axis}_interpolation"
    methods = {r[p] for r in records}
    errors = [r[f"{p}_error"] for r in records if r[p] != "direct"]
    return {p: methods.pop() if len(methods) == 1 else "mixed",
            f"{p}_error": float(np.nanmax(errors)) if errors else float("nan"),
            f"{p}_rtol": max(float(r[f"{p}_rtol"]) for r in records),
            f"{p}_nodes": int(sum(int(r[f"{p}_nodes"]) for r in records))}


def run_sweep(spec: SweepSpec, progress: Callable[[int, int], None] | None = None):
    """Evaluate the sweep; an ``xarray.Dataset`` over (*axes, s) with units and attributes.

    Variables: the elasto-plastic totals and parts of :class:`ElastoPlasticCurves` (A/A0 [1],
    W/A0 [stress], K/A0 [stress/length], ...), ``psi`` (the index each material has), ``Y`` and
    ``H`` of the resolved material, and with ``with_elastic`` the purely elastic model
    ``elastic_model_area_fraction``, ``elastic_model_pressure``, ``elastic_model_stiffness``.
    """
    import xarray as xr

    from ..asperity import plasticity_index
    from .elastic import elastic_contact
    from .elastoplastic import ElastoPlasticCurves

    ep_fields = ElastoPlasticCurves.FIELDS
    jobs = _validate(spec)
    shape = spec.shape
    counter = _Progress(progress, len(jobs))
    block, records = _ep_block(spec, counter)
    data = {f: block[..., k] for k, f in enumerate(ep_fields)}
    if spec.with_elastic:
        data.update({f"elastic_model_{f}": np.empty(shape) for f in _ELASTIC_FIELDS})
    per_combo = {k: np.empty(shape[:-1]) for k in ("psi", "Y", "H")}
    elastic_done = {}  # the elastic model depends on (surface, E*) only, not on the material
    for idx, surface, material in jobs:
        if spec.with_elastic:
            key = (surface, material.E_star)
            if key not in elastic_done:
                elastic_done[key] = elastic_contact(
                    surface, spec.s, material.E_star, hertz=spec.hertz, accuracy=spec.accuracy,
                    validity=spec.validity,
                )
            for f in _ELASTIC_FIELDS:
                data[f"elastic_model_{f}"][idx] = getattr(elastic_done[key], f)
        per_combo["psi"][idx] = plasticity_index(surface, material)
        per_combo["Y"][idx], per_combo["H"][idx] = material.Y, material.H
    counter.finish()

    system = check_units(spec.units)
    punits = parameter_units(system["length"], system["stress"]) if system else {
        k: ("1" if u == "1" else None) for k, u in parameter_units("L", "S").items()}  # no unit stated

    def param(n):
        return {"long_name": PARAMETER_LONG_NAMES[n], **({"units": punits[n]} if punits[n] else {})}

    dims = (*spec.axes, "s")
    ds = xr.Dataset(
        {k: (dims, v, attrs(k, system)) for k, v in data.items()},
        coords={
            **{n: (n, v, param(n)) for n, v in spec.axes.items()},
            "s": ("s", spec.s, attrs("s", system)),
        },
    )
    for k, v in per_combo.items():
        ds[f"material_{k}"] = (tuple(spec.axes), v, {**param(k), "long_name": f"{PARAMETER_LONG_NAMES[k]} of the resolved material"})
    ds.attrs.update(
        model="bgk-elastoplastic",
        closure=str(spec.closure),
        hertz=spec.hertz,
        accuracy=spec.accuracy,
        route=spec.route,
        route_used=_route_used(records["route"]),
        **{f"fixed_{k}": v for k, v in spec.fixed.items()},
        **_interpolation_attrs(records["s"]),
        **{k: v for axis in INTERPOLABLE if records[axis] for k, v in _axis_attrs(axis, records[axis]).items()},
    )
    return ds


def _route_used(routes) -> str:
    """"tau" or "table" if every curve took that route, else "mixed"."""
    used = set(routes)
    return used.pop() if len(used) == 1 else "mixed"


def _interpolation_attrs(records) -> dict:
    """The s-interpolation of a sweep's curves from their attributes (SInterpolation.as_attrs,
    or those of sweep pieces): "chebyshev" if every curve was interpolated, "direct" if none,
    else "mixed"; the largest measured error between nodes over the interpolated curves (the
    bound), the tolerance and the number of model evaluations."""
    methods = {r["s_interpolation"] for r in records}
    errors = [r["s_interpolation_error"] for r in records if r["s_interpolation"] != "direct"]
    return {
        "s_interpolation": methods.pop() if len(methods) == 1 else "mixed",
        "s_interpolation_error": float(np.nanmax(errors)) if errors else float("nan"),
        "s_interpolation_rtol": max(float(r["s_interpolation_rtol"]) for r in records),
        "s_interpolation_nodes": int(sum(int(r["s_interpolation_nodes"]) for r in records)),
    }


def split(spec: SweepSpec, axis: str, chunks: int) -> list[SweepSpec]:
    """Split ``spec`` along ``axis`` into at most ``chunks`` contiguous pieces (for jobs)."""
    if axis not in spec.axes:
        raise ValueError(f"cannot split along {describe(axis)}: not a sweep axis ({', '.join(spec.axes)})")
    values = spec.axes[axis]
    n = max(1, min(int(chunks), values.size))
    return [replace(spec, axes={**spec.axes, axis: part}) for part in np.array_split(values, n)]


def combine(pieces: Sequence, axis: str):
    """Join the Datasets of :func:`split` pieces back along ``axis`` (in the given order)."""
    import xarray as xr

    if not pieces:
        raise ValueError("nothing to combine")
    ds = xr.concat(list(pieces), dim=axis, data_vars="all", coords="minimal", compat="override",
                   combine_attrs="override")
    if all("s_interpolation" in p.attrs for p in pieces):  # the whole sweep's, not the first piece's
        ds.attrs.update(_interpolation_attrs([p.attrs for p in pieces]))
    if all("route_used" in p.attrs for p in pieces):
        ds.attrs["route_used"] = _route_used(p.attrs["route_used"] for p in pieces)
    for name in INTERPOLABLE:
        with_axis = [p.attrs for p in pieces if f"{name}_interpolation" in p.attrs]
        if with_axis:
            ds.attrs.update(_axis_attrs(name, with_axis))
    return ds


def chunk_count(spec: SweepSpec, axis: str, points_per_job: int) -> int:
    """How many jobs of about ``points_per_job`` points the split along ``axis`` needs."""
    per_value = spec.points // spec.axes[axis].size
    return max(1, min(spec.axes[axis].size, math.ceil(spec.points / max(points_per_job, per_value))))


def axis_values(axis) -> np.ndarray:
    """Values of a configured axis: a list, or a grid {start, stop, num, spacing: linear|log}."""
    if isinstance(axis, Mapping):
        start, stop, num = float(axis["start"]), float(axis["stop"]), int(axis["num"])
        spacing = axis.get("spacing", "linear")
        if spacing == "linear":
            return np.linspace(start, stop, num)
        if spacing == "log":
            if not (start > 0 and stop > 0):
                raise ValueError(f"a log-spaced axis needs positive start and stop, got {start}, {stop}")
            return np.geomspace(start, stop, num)
        raise ValueError(f"axis spacing must be 'linear' or 'log', got {describe(spacing)}")
    return np.atleast_1d(np.asarray(axis, dtype=float))


def _fixed_with_moments_file(cfg: Mapping, units: Mapping[str, str] | None) -> dict:
    fixed = dict(cfg.get("fixed", {}))
    if not cfg.get("moments"):
        return fixed
    from ..readers import load_moments, moments_in_unit

    moments, unit = load_moments(cfg["moments"])
    length = (units or {}).get("length")
    if unit is not None and length is not None:
        moments = moments_in_unit(moments, unit, length)
    for name, value in moments.as_dict().items():
        if name in fixed:
            raise ValueError(f"{name} is both in fixed and in the moments file {cfg['moments']}")
        if name not in cfg["axes"]:
            fixed[name] = value
    return fixed


def spec_from_config(cfg: Mapping, units: Mapping[str, str] | None = None) -> SweepSpec:
    """A SweepSpec from a ``sweeps:`` entry of config/config.yaml (axes as lists or grids).
    ``moments: FILE.json`` (e.g. written by ``roughcontact moments SCAN --json``) fixes the five
    moments that are not swept, converted into ``units["length"]`` when the file states its unit."""
    return SweepSpec(
        axes={k: axis_values(v) for k, v in cfg["axes"].items()},
        s=axis_values(cfg["s"]),
        fixed=_fixed_with_moments_file(cfg, units),
        closure=cfg.get("closure"),
        hertz=cfg.get("hertz", "exact"),
        accuracy=cfg.get("accuracy", "plot"),
        with_elastic=bool(cfg.get("with_elastic", True)),
        interpolate_s=bool(cfg.get("interpolate_s", True)),
        interpolate_axes=tuple(cfg.get("interpolate_axes", ())),
        route=cfg.get("route", "auto"),
        **({"units": dict(units)} if units else {}),
    )
