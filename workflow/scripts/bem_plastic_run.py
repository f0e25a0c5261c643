"""One plastic BEM realisation (rule bem_plastic_run): the map of (family, n, seed) and its
contact with a hardness cap at every plasticity index and pressure of the config's bem: plastic:, as netCDF over
(psi, pressure) (roughcontact.bem.solver with hardness; the material from bem.compare). Each
pressure is solved from scratch: the capped problem keeps no plastic history (a warm start is
only the initial guess), and from the previous load's solution it can stall."""

import logging

import numpy as np
import xarray as xr

from roughcontact import io
from roughcontact.bem.compare import plastic_material
from roughcontact.bem.solver import SolverSettings, solve_pressures
from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.statistics.surface import SpectralMoments


def run(job, output, log):
    with io.log_to(log) as logger:
        moments = SpectralMoments(**job["moments"])
        surface = BandLimitedSurface.design(moments, hurst=job["hurst"], k_high=job["k_high"])
        n, seed = job["n"], job["seed"]
        dx, dy = surface.spacing(n)
        z = surface.heights(n, seed)
        cols = {k: [] for k in ("area", "plastic", "gap", "it", "sec", "Y", "H", "cap")}
        for psi in job["psi"]:
            material = plastic_material(moments, job["E_star"], psi, job["yield_coefficient"])
            cap = material.c_h * material.H  # eq. (66): the model's fully plastic mean contact pressure
            name = f"{job['family']} n={n} seed={seed} psi={psi:g}"

            def progress(i, p, r):
                logging.getLogger(io.PROGRESS).info("%s: W/A0 = %g (%d/%d): A/A0 = %.5f, %d iterations, %.1f s",
                                                    name, p, i + 1, len(job["pressures"]), r["area_fraction"],
                                                    r["iterations"], r["seconds"])

            logger.info("%s: Y = %.6g, H = %.6g, cap c_h H = %.6g", name, material.Y, material.H, cap)
            # each pressure from scratch: warm-started from the previous load, the capped conjugate
            # gradients can stall (alpha3 512² seed 1, psi = 5: no convergence at W/A0 = 5 after
            # 3000 iterations from the solution at 2; 135 iterations from scratch)
            res = [solve_pressures(z, dx, dy, job["E_star"], [p], settings=SolverSettings(**job["solver"]),
                                   hardness=cap, progress=lambda _i, p, r, i=i: progress(i, p, r))
                   for i, p in enumerate(job["pressures"])]
            for k, attr in (("area", "area_fraction"), ("plastic", "plastic_area_fraction"), ("gap", "mean_gap"),
                            ("it", "iterations"), ("sec", "seconds")):
                cols[k].append(np.concatenate([getattr(r, attr) for r in res]))
            cols["Y"].append(material.Y)
            cols["H"].append(material.H)
            cols["cap"].append(cap)
        L, S = job["units"]["length"], job["units"]["stress"]
        dims = ("psi", "pressure")
        ds = xr.Dataset(
            {"area_fraction": (dims, np.array(cols["area"]), {"units": "1", "long_name": "real contact area A/A0 (BEM)"}),
             "plastic_area_fraction": (dims, np.array(cols["plastic"]),
                                       {"units": "1", "long_name": "area at the hardness cap over A0 (BEM)"}),
             "mean_gap": (dims, np.array(cols["gap"]), {"units": L, "long_name": "mean gap, points at the cap at gap 0 (BEM)"}),
             "iterations": (dims, np.array(cols["it"]), {"units": "1", "long_name": "constrained conjugate gradient iterations"}),
             "solve_time": (dims, np.array(cols["sec"]), {"units": "s", "long_name": "wall time of the solve"}),
             "Y": ("psi", np.array(cols["Y"]), {"units": S, "long_name": "yield strength giving psi (asperity.laws)"}),
             "H": ("psi", np.array(cols["H"]), {"units": S, "long_name": "hardness H = Y/0.354 (68)"}),
             "cap": ("psi", np.array(cols["cap"]), {"units": S, "long_name": "BEM pressure cap c_h H (66)"})},
            coords={"psi": xr.Variable("psi", np.asarray(job["psi"], dtype=float),
                                       {"units": "1", "long_name": "plasticity index (asperity.laws.plasticity_index)"}),
                    "pressure": xr.Variable("pressure", np.asarray(job["pressures"], dtype=float),
                                            {"units": S, "long_name": "nominal pressure W/A0"})},
            attrs={"title": f"plastic BEM contact of {job['family']} n={n} seed={seed} (roughcontact.bem)",
                   "family": job["family"], "n": n, "seed": seed, "dx": dx, "dy": dy, "E_star": job["E_star"],
                   "length_unit": L, "stress_unit": S})
        io.write_netcdf(ds, output, config=job, settings={"solver": "ContactMechanics constrained conjugate gradients, "
                                                          "hardness cap", **SolverSettings(**job["solver"]).as_dict()})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.job, sm.output[0], sm.log[0])
