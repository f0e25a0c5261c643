"""The contact commands of the ``roughcontact`` command: surface, elastic, elastoplastic, mindlin."""

from __future__ import annotations

import warnings
from typing import Any

from ..statistics import SpectralMoments
from . import (
    CLIError, CLOSURES, EP_DEFAULTS, MODELS, SURFACE_UNITS, _MOMENTS, _contact_parent, _real,
    effective_modulus_from,
)

__all__ = ["add_commands"]


def add_commands(sub, parents) -> None:
    """Register surface, elastic, elastoplastic (on the moments and output parents) and mindlin."""
    _add_surface(sub, parents)
    contact = [*parents, _contact_parent()]
    _add_elastic(sub, contact)
    _add_elastoplastic(sub, contact)
    _add_mindlin(sub, parents[1:])


def _add_surface(sub, parents) -> None:
    p = sub.add_parser(
        "surface",
        parents=parents,
        help="summit statistics of the surface",
        description="Bandwidth parameters and summit statistics (section 2 of the paper).",
    )
    p.set_defaults(func=_run_surface, render=_render_surface)


def _add_elastic(sub, parents) -> None:
    p = sub.add_parser(
        "elastic",
        parents=parents,
        help="elastic contact area, pressure and stiffness vs separation",
        description="Elastic contact with a rigid flat per unit nominal area at the "
        "separations s = h/sqrt(m00).",
    )
    p.add_argument("--model", choices=MODELS, default="bgk",
                   help="bgk: elliptic asperities; gw: McCool's equivalent GW (default bgk)")
    p.set_defaults(func=_run_elastic, render=_render_elastic)


def _add_elastoplastic(sub, parents) -> None:
    p = sub.add_parser(
        "elastoplastic",
        parents=parents,
        help="elasto-plastic contact area, pressure and stiffness vs separation",
        description="Elasto-plastic contact (sections 5-7: Hertz, ZMC/Jeng-Wang transition, "
        "CEB/Horng plastic) with a rigid flat per unit nominal area at s = h/sqrt(m00). "
        "With --yield-strength the material is physical and psi is an output; with --psi the "
        "closure yield-from-psi derives Y from psi at fixed E* (docs: roughcontact.contact.closures).",
    )
    p.add_argument("--psi", type=_real, metavar="P", help="plasticity index psi (prescribed)")
    p.add_argument("--yield-strength", dest="Y", type=_real, metavar="Y",
                   help="yield strength Y (unit of E*); H = Y/0.354 (Tabor) unless --hardness")
    p.add_argument("--closure", choices=CLOSURES, default=None,
                   help="how psi and the material are reconciled (default: material with "
                   "--yield-strength, yield-from-psi with --psi; paper-literal needs both)")
    p.add_argument("--yield-coefficient", dest="yield_coefficient", type=_real,
                   default=EP_DEFAULTS["yield_coefficient"], metavar="K",
                   help="K in p_max = K Y at first yield, eq. (63) (default 1.62)")
    p.add_argument("--c-h", dest="c_h", type=_real, default=EP_DEFAULTS["c_h"], metavar="C",
                   help="fully plastic mean pressure c_h H, eq. (66) (default 0.967)")
    p.add_argument("--wp-over-wc", dest="wp_over_wc", type=_real, default=EP_DEFAULTS["wp_over_wc"],
                   metavar="R", help="omega_p/omega_c, end of the transition (default 45)")
    p.add_argument("--hardness", dest="H", type=_real, default=None, metavar="H",
                   help="hardness H (unit of E*; default Y/0.354, eq. (68))")
    p.add_argument("--K-v", dest="K_v", type=_real, default=None, metavar="KV",
                   help="K_v of eq. (75) (default: K Y/H, continuous load at omega_c)")
    p.set_defaults(func=_run_elastoplastic, render=_render_elastic)


def _add_mindlin(sub, parents) -> None:
    p = sub.add_parser(
        "mindlin",
        parents=parents,
        help="Mindlin's normal/tangential stiffness ratio k_N/k_T of an elliptical contact",
        description="k_N/k_T of two bodies with the same elastic constants for a contact "
        "ellipse with semi-axis B along the tangential force and A across it (corrected "
        "eq. (96) of the paper; Table 3). Needs no surface moments.",
    )
    p.add_argument(
        "--b2-over-a2", dest="b2_over_a2", type=_real, nargs="+", required=True, metavar="R",
        help="B^2/A^2 > 0 (B: semi-axis along the tangential force); Table 3 uses 1e-3 ... 1e3",
    )
    p.add_argument(
        "--nu", type=_real, required=True, metavar="NU",
        help="Poisson's ratio of both bodies, -1 < nu <= 0.5",
    )
    p.set_defaults(func=_run_mindlin, render=_render_mindlin)


# ---------------------------------------------------------------------------------------
# handlers: args -> payload (plain JSON-able dict)
# ---------------------------------------------------------------------------------------
def _surface_from(args) -> SpectralMoments:
    """The moments of the command line (--m00 … --m04, or --moments FILE [FILE2]), plus those of
    --second-surface where given (the sum: two rough surfaces as one on a flat,
    SpectralMoments.combined_with). Sets ``args.moments_unit`` to the files' length unit where they
    state it, else keeps the command's own ``--moments-unit`` (export), else None (not known)."""
    files = getattr(args, "moments_files", None)
    given = [name for name in _MOMENTS if getattr(args, name) is not None]
    second = getattr(args, "second_surface", None)
    args.moments_unit = getattr(args, "moments_unit", None)
    if files:
        if given:
            raise CLIError(f"--moments replaces --{' --'.join(given)}: give the moments one way")
        if len(files) > 2:
            raise CLIError(f"--moments takes one file, or two for two rough surfaces; got {len(files)}")
        if second is not None and len(files) == 2:
            raise CLIError("two --moments files already give two surfaces: drop --second-surface")
        return _surfaces_from_files(args, files, second)
    if len(given) != len(_MOMENTS):
        missing = [f"--{n}" for n in _MOMENTS if n not in given]
        raise CLIError(f"the moments are missing: {' '.join(missing)} (or --moments FILE.json)")
    surface = SpectralMoments(*(getattr(args, name) for name in _MOMENTS))
    return surface if second is None else surface.combined_with(SpectralMoments(*second))


def _surfaces_from_files(args, files, second) -> SpectralMoments:
    from ..readers import load_moments, moments_in_unit

    (surface, unit), *others = [load_moments(f) for f in files]
    for other, other_unit in others:
        if (unit is None) != (other_unit is None):
            raise CLIError(f"{files[0]} and {files[1]}: one states its length unit and the other does not")
        if unit is not None and other_unit != unit:
            other = moments_in_unit(other, other_unit, unit)
        surface = surface.combined_with(other)
    if second is not None:
        surface = surface.combined_with(SpectralMoments(*second))
    if unit is not None:
        given = args.moments_unit  # export's --moments-unit: must not contradict what the file states
        if given is not None and _length_unit(given, "--moments-unit") != unit:
            raise CLIError(f"--moments-unit {given} contradicts {files[0]}, whose moments are in {unit}: drop "
                           f"--moments-unit (the file's unit is used; --length-unit converts the output)")
        args.moments_unit = unit
    return surface


def _length_unit(text: str, option: str) -> str:
    """The canonical name of the length unit ``text`` (readers.lengths.normalise) or CLIError naming ``option``."""
    from ..readers import lengths

    try:
        return lengths.normalise(text)
    except ValueError as exc:
        raise CLIError(f"{option}: {exc}") from None


def _tangential(args, surface, stiffness) -> tuple[dict, dict]:
    """k_Tx, k_Ty per unit nominal area from Mindlin's k_T/k_N (corrected (96)) at the surface's
    representative contact ellipse (section 8; interface.tangential.representative_aspect), and
    how they were obtained."""
    from ..interface.normal_law import mindlin_kT_over_kN
    from ..interface.tangential import representative_aspect

    if args.nu is not None:
        nu, source = args.nu, "--nu"
    elif getattr(args, "nu1", None) is not None:
        nu, source = args.nu1, "--nu1"
        if args.E2 != float("inf") and args.nu2 != args.nu1:
            source += " (body 2 differs; Mindlin's ratio is for bodies with equal elastic constants)"
    else:
        nu, source = 0.3, "default (give --nu)"
    aspect = representative_aspect(surface)
    ax, ay = mindlin_kT_over_kN(aspect, nu)
    k = [float(v) for v in stiffness]
    columns = {"k_Tx": [ax * v for v in k], "k_Ty": [ay * v for v in k]}
    info = {"model": "Mindlin (1949), eq. (96) corrected, at the representative contact ellipse of the surface "
                     "(the summit with the rms curvatures sqrt(m40), sqrt(m04); section 8)",
            "ay2_over_ax2": float(aspect), "nu": float(nu), "nu_source": source,
            "kT_over_kN_x": float(ax), "kT_over_kN_y": float(ay)}
    return columns, info


def _run_surface(args) -> dict[str, Any]:
    surface = _surface_from(args)
    summary = surface.summary()
    return {**summary, "units": {k: _in_unit(SURFACE_UNITS[k], args.moments_unit) for k in summary}}


def _in_unit(text: str, unit: str | None) -> str:
    """A unit text written with the length unit L, with the moments' unit where it is known."""
    import re

    return text if unit is None else re.sub(r"\bL\b", unit, text)


def _contact(args, surface, compute, **law):
    """Run the contact model at --s, --h or --pressure; relay warnings. Returns (curves, extra
    payload fields: h [L], the requested pressures, the warnings)."""
    from ..contact.at_pressure import contact_at_pressure
    from ..contact.validity import relay_warnings

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if args.pressure is not None:
            result = contact_at_pressure(surface, args.pressure, hertz=args.hertz,
                                         accuracy=args.accuracy, **law)
            curves = result.curves
        else:
            s = args.s if args.s is not None else [h / surface.height_std for h in args.h]
            curves = compute(s)
    messages = relay_warnings(caught)
    extra = {"h": [float(x * surface.height_std) for x in curves.s],
             "pressure_requested": None if args.pressure is None else [float(p) for p in args.pressure],
             "warnings": messages}
    return curves, extra


def _run_elastic(args) -> dict[str, Any]:
    from ..contact import elastic_contact

    surface = _surface_from(args)
    E_star = effective_modulus_from(args)
    if args.pressure is not None and args.method != "production":
        raise ValueError("--pressure solves with the production integrators: drop --method reference")
    curves, extra = _contact(
        args, surface,
        lambda s: elastic_contact(surface, s, E_star, model=args.model, hertz=args.hertz,
                                  method=args.method, accuracy=args.accuracy),
        E_star=E_star, model=args.model,
    )
    kt, tangential = _tangential(args, surface, curves.stiffness)
    return {
        "s": [float(x) for x in curves.s],
        "h": extra["h"],
        "area_fraction": [float(x) for x in curves.area_fraction],
        "pressure": [float(x) for x in curves.pressure],
        "stiffness": [float(x) for x in curves.stiffness],
        **kt,
        "pressure_requested": extra["pressure_requested"],
        "tangential": tangential,
        "length_unit": args.moments_unit,
        "units": {k: _in_unit(v, args.moments_unit) for k, v in curves.units.items()}
        | {"h": f"{args.moments_unit or 'L'} (the moments' length unit)", "pressure_requested": "unit of E*"}
        | _kt_units(args),
        "model": curves.model,
        "hertz": curves.hertz,
        "method": curves.method,
        "accuracy": args.accuracy if curves.method == "production" else None,
        "E_star": curves.E_star,
        "moments": surface.as_dict(),
        "warnings": extra["warnings"],
    }


def _run_elastoplastic(args) -> dict[str, Any]:
    from ..contact import elastoplastic_contact
    from ..contact.closures import default_closure, resolve_material

    surface = _surface_from(args)
    if args.pressure is not None and args.method != "production":
        raise ValueError("--pressure solves with the production integrators: drop --method reference")
    if not 0.0 < args.yield_coefficient < float("inf"):  # K_Y = 0 divides by zero deriving Y from psi
        raise CLIError(f"--yield-coefficient {args.yield_coefficient:g}: K in p_max = K Y at first yield "
                       "(eq. 63) must be finite and positive (default 1.62)")
    material = resolve_material(
        surface, E_star=effective_modulus_from(args), psi=args.psi, Y=args.Y, closure=args.closure,
        H=args.H, yield_coefficient=args.yield_coefficient, c_h=args.c_h,
        wp_over_wc=args.wp_over_wc, K_v=args.K_v,
    )
    curves, extra = _contact(
        args, surface,
        lambda s: elastoplastic_contact(surface, s, material, hertz=args.hertz, method=args.method,
                                        accuracy=args.accuracy),
        material=material,
    )
    fields = ("area_fraction", "pressure", "stiffness", "elastic_area_fraction",
              "elastoplastic_area_fraction", "plastic_area_fraction", "elastic_pressure",
              "elastoplastic_pressure", "plastic_pressure")
    m = curves.material
    kt, tangential = _tangential(args, surface, curves.stiffness)
    return {
        "s": [float(x) for x in curves.s],
        "h": extra["h"],
        **{f: [float(x) for x in getattr(curves, f)] for f in fields},
        **kt,
        "pressure_requested": extra["pressure_requested"],
        "tangential": tangential,
        "length_unit": args.moments_unit,
        "psi": float(curves.psi),
        "closure": args.closure or default_closure(args.psi, args.Y),
        "material": {"E_star": m.E_star, "Y": m.Y, "H": m.H, "yield_coefficient": m.yield_coefficient,
                     "c_h": m.c_h, "wp_over_wc": m.wp_over_wc, "K_v": m.K_v},
        "units": {k: _in_unit(v, args.moments_unit) for k, v in curves.units.items() if k in ("s", *fields)}
        | {"psi": "1", "material": "stresses in the unit of E*", "h": f"{args.moments_unit or 'L'} (the moments' length unit)",
           "pressure_requested": "unit of E*"} | _kt_units(args),
        "model": "bgk-elastoplastic",
        "hertz": curves.hertz,
        "method": curves.method,
        "accuracy": args.accuracy if curves.method == "production" else None,
        "E_star": m.E_star,
        "moments": surface.as_dict(),
        "warnings": extra["warnings"],
    }


def _kt_units(args) -> dict[str, str]:
    L = args.moments_unit or "L"
    return {k: f"unit of E* per {L} (k_T/A0: Mindlin's k_T/k_N times K/A0)" for k in ("k_Tx", "k_Ty")}


def _run_mindlin(args) -> dict[str, Any]:
    from ..interface.tangential import kn_over_kt

    ratio = kn_over_kt([float(r) for r in args.b2_over_a2], args.nu)
    return {
        "b2_over_a2": [float(r) for r in args.b2_over_a2],
        "kn_over_kt": [float(x) for x in ratio],
        "nu": float(args.nu),
    }


def _render_surface(payload: dict[str, Any]) -> str:
    units = payload["units"]
    names = list(units)
    width = max(map(len, names))
    lines = [f"{name:<{width}}  {payload[name]:>14.8g}  {units[name]}" for name in names]
    return "\n".join(lines)


def _render_elastic(payload: dict[str, Any]) -> str:
    """Every field of the payload: scalars in the head, per-point lists as columns (with their
    units), the moments and material below, then the warnings."""
    head = (
        f"model={payload['model']}  hertz={payload['hertz']}  method={payload['method']}"
        f"  accuracy={payload['accuracy']}  E*={payload['E_star']:.8g}"
    )
    if "psi" in payload:
        head += f"  psi={payload['psi']:.6g}  closure={payload['closure']}"
    n = len(payload["s"])
    cols = [k for k, v in payload.items() if isinstance(v, list) and len(v) == n and k != "warnings"]
    if payload["pressure_requested"] is None:
        lines_note = "pressure_requested=None (separations given)"
    else:
        lines_note = "pressure_requested: the column above (load control)"
    units = payload["units"]
    brackets = [f"[{units.get(c, '').split(' (')[0]}]" for c in cols]
    # each column as wide as its name and its unit, plus two spaces: headers never run together
    w = [max(16, len(c) + 2, len(b) + 2) for c, b in zip(cols, brackets)]
    lines = [
        head,
        "".join(f"{c:>{wc}}" for c, wc in zip(cols, w)),
        "".join(f"{b:>{wc}}" for b, wc in zip(brackets, w)),
    ]
    for row in zip(*(payload[c] for c in cols)):
        lines.append("".join(f"{v:>{wc}.8g}" for v, wc in zip(row, w)))
    lines.append(lines_note)
    lines.append("moments: " + "  ".join(f"{k}={v:.8g}" for k, v in payload["moments"].items()))
    if "material" in payload:
        lines.append("material: " + "  ".join(f"{k}={v:.8g}" for k, v in payload["material"].items()))
    if "tangential" in payload:
        t = payload["tangential"]
        lines.append(f"tangential: k_Tx = {t['kT_over_kN_x']:.6g} K, k_Ty = {t['kT_over_kN_y']:.6g} K at "
                     f"ay^2/ax^2 = {t['ay2_over_ax2']:.6g}, nu = {t['nu']:g} ({t['nu_source']}); {t['model']}")
    if "length_unit" in payload:
        lines.append(f"length_unit={payload['length_unit'] or 'not stated (L)'}")
    lines.append("units: " + "; ".join(f"{k}: {v}" for k, v in units.items()))
    lines.append(f"warnings: {len(payload['warnings'])}")
    lines.extend(f"warning: {m}" for m in payload["warnings"])
    return "\n".join(lines)


def _render_mindlin(payload: dict[str, Any]) -> str:
    w = 16
    lines = [
        f"nu={payload['nu']:.8g}",
        "".join(f"{c:>{w}}" for c in ("b2_over_a2", "kn_over_kt")),
    ]
    for r, k in zip(payload["b2_over_a2"], payload["kn_over_kt"]):
        lines.append(f"{r:>{w}.8g}{k:>{w}.10g}")
    return "\n".join(lines)
