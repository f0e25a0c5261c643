"""A_G/A_B(s) for each surface of a bearing-ratio scene (Fig. 3) at plotting accuracy."""

import time

import numpy as np
import xarray as xr

from roughcontact import SpectralMoments, io
from roughcontact.contact import bearing_area_ratio
from roughcontact.contact.units import PARAMETER_LONG_NAMES, parameter_units
from roughcontact.contact.units import attrs as contact_attrs


def run(scene, scene_config, surfaces, provenance, output, log, units):
    with io.log_to(log) as logger:
        grid = scene_config["s"]
        s = np.linspace(grid["start"], grid["stop"], int(grid["num"]))
        accuracy = scene_config["accuracy"]["production"]
        ratios = []
        for curve in scene_config["curves"]:
            t0 = time.perf_counter()
            surface = SpectralMoments(**surfaces[curve["surface"]])
            ratios.append(bearing_area_ratio(surface, s, method="production", accuracy=accuracy))
            logger.info("%s: %d points in %.2f s", curve["surface"], s.size, time.perf_counter() - t0)
        names = [c["surface"] for c in scene_config["curves"]]
        ds = xr.Dataset(
            {"bearing_area_ratio": (("surface", "s"), np.array(ratios), {
                "units": "1", "long_name": "A_G/A_B (summit-model over Gaussian bearing area, eqs. 24-25)"})},
            coords={
                "surface": ("surface", names, {"long_name": "surface name (config/config.yaml)"}),
                "label": ("surface", [c["label"] for c in scene_config["curves"]], {"long_name": "legend label"}),
                "s": ("s", s, contact_attrs("s", units)),
                **{
                    m: ("surface", [surfaces[n][m] for n in names], {"units": u, "long_name": PARAMETER_LONG_NAMES[m]})
                    for m, u in parameter_units(units["length"], units["stress"]).items() if m in surfaces[names[0]]
                },
            },
            attrs={"scene": scene},
        )
        io.write_netcdf(ds, output, config=provenance,
                        settings={"method": "production", "accuracy": accuracy})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.params.surfaces, sm.params.provenance, sm.output[0], sm.log[0],
        sm.config["units"])
