"""The statistical law checked against the converged BEM (issue 32, target ``bem``): the mean
gap ḡ and the normal stiffness K/A0 = −dp/dḡ of the BEM extrapolated to the continuum, against
the law p(u_N), k_N the FE model uses — the model's separation h = s√m00 of (53) and its
stiffness K/A0 of (55) at equal W/A0 — and the real contact area likewise. No I/O.

The continuum estimate (stated in the report): the same surface (the lowest seed solved on
every grid; a trigonometric polynomial, so the grids sample one surface) on three grids refined
by 2 gives, per pressure, Richardson's extrapolation with the observed order
(:func:`roughcontact.bem.compare.richardson`); the seed mean on the reference grid (the one with
the most seeds) times that surface's continuum/reference ratio is the estimate of the exact
law. The seeds' scatter (standard error of the mean) and the finest grid's discretisation error
are stated beside it.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

from ..bem.compare import holding_ranges, ladder_stiffness, model_at_pressures, richardson, seed_mean
from ..statistics.surface import SpectralMoments
from .verify import NOT_REPRODUCED, REPRODUCED, Check

__all__ = ["LAW_TOLERANCES", "QUANTITIES", "LAW_COLUMNS", "law_rows", "law_ranges", "convergence_checks",
           "worst_finding", "law_findings", "render_check_rows", "render_law_markdown", "law_dataset", "range_text"]

SCENE = "bem"
#: the agreement levels stated for the law (issue 32): 5, 10 and 20 %
LAW_TOLERANCES = (0.05, 0.10, 0.20)
#: quantity -> (label, model column, BEM column)
QUANTITIES = {"gap": ("mean gap ḡ vs h = s√m00", "gap_model", "gap_exact"),
              "stiffness": ("stiffness −dp/dḡ vs K/A0 (55)", "K_model", "K_exact"),
              "area": ("real contact area A/A0 (52)", "A_model", "A_exact")}
_PER_QUANTITY = ("exact", "exact_sem", "reference", "finest", "order", "extrapolated", "finest_error", "model",
                 "ratio")
LAW_COLUMNS = ("family", "W_over_A0", "grids", "reference_N", "seeds", "paired_seed") + tuple(
    f"{q}_{c}" for q in ("gap", "K", "A") for c in _PER_QUANTITY)


def _ladders(runs: Sequence[Mapping], fam: str):
    """{n: {seed: run}} of one family."""
    out: dict[int, dict[int, Mapping]] = {}
    for r in runs:
        if r["family"] == fam:
            out.setdefault(int(r["n"]), {})[int(r["seed"])] = r
    return out


def _at(run: Mapping, p: np.ndarray, what: str, full_ladder: bool = False) -> np.ndarray:
    """``what`` of a run at the pressures p (a subset of its ladder). The stiffness from the
    ladder restricted to p, so that every grid's differences use the same points (for the grid
    study), or with ``full_ladder`` from the run's whole ladder (central differences wherever the
    ladder goes on: the estimate itself)."""
    pr = np.asarray(run["pressure"], dtype=float)
    idx = [int(np.flatnonzero(np.isclose(pr, x, rtol=1e-12))[0]) for x in p]
    if what == "stiffness":
        if full_ladder:
            return ladder_stiffness(pr, np.asarray(run["mean_gap"], dtype=float))[idx]
        return ladder_stiffness(p, np.asarray(run["mean_gap"], dtype=float)[idx])
    return np.asarray(run[what], dtype=float)[idx]


def _common(p: np.ndarray, runs) -> np.ndarray:
    """The pressures of p solved by every run."""
    for r in runs:
        pr = np.asarray(r["pressure"], dtype=float)
        p = p[[bool(np.any(np.isclose(pr, x, rtol=1e-12))) for x in p]]
    return p


def _values(q, exact, sem, mean, finest, order, extrapolated, error, model) -> list[dict]:
    return [{f"{q}_exact": float(exact[i]), f"{q}_exact_sem": float(sem[i]), f"{q}_reference": float(mean[i]),
             f"{q}_finest": float(finest[i]), f"{q}_order": float(order[i]), f"{q}_extrapolated": bool(extrapolated[i]),
             f"{q}_finest_error": float(error[i]), f"{q}_model": float(model[i]), f"{q}_ratio": float(model[i] / exact[i])}
            for i in range(len(exact))]


def law_rows(runs: Sequence[Mapping], families: Mapping[str, SpectralMoments], E_star: float, *,
             min_order: float = 0.5) -> list[dict]:
    """One row per (family, W/A0) where the continuum estimate exists: the family's three finest
    grids (each twice the previous) share a seed and at least three pressures; the stiffness is
the reference grid's on its whole ladder times the paired seed's continuum/reference ratio from
ladders restricted to the common pressures (the same differences on every grid). Beyond the finest
    grid's ladder, up to the reference grid's, the gap and the stiffness (not the area) continue
    from two grids: the reference grid's seed mean, with the paired seed's change from the grid
    below as its error (``grids`` names the grids of each row). ``runs``: as for
    paper.bem.summary_rows. Families without three grids give no rows (stated by the report)."""
    rows = []
    for fam, m in families.items():
        by_n = _ladders(runs, fam)
        grids = sorted(by_n)[-3:]
        if len(grids) < 3 or grids[1] != 2 * grids[0] or grids[2] != 2 * grids[1]:
            continue
        common = set.intersection(*(set(by_n[n]) for n in grids))
        if not common:
            continue
        seed = min(common)
        ref_n = max(grids, key=lambda n: (len(by_n[n]), n))  # most seeds; the finer on a tie
        p = _common(np.asarray(by_n[grids[-1]][seed]["pressure"], dtype=float), [r for n in grids for r in by_n[n].values()])
        if p.size < 3:
            continue
        model = model_at_pressures(m, p, E_star)
        model_values = {"gap": model.s * m.height_std, "K": model.stiffness, "A": model.area_fraction}
        fam_rows = [{"family": fam, "W_over_A0": float(x), "grids": ",".join(map(str, grids)), "reference_N": ref_n,
                     "seeds": len(by_n[ref_n]), "paired_seed": seed} for x in p]
        for q, what in (("gap", "mean_gap"), ("K", "stiffness"), ("A", "area_fraction")):
            ext = richardson(*(_at(by_n[n][seed], p, what) for n in grids), ratio=2.0, min_order=min_order)
            factor = ext.value / _at(by_n[ref_n][seed], p, what)  # the paired surface's continuum/reference ratio
            mean, sem = seed_mean([_at(r, p, what, full_ladder=True) for r in by_n[ref_n].values()])
            for row, v in zip(fam_rows, _values(q, mean * factor, sem * np.abs(factor), mean, ext.finest, ext.order,
                                                 ext.extrapolated, ext.error, model_values[q])):
                row.update(v)
        below = ref_n // 2
        if below in by_n and seed in by_n[below]:
            ladder = _common(np.asarray(by_n[ref_n][seed]["pressure"], dtype=float),
                             list(by_n[ref_n].values()) + [by_n[below][seed]])
            beyond = ladder > p[-1]
            if np.any(beyond) and ladder.size >= 3:
                pb = ladder[beyond]
                model_b = model_at_pressures(m, pb, E_star)
                extra = [{"family": fam, "W_over_A0": float(x), "grids": f"{below},{ref_n}", "reference_N": ref_n,
                          "seeds": len(by_n[ref_n]), "paired_seed": seed} for x in pb]
                nan = np.full(pb.size, np.nan)
                for q, what, mv in (("gap", "mean_gap", model_b.s * m.height_std), ("K", "stiffness", model_b.stiffness),
                                    ("A", None, nan)):
                    if what is None:  # the area is not converged on two grids (the resolution study):
                        # only the reference grid's mean, to place the loads on the area scale
                        ref_area = seed_mean([_at(r, ladder, "area_fraction")[beyond] for r in by_n[ref_n].values()])[0]
                        vals = _values(q, nan, nan, ref_area, nan, nan, np.zeros(pb.size, bool), nan, nan)
                    else:
                        mean, sem = seed_mean([_at(r, ladder, what, full_ladder=True)[beyond]
                                               for r in by_n[ref_n].values()])
                        fine, coarse = (_at(by_n[n][seed], ladder, what)[beyond] for n in (ref_n, below))
                        vals = _values(q, mean, sem, mean, fine, nan, np.zeros(pb.size, bool),
                                       np.abs(fine - coarse) / np.abs(fine), mv)
                    for row, v in zip(extra, vals):
                        row.update(v)
                fam_rows += extra
        rows += fam_rows
    return rows


_COLUMN = {"gap": "gap", "stiffness": "K", "area": "A"}


def law_ranges(rows: Sequence[Mapping]) -> dict:
    """{family: {quantity: {tolerance: [HoldingRange]}}}: where |model/exact − 1| ≤ tolerance."""
    out = {}
    for fam in dict.fromkeys(r["family"] for r in rows):
        out[fam] = {}
        for q in QUANTITIES:
            rs = [r for r in rows if r["family"] == fam and np.isfinite(r[f"{_COLUMN[q]}_ratio"])]
            p = [r["W_over_A0"] for r in rs]
            a = [r["A_exact"] if np.isfinite(r["A_exact"]) else r["A_reference"] for r in rs]
            out[fam][q] = {tol: holding_ranges(p, [r[f"{_COLUMN[q]}_ratio"] for r in rs], a, tol)
                           for tol in LAW_TOLERANCES}
    return out


def range_text(ranges, stress_unit: str) -> str:
    """'W/A0 = 1–20 N/mm^2 (A/A0 = 0.1–2 %)' per range, or 'nowhere'."""
    if not ranges:
        return "nowhere"
    return "; ".join(f"W/A0 = {r.p_low:g} {stress_unit} (A/A0 = {100 * r.area_low:.2g} %)" if r.p_low == r.p_high
                     else f"W/A0 = {r.p_low:g}–{r.p_high:g} {stress_unit} (A/A0 = {100 * r.area_low:.2g}–"
                          f"{100 * r.area_high:.2g} %)" for r in ranges)


def convergence_checks(rows: Sequence[Mapping], rtol: Mapping[str, float], why: str) -> list[Check]:
    """The BEM's own convergence, one pass/fail row per (family, quantity, grid set): the finest
    grid's estimated discretisation error (compare.Extrapolation.error; on two grids the last
    refinement's change) within ``rtol[quantity]`` at every load."""
    out = []
    for fam, grids in dict.fromkeys((r["family"], r["grids"]) for r in rows):
        rs = [r for r in rows if (r["family"], r["grids"]) == (fam, grids)]
        two = grids.count(",") == 1
        for q, col in _COLUMN.items():
            err = np.array([r[f"{col}_finest_error"] for r in rs])
            if not np.all(np.isfinite(err)):
                continue  # the area on two grids: not converged, not claimed
            i = int(np.argmax(err))
            n = grids.split(",")[-1]
            extra = sum(r[f"{col}_extrapolated"] for r in rs)
            orders = [r[f"{col}_order"] for r in rs if r[f"{col}_extrapolated"]]
            how = ("beyond the finest grid's ladder" if two else
                   f"Richardson at {extra} of {len(rs)} loads"
                   + (f", observed orders {min(orders):.2g}–{max(orders):.2g}" if orders else ""))
            out.append(Check(
                id=f"numerics:bem/converged/{fam}/{q}" + ("/beyond-finest" if two else ""), kind="numerics",
                scene=SCENE, verdict=REPRODUCED if err[i] <= rtol[q] else NOT_REPRODUCED,
                detail=(f"{fam}, grids {grids} (seed {rs[0]['paired_seed']}), W/A0 = {rs[0]['W_over_A0']:g}–"
                        f"{rs[-1]['W_over_A0']:g}: the {n}² {q} within {100 * err[i]:.2g} % of the "
                        + (f"{grids.split(',')[0]}² value" if two else "continuum estimate")
                        + f" (worst at W/A0 = {rs[i]['W_over_A0']:g}); {how}"),
                description=f"BEM grid convergence: {QUANTITIES[q][0]}", model="bem", quantity=q,
                s=f"grids={grids}", unit="1", target=0.0, value=float(err[i]), error=float(err[i]),
                tolerance=float(rtol[q]), tolerance_why=why))
    return out


def worst_finding(check_id: str, rows: Sequence[Mapping], ratios, tolerance: float, head: str, where: str,
                  description: str, model: str, quantity: str, s: str) -> Check:
    """A documented comparison row: the worst model/BEM − 1 over the loads of ``rows`` (ratios
    model/BEM in their order), "reproduced" only if every load is within ``tolerance``; ``s``
    defaults to the load of the worst."""
    dev = np.asarray(ratios, dtype=float) - 1.0
    i = int(np.argmax(np.abs(dev)))
    p = [r["W_over_A0"] for r in rows]
    return Check(
        id=check_id, kind="claim", scene=SCENE, verdict=REPRODUCED if abs(dev[i]) <= tolerance else NOT_REPRODUCED,
        detail=(f"{head} {1 + dev.min():.3f}–{1 + dev.max():.3f} over W/A0 = {p[0]:g}–{p[-1]:g}{where}; worst "
                f"{100 * dev[i]:+.1f} % at W/A0 = {p[i]:g}"),
        description=description, model=model, quantity=quantity, s=s or f"W/A0={p[i]:g}", unit="1", target=1.0,
        value=float(1 + dev[i]), error=float(dev[i]), tolerance=float(tolerance),
        tolerance_why="the loosest agreement level the report states (5 / 10 / 20 %)")


def law_findings(rows: Sequence[Mapping], tolerance: float) -> list[Check]:
    """The comparison of the law with the converged BEM as documented rows (a finding, not a
    pass/fail): per (family, quantity) the worst model/exact − 1 over the loads, "reproduced"
    only if the law is within ``tolerance`` at every load (config/expected_verdicts.yaml
    documents the measured band)."""
    out = []
    for fam in dict.fromkeys(r["family"] for r in rows):
        for q, col in _COLUMN.items():
            rs = [r for r in rows if r["family"] == fam and np.isfinite(r[f"{col}_ratio"])]
            out.append(worst_finding(
                f"claim:bem/law/{fam}/{q}", rs, [r[f"{col}_ratio"] for r in rs], tolerance,
                f"{fam}: model/BEM of the {q}",
                f" (converged BEM, grids {' and '.join(dict.fromkeys(r['grids'] for r in rs))})",
                f"the statistical law against the converged BEM: {QUANTITIES[q][0]}", "bgk", q, ""))
    return out


def render_law_markdown(rows: Sequence[Mapping], *, stress_unit: str, length_unit: str, scale: str,
                        min_order: float) -> str:
    """The section "Where the law holds": the converged gap and stiffness against the model's
    law per load, and the pressure ranges within 5 / 10 / 20 %."""
    S, L = stress_unit, length_unit
    lines = ["", "## Where the law holds: gap and stiffness against the converged BEM", ""]
    if not rows:
        return "\n".join(lines + [
            f"Not resolved at this scale (`{scale}`): the continuum estimate needs the same surface on three "
            "grids refined by 2 (scale `full`: 256², 512², 1024², seed 0 on each); docs/bem.md gives the "
            "full-scale numbers.", ""])
    r0 = rows[0]
    lines += [
        "What an FE model feels is the law p(u_N), k_N: the model's separation h = s√m00 (53) and stiffness K/A0 "
        "(55) at W/A0, against the BEM's mean gap ḡ and −dp/dḡ (differences along the load ladder). The BEM in the "
        f"continuum: per load, the same surface (seed {r0['paired_seed']}) on grids {r0['grids']} extrapolated by "
        f"Richardson with the observed order (where the three values converge monotonically with order ≥ "
        f"{min_order:g}; else the finest grid, order marked –), times the seed mean over its value on the reference "
        f"grid {r0['reference_N']}² ({r0['seeds']} seeds; ± their sem). Beyond the finest grid's ladder (rows on two "
        "grids) the gap and the stiffness are the reference grid's seed mean, their error the change from the grid "
        "below; the area is not converged there (its count on the reference grid in parentheses). ḡ in "
        f"{L}, K in {S}/{L}, W/A0 in {S}.", "",
        "| family | W/A0 | grids | ḡ exact (± sem) | h model | h/ḡ | order ḡ | K exact (± sem) | K model | K_model/K "
        "| order K | A/A0 exact [%] | A_model/A | finest-grid error ḡ / K / A [%] |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]

    def order(r, q):
        return f"{r[f'{q}_order']:.2g}" if r[f"{q}_extrapolated"] else "–"

    def num(x, fmt):
        return format(x, fmt) if np.isfinite(x) else "–"

    for r in rows:
        area = (num(100 * r["A_exact"], ".3g") if np.isfinite(r["A_exact"])
                else f"({num(100 * r['A_reference'], '.3g')} at {r['reference_N']}²)")
        lines.append(
            f"| {r['family']} | {r['W_over_A0']:g} | {r['grids']} | {r['gap_exact']:.4g} ± {r['gap_exact_sem']:.2g} | "
            f"{r['gap_model']:.4g} | {r['gap_ratio']:.3f} | {order(r, 'gap')} | {r['K_exact']:.4g} ± {r['K_exact_sem']:.2g} | "
            f"{r['K_model']:.4g} | {r['K_ratio']:.3f} | {order(r, 'K')} | {area} | {num(r['A_ratio'], '.3f')} | "
            f"{100 * r['gap_finest_error']:.2f} / {100 * r['K_finest_error']:.2f} / {num(100 * r['A_finest_error'], '.2f')} |")
    lines += ["", "Where the law is within 5 / 10 / 20 % of the exact one (|model/exact − 1| ≤ tol on the ladder's "
              "points; a range ends at the last point inside):", ""]
    for fam, by_q in law_ranges(rows).items():
        for q, by_tol in by_q.items():
            lines.append(f"- **{fam}, {q}**: " + " — ".join(f"within {100 * tol:.0f} %: {range_text(rs, S)}"
                                                          for tol, rs in by_tol.items()))
    return "\n".join(lines) + "\n"


def render_check_rows(checks: Sequence[Check]) -> str:
    """The gate's rows of this module and paper.bem_plastic (convergence: pass/fail; findings:
    documented in config/expected_verdicts.yaml) as a Markdown table; empty without rows."""
    if not checks:
        return ""
    lines = ["", "## Verification rows of the law and plastic comparisons", "",
             "| id | value | tolerance | verdict | detail |", "| --- | --- | --- | --- | --- |"]
    for c in checks:
        lines.append(f"| `{c.id}` | {c.value:.4g} | {100 * c.tolerance:g} % | {c.verdict} | {c.detail} |")
    return "\n".join(lines) + "\n"


def law_dataset(rows: Sequence[Mapping], units: Mapping[str, str]):
    """The law comparison as an xarray.Dataset over a ``row`` dimension with CF units."""
    import xarray as xr

    L, S = units["length"], units["stress"]
    unit = {"gap": L, "K": f"{S} {L}-1", "A": "1"}
    data = {"family": ("row", np.array([r["family"] for r in rows], dtype=str), {"long_name": "surface family"}),
            "W_over_A0": ("row", [r["W_over_A0"] for r in rows], {"units": S, "long_name": "nominal pressure W/A0"}),
            "grids": ("row", np.array([r["grids"] for r in rows], dtype=str),
                      {"long_name": "grids of the extrapolation (points per side)"}),
            "reference_N": ("row", [r["reference_N"] for r in rows], {"units": "1", "long_name": "grid of the seed mean"}),
            "seeds": ("row", [r["seeds"] for r in rows], {"units": "1", "long_name": "seeds on the reference grid"}),
            "paired_seed": ("row", [r["paired_seed"] for r in rows], {"units": "1", "long_name": "seed on every grid"})}
    long = {"exact": "continuum estimate (BEM)", "exact_sem": "seeds' standard error of the continuum estimate",
            "reference": "seed mean on the reference grid (BEM)", "finest": "paired seed on the finest grid (BEM)",
            "order": "observed order of convergence", "extrapolated": "Richardson extrapolation applied (1) or finest (0)",
            "finest_error": "finest grid's estimated relative discretisation error", "model": "statistical model",
            "ratio": "model over continuum estimate"}
    names = {"gap": "mean gap", "K": "normal stiffness K/A0", "A": "real contact area A/A0"}
    for q in ("gap", "K", "A"):
        for c in _PER_QUANTITY:
            u = unit[q] if c in ("exact", "exact_sem", "reference", "finest", "model") else "1"
            values = [int(r[f"{q}_{c}"]) if c == "extrapolated" else r[f"{q}_{c}"] for r in rows]
            data[f"{q}_{c}"] = ("row", values, {"units": u, "long_name": f"{names[q]}: {long[c]}"})
    ds = xr.Dataset(data, coords={"row": ("row", np.arange(len(rows)), {"units": "1", "long_name": "row"})})
    ds.attrs["title"] = "The statistical law against the converged BEM (issue 32)"
    return ds
