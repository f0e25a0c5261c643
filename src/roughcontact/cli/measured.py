"""The command from a surface to an FE code: ``export`` (the law as an Abaqus / CalculiX / CSV
pressure–overclosure table). The moments of a measured map: :mod:`.moments`."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

from . import (
    CLIError, EP_DEFAULTS, _add_modulus_options, _real, effective_modulus_from, output_file, writing,
)

__all__ = ["add_commands"]

FORMATS = ("abaqus", "calculix", "csv")  # interface.export.FORMATS
#: what the table of each format cannot express; the k_T(p) entry applies with --mu only
#: (:func:`_cannot_express` adds it, naming the pressure k_T is taken at)
CANNOT_EXPRESS = {
    "abaqus": ["the orthotropic / hardening friction of section 8.1",
               "elasto-plastic unloading (the table is the loading curve)"],
    "calculix": ["the orthotropic / hardening friction of section 8.1",
                 "elasto-plastic unloading (the table is the loading curve)",
                 "more than 200 rows (resampled evenly in overclosure) and pressures beyond the last row (held constant)"],
    "csv": [],
}
#: the k_T(p) entry of CANNOT_EXPRESS, with the pressure P of k_T(P) (--kt-at or its default)
KT_CANNOT_EXPRESS = {
    "abaqus": "k_T(p): the stick stiffness follows k_N(p); *FRICTION takes one elastic slip: k_T matches only at p = {p}",
    "calculix": "k_T(p): *FRICTION takes one stick slope: k_T at p = {p}",
}


def _cannot_express(fmt: str, stick: dict | None, kt_at_given: bool) -> list[str]:
    """CANNOT_EXPRESS of ``fmt``, with the k_T(p) entry where a *FRICTION block is written
    (``stick``: interface.export.stick_stiffness), naming the pressure k_T is taken at."""
    if stick is None:
        return list(CANNOT_EXPRESS[fmt])
    where = f"{stick['pressure']:.6g}" + (", from --kt-at" if kt_at_given else ", the default (the geometric middle)")
    return [KT_CANNOT_EXPRESS[fmt].format(p=where), *CANNOT_EXPRESS[fmt]]


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
    p.add_argument("--moments-unit", dest="moments_unit", default=None, metavar="NAME",
                   help="length unit of the moments (default: the --moments file's, else um); with a known "
                   "--length-unit (m, mm, um, nm) the overclosures are converted")
    p.add_argument("--length-unit", dest="length_unit", default=None, metavar="NAME",
                   help="output length unit (default: the moments' unit); m, mm, um, nm are converted from "
                   "--moments-unit, any other name needs --length-scale")
    p.add_argument("--length-scale", dest="length_scale", type=_real, default=None, metavar="F",
                   help="multiply overclosures by F (e.g. 1e-3: moments in um, FE model in mm); must agree with the "
                   "units where both are known")
    p.add_argument("--stress-scale", dest="stress_scale", type=_real, default=1.0, metavar="G",
                   help="multiply pressures by G (e.g. 1e6: E* in N/mm^2 = MPa, FE model in Pa)")
    p.add_argument("--stress-unit", dest="stress_unit", default="unit of E*", metavar="NAME",
                   help="name of the output stress unit")
    p.add_argument("--mu", type=_real, default=None, help="Coulomb friction coefficient: adds a *FRICTION block")
    p.add_argument("--kt-over-kn", dest="kt_over_kn", type=_real, default=None, metavar="A",
                   help="k_T/k_N: the stick stiffness k_T(P) = A k_N(P) (with --mu)")
    p.add_argument("--kt-at", dest="kt_at", type=_real, default=None, metavar="P",
                   help="the pressure P (unit of E*) of k_T(P) (with --mu; default: where k_N is the geometric mean of "
                   "its values at the ends of --pressure-range, the constant with the smallest largest factor error "
                   "over the range); the k_T(p) range is printed")
    p.add_argument("--max-rows", dest="max_rows", type=int, default=None, metavar="N",
                   help="fail if more rows are needed (calculix: 200 always)")
    p.add_argument("-o", "--output", type=output_file, default=None, metavar="FILE", help="write the table to FILE")
    p.set_defaults(func=_run_export, render=_render_export)


def _run_export(args) -> dict[str, Any]:
    from ..contact.closures import resolve_material
    from ..contact.validity import relay_warnings
    from ..interface.export import (CALCULIX_MAX_ROWS, NonFiniteTableError, format_table, friction_block,
                                    overclosure_table, stick_stiffness, unit_name)
    from .contact import _surface_from

    surface = _surface_from(args)  # a --moments file that states its unit sets args.moments_unit
    args.moments_unit = args.moments_unit or "um"
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
    if args.kt_at is not None and args.mu is None:
        raise CLIError("--kt-at goes with --mu and --kt-over-kn (the *FRICTION block)")
    length_scale, length_unit = export_length_units(args, args.moments_unit)
    unit_name("--stress-unit", args.stress_unit)
    max_rows = CALCULIX_MAX_ROWS if args.fmt == "calculix" else args.max_rows
    if args.fmt == "calculix" and args.max_rows is not None:
        max_rows = min(args.max_rows, CALCULIX_MAX_ROWS)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = overclosure_table(surface, pressure_range=args.pressure_range, rtol=args.rtol,
                                  reference="mean-plane" if args.p0 is None else "seating",
                                  seating_pressure=args.p0, max_rows=max_rows, **law)
        scales = {"length_scale": length_scale, "stress_scale": args.stress_scale}
        friction, stick = "", None
        try:  # every row checked before any text is made: nothing is written or printed otherwise
            if args.mu is not None:
                friction = friction_block(table, args.fmt, args.mu, args.kt_over_kn, kt_at=args.kt_at, **scales)
                stick = stick_stiffness(table, args.kt_over_kn, args.kt_at, **scales)
            text = format_table(table, args.fmt, length_unit=length_unit, stress_unit=args.stress_unit,
                                moments_unit=args.moments_unit, friction=friction, **scales)
        except NonFiniteTableError as exc:  # a computed value that is not finite: exit 1
            written = "no table printed" if args.output is None else f"-o {args.output} not written"
            raise CLIError(f"{exc} ({written}; check --stress-scale and --length-scale)", code=1) from None
    if args.output is not None:
        with writing(args.output, "-o") as tmp:
            tmp.write_text(text)
    return {
        "format": args.fmt,
        **table.summary(),
        "law": args.law,
        "moments": surface.as_dict(),
        "moments_unit": args.moments_unit,
        "length_scale": length_scale, "stress_scale": args.stress_scale,
        "units": {"pressure": args.stress_unit, "overclosure": length_unit, "moments": args.moments_unit,
                  "h_ref": args.moments_unit, "zero_pressure_overclosure": args.moments_unit,
                  "k_T": f"{args.stress_unit}/{length_unit}"},
        "friction": None if stick is None else {
            "mu": args.mu, "kT_over_kN": args.kt_over_kn, "kt_at": stick["pressure"], "k_T": stick["k_T"],
            "k_T_range": [list(r) for r in stick["range"]], "k_T_factor": stick["factor"],
            "kt_at_default": args.kt_at is None},
        "cannot_express": _cannot_express(args.fmt, stick, args.kt_at is not None),
        "output": None if args.output is None else str(args.output),
        "table": [[float(p) * args.stress_scale, float(c) * length_scale]
                  for p, c in zip(table.pressure, table.overclosure)],
        "text": text,
        "warnings": relay_warnings(caught),
    }


def export_length_units(args, moments_unit: str) -> tuple[float, str]:
    """(length scale, output length unit) of the export from --length-unit and --length-scale
    and the moments' unit (``--moments-unit``; a moments file that states its unit overrides it):
    known units (interface.export.LENGTH_UNITS) are converted, and a --length-scale must agree;
    another name needs --length-scale; without --length-unit the output is in the moments' unit."""
    from ..interface.export import length_scale_between, unit_name

    unit_name("--moments-unit", moments_unit)
    if args.length_unit is None:
        if args.length_scale is not None:
            raise CLIError("--length-scale needs --length-unit (the name of the unit it converts to)")
        return 1.0, moments_unit
    unit_name("--length-unit", args.length_unit)
    try:
        return length_scale_between(moments_unit, args.length_unit, args.length_scale), args.length_unit
    except ValueError as exc:
        raise CLIError(f"--length-unit {args.length_unit}: {exc}") from None


def _render_export(payload: dict[str, Any]) -> str:
    if payload["output"] is None:
        out = payload["text"].rstrip("\n")
    else:
        out = (f"wrote {payload['rows']} rows ({payload['format']}) to {payload['output']}: within rtol = "
               f"{payload['rtol']:g} of the {payload['level']} law (max measured {payload['max_error']:.3g}) for "
               f"pressures {payload['pressure_range'][0]:g} ... {payload['pressure_range'][1]:g}; reference "
               f"{payload['reference']}")
        f = payload["friction"]
        if f is not None:
            (p_lo, k_lo), (p_hi, k_hi) = f["k_T_range"]
            kt = payload["units"]["k_T"]
            out += (f"\nfriction: mu = {f['mu']:g}, k_T = {f['k_T']:.6g} {kt} at p = {f['kt_at']:.6g}"
                    f"{' (default: the geometric middle of k_T over the range)' if f['kt_at_default'] else ''}; "
                    f"the law's k_T(p) runs from {k_lo:.4g} at p = {p_lo:.4g} to {k_hi:.4g} at p = {p_hi:.4g} "
                    f"(factor {f['k_T_factor']:.3g})")
        out += "".join(f"\nnot expressed: {m}" for m in payload["cannot_express"])
    return out + "".join(f"\nwarning: {m}" for m in payload["warnings"])
