"""Table 4 (rule fe_table4): the main runs against the printed values (both element families),
the prose claims of 9.1; paper_figures/table4.md/.csv and results/verify/table4.checks.csv."""

from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import fe_beam, report, verify


def derive(paths, runs, cfg, paper, expected):
    """(checks with their expectations, models, the printed table, the datasets) of Table 4 from
    the main runs (what run writes; the published-CSV anchor re-derives the CSV with it)."""
    paper_table = yaml.safe_load(Path(paper).read_text())["table4"]
    data = {name: io.read_netcdf(path) for name, path in paths.items()}
    attrs = {name: ds.attrs for name, ds in data.items()}
    cases = [str(c) for c in paper_table["rows"]]
    results = fe_beam.table4_results(attrs, runs, cases)
    models = {f"fe-{fam}": {"paper_column": "printed",
                            "label": f"{'28-node + 32-node' if fam == 'cubic' else '21-node + 18-node'} elements, "
                                     f"{cfg['tangential']} tangential restraint"}
              for fam in cfg["families"]}
    tol = cfg["tolerances"]
    tolerances = {"printed_rounding": tol["printed_rounding"],
                  **{m: {"u_N_centre": tol["centre"], "u_N_end": tol["end"]} for m in models}}
    checks = verify.table_cell_checks("table4", paper_table, results, models, tolerances)
    open_points = {f"fe-{runs[n].family}": {} for n in runs}
    for name, run_cfg in runs.items():
        open_points[f"fe-{run_cfg.family}"][run_cfg.case] = attrs[name]["open_points"]
    checks += fe_beam.table4_claims("table4", results, cfg["cases"], open_points, cfg["claims"])
    checks += fe_beam.equilibrium_checks("table4", attrs, runs, cfg["equilibrium"])
    checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
    return checks, models, paper_table, data


def csv_text(paths, runs, cfg, paper, expected):
    """paper_figures/table4.csv from the main runs."""
    checks, models, _, _ = derive(paths, runs, cfg, paper, expected)
    return report.render_table_csv(checks, models)


def run(paths, runs, cfg, paper, expected, out, log):
    with io.log_to(log) as logger:
        checks, models, paper_table, data = derive(paths, runs, cfg, paper, expected)
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        shown = report.shown_provenance(io.read_provenance(next(iter(data.values()))))
        title = ("Table 4: interface deflection at the centre and the end of the beam [um], from the seated state "
                 f"(E* = {cfg['E_star']:.6g} N/mm^2, {cfg['tangential']} tangential restraint)")
        io.write_text(out["md"], report.render_table_markdown(title, checks, paper_table, models, provenance=shown))
        io.write_text(out["csv"], report.render_table_csv(checks, models))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.paths, sm.params.runs, sm.params.cfg, sm.input.paper, sm.input.expected,
        {"md": sm.output.md, "csv": sm.output.csv, "checks": sm.output.checks}, sm.log[0])
