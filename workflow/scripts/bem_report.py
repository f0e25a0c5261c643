"""The BEM comparison report (rule bem_report): results/bem/summary.{csv,nc}, summits.csv,
paper_figures/bem.{png,md} and the checks' verification rows (roughcontact.paper.bem)."""

import csv
import io as _io
from pathlib import Path

import numpy as np
import xarray as xr

from roughcontact import io
from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.paper import bem as report
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
        seed_ratios = {}
        for r in runs:
            model = [row["A_BGK_over_A0"] for row in rows if (row["family"], row["N"]) == (r["family"], r["n"])]
            seed_ratios.setdefault((r["family"], r["n"]), []).append(np.asarray(r["area_fraction"]) / np.asarray(model))
        io.write_text(out["csv"], _csv(rows, report.SUMMARY_COLUMNS))
        io.write_text(out["summits"], _csv(summits, list(summits[0])))
        io.write_text(out["checks"], checks_to_csv(checks))
        fig = report.figure(rows, seed_ratios, stress_unit=units["stress"])
        style.save(fig, out["png"])
        io.write_text(out["md"], report.render_markdown(rows, summits, checks, scale=scale, grids=grids,
                                                        E_star=cfg["E_star"], units=units,
                                                        timing=_timing(runs, bench_dir),
                                                        resolution=report.resolution_rows(runs)))
        ds = report.summary_dataset(rows, units)
        io.write_netcdf(ds, out["nc"], config={"bem": cfg, "scale": scale, "grids": grids})
        logger.info("%d rows, %d summit rows, %d checks", len(rows), len(summits), len(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run({"runs": list(sm.input.runs), "checks": sm.input.checks},
        {k: sm.output[k] for k in ("csv", "nc", "png", "md", "checks", "summits")}, sm.params.cfg, sm.params.scale,
        sm.params.grids, sm.params.units, sm.params.benchmarks, sm.log[0])
