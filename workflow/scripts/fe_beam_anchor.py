"""The beam's anchor checks (rule fe_beam_anchor): the anchored runs against the 2D plane-stress
solutions; paper_figures/fe_beam_anchor.md and results/verify/fe_beam_anchor.checks.csv."""

from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import fe_anchors, report, verify


def run(paths, runs, cfg, reference, expected, out, log):
    with io.log_to(log) as logger:
        data = {name: io.read_netcdf(path) for name, path in paths.items()}
        ref_ds = io.read_netcdf(reference)
        ref = {str(key): {"x_mm": ref_ds["x"].values, "u_N_um": ref_ds["u_N_um"].values[i],
                          "error_centre_um": float(ref_ds["error_centre_um"].values[i]),
                          "error_end_um": float(ref_ds["error_end_um"].values[i])}
               for i, key in enumerate(ref_ds["law"].values)}
        checks = fe_anchors.beam_anchor_checks(runs, data, ref, cfg["tolerances"])
        checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        mesh = "×".join(map(str, cfg["plane_stress"]["mesh"]))
        rows = [{"law": str(key), "mesh": f"{mesh} Q9", **{k: float(ref_ds[k].values[i]) for k in (
            "u_N_centre_um", "u_N_end_um", "error_centre_um", "error_end_um", "seconds")},
                 "dofs": int(ref_ds["dofs"].values[i])} for i, key in enumerate(ref_ds["law"].values)]
        shown = report.shown_provenance(io.read_provenance(next(iter(data.values()))))
        io.write_text(out["md"], fe_anchors.render_markdown(
            "Example 9.1 against a 2D plane-stress solution by a separate code", checks, rows, shown))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.paths, sm.params.runs, sm.params.cfg, sm.input.reference, sm.input.expected,
        {"md": sm.output.md, "checks": sm.output.checks}, sm.log[0])
