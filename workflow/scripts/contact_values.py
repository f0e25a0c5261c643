"""Contact values of one table scene and one model level (rules `reference`, `production`).

Thin: read the job from the rule's params (exactly what the numbers depend
on; it is also the provenance stored with them), call roughcontact.contact.elastic_contact at the
scene's separations, keep the scene's quantities, write netCDF with provenance.

The mpmath references of the anisotropic model (10–60 s per job) are deterministic: they come
from the committed seed of the benchmark references (benchmarks/data/references.json, through
benchmarks/references.ReferenceCache, key = the whole job) when the record was computed by the
same reference code (the seed's fingerprint hashes every module the integrator runs through),
and are computed otherwise; the netCDF's ``reference_source`` says which. After a change to the
reference integrators, refresh the seed from a workflow run's results:

    .venv/bin/python workflow/scripts/contact_values.py --update-seed results/reference/dps20
"""

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "benchmarks"))

import references as refs  # noqa: E402

from roughcontact import SpectralMoments, io  # noqa: E402
from roughcontact.contact import elastic_contact  # noqa: E402
from roughcontact.contact.elastic import ContactCurves  # noqa: E402


def seed_key(job) -> str:
    return "contact_reference|" + io.canonical_json(job)


def _seeded(job) -> bool:
    """The anisotropic model's mpmath references go through the seed (GW's take ~1 s)."""
    return job["method"] == "reference" and job["model"] == "bgk"


def _compute(job, surface):
    return elastic_contact(
        surface,
        job["s"],
        job["E_star"],
        model=job["model"],
        hertz=job["hertz"],
        method=job["method"],
        **{k: job[k] for k in ("accuracy", "dps") if k in job},
    )


def _curves(job, surface):
    """(ContactCurves, where the values came from)."""
    if not _seeded(job):
        return _compute(job, surface), "computed"

    def columns():
        curves = _compute(job, surface)
        return [getattr(curves, q).tolist() for q in job["quantities"]]

    with tempfile.TemporaryDirectory() as tmp:
        cache = refs.ReferenceCache(Path(tmp) / "reference.json", seed=refs.SEED)
        values = cache.get(seed_key(job), columns)
        source = (f"seed {refs.SEED.relative_to(REPO)} (computed {cache.seeded[seed_key(job)]} by the same "
                  f"reference code, fingerprint {cache.fingerprint})" if cache.seeded else "computed")
    nan = np.full(len(job["s"]), np.nan)  # fields the job does not keep
    fields = {q: np.asarray(v, dtype=float) for q, v in zip(job["quantities"], values)}
    return ContactCurves(s=np.asarray(job["s"], dtype=float), model=job["model"], hertz=job["hertz"],
                         method=job["method"], E_star=float(job["E_star"]), surface=surface,
                         **{q: fields.get(q, nan) for q in ("area_fraction", "pressure", "stiffness")}), source


def run(job, output, log):
    with io.log_to(log) as logger:
        logger.info("job %s", io.canonical_json(job))
        surface = SpectralMoments(**job["surface"])
        t0 = time.perf_counter()
        curves, source = _curves(job, surface)
        logger.info("computed in %.2f s (%s)", time.perf_counter() - t0, source)
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
            reference_source=source,
        )
        for q in job["quantities"]:
            logger.info("%s = %s", q, ds[q].values.tolist())
        settings = {k: job[k] for k in ("method", "accuracy", "dps", "model", "hertz") if k in job}
        io.write_netcdf(ds, output, config=job, settings=settings)


def update_seed(results_dir) -> int:
    """Merge the anisotropic references of a workflow run (their netCDFs under ``results_dir``:
    job in the provenance, values) into the seed; only files written by today's reference code
    (their ``reference_source`` says computed) are taken."""
    import json

    import xarray as xr

    with tempfile.TemporaryDirectory() as tmp:
        cache = refs.ReferenceCache(Path(tmp) / "reference.json")
        for path in sorted(Path(results_dir).glob("*/*.nc")):
            with xr.open_dataset(path) as ds:
                job = json.loads(ds.attrs["config_json"])
                if _seeded(job) and ds.attrs.get("reference_source", "computed") == "computed":
                    cache.get(seed_key(job), lambda: [ds[q].values.tolist() for q in job["quantities"]])
        return cache.update_seed()


if "snakemake" in globals():
    run(snakemake.params.job, snakemake.output[0], snakemake.log[0])  # noqa: F821
elif __name__ == "__main__" and sys.argv[1:2] == ["--update-seed"]:
    print(f"{update_seed(sys.argv[2])} references written to {refs.SEED}")
