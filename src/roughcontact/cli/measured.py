"""The command from a surface to an FE code: ``export`` (the law as an Abaqus / CalculiX / CSV
pressure–overclosure table). The moments of a measured map: :mod:`.moments`."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

from . import (
    CLIError, EP_DEFAULTS, _add_modulus_options, _real, effective_modulus_from,
)

__all__ = ["add_commands"]

FORMATS = ("abaqus", "calculix", "csv")  # interface.export.FORMATS
CANNOT_EXPRESS = {
    "abaqus": ["k_T(p): the stick stiffness follows k_N(p); *FRICTION takes one elastic slip (k_T matches at p0 only)",
               "the orthotropic / hardening friction of section 8.1",
               "elasto-plastic unloading (the table is the loading curve)"],
    "calculix": ["k_T(p): *FRICTION takes one stick slope (k_T(p0))",
                 "the orthotropic / hardening friction of section 8.1",
                 "elasto-plastic unloading (the table is the loading curve)",
                 "more than 200 rows (resampled evenly in overclosure) and pressures beyond the last row (held constant)"],
    "csv": [],
}


def add_commands(sub, parents) -> None:
    """Register ``export`` (moments and output parents)."""
    _add_export(sub, parents)


def _add_export(sub, parents) -> None:
    p = sub.add_parser(
        "export", parents=parents, help="pressure-overclosure table for Abaqus, CalculiX or CSV",
        description="The statistical law as a pressure-overclosure table whose piecewise-linear "
        "interpolation stays within --rtol of the law for pressures in --pressure-range; first row at "
        "zero pressure; overclosure zero at the seating pressure (--seating-pressure) or the mean "
        "planes. Without -o the table is printed.")
    _add_modulus_options(p)
    p.add_argument("--format", dest="fmt", choices=FORMATS, required=True, help="the target code's syntax")
    p.add_argument("--law", choices=("elastic", "elastoplastic"), default="elastic",
                   help="elastic (53) or elasto-plastic (82) law (default elastic)")
    p.add_argument("--psi", type=_real, metavar="P", help="plasticity index (elastoplastic; closure yield-from-psi)")
    p.add_argument("--yield-strength", dest="Y", type=_real, metavar="Y",
                   help="yield strength (elastoplastic; closure material)")
    p.add_argument("--pressure-range", dest="pressure_range", type=_real, nargs=2, required=True,
                   metavar=("PMIN", "PMAX"), help="pressures (unit of E*) where the table meets rtol; keep "
                   "PMAX far above every pressure of the FE model")
    p.add_argument("--rtol", type=_real, default=1e-3, help="relative error of the table against the law (default 1e-3)")
    p.add_argument("--seating-pressure", dest="p0", type=_real, default=None, metavar="P0",
                   help="overclosure zero at this pressure (unit of E*); default: at the mean planes")
    p.add_argument("--length-scale", dest="length_scale", type=_real, default=1.0, metavar="F",
                   help="multiply overclosures by F (e.g. 1e-3: moments in um, FE model in mm)")
    p.add_argument("--length-unit", dest="length_unit", default="L", metavar="NAME", help="name of the output length unit")
    p.add_argument("--stress-scale", dest="stress_scale", type=_real, default=1.0, metavar="G",
                   help="multiply pressures by G (e.g. 1e6: E* in N/mm^2 = MPa, FE model in Pa)")
    p.add_argument("--stress-unit", dest="stress_unit", default="unit of E*", metavar="NAME",
                   help="name of the output stress unit")
    p.add_argument("--mu", type=_real, default=None, help="Coulomb friction coefficient: adds a *FRICTION block")
    p.add_argument("--kt-over-kn", dest="kt_over_kn", type=_real, default=None, metavar="A",
                   help="k_T/k_N for the stick stiffness k_T(p0) = A k_N(p0) (with --mu)")
    p.add_argument("--max-rows", dest="max_rows", type=int, default=None, metavar="N",
                   help="fail if more rows are needed (calculix: 200 always)")
    p.add_argument("-o", "--output", default=None, metavar="FILE", help="write the table to FILE")
    p.set_defaults(func=_run_export, render=_render_export)


def _run_export(args) -> dict[str, Any]:
    from ..contact.closures import resolve_material
    from ..contact.validity import relay_warnings
    from ..interface.export import CALCULIX_MAX_ROWS, format_table, friction_block, overclosure_table
    from .contact import _surface_from

    surface = _surface_from(args)
    E_star = effective_modulus_from(args)
    if args.law == "elastic":
        if args.psi is not None or args.Y is not None:
            raise CLIError("--psi / --yield-strength need --law elastoplastic")
        law = {"E_star": E_star}
    else:
        law = {"material": resolve_material(surface, E_star=E_star, psi=args.psi, Y=args.Y,
                                            **EP_DEFAULTS)}
    if (args.mu is None) != (args.kt_over_kn is None):
        raise CLIError("--mu and --kt-over-kn go together (the *FRICTION block needs both)")
    if args.mu is not None and args.fmt == "csv":
        raise CLIError("--mu: the csv format has no friction block")
    if args.mu is not None and args.p0 is None:
        raise CLIError("--mu needs --seating-pressure (k_T is taken at p0)")
    max_rows = CALCULIX_MAX_ROWS if args.fmt == "calculix" else args.max_rows
    if args.fmt == "calculix" and args.max_rows is not None:
        max_rows = min(args.max_rows, CALCULIX_MAX_ROWS)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = overclosure_table(surface, pressure_range=args.pressure_range, rtol=args.rtol,
                                  reference="mean-plane" if args.p0 is None else "seating",
                                  seating_pressure=args.p0, max_rows=max_rows, **law)
        scales = {"length_scale": args.length_scale, "stress_scale": args.stress_scale}
        friction = "" if args.mu is None else friction_block(table, args.fmt, args.mu, args.kt_over_kn, **scales)
        text = format_table(table, args.fmt, length_unit=args.length_unit, stress_unit=args.stress_unit,
                            friction=friction, **scales)
    if args.output:
        Path(args.output).write_text(text)
    return {
        "format": args.fmt,
        **table.summary(),
        "law": args.law,
        "moments": surface.as_dict(),
        "moments_unit": args.moments_unit,
        "length_scale": args.length_scale, "stress_scale": args.stress_scale,
        "units": {"pressure": args.stress_unit, "overclosure": args.length_unit,
                  "h_ref": "the moments' length unit", "zero_pressure_overclosure": "the moments' length unit"},
        "friction": None if args.mu is None else {"mu": args.mu, "kT_over_kN": args.kt_over_kn},
        "cannot_express": CANNOT_EXPRESS[args.fmt],
        "output": args.output,
        "table": [[float(p) * args.stress_scale, float(c) * args.length_scale]
                  for p, c in zip(table.pressure, table.overclosure)],
        "text": text,
        "warnings": relay_warnings(caught),
    }


def _render_export(payload: dict[str, Any]) -> str:
    if payload["output"] is None:
        out = payload["text"].rstrip("\n")
    else:
        out = (f"wrote {payload['rows']} rows ({payload['format']}) to {payload['output']}: within rtol = "
               f"{payload['rtol']:g} of the {payload['level']} law (max measured {payload['max_error']:.3g}) for "
               f"pressures {payload['pressure_range'][0]:g} ... {payload['pressure_range'][1]:g}; reference "
               f"{payload['reference']}")
        out += "".join(f"\nnot expressed: {m}" for m in payload["cannot_express"])
    return out + "".join(f"\nwarning: {m}" for m in payload["warnings"])
