"""The runs of one element family and reading of example 9.2 (rule fe_punch_case): each solved by
roughcontact.examples.punch.run_punch (the punch's deck and law through the deck reader) and
written as <case>.nc (the whole load history, with provenance), <case>.vtu and
<case>_interface.vtu (the maximum load) in the job's directory. The dataset carries the tangential
stiffnesses of every point and level besides (roughcontact.paper.fe_anchors.stiffness_fields), for
the energy balance of the anchor."""

import logging
from pathlib import Path

from roughcontact import io
from roughcontact.examples.punch import run_punch, to_dataset
from roughcontact.paper.fe_anchors import stiffness_fields


def run(runs, provenance, out_dir, log):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    group = provenance["group"]
    with io.log_to(log) as logger:
        for name, run_cfg in runs.items():
            case = name[len(group) + 1:]

            def progress(k, n, inc):
                logger.info("%s: level %d/%d: patch load %.6g N (quarter), %d Newton iterations, %d cut-backs",
                            case, k, n, inc.level, inc.iterations, inc.cutbacks)

            result = run_punch(run_cfg, progress=progress)
            ds = to_dataset(result)
            # k_T per level and point: the punch anchor's energy balance rebuilds the slips from them
            variables, attrs = stiffness_fields(result)
            ds = ds.assign(variables)
            ds.attrs.update(attrs)
            logging.getLogger(io.PROGRESS).info("%s: D %.5g N mm, %d slipped points, %d dofs, %d contact points, %.2f s", case,
                        ds.attrs["D_max_area_whole"], ds.attrs["slipped_points"], result.n_dofs, result.n_points,
                        result.seconds)
            io.write_netcdf(ds, out / f"{case}.nc", config={**provenance, "run": name},
                            settings={"solver": "Newton (roughcontact.fe.solver)", "rule": "lobatto"})
            result.write_vtu(out / f"{case}.vtu")


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.runs, sm.params.provenance, sm.output[0], sm.log[0])
