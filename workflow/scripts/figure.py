"""Plot a figure scene (PNG), export its data (CSV), check its prose claims."""

import csv
import io as _io
from pathlib import Path

import yaml

from roughcontact import io, plots, verify


def _csv(header, columns):
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for row in zip(*columns):
        w.writerow([repr(float(x)) for x in row])
    return buf.getvalue()


def bearing_ratio(scene, cfg, ds):
    s = ds["s"].values
    labels = [str(x) for x in ds["label"].values]
    ratios = {lab: ds["bearing_area_ratio"].values[i] for i, lab in enumerate(labels)}
    markers = {c["label"]: c.get("marker") for c in cfg["curves"]}
    fig = plots.fig3(s, ratios, markers=markers)
    header = ["s"] + [f"AG_over_AB[{name}]" for name in ds["surface"].values]
    data = _csv(header, [s, *ratios.values()])
    checks = [verify.claim_check(scene, claim, s, ratios, x_name="s") for claim in cfg["claims"]]
    return fig, data, checks


def hertz_factors(scene, cfg, ds):
    e = ds["e"].values
    hertz = [str(h) for h in ds["hertz"].values]
    curves = {f"hertz={h}": (ds["f1"].values[i], ds["f2"].values[i]) for i, h in enumerate(hertz)}
    fig = plots.fig4(e, curves)
    header, columns = ["e"], [e]
    for i, h in enumerate(hertz):
        header += [f"f1[{h}]", f"f2[{h}]"]
        columns += [ds["f1"].values[i], ds["f2"].values[i]]
    checks = []
    for claim in cfg["claims"]:
        i = hertz.index(claim.get("hertz", hertz[0]))
        checks.append(verify.claim_check(scene, claim, e, {"f1": ds["f1"].values[i], "f2": ds["f2"].values[i]}, x_name="e"))
    return fig, _csv(header, columns), checks


def run(scene, cfg, data, expected, out, log):
    with io.log_to(log) as logger:
        ds = io.read_netcdf(data)
        make = {"bearing_ratio": bearing_ratio, "hertz_factors": hertz_factors}[cfg["kind"]]
        fig, table, checks = make(scene, cfg, ds)
        checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        plots.save(fig, out["png"])
        io.write_text(out["csv"], table)
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.input.data, sm.input.expected,
        {"png": sm.output.png, "csv": sm.output.csv, "checks": sm.output.checks}, sm.log[0])
