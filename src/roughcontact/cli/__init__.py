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
    roughcontact moments FILE [--dx DX] [--dy DY] [--unit um] [--xy-unit U] [--z-unit U]
                         [--estimator fd|spectral] [--order 6] [--fill none|harmonic]
                         [--layout auto|grid|xyz] [--channel N] [--plot FILE.png] [--json]
    roughcontact plot RESULT.json [RESULT.json ...] -o FILE.png|pdf [--x separation|pressure]
                         [--label TEXT [--label TEXT ...]] [--stress-unit U] [--length-unit U]
    roughcontact export --format abaqus|calculix|csv --m00 M ... --m04 M --E-star E
                         [--law elastic|elastoplastic --psi P] --pressure-range PMIN PMAX
                         [--rtol 1e-3] [--seating-pressure P0] [--moments-unit um] [--length-unit NAME]
                         [--length-scale F] [--stress-scale G] [--mu MU --kt-over-kn A [--kt-at P]]
                         [-o FILE] [--law-table BEM.json] [--json]
    roughcontact bem SCAN --E-star E (--pressure P [P ...] | --pressure-range LO HI [--n-pressures N])
                         [--periodic] [--stress-unit U] [--law-table FILE] [--quiet] [--json]
                         (and the reading options of moments)
    roughcontact ccx build [--source DIR] [--jobs N] [--force] [--json]
    roughcontact ccx run MODEL.inp --interface LAW.yaml [--keep DIR] [--increments N] [--json]

The contact commands (elastic, elastoplastic) take --s, --h (length unit) or --pressure (the
separation solved, load control); E* as --E-star or --E1 --nu1 [--E2 --nu2] (eq. 42); a second
rough surface with --second-surface M00 M20 M02 M40 M04 (moments summed). Wherever the five
moments are asked, --moments FILE.json reads them (and their unit) from a file, two files for two
rough surfaces. Warnings raised during a computation are shown in the text output and as the JSON
list "warnings".

Files a command writes (export -o, moments --save-rotated, fe --vtu) are options of type
:func:`output_file` (checked at parsing, before any computation) written through :func:`writing`
(atomically, under exactly the name given).

Exit codes: 0 success; 2 bad input (one line on stderr, "roughcontact: error: ...");
1 a computed value is not finite (also an arithmetic error of the computation: a division by
zero or an overflow on inputs far outside the model's range); 141 (128 + SIGPIPE, as ``cat`` or ``seq`` give) when the
reader of the output went away (``roughcontact ... | head -1``): no message, no traceback. Any
other exception is a bug and propagates (traceback).
The library's warnings (results outside the model's range of validity) are printed as one
line each, "roughcontact: warning: ...", and do not change the exit code.

Lengths are in the unit L of the moments (m00 [L²], m20, m02 [–], m40, m04 [L⁻²]);
pressures come out in the unit of E*, stiffnesses in (unit of E*)/L.

Subcommands register themselves like :func:`_add_surface` / :func:`_add_elastic`: a subparser
built on the shared ``moments`` (and, for contact, ``contact``) parent parsers, with ``func``
set to a handler ``(args) -> payload dict`` and ``render`` set to the human-readable formatter
of that payload.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import json
import math
import os
import re
import sys
import warnings
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence

from .. import __version__
from ..files import atomic_path

__all__ = ["main", "build_parser", "CLIError", "output_file", "writing"]

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
# does not import numba (tests/cli/test_contact_commands.py checks they match contact.elastic.MODELS/HERTZ/METHODS).
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
    """ArgumentParser whose errors are one stderr line (no usage block), exit code 2, and that
    reads a negative number in any form ``float()`` accepts ("-1e6", "-1.04e-4", "-.5") as a
    value: argparse's own pattern knows only "-12" and "-1.5", so ``--s -1e6`` failed with
    "expected one argument". Subcommand parsers are built with ``type(parent)`` by argparse,
    so every subcommand, also one added later, inherits both."""

    #: argparse.ArgumentParser._negative_number_matcher, widened to exponents
    NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = self.NEGATIVE_NUMBER

    def error(self, message: str):  # type: ignore[override]
        self.exit(2, f"{PROG}: error: {_one_line(message)}\n")


def _real(text: str) -> float:
    """argparse type: any string float() accepts; range checks are the library's."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a real number, got {text!r}") from None


# ---------------------------------------------------------------------------------------
# output files: every command that writes a file declares its option with type=output_file
# (checked when the arguments are parsed, before any computation) and writes through writing()
# ---------------------------------------------------------------------------------------
def output_file(text: str) -> Path:
    """argparse type of an option naming a file to write: a non-empty name, not a directory nor
    another existing non-regular file (/dev/null, a pipe: the atomic rename would replace it),
    in an existing writable directory (nothing is created). A bad name is a parse error: one
    line, exit 2, before the command computes anything."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty file name")
    path = Path(text)
    if path.is_dir() or text.endswith(os.sep):
        raise argparse.ArgumentTypeError(f"{text} is a directory, not a file")
    if path.exists() and not path.is_file():  # a device or a pipe: renaming onto it would replace it
        raise argparse.ArgumentTypeError(f"{text} is not a regular file (without the option the command prints)")
    parent = path.parent
    if not parent.is_dir():
        raise argparse.ArgumentTypeError(f"{text}: no such directory {str(parent)!r} (it is not created)")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise argparse.ArgumentTypeError(f"{text}: the directory {str(parent)!r} is not writable")
    return path


@contextlib.contextmanager
def writing(path: Path, option: str, *, atomic: bool = True) -> Iterator[Path]:
    """Yield a temporary path next to ``path`` to write; renamed onto ``path`` when the block
    succeeds (``roughcontact.files.atomic_path``: never a half-written file under the final
    name, the mode the umask gives). ``atomic=False`` yields ``path`` itself, for a library
    writer that writes atomically on its own (e.g. ``fe.vtu``). An OSError is one line
    (CLIError, exit 2) naming the option."""
    try:
        if atomic:
            with atomic_path(path) as tmp:
                yield tmp
        else:
            yield path
    except OSError as exc:
        raise CLIError(f"{option} {path}: cannot write it ({exc.strerror or exc})") from None


# ---------------------------------------------------------------------------------------
# parser
# ---------------------------------------------------------------------------------------
def _moments_parent() -> argparse.ArgumentParser:
    parent = _Parser(add_help=False)
    group = parent.add_argument_group("spectral moments (one consistent length unit L): the five, or --moments")
    for name in _MOMENTS:
        group.add_argument(
            f"--{name}", type=_real, default=None, metavar="M", help=_MOMENT_HELP[name]
        )
    group.add_argument(
        "--moments", dest="moments_files", nargs="+", default=None, metavar="FILE.json",
        help="the five moments (and their unit) from a JSON file, e.g. written by roughcontact moments "
        "SCAN --json; two files: two rough surfaces (moments summed)",
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
    _add_modulus_options(parent)
    where = parent.add_mutually_exclusive_group(required=True)
    where.add_argument(
        "--s", dest="s", type=_real, nargs="+", metavar="S",
        help="separations s = h/sqrt(m00) of the flat from the mean plane",
    )
    where.add_argument("--h", dest="h", type=_real, nargs="+", metavar="H",
                       help="separations h of the flat from the mean plane [L]")
    where.add_argument("--pressure", dest="pressure", type=_real, nargs="+", metavar="P",
                       help="nominal pressures W/A0 (unit of E*): the separation is solved (load control)")
    parent.add_argument("--hertz", choices=HERTZ, default="exact",
                        help="Hertz functions: exact, or the paper's approximations (default exact)")
    parent.add_argument("--method", choices=METHODS, default="production",
                        help="integrator: production (numba) or reference (slow twin)")
    parent.add_argument("--accuracy", choices=ACCURACIES, default="table",
                        help="production quadrature preset (default table)")
    parent.add_argument("--nu", dest="nu", type=_real, default=None, metavar="NU",
                        help="Poisson's ratio for Mindlin's k_Tx, k_Ty (eq. (96); default: --nu1, else 0.3)")
    return parent


def _add_modulus_options(parser) -> None:
    """E* directly, or from the two bodies' (E, nu) (eq. (42)); a second rough surface."""
    modulus = parser.add_mutually_exclusive_group(required=True)
    modulus.add_argument(
        "--E-star", dest="E_star", type=_real, metavar="E",
        help="effective modulus E* (any stress unit; the pressure comes out in it)",
    )
    modulus.add_argument("--E1", dest="E1", type=_real, metavar="E",
                         help="Young's modulus of body 1 (with --nu1; E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2), eq. (42))")
    parser.add_argument("--nu1", dest="nu1", type=_real, metavar="NU", help="Poisson's ratio of body 1")
    parser.add_argument("--E2", dest="E2", type=_real, default=math.inf, metavar="E",
                        help="Young's modulus of body 2 (default: rigid)")
    parser.add_argument("--nu2", dest="nu2", type=_real, default=0.0, metavar="NU",
                        help="Poisson's ratio of body 2 (default 0)")
    parser.add_argument(
        "--second-surface", dest="second_surface", type=_real, nargs=5, default=None,
        metavar=("M00", "M20", "M02", "M40", "M04"),
        help="moments of the second rough surface (same lay frame and unit): the contact of "
        "two rough surfaces is that of their sum with a flat",
    )


def effective_modulus_from(args) -> float:
    """E* of --E-star or of --E1/--nu1 [--E2/--nu2] (asperity.effective_modulus, eq. (42))."""
    if args.E_star is not None:
        if args.nu1 is not None or args.E2 != math.inf or args.nu2 != 0.0:
            raise CLIError("--nu1, --E2 and --nu2 go with --E1, not with --E-star")
        return args.E_star
    if args.nu1 is None:
        raise CLIError("--E1 needs --nu1")
    from ..asperity import effective_modulus

    return effective_modulus(args.E1, args.nu1, args.E2, args.nu2)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog=PROG,
        description="Statistical contact of strongly anisotropic rough surfaces "
        "(Buczkowski & Kleiber 2009).",
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    from . import bem, ccx, contact, fe, measured, moments, plot

    parents = [_moments_parent(), _output_parent()]
    contact.add_commands(sub, parents)
    moments.add_command(sub, parents[1:])
    measured.add_commands(sub, parents)
    fe.add_commands(sub, parents)
    plot.add_command(sub, parents[1:])
    bem.add_command(sub, parents[1:])
    ccx.add_command(sub, parents[1:])
    return parser


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


# ---------------------------------------------------------------------------------------
# entry point
# ---------------------------------------------------------------------------------------
#: the exit code when the reader of stdout went away: 128 + SIGPIPE, what a shell reports for a
#: writer killed by SIGPIPE (``seq 1 100000 | head -1`` under ``set -o pipefail``), so a script
#: sees that the output was cut off, as for any other Unix tool
EXIT_BROKEN_PIPE = 141
#: the exit code of a command interrupted by Ctrl-C: 128 + SIGINT, as a shell reports it
EXIT_INTERRUPTED = 130


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI on ``argv`` (default ``sys.argv[1:]``); return the exit code. A closed
    output pipe ends the command quietly with :data:`EXIT_BROKEN_PIPE`."""
    try:
        code = _main(argv)
        sys.stdout.flush()  # inside the try: a reader gone away shows up here or in print
        return code
    except BrokenPipeError:
        # Python's documented recipe (library/signal, "Note on SIGPIPE"): point stdout at
        # devnull so that the interpreter's final flush at exit raises nothing either
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError):  # stdout has no descriptor (e.g. replaced in tests)
            pass
        return EXIT_BROKEN_PIPE


def entry_point() -> int:
    """The console script ``roughcontact`` and ``python -m roughcontact``: :func:`main` on
    ``sys.argv[1:]``, then the process ends.

    Before it ends, every object is frozen out of the cyclic garbage collector
    (:func:`gc.freeze`): the interpreter's collections at exit would otherwise walk all that
    numba and scipy created, 0.2–0.3 s after a command that ran numba kernels (measured on a
    2-core machine: 0.22–0.30 s from the last statement to the end of the process, 0.03 s
    frozen). The operating system frees the memory; the output is flushed by then. Not in
    :func:`main`, which tests and scripts call in a process that goes on."""
    code = main()
    gc.freeze()
    return code


def _main(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a parse error (already reported)
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)

    handler: Callable[[Any], dict[str, Any]] = args.func
    try:
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                payload = handler(args)
            for w in caught:  # the library's warnings (e.g. ModelValidityWarning): one line each
                print(f"{PROG}: warning: {_one_line(str(w.message))}", file=sys.stderr)
        except (ValueError, TypeError) as exc:
            # the library's validation errors name the violated condition
            raise CLIError(_one_line(str(exc)), code=2) from exc
        except ArithmeticError as exc:
            # a numba kernel's division by zero or an overflow on inputs its checks let through
            # (e.g. m00 = 1e23 um^2 with --psi 1: a yield strength 2e4 times E*): not finite, exit 1
            raise CLIError(f"the computation failed for these inputs ({type(exc).__name__}: {exc}); they are far "
                           "outside the model's range (docs/derivation.md, 'Range of validity')", code=1) from exc
        _check_finite(payload)
        text = (
            json.dumps(payload, indent=2, allow_nan=False)
            if args.json
            else args.render(payload)
        )
    except CLIError as exc:
        print(f"{PROG}: error: {_one_line(str(exc))}", file=sys.stderr)
        return exc.code
    except KeyboardInterrupt:  # Ctrl-C: one line, no traceback (files are written atomically)
        print(f"{PROG}: error: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
