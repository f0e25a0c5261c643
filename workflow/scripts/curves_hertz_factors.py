"""f1(e), f2(e) (eqs. 46-47) for each Hertz option of a Hertz-factor scene (Fig. 4)."""

import numpy as np
import xarray as xr

from roughcontact import io
from roughcontact.asperity.ellipse import fig4_curves


def run(scene, scene_config, provenance, output, log):
    with io.log_to(log) as logger:
        grid = scene_config["e"]
        e = np.linspace(grid["start"], grid["stop"], int(grid["num"]))
        f1, f2 = [], []
        for hertz in scene_config["hertz"]:
            a, b = fig4_curves(e, hertz=hertz)
            f1.append(np.asarray(a, dtype=float))
            f2.append(np.asarray(b, dtype=float))
            logger.info("hertz=%s: f1(0) = %.17g, f2(0) = %.17g", hertz, f1[-1][0], f2[-1][0])
        ds = xr.Dataset(
            {
                "f1": (("hertz", "e"), np.array(f1), {"units": "1", "long_name": "area factor f1(e), eq. (46)"}),
                "f2": (("hertz", "e"), np.array(f2), {"units": "1", "long_name": "load factor f2(e), eq. (47)"}),
            },
            coords={
                "hertz": ("hertz", list(scene_config["hertz"]), {"units": "1", "long_name": "Hertz functions"}),
                "e": ("e", e, {"units": "1", "long_name": "eccentricity of the contact ellipse"}),
            },
            attrs={"scene": scene},
        )
        io.write_netcdf(ds, output, config=provenance, settings={"hertz": list(scene_config["hertz"])})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.params.provenance, sm.output[0], sm.log[0])
