"""Join the parts of a sweep (rule sweep_merge) into results/sweeps/<name>.nc."""

from roughcontact import io
from roughcontact.contact.sweep import combine


def run(name, cfg, parts, output, log):
    with io.log_to(log) as logger:
        pieces = [io.read_netcdf(p) for p in parts]
        ds = combine(pieces, cfg["split"]["axis"])  # attributes of the first part
        ds.attrs.pop("part", None)  # (write_netcdf replaces its provenance attributes)
        prov = io.read_provenance(pieces[0])
        logger.info("sweep %s: %s from %d parts", name, dict(ds.sizes), len(parts))
        io.write_netcdf(ds, output, config={"sweep": name, "sweep_config": cfg, "units": prov["config"]["units"]},
                        settings=prov["settings"])


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.name, sm.params.sweep_config, list(sm.input.parts), sm.output[0], sm.log[0])
