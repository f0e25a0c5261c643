"""Every published CSV against the files it was written from (rule published_csv): each re-derived
by its writer's own function from the same result files, compared cell by cell
(roughcontact.paper.gate_anchors.csv_cell_check); results/verify/published_csv.checks.csv."""

import importlib.util
from pathlib import Path

from roughcontact import io
from roughcontact.paper import gate_anchors, report, verify

SCRIPTS = Path(__file__).resolve().parent


def _writer(name):
    """A workflow script as a module (its functions; the script part runs only under Snakemake)."""
    spec = importlib.util.spec_from_file_location(f"_writer_{name}", SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def derive(job, cache):
    """The CSV text the job's writer makes from its result files (``cache``: writers that make two
    CSVs at once, e.g. Table 5 and the readings, run once)."""
    kind = job["kind"]
    if kind == "table":
        checks, _, _ = _writer("table").derive(job["scene"], job["scene_config"], job["models"], job["numerics_rtol"],
                                               job["reference_dps"], job["production"], job["reference"],
                                               job["paper"], job["expected"])
        return report.render_table_csv(checks, job["models"])
    if kind == "figure":
        return _writer("figure").csv_text(job["scene"], job["scene_config"], io.read_netcdf(job["data"]))
    if kind == "numerics":
        writer = _writer("numerics_report")
        return writer.csv_text(writer.read(job["data"]))
    if kind == "fe_table4":
        return _writer(kind).csv_text(job["paths"], job["runs"], job["cfg"], job["paper"], job["expected"])
    if kind == "fe_table5":
        if kind not in cache:
            cache[kind] = _writer(kind).csv_texts(job["paths"], job["runs"], job["cfg"], job["paper"], job["expected"])
        return cache[kind][job["part"]]
    if kind == "fe_fig13":
        return _writer(kind).csv_text(job["paths"], job["runs"], job["paper"])
    if kind == "fe_beam_study":
        return _writer(kind).csv_text(job["paths"], job["runs"])
    if kind == "fe_punch_slips":
        return _writer(kind).csv_text(job["family"], job["readings"], job["paths"])
    if kind == "fe_export":
        return _writer("fe_export_figure").csv_text(job["cfg"], job["beam_cfg"])
    if kind == "drawing":
        return _writer(kind).csv_text(job["element"])
    if kind == "geometry":
        return _writer("geometry_figure").csv_text(job["name"], job["cfg"], job["surface"], job["length"])
    raise ValueError(f"no writer for a published CSV of kind {kind!r}")


def run(jobs, tolerance, expected, out, log):
    import yaml

    with io.log_to(log) as logger:
        checks, cache = [], {}
        for name, job in jobs.items():
            checks.append(gate_anchors.csv_cell_check(name, Path(name).read_text(encoding="utf-8"), derive(job, cache),
                                                      tolerance))
        checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        io.write_text(out, verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.jobs, sm.params.tolerance, sm.input.expected, sm.output.checks, sm.log[0])
