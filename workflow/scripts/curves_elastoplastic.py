"""Elasto-plastic curves of one scene (rule curves_elastoplastic): call roughcontact.paper.scenes with
exactly what the scene declares, write netCDF with provenance."""

import time

import numpy as np

from roughcontact import io
from roughcontact.paper import scenes


def _grid(g):
    return np.linspace(g["start"], g["stop"], int(g["num"]))


def run(scene, cfg, surface, units, provenance, output, log):
    with io.log_to(log) as logger:
        t0 = time.perf_counter()
        s = _grid(cfg["s"])
        common = dict(accuracy=cfg["accuracy"]["production"], units=units)
        if cfg["kind"] == "elastoplastic_psi":
            ds = scenes.psi_curves(surface, cfg["E_star"], cfg["psi"], s, closure=cfg["closure"], **common)
        elif cfg["kind"] == "stiffness_pressure":
            ds = scenes.stiffness_curves(surface, cfg["m00"], cfg["E_star"], cfg["psi"], cfg["Y"],
                                         cfg["closures"], s, **common)
        elif cfg["kind"] == "stiffness_sensitivity":
            ds = scenes.stiffness_sensitivity(surface, cfg["E_star"], cfg["psi"], cfg["variants"],
                                              cfg["psi_values"], s, closure=cfg["closure"], **common)
        else:
            raise ValueError(f"{scene}: not an elasto-plastic scene kind: {cfg['kind']!r}")
        logger.info("%s: %s in %.2f s", scene, dict(ds.sizes), time.perf_counter() - t0)
        ds.attrs["scene"] = scene
        io.write_netcdf(ds, output, config=provenance, settings={"method": "production", **common})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.params.surface, sm.params.units, sm.params.provenance,
        sm.output[0], sm.log[0])
