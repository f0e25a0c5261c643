"""One BEM realisation (rule bem_run): the map of (family, n, seed) and its contact at every
pressure of the ladder, as netCDF over the pressure (roughcontact.bem)."""

import logging

import numpy as np
import xarray as xr

from roughcontact import io
from roughcontact.bem.solver import SolverSettings, solve_pressures
from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.statistics.surface import SpectralMoments


def run(job, output, log):
    with io.log_to(log) as logger:
        surface = BandLimitedSurface.design(SpectralMoments(**job["moments"]), hurst=job["hurst"],
                                            k_high=job["k_high"])
        n, seed = job["n"], job["seed"]
        dx, dy = surface.spacing(n)
        z = surface.heights(n, seed)
        name = f"{job['family']} n={n} seed={seed}"

        def progress(i, p, r):
            logging.getLogger(io.PROGRESS).info("%s: W/A0 = %g (%d/%d): A/A0 = %.5f, %d iterations, %.1f s",
                                                name, p, i + 1, len(job["pressures"]), r["area_fraction"],
                                                r["iterations"], r["seconds"])

        logger.info("%s: cell %.6g x %.6g, dx = %.6g, dy = %.6g, k_low = %.6g", name, *surface.lengths, dx, dy,
                    surface.k_low)
        res = solve_pressures(z, dx, dy, job["E_star"], job["pressures"], settings=SolverSettings(**job["solver"]),
                              progress=progress)
        L, S = job["units"]["length"], job["units"]["stress"]
        p = xr.Variable("pressure", res.pressure, {"units": S, "long_name": "nominal pressure W/A0"})
        ds = xr.Dataset(
            {"area_fraction": ("pressure", res.area_fraction, {"units": "1", "long_name": "real contact area A/A0 (BEM)"}),
             "mean_gap": ("pressure", res.mean_gap, {"units": L, "long_name": "mean gap between flat and deformed surface (BEM)"}),
             "iterations": ("pressure", res.iterations, {"units": "1", "long_name": "constrained conjugate gradient iterations"}),
             "max_penetration": ("pressure", res.max_penetration, {"units": L, "long_name": "largest overlap left in the contact"}),
             "solve_time": ("pressure", res.seconds, {"units": "s", "long_name": "wall time of the solve"})},
            coords={"pressure": p},
            attrs={"title": f"BEM contact of {name} (roughcontact.bem)", "family": job["family"], "n": n,
                   "seed": seed, "dx": dx, "dy": dy, "Lx": surface.lengths[0], "Ly": surface.lengths[1],
                   "k_low": surface.k_low, "k_high": surface.k_high, "hurst": surface.hurst,
                   "E_star": job["E_star"], "length_unit": L, "stress_unit": S, "rms_height": float(np.std(z))})
        io.write_netcdf(ds, output, config=job, settings={"solver": "ContactMechanics constrained conjugate gradients",
                                                          **res.settings.as_dict()})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.job, sm.output[0], sm.log[0])
