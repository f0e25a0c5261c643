"""Speed against error of the elastic and elasto-plastic summit integrals (issue 5).

    .venv/bin/python benchmarks/speed_vs_error.py --out-dir results/benchmarks/speed_vs_error \\
        --figure paper_figures/speed_vs_error.png --report paper_figures/speed_vs_error.md [--quick]

For A/A0, W/A0, K/A0 of the elastic model (52), (53), (55) and of the elasto-plastic model
(78), (82), K = −dW/dh, at representative points — the Table 1 and Table 2 surfaces, a
low-bandwidth surface (α ≈ 2.2, μ = 0.09), an extreme-anisotropy surface (m04/m40 = 10⁴), each
at a heavy and a light load (ψ = 1 for the elasto-plastic model) — it times, per separation:

* the production integrator at several accuracy settings (single-separation calls, serial;
  plus a batch of 64 separations split over the threads) — elasto-plastic: the τ = r t route
  (route="tau", what the default route "auto" takes for a single separation without a cached
  table), and the summit-table route (route="table", what "auto" takes once the table is
  cached: rows "table route <preset> (warm)", family "production (table route)", the cold
  call that builds the table in the row's note; full mode only: in --quick the table kernels'
  compilation would be most of their cost);
* the paper's Gauss–Legendre product rule in (ω1, ω4, ω6), n = 50 as printed and other n
  (baselines.product_rule, truncation documented there);
* scipy: a plain tplquad over the infinite ranges (once per quantity, full mode; cached) and,
  for the elasto-plastic model, the adaptive scipy twin at several tolerances;
* mpmath itself (the elastic reference integrator; dps 8, 12 and 20).

Errors are relative to the references of references.py (cached under --out-dir). Methods are
interleaved (round-robin over one point's methods, --repeat times) and medians reported.
Writes <out-dir>/results.json, <out-dir>/results.nc (roughcontact.io.write_netcdf, with
provenance), the figure and a markdown report fragment. Full mode takes ~5 min on 2 cores plus
the naive tplquad where benchmarks/data/tplquad.json lacks a record (10–60 min per quantity);
--quick ~1 min (it reports the recorded tplquad runs, never computes one).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import baselines  # noqa: E402
import machine  # noqa: E402
import references as refs  # noqa: E402
import report  # noqa: E402

from roughcontact import SpectralMoments  # noqa: E402
from roughcontact.contact import elastic_contact  # noqa: E402
from roughcontact.contact import elastoplastic_contact  # noqa: E402
from roughcontact.integrals.rules import QuadratureSettings as QS  # noqa: E402
from roughcontact.io import write_text  # noqa: E402

SURFACES = {
    "table1": SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4),
    "table2": SpectralMoments(3.0, 1.0, 81.0, 1.0, 6561.0),
    "alpha2.2": SpectralMoments(1.0, 1.0, 1.0, 2.2, 2.2),
    "aniso1e4": SpectralMoments(1.0, 0.1, 1.0, 0.03, 300.0),
}
#: (surface, s) — heavy and light load per surface (Tables 1–2: their first and last rows)
LOADS = {"table1": (1.0, 3.5), "table2": (2.0, 4.5), "alpha2.2": (0.0, 3.0), "aniso1e4": (0.0, 3.0)}
PSI = 1.0
#: the naive tplquad's measurements (10–60 min per quantity: too slow for a reproduction run),
#: kept in the repository with their date and load; full mode adds missing ones
TPLQUAD_CACHE = Path(__file__).resolve().parent / "data" / "tplquad.json"
QUANTITIES = ("A", "W", "K")

ELASTIC_SETTINGS = {
    "prod L(3,2,1)": QS(3, 2, 1),
    "prod plot": "plot",
    "prod L(4,4,3)": QS(4, 4, 3),
    "prod table": "table",
    "prod L(5,6,5)": QS(5, 6, 5),
}
EP_SETTINGS = {
    "prod L(2,2,2)": QS(2, 2, 2),
    "prod L(3,2,3)": QS(3, 2, 3),
    "prod plot": "plot",
    "prod L(3,4,4)": QS(3, 4, 4),
    "prod table": "table",
}


@dataclass
class Row:
    model: str
    point: str
    method: str
    family: str  # production | GL product rule | scipy tplquad | scipy twin | mpmath
    seconds: list = field(default_factory=list)  # per separation, one entry per repeat
    values: np.ndarray | None = None  # (A, W, K) at E* = 1 (elastic) or E* = 1.14e5
    errors: list | None = None  # relative, per quantity
    note: str = ""

    def as_dict(self) -> dict:
        return {
            "model": self.model, "point": self.point, "method": self.method, "family": self.family,
            "seconds_median": statistics.median(self.seconds) if self.seconds else None,
            "seconds_all": self.seconds, "errors": self.errors, "note": self.note,
            "values": None if self.values is None else [None if np.isnan(v) else float(v) for v in self.values],
        }


def _relative_errors(values, ref) -> list:
    """|value/reference − 1| per quantity."""
    return [float(abs(v / r - 1.0)) for v, r in zip(values, ref)]


def _timed(fn, n_sep=1):
    t0 = time.perf_counter()
    v = fn()
    return v, (time.perf_counter() - t0) / n_sep


def _elastic_methods(surface, s, quick):
    m = {}
    for name, acc in ELASTIC_SETTINGS.items():
        m[name] = ("production", lambda acc=acc: refs.first_values(elastic_contact(surface, [s], 1.0, accuracy=acc)))
    for n in ((16, 50) if quick else (16, 32, 50, 100, 200)):
        m[f"GL-{n}³" + (" (paper)" if n == 50 else "")] = (
            "GL product rule", lambda n=n: baselines.product_rule(surface, s, n=n))
    return m


def _ep_methods(surface, s, quick):
    mat = refs.material_for(PSI, surface)
    m = {}
    for name, acc in EP_SETTINGS.items():
        m[name] = ("production", lambda acc=acc: refs.first_values(elastoplastic_contact(surface, [s], mat, accuracy=acc,
                                                                                         route="tau")))
    for n in ((16, 50) if quick else (16, 32, 50, 100)):
        m[f"GL-{n}³" + (" (paper)" if n == 50 else "")] = (
            "GL product rule", lambda n=n: baselines.product_rule(surface, s, n=n, kind="elastoplastic", material=mat))
    for rtol in (() if quick else (1e-4, 1e-6, 1e-8)):
        m[f"scipy twin rtol={rtol:g}"] = ("scipy twin", lambda rtol=rtol: refs.twin_values(surface, s, mat, rtol=rtol)[:3])
    return m


def _run_point(model, point, methods, ref, repeat, rows):
    """Interleaved repeats of every method at one point; medians later."""
    by_name = {name: Row(model, point, name, fam) for name, (fam, _) in methods.items()}
    for name, (_, fn) in methods.items():  # warm-up (compile, θ-node set-up), not timed
        by_name[name].values = fn()
    reps = {name: (repeat if fam in ("production", "GL product rule") else 1) for name, (fam, _) in methods.items()}
    for k in range(repeat):
        for name, (_, fn) in methods.items():
            if k < reps[name]:
                _, dt = _timed(fn)
                by_name[name].seconds.append(dt)
    for row in by_name.values():
        row.errors = _relative_errors(row.values, ref)
        rows.append(row)


def _batch_rows(model, point, surface, s, ref, rows, quick=False):
    """The production presets on 64 separations in one call (threads), per separation; for the
    elasto-plastic model also the s-interpolated curve and (full mode) the table route."""
    svals = np.full(64, s)
    for name, acc in (("prod table (batch of 64)", "table"), ("prod plot (batch of 64)", "plot")):
        if model == "elastic":
            fn = lambda acc=acc: elastic_contact(surface, svals, 1.0, accuracy=acc)  # noqa: E731
        else:
            mat = refs.material_for(PSI, surface)
            fn = lambda acc=acc, mat=mat: elastoplastic_contact(surface, svals, mat, accuracy=acc, route="tau")  # noqa: E731
        fn()
        row = Row(model, point, name, "production (batch)")
        for _ in range(3):
            c, dt = _timed(fn, 64)
            row.seconds.append(dt)
        v = refs.first_values(c)
        row.errors = _relative_errors(v, ref)
        rows.append(row)
    if model == "elastoplastic":
        _curve_row(point, surface, s, ref, rows)
        if not quick:  # make reproduce's quick form: the table kernels' compilation (~4 s) spared
            _table_route_rows(point, surface, s, ref, rows)


def _table_route_rows(point, surface, s, ref, rows, repeat=7):
    """route="table" (integrals.summit_table) at the presets "plot" and "table": single-separation
    calls with the material's table cached (warm: what route="auto" takes once a table exists),
    and in the note the cold call that builds it (cache cleared first)."""
    from roughcontact.contact.elastoplastic import _TABLES, clear_table_cache

    mat = refs.material_for(PSI, surface)
    for acc in ("plot", "table"):
        fn = lambda acc=acc: elastoplastic_contact(surface, [s], mat, accuracy=acc, route="table")  # noqa: E731
        clear_table_cache()
        _, cold = _timed(fn)
        table = next(iter(_TABLES.values()))
        row = Row("elastoplastic", point, f"table route {acc} (warm)", "production (table route)",
                  note=f"table cached; the cold call (the build, {table.evaluations} rho-evaluations) took "
                       f"{cold * 1e3:.0f} ms")
        for _ in range(repeat):
            c, dt = _timed(fn)
            row.seconds.append(dt)
        row.values = refs.first_values(c)
        row.errors = _relative_errors(row.values, ref)
        rows.append(row)
    clear_table_cache()


def _curve_row(point, surface, s, ref, rows, n=201):
    """A curve of n separations on [s − 1, s + 1] in one call, preset "plot" (built from the
    verified interpolant in s, contact.s_interpolation); time per separation and the error at
    its middle point s."""
    mat = refs.material_for(PSI, surface)
    svals = np.linspace(s - 1.0, s + 1.0, n)
    svals[n // 2] = s
    fn = lambda: elastoplastic_contact(surface, svals, mat, accuracy="plot", route="tau")  # noqa: E731
    c = fn()
    row = Row("elastoplastic", point, f"prod plot (curve of {n}, s-interpolated)", "production (curve)",
              note=f"{c.interpolation.nodes} model evaluations, measured interpolation error "
                   f"{c.interpolation.error:.1e} ({c.interpolation.method})")
    for _ in range(3):
        _, dt = _timed(fn, n)
        row.seconds.append(dt)
    row.values = np.array([c.area_fraction[n // 2], c.pressure[n // 2], c.stiffness[n // 2]])
    row.errors = _relative_errors(row.values, ref)
    rows.append(row)


def _mpmath_rows(point, surface, s, ref, rows):
    for dps in (8, 12):
        v, dt = _timed(lambda dps=dps: refs.mpmath_values(surface, s, dps=dps))
        rows.append(Row("elastic", point, f"mpmath dps={dps}", "mpmath", [dt], v,
                        _relative_errors(v, ref)))
    dt = refs.mpmath_time(surface, s, dps=20)
    rows.append(Row("elastic", point, "mpmath dps=20 (reference)", "mpmath", [dt], ref, [0.0, 0.0, 0.0],
                    note="the reference itself: error ≤ 1e-15 by construction"))


def tplquad_label(quantity: str, rec: dict, measured_now: bool) -> tuple[str, str]:
    """(method label, note) of a tplquad row: a time taken from the recorded cache says so in
    the label itself, "recorded on <date>, not re-measured", so that no report shows it as a
    measurement of this run."""
    if measured_now:
        return f"scipy tplquad ({quantity} only)", f"measured in this run, load {rec['loadavg']:.2f}"
    return (f"scipy tplquad ({quantity} only; recorded on {rec['date']}, not re-measured)",
            f"recorded on {rec['date']} at load {rec['loadavg']:.2f}, not re-measured")


def _tplquad_rows(cache_path: Path, references: refs.ReferenceCache, quick: bool, rows):
    """The naive scipy tplquad: one point, each quantity once (10–60 min each); cached with the
    time it took and the load average (TPLQUAD_CACHE, in the repository), reused by later runs
    and marked as cached in the report."""
    cache = json.loads(cache_path.read_text()) if cache_path.exists() else {}
    measured = set()
    cases = [("elastic", "table1", 3.5, q) for q in ("area", "load", "stiffness")]
    cases.append(("elastoplastic", "table1", 3.5, "area"))
    for model, sname, s, quantity in cases:
        key = f"{model}|{sname}|{s}|{quantity}"
        surface = SURFACES[sname]
        if key not in cache:
            if quick:
                continue
            mat = refs.material_for(PSI, surface) if model == "elastoplastic" else None
            load = os.getloadavg()[0]
            with warnings.catch_warnings():  # QUADPACK's subdivision-limit warnings, as a user would see
                warnings.simplefilter("ignore")
                v, dt = _timed(lambda: baselines.naive_tplquad(surface, s, quantity=quantity, kind=model,
                                                               material=mat))
            cache[key] = {"value": v, "seconds": dt, "loadavg": load, "date": time.strftime("%Y-%m-%d")}
            measured.add(key)
            write_text(cache_path, json.dumps(cache, indent=1))
        rec = cache[key]
        ref = refs.elastic(references, surface, s) if model == "elastic" else refs.elastoplastic(references, surface, s, PSI)
        q = ("area", "load", "stiffness").index(quantity)
        method, note = tplquad_label(quantity, rec, measured_now=key in measured)
        row = Row(model, f"{sname} s={s}", method, "scipy tplquad", [rec["seconds"]],
                  values=np.full(3, np.nan), errors=[None, None, None], note=note)
        row.values[q] = rec["value"]
        row.errors[q] = _relative_errors([rec["value"]], [ref[q]])[0]
        rows.append(row)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", default="results/benchmarks/speed_vs_error")
    ap.add_argument("--figure", default="paper_figures/speed_vs_error.png")
    ap.add_argument("--report", default="paper_figures/speed_vs_error.md")
    ap.add_argument("--quick", action="store_true", help="fewer points and methods (CI, ~2 min)")
    ap.add_argument("--repeat", type=int, default=None, help="timing repeats (default 7, quick 3)")
    ap.add_argument("--no-compile-probe", action="store_true", help="skip the cold/warm numba cache probe")
    ap.add_argument("--no-seed", action="store_true",
                    help="compute every reference here, none from benchmarks/data/references.json")
    ap.add_argument("--update-seed", action="store_true",
                    help="write the references computed in this run into benchmarks/data/references.json")
    ap.add_argument("--from-json", action="store_true",
                    help="only redraw the figure and rewrite the report from <out-dir>/results.json")
    args = ap.parse_args(argv)
    if args.from_json:
        results = json.loads((Path(args.out_dir) / "results.json").read_text())
        results["summary"] = report.summarise(results)
        report.figure(results, args.figure)
        write_text(args.report, report.markdown(results))
        return 0
    quick = args.quick
    repeat = args.repeat or (3 if quick else 7)
    out_dir = Path(args.out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    info_before = machine.info()
    cache = refs.ReferenceCache(out_dir / "references.json", seed=None if args.no_seed else refs.SEED)

    if quick:
        el_points = [("table1", 1.0), ("table1", 3.5), ("aniso1e4", 0.0), ("aniso1e4", 3.0)]
        ep_points = [("table1", 1.0), ("table1", 3.5)]
    else:
        el_points = [(k, s) for k, loads in LOADS.items() for s in loads]
        ep_points = el_points
    rows: list[Row] = []
    for sname, s in el_points:
        surface = SURFACES[sname]
        ref = refs.elastic(cache, surface, s)
        point = f"{sname} s={s}"
        _run_point("elastic", point, _elastic_methods(surface, s, quick), ref, repeat, rows)
        _batch_rows("elastic", point, surface, s, ref, rows)
        if not quick or sname == "table1":
            _mpmath_rows(point, surface, s, ref, rows)
        print(f"[{time.perf_counter() - t_start:7.1f} s] elastic {point}", flush=True)
    for sname, s in ep_points:
        surface = SURFACES[sname]
        ref = refs.elastoplastic(cache, surface, s, PSI)[:3]
        point = f"{sname} s={s}"
        _run_point("elastoplastic", point, _ep_methods(surface, s, quick), ref, repeat, rows)
        _batch_rows("elastoplastic", point, surface, s, ref, rows, quick)
        print(f"[{time.perf_counter() - t_start:7.1f} s] elastoplastic {point}", flush=True)
    _tplquad_rows(TPLQUAD_CACHE, cache, quick, rows)

    checks = {}
    limit_points = [("table1", 1.0)] if quick else [("table1", 1.0), ("aniso1e4", 0.0)]
    for sname, s in limit_points:
        if quick and not refs.plastic_limit_cached(cache, SURFACES[sname], s):
            continue
        checks[f"{sname} s={s}"] = {
            "twin psi=1e-3 vs elastic mpmath (max rel over A, W, K)": refs.elastic_limit_check(cache, SURFACES[sname], s),
            "twin psi=1e4 area vs mpmath fully plastic area": refs.plastic_limit_check(cache, SURFACES[sname], s),
        }
    compile_info = None if args.no_compile_probe else machine.compile_times()
    info_after = machine.info()
    results = {
        "mode": "quick" if quick else "full",
        "repeat": repeat,
        "machine_before": info_before,
        "machine_after": info_after,
        "wall_seconds": time.perf_counter() - t_start,
        "rows": [r.as_dict() for r in rows],
        "reference_checks": checks,
        "compile": compile_info,
        "reference_seconds": {k: v["seconds"] for k, v in cache.data.items()},
        "references_seeded": cache.seeded,
        "reference_fingerprint": cache.fingerprint,
    }
    results["summary"] = report.summarise(results)
    write_text(out_dir / "results.json", json.dumps(results, indent=1, default=float))
    report.write_netcdf(results, out_dir / "results.nc")
    report.figure(results, args.figure)
    write_text(args.report, report.markdown(results))
    if args.update_seed:
        print(f"{cache.update_seed()} references written to {refs.SEED}")
    print(f"wrote {out_dir}/results.json, results.nc, {args.figure}, {args.report} "
          f"in {time.perf_counter() - t_start:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
