"""The 2D plane-stress solutions of the anchored beam runs (rule fe_beam_plane_stress): one per
interface law, results/fe/beam_plane_stress.nc (roughcontact.paper.plane_stress)."""

from dataclasses import asdict

import numpy as np
import xarray as xr

from roughcontact import io
from roughcontact.paper.fe_anchors import law_key
from roughcontact.paper.plane_stress import plane_stress_beam, reference_solution


def run(runs, cfg, out, log):
    with io.log_to(log) as logger:
        mesh, coarse = cfg["mesh"], cfg["estimate_mesh"]
        laws, beams = {}, {}
        for name, r in runs.items():
            key = law_key(r)
            first = laws.setdefault(key, r)
            beams[key] = plane_stress_beam(first, *mesh)
            if plane_stress_beam(r, *mesh) != beams[key]:  # one 2D solution per law needs one 2D problem
                raise ValueError(f"beam run {name} shares the law {key} with another run but not its geometry, "
                                 "material or loads: the 2D solution per law would not be its own")
        sols = {}
        for key, r in laws.items():
            sols[key] = reference_solution(r, mesh, coarse)
            logger.info("%s: u_N centre %+.6f um, end %+.6f um (change from %s: %.1e, %.1e um), %d dofs, %.1f s", key,
                        sols[key]["u_N_centre_um"], sols[key]["u_N_end_um"], coarse, sols[key]["error_centre_um"],
                        sols[key]["error_end_um"], sols[key]["dofs"], sols[key]["seconds"])
        keys = list(sols)
        x = sols[keys[0]]["x_mm"]
        per_law = {"u_N_centre_um", "u_N_end_um", "error_centre_um", "error_end_um", "dofs", "seconds",
                   "newton_iterations", "equilibrium_error"}
        units = {"u_N_centre_um": "um", "u_N_end_um": "um", "error_centre_um": "um", "error_end_um": "um", "dofs": "1",
                 "seconds": "s", "newton_iterations": "1", "equilibrium_error": "1"}
        long = {"u_N_centre_um": "interface deflection at the centre from the seated state, negative = approach",
                "u_N_end_um": "interface deflection at the end from the seated state, negative = approach",
                "error_centre_um": "change of u_N_centre_um from the mesh half as fine (discretisation error estimate)",
                "error_end_um": "change of u_N_end_um from the mesh half as fine (discretisation error estimate)",
                "dofs": "degrees of freedom of the 2D model", "seconds": "solve time of both meshes",
                "newton_iterations": "Newton iterations over all load levels",
                "equilibrium_error": "|sum of w b p_N - P/2| / (P/2) at the final load"}
        data = {k: ("law", np.array([sols[key][k] for key in keys]), {"units": units[k], "long_name": long[k]})
                for k in per_law}
        data["u_N_um"] = (("law", "x"), np.stack([sols[key]["u_N_um"] for key in keys]),
                          {"units": "um", "long_name": "interface deflection from the seated state, negative = approach"})
        data["p_N"] = (("law", "x"), np.stack([sols[key]["p_N"] for key in keys]),
                       {"units": "N/mm^2", "long_name": "interface pressure at the final load"})
        ds = xr.Dataset(data, coords={
            "law": ("law", keys, {"long_name": "interface law (roughcontact.paper.fe_anchors.law_key)"}),
            "x": ("x", x, {"units": "mm", "long_name": "position along the beam from mid-length"})})
        ds.attrs["title"] = "Example 9.1 in 2D plane stress (roughcontact.paper.plane_stress): the gate's engine-free anchor"
        io.write_netcdf(ds, out, config={"runs": {n: r.to_dict() for n, r in runs.items()}, "plane_stress": cfg,
                                         "beams": {key: asdict(b) for key, b in beams.items()}},
                        settings={"solver": "roughcontact.paper.plane_stress (Q9, plane stress, Newton)"})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.runs, sm.params.cfg, sm.output[0], sm.log[0])
