"""The punch's anchor checks (rule fe_punch_anchor): every run's equilibrium, friction limit,
dissipation, frictionless bound and energy balance from its written fields; paper_figures/fe_punch_anchor.md and
results/verify/fe_punch_anchor.checks.csv."""

from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import fe_anchors, fe_punch, report, verify


def run(paths, runs, cfg, d_attr, expected, out, log):
    with io.log_to(log) as logger:
        data = {name: io.read_netcdf(path) for name, path in paths.items()}
        bounds = fe_punch.run_bounds(data, runs)
        # the quarter punch's top face [mm²] (input data: the run's geometry)
        area = {name: r.spec.geometry.punch_half_width ** 2 for name, r in runs.items()}
        checks = fe_anchors.punch_anchor_checks(runs, data, bounds, area, cfg["tolerances"], d_attr)
        checks += fe_anchors.punch_energy_checks(runs, data, cfg["tolerances"]["energy"])
        checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        shown = report.shown_provenance(io.read_provenance(next(iter(data.values()))))
        io.write_text(out["md"], fe_anchors.render_markdown(
            "Example 9.2 against its equilibrium, friction limit, dissipation and frictionless bound", checks, [], shown))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.paths, sm.params.runs, sm.params.cfg, sm.params.d_attr, sm.input.expected,
        {"md": sm.output.md, "checks": sm.output.checks}, sm.log[0])
