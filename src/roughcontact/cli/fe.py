"""The finite-element commands of ``roughcontact``: ``fe run`` (your own model: a CalculiX/Abaqus
deck with the statistical interface law), ``fe beam`` (example 9.1) and ``fe punch`` (example
9.2), the two examples being decks of the same kind run through the same reader.

    roughcontact fe run MODEL.inp --interface LAW.yaml [--elements quadratic|cubic]
        [--increments N] [--max-increments N]
        [--vtu OUT.pvd] [--quiet] [--json]
    roughcontact fe beam --m00 M --m20 M --m02 M --m40 M --m04 M [--E-star E]
        [--law elastic|elastoplastic --psi PSI] [--load 1962] [--initial-load 4.9]
        [--tangential free|stick|coulomb] [--mu MU] [--elements quadratic|cubic]
        [--increments 16] [--n-x 25] [--n-z 6] [--vtu FILE] [--quiet] [--json]
    roughcontact fe punch --case a|b|c [--m00 0.625 ...] [--elements quadratic|cubic]
        [--load 1000 (N, whole punch)] [--load-on whole|quarter] [--load-patch SIDE]
        [--seating-pressure P0] [--E-star E] [--law elastic|elastoplastic] [--psi 0.35]
        [--tangential incremental|incremental-start|secant] [--increments 16] [--vtu FILE]
        [--quiet] [--json]
    roughcontact fe msh2inp MODEL.msh -o MODEL.inp [--template FILE]   (a gmsh mesh as a deck: fe.msh)

``fe run``: docs/own-model.md (the deck subset, LAW.yaml, the JSON and the series). For the
examples: moments in µm (the paper's surfaces), stresses in N/mm², lengths in mm. Progress
(one line per load increment) goes to stderr unless --quiet. Exit codes as the other commands;
a run that does not converge exits 1 naming the step, the increment and the residual. The
law's model validity is judged on the solved pressures (warnings).
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from ..limits import describe
from . import EXIT_INTERRUPTED, CLIError, _MOMENTS, _real, output_file, writing

__all__ = ["add_commands"]

LAWS = ("elastic", "elastoplastic")
TANGENTIAL = ("free", "stick", "coulomb")  # roughcontact.examples.beam.TANGENTIAL (checked by the tests)
FAMILIES = ("quadratic", "cubic")  # roughcontact.fe.deck_mesh.FAMILIES
LINEAR_SOLVERS = ("auto", "condensed", "sparse", "condensed-krylov", "sparse-krylov")  # roughcontact.fe.solver
#: the friction update's status codes (roughcontact.interface.friction STICK, SLIP, OPEN) by name
STATUS_NAMES = ("stick", "slip", "open")
#: "incremental" is the (93) form with k_T at the end of the increment
TANGENTIAL_FORMS = {"incremental": "incremental-end", "incremental-start": "incremental-start", "secant": "secant"}
#: fe beam warns when its discretisation error estimate exceeds this share of the centre
#: deflection (the convergence band of config.yaml fe.beam.study.convergence)
MESH_RTOL = 0.01


def add_commands(sub, parents) -> None:
    fe = sub.add_parser("fe", help="finite-element contact: your deck, or the examples of section 9",
                        description="3D finite-element contact through the statistical interface law.")
    fe_sub = fe.add_subparsers(dest="example", metavar="COMMAND", required=True)
    _add_run(fe_sub, parents[1:])
    _add_beam(fe_sub, parents)
    _add_punch(fe_sub, parents[1:])
    _add_msh2inp(fe_sub, parents[1:])


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {describe(text)}") from None


def _progress(step: int, n_steps: int, k: int, n: int | None, increment) -> None:
    """One line per converged increment (n None: a step whose increments grow, count unknown)."""
    of = "" if n is None else f"/{n}"
    print(f"step {step}/{n_steps}, increment {k}{of}: {increment.iterations} Newton iterations"
          f"{f', {increment.cutbacks} cut-backs' if increment.cutbacks else ''}", file=sys.stderr, flush=True)


def _level_progress(k: int, n: int, increment) -> None:
    print(f"increment {k}/{n}: {increment.iterations} Newton iterations"
          f"{f', {increment.cutbacks} cut-backs' if increment.cutbacks else ''}", file=sys.stderr, flush=True)


def _solved(call):
    """Run a solve; no convergence → exit 1; the law's validity judged on the solved state."""
    from ..contact.validity import ModelValidityWarning
    from ..fe.solver import ConvergenceError

    try:
        result = call()
    except ConvergenceError as exc:
        raise CLIError(str(exc), code=1) from exc
    deck = getattr(result, "deck", result)
    for message in deck.validity_warnings():
        warnings.warn(message, ModelValidityWarning, stacklevel=2)
    return result


# ---------------------------------------------------------------------------------------------
# fe run
# ---------------------------------------------------------------------------------------------
def _add_run(sub, parents) -> None:
    p = sub.add_parser(
        "run", parents=parents, help="your own model: a CalculiX/Abaqus deck with the statistical interface law",
        description="Run a CalculiX/Abaqus input deck (C3D20 or C3D10 elements, *CONTACT PAIR between conforming faces) with "
        "the statistical normal law and the orthotropic hardening friction of LAW.yaml in place of each "
        "*SURFACE INTERACTION (docs/own-model.md).",
    )
    p.add_argument("deck", type=Path, metavar="MODEL.inp", help="the input deck")
    p.add_argument("--interface", type=Path, required=True, metavar="LAW.yaml", help="the interface law of every interaction")
    p.add_argument("--elements", choices=FAMILIES, default="quadratic",
                   help="transition + interface elements on the contact faces: 21-node + 18-node (quadratic, "
                   "default) or 28-node + 32-node (cubic)")
    p.add_argument("--increments", type=_int, default=None, metavar="N",
                   help="every step in N fixed increments, in place of *STATIC's initial and maximum increments")
    p.add_argument("--max-increments", dest="max_increments", type=_int, default=None, metavar="N",
                   help="every step's maximum number of increments, in place of *STEP, INC=")
    p.add_argument("--vtu", type=output_file, default=None, metavar="OUT.pvd",
                   help="a ParaView series: OUT.pvd and OUT/<increment>.vtu, OUT/<increment>_interface.vtu")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.add_argument("--solver", choices=LINEAR_SOLVERS, default="auto",
                   help="the linear solves (roughcontact.fe.solver, docs/performance.md): auto (default), condensed, "
                   "sparse, or either with its factor reused as a GMRES preconditioner (condensed-krylov, sparse-krylov); auto is "
                   "condensed-krylov up to 3000 interface dofs, else sparse-krylov; the sparse factorisation is MKL PARDISO "
                   "when the optional package pypardiso is installed (much faster on large models), else SuperLU")
    p.set_defaults(func=_run_deck, render=_render_deck)


def _run_deck(args) -> dict[str, Any]:
    from ..fe.deck_run import run_deck_file
    from ..fe.solver import NewtonOptions

    if args.vtu is not None and args.vtu.suffix.lower() != ".pvd":
        raise CLIError(f"--vtu takes a .pvd file (the series), got {describe(str(args.vtu))}")
    _check_run_increments(args)
    try:
        result = _solved(lambda: run_deck_file(args.deck, args.interface, args.elements,
                                               NewtonOptions(linear_solver=args.solver),
                                               progress=None if args.quiet else _progress,
                                               increments=args.increments, max_increments=args.max_increments))
        if args.vtu is not None:
            from ..fe.pvd import write_series

            # the series goes to a temporary folder, renamed into place when whole (fe.pvd)
            with writing(args.vtu, "--vtu", atomic=False) as path:
                write_series(path, result)
    except KeyboardInterrupt:  # Ctrl-C: one line, no traceback; write_series removed its temporaries
        written = f"; nothing written to {args.vtu}" if args.vtu is not None else ""
        raise CLIError(f"interrupted{written}", code=EXIT_INTERRUPTED) from None
    out = result.summary()
    out["vtu"] = str(args.vtu) if args.vtu else None
    return out


def _check_run_increments(args) -> None:
    """--increments and --max-increments of fe run within 1 ... fe.deck.MAX_INCREMENTS."""
    from ..fe.deck import MAX_INCREMENTS

    for name in ("increments", "max_increments"):
        value = getattr(args, name)
        if value is not None and not 1 <= value <= MAX_INCREMENTS:
            raise CLIError(f"--{name.replace('_', '-')} {value}: must lie in 1 ... {MAX_INCREMENTS}")


def _render_deck(payload: dict[str, Any]) -> str:
    lines = [f"{payload['deck']}: {payload['dofs']} dofs, {payload['interface_points']} interface points, "
             f"{payload['elements']} elements, {payload['newton_iterations']} Newton iterations, "
             f"{payload['cutbacks']} cut-backs, {payload['seconds']:.1f} s"]
    lines += [f"E* of {name}: {e:.6g}" for name, e in payload["E_star"].items()]
    for step in payload["steps"]:
        f = step["interface"]
        status = {s: f["status"].count(s) for s in STATUS_NAMES}
        lines.append(f"step {step['step']} (time {step['time']:g}, {step['increments']} increments): p_N "
                     f"{min(f['p_N']):.4g} ... {max(f['p_N']):.4g}, u_N {min(f['u_N_um']):.4g} ... {max(f['u_N_um']):.4g} um, "
                     + ", ".join(f"{v} {k}" for k, v in status.items()))
        for name, ns in step.get("node_sets", {}).items():
            u = np.asarray(ns["u"]).reshape(-1, 3)
            if len(u):
                lines.append(f"  {name}: {len(u)} nodes, mean u = ({', '.join(f'{v:.6g}' for v in u.mean(axis=0))})")
    lines += [f"note: {n}" for n in payload["notes"]]
    if payload.get("vtu"):
        lines.append(f"wrote {payload['vtu']}")
    return "\n".join(lines)


def _add_msh2inp(sub, parents) -> None:
    p = sub.add_parser("msh2inp", parents=parents, help="a gmsh .msh with physical groups as a deck's mesh, sets and surfaces",
                       description="Write the *NODE, *ELEMENT (C3D10/C3D20), *NSET and *SURFACE lines of a gmsh mesh "
                       "(physical groups: volumes, contact faces, supports; docs/own-model.md, From gmsh).")
    p.add_argument("msh", type=Path, metavar="MODEL.msh", help="the gmsh mesh (gmsh -order 2)")
    p.add_argument("-o", dest="out", type=output_file, required=True, metavar="MODEL.inp", help="the deck to write")
    p.add_argument("--template", type=Path, default=None, metavar="FILE",
                   help="text appended to the deck (materials, sections, contact pairs, steps)")
    p.set_defaults(func=_msh2inp, render=lambda payload: f"wrote {payload['deck']}")


def _msh2inp(args) -> dict[str, Any]:
    from ..fe.msh import MISSING, MshError, msh_deck

    try:
        template = None if args.template is None else args.template.read_text()
    except OSError as exc:
        raise CLIError(f"--template {args.template}: cannot read it ({exc.strerror or exc})") from None
    try:
        text = msh_deck(args.msh, template)
    except MshError as exc:
        raise CLIError(str(exc)) from None
    with writing(args.out, "-o") as path:
        path.write_text(text)
    if template is None:
        print(f"note: {MISSING}", file=sys.stderr)
    return {"deck": str(args.out), "template": None if args.template is None else str(args.template)}


# ---------------------------------------------------------------------------------------------
# fe beam
# ---------------------------------------------------------------------------------------------
def _add_beam(sub, parents) -> None:
    from ..examples.section9 import BEAM, BEAM_E_STAR

    p = sub.add_parser(
        "beam", parents=parents, help="prismatic beam on a rigid base (example 9.1, Table 4, Fig. 13)",
        description="Beam 500 x 10 x 120 mm on its 500 x 10 face on a rigid base through the statistical "
        "interface (moments in um), loaded at mid-length: the initial load, then --load in --increments "
        "steps (the deck roughcontact/examples/decks/beam.inp). u_N is the interface deflection from the seated "
        "state, negative = approach [um]. The discretisation error is estimated against a mesh of half the "
        "elements each way (a warning above 1 % of the centre deflection).",
    )
    p.add_argument("--E-star", dest="E_star", type=_real, default=BEAM_E_STAR, metavar="E",
                   help=f"effective modulus E* [N/mm^2] (default E1/(1-nu1^2) = {BEAM_E_STAR:.6g}, eq. (42))")
    p.add_argument("--law", choices=LAWS, default="elastic", help="normal law (default elastic)")
    p.add_argument("--psi", type=_real, default=None, metavar="PSI",
                   help="plasticity index of the elasto-plastic law (closure yield-from-psi)")
    p.add_argument("--load", type=_real, default=BEAM["load"], metavar="N", help="load on the full beam [N] (1962)")
    p.add_argument("--initial-load", dest="initial_load", type=_real, default=BEAM["initial_load"], metavar="N",
                   help="seating load [N] (4.9): the reference state of u_N")
    p.add_argument("--tangential", choices=TANGENTIAL, default="free",
                   help="tangential restraint: free sliding, k_T (Mindlin) without slip, or k_T with a "
                   "Coulomb limit --mu (default free)")
    p.add_argument("--mu", type=_real, default=None, metavar="MU", help="Coulomb coefficient (with coulomb)")
    p.add_argument("--elements", choices=FAMILIES, default="cubic",
                   help="28-node transition + 32-node interface (cubic) or 21 + 18 (quadratic)")
    p.add_argument("--increments", type=_int, default=BEAM["increments"], metavar="N", help="load increments (16)")
    p.add_argument("--n-x", dest="n_x", type=_int, default=25, metavar="N", help="elements along the half beam")
    p.add_argument("--n-z", dest="n_z", type=_int, default=6, metavar="N", help="elements over the height")
    p.add_argument("--vtu", type=output_file, default=None, metavar="FILE",
                   help="write the mesh with displacements to FILE and the interface points to "
                   "FILE's stem + '_interface.vtu'")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=_run_beam, render=_render_beam)


def _beam_dofs(n_x: int, n_z: int, elements: str) -> int:
    """An upper bound of the beam model's unknowns (3 per node), from its mesh of n_x × 1 × n_z
    20-node hexahedra over a base of n_x × 1 × 1 (examples.beam.beam_deck): a 20-node grid of
    a × b × c elements has at most (2a+1)(2b+1)(2c+1) nodes; each contact-face element adds
    its transition nodes (cubic: 8 per face, quadratic: 1)."""
    extra = 8 if elements == "cubic" else 1
    return 3 * ((2 * n_x + 1) * 3 * (2 * n_z + 1) + (2 * n_x + 1) * 3 * 3 + 2 * extra * n_x)


def _check_increments(args) -> None:
    """--increments within what a deck's step may have (fe.deck.MAX_INCREMENTS), said of the
    option rather than of the example's generated deck."""
    from ..fe.deck import MAX_INCREMENTS

    if args.increments < 1 or args.increments > MAX_INCREMENTS:
        raise CLIError(f"--increments {args.increments}: must lie in 1 ... {MAX_INCREMENTS} (the increments of a step)")


def _check_beam_size(args) -> None:
    """Refuse a beam model beyond the limit "fe_dofs" (roughcontact.limits) before it is built
    (one line naming the options, the limit and how to raise it)."""
    from ..limits import check_count

    for name in ("n_x", "n_z"):
        if getattr(args, name) < 1:
            raise CLIError(f"--{name.replace('_', '-')} must be a positive integer, got {getattr(args, name)}")
    dofs = _beam_dofs(args.n_x, args.n_z, args.elements)
    check_count(float(dofs), "fe_dofs", f"--n-x {args.n_x} --n-z {args.n_z}: the model's unknowns (at most)")


def _beam_moments(args) -> dict[str, float]:
    """The five moments in µm (the beam's unit): --m00 … --m04 as given, or --moments FILE
    (cli.contact's reader; moments in another stated length unit converted, eq. units
    m00·f², m40·f⁻²; a file without a unit read in µm like the numbers)."""
    from ..readers import moments_in_unit
    from .contact import _surface_from

    surface = _surface_from(args)
    unit = getattr(args, "moments_unit", None)
    if unit is not None and unit != "um":
        surface = moments_in_unit(surface, unit, "um")
    return {name: float(getattr(surface, name)) for name in _MOMENTS}


def _run_beam(args) -> dict[str, Any]:
    from ..examples.beam import BeamRun, BeamSpec, run_beam

    _check_increments(args)
    _check_beam_size(args)
    moments = _beam_moments(args)
    if (args.psi is not None) != (args.law == "elastoplastic"):
        raise CLIError("--psi is needed with --law elastoplastic and only used there")
    spec = BeamSpec(elements=args.elements, load=args.load, initial_load=args.initial_load,
                    increments=args.increments, n_x=args.n_x, n_z=args.n_z)
    run = BeamRun(spec=spec, m00=moments.pop("m00"), surface=tuple(moments.items()), law=args.law, psi=args.psi,
                  E_star=args.E_star, tangential=args.tangential, mu=args.mu)
    result = _solved(lambda: run_beam(run, progress=None if args.quiet else _level_progress))
    coarse_spec = (max(1, math.ceil(args.n_x / 2)), max(1, math.ceil(args.n_z / 2)))
    if coarse_spec != (args.n_x, args.n_z):
        coarse = _solved(lambda: run_beam(run.with_(spec={"n_x": coarse_spec[0], "n_z": coarse_spec[1]})))
        estimate = max(abs(result.u_N_centre_um - coarse.u_N_centre_um), abs(result.u_N_end_um - coarse.u_N_end_um))
        check = {"coarse_mesh": list(coarse_spec), "u_N_centre_um": coarse.u_N_centre_um,
                 "u_N_end_um": coarse.u_N_end_um, "estimate_um": estimate}
        if estimate > MESH_RTOL * abs(result.u_N_centre_um):
            warnings.warn(f"discretisation error: the deflections move by up to {estimate:.3g} um "
                          f"({100 * estimate / abs(result.u_N_centre_um):.2g} % of the centre deflection) against a "
                          f"mesh of {coarse_spec[0]} x {coarse_spec[1]} elements; refine --n-x, --n-z", stacklevel=1)
    else:
        check = {"coarse_mesh": None, "estimate_um": None}
        warnings.warn("discretisation error not estimated: one element each way has no coarser mesh; refine "
                      "--n-x, --n-z", stacklevel=1)
    if args.vtu is not None:
        with writing(args.vtu, "--vtu", atomic=False) as path:  # fe.vtu writes its files atomically
            result.write_vtu(path)
    payload = result.summary()
    payload.update(law=args.law, psi=args.psi, tangential=args.tangential, mu=args.mu, E_star=args.E_star,
                   moments={"m00": run.m00, **moments}, discretisation=check,
                   vtu=str(args.vtu) if args.vtu else None)
    return payload


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
    ]
    d = payload["discretisation"]
    if d["coarse_mesh"]:
        lines.append(f"discretisation estimate: {d['estimate_um']:.3g} um (against {d['coarse_mesh'][0]} x "
                     f"{d['coarse_mesh'][1]} elements)")
    lines.append(f"{'x [mm]':>10}{'u_N [um]':>12}{'p_N [N/mm^2]':>16}")
    lines += [f"{x:>10.2f}{u:>+12.4f}{p:>16.5g}" for x, u, p in zip(payload["x_mm"], payload["u_N_um"], payload["p_N"])]
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# fe punch
# ---------------------------------------------------------------------------------------------
def _add_punch(sub, parents) -> None:
    from ..examples.section9 import PUNCH, PUNCH_M00, PUNCH_PSI, SURFACE

    p = sub.add_parser(
        "punch", parents=parents, help="flat punch on an elastic foundation with orthotropic friction (example 9.2)",
        description="Punch 20 x 20 x 10 mm on a foundation 100 x 100 x 50 mm (E = 200 GPa, nu = 0.25; quarter "
        "model) through the statistical interface with the orthotropic hardening friction of Fig. 18's case; "
        "seated, loaded on a centred patch of the punch top in --increments steps, unloaded likewise (the deck "
        "roughcontact/examples/decks/punch.inp). Prints the dissipation D, its frictionless upper bound and the "
        "state of every contact point at the maximum load.",
    )
    p.add_argument("--case", choices=("a", "b", "c"), required=True, help="friction parameters of Fig. 18 (a, b, c)")
    for name, value in {"m00": PUNCH_M00, **SURFACE}.items():
        p.add_argument(f"--{name}", type=_real, default=value, metavar="M", help=f"{name} (default {value:g}, um units)")
    p.add_argument("--elements", choices=FAMILIES, default="quadratic",
                   help="21-node + 18-node (quadratic, 81 points) or 28-node + 32-node (cubic, 100 points)")
    p.add_argument("--load", type=_real, default=PUNCH["load"], metavar="N", help="maximum patch load [N] (1000)")
    p.add_argument("--load-on", dest="load_on", choices=("whole", "quarter"), default="whole",
                   help="the load acts on the whole punch (default) or on the quarter model")
    p.add_argument("--load-patch", dest="load_patch", type=_real, default=None, metavar="SIDE",
                   help="side of the centred loaded square on the whole punch [mm] (default: the punch's central element)")
    p.add_argument("--seating-pressure", dest="seating_pressure", type=_real, default=0.1, metavar="P0",
                   help="seating pressure on the punch top [N/mm^2] (0.1): the reference state")
    p.add_argument("--E-star", dest="E_star", type=_real, default=None, metavar="E",
                   help="effective modulus [N/mm^2] (default: two like bodies, E/(2(1-nu^2)), eq. (42))")
    p.add_argument("--law", choices=LAWS, default="elastoplastic", help="normal law (default elastoplastic)")
    p.add_argument("--psi", type=_real, default=None, metavar="PSI",
                   help=f"plasticity index of the elasto-plastic law (default {PUNCH_PSI}; not with --law elastic)")
    p.add_argument("--tangential", choices=tuple(TANGENTIAL_FORMS), default="incremental",
                   help="how k_T enters (93): incremental (k_T at the end of the increment), incremental-start, "
                   "or secant (a total elastic law)")
    p.add_argument("--increments", type=_int, default=PUNCH["increments"], metavar="N",
                   help="loading and unloading increments (16)")
    p.add_argument("--vtu", type=output_file, default=None, metavar="FILE",
                   help="write both bodies with displacements (maximum load) to FILE and the contact points "
                   "to FILE's stem + '_interface.vtu'")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=_run_punch, render=_render_punch)


def _run_punch(args) -> dict[str, Any]:
    from ..examples.punch import PunchRun, PunchSpec, dissipation, frictionless_bound, mu_max, run_punch, summary_of
    from ..examples.punch_geometry import PunchGeometry
    from ..examples.section9 import PUNCH_PSI

    if args.law == "elastic" and args.psi is not None:
        raise CLIError("--psi is only used with --law elastoplastic")
    _check_increments(args)
    psi = (PUNCH_PSI if args.psi is None else args.psi) if args.law == "elastoplastic" else None
    geometry = PunchGeometry(family=args.elements, **({} if args.load_patch is None else {"load_patch": args.load_patch}))
    spec = PunchSpec(geometry=geometry, load=args.load, load_on=args.load_on, seating_pressure=args.seating_pressure,
                     increments=args.increments, unload_increments=args.increments)
    run = PunchRun(case=args.case, spec=spec, m00=args.m00, law=args.law, psi=psi, E_star=args.E_star,
                   tangential_form=TANGENTIAL_FORMS[args.tangential],
                   surface=tuple((k, getattr(args, k)) for k in ("m20", "m02", "m40", "m04")))
    progress = None if args.quiet else _level_progress
    result = _solved(lambda: run_punch(run, progress=progress))
    free = _solved(lambda: run_punch(run.with_(case="frictionless"), progress=progress))
    mu = mu_max(args.case)
    D, bound = dissipation(result, whole=True), frictionless_bound(result, free, mu, whole=True)
    if D > bound:
        warnings.warn(f"D = {D:.4g} N mm exceeds the frictionless bound {bound:.4g} N mm: the bound's premise (friction "
                      "only reduces the relative slip of the frictionless problem) does not hold here", stacklevel=1)
    points = result.fields()
    if args.vtu is not None:
        with writing(args.vtu, "--vtu", atomic=False) as path:  # fe.vtu writes its files atomically
            result.write_vtu(path)
    summary = summary_of(result)
    return {
        "dissipation_quarter_Nmm": dissipation(result, whole=False),
        "dissipation_full_Nmm": D,
        "dissipation_work_full_Nmm": dissipation(result, weight="work", whole=True),
        "frictionless_bound_quarter_Nmm": frictionless_bound(result, free, mu, whole=False),
        "frictionless_bound_full_Nmm": bound,
        "newton_iterations": summary["newton_iterations"],
        "equilibrium_error": summary["equilibrium_error_max_load"],
        "dofs": summary["dofs"], "interface_points": summary["interface_points"], "seconds": summary["seconds"],
        "E_star": summary["E_star"], "law": args.law, "psi": psi,
        "points": {**{k: np.asarray(v).tolist() for k, v in points.items()},
                   "status": [STATUS_NAMES[int(v)] for v in points["status"]]},
        "case": args.case, "elements": args.elements, "spec": summary["spec"],
        "units": {"dissipation": "N mm", "x_mm": "mm", "slip_um": "um (plastic slip at the maximum load)",
                  "t_x, t_y, p_N, E_star": "N/mm^2", "utilisation": "1 (|t_T|/(mu p_N) on the limit (91); 1 slip)",
                  "seconds": "s"},
    }


def _render_punch(payload: dict[str, Any]) -> str:
    pts = payload["points"]
    lines = [
        f"punch on foundation, case {payload['case']}, {payload['elements']} elements, {payload['law']} law, "
        f"E* = {payload['E_star']:.6g} N/mm^2: {payload['interface_points']} contact points, {payload['dofs']} dofs, "
        f"{payload['seconds']:.1f} s",
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
