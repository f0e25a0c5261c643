"""Command-line interface: ``roughcontact <command> ...``.

A thin layer: parse and validate the arguments, call the library, print the result.

    roughcontact --version
    roughcontact surface --m00 M --m20 M --m02 M --m40 M --m04 M [--json]
    roughcontact elastic --m00 M ... --m04 M --E-star E --s S [S ...]
                         [--model bgk|gw] [--hertz exact|paper]
                         [--method production|reference] [--accuracy table|plot] [--json]
    roughcontact elastoplastic --m00 M ... --m04 M --E-star E (--psi P | --yield-strength Y)
                         [--closure material|yield-from-psi|paper-literal] --s S [S ...]
                         [--yield-coefficient K] [--c-h C] [--wp-over-wc R] [--hardness H]
                         [--K-v KV] [--hertz exact|paper] [--method production|reference]
                         [--accuracy table|plot] [--json]
    roughcontact mindlin --b2-over-a2 R [R ...] --nu NU [--json]

Exit codes: 0 success; 2 bad input (one line on stderr, "roughcontact: error: ...");
1 a computed value is not finite. Any other exception is a bug and propagates (traceback).

Lengths are in the unit L of the moments (m00 [L²], m20, m02 [–], m40, m04 [L⁻²]);
pressures come out in the unit of E*, stiffnesses in (unit of E*)/L.

Subcommands register themselves like :func:`_add_surface` / :func:`_add_elastic`: a subparser
built on the shared ``moments`` (and, for contact, ``contact``) parent parsers, with ``func``
set to a handler ``(args) -> payload dict`` and ``render`` set to the human-readable formatter
of that payload.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from typing import Any, Callable, Sequence

from . import __version__
from .statistics import SpectralMoments

__all__ = ["main", "build_parser", "CLIError"]

PROG = "roughcontact"
_MOMENTS = ("m00", "m20", "m02", "m40", "m04")
_MOMENT_HELP = {
    "m00": "height variance m00 [L^2]",
    "m20": "slope variance along the grain m20 [1]",
    "m02": "slope variance across the grain m02 [1]",
    "m40": "curvature variance along the grain m40 [1/L^2]",
    "m04": "curvature variance across the grain m04 [1/L^2]",
}

#: units of SpectralMoments.summary() in terms of the length unit L of the moments
SURFACE_UNITS = {
    "m00": "L^2",
    "m20": "1",
    "m02": "1",
    "m40": "1/L^2",
    "m04": "1/L^2",
    "alpha1": "1",
    "alpha2": "1",
    "beta1": "1",
    "beta2": "1",
    "mu": "1",
    "summit_density": "1/L^2",
    "mean_summit_curvature": "1/L",
    "summit_height_std": "L",
    "summit_mean_height": "L",
}

# Choices of roughcontact.contact.elastic_contact, repeated here so that building the parser
# does not import numba (tests/test_cli.py checks they match contact.MODELS/HERTZ/METHODS).
MODELS = ("bgk", "gw")
HERTZ = ("exact", "paper")
METHODS = ("production", "reference")
ACCURACIES = ("table", "plot")
# roughcontact.contact.closures.CLOSURES / DEFAULTS, likewise repeated (and checked by the tests)
CLOSURES = ("material", "yield-from-psi", "paper-literal")
EP_DEFAULTS = {"yield_coefficient": 1.62, "c_h": 0.967, "wp_over_wc": 45.0}


class CLIError(Exception):
    """An error reported as one stderr line with the given exit code."""

    def __init__(self, message: str, code: int = 2):
        super().__init__(message)
        self.code = code


def _one_line(message: str) -> str:
    return " ".join(str(message).split())


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one stderr line (no usage block), exit code 2."""

    def error(self, message: str):  # type: ignore[override]
        self.exit(2, f"{PROG}: error: {_one_line(message)}\n")


def _real(text: str) -> float:
    """argparse type: any string float() accepts; range checks are the library's."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a real number, got {text!r}") from None


# ---------------------------------------------------------------------------------------
# parser
# ---------------------------------------------------------------------------------------
def _moments_parent() -> argparse.ArgumentParser:
    parent = _Parser(add_help=False)
    group = parent.add_argument_group("spectral moments (one consistent length unit L)")
    for name in _MOMENTS:
        group.add_argument(
            f"--{name}", type=_real, required=True, metavar="M", help=_MOMENT_HELP[name]
        )
    return parent


def _output_parent() -> argparse.ArgumentParser:
    parent = _Parser(add_help=False)
    parent.add_argument(
        "--json", action="store_true", help="print one strict JSON object instead of text"
    )
    return parent


def _contact_parent() -> argparse.ArgumentParser:
    """Options shared by the contact commands (elastic, elastoplastic)."""
    parent = _Parser(add_help=False)
    parent.add_argument(
        "--E-star", dest="E_star", type=_real, required=True, metavar="E",
        help="effective modulus E* (any stress unit; the pressure comes out in it)",
    )
    parent.add_argument(
        "--s", dest="s", type=_real, nargs="+", required=True, metavar="S",
        help="separations s = h/sqrt(m00) of the flat from the mean plane",
    )
    parent.add_argument("--hertz", choices=HERTZ, default="exact",
                        help="Hertz functions: exact, or the paper's approximations (default exact)")
    parent.add_argument("--method", choices=METHODS, default="production",
                        help="integrator: production (numba) or reference (slow twin)")
    parent.add_argument("--accuracy", choices=ACCURACIES, default="table",
                        help="production quadrature preset (default table)")
    return parent


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog=PROG,
        description="Statistical contact of strongly anisotropic rough surfaces "
        "(Buczkowski & Kleiber 2009).",
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    parents = [_moments_parent(), _output_parent()]
    _add_surface(sub, parents)
    contact = [*parents, _contact_parent()]
    _add_elastic(sub, contact)
    _add_elastoplastic(sub, contact)
    _add_mindlin(sub, [_output_parent()])
    return parser


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
    from .contact import elastic_contact

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
    from .contact import elastoplastic_contact
    from .contact.closures import default_closure, resolve_material

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
    from .interface.tangential import kn_over_kt

    ratio = kn_over_kt([float(r) for r in args.b2_over_a2], args.nu)
    return {
        "b2_over_a2": [float(r) for r in args.b2_over_a2],
        "kn_over_kt": [float(x) for x in ratio],
        "nu": float(args.nu),
    }


# ---------------------------------------------------------------------------------------
# output
# ---------------------------------------------------------------------------------------
def _check_finite(payload: Any, path: str = "") -> None:
    """Raise CLIError (exit 1) naming the first non-finite number in the payload."""
    if isinstance(payload, dict):
        for key, value in payload.items():
            _check_finite(value, f"{path}.{key}" if path else str(key))
    elif isinstance(payload, (list, tuple)):
        for i, value in enumerate(payload):
            _check_finite(value, f"{path}[{i}]")
    elif isinstance(payload, float) and not math.isfinite(payload):
        raise CLIError(f"computed {path} is not finite ({payload!r})", code=1)


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


# ---------------------------------------------------------------------------------------
# entry point
# ---------------------------------------------------------------------------------------
def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI on ``argv`` (default ``sys.argv[1:]``); return the exit code."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a parse error (already reported)
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)

    handler: Callable[[Any], dict[str, Any]] = args.func
    try:
        try:
            payload = handler(args)
        except (ValueError, TypeError) as exc:
            # the library's validation errors name the violated condition
            raise CLIError(_one_line(str(exc)), code=2) from exc
        _check_finite(payload)
        text = (
            json.dumps(payload, indent=2, allow_nan=False)
            if args.json
            else args.render(payload)
        )
    except CLIError as exc:
        print(f"{PROG}: error: {_one_line(str(exc))}", file=sys.stderr)
        return exc.code
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
