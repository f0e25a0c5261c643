"""One paper table: compare production values with the printed ones and with the mpmath
reference; write paper_figures/<scene>.md/.csv and results/verify/<scene>.checks.csv."""

from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import report, verify


def _values(paths):
    """{model name: {quantity: values}} from the scene's netCDF files (file name = model)."""
    out = {}
    for path in paths:
        ds = io.read_netcdf(path)
        out[Path(path).stem] = {name: ds[name].values for name in ds.data_vars}
        out[Path(path).stem]["_provenance"] = io.read_provenance(ds)
    return out


def derive(scene, scene_config, models, numerics_rtol, reference_dps, production, reference, paper, expected):
    """(checks with their expectations, provenance shown) of one table scene from its result
    files (what run writes; the published-CSV anchor re-derives the CSV with it)."""
    paper_table = yaml.safe_load(Path(paper).read_text())[scene]
    # the scene's row values (its s, or its reading of the printed labels) match the rows
    key = paper_table.get("row_key", "s")
    configured = [float(x) for x in scene_config[key]]
    printed_rows = paper_table["rows"]
    if len(configured) != len(printed_rows) or (key == "s" and configured != [float(x) for x in printed_rows]):
        raise ValueError(f"{scene}: configured {key} {configured} do not match the printed rows {printed_rows}")
    prod = _values(production)
    ref = _values(reference) if reference else {}
    provenance = next(iter(prod.values()))["_provenance"]
    for d in (prod, ref):
        for v in d.values():
            v.pop("_provenance")
    quantities = scene_config["quantities"]
    checks = verify.table_cell_checks(
        scene, paper_table, prod, models, scene_config["tolerances"], quantities
    )
    if ref:
        checks += verify.numerics_checks(
            scene, paper_table["rows"], prod, ref, numerics_rtol, quantities, reference_dps,
            paper_table.get("row_key", "s"),
        )
    checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
    shown = {**report.shown_provenance(provenance), "reference dps": reference_dps if ref else "none"}
    return checks, paper_table, shown


def run(scene, scene_config, models, numerics_rtol, reference_dps, production, reference, paper, expected, out, log):
    with io.log_to(log) as logger:
        checks, paper_table, shown = derive(scene, scene_config, models, numerics_rtol, reference_dps, production,
                                            reference, paper, expected)
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        io.write_text(out["md"], report.render_table_markdown(scene_config["title"], checks, paper_table, models, provenance=shown))
        io.write_text(out["csv"], report.render_table_csv(checks, models))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(
        sm.params.scene,
        sm.params.scene_config,
        sm.params.models,
        sm.params.numerics_rtol,
        sm.params.reference_dps,
        list(sm.input.production),
        list(sm.input.reference) if hasattr(sm.input, "reference") else [],
        sm.input.paper,
        sm.input.expected,
        {"md": sm.output.md, "csv": sm.output.csv, "checks": sm.output.checks},
        sm.log[0],
    )
