"""``roughcontact plot RESULT.json [...] -o fig.png|pdf``: contact results of ``elastic`` /
``elastoplastic ... --json`` drawn with :func:`roughcontact.plots.contact_curves`, several overlaid."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from . import CLIError, output_file

__all__ = ["add_command"]


def add_command(sub, parents) -> None:
    """Register ``plot`` (on the output parent)."""
    p = sub.add_parser(
        "plot", parents=parents, help="draw contact results (JSON of elastic/elastoplastic) as a figure",
        description="A/A0, W/A0, K_N/A0 and k_Tx, k_Ty per unit nominal area against the separation s or the "
        "nominal pressure, one panel each, every RESULT (JSON written by roughcontact elastic/elastoplastic "
        "--json) overlaid. Needs matplotlib (the workflow extra).")
    p.add_argument("results", nargs="+", metavar="RESULT.json", help="results of roughcontact elastic/elastoplastic --json")
    p.add_argument("-o", "--output", type=output_file, required=True, metavar="FILE",
                   help="the figure: .png, .pdf or .svg")
    p.add_argument("--x", dest="x", choices=("separation", "pressure"), default="separation",
                   help="abscissa: the separation s = h/sqrt(m00) (default) or the nominal pressure")
    p.add_argument("--label", dest="labels", action="append", default=None, metavar="TEXT",
                   help="legend entry of each result, in order (default: the file names)")
    p.add_argument("--stress-unit", dest="stress_unit", default=None, metavar="UNIT",
                   help="unit of E* for the axes (UDUNITS, e.g. N/mm^2; default 'unit of E*')")
    p.add_argument("--length-unit", dest="length_unit", default=None, metavar="UNIT",
                   help="length unit of the moments (default: the results' length_unit, else L)")
    p.set_defaults(func=_run_plot, render=_render_plot)


def _load(path: str) -> dict:
    from ..readers.moments_file import read_json

    data = read_json(path)
    needed = ("s", "area_fraction", "pressure", "stiffness")
    missing = [k for k in needed if k not in data] if isinstance(data, dict) else list(needed)
    if missing:
        raise CLIError(f"{path}: not a contact result (no {', '.join(missing)}): write it with "
                       "roughcontact elastic/elastoplastic --json")
    return data


def _run_plot(args) -> dict[str, Any]:
    from ..plots import contact_curves, save_figure

    results = [_load(p) for p in args.results]
    labels = args.labels or [Path(p).stem for p in args.results]
    if len(labels) != len(results):
        raise CLIError(f"{len(labels)} --label for {len(results)} results")
    units = {r.get("length_unit") for r in results} - {None}
    if len(units) > 1 and args.length_unit is None:
        raise CLIError(f"the results are in different length units ({', '.join(sorted(units))}): plot them separately")
    length = args.length_unit or (units.pop() if units else None)
    try:
        fig = contact_curves(results, labels=labels, x=args.x, length_unit=length, stress_unit=args.stress_unit)
    except ImportError as exc:
        raise CLIError(str(exc)) from None
    save_figure(fig, args.output)
    return {"output": str(args.output), "results": list(args.results), "labels": labels, "x": args.x,
            "length_unit": length, "stress_unit": args.stress_unit}


def _render_plot(payload: dict[str, Any]) -> str:
    return f"wrote {payload['output']}: {len(payload['results'])} result(s) against {payload['x']}"
