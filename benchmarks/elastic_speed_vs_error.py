"""Speed against error of the elastic integrals (A/A0, W/A0, K/A0) at the table cells.

    .venv/bin/python benchmarks/elastic_speed_vs_error.py [--repeat 5] [--json out.json]

For each surface (Tables 1–2) and Hertz option, the mpmath reference (dps = 20, ≥15 correct
digits) is computed once; then each production preset and a few explicit quadrature levels
are timed (numba compile time reported separately, runs interleaved, median of --repeat) and
their worst relative error over the three quantities and the six cells is reported.
Times are per separation value, wall clock, with numba's thread pool as configured
(NUMBA_NUM_THREADS; the machine info line says how many cores).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time

import numpy as np

from roughcontact import SpectralMoments, __version__
from roughcontact.contact import elastic_contact
from roughcontact.quadrature import PRESETS, QuadratureSettings

SURFACES = {
    "table1": (SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4), [1.0, 1.5, 2.0, 2.5, 3.0, 3.5]),
    "table2": (SpectralMoments(3.0, 1.0, 81.0, 1.0, 6561.0), [2.0, 2.5, 3.0, 3.5, 4.0, 4.5]),
}
QUANTITIES = ("area_fraction", "pressure", "stiffness")


def _worst_error(c, ref) -> float:
    return max(float(np.max(np.abs(getattr(c, q) / getattr(ref, q) - 1.0))) for q in QUANTITIES)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--json", help="also write the rows to this JSON file")
    args = ap.parse_args(argv)

    import numba

    print(
        f"roughcontact {__version__}; numba {numba.__version__}; {platform.processor() or platform.machine()}; "
        f"{os.cpu_count()} cores; NUMBA_NUM_THREADS={numba.config.NUMBA_NUM_THREADS}"
    )
    methods = {name: settings for name, settings in PRESETS.items()}
    methods.update({f"levels{lv}": QuadratureSettings(*lv) for lv in [(3, 3, 3), (5, 5, 5)]})
    rows = []
    for sname, (surface, s) in SURFACES.items():
        for hertz in ("exact", "paper"):
            t0 = time.perf_counter()
            ref = elastic_contact(surface, s, 1.0, hertz=hertz, method="reference", dps=20)
            t_ref = (time.perf_counter() - t0) / len(s)
            first = {}
            for name, st in methods.items():  # compile + θ-node set-up, reported separately
                t0 = time.perf_counter()
                elastic_contact(surface, s[:1], 1.0, hertz=hertz, accuracy=st)
                first[name] = time.perf_counter() - t0
            times = {name: [] for name in methods}
            for _ in range(args.repeat):  # interleaved
                for name, st in methods.items():
                    t0 = time.perf_counter()
                    c = elastic_contact(surface, s, 1.0, hertz=hertz, accuracy=st)
                    times[name].append((time.perf_counter() - t0) / len(s))
            for name, st in methods.items():
                rows.append(
                    dict(
                        surface=sname,
                        hertz=hertz,
                        method=name,
                        levels=[st.theta_level, st.r_level, st.t_level],
                        seconds_per_separation=statistics.median(times[name]),
                        first_call_seconds=first[name],
                        max_relative_error=_worst_error(
                            elastic_contact(surface, s, 1.0, hertz=hertz, accuracy=st), ref
                        ),
                    )
                )
            rows.append(
                dict(surface=sname, hertz=hertz, method="mpmath dps=20", levels=None,
                     seconds_per_separation=t_ref, first_call_seconds=None, max_relative_error=0.0)
            )
    print(f"{'surface':8} {'hertz':6} {'method':14} {'ms/sep':>9} {'first call s':>12} {'max rel err':>12}")
    for r in rows:
        fc = "" if r["first_call_seconds"] is None else f"{r['first_call_seconds']:.2f}"
        print(
            f"{r['surface']:8} {r['hertz']:6} {r['method']:14} {1e3 * r['seconds_per_separation']:9.2f} "
            f"{fc:>12} {r['max_relative_error']:12.2e}"
        )
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
