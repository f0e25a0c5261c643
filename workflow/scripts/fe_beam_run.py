"""One run of example 9.1 (rule fe_beam_run): solve with roughcontact.paper.fe_beam.beam_case,
write netCDF (with provenance) and the VTU files."""

from roughcontact import io
from roughcontact.fe.beam import interface_fields
from roughcontact.fe.vtu import write_solution
from roughcontact.paper.fe_beam import beam_case


def run(run_cfg, provenance, out, log):
    with io.log_to(log) as logger:
        def progress(k, n, inc):
            logger.info("increment %d/%d: load %.6g N, %d Newton iterations, %d cut-backs, %.2f s",
                        k, n, inc.level, inc.iterations, inc.cutbacks, inc.seconds)

        result = beam_case(run_cfg, progress)
        logger.info("u_N centre %+.5f um, end %+.5f um; %d dofs, %d interface points, %.2f s, equilibrium %.1e",
                    result.u_N_centre_um, result.u_N_end_um, result.n_dofs, result.n_points, result.seconds,
                    result.equilibrium_error)
        io.write_netcdf(result.to_dataset(), out["nc"], config=provenance,
                        settings={"solver": "Newton, sparse LU (roughcontact.fe.solver)", "rule": result.spec.rule})
        write_solution(out["vtu"], result.mesh, result.solution.final.u, interface_fields(result), out["points"])


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.run, sm.params.provenance, {"nc": sm.output.nc, "vtu": sm.output.vtu, "points": sm.output.points},
        sm.log[0])
