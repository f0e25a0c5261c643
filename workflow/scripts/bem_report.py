"""The BEM comparison report (rule bem_report): results/bem/summary.{csv,nc}, summits.csv,
law.{csv,nc}, plastic.{csv,nc}, paper_figures/bem.{png,md} and the verification rows
(roughcontact.paper.bem, .bem_law, .bem_plastic)."""

import csv
import io as _io
from pathlib import Path

import numpy as np

from roughcontact import io
from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.paper import bem as report
from roughcontact.paper import bem_law, bem_plastic
from roughcontact.plots import style
from roughcontact.paper.verify import checks_to_csv
from roughcontact.statistics.surface import SpectralMoments


def _csv(rows, fields):
    buf = _io.StringIO()
    w = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    w.writerows({k: r[k] for k in fields} for r in rows)
    return buf.getvalue()


def _timing(runs, bench_dir):
    by = {}
    for r in runs:
        tsv = Path(bench_dir) / r["family"] / f"n{r['n']}" / f"seed{r['seed']}.tsv"
        if not tsv.exists():
            continue
        head, values = tsv.read_text().splitlines()[:2]
        rec = dict(zip(head.split("\t"), values.split("\t")))
        by.setdefault((r["family"], r["n"]), []).append(rec)
    out = []
    for (fam, n), recs in by.items():
        def num(k):
            return [float(x[k]) for x in recs if x.get(k, "NA") not in ("NA", "-")]
        out.append({"family": fam, "N": n, "jobs": len(recs), "wall_s": float(np.mean(num("s"))),
                    "cpu_s": float(np.mean(num("cpu_time") or [np.nan])),
                    "max_rss_mb": float(np.max(num("max_rss") or [np.nan]))})
    return sorted(out, key=lambda t: (t["family"], t["N"]))


def _plastic_runs(paths):
    runs = []
    for path in paths:
        ds = io.read_netcdf(path)
        runs.append({"family": ds.attrs["family"], "n": int(ds.attrs["n"]), "seed": int(ds.attrs["seed"]),
                     **{k: ds[k].values for k in ("psi", "pressure", "area_fraction", "plastic_area_fraction",
                                                  "mean_gap")}})
    return runs


def run(inp, out, cfg, scale, grids, units, bench_dir, log):
    with io.log_to(log) as logger:
        families = {f: SpectralMoments(**m) for f, m in cfg["families"].items()}
        designs = {f: BandLimitedSurface.design(m, hurst=cfg["hurst"], k_high=cfg["k_high"]) for f, m in families.items()}
        runs = []
        for path in inp["runs"]:
            ds = io.read_netcdf(path)
            runs.append({"family": ds.attrs["family"], "n": int(ds.attrs["n"]), "seed": int(ds.attrs["seed"]),
                         "pressure": ds["pressure"].values, "area_fraction": ds["area_fraction"].values,
                         "mean_gap": ds["mean_gap"].values, "iterations": ds["iterations"].values,
                         "solve_time": ds["solve_time"].values})
        rows = report.summary_rows(runs, families, cfg["E_star"], cfg["k_high"])
        maps = {}
        for r in runs:
            d = designs[r["family"]]
            maps.setdefault((r["family"], r["n"]), []).append((d.heights(r["n"], r["seed"]), *d.spacing(r["n"])))
        summits = report.summit_rows(maps, families, {f: d.grid_moments()["m22"] for f, d in designs.items()})
        with open(inp["checks"]) as fh:
            check_results = [{**r, "n": int(r["n"]), **{k: float(r[k]) for k in
                              ("size", "size_exact", "p_max", "p_max_exact", "pixels_across")}}
                             for r in csv.DictReader(fh)]
        checks = report.check_rows(check_results, cfg["checks"]["rtol"], " ".join(cfg["checks"]["why"].split()))
        # (a configuration older than issue 32 has neither section: the report is then the elastic one)
        conv = cfg.get("converged", {"min_order": 0.5, "rtol": 0.0, "why": ""})
        law = bem_law.law_rows(runs, families, cfg["E_star"], min_order=conv["min_order"]) if "converged" in cfg else []
        plastic = bem_plastic.plastic_rows(_plastic_runs(inp.get("plastic", [])), families, cfg["E_star"],
                                           cfg.get("plastic", {}).get("yield_coefficient", 1.62))
        top = bem_law.LAW_TOLERANCES[-1]
        closed_form = checks
        checks = closed_form + (bem_law.convergence_checks(law, conv["rtol"], " ".join(conv["why"].split()))
                                + bem_law.law_findings(law, top) + bem_plastic.plastic_findings(plastic, top))
        seed_ratios = {}
        for r in runs:
            model = [row["A_BGK_over_A0"] for row in rows if (row["family"], row["N"]) == (r["family"], r["n"])]
            seed_ratios.setdefault((r["family"], r["n"]), []).append(np.asarray(r["area_fraction"]) / np.asarray(model))
        io.write_text(out["csv"], _csv(rows, report.SUMMARY_COLUMNS))
        io.write_text(out["summits"], _csv(summits, list(summits[0])))
        io.write_text(out["checks"], checks_to_csv(checks))
        fig = report.figure(rows, seed_ratios, stress_unit=units["stress"])
        style.save(fig, out["png"])
        io.write_text(out["md"], report.render_markdown(rows, summits, closed_form, scale=scale, grids=grids,
                                                        E_star=cfg["E_star"], units=units,
                                                        timing=_timing(runs, bench_dir),
                                                        resolution=report.resolution_rows(runs))
                     + bem_law.render_law_markdown(law, stress_unit=units["stress"], length_unit=units["length"],
                                                   scale=scale, min_order=conv["min_order"])
                     + bem_plastic.render_plastic_markdown(plastic, stress_unit=units["stress"],
                                                           length_unit=units["length"], scale=scale)
                     + bem_law.render_check_rows(checks[len(closed_form):]))
        provenance = {"bem": cfg, "scale": scale, "grids": grids}
        if out.get("law_csv"):
            io.write_text(out["law_csv"], _csv(law, bem_law.LAW_COLUMNS))
            io.write_netcdf(bem_law.law_dataset(law, units), out["law_nc"], config=provenance)
        if out.get("plastic_csv"):
            io.write_text(out["plastic_csv"], _csv(plastic, bem_plastic.PLASTIC_COLUMNS))
            io.write_netcdf(bem_plastic.plastic_dataset(plastic, units), out["plastic_nc"], config=provenance)
        ds = report.summary_dataset(rows, units)
        io.write_netcdf(ds, out["nc"], config=provenance)
        logger.info("%d rows, %d summit rows, %d law rows, %d plastic rows, %d checks", len(rows), len(summits),
                    len(law), len(plastic), len(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    inputs, outputs = dict(sm.input.items()), dict(sm.output.items())
    run({"runs": list(sm.input.runs), "checks": sm.input.checks, "plastic": list(inputs.get("plastic", []))},
        outputs, sm.params.cfg, sm.params.scale, sm.params.grids, sm.params.units, sm.params.benchmarks, sm.log[0])
