"""Issue 33's three cost ratios of the elasto-plastic law for its default route ("auto"), in one
process with the elastic model, and the routes behind it.

    nice -n 10 .venv/bin/python benchmarks/ep_cost.py [--accuracy plot] [--repeat 7] [--m00 2] [--psi 50] [--grid 5]

Table 1 surface, ψ = 1, E* = 1.14e5, preset "plot". route="auto" (contact.elastoplastic, the
default of elastoplastic_contact, elastoplastic_contact_many and SweepSpec) takes the summit
table when the material's table is cached, or when a call's τ-route cost reaches the table's
build, else the τ = r t route. Measured, medians of --repeat calls:

* per separation (s = 1): the elastic model; auto **warm** (the material's table cached, as
  every call after the first big one of a process sees it) and **cold** (cache cleared before
  each call: a lone separation stays on τ, no build);
* a 200-point curve (s ∈ [0, 2]) warm and cold, in single separations of the same state
  (issue 33: "a 200-point curve = N single separations");
* the sweep: a real sub-grid of benchmarks/sweep_throughput.py (--m00 values of m00 × --psi
  values of ψ × 400 separations, contact.sweep.run_sweep with its default route, elastic
  model off, cache cleared first), extrapolated linearly in m00 to 50 × 50 × 400 = 10⁶ points
  (auto takes the table route there: one shared summit-table build per m00, so a sub-grid
  with fewer ψ would overstate the cost); and, for comparison, the τ route on --grid × --grid
  (its cost is per curve: extrapolated in the number of (m00, ψ); --grid 0 skips it);
* behind the rule: the τ route's single separation and the cold build of one table
  (route="table", cache cleared), whose ratio is the break-even the rule uses
  (contact.elastoplastic.BUILD_IN_TAU_SEPARATIONS), and the routes' agreement.

Wall and CPU time (the process's CPU, all threads); the load average before and after (the
machine's load inflates every wall time alike). The summary's last lines state the ratios
against the goals (≤ 12× elastic per separation, ≤ 20 separations per 200-point curve,
≤ 60 s for 10⁶ sweep points).
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
GOALS = {"single": 12.0, "curve": 20.0, "sweep": 60.0}


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


def _sweep_seconds(n_m00, n_psi, accuracy, route, extrapolate_psi):
    """(wall, CPU, wall extrapolated to 50 × 50 × 400, CPU extrapolated, routes taken)."""
    sp = sweep_throughput.spec(n_m00, n_psi, 400, accuracy, route)
    sweep.run_sweep(sweep_throughput.spec(1, ep.SHARED_MIN, 2, accuracy, "table"))  # the shared build's kernel loaded
    ep.clear_table_cache()
    t0, c0 = time.perf_counter(), time.process_time()
    ds = sweep.run_sweep(sp)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    scale = 50 / n_m00 * (50 / n_psi if extrapolate_psi else 1.0)
    return wall, cpu, wall * scale, cpu * scale, ds.attrs["route_used"]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--accuracy", default="plot")
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--m00", type=int, default=2, help="default-route sweep sub-grid: m00 values (x --psi values)")
    ap.add_argument("--psi", type=int, default=50, help="default-route sweep sub-grid: psi values (50: the full axis)")
    ap.add_argument("--grid", type=int, default=5, help="tau-route sweep sub-grid grid x grid (0: skip)")
    args = ap.parse_args(argv)
    acc, rep = args.accuracy, args.repeat
    load0 = os.getloadavg()
    print(f"load average before: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}  (preset {acc!r}, Table 1, psi = 1)")
    mat = AsperityMaterial(E, yield_strength_for_plasticity_index(1.0, SURFACE, E))
    one, curve = [1.0], np.linspace(0.0, 2.0, 200)
    kw = dict(accuracy=acc, validity="off")
    clear = ep.clear_table_cache

    def auto(s):
        return ep.elastoplastic_contact(SURFACE, s, mat, **kw)

    el = _median(lambda: elastic_contact(SURFACE, one, E, accuracy=acc), rep)
    # cold: no table cached (each call as a process's first for this material)
    clear()
    cold_routes = (auto(one).route, auto(curve).route)
    cold1 = _median(lambda: auto(one), rep, clear)
    coldc = _median(lambda: auto(curve), max(3, rep // 2), clear)
    # warm: the material's table cached (here by one route="table" call over the curve's range)
    clear()
    ep.elastoplastic_contact(SURFACE, curve, mat, route="table", **kw)
    warm_routes = (auto(one).route, auto(curve).route)
    warm1 = _median(lambda: auto(one), rep)
    warmc = _median(lambda: auto(curve), rep)
    table = next(iter(ep._TABLES.values()))
    # behind the rule: the τ route and the cold build
    tau1 = _median(lambda: ep.elastoplastic_contact(SURFACE, one, mat, route="tau", **kw), rep)
    build = _median(lambda: ep.elastoplastic_contact(SURFACE, one, mat, route="table", **kw), max(3, rep // 2), clear)
    agree = _max_rel(ep.elastoplastic_contact(SURFACE, curve, mat, route="table", **kw),
                     ep.elastoplastic_contact(SURFACE, curve, mat, route="tau", interpolate_s=False, **kw))
    print(f"elastic, one separation                       {el * 1e6:8.0f} us")
    print(f"EP auto, one separation     warm ({warm_routes[0]:5s}) {warm1 * 1e6:8.0f} us = {warm1 / el:6.2f}x elastic")
    print(f"                            cold ({cold_routes[0]:5s}) {cold1 * 1e6:8.0f} us = {cold1 / el:6.2f}x elastic")
    print(f"EP auto, 200-point curve    warm ({warm_routes[1]:5s}) {warmc * 1e3:8.2f} ms = {warmc / warm1:6.1f} warm separations")
    print(f"                            cold ({cold_routes[1]:5s}) {coldc * 1e3:8.2f} ms = {coldc / cold1:6.1f} cold separations")
    print(f"behind the rule: tau route one separation {tau1 * 1e3:.2f} ms; cold table build (route='table', one "
          f"separation) {build * 1e3:.0f} ms = {build / tau1:.0f} tau separations (the rule assumes "
          f"{ep.BUILD_IN_TAU_SEPARATIONS.get(acc, ep.BUILD_IN_TAU_SEPARATIONS_OTHER):.0f}); table: "
          f"{table.evaluations} rho-evaluations, {table.y.size} convolution nodes, {table.nbytes / 1024:.0f} kB")
    print(f"accuracy: table vs tau route (no s-interpolation) over the curve: max rel. {agree:.1e} (bound 1e-8 each)")
    sw = _sweep_seconds(args.m00, args.psi, acc, "auto", extrapolate_psi=False)
    print(f"sweep, default route ({sw[4]}) {args.m00}x{args.psi}x400 = {args.m00 * args.psi * 400} points: wall "
          f"{sw[0]:.1f} s, CPU {sw[1]:.1f} s -> 10^6 points: wall {sw[2]:.0f} s, CPU {sw[3]:.0f} s")
    if args.grid > 0:
        st = _sweep_seconds(args.grid, args.grid, acc, "tau", extrapolate_psi=True)
        print(f"sweep, tau route (before) {args.grid}x{args.grid}x400: wall {st[0]:.1f} s -> 10^6 points: "
              f"wall {st[2]:.0f} s, CPU {st[3]:.0f} s")
    load1 = os.getloadavg()
    print("-- issue 33, default route 'auto', one process --")
    print(f"per separation <= {GOALS['single']:.0f}x elastic:  warm {warm1 / el:.2f}x "
          f"({'met' if warm1 / el <= GOALS['single'] else 'NOT met'}); cold {cold1 / el:.1f}x "
          f"({'met' if cold1 / el <= GOALS['single'] else 'NOT met'}: a lone separation without a table runs the tau route)")
    print(f"200-point curve <= {GOALS['curve']:.0f} separations: warm {warmc / warm1:.1f} "
          f"({'met' if warmc / warm1 <= GOALS['curve'] else 'NOT met'}); cold {coldc / cold1:.1f} "
          f"({'met' if coldc / cold1 <= GOALS['curve'] else 'NOT met'}: tau route with s-interpolation, no build)")
    print(f"10^6 sweep points <= {GOALS['sweep']:.0f} s: {sw[2]:.0f} s wall ({sw[3]:.0f} s CPU) "
          f"({'met' if sw[2] <= GOALS['sweep'] else 'NOT met'})")
    print(f"load average before {load0[0]:.2f}, after {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f} (2 cores; "
          "wall times are upper bounds on a loaded machine)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
