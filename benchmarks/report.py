"""Summary, netCDF, figure and markdown fragment of the speed-against-error benchmark."""

from __future__ import annotations

import json
import math
import statistics
from pathlib import Path

import numpy as np

QUANTITIES = ("A", "W", "K")
GOALS = {  # model: (max relative error, max seconds per separation)
    "elastic": (1e-10, 100e-6),
    "elastoplastic": (1e-8, 1e-3),
}
SPEEDUP_GOAL = 1000.0
#: below this observed order in n the product rule is taken as stalled, not extrapolated
MIN_ORDER = 1.0
FLOOR = 1e-17  # errors below are plotted/printed at the floor (double rounding)


def _prod(rows, model, point):
    return [r for r in rows if r["model"] == model and r["point"] == point and r["family"] == "production"]


def _fastest_within(rows, model, point, q, err):
    """Fastest single-call production setting whose error in quantity q is ≤ err."""
    ok = [r for r in _prod(rows, model, point) if r["errors"][q] is not None and r["errors"][q] <= err]
    return min(ok, key=lambda r: r["seconds_median"]) if ok else None


def summarise(results: dict) -> dict:
    rows = results["rows"]
    out = {"goals": {}, "speedups": [], "settings": []}
    for model, (err_goal, t_goal) in GOALS.items():
        per_point = {}
        for point in sorted({r["point"] for r in rows if r["model"] == model}):
            ok = [r for r in _prod(rows, model, point) if max(r["errors"]) <= err_goal]
            best = min(ok, key=lambda r: r["seconds_median"]) if ok else None
            per_point[point] = None if best is None else {"method": best["method"], "seconds": best["seconds_median"],
                                                          "max_error": max(best["errors"])}
        met = all(v is not None and v["seconds"] <= t_goal for v in per_point.values()) and bool(per_point)
        out["goals"][model] = {"error_goal": err_goal, "seconds_goal": t_goal, "met": met, "per_point": per_point}
    # speed-up of production over each baseline run, at equal or better error, per quantity
    for r in rows:
        if r["family"] not in ("GL product rule", "scipy tplquad", "scipy twin"):
            continue
        for q in range(3):
            e = r["errors"][q]
            if e is None or r["seconds_median"] is None:
                continue
            best = _fastest_within(rows, r["model"], r["point"], q, e)
            if best is None and r["family"] == "scipy tplquad":  # its point may not be timed in this mode
                continue
            out["speedups"].append({
                "model": r["model"], "point": r["point"], "baseline": r["method"], "quantity": QUANTITIES[q],
                "baseline_error": e, "baseline_seconds": r["seconds_median"],
                "production": None if best is None else best["method"],
                "production_seconds": None if best is None else best["seconds_median"],
                "speedup": None if best is None else r["seconds_median"] / best["seconds_median"],
            })
    # one point per (model, method): median time over points, worst error over points
    for model in GOALS:
        methods = []
        for r in rows:
            if r["model"] == model and (r["method"], r["family"]) not in methods:
                methods.append((r["method"], r["family"]))
        for method, family in methods:
            sel = [r for r in rows if r["model"] == model and r["method"] == method]
            times = [r["seconds_median"] for r in sel if r["seconds_median"] is not None]
            errs = [max((r["errors"][q] for r in sel if r["errors"][q] is not None), default=None) for q in range(3)]
            out["settings"].append({"model": model, "method": method, "family": family,
                                    "seconds_median": statistics.median(times) if times else None,
                                    "worst_errors": errs, "points": len(sel)})
    out["gl_extrapolated"] = _gl_at_production_accuracy(rows)
    gl50 = [s for s in out["speedups"] if s["baseline"].startswith("GL-50³") and s["speedup"] is not None]
    out["gl50_speedup_min"] = min((s["speedup"] for s in gl50), default=None)
    out["gl50_speedup_median"] = statistics.median([s["speedup"] for s in gl50]) if gl50 else None
    out["gl50_goal_met"] = out["gl50_speedup_min"] is not None and out["gl50_speedup_min"] >= SPEEDUP_GOAL
    return out


def _gl_at_production_accuracy(rows, target="prod plot"):
    """The other way round: how large n would the GL product rule need to reach the error of
    the production preset ``target``? Extrapolated, not measured: the observed order p from the
    two largest n (error ∝ n^−p) and time ∝ n³. One entry per (model, point, quantity)."""
    out = []
    for model in GOALS:
        for point in sorted({r["point"] for r in rows if r["model"] == model}):
            gl = sorted((int(r["method"].split("-")[1].split("³")[0]), r) for r in rows
                        if r["model"] == model and r["point"] == point and r["family"] == "GL product rule")
            prod = [r for r in _prod(rows, model, point) if r["method"] == target]
            if len(gl) < 2 or not prod:
                continue
            (n1, r1), (n2, r2) = gl[-2], gl[-1]
            for q in range(3):
                e1, e2, e_t = r1["errors"][q], r2["errors"][q], max(prod[0]["errors"][q], FLOOR)
                if not (e1 and e2 and e2 < e1):
                    continue
                order = math.log(e1 / e2) / math.log(n2 / n1)
                n_star = n2 * (e2 / e_t) ** (1.0 / order)
                t_star = r2["seconds_median"] * (n_star / n2) ** 3
                out.append({"model": model, "point": point, "quantity": QUANTITIES[q], "order": order,
                            "n_needed": n_star, "seconds_needed": t_star, "production_error": e_t,
                            "speedup": t_star / prod[0]["seconds_median"]})
    return out


def _reproduction_time(path=Path("results/benchmarks/reproduce_wall_time.json")) -> str:
    """The wall time of the last `make reproduce` (workflow/scripts/record_wall_time.py), which
    runs after the workflow and therefore after this report: the previous run's number."""
    head = ("`make reproduce` on 2 cores (goal ≤ 5 min) records its wall time at the end of the run in "
            "paper_figures/reproduction_time.md")
    if not path.exists():
        return head + "; no run recorded on this machine yet."
    data = json.loads(path.read_text())
    got = [f"{label} {data[k]['seconds']:.0f} s (commit `{data[k]['commit'][:12]}`, {data[k]['utc']})"
           for k, label in (("from_scratch", "from scratch:"), ("latest_incremental", "latest incremental run:"))
           if k in data]
    return head + ". Last recorded here (the run before this report): " + "; ".join(got) + "."


def write_netcdf(results: dict, path: Path) -> None:
    """The rows as a netCDF table (dimension ``row``) with provenance (roughcontact.io)."""
    import xarray as xr

    from roughcontact.io import write_netcdf as _write

    rows = results["rows"]

    def col(key):
        return np.array([r[key] for r in rows], dtype=str)

    err = np.array([[np.nan if e is None else e for e in r["errors"]] for r in rows], dtype=float)
    ds = xr.Dataset(
        {
            "model": ("row", col("model"), {"units": "1", "long_name": "elastic | elastoplastic"}),
            "point": ("row", col("point"), {"units": "1", "long_name": "surface and separation s = h/sqrt(m00)"}),
            "method": ("row", col("method"), {"units": "1"}),
            "family": ("row", col("family"), {"units": "1"}),
            "seconds_per_separation": ("row", np.array([np.nan if r["seconds_median"] is None else r["seconds_median"]
                                                        for r in rows]),
                                       {"units": "s", "long_name": "median wall time per separation value"}),
            "relative_error": (("row", "quantity"), err, {"units": "1", "long_name": "|value/reference - 1|"}),
        },
        coords={"quantity": ("quantity", list(QUANTITIES), {"units": "1", "long_name": "A/A0, W/A0, K/A0"}),
                "row": ("row", np.arange(len(rows)), {"units": "1", "long_name": "benchmark setting (row of the table)"})},
    )
    ds.attrs["machine"] = json.dumps(results["machine_before"])
    _write(ds, path, settings={"benchmark": "speed_vs_error", "mode": results["mode"], "repeat": results["repeat"]})


def figure(results: dict, path) -> None:
    """Error (log) against time per separation (log), one curve per method family, per
    quantity; each marker one setting: median time over the points, worst error over them."""
    from roughcontact.plots.style import legend_outside, new_figure, save, style

    styles = {
        "production": dict(color="#1b4f72", marker="o", ls="-"),
        "production (batch)": dict(color="#1b4f72", marker="s", ls="none", mfc="none"),
        "production (curve)": dict(color="#1b4f72", marker="P", ls="none"),
        "GL product rule": dict(color="#b03a2e", marker="^", ls="-"),
        "scipy twin": dict(color="#1e8449", marker="D", ls="-"),
        "scipy tplquad": dict(color="#1e8449", marker="*", ls="none", ms=10),
        "mpmath": dict(color="#7d3c98", marker="v", ls="-"),
    }
    settings = results["summary"]["settings"]
    with style():  # the project's figure style (roughcontact.plots.style)
        fig = new_figure(figsize=(11.0, 6.6))
        axes = fig.subplots(2, 3, sharex="row")
        for i, (model, (err_goal, t_goal)) in enumerate(GOALS.items()):
            for q in range(3):
                ax = axes[i, q]
                for family, st in styles.items():
                    pts = [(s["seconds_median"], s["worst_errors"][q]) for s in settings
                           if s["model"] == model and s["family"] == family and s["seconds_median"] is not None
                           and s["worst_errors"][q] is not None]
                    if not pts:
                        continue
                    pts.sort()
                    t, e = zip(*pts)
                    ax.loglog(t, np.maximum(e, FLOOR), label=family, **st)
                ax.axhline(err_goal, color="0.5", lw=0.8, ls=":")
                ax.axvline(t_goal, color="0.5", lw=0.8, ls=":")
                ax.set_title(f"{model}: {QUANTITIES[q]}")
                ax.set_xlabel("time per separation [s]")
                if q == 0:
                    ax.set_ylabel("relative error (worst over points)")
        legend_outside(fig, where="bottom", ncol=6, fontsize=8)  # off the data; every method once
    save(fig, path)


def _fmt_t(t):
    if t is None or (isinstance(t, float) and math.isnan(t)):
        return "–"
    if t < 1e-3:
        return f"{t * 1e6:.0f} µs"
    if t < 1.0:
        return f"{t * 1e3:.2f} ms"
    return f"{t:.1f} s"


def _fmt_e(e):
    if e is None:
        return "–"
    return f"≤{FLOOR:.0e}" if e < FLOOR else f"{e:.1e}"


def _seed_note(results: dict) -> str:
    """Where the references came from: computed in this run, or the committed seed."""
    seeded = results.get("references_seeded", {})
    total = len(results.get("reference_seconds", {}))
    if not seeded:
        return f"References: all {total} computed in this run."
    dates = ", ".join(sorted(set(seeded.values())))
    return (f"References: {total - len(seeded)} computed in this run, {len(seeded)} taken from "
            f"benchmarks/data/references.json (computed on {dates} by the same reference code: source "
            f"fingerprint {results.get('reference_fingerprint', '?')}; a changed reference integrator is "
            "recomputed, `--no-seed` recomputes all).")


def markdown(results: dict) -> str:
    s = results["summary"]
    m0, m1 = results["machine_before"], results["machine_after"]
    lines = ["# Speed against error (issue 5)", ""]
    lines += [
        f"Mode **{results['mode']}**, {results['repeat']} interleaved repeats, medians; wall time "
        f"{results['wall_seconds']:.0f} s. Machine: {m0['cpu']}, {m0['cores']} cores, numba "
        f"{m0['numba']} ({m0['numba_threads']} threads, layer {m1['numba_threading_layer']}), numpy {m0['numpy']}, "
        f"scipy {m0['scipy']}, mpmath {m0['mpmath']}, Python {m0['python']}; load average "
        f"{m0['loadavg']} before, {m1['loadavg']} after (2 cores shared with other work: timings are "
        "upper bounds).",
        "",
        "Times are wall time per separation value for all three quantities together (A, W, K come "
        "from one call), one separation per call unless marked *batch* (64 separations in one "
        "call). Threads: elastic single calls run on one thread (batches split the separations over "
        "the threads); elasto-plastic calls always split their (s, θ-node) pairs over the threads. "
        "Errors are relative to the mpmath "
        "reference (elastic, dps 20) or to the scipy twin at rtol 1e-10 (elasto-plastic; mpmath is "
        "infeasible there, see the reference checks; the twin's own rows at looser rtol are therefore "
        "compared with itself and look better than they are). The naive scipy tplquad computes one "
        "quantity per call (its time is per quantity).",
        "",
        _seed_note(results),
        "",
        "## Goals",
        "",
        "| goal | met | fastest production setting per point (time, worst error) |",
        "| --- | --- | --- |",
    ]
    for model, g in s["goals"].items():
        per = "; ".join(f"{p}: " + ("none" if v is None else f"{v['method']} {_fmt_t(v['seconds'])} {_fmt_e(v['max_error'])}")
                        for p, v in g["per_point"].items())
        lines.append(f"| {model}: ≤ {g['error_goal']:.0e} in ≤ {_fmt_t(g['seconds_goal'])} per separation | "
                     f"{'yes' if g['met'] else '**no**'} | {per} |")
    gl = s["gl50_speedup_min"]
    lines.append(f"| ≥ {SPEEDUP_GOAL:.0f}× faster than GL-50³ at equal or better error | "
                 f"{'yes' if s['gl50_goal_met'] else '**no**'} | min {gl:.0f}×, median {s['gl50_speedup_median']:.0f}× "
                 "over points and quantities |" if gl else "| GL-50³ speed-up | – | not measured |")
    ext = s.get("gl_extrapolated") or []
    conv = [x for x in ext if x["order"] >= MIN_ORDER]
    if conv:
        ups = [x["speedup"] for x in conv]
        lines.append(f"| (the other way round) GL product rule at the error of \"prod plot\" | – | extrapolated "
                     f"from the two largest n (error ∝ n^−p, time ∝ n³) where it converges (p ≥ {MIN_ORDER:g}: "
                     f"{len(conv)} of {len(ext)} point-quantities, p = {min(x['order'] for x in conv):.1f}–"
                     f"{max(x['order'] for x in conv):.1f}): median n ≈ {statistics.median(x['n_needed'] for x in conv):.0f}, "
                     f"speed-up ≥ {min(ups):.1e}×, median {statistics.median(ups):.1e}×; the rest stall |")
    lines += ["", "## Speed-up of production at equal or better error", "",
              "Per baseline run: the fastest single-call production setting whose error in that quantity is "
              "at most the baseline's; speed-up = baseline time / production time (min and median over "
              "the points).", "",
              "| model | baseline | quantity | baseline error (median) | baseline time (median) | speed-up min | speed-up median |",
              "| --- | --- | --- | --- | --- | --- | --- |"]
    groups = {}
    for sp in s["speedups"]:
        groups.setdefault((sp["model"], sp["baseline"], sp["quantity"]), []).append(sp)
    for (model, base, q), sps in groups.items():
        ups = [x["speedup"] for x in sps if x["speedup"] is not None]
        lines.append(f"| {model} | {base} | {q} | {_fmt_e(statistics.median(x['baseline_error'] for x in sps))} | "
                     f"{_fmt_t(statistics.median(x['baseline_seconds'] for x in sps))} | "
                     + (f"{min(ups):.3g}× | {statistics.median(ups):.3g}× |" if ups else "no production setting that accurate | – |"))
    for model in ("elastic", "elastoplastic"):
        lines += ["", f"## {model}: every method at every point", "",
                  "| point | method | time per separation | error A | error W | error K |", "| --- | --- | --- | --- | --- | --- |"]
        for r in results["rows"]:
            if r["model"] == model:
                lines.append(f"| {r['point']} | {r['method']} | {_fmt_t(r['seconds_median'])} | "
                             + " | ".join(_fmt_e(e) for e in r["errors"]) + " |")
    if results.get("reference_checks"):
        lines += ["", "## Checks of the elasto-plastic reference (scipy twin) against mpmath", "",
                  "| point | check | relative difference |", "| --- | --- | --- |"]
        for point, checks in results["reference_checks"].items():
            for name, v in checks.items():
                lines.append(f"| {point} | {name} | {v:.1e} |")
    c = results.get("compile")
    lines += ["", "## numba: compile time against run time", ""]
    if not c:
        lines.append("Not measured in this run (`--no-compile-probe`; the workflow's benchmark_mode \"ci\").")
    else:
        lines += ["Two fresh processes sharing an empty NUMBA_CACHE_DIR; the first compiles and writes the "
                  "cache, the second loads it. *first* calls include the one-off θ-node set-up of the "
                  "surface (Hertz inversion) as well.", "",
                  "| call | cold cache | warm cache |", "| --- | --- | --- |"]
        for k in c["cold_cache"]:
            lines.append(f"| {k} | {_fmt_t(c['cold_cache'][k])} | {_fmt_t(c['warm_cache'][k])} |")
    lines += ["", "## Full workflow", "", _reproduction_time(), ""]
    sweep = Path(results.get("sweep_json", "results/benchmarks/sweep_throughput/results.json"))
    if sweep.exists():
        sw = json.loads(sweep.read_text())
        lines += ["## Sweep throughput", "", sw["markdown"], ""]
    return "\n".join(lines)
