"""The commands from a measured surface to an FE code: ``moments`` (a height map's spectral
moments) and ``export`` (the law as an Abaqus / CalculiX / CSV pressure–overclosure table)."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

import numpy as np

from . import (
    CLIError, EP_DEFAULTS, _MOMENTS, _add_modulus_options, _real, effective_modulus_from, output_file, writing,
)

__all__ = ["add_commands", "read_height_map", "save_height_map", "export_length_units"]

ESTIMATORS = ("spectral", "fd")  # statistics.measure.ESTIMATORS (checked by the tests)
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
    """Register ``moments`` (output parent) and ``export`` (moments and output parents)."""
    _add_moments(sub, parents[1:])
    _add_export(sub, parents)


def _add_moments(sub, parents) -> None:
    p = sub.add_parser(
        "moments", parents=parents, help="spectral moments of a measured height map",
        description="The five moments m00, m20, m02, m40, m04 in the lay frame (x along the lay) of a "
        "height map z[i, j] at x = j*dx, y = i*dy, with the lay angle, m11 before rotation, m22, m31, "
        "m13 and the distance from the model's strong-anisotropy assumption. Angular wavenumbers: "
        "m_pq = integral of qx^p qy^q Phi(q) d2q = the variances of the height derivatives "
        "(docs/fe-export.md).")
    p.add_argument("file", help="height map: .npy, or a text/CSV grid (one row of the map per line)")
    p.add_argument("--dx", type=_real, required=True, metavar="DX", help="sampling interval along x (columns) [L]")
    p.add_argument("--dy", type=_real, default=None, metavar="DY", help="sampling interval along y (rows) [L] (default dx)")
    p.add_argument("--z-scale", dest="z_scale", type=_real, default=1.0, metavar="F",
                   help="multiply the heights by F to express them in the unit of dx (default 1)")
    p.add_argument("--estimator", choices=ESTIMATORS, default="spectral",
                   help="spectral (periodogram, default) or fd (central differences)")
    p.add_argument("--window", choices=("hann", "none"), default="hann",
                   help="spectral estimator's window: hann (default; measured, non-periodic maps) or none (periodic maps)")
    p.add_argument("--detrend", choices=("plane", "mean", "none"), default="plane",
                   help="remove the least-squares plane (default), the mean, or nothing")
    p.add_argument("--lay-angle", dest="lay_angle", type=_real, default=None, metavar="DEG",
                   help="the lay angle if known [deg from the map's x axis]; default: found (m11 = 0)")
    p.add_argument("--length-unit", dest="length_unit", default="L", metavar="NAME",
                   help="name of the unit of dx for the output (e.g. um)")
    p.add_argument("--save-rotated", dest="save_rotated", type=output_file, default=None, metavar="FILE",
                   help="write the map rotated into the lay frame (x along the lay; NaN outside the map) to FILE: "
                   "NumPy .npy, or a text grid (.csv comma-separated, any other name whitespace-separated) "
                   "that `roughcontact moments` reads back")
    p.set_defaults(func=_run_moments, render=_render_moments)


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
    p.add_argument("--moments-unit", dest="moments_unit", default="um", metavar="NAME",
                   help="length unit of the moments (default um); with a known --length-unit (m, mm, um, nm) the "
                   "overclosures are converted")
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


# ---------------------------------------------------------------------------------------
def read_height_map(path: str) -> np.ndarray:
    """A 2-d height map from .npy or a text/CSV grid (comma, semicolon or whitespace separated,
    '#' comments)."""
    file = Path(path)
    if not file.is_file():
        raise CLIError(f"no such file: {path}")
    if file.suffix.lower() == ".npy":
        z = np.load(file, allow_pickle=False)
    else:
        text = file.read_text()
        first = next((line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")), "")
        delimiter = "," if "," in first else (";" if ";" in first else None)
        try:
            z = np.loadtxt(file, delimiter=delimiter, comments="#", ndmin=2)
        except ValueError as exc:
            raise CLIError(f"{path}: not a numeric grid ({exc})") from None
    return np.asarray(z, dtype=float)


def save_height_map(path: Path, z: np.ndarray, option: str) -> None:
    """Write a height map to exactly ``path`` (atomically): .npy as NumPy's format, any other
    name as a text grid that :func:`read_height_map` reads back (.csv comma-separated, else
    whitespace; NaN written as "nan")."""
    with writing(path, option) as tmp:
        if path.suffix.lower() == ".npy":
            with open(tmp, "wb") as f:  # a file object: np.save appends no ".npy" to the name
                np.save(f, z, allow_pickle=False)
        else:
            np.savetxt(tmp, z, delimiter="," if path.suffix.lower() == ".csv" else " ", fmt="%.17g")


def _run_moments(args) -> dict[str, Any]:
    from ..contact.validity import relay_warnings
    from ..statistics.measure import measure_heights, rotate_map

    z = read_height_map(args.file) * args.z_scale
    options = {"estimator": args.estimator, "window": args.window, "detrend": args.detrend}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = measure_heights(z, args.dx, args.dy, lay_angle_deg=args.lay_angle, **options)
        # the band-limit dependence: the same map sampled at twice the interval, same lay angle
        coarse = None
        if min(z.shape) >= 10:
            try:
                coarse = measure_heights(z[::2, ::2], 2 * r.dx, 2 * r.dy, lay_angle_deg=r.lay_angle_deg,
                                         **options).moments.as_dict()
            except ValueError:  # the coarser map may fall outside the model (mu <= 0)
                coarse = None
        if args.save_rotated is not None:
            save_height_map(args.save_rotated, rotate_map(z, r.dx, r.dy, r.lay_angle_deg), "--save-rotated")
    L = args.length_unit
    return {
        **r.moments.as_dict(),
        "lay_angle_deg": r.lay_angle_deg,
        "m11_map": r.m11_map,
        "m22": r.lay["m22"], "m31": r.lay["m31"], "m13": r.lay["m13"],
        "anisotropy": r.anisotropy(),
        "at_twice_the_interval": coarse,
        "ratio_to_twice_the_interval": None if coarse is None else
        {k: getattr(r.moments, k) / v for k, v in coarse.items()},
        "estimator": r.estimator, "window": r.window, "detrend": r.detrend,
        "dx": r.dx, "dy": r.dy, "shape": list(z.shape),
        "units": {"m00": f"{L}^2", "m20": "1", "m02": "1", "m40": f"1/{L}^2", "m04": f"1/{L}^2",
                  "m11_map": "1", "m22": f"1/{L}^2", "m31": f"1/{L}^2", "m13": f"1/{L}^2",
                  "lay_angle_deg": "deg (from the map's x axis to the lay, counter-clockwise)",
                  "dx": L, "dy": L, "wavenumbers": "angular (rad per unit length), no 2*pi in m_pq",
                  "at_twice_the_interval": "as m00 ... m04: the map sampled at 2 dx, 2 dy (band-limit check)"},
        "warnings": relay_warnings(caught),
    }


def _render_moments(payload: dict[str, Any]) -> str:
    u = payload["units"]
    lines = [f"{k:<24}{payload[k]:>16.8g}  {u[k]}" for k in (*_MOMENTS, "lay_angle_deg", "m11_map", "m22", "m31", "m13")]
    lines += [f"{k:<24}{v:>16.8g}" for k, v in payload["anisotropy"].items()]
    if payload["ratio_to_twice_the_interval"] is not None:
        lines.append("at 2dx, 2dy:  " + "  ".join(f"{k}={v:.6g}" for k, v in payload["at_twice_the_interval"].items()))
        lines.append("ratio dx/2dx: " + "  ".join(f"{k}={v:.4g}" for k, v in payload["ratio_to_twice_the_interval"].items())
                     + "  (far from 1 for m40, m04: the spectrum is not resolved at this scale, docs/fe-export.md)")
    lines += [f"estimator={payload['estimator']}  window={payload['window']}  detrend={payload['detrend']}  "
              f"dx={payload['dx']:g} {u['dx']}  dy={payload['dy']:g} {u['dy']}  shape={payload['shape']}",
              f"wavenumbers: {u['wavenumbers']}", f"warnings: {len(payload['warnings'])}"]
    lines += [f"warning: {m}" for m in payload["warnings"]]
    return "\n".join(lines)


def _run_export(args) -> dict[str, Any]:
    from ..contact.closures import resolve_material
    from ..contact.validity import relay_warnings
    from ..interface.export import (CALCULIX_MAX_ROWS, format_table, friction_block, overclosure_table,
                                    stick_stiffness, unit_name)
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
        if args.mu is not None:
            friction = friction_block(table, args.fmt, args.mu, args.kt_over_kn, kt_at=args.kt_at, **scales)
            stick = stick_stiffness(table, args.kt_over_kn, args.kt_at, **scales)
        text = format_table(table, args.fmt, length_unit=length_unit, stress_unit=args.stress_unit,
                            moments_unit=args.moments_unit, friction=friction, **scales)
    if args.output is not None:
        with writing(args.output, "-o") as tmp:
            tmp.write_text(text)
    return {
        "format": args.fmt,
        **table.summary(),
        "law": args.law,
        "moments": surface.as_dict(),
        "length_scale": length_scale, "stress_scale": args.stress_scale,
        "units": {"pressure": args.stress_unit, "overclosure": length_unit, "moments": args.moments_unit,
                  "h_ref": args.moments_unit, "zero_pressure_overclosure": args.moments_unit,
                  "k_T": f"{args.stress_unit}/{length_unit}"},
        "friction": None if stick is None else {
            "mu": args.mu, "kT_over_kN": args.kt_over_kn, "kt_at": stick["pressure"], "k_T": stick["k_T"],
            "k_T_range": [list(r) for r in stick["range"]], "k_T_factor": stick["factor"],
            "kt_at_default": args.kt_at is None},
        "cannot_express": CANNOT_EXPRESS[args.fmt],
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
