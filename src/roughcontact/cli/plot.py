"""``roughcontact plot RESULT.json [...] -o fig.png|pdf``: contact results of ``elastic`` /
``elastoplastic ... --json`` drawn with :func:`roughcontact.plots.contact_curves`, several overlaid.

Bad input is one line (exit 2): ``--label a b`` (the flag takes one entry and repeats), a label or
unit matplotlib cannot typeset (checked before drawing), a RESULT that is not a contact result
(read within the limits of :mod:`roughcontact.limits`), a figure that cannot be written (a full
disk: naming -o; nothing is left under its name)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .. import limits
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
    _say_label_repeats(p)


def _say_label_repeats(p) -> None:
    """argparse leaves the second word of ``--label a b`` over, and the top parser says only
    "unrecognized arguments: b": wrap this subparser's parse_known_args (which argparse calls on
    the subparser instance; its class stays the shared one) to say that the flag repeats."""
    parse = p.parse_known_args

    def parse_known_args(args=None, namespace=None):
        ns, extras = parse(args, namespace)
        words = list(args or [])
        for i, word in enumerate(words):
            after = i + 2 if word == "--label" else i + 1 if word.startswith("--label=") else None
            if extras and after is not None and after < len(words) and words[after] == extras[0]:
                label = words[i + 1] if word == "--label" else word.split("=", 1)[1]
                p.error(f"--label takes one legend entry; repeat the flag for each result "
                        f"(--label {label} --label {words[after]}), got {limits.describe(words[after])} left over")
        return ns, extras

    p.parse_known_args = parse_known_args


def _load(path: str) -> dict:
    """A contact result read within the input limits (readers.moments_file.read_json): the lists
    plot draws must be numbers (not ``true``, not strings), all as long as ``s``; CLIError
    naming the file and the key otherwise."""
    from ..readers.moments_file import read_json

    data = read_json(path)
    needed = ("s", "area_fraction", "pressure", "stiffness")
    missing = [k for k in needed if k not in data] if isinstance(data, dict) else list(needed)
    if missing:
        raise CLIError(f"{path}: not a contact result (no {', '.join(missing)}): write it with "
                       "roughcontact elastic/elastoplastic --json")
    n = len(data["s"]) if isinstance(data["s"], list) else None
    for key in (*needed, *(k for k in ("k_Tx", "k_Ty") if k in data)):
        column = data[key]
        if not (isinstance(column, list) and column and len(column) == n
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in column)):
            raise CLIError(f"{path}: {key} must be a non-empty list of numbers as long as s, got "
                           f"{limits.describe(column)}")
    unit = data.get("length_unit")
    if unit is not None and not isinstance(unit, str):
        raise CLIError(f"{path}: length_unit must be a unit name or null, got {limits.describe(unit)}")
    return data


def _run_plot(args) -> dict[str, Any]:
    from ..write_errors import WriteError
    from ..plots import contact_curves, save_figure
    from ..plots.style import check_text

    results = [_load(p) for p in args.results]
    labels = args.labels or [Path(p).stem for p in args.results]
    if len(labels) != len(results):
        raise CLIError(f"{len(labels)} --label for {len(results)} results")
    units = {r.get("length_unit") for r in results} - {None}
    if len(units) > 1 and args.length_unit is None:
        raise CLIError(f"the results are in different length units ({', '.join(sorted(units))}): plot them separately")
    length = args.length_unit or (units.pop() if units else None)
    # every text drawn, typeset once before drawing (check_text): a label that is mathtext matplotlib
    # cannot parse would otherwise fail (or recurse without end) while the figure is saved
    texts = [(label, f"--label {limits.describe(label)}" if args.labels else
              f"the legend entry {limits.describe(label)} (the name of {path}; give --label)")
             for label, path in zip(labels, args.results)]
    texts += [(args.stress_unit, f"--stress-unit {limits.describe(args.stress_unit)}")] if args.stress_unit else []
    texts += [(length, f"--length-unit {limits.describe(length)}" if args.length_unit else
               f"the results' length_unit {limits.describe(length)}")] if length else []
    try:
        for text, what in texts:
            check_text(text, what)
        fig = contact_curves(results, labels=labels, x=args.x, length_unit=length, stress_unit=args.stress_unit)
    except ImportError as exc:
        raise CLIError(str(exc)) from None
    try:  # the axis labels combine the units (N/mm^2/um): draw once, before anything is written
        fig.canvas.draw()
    except RecursionError:
        raise CLIError("the figure's labels are nested too deeply to typeset: check --stress-unit, --length-unit") from None
    except ValueError as exc:
        raise CLIError(f"the figure's labels cannot be typeset ({' '.join(str(exc).split())[:200]}): check the $...$ "
                       "of --stress-unit and --length-unit") from None
    try:
        save_figure(fig, args.output)
    except WriteError as exc:  # a full disk: one line naming the option
        raise CLIError(f"-o: {exc}") from None
    return {"output": str(args.output), "results": list(args.results), "labels": labels, "x": args.x,
            "length_unit": length, "stress_unit": args.stress_unit}


def _render_plot(payload: dict[str, Any]) -> str:
    return f"wrote {payload['output']}: {len(payload['results'])} result(s) against {payload['x']}"
