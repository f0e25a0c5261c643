"""The BEM comparison as a report (issue 21, target ``bem``): the summary table, the figure,
the summit statistics, the BEM's closed-form checks as verification rows, and the Markdown
section "Where the model holds". No I/O: the workflow script reads the runs and writes these.
"""

from __future__ import annotations

import math
from collections import defaultdict
from typing import Mapping, Sequence

import numpy as np

from ..bem.compare import holding_ranges, kappa, ladder_stiffness, model_at_pressures, seed_mean
from ..statistics.summits import gaussian_summit_statistics, measure_summits
from ..statistics.surface import SpectralMoments
from ..plots import style
from .verify import NOT_REPRODUCED, REPRODUCED, Check, relative_error

__all__ = ["SUMMARY_COLUMNS", "group_runs", "summary_rows", "summary_dataset", "resolution_rows", "summit_rows", "check_rows", "figure", "render_markdown",
           "TOLERANCES"]

SCENE = "bem"
#: the agreement levels of the report (issue 21): the model within 10 % and 20 % of the BEM
TOLERANCES = (0.10, 0.20)
SUMMARY_COLUMNS = ("family", "alpha", "N", "seeds", "px_per_shortest_wavelength", "W_over_A0",
                   "A_BEM_over_A0", "A_BEM_sem", "A_BGK_over_A0", "A_ratio", "A_ratio_sem", "s_BEM", "s_BEM_sem",
                   "s_BGK", "kappa_BEM", "kappa_BGK", "K_BEM", "K_BGK", "iterations", "solve_seconds")


def group_runs(runs: Sequence[Mapping], families: Mapping) -> list[tuple[tuple[str, int], list]]:
    """[((family, N), [run, ...]), ...] in the families' order, then by N."""
    groups = defaultdict(list)
    for r in runs:
        groups[(r["family"], int(r["n"]))].append(r)
    return sorted(groups.items(), key=lambda kv: (list(families).index(kv[0][0]), kv[0][1]))


def summary_rows(runs: Sequence[Mapping], families: Mapping[str, SpectralMoments], E_star: float,
                 k_high: float) -> list[dict]:
    """One row per (family, N, W/A0) from the runs (each {family, n, seed, pressure, area_fraction,
    mean_gap, iterations, solve_time}); A_ratio = A_BEM/A_BGK, its sem over the seeds' ratios."""
    rows = []
    for (fam, n), rs in group_runs(runs, families):
        m = families[fam]
        p = np.asarray(rs[0]["pressure"], dtype=float)
        for r in rs:
            if not np.array_equal(np.asarray(r["pressure"], dtype=float), p):
                raise ValueError(f"{fam} n={n}: the seeds were solved at different pressures")
        model = model_at_pressures(m, p, E_star)
        area = np.array([r["area_fraction"] for r in rs])
        gap = np.array([r["mean_gap"] for r in rs])
        stiff = np.array([ladder_stiffness(p, g) for g in gap])
        a_mean, a_sem = seed_mean(area)
        ratio_mean, ratio_sem = seed_mean(area / model.area_fraction)
        s_mean, s_sem = seed_mean(gap / m.height_std)
        k_bem = kappa(a_mean, p, E_star, m)
        k_bgk = kappa(model.area_fraction, p, E_star, m)
        it = np.mean([r["iterations"] for r in rs], axis=0)
        sec = np.mean([r["solve_time"] for r in rs], axis=0)
        for i, pi in enumerate(p):
            rows.append({"family": fam, "alpha": m.alpha1, "N": n, "seeds": len(rs),
                         "px_per_shortest_wavelength": n / k_high, "W_over_A0": float(pi),
                         "A_BEM_over_A0": float(a_mean[i]), "A_BEM_sem": float(a_sem[i]),
                         "A_BGK_over_A0": float(model.area_fraction[i]), "A_ratio": float(ratio_mean[i]),
                         "A_ratio_sem": float(ratio_sem[i]), "s_BEM": float(s_mean[i]), "s_BEM_sem": float(s_sem[i]),
                         "s_BGK": float(model.s[i]), "kappa_BEM": float(k_bem[i]), "kappa_BGK": float(k_bgk[i]),
                         "K_BEM": float(np.mean(stiff[:, i])), "K_BGK": float(model.stiffness[i]),
                         "iterations": float(it[i]), "solve_seconds": float(sec[i])})
    return rows


def resolution_rows(runs: Sequence[Mapping]) -> list[dict]:
    """The resolution study: per family, the seeds solved on every grid, and each pressure solved
    on every grid: A/A0 on each grid over A/A0 on the finest (paired: the same surface)."""
    rows = []
    for fam in dict.fromkeys(r["family"] for r in runs):
        rs = [r for r in runs if r["family"] == fam]
        grids = sorted({int(r["n"]) for r in rs})
        seeds = sorted(set.intersection(*({int(r["seed"]) for r in rs if int(r["n"]) == n} for n in grids)))
        for seed in seeds:
            by_n = {int(r["n"]): r for r in rs if int(r["seed"]) == seed}
            finest = by_n[grids[-1]]
            for i, p in enumerate(finest["pressure"]):
                row = {"family": fam, "seed": seed, "W_over_A0": float(p),
                       "A_finest": float(finest["area_fraction"][i]), "N_finest": grids[-1]}
                for n in grids:
                    k = np.flatnonzero(np.isclose(by_n[n]["pressure"], p))
                    row[f"A_{n}_over_finest"] = float(by_n[n]["area_fraction"][k[0]] / row["A_finest"]) if k.size else math.nan
                rows.append(row)
    return rows


def summit_rows(maps: Mapping[tuple, Sequence[tuple]], families: Mapping[str, SpectralMoments],
                m22: Mapping[str, float]) -> list[dict]:
    """Measured summit statistics per (family, N) (mean over the seeds' maps; ``maps`` maps
    (family, n) to [(z, dx, dy), ...]) against the expectations without m22 (the model: (17),
    (70), (71)–(73)) and with the surfaces' m22 (statistics.summits)."""
    rows = []
    for (fam, n), items in maps.items():
        m = families[fam]
        measured = [measure_summits(z, dx, dy) for z, dx, dy in items]
        model, gauss = gaussian_summit_statistics(m), gaussian_summit_statistics(m, m22[fam])
        for q in ("density", "mean_curvature", "mean_height", "height_std"):
            v = np.array([getattr(s, q) for s in measured])
            mean, sem = seed_mean(v)
            rows.append({"family": fam, "N": n, "seeds": len(items), "quantity": q, "measured": float(mean),
                         "measured_sem": float(sem), "model_without_m22": getattr(model, q),
                         "gaussian_with_m22": getattr(gauss, q),
                         "measured_over_model": float(mean / getattr(model, q)),
                         "measured_over_gaussian": float(mean / getattr(gauss, q)),
                         "summits_per_map": float(np.mean([s.count for s in measured]))})
    return rows


def check_rows(results: Sequence[Mapping], rtol: float, why: str) -> list[Check]:
    """Verification rows of the BEM's closed-form checks (each {case, n, size, size_exact,
    p_max, p_max_exact, ...}): size and p_max within ``rtol``."""
    out = []
    for r in results:
        for q, label in (("size", "contact size"), ("p_max", "largest pressure")):
            err = relative_error(r[q], r[f"{q}_exact"])
            ok = abs(err) <= rtol
            out.append(Check(
                id=f"numerics:bem/{r['case']}/{q}/n={r['n']}", kind="numerics", scene=SCENE,
                verdict=REPRODUCED if ok else NOT_REPRODUCED,
                detail=f"{r['case']} on {r['n']}^2 ({r['pixels_across']:.0f} pixels across): {label} "
                       f"{r[q]:.6g} vs closed form {r[f'{q}_exact']:.6g} ({100 * err:+.2f} %)",
                description=f"BEM vs closed form: {r['case']}, {label}", model=r["case"], quantity=q,
                s=f"n={r['n']}", unit="1", target=float(r[f"{q}_exact"]), value=float(r[q]), error=float(err),
                tolerance=float(rtol), tolerance_why=why))
    return out


def _band(ax, tol, **kw):
    ax.axhspan(1.0 / (1.0 + tol), 1.0 / (1.0 - tol), **kw)


def figure(rows: Sequence[Mapping], seed_ratios: Mapping[tuple, np.ndarray], *, stress_unit: str = "N/mm^2"):
    """A_BEM/A_BGK against W/A0 per family (columns), one curve per grid with ±2 sem and every
    seed's ratio as dots; below, the separations s_BEM (mean gap) and s_BGK."""
    fams = list(dict.fromkeys(r["family"] for r in rows))
    fig = style.new_figure(figsize=(6.4 * len(fams) / 1.6, 6.4))
    axes = fig.subplots(2, len(fams), sharex=True, squeeze=False)
    for j, fam in enumerate(fams):
        ax, ax2 = axes[0, j], axes[1, j]
        for tol, a in zip(TOLERANCES, (0.25, 0.12)):
            _band(ax, tol, color="0.5", alpha=a, lw=0)
        grids = sorted({r["N"] for r in rows if r["family"] == fam})
        colors = style.ordered_colors(len(grids))
        for c, n in zip(colors, grids):
            rs = [r for r in rows if r["family"] == fam and r["N"] == n]
            p = np.array([r["W_over_A0"] for r in rs])
            ratio = np.array([r["A_ratio"] for r in rs])
            sem = np.array([r["A_ratio_sem"] for r in rs])
            label = f"{n}², {rs[0]['px_per_shortest_wavelength']:g} px/λ_s, {rs[0]['seeds']} seeds"
            ax.errorbar(p, ratio, yerr=2 * sem, color=c, marker="o", ms=3, capsize=2, label=label)
            seeds = seed_ratios.get((fam, n))
            if seeds is not None:
                for s in seeds:
                    ax.plot(p, s, ls="none", marker=".", ms=2.5, color=c, alpha=0.5)
            ax2.plot(p, [r["s_BEM"] for r in rs], color=c, marker="o", ms=3, label=f"BEM mean gap, {n}²")
        longest = max(grids, key=lambda n: sum(1 for r in rows if r["family"] == fam and r["N"] == n))
        rs = [r for r in rows if r["family"] == fam and r["N"] == longest]
        ax2.plot([r["W_over_A0"] for r in rs], [r["s_BGK"] for r in rs], color="k", ls="--", label="model s")
        alpha = rows[[r["family"] for r in rows].index(fam)]["alpha"]
        ax.set_title(f"{fam} (α = {alpha:.3g})")
        ax.set_xscale("log")
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_ylabel("A_BEM/A_BGK (mean ± 2 sem; dots: seeds)")
        style.note(ax, "shaded: model within 10 %, 20 %", loc="lower right", fontsize=7)
        ax2.set_ylabel("separation ḡ/√m00, s")
        ax2.set_xlabel(style.axis_label("W/A0", stress_unit))
        ax.legend(fontsize=7)
        ax2.legend(fontsize=7)
    return fig


def _max_text(max_pressure) -> str:
    if isinstance(max_pressure, Mapping):
        return ", ".join(f"{v:g} ({k})" for k, v in max_pressure.items())
    return f"{max_pressure:g}"


def _range_text(ranges, stress_unit):
    if not ranges:
        return "nowhere on the ladder"
    return "; ".join(f"W/A0 = {r.p_low:g}–{r.p_high:g} {stress_unit} (A_BEM/A0 = {100 * r.area_low:.2g}–"
                     f"{100 * r.area_high:.2g} %, worst {100 * r.worst:.1f} %)" for r in ranges)


def holding(rows: Sequence[Mapping]) -> dict:
    """{(family, N): {tolerance: [HoldingRange]}} of |A_BGK/A_BEM − 1| ≤ tolerance."""
    out = {}
    for key in dict.fromkeys((r["family"], r["N"]) for r in rows):
        rs = [r for r in rows if (r["family"], r["N"]) == key]
        p = [r["W_over_A0"] for r in rs]
        model_over_bem = [1.0 / r["A_ratio"] for r in rs]
        a = [r["A_BEM_over_A0"] for r in rs]
        out[key] = {tol: holding_ranges(p, model_over_bem, a, tol) for tol in TOLERANCES}
    return out


def render_markdown(rows, summits, checks: Sequence[Check], *, scale: str, grids: Mapping, E_star: float,
                    units: Mapping[str, str], timing: Sequence[Mapping], resolution: Sequence[Mapping] = ()) -> str:
    """paper_figures/bem.md: setup, the BEM's checks, A_BEM/A_BGK per load, where the model
    holds, separations, κ and stiffness, summit statistics, runtime and memory."""
    S = units["stress"]
    L = units["length"]
    lines = ["# The model against the BEM on the same surfaces (target bem)", "",
             f"Scale `{scale}`: grids " + ", ".join(f"{n}² ({g['seeds']} seeds, W/A0 ≤ {_max_text(g['max_pressure'])} {S})"
                                                    for n, g in sorted(grids.items())) +
             f"; E* = {E_star:g} {S}; lengths in {L}. Elastic, frictionless, periodic, load-controlled BEM "
             "(ContactMechanics, constrained conjugate gradients); the model is the Bush–Gibson–Keogh "
             "elastic model (52)–(53) with exact Hertz functions at the same W/A0 (docs/bem.md).", "",
             "## The BEM checked on closed forms", "",
             "| check | grid | pixels across | computed | closed form | error | tolerance | verdict |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for c in checks:
        lines.append(f"| {c.model} {c.quantity} | {c.s} | {c.detail.split('(')[1].split(' pixels')[0]} | "
                     f"{c.value:.6g} | {c.target:.6g} | {100 * c.error:+.2f} % | {100 * c.tolerance:g} % | {c.verdict} |")
    lines += ["", "## A_BEM/A_BGK against the load", "",
              "| family | N | px/λ_s | seeds | W/A0 | A_BEM/A0 [%] | A_BGK/A0 [%] | A_BEM/A_BGK (± sem) | s_BEM | s_BGK | κ_BEM | κ_BGK | K_BEM/K_BGK |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        lines.append(f"| {r['family']} | {r['N']} | {r['px_per_shortest_wavelength']:g} | {r['seeds']} | {r['W_over_A0']:g} | "
                     f"{100 * r['A_BEM_over_A0']:.4g} | {100 * r['A_BGK_over_A0']:.4g} | {r['A_ratio']:.3f} ± {r['A_ratio_sem']:.3f} | "
                     f"{r['s_BEM']:.3f} | {r['s_BGK']:.3f} | {r['kappa_BEM']:.3f} | {r['kappa_BGK']:.3f} | "
                     f"{r['K_BEM'] / r['K_BGK']:.3f} |")
    if resolution:
        ns = sorted(int(k.split("_")[1]) for k in resolution[0] if k.startswith("A_") and k.endswith("_over_finest"))
        lines += ["", "## Resolution study (the same surfaces on every grid)", "",
                  f"A/A0 on each grid over A/A0 on the finest ({ns[-1]}²) for the same seed, i.e. the same "
                  "surface sampled more finely:", "",
                  "| family | seed | W/A0 | A/A0 finest [%] | " + " | ".join(f"{n}²" for n in ns) + " |",
                  "| --- | --- | --- | --- | " + " | ".join("---" for _ in ns) + " |"]
        for r in resolution:
            lines.append(f"| {r['family']} | {r['seed']} | {r['W_over_A0']:g} | {100 * r['A_finest']:.4g} | "
                         + " | ".join(f"{r[f'A_{n}_over_finest']:.3f}" for n in ns) + " |")
    lines += ["", "## Where the model holds", "",
              f"The model's real contact area A_BGK within 10 % and 20 % of the BEM's, |A_BGK/A_BEM − 1| ≤ tol, "
              f"on the mean over the seeds (W/A0 in {S}; the load ladder's points, so a range ends at the last "
              "point inside):", ""]
    for fam in dict.fromkeys(r["family"] for r in rows):
        rs = [r for r in rows if r["family"] == fam]
        n = max((r["seeds"], r["N"]) for r in rs)[1]
        rs = [r for r in rs if r["N"] == n and r["A_ratio_sem"] <= 0.05 * r["A_ratio"]]
        if rs:
            err = [1.0 / r["A_ratio"] - 1.0 for r in rs]
            lines.append(f"- {fam}, {n}² (the grid with the most seeds), loads where the seeds agree to 5 % "
                         f"(W/A0 = {rs[0]['W_over_A0']:g}–{rs[-1]['W_over_A0']:g} {S}): the model's area is "
                         f"{100 * min(err):+.1f} % to {100 * max(err):+.1f} % off the BEM's; the BEM's κ = "
                         f"{min(r['kappa_BEM'] for r in rs):.2f}–{max(r['kappa_BEM'] for r in rs):.2f}, the model's "
                         f"{min(r['kappa_BGK'] for r in rs):.2f}–{max(r['kappa_BGK'] for r in rs):.2f}.")
    lines.append("")
    for (fam, n), by_tol in holding(rows).items():
        lines.append(f"- **{fam}, {n}²**: " + " — ".join(f"within {100 * tol:.0f} %: {_range_text(rs, S)}"
                                                       for tol, rs in by_tol.items()))
    lines += ["", "## Summit statistics of the maps against (17), (70)–(73)", "",
              "Measured: 8-neighbour maxima of the maps, curvatures by spectral differentiation; model: m22 "
              "neglected (closed forms); Gaussian: the surfaces' m22 kept (statistics.summits).", "",
              "| family | N | summits/map | quantity | measured (± sem) | model (no m22) | measured/model | Gaussian (m22) | measured/Gaussian |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in summits:
        lines.append(f"| {r['family']} | {r['N']} | {r['summits_per_map']:.0f} | {r['quantity']} | {r['measured']:.5g} ± "
                     f"{r['measured_sem']:.2g} | {r['model_without_m22']:.5g} | {r['measured_over_model']:.3f} | "
                     f"{r['gaussian_with_m22']:.5g} | {r['measured_over_gaussian']:.3f} |")
    lines += ["", "## Runtime and memory (Snakemake benchmarks of the bem_run jobs)", "",
              "| family | N | jobs | wall s per job (mean) | CPU s per job (mean) | peak RSS MB (max) |", "| --- | --- | --- | --- | --- | --- |"]
    for t in timing:
        lines.append(f"| {t['family']} | {t['N']} | {t['jobs']} | {t['wall_s']:.0f} | {t['cpu_s']:.0f} | {t['max_rss_mb']:.0f} |")
    return "\n".join(lines) + "\n"


#: (units key or UDUNITS string, long name) of the numeric columns of the summary
_COLUMN_META = {
    "alpha": ("1", "bandwidth parameter alpha1 = alpha2 (11)"),
    "seeds": ("1", "realisations averaged"),
    "px_per_shortest_wavelength": ("1", "grid points per shortest wavelength"),
    "A_BEM_over_A0": ("1", "real contact area A/A0, BEM (mean over seeds)"),
    "A_BEM_sem": ("1", "standard error of the mean of A/A0, BEM"),
    "A_BGK_over_A0": ("1", "real contact area A/A0, model (52)-(53), exact Hertz"),
    "A_ratio": ("1", "A_BEM/A_BGK (mean over seeds)"),
    "A_ratio_sem": ("1", "standard error of the mean of A_BEM/A_BGK"),
    "s_BEM": ("1", "mean gap over sqrt(m00), BEM"),
    "s_BEM_sem": ("1", "standard error of the mean of s_BEM"),
    "s_BGK": ("1", "separation s = h/sqrt(m00) of the model at W/A0"),
    "kappa_BEM": ("1", "kappa = A E* h'/W, BEM"),
    "kappa_BGK": ("1", "kappa = A E* h'/W, model"),
    "K_BEM": ("stiffness", "normal stiffness K/A0 = -dp/d(mean gap), BEM"),
    "K_BGK": ("stiffness", "normal stiffness K/A0 (55), model"),
    "iterations": ("1", "solver iterations (mean over seeds)"),
    "solve_seconds": ("s", "wall time of one solve (mean over seeds)"),
}


def summary_dataset(rows: Sequence[Mapping], units: Mapping[str, str]):
    """The summary as an xarray.Dataset over a ``row`` dimension with CF units and long names."""
    import xarray as xr

    unit = {"1": "1", "s": "s", "stiffness": f"{units['stress']} {units['length']}-1"}
    data = {"family": ("row", [r["family"] for r in rows], {"long_name": "surface family"}),
            "N": ("row", [r["N"] for r in rows], {"units": "1", "long_name": "grid points per side"}),
            "W_over_A0": ("row", [r["W_over_A0"] for r in rows], {"units": units["stress"], "long_name": "nominal pressure W/A0"})}
    for name, (u, long_name) in _COLUMN_META.items():
        data[name] = ("row", [r[name] for r in rows], {"units": unit[u], "long_name": long_name})
    ds = xr.Dataset(data, coords={"row": ("row", np.arange(len(rows)), {"units": "1", "long_name": "row"})})
    ds.attrs["title"] = "The statistical model against the BEM on the same surfaces (issue 21)"
    return ds
