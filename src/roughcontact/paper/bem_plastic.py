"""The elasto-plastic model against a BEM with a hardness cap (issue 32, target ``bem``): real
contact area and mean gap against the load on the same surfaces as the elastic comparison. No I/O.

The material of a plasticity index ψ: Y from ψ at the configured K_Y
(asperity.laws.yield_strength_for_plasticity_index, the closure of Figs 5–8), H = Y/0.354 (68),
c_h = 0.967, ω_p/ω_c = 45 (AsperityMaterial's defaults, the paper's). The BEM's perfectly
plastic cap is c_h H: the mean pressure (66) the model gives a fully plastic contact, so that a
fully plastic spot carries the same pressure in both. The model: (78)–(85) at the separation
that gives W/A0 (contact.at_pressure), its separation h = s√m00 against the BEM's mean gap ḡ
(points at the cap at gap 0, bem.solver).
"""

from __future__ import annotations

import warnings
from typing import Mapping, Sequence

import numpy as np

from ..bem.compare import holding_ranges, plastic_material, seed_mean
from ..contact.at_pressure import contact_at_pressure
from ..statistics.surface import SpectralMoments
from .bem import group_runs
from .bem_law import LAW_TOLERANCES, range_text, worst_finding
from .verify import Check

__all__ = ["PLASTIC_COLUMNS", "plastic_rows", "plastic_ranges", "plastic_findings",
           "render_plastic_markdown", "plastic_dataset"]

SCENE = "bem"
PLASTIC_COLUMNS = ("family", "psi", "N", "seeds", "W_over_A0", "Y", "H", "cap", "A_BEM", "A_BEM_sem", "A_model",
                   "A_ratio", "cap_over_A_BEM", "yielded_over_A_model", "plastic_over_A_model", "gap_BEM",
                   "gap_BEM_sem", "h_model", "gap_ratio", "A_elastic_model")


def _model(moments, pressures, material):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ep = contact_at_pressure(moments, pressures, material=material, hertz="exact", validity="off")
        el = contact_at_pressure(moments, pressures, E_star=material.E_star, model="bgk", hertz="exact",
                                 validity="off")
    return ep, el


def plastic_rows(runs: Sequence[Mapping], families: Mapping[str, SpectralMoments], E_star: float,
                 yield_coefficient: float = 1.62) -> list[dict]:
    """One row per (family, ψ, N, W/A0) from the plastic runs (each {family, n, seed, psi[k],
    pressure[j], area_fraction[k, j], plastic_area_fraction[k, j], mean_gap[k, j]}): the BEM's seed
    means (± sem) against the elasto-plastic model; ratios are model/BEM."""
    rows = []
    for (fam, n), rs in group_runs(runs, families):
        m = families[fam]
        p, psis = np.asarray(rs[0]["pressure"], dtype=float), np.asarray(rs[0]["psi"], dtype=float)
        for r in rs:
            if not (np.array_equal(np.asarray(r["pressure"], dtype=float), p)
                    and np.array_equal(np.asarray(r["psi"], dtype=float), psis)):
                raise ValueError(f"plastic {fam} n={n}: the seeds were solved at different pressures or psi")
        for k, psi in enumerate(psis):
            material = plastic_material(m, E_star, float(psi), yield_coefficient)
            ep, el = _model(m, p, material)
            area = np.array([np.asarray(r["area_fraction"], dtype=float)[k] for r in rs])
            at_cap = np.array([np.asarray(r["plastic_area_fraction"], dtype=float)[k] for r in rs])
            gap = np.array([np.asarray(r["mean_gap"], dtype=float)[k] for r in rs])
            a_mean, a_sem = seed_mean(area)
            g_mean, g_sem = seed_mean(gap)
            h_model = np.asarray(ep.s) * m.height_std
            curves = ep.curves
            for i, pi in enumerate(p):
                rows.append({"family": fam, "psi": float(psi), "N": n, "seeds": len(rs), "W_over_A0": float(pi),
                             "Y": material.Y, "H": material.H, "cap": material.c_h * material.H,
                             "A_BEM": float(a_mean[i]), "A_BEM_sem": float(a_sem[i]),
                             "A_model": float(ep.area_fraction[i]), "A_ratio": float(ep.area_fraction[i] / a_mean[i]),
                             "cap_over_A_BEM": float(np.mean(at_cap[:, i]) / a_mean[i]),
                             "yielded_over_A_model": float(curves.yielded_area_ratio[i]),
                             "plastic_over_A_model": float(curves.plastic_area_ratio[i]),
                             "gap_BEM": float(g_mean[i]), "gap_BEM_sem": float(g_sem[i]), "h_model": float(h_model[i]),
                             "gap_ratio": float(h_model[i] / g_mean[i]),
                             "A_elastic_model": float(el.area_fraction[i])})
    return rows


def _finest(rows):
    """{(family, ψ): the rows of the family's finest grid}."""
    out = {}
    for fam, psi in dict.fromkeys((r["family"], r["psi"]) for r in rows):
        rs = [r for r in rows if (r["family"], r["psi"]) == (fam, psi)]
        n = max(r["N"] for r in rs)
        out[(fam, psi)] = [r for r in rs if r["N"] == n]
    return out


def plastic_ranges(rows: Sequence[Mapping]) -> dict:
    """{(family, ψ): {"area"|"gap": {tolerance: [HoldingRange]}}} on each family's finest grid."""
    out = {}
    for key, rs in _finest(rows).items():
        p, a = [r["W_over_A0"] for r in rs], [r["A_BEM"] for r in rs]
        out[key] = {q: {tol: holding_ranges(p, [r[col] for r in rs], a, tol) for tol in LAW_TOLERANCES}
                    for q, col in (("area", "A_ratio"), ("gap", "gap_ratio"))}
    return out


def plastic_findings(rows: Sequence[Mapping], tolerance: float, min_seeds: int = 2) -> list[Check]:
    """Documented rows (a finding, not a pass/fail): per (family, ψ, area|gap) on the finest grid
    the worst model/BEM − 1 over the loads; "reproduced" only within ``tolerance`` everywhere.
    Only where the finest grid has at least ``min_seeds`` seeds (one surface is not a finding:
    the CI scale's single seed gives none)."""
    out = []
    for (fam, psi), rs in _finest(rows).items():
        if rs[0]["seeds"] < min_seeds:
            continue
        for q, col in (("area", "A_ratio"), ("gap", "gap_ratio")):
            out.append(worst_finding(
                f"claim:bem/plastic/{fam}/psi={psi:g}/{q}", rs, [r[col] for r in rs], tolerance,
                f"{fam}, ψ = {psi:g}, {rs[0]['N']}² ({rs[0]['seeds']} seeds): model/BEM of the {q}", "",
                f"the elasto-plastic model against the BEM with a hardness cap: {q}", "bgk-ep", q, f"psi={psi:g}"))
    return out


def render_plastic_markdown(rows: Sequence[Mapping], *, stress_unit: str, length_unit: str, scale: str) -> str:
    """The section "Plastic contact": the model (78)–(85) against the BEM with the cap c_h H."""
    S, L = stress_unit, length_unit
    lines = ["", "## Plastic contact: the elasto-plastic model against the BEM with a hardness cap", ""]
    if not rows:
        return "\n".join(lines + [f"No plastic BEM runs at this scale (`{scale}`).", ""])
    lines += [
        "The material of a plasticity index ψ: Y from ψ (K_Y = 1.62), H = Y/0.354 (68), c_h = 0.967, ω_p/ω_c = 45; "
        "the BEM caps the contact pressure at c_h H (66), the model's fully plastic mean pressure. At equal W/A0: "
        "the model's A/A0 (78) and separation h = s√m00 against the BEM's A/A0 and mean gap ḡ (points at the cap "
        f"at gap 0); ratios model/BEM; A_cap/A: the BEM's contact at the cap, against the model's yielded "
        f"(A^ep + A^p)/A and fully plastic A^p/A. Seed means (± sem) on each family's finest grid (the coarser "
        f"grids: results/bem/plastic.csv); W/A0, Y, H in {S}, ḡ and h in {L}.", "",
        "| family | ψ | Y | c_h H | N | seeds | W/A0 | A_BEM/A0 [%] | A_model/A0 [%] | A_model/A_BEM | elastic model A/A0 [%] "
        "| A_cap/A (BEM) | yielded / A^p/A (model) | ḡ BEM | h model | h/ḡ |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in (r for rs in _finest(rows).values() for r in rs):
        lines.append(
            f"| {r['family']} | {r['psi']:g} | {r['Y']:.4g} | {r['cap']:.4g} | {r['N']} | {r['seeds']} | {r['W_over_A0']:g} | "
            f"{100 * r['A_BEM']:.4g} ± {100 * r['A_BEM_sem']:.2g} | {100 * r['A_model']:.4g} | {r['A_ratio']:.3f} | "
            f"{100 * r['A_elastic_model']:.4g} | {r['cap_over_A_BEM']:.3f} | {r['yielded_over_A_model']:.3f} / "
            f"{r['plastic_over_A_model']:.3f} | {r['gap_BEM']:.4g} ± {r['gap_BEM_sem']:.2g} | {r['h_model']:.4g} | "
            f"{r['gap_ratio']:.3f} |")
    lines += ["", "Where the elasto-plastic model is within 5 / 10 / 20 % of the BEM with the cap (each family's "
              "finest grid, seed means; |model/BEM − 1| ≤ tol on the ladder's points):", ""]
    for (fam, psi), by_q in plastic_ranges(rows).items():
        for q, by_tol in by_q.items():
            lines.append(f"- **{fam}, ψ = {psi:g}, {q}**: " + " — ".join(
                f"within {100 * tol:.0f} %: {range_text(rs, S)}" for tol, rs in by_tol.items()))
    return "\n".join(lines) + "\n"


def plastic_dataset(rows: Sequence[Mapping], units: Mapping[str, str]):
    """The plastic comparison as an xarray.Dataset over a ``row`` dimension with CF units."""
    import xarray as xr

    L, S = units["length"], units["stress"]
    meta = {"psi": ("1", "plasticity index"), "N": ("1", "grid points per side"), "seeds": ("1", "realisations"),
            "W_over_A0": (S, "nominal pressure W/A0"), "Y": (S, "yield strength"), "H": (S, "hardness (68)"),
            "cap": (S, "BEM pressure cap c_h H (66)"), "A_BEM": ("1", "A/A0, BEM with the cap (seed mean)"),
            "A_BEM_sem": ("1", "sem of A/A0, BEM"), "A_model": ("1", "A/A0, elasto-plastic model (78)"),
            "A_ratio": ("1", "A_model/A_BEM"), "cap_over_A_BEM": ("1", "BEM contact area at the cap over A"),
            "yielded_over_A_model": ("1", "(A^ep + A^p)/A, model"), "plastic_over_A_model": ("1", "A^p/A, model"),
            "gap_BEM": (L, "mean gap, BEM with the cap (seed mean)"), "gap_BEM_sem": (L, "sem of the mean gap"),
            "h_model": (L, "separation h = s sqrt(m00), model"), "gap_ratio": ("1", "h_model/gap_BEM"),
            "A_elastic_model": ("1", "A/A0, elastic model (52) at the same W/A0")}
    data = {"family": ("row", np.array([r["family"] for r in rows], dtype=str), {"long_name": "surface family"})}
    for name, (u, long_name) in meta.items():
        data[name] = ("row", [r[name] for r in rows], {"units": u, "long_name": long_name})
    ds = xr.Dataset(data, coords={"row": ("row", np.arange(len(rows)), {"units": "1", "long_name": "row"})})
    ds.attrs["title"] = "The elasto-plastic model against the BEM with a hardness cap (issue 32)"
    return ds
