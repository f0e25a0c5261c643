"""The commands from a surface to an FE code: ``export`` (the law as an Abaqus / CalculiX / CSV
pressure–overclosure table) and ``export-law`` (a LAW.yaml interaction's full law, friction
included, as Fortran: interface.fortran_export, docs/fortran-law.md). The moments of a measured
map: :mod:`.moments`."""

from __future__ import annotations

import math
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
    """Register ``export`` (moments and output parents) and ``export-law`` (output parent)."""
    _add_export(sub, parents)
    _add_export_law(sub, parents[1:])


def _add_export(sub, parents) -> None:
    p = sub.add_parser(
        "export", parents=parents, help="pressure-overclosure table for Abaqus, CalculiX or CSV",
        description="The statistical law as a pressure-overclosure table whose piecewise-linear "
        "interpolation stays within --rtol of the law for pressures in --pressure-range; first row at "
        "zero pressure; overclosure zero at the seating pressure (--seating-pressure) or the mean "
        "planes. Without -o the table is printed. --law-table FILE: the BEM's law of "
        "`roughcontact bem ... --law-table FILE` instead of the moments (E* and the length unit the table's).")
    _add_modulus_options(p)
    for group in p._mutually_exclusive_groups:  # E* is the table's with --law-table (checked in _run_export)
        group.required = False
    p.add_argument("--law-table", dest="law_table", type=Path, default=None, metavar="FILE",
                   help="the BEM law table (JSON of `roughcontact bem --law-table`) instead of the moments and "
                   "--law; its pressures are in the unit of its E* (--E-star, if given, must agree within 1 %%)")
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
    from ..contact.validity import relay_warnings
    from ..interface.export import (CALCULIX_MAX_ROWS, NonFiniteTableError, format_table, friction_block,
                                    overclosure_table, stick_stiffness, unit_name)

    if args.law_table is not None:
        surface, law = _bem_law(args)
    elif args.E_star is None and args.E1 is None:
        raise CLIError("one of the arguments --E-star --E1 is required (or --law-table FILE)")
    else:
        surface, law = _statistical_law(args)
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
        table = overclosure_table(None if "law" in law else surface, pressure_range=args.pressure_range, rtol=args.rtol,
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
        "law_table": None if args.law_table is None else {
            "file": str(args.law_table), "samples": table.law.n_evaluations,
            "error_estimate": {"pressure": table.law.max_error_pressure, "stiffness": table.law.max_error_stiffness},
            "note": "the rows are within rtol of the BEM law's interpolant; its own estimated error adds"},
        "output": None if args.output is None else str(args.output),
        "table": [[float(p) * args.stress_scale, float(c) * length_scale]
                  for p, c in zip(table.pressure, table.overclosure)],
        "text": text,
        "warnings": relay_warnings(caught),
    }


def _statistical_law(args):
    """(moments, {"E_star"} or {"material"}) of the moments options, E* and --law."""
    from ..contact.closures import resolve_material
    from .contact import _surface_from

    surface = _surface_from(args)  # a --moments file that states its unit sets args.moments_unit
    args.moments_unit = args.moments_unit or "um"
    E_star = effective_modulus_from(args)
    if args.law == "elastic":
        if args.psi is not None or args.Y is not None:
            raise CLIError("--psi / --yield-strength need --law elastoplastic")
        return surface, {"E_star": E_star}
    return surface, {"material": resolve_material(surface, E_star=E_star, psi=args.psi, Y=args.Y, **EP_DEFAULTS)}


def _bem_law(args):
    """(moments, {"law": NormalLawTable}) of --law-table: the BEM's law (bem.law_table), in the
    table's length unit (--moments-unit, if given, must be it) and the unit of its E* (--E-star
    or --E1 …, if given, must agree within fe.laws.UNIT_RTOL)."""
    from ..bem.law_table import normal_law_table, read_law_table
    from ..fe.laws import UNIT_RTOL

    given = [f"--{n}" for n in ("m00", "m20", "m02", "m40", "m04") if getattr(args, n) is not None]
    given += ["--moments"] * bool(getattr(args, "moments_files", None))
    given += ["--second-surface"] * (args.second_surface is not None)
    given += [f"--{o}" for o, v in (("law", args.law != "elastic"), ("psi", args.psi is not None),
                                    ("yield-strength", args.Y is not None)) if v]
    if given:
        raise CLIError(f"--law-table replaces the moments and the statistical law: drop {' '.join(given)}")
    try:
        samples = read_law_table(args.law_table)
        law = normal_law_table(samples)
    except ValueError as exc:
        raise CLIError(f"--law-table: {exc}") from None
    if args.moments_unit not in (None, samples.length_unit):
        raise CLIError(f"--moments-unit {args.moments_unit} contradicts the table's length unit {samples.length_unit}")
    args.moments_unit = samples.length_unit
    if args.E_star is not None or args.E1 is not None:
        E = effective_modulus_from(args)
        if abs(E / samples.E_star - 1.0) > UNIT_RTOL:
            raise CLIError(f"E* = {E:g} differs from the table's {samples.E_star:g} ({args.law_table}) by more than "
                           f"{100 * UNIT_RTOL:g} %: the ladder was solved with its own")
    # the table's end pressures exp(ln p) differ from the ladder's by rounding: its ends as given
    lo, hi = args.pressure_range
    lo = law.p_light if math.isclose(lo, law.p_light, rel_tol=1e-12) else lo
    hi = law.p_max if math.isclose(hi, law.p_max, rel_tol=1e-12) else hi
    args.pressure_range = [lo, hi]
    if not (law.p_light <= lo and hi <= law.p_max):
        raise CLIError(f"--pressure-range {lo:g} {hi:g} reaches beyond the BEM table's pressures {law.p_light:g} ... "
                       f"{law.p_max:g} ({args.law_table}): its law holds in the ladder's range only")
    args.law = "bem"
    return law.surface, {"law": law}


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
        bem = payload["law_table"]
        if bem is not None:
            out += (f"\nthe BEM law of {bem['file']} ({bem['samples']} samples): its interpolant's estimated error "
                    f"{bem['error_estimate']['pressure']:.2g} in p, {bem['error_estimate']['stiffness']:.2g} in k "
                    "adds to rtol")
        out += "".join(f"\nnot expressed: {m}" for m in payload["cannot_express"])
    return out + "".join(f"\nwarning: {m}" for m in payload["warnings"])


def _add_export_law(sub, parents) -> None:
    p = sub.add_parser(
        "export-law", parents=parents, help="a law file's interface law (friction included) as Fortran (Abaqus UINTER)",
        description="The law of one interaction of LAW.yaml (the file of `fe run --interface`) as Fortran: "
        "roughcontact_law.f90 (the normal law and the friction return mapping, a port of the engine's kernels), "
        "roughcontact_law_data.f90 (this law's table and parameters) and uinter.f90 (an Abaqus UINTER; not run "
        "inside Abaqus), written to the directory -o DIR (docs/fortran-law.md). E*: the law file's E_star, else "
        "--E-star or --E1/--nu1/--E2/--nu2 (the two bodies' moduli, eq. (42), as fe run takes them from the deck).")
    p.add_argument("law_file", type=Path, metavar="LAW.yaml", help="the law file (docs/own-model.md)")
    p.add_argument("--interaction", default=None, metavar="NAME",
                   help="the interaction to export (default: the only one of the file)")
    p.add_argument("--format", dest="fmt", choices=("fortran",), default="fortran", help="the output (fortran)")
    _add_modulus_options(p)
    for group in p._mutually_exclusive_groups:  # E* may come from the law file
        group.required = False
    p.add_argument("-o", "--output", type=Path, required=True, metavar="DIR",
                   help="directory for the three .f90 files (created if its parent exists)")
    p.set_defaults(func=_run_export_law, render=_render_export_law)


def _run_export_law(args) -> dict[str, Any]:
    from ..fe.laws import LawError, mindlin_poisson, read_law_file
    from ..interface.fortran_export import DATA_FILE, SOURCES, fortran_source, law_data_module

    if args.second_surface is not None:
        raise CLIError("--second-surface: the moments are the law file's")
    try:
        laws = read_law_file(args.law_file)
    except (LawError, ValueError) as exc:
        raise CLIError(str(exc)) from None
    names = sorted(laws.interactions)
    name = (args.interaction or (names[0] if len(names) == 1 else "")).upper()
    if name not in laws.interactions:
        raise CLIError(f"--interaction: {'give one of' if args.interaction is None else 'no ' + repr(args.interaction) + ' in'} "
                       f"{args.law_file} ({', '.join(names)})")
    law = laws.interactions[name]
    nu = None
    if law.E_star is not None:
        if args.E_star is not None or args.E1 is not None:
            raise CLIError(f"{args.law_file} gives E_star = {law.E_star:g} for {name}: drop --E-star/--E1")
        E_star = law.E_star
    elif args.E_star is None and args.E1 is None:
        raise CLIError(f"{args.law_file} gives no E_star for {name}: give --E-star or --E1/--nu1 [--E2/--nu2] "
                       "(the two bodies' moduli)")
    else:
        E_star = effective_modulus_from(args)
        if args.E1 is not None and math.isfinite(args.E2):
            nu = mindlin_poisson(args.E1, args.nu1, args.E2, args.nu2)
        elif args.E1 is not None:
            nu = args.nu1
    try:
        material = law.material(laws.length_unit, E_star, nu)
    except (LawError, ValueError) as exc:
        raise CLIError(str(exc)) from None
    if not (args.output.is_dir() or args.output.parent.is_dir()):
        raise CLIError(f"-o {args.output}: no such directory {str(args.output.parent)!r} (only the last part is created)")
    header = (f"law file {args.law_file}, interaction {name}, E* = {E_star!r} (deck stress unit), "
              f"deck length {laws.length_unit}, law length {law.moments_unit}",)
    texts = {DATA_FILE: law_data_module(material.normal, material.model, interaction=name,
                                        law_per_deck=material.length_per_mm, lay_direction=law.lay_direction,
                                        tangential_form=material.tangential_form, header=header)}
    texts.update({source: fortran_source(source) for source in SOURCES})
    try:
        args.output.mkdir(exist_ok=True)
    except OSError as exc:
        raise CLIError(f"-o {args.output}: cannot create it ({exc.strerror or exc})") from None
    files = []
    for file in (SOURCES[0], DATA_FILE, SOURCES[1]):  # compilation order
        with writing(args.output / file, "-o") as tmp:
            tmp.write_text(texts[file], encoding="utf-8")
        files.append(str(args.output / file))
    normal = material.normal
    return {
        "format": args.fmt, "interaction": name, "law_file": str(args.law_file), "files": files,
        "model": type(material.model).__name__, "E_star": E_star, "tangential_form": material.tangential_form,
        "law_per_deck": material.length_per_mm, "rows": int(normal.extrapolated().kernel_data()[0].shape[0]),
        "p0": normal.p0, "p_max": normal.table.p_max, "u_max": normal.u_max, "u_open": normal.u_open,
        "units": {"pressure": "deck stress unit (that of E*)", "u": law.moments_unit, "deck_length": laws.length_unit},
    }


def _render_export_law(payload: dict[str, Any]) -> str:
    u = payload["units"]["u"]
    return (f"wrote {', '.join(payload['files'])}: interaction {payload['interaction']} ({payload['model']}, "
            f"{payload['tangential_form']}), {payload['rows']} table rows; seating pressure {payload['p0']:.6g} at u_N = 0, "
            f"open below u_N = {payload['u_open']:.6g} {u}, tabulated up to p_max = {payload['p_max']:.6g} "
            f"(u_N = {payload['u_max']:.6g} {u}; beyond: the tangent tail, check the contact pressures)\n"
            "compile in this order: roughcontact_law.f90 roughcontact_law_data.f90 uinter.f90 (docs/fortran-law.md)")
