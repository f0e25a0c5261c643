"""The contact commands of the ``roughcontact`` command: surface, elastic, elastoplastic, mindlin."""

from __future__ import annotations

from typing import Any

from ..statistics import SpectralMoments
from . import CLOSURES, EP_DEFAULTS, MODELS, SURFACE_UNITS, _MOMENTS, _contact_parent, _real

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
    return SpectralMoments(*(getattr(args, name) for name in _MOMENTS))


def _run_surface(args) -> dict[str, Any]:
    surface = _surface_from(args)
    summary = surface.summary()
    return {**summary, "units": {k: SURFACE_UNITS[k] for k in summary}}


def _run_elastic(args) -> dict[str, Any]:
    from ..contact import elastic_contact

    surface = _surface_from(args)
    curves = elastic_contact(
        surface, args.s, args.E_star,
        model=args.model, hertz=args.hertz, method=args.method, accuracy=args.accuracy,
    )
    return {
        "s": [float(x) for x in curves.s],
        "area_fraction": [float(x) for x in curves.area_fraction],
        "pressure": [float(x) for x in curves.pressure],
        "stiffness": [float(x) for x in curves.stiffness],
        "units": dict(curves.units),
        "model": curves.model,
        "hertz": curves.hertz,
        "method": curves.method,
        "accuracy": args.accuracy if curves.method == "production" else None,
        "E_star": curves.E_star,
        "moments": surface.as_dict(),
    }


def _run_elastoplastic(args) -> dict[str, Any]:
    from ..contact import elastoplastic_contact
    from ..contact.closures import default_closure, resolve_material

    surface = _surface_from(args)
    material = resolve_material(
        surface, E_star=args.E_star, psi=args.psi, Y=args.Y, closure=args.closure, H=args.H,
        yield_coefficient=args.yield_coefficient, c_h=args.c_h, wp_over_wc=args.wp_over_wc,
        K_v=args.K_v,
    )
    curves = elastoplastic_contact(
        surface, args.s, material, hertz=args.hertz, method=args.method, accuracy=args.accuracy
    )
    fields = ("area_fraction", "pressure", "stiffness", "elastic_area_fraction",
              "elastoplastic_area_fraction", "plastic_area_fraction")
    m = curves.material
    return {
        "s": [float(x) for x in curves.s],
        **{f: [float(x) for x in getattr(curves, f)] for f in fields},
        "psi": float(curves.psi),
        "closure": args.closure or default_closure(args.psi, args.Y),
        "material": {"E_star": m.E_star, "Y": m.Y, "H": m.H, "yield_coefficient": m.yield_coefficient,
                     "c_h": m.c_h, "wp_over_wc": m.wp_over_wc, "K_v": m.K_v},
        "units": {k: v for k, v in curves.units.items() if k in ("s", *fields)}
        | {"psi": "1", "material": "stresses in the unit of E*"},
        "model": "bgk-elastoplastic",
        "hertz": curves.hertz,
        "method": curves.method,
        "accuracy": args.accuracy if curves.method == "production" else None,
        "E_star": m.E_star,
        "moments": surface.as_dict(),
    }


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
    head = (
        f"model={payload['model']}  hertz={payload['hertz']}  method={payload['method']}"
        f"  E*={payload['E_star']:.8g}"
    )
    if "psi" in payload:
        head += f"  psi={payload['psi']:.6g}  closure={payload['closure']}"
    cols = ("s", "area_fraction", "pressure", "stiffness")
    units = ("h/sqrt(m00)", "A/A0", "unit of E*", "E*-unit/L")
    w = 16
    lines = [
        head,
        "".join(f"{c:>{w}}" for c in cols),
        "".join(f"{'[' + u + ']':>{w}}" for u in units),
    ]
    for row in zip(*(payload[c] for c in cols)):
        lines.append("".join(f"{v:>{w}.8g}" for v in row))
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
