"""Table 5 (rule fe_table5): D against the printed values under every reading (both element
families), the prose of section 9.2 as checks under the main reading and the sensitivity's, the
printed D against each reading's frictionless bound, and Table 5 under every reading next to the
bound; paper_figures/table5.md/.csv, fe_punch_readings.md/.csv and results/verify/table5.checks.csv."""

from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import fe_punch, report, verify


def derive(paths, runs, cfg, paper, expected):
    """(checks with their expectations, models, the printed table, the datasets, the readings'
    rows) of example 9.2 from the runs (what run writes; the published-CSV anchor re-derives the
    CSVs with it)."""
    paper_table = yaml.safe_load(Path(paper).read_text())["table5"]
    data = {name: io.read_netcdf(path) for name, path in paths.items()}
    checks, models, bounds = fe_punch.table5_checks(data, runs, cfg, paper_table)
    checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
    rows = fe_punch.reading_rows({n: ds.attrs for n, ds in data.items()},
                                 {n: r for n, r in runs.items() if r.case != "frictionless"}, bounds)
    return checks, models, paper_table, data, rows


def readings_csv(rows):
    return report.render_rows_csv(
        rows, units={**{k: "N mm" for k in rows[0] if k.startswith("D_") or k == "bound"}, "seconds": "s"})


def csv_texts(paths, runs, cfg, paper, expected):
    """{"table5": paper_figures/table5.csv, "readings": fe_punch_readings.csv} from the runs."""
    checks, models, _, _, rows = derive(paths, runs, cfg, paper, expected)
    return {"table5": report.render_table_csv(checks, models), "readings": readings_csv(rows)}


def run(paths, runs, cfg, paper, expected, out, log):
    with io.log_to(log) as logger:
        checks, models, paper_table, data, rows = derive(paths, runs, cfg, paper, expected)
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        shown = report.shown_provenance(io.read_provenance(next(iter(data.values()))))
        title = "Table 5: the total dissipation energy D [N mm] under every reading"
        io.write_text(out["md"], report.render_table_markdown(title, checks, paper_table, models, provenance=shown))
        io.write_text(out["csv"], report.render_table_csv(checks, models))
        io.write_text(out["readings_md"], fe_punch.render_readings_markdown(rows, checks, shown, cfg["d_attr"]))
        io.write_text(out["readings_csv"], readings_csv(rows))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.paths, sm.params.runs, sm.params.cfg, sm.input.paper, sm.input.expected,
        {"md": sm.output.md, "csv": sm.output.csv, "readings_md": sm.output.readings_md,
         "readings_csv": sm.output.readings_csv, "checks": sm.output.checks}, sm.log[0])
