"""The study of example 9.1 (rule fe_beam_study): tangential restraint, E*, mesh convergence;
paper_figures/fe_beam_study.md/.csv and results/verify/fe_beam_study.checks.csv."""

from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import fe_beam, report, verify


UNITS = {"E_star": "N/mm^2", "mu": "1", "seconds": "s"}


def csv_text(paths, runs):
    """paper_figures/fe_beam_study.csv from the runs (what run writes)."""
    attrs = {name: io.read_netcdf(path).attrs for name, path in paths.items()}
    return report.render_rows_csv(fe_beam.study_rows(attrs, runs), units=UNITS)


def run(paths, runs, cfg, expected, out, log):
    with io.log_to(log) as logger:
        data = {name: io.read_netcdf(path) for name, path in paths.items()}
        attrs = {name: ds.attrs for name, ds in data.items()}
        rows = fe_beam.study_rows(attrs, runs)
        main = {f"{r['family']}/{r['case']}/{q}": r[f"{q}_um"] for r in rows if r["variant"] == "main"
                for q in fe_beam.QUANTITIES}
        variants = {f"{r['family']}/{r['case']}/{r['variant']}": {q: r[f"{q}_um"] for q in fe_beam.QUANTITIES}
                    for r in rows if r["variant"] != "main"}
        elastic = {c: next(e for e, ce in cfg["cases"].items() if ce["law"] == "elastic" and ce["m00"] == cc["m00"])
                   for c, cc in cfg["cases"].items()}
        checks = fe_beam.study_checks("fe_beam_study", main, variants, cfg["study"], elastic)
        checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        shown = report.shown_provenance(io.read_provenance(next(iter(data.values()))))
        io.write_text(out["md"], fe_beam.render_study_markdown(rows, checks, shown))
        io.write_text(out["csv"], report.render_rows_csv(rows, units=UNITS))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.paths, sm.params.runs, sm.params.cfg, sm.input.expected,
        {"md": sm.output.md, "csv": sm.output.csv, "checks": sm.output.checks}, sm.log[0])
