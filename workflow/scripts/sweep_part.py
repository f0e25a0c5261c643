"""One part of a parameter sweep (rule sweep_part): split the configured sweep, evaluate the
part, write netCDF with provenance. Progress goes to the rule's log and the console."""

import logging
import time

from roughcontact import io
from roughcontact.contact.sweep import run_sweep, spec_from_config, split


def run(name, part, cfg, units, output, log):
    with io.log_to(log) as logger:
        spec = split(spec_from_config(cfg, units), cfg["split"]["axis"], cfg["split"]["jobs"])[part]
        logger.info("sweep %s part %d: axes %s, %d points", name, part,
                    {k: v.tolist() for k, v in spec.axes.items()}, spec.points)
        t0 = time.perf_counter()

        console = logging.getLogger(io.PROGRESS)

        def progress(done, total):
            console.info("sweep %s part %d: %d/%d combinations, %.1f s", name, part, done, total,
                         time.perf_counter() - t0)

        ds = run_sweep(spec, progress=progress)
        ds.attrs.update(sweep=name, part=part)
        io.write_netcdf(ds, output, config={"sweep": name, "part": part, "sweep_config": cfg, "units": units},
                        settings={"method": "production", "accuracy": spec.accuracy, "hertz": spec.hertz})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.name, sm.params.part, sm.params.sweep_config, sm.params.units, sm.output[0], sm.log[0])
