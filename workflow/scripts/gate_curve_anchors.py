"""The elasto-plastic curves and sweeps at their sample points against the slow twins (rule
curve_anchors): results/verify/curve_anchors.checks.csv."""

import json
from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import gate_anchors, verify


def run(twins, files, tolerance, expected, out, log):
    with io.log_to(log) as logger:
        points, values, data = [], [], {}
        for path in twins:
            record = json.loads(Path(path).read_text())
            points += [gate_anchors.TwinPoint(**p) for p in record["points"]]
            values += record["values"]
            twin_rtol, dps = record["twin_rtol"], record["dps"]
        for name, path in files.items():
            data[name] = io.read_netcdf(path)
        checks = gate_anchors.curve_anchor_checks(points, values, data, files, tolerance, twin_rtol, dps)
        checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        io.write_text(out, verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(list(sm.input.twins), sm.params.files, sm.params.tolerance, sm.input.expected, sm.output.checks, sm.log[0])
