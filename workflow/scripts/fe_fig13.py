"""Fig. 13 (rule fe_fig13): u_N along the beam for the three m00 of the elastic rows, with
Table 4's printed centre and end values; PNG and CSV."""

import csv
import io as _io
from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.examples.section9 import FIG13_MARKERS
from roughcontact.paper import plots
from roughcontact.plots.style import parameter_label


def csv_text(paths, runs, paper):
    """paper_figures/fig13.csv from the runs (what run writes)."""
    return _profiles(paths, runs, paper)[2]


def _profiles(paths, runs, paper):
    """(profiles, printed marks, the CSV text) of Fig. 13."""
    table = yaml.safe_load(Path(paper).read_text())["table4"]
    printed = table["columns"]["printed"]
    rows = [str(r) for r in table["rows"]]
    profiles, marks, buf = {}, {}, _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["m00_um2", "x_mm", "u_N_um", "p_N_N_per_mm2"])
    for name in sorted(paths, key=lambda n: -runs[n].m00):
        run_cfg = runs[name]
        ds = io.read_netcdf(paths[name])
        label = parameter_label("m00", run_cfg.m00, "um^2")
        x, u = ds["x"].values, ds["u_N_um"].values
        profiles[label] = (x, u, FIG13_MARKERS.get(run_cfg.m00, "o"))
        i = rows.index(run_cfg.case)
        marks[label] = ((0.0, float(printed["u_N_centre"][i])), (float(x[-1]), float(printed["u_N_end"][i])))
        for xi, ui, pi in zip(x, u, ds["p_N"].values):
            w.writerow([repr(run_cfg.m00), repr(float(xi)), repr(float(ui)), repr(float(pi))])
    return profiles, marks, buf.getvalue()


def run(paths, runs, paper, out, log):
    with io.log_to(log):
        profiles, marks, text = _profiles(paths, runs, paper)
        fig = plots.fig13(profiles, marks)
        io.write_text(out["csv"], text)
        plots.save(fig, out["png"])


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.paths, sm.params.runs, sm.input.paper, {"png": sm.output.png, "csv": sm.output.csv}, sm.log[0])
