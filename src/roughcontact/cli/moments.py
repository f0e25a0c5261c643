"""``roughcontact moments FILE``: the spectral moments of a measured height map, in a stated
length unit, with the lay, the moments at 1x, 2x, 4x the sampling interval, their uncertainties,
whether the model applies — never refused for being outside the model (exit 0 with warnings)."""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from typing import Any

from . import CLIError, _MOMENTS, _real, output_file, writing

__all__ = ["add_command", "add_map_options"]

ESTIMATORS = ("fd", "spectral")  # statistics.measure.ESTIMATORS (checked by the tests)
DETRENDS = ("plane", "mean", "none", "poly2", "poly3", "poly4", "sphere")  # statistics.measure.DETRENDS (tested)


def add_command(sub, parents) -> None:
    """Register ``moments`` (on the output parent)."""
    p = sub.add_parser(
        "moments", parents=parents, help="spectral moments of a measured height map (x3p, gsf, xyz, csv, npy, ...)",
        description="The five moments m00, m20, m02, m40, m04 in the lay frame (x along the lay) of a measured "
        "height map: m00 = Sq^2 about the fitted plane, the others the variances of the derivative fields "
        "(central differences, around dropouts and edges), rotated as fields; with the lay angle, m22, m31, "
        "m13, the moments at 1x, 2x, 4x the sampling interval, standard uncertainties and whether the model "
        "of the paper applies. Angular wavenumbers (docs/fe-export.md). Instrument formats (x3p, sur, opd, "
        "datx, plu, gwy, ...) need the measure extra (SurfaceTopography).")
    p.add_argument("file", help="height map: .npy, text grid or x y z points (.csv .txt .dat .asc .xyz), .gsf, "
                   "or an instrument file (SurfaceTopography)")
    add_map_options(p)
    p.add_argument("--estimator", choices=ESTIMATORS, default="fd",
                   help="fd (derivative fields of the window, default) or spectral (periodogram; periodic maps)")
    p.add_argument("--order", type=int, choices=(2, 4, 6, 8), default=6, help="accuracy order of the fd stencils (default 6)")
    p.add_argument("--window", choices=("hann", "none"), default="hann",
                   help="spectral estimator's window: hann (default) or none (periodic maps)")
    p.add_argument("--detrend", choices=DETRENDS, default="plane",
                   help="the form removed before the moments (least squares): the plane (default), the mean, nothing, "
                   "a polynomial of total degree 2-4 (poly2 ... poly4: curvature form), or a sphere (its radius is "
                   "reported); what was removed is stated in 'form'")
    p.add_argument("--fill", choices=("none", "harmonic"), default="none",
                   help="missing points: none (the fd stencils avoid them; default) or harmonic (Laplace fill)")
    p.add_argument("--lay-angle", dest="lay_angle", type=_real, default=None, metavar="DEG",
                   help="the lay angle if known [deg from the map's x axis]; default: found (m11 = 0)")
    p.add_argument("--save-rotated", dest="save_rotated", type=output_file, default=None, metavar="FILE",
                   help="write the map rotated into the lay frame (x along the lay; NaN outside the map) to FILE: "
                   "NumPy .npy, or a text grid (.csv comma-separated, any other name whitespace-separated) "
                   "that `roughcontact moments` reads back")
    p.add_argument("--plot", type=output_file, default=None, metavar="FILE.png",
                   help="draw the moments against the sampling interval, with their uncertainties (png or pdf)")
    p.set_defaults(func=_run_moments, render=_render_moments)


def add_map_options(p) -> None:
    """The options that say how a height map is read (``moments`` and ``bem`` share them)."""
    p.add_argument("--unit", "--length-unit", dest="unit", default="um", metavar="UNIT",
                   help="length unit of the output and of the map (default um)")
    p.add_argument("--dx", type=_real, default=None, metavar="DX",
                   help="sampling interval along x (columns), in --xy-unit if given, else in --unit; needed when "
                   "the file has none (overrides the file's)")
    p.add_argument("--dy", type=_real, default=None, metavar="DY", help="sampling interval along y (rows) (default dx)")
    p.add_argument("--xy-unit", dest="xy_unit", default=None, metavar="UNIT",
                   help="unit of --dx and of a file's lateral coordinates that state none (default: the file's, "
                   "else --unit)")
    p.add_argument("--z-unit", dest="z_unit", default=None, metavar="UNIT",
                   help="unit of the heights (default: the file's, else the lateral unit)")
    p.add_argument("--z-scale", dest="z_scale", type=_real, default=1.0, metavar="F",
                   help="multiply the heights by F before the unit conversion (default 1)")
    p.add_argument("--layout", choices=("auto", "grid", "xyz"), default="auto",
                   help="text files: a grid (one map row per line) or x y z points (default: detected)")
    p.add_argument("--channel", type=int, default=None, metavar="N", help="data channel of an instrument file")


def _map_in_unit(args):
    """(heights, dx, dy, source payload) in --unit, from the file and the unit options."""
    from ..readers import UnitWarning, read_height_map, unit_warning
    from ..readers.lengths import factor, normalise

    found = read_height_map(args.file, layout=args.layout, channel=args.channel)
    unit = normalise(args.unit)
    xy_unit = normalise(args.xy_unit) if args.xy_unit else found.xy_unit or unit
    z_unit = normalise(args.z_unit) if args.z_unit else found.z_unit or xy_unit
    notes = list(found.notes)
    for name, given, in_file in (("--xy-unit", args.xy_unit, found.xy_unit), ("--z-unit", args.z_unit, found.z_unit)):
        if given and in_file and normalise(given) != in_file:
            notes.append(f"{name} {given} overrides the file's {in_file}")
    # --dx, --dy are in --xy-unit if given, else in --unit; the file's spacing in its own unit
    given_unit = normalise(args.xy_unit) if args.xy_unit else unit
    # the spacing judged as used: --dx in its unit where given, else the file's
    doubt = unit_warning(found, given_unit if args.dx is not None else xy_unit, z_unit, args.file, dx=args.dx)
    if doubt:  # e.g. metres taken as µm: said (note and warning), not refused
        notes.append(doubt)
        warnings.warn(UnitWarning(doubt))
    if args.dx is not None or args.dy is not None:
        if args.dx is None:
            raise CLIError("--dy needs --dx")
        if found.dx is not None:
            notes.append(f"--dx {args.dx:g} {given_unit} overrides the file's spacing {found.dx:g} {xy_unit}")
        f = factor(given_unit, unit)
        dx, dy = args.dx * f, (args.dy if args.dy is not None else args.dx) * f
    elif found.dx is None:
        raise CLIError(f"{args.file} does not give the sampling interval: pass --dx (in --xy-unit, default {unit})")
    else:
        f = factor(xy_unit, unit)
        dx, dy = found.dx * f, (found.dy if found.dy is not None else found.dx) * f
    _check_spacing(found.heights.shape, dx, dy, "--dx" if args.dx is not None else f"the spacing of {args.file}", unit)
    fz = factor(z_unit, unit) * args.z_scale
    assumed = found.z_unit is None and args.z_unit is None
    source = {"file": str(args.file), "format": found.source, "notes": notes,
              "units_in_file": {"xy": found.xy_unit, "z": found.z_unit},
              "units_read": {"xy": xy_unit, "z": z_unit, "assumed": assumed}}
    return found.heights * fz, dx, dy, source


def _check_spacing(shape, dx, dy, option, unit) -> None:
    """CLIError naming ``option`` unless dx, dy [unit] are finite, positive, and the map's extent
    (n dx) and curvature scale (dx^-4) are finite doubles (statistics.measure.spacing_fits: --dx 1e308
    ended in "SVD did not converge"); the library checks the same, naming dx rather than the option."""
    from ..statistics.measure import spacing_fits

    for name, d, n in (("dx", dx, shape[1]), ("dy", dy, shape[0])):
        shown = option if name == "dx" or option != "--dx" else "--dy"
        if not (math.isfinite(d) and d > 0):
            raise CLIError(f"{shown}: the sampling interval must be a finite positive length, got {d:g} {unit}")
        if not spacing_fits(n, d):
            raise CLIError(f"{shown} {d:g} {unit}: with {n} points the map's extent or its curvatures (~1/{name}^4) are "
                           f"not finite double-precision numbers; give the spacing in a unit near it (--xy-unit, --unit)")


def _run_moments(args) -> dict[str, Any]:
    from ..contact.validity import relay_warnings
    from ..readers.lengths import normalise
    from ..statistics.measure import measure_heights, rotate_map

    unit = normalise(args.unit)
    if args.lay_angle is not None and not math.isfinite(args.lay_angle):
        raise CLIError(f"--lay-angle {args.lay_angle}: the lay angle must be a finite number of degrees")
    with warnings.catch_warnings(record=True) as caught:  # the reading's warnings too ("warnings" in the JSON)
        warnings.simplefilter("always")
        z, dx, dy, source = _map_in_unit(args)
        try:
            r = measure_heights(z, dx, dy, estimator=args.estimator, order=args.order, window=args.window,
                                detrend=args.detrend, lay_angle_deg=args.lay_angle, fill=args.fill)
        except ValueError as exc:  # e.g. too few points: say of which file
            raise CLIError(f"{args.file}: {exc}") from None
    L = unit
    units = {"m00": f"{L}^2", "m20": "1", "m02": "1", "m40": f"1/{L}^2", "m04": f"1/{L}^2", "m11_map": "1",
             "m22": f"1/{L}^2", "m31": f"1/{L}^2", "m13": f"1/{L}^2", "dx": L, "dy": L,
             "lay_angle_deg": "deg (from the map's x axis to the lay, counter-clockwise)",
             "wavenumbers": "angular (rad per unit length), no 2*pi in m_pq",
             "scales": "the moments with the stencils at factor * dx, factor * dy",
             "uncertainty": "standard uncertainty of the surface's moments from this map (batch means over 4x4 "
                            "sub-windows), same units as the moments",
             "form": f"radius, centre_x, centre_y, form_rms in {L}",
             "noise_floor": f"height_step in {L}; variance, tail_variance in {L}^2; contribution in the units of each "
                            "moment; fraction: of the measured moment"}
    payload = {
        **{k: r.values[k] for k in _MOMENTS}, "unit": L,
        "lay_angle_deg": r.lay_angle_deg,
        "lay_angle_uncertainty_deg": None if r.uncertainty is None else r.uncertainty["lay_angle_deg"],
        "m11_map": r.m11_map, "m22": r.values["m22"], "m31": r.values["m31"], "m13": r.values["m13"],
        "uncertainty": None if r.uncertainty is None else {k: r.uncertainty[k] for k in (*_MOMENTS, "m22")},
        "scales": [dict(s) for s in r.scales],
        "anisotropy": r.anisotropy(), "model": r.validity(),
        "estimator": r.estimator, "order": r.order, "window": r.window, "detrend": r.detrend, "fill": r.fill,
        "missing_fraction": r.missing_fraction, "dx": r.dx, "dy": r.dy, "shape": list(z.shape),
        "form": r.form, "noise_floor": r.noise_floor,
        "source": source, "units": units,
    }
    if args.save_rotated is not None:
        save_height_map(args.save_rotated, rotate_map(z, r.dx, r.dy, r.lay_angle_deg), "--save-rotated")
    if args.plot:
        from ..plots import moments_against_scale, save_figure
        from ..write_errors import WriteError

        try:
            save_figure(moments_against_scale(_json_safe(payload)), args.plot)
        except ImportError as exc:
            raise CLIError(str(exc)) from None
        except OSError as exc:  # e.g. a full disk (ENOSPC): atomic_path left nothing under the name
            raise CLIError(f"--plot {args.plot}: cannot write it ({exc.strerror or exc})") from None
        except WriteError as exc:  # save_figure's one line: the file, the reason, whether the disk is full
            raise CLIError(f"--plot: {exc}") from None
        payload["plot"] = str(args.plot)
    payload["warnings"] = relay_warnings(caught)
    return _json_safe(payload)


def save_height_map(path: Path, z, option: str) -> None:
    """Write a height map to exactly ``path`` (atomically): .npy in NumPy's format, any other
    name as a text grid that :func:`roughcontact.readers.read_height_map` reads back (.csv
    comma-separated, else whitespace; NaN written as "nan")."""
    import numpy as np

    with writing(path, option) as tmp:
        if path.suffix.lower() == ".npy":
            with open(tmp, "wb") as f:  # a file object: np.save appends no ".npy" to the name
                np.save(f, z, allow_pickle=False)
        else:
            np.savetxt(tmp, z, delimiter="," if path.suffix.lower() == ".csv" else " ", fmt="%.17g")


def _json_safe(value):
    """Non-finite floats (an undefined ratio, an infinite lay uncertainty of an isotropic map) as
    None: the payload is strict JSON and the CLI's finiteness check is for computed results."""
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _render_moments(payload: dict[str, Any]) -> str:
    u = payload["units"]
    unc = payload["uncertainty"] or {}
    lines = [f"{k:<24}{payload[k]:>16.8g}  {('+- ' + format(unc[k], '.2g')) if k in unc else '':<12}{u[k]}"
             for k in _MOMENTS]
    lines.append(f"{'lay_angle_deg':<24}{payload['lay_angle_deg']:>16.6g}  "
                 + (f"+- {payload['lay_angle_uncertainty_deg']:.2g}" if payload["lay_angle_uncertainty_deg"] is not None else ""))
    lines += [f"{k:<24}{payload[k]:>16.8g}  {u[k]}" for k in ("m11_map", "m22", "m31", "m13")]
    lines += [f"{k:<24}{v:>16.8g}" for k, v in payload["anisotropy"].items()]
    m = payload["model"]
    lines.append("model of the paper applies: " + ("yes" if m["model_applies"] else "no") + "  ("
                 + "  ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in m.items() if k not in ("model_applies", "m22"))
                 + ")")
    mm = m.get("m22")
    if mm and mm.get("summit_ratio") is not None:
        lines.append(f"m22 (neglected by the model): m22^2/(m40 m04)={mm['rho2']:.3g}, {mm['summit_ratio']:.3g} x the "
                     "summits of (17); " + ("within" if mm["within_bem_measured"] else "beyond")
                     + " what the BEM comparison measured (docs/bem.md)")
    form = payload.get("form") or {}
    if form:
        lines.append("form removed: " + form["removed"] + (f", radius {form['radius']:.6g} {u['dx']} ({form['shape']})"
                                                           if form.get("radius") is not None else "")
                     + f", rms {form['form_rms']:.4g} {u['dx']}" + (f" ({form['note']})" if form.get("note") else ""))
    nf = payload.get("noise_floor")
    if nf:
        lines.append("noise floor (" + nf["source"] + "): " + "  ".join(
            f"{k} {100 * f:.3g} %" for k, f in nf["fraction"].items() if f is not None)
            + (f"  (height step {nf['height_step']:.3g} {u['dx']})" if nf.get("height_step") is not None else ""))
    for s in payload["scales"]:
        lines.append(f"at {s['factor']}x dx ({s['dx']:g} {u['dx']}): " + "  ".join(f"{k}={s[k]:.6g}" for k in _MOMENTS))
    src = payload["source"]
    lines += [f"file={src['file']}  format={src['format']}  units in file: xy={src['units_in_file']['xy']} "
              f"z={src['units_in_file']['z']}" + ("  (none: taken in " + payload["unit"] + ")" if src["units_read"]["assumed"] else ""),
              f"estimator={payload['estimator']}  order={payload['order']}  window={payload['window']}  "
              f"detrend={payload['detrend']}  fill={payload['fill']}  missing={100 * payload['missing_fraction']:.2f} %  "
              f"dx={payload['dx']:g} {u['dx']}  dy={payload['dy']:g} {u['dy']}  shape={payload['shape']}",
              f"wavenumbers: {u['wavenumbers']}"]
    lines += [f"note: {n}" for n in src["notes"]]
    if payload.get("plot"):
        lines.append(f"plot: {payload['plot']}")
    lines.append(f"warnings: {len(payload['warnings'])}")
    lines += [f"warning: {w}" for w in payload["warnings"]]
    return "\n".join(lines)
