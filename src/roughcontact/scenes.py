"""The data of the elasto-plastic figure scenes (Figs 5–8 and the stiffness-sensitivity scene),
assembled from :mod:`roughcontact.sweep` — exactly the curves each scene needs, as labelled
xarray Datasets ready for :mod:`roughcontact.claims` and :mod:`roughcontact.plots`. No I/O.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

from .sweep import SweepSpec, parameter_units, run_sweep

__all__ = ["psi_curves", "stiffness_curves", "stiffness_sensitivity"]

_MOMENTS = ("m00", "m20", "m02", "m40", "m04")


def psi_curves(moments: Mapping[str, float], E_star: float, psi: Sequence[float], s, *,
               closure: str = "yield-from-psi", hertz="exact", accuracy="plot", units=None):
    """Figs 5–6: the elasto-plastic model of one surface for several plasticity indices ψ
    (dims psi, s), with ``material_H`` for the load axis W/(H A0)."""
    spec = SweepSpec(axes={"psi": psi}, s=s, fixed={**moments, "E_star": E_star}, closure=closure,
                     hertz=hertz, accuracy=accuracy, with_elastic=False, **_units(units))
    return run_sweep(spec)


def stiffness_curves(moments: Mapping[str, float], m00: Sequence[float], E_star: float, psi: float,
                     Y: float, closures: Sequence[str], s, *, hertz="exact", accuracy="plot", units=None):
    """Figs 7–8: elasto-plastic and purely elastic K/A0 and W/A0 for several m00 (the other
    moments fixed), one per closure (dims closure, m00, s). The captions give both ψ and Y:
    "material" uses Y (ψ follows), "yield-from-psi" uses ψ, "paper-literal" both."""
    import xarray as xr

    fixed = {k: v for k, v in moments.items() if k != "m00"}
    inputs = {"material": {"Y": Y}, "yield-from-psi": {"psi": psi}, "paper-literal": {"psi": psi, "Y": Y}}
    parts = []
    for closure in closures:
        spec = SweepSpec(axes={"m00": m00}, s=s, fixed={**fixed, "E_star": E_star, **inputs[closure]},
                         closure=closure, hertz=hertz, accuracy=accuracy, **_units(units))
        parts.append(run_sweep(spec).expand_dims(closure=[closure]))
    ds = xr.concat(parts, dim="closure", combine_attrs="drop_conflicts")
    ds["closure"].attrs["units"] = "1"
    ds.attrs.update(psi=float(psi), Y=float(Y))
    return ds


def stiffness_sensitivity(moments: Mapping[str, float], E_star: float, psi: float,
                          variants: Mapping[str, Mapping[str, float]], psi_values: Sequence[float], s, *,
                          closure: str = "yield-from-psi", hertz="exact", accuracy="plot", units=None):
    """Sections 7 and 10: K/A0 vs W/A0 of the base surface and of ``variants`` (each a map
    moment → factor, e.g. {"m20": 2, "m02": 2}; the base is added as "base") at plasticity
    index ``psi`` (dims variant, s), and the elasto-plastic model of the base surface for
    ``psi_values`` (variables psi_pressure, psi_stiffness over psi, s)."""
    import xarray as xr

    rows = {"base": dict(moments)}
    for name, factors in variants.items():
        unknown = set(factors) - set(_MOMENTS)
        if unknown:
            raise ValueError(f"variant {name!r}: unknown moments {', '.join(sorted(unknown))}")
        rows[name] = {k: v * float(factors.get(k, 1.0)) for k, v in moments.items()}
    parts = []
    for name, mom in rows.items():
        spec = SweepSpec(axes={"psi": [psi]}, s=s, fixed={**mom, "E_star": E_star}, closure=closure,
                         hertz=hertz, accuracy=accuracy, **_units(units))
        parts.append(run_sweep(spec).isel(psi=0, drop=True).expand_dims(variant=[name]))
    ds = xr.concat(parts, dim="variant", combine_attrs="drop_conflicts")
    ds["variant"].attrs["units"] = "1"
    punits = parameter_units(**(units or {"length": "L", "stress": "unit of E*"}))
    for k in _MOMENTS:
        ds[f"variant_{k}"] = ("variant", [rows[n][k] for n in rows], {"units": punits[k]})
    by_psi = psi_curves(moments, E_star, psi_values, s, closure=closure, hertz=hertz, accuracy=accuracy, units=units)
    for v in ("pressure", "stiffness"):
        ds[f"psi_{v}"] = by_psi[v]
    ds.attrs.update(psi=float(psi), closure=closure)
    return ds


def _units(units):
    return {} if units is None else {"units": dict(units)}
