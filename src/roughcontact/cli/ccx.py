"""``roughcontact ccx build`` and ``roughcontact ccx run``: the interface law inside CalculiX
(roughcontact.ccx, docs/ccx.md).

    roughcontact ccx build [--source DIR] [--jobs N] [--force] [--json]
    roughcontact ccx run MODEL.inp --interface LAW.yaml [--keep DIR] [--ccx EXE] [--increments N]
                         [--threads N] [--timeout S] [--quiet] [--json]

``ccx build`` compiles CalculiX 2.20 from Debian's source package with the law as a user element
and caches it outside the clone (``$ROUGHCONTACT_CCX_CACHE`` or ``~/.cache/roughcontact``); a
second call finds it. ``ccx run`` takes the deck and the law file of ``fe run`` and prints the same
JSON. Without the build tools or the source, one line says what to install (exit 2).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np

from . import CLIError

__all__ = ["add_command"]


def add_command(sub, parents) -> None:
    ccx = sub.add_parser("ccx", help="the interface law inside CalculiX: build ccx with it, run your deck in it",
                         description="CalculiX 2.20 with the statistical normal law and the orthotropic hardening "
                         "friction as a user element (docs/ccx.md).")
    ccx_sub = ccx.add_subparsers(dest="ccx_command", metavar="COMMAND", required=True)
    b = ccx_sub.add_parser("build", parents=parents, help="build ccx 2.20 with the law (minutes; cached)",
                           description="Build CalculiX 2.20 from Debian's source package with the interface law as a "
                           "user element, into the cache (ROUGHCONTACT_CCX_CACHE or ~/.cache/roughcontact). Needs "
                           "gfortran, gcc, make, libspooles-dev, libarpack2-dev and the source (apt-get source "
                           "calculix-ccx, or --source).")
    b.add_argument("--source", type=Path, default=None, metavar="DIR",
                   help="Debian's calculix-ccx 2.20 source: the unpacked calculix-ccx-2.20 tree or a folder with its .dsc")
    b.add_argument("--jobs", type=int, default=None, metavar="N", help="parallel compilations (default: the cores)")
    b.add_argument("--force", action="store_true", help="build again even if the cache has this build")
    b.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    b.set_defaults(func=_build, render=lambda p: f"ccx {p['ccx']} with the interface law: {p['executable']}"
                   f" ({'cached' if p['cached'] else 'built'}; build {p['key']})")
    r = ccx_sub.add_parser("run", parents=parents, help="your deck and law file in the built ccx (the JSON of fe run)",
                           description="Run a deck (C3D20 or C3D10, *CONTACT PAIR between conforming faces) with the "
                           "interface law of LAW.yaml in the ccx of `roughcontact ccx build`: each contact pair's faces "
                           "joined by user elements carrying the law; prints what `fe run` prints.")
    r.add_argument("deck", type=Path, metavar="MODEL.inp", help="the input deck")
    r.add_argument("--interface", type=Path, required=True, metavar="LAW.yaml", help="the interface law of every interaction")
    r.add_argument("--keep", type=Path, default=None, metavar="DIR",
                   help="run in DIR and keep the rewritten deck (<model>_ccx.inp) and ccx's files there")
    r.add_argument("--ccx", type=Path, default=None, metavar="EXE",
                   help="a ccx with the law compiled in (default: the cached build of `roughcontact ccx build`)")
    r.add_argument("--increments", type=int, default=None, metavar="N",
                   help="every step in N fixed increments (as fe run --increments N)")
    r.add_argument("--threads", type=int, default=1, metavar="N", help="ccx's threads (default 1)")
    r.add_argument("--timeout", type=float, default=None, metavar="S", help="stop ccx after S seconds")
    r.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    r.set_defaults(func=_run, render=_render_run)


def _progress(quiet: bool):
    return (lambda message: None) if quiet else (lambda message: print(message, file=sys.stderr, flush=True))


def _build(args) -> dict[str, Any]:
    from ..ccx.build import CCX_VERSION, BuildError, build_ccx

    if args.jobs is not None and not 1 <= args.jobs <= 256:
        raise CLIError(f"--jobs {args.jobs}: must lie in 1 ... 256")
    try:
        build = build_ccx(source=args.source, jobs=args.jobs, force=args.force, progress=_progress(args.quiet))
    except BuildError as exc:
        raise CLIError(str(exc)) from None
    return {"ccx": CCX_VERSION, "executable": str(build.executable), "folder": str(build.folder),
            "key": build.info.get("key"), "cached": build.cached, "build": build.info}


def _run(args) -> dict[str, Any]:
    from ..ccx.build import find_build
    from ..ccx.run import CCXRunError, run_deck_in_ccx

    if not 1 <= args.threads <= 256:
        raise CLIError(f"--threads {args.threads}: must lie in 1 ... 256")
    if args.timeout is not None and not args.timeout > 0:
        raise CLIError(f"--timeout {args.timeout}: must be positive")
    if args.ccx is not None:
        if not args.ccx.is_file():
            raise CLIError(f"--ccx {args.ccx}: no such file")
        exe, info = args.ccx, {}
    else:
        build = find_build()
        if build is None:
            raise CLIError("no ccx with the interface law: run `roughcontact ccx build` first (docs/ccx.md)")
        exe, info = build.executable, build.info
    if args.keep is not None and args.keep.exists() and not args.keep.is_dir():
        raise CLIError(f"--keep {args.keep}: not a directory")
    try:
        return run_deck_in_ccx(args.deck, args.interface, exe, keep=args.keep, threads=args.threads,
                               timeout=args.timeout, progress=_progress(args.quiet), build_info=info,
                               increments=args.increments)
    except CCXRunError as exc:
        raise CLIError(str(exc), code=1) from None


def _render_run(payload: dict[str, Any]) -> str:
    lines = [f"{payload['deck']} in ccx: {payload['dofs']} equations, {payload['interface_points']} interface points, "
             f"{payload['newton_iterations']} iterations, {payload['cutbacks']} cut-backs, {payload['seconds']:.1f} s"]
    lines += [f"E* of {name}: {e:.6g}" for name, e in payload["E_star"].items()]
    for step in payload["steps"]:
        f = step["interface"]
        counts = {s: f["status"].count(s) for s in dict.fromkeys(f["status"])}
        lines.append(f"step {step['step']} (time {step['time']:g}, {step['increments']} increments): p_N "
                     f"{min(f['p_N']):.4g} ... {max(f['p_N']):.4g}, u_N {min(f['u_N_um']):.4g} ... "
                     f"{max(f['u_N_um']):.4g} um, " + ", ".join(f"{v} {k}" for k, v in counts.items()))
        for name, ns in step["node_sets"].items():
            u = np.asarray(ns["u"]).reshape(-1, 3)
            if len(u):
                lines.append(f"  {name}: {len(u)} nodes, mean u = ({', '.join(f'{v:.6g}' for v in u.mean(axis=0))})")
    lines += [f"note: {n}" for n in payload["notes"]]
    if payload["ccx"]["job"]:
        lines.append(f"kept {payload['ccx']['job']} ({payload['ccx']['deck']})")
    return "\n".join(lines)
