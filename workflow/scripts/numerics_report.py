"""Numerics rows of a numerics scene (rule numerics_report): checks CSV and the data as CSV."""

from roughcontact import io
from roughcontact.paper import claims, verify


def read(data):
    """The scene's points in one dataset (the point files in order)."""
    import xarray as xr

    return xr.concat([io.read_netcdf(path) for path in data], dim="point", combine_attrs="override")


def csv_text(ds):
    """The published CSV: production and reference of every column at every point, units in the header."""
    names = [f"{m}_{c}" for c in ds.attrs["columns"].split() for m in ("production", "reference")]
    table = ds[names].to_dataframe().reset_index()
    table = table.rename(columns={n: f"{n} [{ds[n].attrs['units']}]" for n in names})  # units in the header
    return table.to_csv(index=False, float_format="%.17g")


def run(scene, cfg, data, out, log):
    with io.log_to(log) as logger:
        ds = read(data)
        checks = claims.elastoplastic_numerics_checks(scene, ds, float(cfg["rtol"]), " ".join(cfg["why"].split()))
        for c in checks:
            logger.info("%s: %s %s", c.id, c.verdict, c.detail)
        io.write_text(out["csv"], csv_text(ds))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, list(sm.input.data), {"csv": sm.output.csv, "checks": sm.output.checks},
        sm.log[0])
