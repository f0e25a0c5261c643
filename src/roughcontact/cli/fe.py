"""The finite-element commands of ``roughcontact``: ``fe beam`` (example 9.1) and ``fe punch``
(example 9.2).

    roughcontact fe beam --m00 M --m20 M --m02 M --m40 M --m04 M [--E-star E]
        [--law elastic|elastoplastic --psi PSI] [--load 1962] [--initial-load 4.9]
        [--tangential free|stick|coulomb] [--mu MU] [--elements quadratic|cubic]
        [--increments 16] [--n-x 25] [--n-z 6] [--vtu FILE] [--quiet] [--json]
    roughcontact fe punch --case a|b|c [--m00 0.625 ...] [--elements quadratic|cubic]
        [--load 1000 (N, whole punch)] [--load-on whole|quarter] [--load-patch SIDE]
        [--seating-pressure P0] [--E-star E] [--law elastic|elastoplastic] [--psi 0.35]
        [--tangential incremental|incremental-start|secant] [--increments 16] [--vtu FILE]
        [--quiet] [--json]

Moments in µm (the paper's surfaces), stresses in N/mm², lengths of the beam in mm. Progress
(one line per load increment) goes to stderr unless --quiet. Exit codes as the other commands;
a run that does not converge exits 1 naming the increment and the residual.
"""

from __future__ import annotations

import sys
from typing import Any

import numpy as np

from . import CLIError, _MOMENTS, _real, output_file, writing

__all__ = ["add_commands"]

LAWS = ("elastic", "elastoplastic")
TANGENTIAL = ("free", "stick", "coulomb")  # roughcontact.fe.contact.TANGENTIAL (checked by the tests)
FAMILIES = ("quadratic", "cubic")  # roughcontact.fe.beam.ELEMENT_FAMILIES
#: E* of eq. (42) for the beam on a rigid base: E1/(1 − ν1²) = 1.057e5/0.9375 (the text's 1.127e5)
BEAM_E_STAR = 1.057e5 / (1.0 - 0.25**2)


def add_commands(sub, parents) -> None:
    fe = sub.add_parser("fe", help="finite-element contact examples of section 9",
                        description="3D finite-element contact through the statistical interface law.")
    fe_sub = fe.add_subparsers(dest="example", metavar="EXAMPLE", required=True)
    _add_beam(fe_sub, parents)
    _add_punch(fe_sub, parents[1:])


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise CLIError(f"must be an integer, got {text!r}") from None


def _add_beam(sub, parents) -> None:
    p = sub.add_parser(
        "beam", parents=parents, help="prismatic beam on a rigid base (example 9.1, Table 4, Fig. 13)",
        description="Beam 500 x 10 x 120 mm on its 500 x 10 face on a rigid base through the statistical "
        "interface (moments in um), loaded at mid-length: the initial load, then --load in --increments "
        "steps. u_N is the interface deflection from the seated state, negative = approach [um].",
    )
    p.add_argument("--E-star", dest="E_star", type=_real, default=BEAM_E_STAR, metavar="E",
                   help=f"effective modulus E* [N/mm^2] (default E1/(1-nu1^2) = {BEAM_E_STAR:.6g}, eq. (42))")
    p.add_argument("--law", choices=LAWS, default="elastic", help="normal law (default elastic)")
    p.add_argument("--psi", type=_real, default=None, metavar="PSI",
                   help="plasticity index of the elasto-plastic law (closure yield-from-psi)")
    p.add_argument("--load", type=_real, default=1962.0, metavar="N", help="load on the full beam [N] (1962)")
    p.add_argument("--initial-load", dest="initial_load", type=_real, default=4.9, metavar="N",
                   help="seating load [N] (4.9): the reference state of u_N")
    p.add_argument("--tangential", choices=TANGENTIAL, default="free",
                   help="tangential restraint: free sliding, k_T (Mindlin) without slip, or k_T with a "
                   "Coulomb limit --mu (default free)")
    p.add_argument("--mu", type=_real, default=None, metavar="MU", help="Coulomb coefficient (with coulomb)")
    p.add_argument("--elements", choices=FAMILIES, default="cubic",
                   help="28-node transition + 32-node interface (cubic) or 21 + 18 (quadratic)")
    p.add_argument("--increments", type=_int, default=16, metavar="N", help="load increments (16)")
    p.add_argument("--n-x", dest="n_x", type=_int, default=25, metavar="N", help="elements along the half beam")
    p.add_argument("--n-z", dest="n_z", type=_int, default=6, metavar="N", help="elements over the height")
    p.add_argument("--vtu", type=output_file, default=None, metavar="FILE",
                   help="write the mesh with displacements to FILE and the interface points to "
                   "FILE's stem + '_interface.vtu'")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=_run_beam, render=_render_beam)


def _run_beam(args) -> dict[str, Any]:
    from ..fe.beam import beam_case
    from ..fe.solver import ConvergenceError

    moments = {name: getattr(args, name) for name in _MOMENTS}
    if (args.psi is not None) != (args.law == "elastoplastic"):
        raise CLIError("--psi is needed with --law elastoplastic and only used there")
    run = {"family": args.elements, "m00": moments.pop("m00"), "surface": moments, "law": args.law,
           "psi": args.psi, "E_star": args.E_star, "tangential": args.tangential, "mu": args.mu,
           "spec": {"load": args.load, "initial_load": args.initial_load, "increments": args.increments,
                    "n_x": args.n_x, "n_z": args.n_z}}
    try:
        result = beam_case(run, progress=None if args.quiet else _progress)
    except ConvergenceError as exc:
        raise CLIError(str(exc), code=1) from exc
    if args.vtu is not None:
        from ..fe.beam import interface_fields
        from ..fe.vtu import write_solution

        with writing(args.vtu, "--vtu", atomic=False) as path:  # fe.vtu writes both files atomically
            write_solution(path, result.mesh, result.solution.final.u, interface_fields(result))
    payload = result.summary()
    payload.update(law=args.law, psi=args.psi, tangential=args.tangential, mu=args.mu, E_star=args.E_star,
                   moments={"m00": run["m00"], **moments}, vtu=str(args.vtu) if args.vtu else None)
    return payload


#: the Fig. 18 surface (µm), the punch's default
PUNCH_SURFACE = {"m00": 0.625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}
#: the friction update's status codes (roughcontact.interface.friction STICK, SLIP, OPEN) by name
STATUS_NAMES = ("stick", "slip", "open")
#: "incremental" is the (93) form with k_T at the end of the increment
TANGENTIAL_FORMS = {"incremental": "incremental-end", "incremental-start": "incremental-start", "secant": "secant"}


def _add_punch(sub, parents) -> None:
    p = sub.add_parser(
        "punch", parents=parents, help="flat punch on an elastic foundation with orthotropic friction (example 9.2)",
        description="Punch 20 x 20 x 10 mm on a foundation 100 x 100 x 50 mm (E = 200 GPa, nu = 0.25; quarter "
        "model) through the statistical interface with the orthotropic hardening friction of Fig. 18's case; "
        "seated, loaded on a centred patch of the punch top in --increments steps, unloaded likewise. Prints "
        "the dissipation D, its frictionless upper bound and the state of every contact point at the maximum load.",
    )
    p.add_argument("--case", choices=("a", "b", "c"), required=True, help="friction parameters of Fig. 18 (a, b, c)")
    for name, value in PUNCH_SURFACE.items():
        p.add_argument(f"--{name}", type=_real, default=value, metavar="M", help=f"{name} (default {value:g}, um units)")
    p.add_argument("--elements", choices=FAMILIES, default="quadratic",
                   help="21-node + 18-node (quadratic, 81 points) or 28-node + 32-node (cubic, 100 points)")
    p.add_argument("--load", type=_real, default=1000.0, metavar="N", help="maximum patch load [N] (1000)")
    p.add_argument("--load-on", dest="load_on", choices=("whole", "quarter"), default="whole",
                   help="the load acts on the whole punch (default) or on the quarter model")
    p.add_argument("--load-patch", dest="load_patch", type=_real, default=None, metavar="SIDE",
                   help="side of the centred loaded square on the whole punch [mm] (default: the punch's central element)")
    p.add_argument("--seating-pressure", dest="seating_pressure", type=_real, default=0.1, metavar="P0",
                   help="seating pressure on the punch top [N/mm^2] (0.1): the reference state")
    p.add_argument("--E-star", dest="E_star", type=_real, default=None, metavar="E",
                   help="effective modulus [N/mm^2] (default: two like bodies, E/(2(1-nu^2)), eq. (42))")
    p.add_argument("--law", choices=LAWS, default="elastoplastic", help="normal law (default elastoplastic)")
    p.add_argument("--psi", type=_real, default=0.35, metavar="PSI", help="plasticity index (0.35)")
    p.add_argument("--tangential", choices=tuple(TANGENTIAL_FORMS), default="incremental",
                   help="how k_T enters (93): incremental (k_T at the end of the increment), incremental-start, "
                   "or secant (a total elastic law)")
    p.add_argument("--increments", type=_int, default=16, metavar="N", help="loading and unloading increments (16)")
    p.add_argument("--vtu", type=output_file, default=None, metavar="FILE",
                   help="write both bodies with displacements (maximum load) to FILE and the contact points "
                   "to FILE's stem + '_interface.vtu'")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=_run_punch, render=_render_punch)


def _run_punch(args) -> dict[str, Any]:
    from ..fe.punch import dissipation, frictionless_bound, mu_max, punch_case, summary_of
    from ..fe.solver import ConvergenceError

    surface = {name: getattr(args, name) for name in ("m20", "m02", "m40", "m04")}
    geometry = {"family": args.elements, **({"load_patch": args.load_patch} if args.load_patch else {})}
    run = {"case": args.case, "m00": args.m00, "surface": surface, "law": args.law, "psi": args.psi,
           "E_star": args.E_star, "tangential_form": TANGENTIAL_FORMS[args.tangential], "load": args.load,
           "load_on": args.load_on, "seating_pressure": args.seating_pressure, "increments": args.increments,
           "unload_increments": args.increments, "geometry": geometry}
    progress = None if args.quiet else _progress
    try:
        result = punch_case(run, progress)
        free = punch_case({**run, "case": "frictionless"}, progress)
    except ConvergenceError as exc:
        raise CLIError(str(exc), code=1) from exc
    mu = mu_max(args.case)
    points = result.slip_directions()
    if args.vtu is not None:
        with writing(args.vtu, "--vtu", atomic=False) as path:
            result.write_vtu(path)
    summary = summary_of(result)
    return {
        "dissipation_quarter_Nmm": dissipation(result, whole=False),
        "dissipation_full_Nmm": dissipation(result, whole=True),
        "dissipation_work_full_Nmm": dissipation(result, weight="work", whole=True),
        "frictionless_bound_quarter_Nmm": frictionless_bound(result, free, mu, whole=False),
        "frictionless_bound_full_Nmm": frictionless_bound(result, free, mu, whole=True),
        "newton_iterations": summary["newton_iterations"],
        "equilibrium_error": summary["equilibrium_error_max_load"],
        "dofs": summary["dofs"], "interface_points": summary["interface_points"], "seconds": summary["seconds"],
        "points": {**{k: np.asarray(v).tolist() for k, v in points.items()},
                   "status": [STATUS_NAMES[int(v)] for v in points["status"]]},
        "case": args.case, "elements": args.elements, "spec": summary["spec"],
        "units": {"dissipation": "N mm", "x_mm": "mm", "slip_um": "um (plastic slip at the maximum load)",
                  "t_x, t_y, p_N": "N/mm^2", "utilisation": "1 (|t_T|/(mu p_N) on the limit (91); 1 slip)",
                  "seconds": "s"},
    }


def _render_punch(payload: dict[str, Any]) -> str:
    pts = payload["points"]
    lines = [
        f"punch on foundation, case {payload['case']}, {payload['elements']} elements: "
        f"{payload['interface_points']} contact points, {payload['dofs']} dofs, {payload['seconds']:.1f} s",
        f"D = {payload['dissipation_full_Nmm']:.5g} N mm (whole punch; quarter {payload['dissipation_quarter_Nmm']:.5g})"
        f"   frictionless bound {payload['frictionless_bound_full_Nmm']:.5g} N mm"
        f"   dissipated work {payload['dissipation_work_full_Nmm']:.5g} N mm",
        f"{'x [mm]':>8}{'y [mm]':>8}{'u_x^p [um]':>12}{'u_y^p [um]':>12}{'t_x':>10}{'t_y':>10}{'p_N':>10}  status",
    ]
    for row in zip(pts["x_mm"], pts["y_mm"], pts["slip_x_um"], pts["slip_y_um"], pts["t_x"], pts["t_y"], pts["p_N"],
                   pts["status"]):
        lines.append(f"{row[0]:>8.3f}{row[1]:>8.3f}{row[2]:>12.4g}{row[3]:>12.4g}{row[4]:>10.4g}{row[5]:>10.4g}"
                     f"{row[6]:>10.4g}  {row[7]}")
    return "\n".join(lines)


def _progress(k: int, n: int, increment) -> None:
    print(f"increment {k}/{n}: load {increment.level:.6g} N, {increment.iterations} Newton iterations"
          f"{f', {increment.cutbacks} cut-backs' if increment.cutbacks else ''}", file=sys.stderr, flush=True)


def _render_beam(payload: dict[str, Any]) -> str:
    lines = [
        f"beam on a rigid base: law={payload['law']}  tangential={payload['tangential']}"
        f"  E*={payload['E_star']:.6g} N/mm^2  elements={payload['spec']['elements']}",
        f"u_N centre = {payload['u_N_centre_um']:+.4f} um   u_N end = {payload['u_N_end_um']:+.4f} um"
        "   (from the seated state, negative = approach)",
        f"open interface points: {payload['open_points']}   equilibrium error: {payload['equilibrium_error']:.1e}"
        f"   dofs: {payload['dofs']}   interface points: {payload['interface_points']}"
        f"   time: {payload['seconds']:.1f} s",
        f"Newton iterations per increment: {' '.join(map(str, payload['newton_iterations']))}",
        f"{'x [mm]':>10}{'u_N [um]':>12}{'p_N [N/mm^2]':>16}",
    ]
    lines += [f"{x:>10.2f}{u:>+12.4f}{p:>16.5g}" for x, u, p in zip(payload["x_mm"], payload["u_N_um"], payload["p_N"])]
    return "\n".join(lines)
