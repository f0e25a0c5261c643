"""``roughcontact bem SCAN``: the boundary-element solution (ContactMechanics, extra ``[bem]``) of
a rigid flat on a height map, read as ``moments`` reads it, beside the statistical model of the
same surface from its measured moments (docs/bem-scan.md; library: roughcontact.bem.scan).

    roughcontact bem SCAN --E-star E (--pressure P [P ...] | --pressure-range LO HI [--n-pressures N])
                     [--periodic] [--stress-unit U] [--law-table FILE] [--quiet] [--json]
                     [--unit um] [--dx DX] [--dy DY] [--xy-unit U] [--z-unit U] [--z-scale F]
                     [--layout auto|grid|xyz] [--channel N] [--detrend plane|...] [--fill none|harmonic]

Progress (one line per pressure) on stderr unless --quiet. Without the extra: one line
(roughcontact.bem.solver.SKIP_MESSAGE), exit 2 (as a missing extra [measure] for instrument files).
"""

from __future__ import annotations

import hashlib
import math
import sys
import warnings
from typing import Any

from . import CLIError, _real, output_file
from .moments import DETRENDS, _json_safe, _map_in_unit, add_map_options

__all__ = ["add_command"]

SOLVER_NAME = "ContactMechanics constrained conjugate gradients (Polonsky & Keer 1999), FFT half-space (Stanley & Kato 1997)"


def add_command(sub, parents) -> None:
    """Register ``bem`` (on the output parent)."""
    p = sub.add_parser(
        "bem", parents=parents, help="boundary-element contact of a height map, beside the statistical model",
        description="The elastic contact of a rigid flat with the height map (form removed as by `moments`), solved by "
        "the boundary-element method (ContactMechanics, extra [bem]) at each nominal pressure: the area fraction, "
        "the mean gap, the normal stiffness per nominal area -dp/dgap and the solver's residuals; and the statistical "
        "model's numbers (from the map's measured moments) beside them, with the ratios BEM/model. A measured scan "
        "is solved with the free-boundary (padded) solver; --periodic declares the map one cell of a periodic "
        "surface. docs/bem-scan.md.")
    p.add_argument("file", help="height map: .npy, text grid or x y z points, .gsf, or an instrument file")
    p.add_argument("--E-star", dest="E_star", type=_real, required=True, metavar="E",
                   help="contact modulus E* (eq. 42); the pressures are in its unit")
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--pressure", type=_real, nargs="+", metavar="P",
                       help="nominal pressures W/A0, increasing (unit of --E-star)")
    where.add_argument("--pressure-range", dest="pressure_range", type=_real, nargs=2, metavar=("LO", "HI"),
                       help="a ladder evenly spaced in ln p from LO to HI (4 per decade by default: dense enough "
                       "for --law-table)")
    p.add_argument("--n-pressures", dest="n_pressures", type=int, default=None, metavar="N",
                   help="pressures of --pressure-range (default 4 per decade, at least 3)")
    p.add_argument("--periodic", action="store_true",
                   help="the map is one cell of a periodic surface (synthetic maps): periodic solver; default: "
                   "free boundary (the map is a patch on an unbounded half-space, padded to 2nx x 2ny)")
    p.add_argument("--stress-unit", dest="stress_unit", default=None, metavar="U",
                   help="name of the unit of --E-star, for the output (default: stated as 'unit of --E-star')")
    p.add_argument("--law-table", dest="law_table", type=output_file, default=None, metavar="FILE",
                   help="write the ladder as a BEM law table (JSON) for LAW.yaml's normal: {table: FILE} and "
                   "export --law-table; use a dense ladder (--pressure-range)")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    add_map_options(p)  # the reading options of `moments` (same names and meaning)
    p.add_argument("--detrend", choices=DETRENDS, default=None,
                   help="the form removed before the BEM and the moments (default: plane; with --periodic the mean, "
                   "since a plane taken from a periodic cell would put a step at its edges)")
    p.add_argument("--fill", choices=("none", "harmonic"), default="none",
                   help="missing points: refused (none, default: the BEM needs a complete grid) or harmonic (Laplace fill)")
    p.set_defaults(func=_run_bem, render=_render_bem)


def _pressures(args):
    import numpy as np

    from ..bem.scan import pressure_ladder

    if args.pressure is not None:
        if args.n_pressures is not None:
            raise CLIError("--n-pressures goes with --pressure-range, not with --pressure")
        p = np.asarray(args.pressure, dtype=float)
        if not (np.all(np.isfinite(p) & (p > 0)) and np.all(np.diff(p) > 0)):
            raise CLIError(f"--pressure: the pressures must be positive and increasing, got {' '.join(f'{x:g}' for x in p)}")
        return p
    try:
        return pressure_ladder(*args.pressure_range, args.n_pressures)
    except ValueError as exc:
        raise CLIError(f"--pressure-range: {exc}") from None


def _progress(n):
    def report(i, p, info):
        print(f"bem: W/A0 = {p:g} ({i + 1}/{n}): A/A0 = {info['area_fraction']:.5g}, {info['iterations']} iterations, "
              f"{info['seconds']:.1f} s", file=sys.stderr, flush=True)
    return report


def _run_bem(args) -> dict[str, Any]:
    import numpy as np

    from .. import limits
    from ..bem.scan import bem_of_scan
    from ..bem.solver import SKIP_MESSAGE, BEMConvergenceError, BEMNotInstalled, available
    from ..contact.validity import relay_warnings
    from ..fe.laws import STRESS_UNITS
    from ..interface.normal_law_samples import MIN_SAMPLES
    from ..readers.lengths import normalise

    if not (math.isfinite(args.E_star) and args.E_star > 0):
        raise CLIError(f"--E-star: the contact modulus must be a positive finite number, got {args.E_star:g}")
    pressures = _pressures(args)
    if args.law_table is not None and pressures.size < MIN_SAMPLES:
        raise CLIError(f"--law-table needs at least {MIN_SAMPLES} pressures (the law's error estimate leaves every "
                       f"other one out), got {pressures.size}: use --pressure-range")
    if args.stress_unit is not None and args.stress_unit not in STRESS_UNITS:
        raise CLIError(f"--stress-unit {args.stress_unit}: not one of {', '.join(STRESS_UNITS)} (the units a law "
                       "file converts)")
    if not available():  # before reading a large map
        raise CLIError(SKIP_MESSAGE)
    unit = normalise(args.unit)
    if args.detrend is None:
        args.detrend = "mean" if args.periodic else "plane"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        z, dx, dy, source = _map_in_unit(args)
        missing = int(np.count_nonzero(~np.isfinite(z)))
        if missing and args.fill != "harmonic":
            raise CLIError(f"{args.file}: {missing} of {z.size} points are missing; the BEM needs a complete grid: "
                           "pass --fill harmonic to fill them")
        try:
            r = bem_of_scan(z, dx, dy, E_star=args.E_star, pressures=pressures, periodic=args.periodic,
                            detrend=args.detrend, fill=args.fill, progress=None if args.quiet else _progress(pressures.size))
        except BEMNotInstalled:
            raise CLIError(SKIP_MESSAGE) from None
        except BEMConvergenceError as exc:
            raise CLIError(f"{args.file}: {exc}", code=1) from None
        except ValueError as exc:
            raise CLIError(f"{args.file}: {exc}") from None
    stress = args.stress_unit or "unit of --E-star"
    solver = {"name": SOLVER_NAME, "boundary": r.boundary, **r.settings.as_dict(),
              "stiffness_method": _stiffness_method(r.stiffness_step)}
    sha = hashlib.sha256(limits.read_bytes(args.file, "height map")).hexdigest()
    source.update({"sha256": sha, "shape": list(z.shape), "dx": dx, "dy": dy, "detrend": args.detrend,
                   "form": r.form, "fill": args.fill, "missing_fraction": r.missing_fraction})
    moments = {**{k: r.moment_values[k] for k in ("m00", "m20", "m02", "m40", "m04")}, "unit": unit,
               "lay_angle_deg": r.lay_angle_deg}
    model = None
    if r.model is not None:
        model = {"name": "BGK with exact Hertz functions (eqs. (52), (53), (55)) from the measured moments",
                 **{k: r.model[k].tolist() for k in ("area_fraction", "mean_gap", "s", "stiffness")},
                 "warnings": list(r.model_warnings)}
    payload = {
        "pressure": r.pressure.tolist(), "area_fraction": r.area_fraction.tolist(), "mean_gap": r.mean_gap.tolist(),
        "stiffness": r.stiffness.tolist(),
        "length_unit": unit, "stress_unit": stress, "E_star": args.E_star, "periodic": r.periodic, "solver": solver,
        "residual": {"penetration": r.penetration_residual.tolist(), "tensile_force": r.force_residual.tolist()},
        "iterations": r.iterations.tolist(), "seconds": r.seconds.tolist(),
        "model": model, "model_error": r.model_error,
        "ratio": None if r.ratio is None else {k: v.tolist() for k, v in r.ratio.items()},
        "moments": moments, "source": source,
        "units": {"pressure": stress, "mean_gap": unit, "stiffness": f"({stress})/{unit}", "area_fraction": "1",
                  "residual": "penetration: of the rms height; tensile_force: of the mean force per point",
                  "ratio": "BEM/model", "moments": f"m00 {unit}^2; m20, m02 1; m40, m04 1/{unit}^2"},
    }
    if args.law_table is not None:
        _write_law_table(args, r, payload)
        payload["law_table"] = str(args.law_table)
    payload["warnings"] = relay_warnings(caught) + [f"model: {w}" for w in r.model_warnings]
    return _json_safe(payload)


def _stiffness_method(eps: float) -> str:
    return (f"central difference of the mean gap over ln p at p*exp(+-{eps:g}) (+-{100 * eps:.3g} % in p), "
            "each side solve warm-started")


def _write_law_table(args, r, payload) -> None:
    from ..bem.law_table import BEMLawSamples, write_law_table
    from ..write_errors import WriteError

    if r.moments is None:
        raise CLIError(f"--law-table: {r.model_error}")
    try:
        samples = BEMLawSamples(
            pressure=r.pressure, mean_gap=r.mean_gap, stiffness=r.stiffness, area_fraction=r.area_fraction,
            length_unit=payload["length_unit"], E_star=float(args.E_star), periodic=r.periodic, moments=r.moments,
            lay_angle_deg=r.lay_angle_deg, stress_unit=args.stress_unit, stiffness_method=payload["solver"]["stiffness_method"],
            source={k: payload["source"][k] for k in ("file", "sha256", "shape", "dx", "dy", "detrend", "fill")},
            solver=payload["solver"])
        write_law_table(args.law_table, samples, provenance={"command": "roughcontact bem"})
    except ValueError as exc:
        raise CLIError(f"--law-table: {exc}") from None
    except WriteError as exc:
        raise CLIError(f"--law-table: {exc}") from None


def _row(name, values, fmt=".6g"):
    return f"{name:<22}" + "".join(f"{v:>14{fmt}}" if v is not None else f"{'-':>14}" for v in values)


def _render_bem(payload: dict[str, Any]) -> str:
    L, S = payload["length_unit"], payload["stress_unit"]
    lines = [f"BEM ({payload['solver']['boundary']}) of {payload['source']['file']} "
             f"({payload['source']['shape'][0]} x {payload['source']['shape'][1]}, dx = {payload['source']['dx']:g} {L}, "
             f"dy = {payload['source']['dy']:g} {L}), E* = {payload['E_star']:g} {S}",
             _row("W/A0 [stress]", payload["pressure"]),
             _row("A/A0", payload["area_fraction"]),
             _row(f"mean gap [{L}]", payload["mean_gap"]),
             _row(f"K/A0 [stress/{L}]", payload["stiffness"]),
             _row("residual: penetration", payload["residual"]["penetration"], ".2g"),
             _row("residual: tensile", payload["residual"]["tensile_force"], ".2g")]
    m = payload["model"]
    if m is not None:
        lines += ["statistical model (measured moments):",
                  _row("A/A0", m["area_fraction"]), _row(f"h = s sqrt(m00) [{L}]", m["mean_gap"]),
                  _row(f"K/A0 [stress/{L}]", m["stiffness"]),
                  "ratio BEM/model:"] + [_row(k, v, ".4g") for k, v in payload["ratio"].items()]
    else:
        lines.append(f"statistical model: not applicable ({payload['model_error']})")
    mo = payload["moments"]
    lines.append("moments: " + "  ".join(f"{k}={mo[k]:.6g}" for k in ("m00", "m20", "m02", "m40", "m04"))
                 + f"  ({L}; lay {mo['lay_angle_deg']:.3g} deg)")
    lines.append(f"stress unit: {S}; solver: {payload['solver']['name']}; stiffness: {payload['solver']['stiffness_method']}")
    if payload.get("law_table"):
        lines.append(f"law table: {payload['law_table']}")
    lines += [f"note: {n}" for n in payload["source"]["notes"]]
    lines.append(f"warnings: {len(payload['warnings'])}")
    lines += [f"warning: {w}" for w in payload["warnings"]]
    return "\n".join(lines)
