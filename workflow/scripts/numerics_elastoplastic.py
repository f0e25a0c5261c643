"""Elasto-plastic production vs slow twin at the scene's check points (rule
numerics_elastoplastic); netCDF with provenance."""

import time

from roughcontact import io
from roughcontact.paper import scenes


def run(scene, cfg, surfaces, output, log):
    with io.log_to(log) as logger:
        t0 = time.perf_counter()
        ds = scenes.elastoplastic_numerics(cfg["points"], surfaces, cfg["E_star"], production=cfg["production"],
                                           reference_rtol=cfg["reference_rtol"], units=snakemake.config["units"])  # noqa: F821
        logger.info("%s: %d points in %.1f s", scene, ds.sizes["point"], time.perf_counter() - t0)
        ds.attrs["scene"] = scene
        io.write_netcdf(ds, output, config={"scene": scene, "scene_config": cfg, "surfaces": surfaces},
                        settings={"production": cfg["production"], "reference_rtol": cfg["reference_rtol"]})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.params.surfaces, sm.output[0], sm.log[0])
