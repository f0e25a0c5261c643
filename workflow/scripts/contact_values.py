"""Contact values of one table scene and one model level (rules `reference`, `production`).

Thin: read the job from the rule's params (exactly what the numbers depend
on; it is also the provenance stored with them), call roughcontact.contact.elastic_contact at the
scene's separations, keep the scene's quantities, write netCDF with provenance.
"""

import time

from roughcontact import SpectralMoments, io
from roughcontact.contact import elastic_contact


def run(job, output, log):
    with io.log_to(log) as logger:
        logger.info("job %s", io.canonical_json(job))
        surface = SpectralMoments(**job["surface"])
        t0 = time.perf_counter()
        curves = elastic_contact(
            surface,
            job["s"],
            job["E_star"],
            model=job["model"],
            hertz=job["hertz"],
            method=job["method"],
            **{k: job[k] for k in ("accuracy", "dps") if k in job},
        )
        logger.info("computed in %.2f s", time.perf_counter() - t0)
        # the scene's unit system (config `units`) makes the library's units concrete
        length, stress = job["units"]["length"], job["units"]["stress"]
        ds = curves.to_dataset(units=job["units"])[job["quantities"]]
        ds.attrs.update(
            scene=job["scene"],
            model_name=job["model_name"],
            model_level=job["level"],
            surface_name=job["surface_name"],
            E_star_units=stress,
            length_units=length,
        )
        for q in job["quantities"]:
            logger.info("%s = %s", q, ds[q].values.tolist())
        settings = {k: job[k] for k in ("method", "accuracy", "dps", "model", "hertz") if k in job}
        io.write_netcdf(ds, output, config=job, settings=settings)


if "snakemake" in globals():
    run(snakemake.params.job, snakemake.output[0], snakemake.log[0])  # noqa: F821
