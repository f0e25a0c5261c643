"""The three cost ratios of issue 33 in one process, both production routes of
contact.elastoplastic ("tau": per separation; "table": one summit table per material,
integrals.summit_table), with the table's agreement with the τ-route.

    nice .venv/bin/python benchmarks/ep_cost.py [--accuracy plot] [--repeat 7] [--grid 5] [--m00 2] [--psi 50]

Table 1 surface, ψ = 1, E* = 1.14e5. Per separation (s = 1): the elastic model, the τ-route,
the table route warm (table cached) and cold (a new material: the build included, as a first
call sees it). A 200-point curve (s ∈ [0, 2]) warm and cold, in single separations of the same
route, and the cold curve's cost per separation against the elastic one (the build amortised
over the curve). The sweep: real sub-grids of benchmarks/sweep_throughput.py (400 separations,
contact.sweep.run_sweep, elastic model off): the τ-route on m00 × ψ = grid × grid, extrapolated
linearly in the number of (m00, ψ) to 50 × 50 × 400 = 10⁶ points (its cost is per curve); the
table route on --m00 values of m00 × the full ψ axis (--psi 50 values), extrapolated linearly
in m00 (its cost is one shared build per surface, summit_table.build_tables, plus a cheap
convolution per curve: a sub-grid with fewer ψ would overstate it). Wall and CPU time (the CPU
time of the process, all threads: on an idle 2-core machine the wall time is about CPU/2 to
CPU). The shared build's agreement with the τ-route over ψ = 0.05 … 50 (five materials, one
build). Medians of repeats; the load average is printed (the machine's load inflates every
wall time alike).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import sweep_throughput  # noqa: E402

from roughcontact import SpectralMoments  # noqa: E402
from roughcontact.asperity import AsperityMaterial, yield_strength_for_plasticity_index  # noqa: E402
from roughcontact.contact import elastic_contact, sweep  # noqa: E402
from roughcontact.contact import elastoplastic as ep  # noqa: E402

SURFACE = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
E = 1.14e5


def _median(fn, repeat, before=None):
    fn() if before is None else (before(), fn())
    ts = []
    for _ in range(repeat):
        if before is not None:
            before()
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def _max_rel(a, b) -> float:
    """max relative difference over the fields, parts against max(|part|, 1e-3 |total|)."""
    worst = 0.0
    for f in ep.ElastoPlasticCurves.FIELDS:
        x, y = getattr(a, f), getattr(b, f)
        total = getattr(b, "area_fraction" if "area" in f else "pressure" if "pressure" in f else "stiffness")
        scale = np.maximum(np.abs(y), 1e-3 * np.abs(total))
        ok = scale > 0
        if ok.any():
            worst = max(worst, float(np.max(np.abs(x - y)[ok] / scale[ok])))
    return worst


def _sweep_seconds(n_m00, n_psi, accuracy, route):
    """(wall, CPU, wall extrapolated to 50 × 50 × 400, CPU extrapolated) of a real sub-grid."""
    sp = sweep_throughput.spec(n_m00, n_psi, 400, accuracy, route)
    sweep.run_sweep(sweep_throughput.spec(1, ep.SHARED_MIN, 2, accuracy, route))  # kernels loaded (shared build too)
    ep._TABLES.clear()
    t0, c0 = time.perf_counter(), time.process_time()
    sweep.run_sweep(sp)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    scale = (50 * 50) / (n_m00 * n_psi)
    return wall, cpu, wall * scale, cpu * scale


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--accuracy", default="plot")
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--grid", type=int, default=5, help="τ-route sweep sub-grid: grid × grid (m00, ψ), 400 separations")
    ap.add_argument("--m00", type=int, default=2, help="table-route sweep sub-grid: m00 values (× --psi ψ values)")
    ap.add_argument("--psi", type=int, default=50, help="table-route sweep sub-grid: ψ values (50: the full axis)")
    args = ap.parse_args(argv)
    acc, rep = args.accuracy, args.repeat
    print(f"load average before: {os.getloadavg()}")
    mat = AsperityMaterial(E, yield_strength_for_plasticity_index(1.0, SURFACE, E))
    curve = np.linspace(0.0, 2.0, 200)
    kw = dict(accuracy=acc, validity="off")
    el = _median(lambda: elastic_contact(SURFACE, [1.0], E, accuracy=acc), rep)
    tau1 = _median(lambda: ep.elastoplastic_contact(SURFACE, [1.0], mat, **kw), rep)
    tauc = _median(lambda: ep.elastoplastic_contact(SURFACE, curve, mat, **kw), max(3, rep // 2))
    clear = ep._TABLES.clear
    cold1 = _median(lambda: ep.elastoplastic_contact(SURFACE, [1.0], mat, route="table", **kw), max(3, rep // 2), clear)
    coldc = _median(lambda: ep.elastoplastic_contact(SURFACE, curve, mat, route="table", **kw), max(3, rep // 2), clear)
    tab1 = _median(lambda: ep.elastoplastic_contact(SURFACE, [1.0], mat, route="table", **kw), rep)
    tabc = _median(lambda: ep.elastoplastic_contact(SURFACE, curve, mat, route="table", **kw), rep)
    table = next(iter(ep._TABLES.values()))
    agree = _max_rel(ep.elastoplastic_contact(SURFACE, curve, mat, route="table", **kw),
                     ep.elastoplastic_contact(SURFACE, curve, mat, interpolate_s=False, **kw))
    print(f"elastic single separation               {el * 1e6:9.0f} us")
    print(f"EP tau route:   single {tau1 * 1e6:8.0f} us ({tau1 / el:5.1f}x elastic); curve of 200 "
          f"{tauc * 1e3:7.1f} ms = {tauc / tau1:5.1f} singles = {tauc / 200 / el:5.1f}x elastic per separation")
    print(f"EP table route: warm single {tab1 * 1e6:.0f} us ({tab1 / el:.1f}x elastic); warm curve of 200 "
          f"{tabc * 1e3:.2f} ms = {tabc / tab1:.1f} warm singles")
    print(f"                cold single (build incl.) {cold1 * 1e3:.0f} ms ({cold1 / el:.0f}x elastic); cold curve of 200 "
          f"{coldc * 1e3:.0f} ms = {coldc / cold1:.2f} cold singles = {coldc / 200 / el:.1f}x elastic per separation")
    print(f"                table: {table.evaluations} rho-evaluations, {table.y.size} convolution nodes, "
          f"interpolation bound {table.interp_error:.1e}, theta-error estimate {table.theta_error:.1e}; "
          f"table vs tau route (no s-interpolation) over the curve: max rel. {agree:.1e} (bound 1e-8)")
    psis = (0.05, 0.5, 2.0, 10.0, 50.0)
    mats = [AsperityMaterial(E, yield_strength_for_plasticity_index(p, SURFACE, E)) for p in psis]
    t_shared = _median(lambda: ep.elastoplastic_contact_many(SURFACE, curve, mats, route="table", **kw), 3, clear)
    shared = ep.elastoplastic_contact_many(SURFACE, curve, mats, route="table", **kw)
    tau_many = ep.elastoplastic_contact_many(SURFACE, curve, mats, interpolate_s=False, **kw)
    agree_many = max(_max_rel(a, b) for a, b in zip(shared, tau_many))
    print(f"                shared build: {len(psis)} materials (psi {psis[0]} ... {psis[-1]}) x 200 separations cold "
          f"{t_shared:.2f} s; vs tau route: max rel. {agree_many:.1e} (bound 1e-8)")
    for route, (nm, npsi) in (("tau", (args.grid, args.grid)), ("table", (args.m00, args.psi))):
        wall, cpu, full, full_cpu = _sweep_seconds(nm, npsi, acc, route)
        print(f"sweep ({route:5s} route) {nm}x{npsi}x400 = {nm * npsi * 400} points: wall {wall:.1f} s, CPU {cpu:.1f} s "
              f"-> 10^6 points extrapolated: wall {full:.0f} s, CPU {full_cpu:.0f} s (goal 60 s wall; "
              f"load {os.getloadavg()[0]:.1f})")
    print(f"load average after: {os.getloadavg()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
