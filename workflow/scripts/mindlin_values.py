"""k_N/k_T of one Table-3 column (rule mindlin_values): roughcontact.interface.tangential at the scene's
reading of the printed rows, written as netCDF with provenance."""

import numpy as np
import xarray as xr

from roughcontact import io
from roughcontact.interface.tangential import kn_over_kt


def run(scene, column, b2_over_a2, nu, output, log):
    with io.log_to(log) as logger:
        r = np.asarray(b2_over_a2, dtype=float)
        values = np.asarray(kn_over_kt(r, nu), dtype=float)
        logger.info("%s/%s (nu = %g): %s", scene, column, nu, values.tolist())
        ds = xr.Dataset(
            {"kn_over_kt": ("b2_over_a2", values, {"units": "1", "long_name": "k_N/k_T, corrected eq. (96)"})},
            coords={"b2_over_a2": ("b2_over_a2", r, {"units": "1", "long_name": "B^2/A^2 (B along the force)"})},
            attrs={"scene": scene, "model_name": column, "nu": nu},
        )
        io.write_netcdf(ds, output, config={"scene": scene, "column": column, "b2_over_a2": r.tolist(), "nu": nu},
                        settings={"method": "closed form"})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.column, sm.params.b2_over_a2, sm.params.nu, sm.output[0], sm.log[0])
