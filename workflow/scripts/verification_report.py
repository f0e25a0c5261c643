"""paper_figures/VERIFICATION.md, verification.csv and results/verify/summary.json."""

import json
from pathlib import Path

import yaml

from roughcontact import __version__, io
from roughcontact.paper import ccx_friction as ccx_friction_scene
from roughcontact.paper import gate_anchors, report, verify


def _speed_section(path):
    """The benchmark report fragment without its title (this section's heading replaces it),
    its other headings pushed one level down."""
    lines = [line for line in Path(path).read_text().splitlines() if not line.startswith("# ")]
    body = "\n".join(("#" + line) if line.startswith("#") else line for line in lines)
    return (
        "Measured by `snakemake speed_vs_error` (benchmarks/speed_vs_error.py; `make bench` for the "
        "full mode; docs/performance.md explains the integrators and the profile).\n\n" + body.strip() + "\n"
    )


def _fe_section(path):
    """The FE speed-and-size report's job table and summary (the per-run table stays in its file)."""
    lines = Path(path).read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("| job"))
    return ("Measured by the workflow's FE jobs (`snakemake fe_beam fe_punch`; every run's dofs, interface points, "
            "Newton iterations and solve time in [fe_benchmark.md](fe_benchmark.md)).\n\n"
            + "\n".join(lines[start:]).strip() + "\n")


def _calculix_section(path):
    """paper_figures/calculix.md without its title: the comparison, or "Skipped" without ccx."""
    lines = [line for line in Path(path).read_text().splitlines() if not line.startswith("# ")]
    return "\n".join(("#" + line) if line.startswith("#") else line for line in lines).strip() + "\n"


def _bem_section(files):
    """paper_figures/bem.md without its title, or how to compute it (target bem, not in all)."""
    if not files:
        return ("Not computed in this run: `snakemake bem` (needs the extra `[bem]`, "
                "`pip install '.[bem]'`; about 20 min on 2 cores) compares the model with a boundary-element "
                "solution on surfaces with the same moments and states here where the model holds: the area, "
                "the law an FE model uses (gap and stiffness against the grid-converged BEM) and, with a "
                "hardness cap, the elasto-plastic model.\n")
    return _calculix_section(files[0])


def run(checks_files, speed, fe_speed, calculix, expected, errata, scene_titles, reference_dps, out, log, bem=(),
        ccx_friction=None):
    with io.log_to(log) as logger:
        checks = []
        for path in list(checks_files) + [f for f in bem if f.endswith(".csv")]:
            checks += verify.checks_from_csv(Path(path).read_text())
        expectations = yaml.safe_load(Path(expected).read_text())
        checks = verify.apply_expectations(checks, expectations)
        # optional scenes (CalculiX; the ccx built with the law) count only where their tool is installed
        tools = ccx_friction_scene.installed_tools(expectations)
        coverage = verify.check_coverage(checks, expectations, tools)
        errata_list = report.parse_errata(Path(errata[0]).read_text()) if errata else []
        provenance = {
            "roughcontact": __version__,
            "commit": io.git_commit()[:12],
            "reference dps": reference_dps,
        }
        summary = verify.summarize(checks, coverage)
        summary["regression_details"] = gate_anchors.regression_details(checks)  # printed by the gate
        summary["provenance"] = provenance
        logger.info("summary: %s", json.dumps({k: v for k, v in summary.items() if k != "by_kind"}))
        io.write_text(out["md"], report.render_verification_markdown(
            checks, errata=errata_list, provenance=provenance, scene_titles=scene_titles,
            sections={"Speed against error": _speed_section(speed), "FE speed and size": _fe_section(fe_speed),
                      "CalculiX cross-check (optional scene calculix, tool ccx)": _calculix_section(calculix),
                      "The full law inside CalculiX (optional scene ccx_friction, `make ccx-build`)":
                          _calculix_section(ccx_friction) if ccx_friction else "",
                      "Where the model and its law hold: the BEM comparison (optional target bem)":
                          _bem_section([f for f in bem if f.endswith(".md")])},
            summary=summary))
        io.write_text(out["csv"], verify.checks_to_csv(checks))
        io.write_text(out["summary"], json.dumps(summary, indent=2, sort_keys=True) + "\n")


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(list(sm.input.checks), sm.input.speed, sm.input.fe_speed, sm.input.calculix, sm.input.expected, list(sm.input.errata), sm.params.scene_titles,
        sm.params.reference_dps, {"md": sm.output.md, "csv": sm.output.csv, "summary": sm.output.summary},
        sm.log[0], list(sm.params.bem), sm.input.ccx_friction)
