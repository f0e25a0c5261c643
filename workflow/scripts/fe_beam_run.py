"""The runs of one case and element family of example 9.1 (rule fe_beam_case): each solved by
roughcontact.examples.beam.run_beam (the beam's deck and law through the deck reader) and
written as <variant>.nc (with provenance), <variant>.vtu and <variant>_interface.vtu in the
job's directory."""

import logging
from pathlib import Path

from roughcontact import io
from roughcontact.examples.beam import run_beam


def run(runs, provenance, out_dir, log):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with io.log_to(log) as logger:
        for variant, run_cfg in runs.items():
            def progress(k, n, inc):
                logger.info("%s: increment %d/%d: load %.6g N, %d Newton iterations, %d cut-backs, %.2f s",
                            variant, k, n, inc.level, inc.iterations, inc.cutbacks, inc.seconds)

            result = run_beam(run_cfg, progress=progress)
            logging.getLogger(io.PROGRESS).info("%s: u_N centre %+.5f um, end %+.5f um; %d dofs, %d interface points, %.2f s, "
                        "equilibrium %.1e", variant, result.u_N_centre_um, result.u_N_end_um, result.n_dofs,
                        result.n_points, result.seconds, result.equilibrium_error)
            io.write_netcdf(result.to_dataset(), out / f"{variant}.nc", config={**provenance, "variant": variant},
                            settings={"solver": "Newton (roughcontact.fe.solver)", "rule": "lobatto"})
            result.write_vtu(out / f"{variant}.vtu")


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.runs, sm.params.provenance, sm.output[0], sm.log[0])
