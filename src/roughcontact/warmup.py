"""Compile (or load from numba's on-disk cache) every numba kernel of the package once.

For a step that runs before parallel jobs (the workflow's numba_warmup, ``make test``), so
that they do not all compile the same kernels at the same time on a cold cache
(docs/performance.md, caching). It sits above the kernels it compiles: it calls them through
the public API of :mod:`.contact` and :mod:`.interface`.

The kernels fall into two parts that share no compiled callees: the elasto-plastic integrals
(serial and threaded) and the rest. ``python -m roughcontact.warmup --jobs 2`` compiles them
in two processes at once (on a cold cache, on 2 cores: 55 s instead of 72 s in one process).
"""

from __future__ import annotations

import argparse
import subprocess
import sys

import numpy as np

from .asperity import AsperityMaterial
from .contact import elastic_contact, elastoplastic_contact
from .integrals.production import (PARALLEL_MIN, asperity_law, elastic_inner_integrals, hyperbola_grid_values,
                                   hyperbola_moments, hyperbola_moments_at_zero)
from .interface import InterfaceLaw, NormalLawTable, friction
from .statistics import SpectralMoments

__all__ = ["PARTS", "warm_up", "main"]

_SURFACE = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)


#: one separation for the serial kernels, enough for the threaded ones
_SEPARATIONS = ([1.0], np.linspace(0.0, 1.0, PARALLEL_MIN))


def _elastoplastic() -> None:
    # the serial and threaded kernels in one process: they share most of their compiled callees
    for s in _SEPARATIONS:
        # compiling, not computing results: no range-of-validity warnings (s = 0 is heavy load)
        elastoplastic_contact(_SURFACE, s, AsperityMaterial(1.0, 1e-3), accuracy="plot", validity="off")
    # the summit measure on the hyperbolas r t = τ, as the tests call it
    hyperbola_moments([0.5], [1.0], [0.0])
    hyperbola_moments_at_zero([1.0], [0.0])
    hyperbola_grid_values(0.0, (0.5, 2.0), [0.5], [1.0])


def _the_rest() -> None:
    for s in _SEPARATIONS:
        elastic_contact(_SURFACE, s, 1.0, accuracy="plot", validity="off")
    elastic_contact(_SURFACE, [1.0], 1.0, model="gw")
    elastic_inner_integrals([0.5], [1.0])
    asperity_law([1e-3], 2.0, 1.0, 1.0, 1.0, 1e-3, 1.0, 45.0, 1.0, 0.3)
    state = friction.initial_state(1, u_N=1.0, k_N=1.0)
    for model in (friction.OrthotropicHardening(0.5, 0.5, 0.5, 0.5, 1.0, 1.0),
                  friction.IsotropicHardening(0.5, 0.5, 1.0), friction.Frictionless()):
        friction.update(model, state, [[1.0, 0.5, 0.1]], 1.0, 1.0, 1.0)
    # a tabulated normal law (the FE engine's): its closure-law kernel
    table = NormalLawTable.build(_SURFACE, "elastic", E_star=1.0, s_range=(1.5, 4.5), accuracy="plot")
    InterfaceLaw.from_pressure(table, 1e-6).normal([0.0])


#: the parts, each a callable that runs its kernels on tiny inputs
PARTS = {"elastoplastic": _elastoplastic, "rest": _the_rest}


def warm_up(parts=None) -> None:
    """Run every kernel (or those of the named ``parts``, keys of PARTS), serial and threaded,
    on tiny inputs."""
    for name in PARTS if parts is None else parts:
        PARTS[name]()


def main(argv=None) -> int:
    """``python -m roughcontact.warmup [--jobs N] [--part NAME]``: compile every kernel, the
    parts in up to N processes at once (default 1: in this process)."""
    ap = argparse.ArgumentParser(prog="python -m roughcontact.warmup", description=main.__doc__)
    ap.add_argument("--jobs", type=int, default=1, help="processes at once (default 1)")
    ap.add_argument("--part", choices=sorted(PARTS), action="append", help="only this part (repeatable)")
    args = ap.parse_args(argv)
    if args.jobs < 1:
        ap.error("--jobs must be >= 1")
    parts = args.part or list(PARTS)
    if args.jobs == 1 or len(parts) == 1:
        warm_up(parts)
        return 0
    failed = 0
    for start in range(0, len(parts), args.jobs):
        procs = [subprocess.Popen([sys.executable, "-m", "roughcontact.warmup", "--part", name])
                 for name in parts[start:start + args.jobs]]
        failed += sum(p.wait() != 0 for p in procs)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
