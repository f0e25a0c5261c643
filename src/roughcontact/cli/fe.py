"""The finite-element commands of ``roughcontact``: ``fe beam`` (example 9.1).

    roughcontact fe beam --m00 M --m20 M --m02 M --m40 M --m04 M [--E-star E]
        [--law elastic|elastoplastic --psi PSI] [--load 1962] [--initial-load 4.9]
        [--tangential free|stick|coulomb] [--mu MU] [--elements quadratic|cubic]
        [--increments 16] [--n-x 25] [--n-z 6] [--vtu FILE] [--quiet] [--json]

Moments in µm (the paper's surfaces), stresses in N/mm², lengths of the beam in mm. Progress
(one line per load increment) goes to stderr unless --quiet. Exit codes as the other commands;
a run that does not converge exits 1 naming the increment and the residual.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from . import CLIError, _MOMENTS, _real

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
    p.add_argument("--vtu", type=Path, default=None, metavar="FILE",
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

        write_solution(args.vtu, result.mesh, result.solution.final.u, interface_fields(result))
    payload = result.summary()
    payload.update(law=args.law, psi=args.psi, tangential=args.tangential, mu=args.mu, E_star=args.E_star,
                   moments={"m00": run["m00"], **moments}, vtu=str(args.vtu) if args.vtu else None)
    return payload


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
