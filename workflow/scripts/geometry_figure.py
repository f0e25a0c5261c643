"""Figs 1 and 2 of the paper from the library (rule geometry_figure): PNG + PDF, the drawn data
as CSV (units in the header) and the figure's numbers as JSON for the gallery."""

import csv
import io as _io
import json

import numpy as np

from roughcontact import SpectralMoments, io
from roughcontact.paper import geometry, plots


def _csv(columns):
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(list(columns))
    w.writerows(zip(*[[repr(float(x)) for x in v] for v in columns.values()]))
    return buf.getvalue()


def csv_text(name, cfg, surface, L):
    """The CSV of Fig. 1 or 2 (what run writes), without drawing."""
    return {"fig1": fig1, "fig2": fig2}[name](cfg, SpectralMoments(**surface), L, draw=False)[1]


def fig1(cfg, moments, L, draw=True):
    grid = cfg["grid"]
    p = geometry.fig1_profile(moments, n=int(grid["n"]), dx=float(grid["dx"]), seed=int(cfg["seed"]),
                              profile_length=float(cfg["profile_length"]), separation=float(cfg["separation"]))
    fig = plots.fig1(p, length_unit=L) if draw else None
    numbers = {"delta_73": p.delta, "map_summit_mean": p.map_summit_mean, "map_summit_density": p.map_summit_density,
               "model_summit_density": p.model_summit_density, "map_m00": p.map_m00, "grid_m00": p.grid_m00,
               "m00": moments.m00, "flat": p.flat, "units": {"length": L}}
    return fig, _csv({f"y [{L}]": p.y, f"z [{L}]": p.z}), numbers


def fig2(cfg, moments, L, draw=True):
    g = geometry.fig2_asperity(moments, omega4=float(cfg["omega4"]), omega6=float(cfg["omega6"]),
                               interference=float(cfg["interference"]))
    fig = plots.fig2(g, length_unit=L) if draw else None
    t = np.linspace(0.0, 2.0 * np.pi, 73)
    table = _csv({"theta [rad]": t, f"geometric_x [{L}]": g.a * np.cos(t), f"geometric_y [{L}]": g.b * np.sin(t),
                  f"contact_x [{L}]": g.A * np.cos(t), f"contact_y [{L}]": g.B * np.sin(t)})
    numbers = {"xi4": g.xi4, "xi6": g.xi6, "interference": g.interference, "a": g.a, "b": g.b, "A": g.A, "B": g.B,
               "e1": g.e1, "units": {"length": L, "curvature": f"{L}-1"}}
    return fig, table, numbers


def run(name, cfg, surface, units, out, log):
    with io.log_to(log) as logger:
        moments = SpectralMoments(**surface)
        fig, table, numbers = {"fig1": fig1, "fig2": fig2}[name](cfg, moments, units["length"])
        logger.info("%s: %s", name, numbers)
        plots.save(fig, out["png"])
        io.write_text(out["csv"], table)
        io.write_text(out["json"], json.dumps(numbers, indent=1, sort_keys=True) + "\n")


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.wildcards.fig, sm.params.cfg, sm.params.surface, sm.config["units"],
        {"png": sm.output.png, "csv": sm.output.csv, "json": sm.output.json}, sm.log[0])
