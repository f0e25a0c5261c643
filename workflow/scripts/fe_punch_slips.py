"""Figs 18/19 (rule fe_punch_slips): directions of the plastic slips at the contact points at
the maximum load, cases a, b, c, under the main reading and the sensitivity's; PNG and CSV."""

from roughcontact import io
from roughcontact.paper import fe_punch, plots, report


def csv_text(family, readings, paths):
    """paper_figures/fig18.csv or fig19.csv from the runs (what run writes)."""
    rows = []
    for reading in readings:
        for case in "abc":
            rows += fe_punch.slip_rows(io.read_netcdf(paths[f"{family}-{reading}-{case}"]), reading=reading, case=case)
    return report.render_rows_csv(rows, units=fe_punch.SLIP_ROW_UNITS)


def run(family, readings, paths, out, log):
    with io.log_to(log):
        panels, rows = {}, []
        for reading in readings:
            row = panels.setdefault(fe_punch.READING_LABEL.get(reading, reading), {})
            for case in "abc":
                ds = io.read_netcdf(paths[f"{family}-{reading}-{case}"])
                row[f"case ({case})"] = fe_punch.slip_panel(ds)
                rows += fe_punch.slip_rows(ds, reading=reading, case=case)
        name = fe_punch.FAMILY_ROW[family]
        fig = plots.punch_slips(panels, title=f"Fig. {18 if family == 'quadratic' else 19}: directions of the plastic "
                                              f"slips at the contact points, {name} elements, maximum load")
        io.write_text(out["csv"], report.render_rows_csv(rows, units=fe_punch.SLIP_ROW_UNITS))
        plots.save(fig, out["png"])


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.family, sm.params.readings, sm.params.paths, {"png": sm.output.png, "csv": sm.output.csv},
        sm.log[0])
