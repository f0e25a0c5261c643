"""The interface law inside CalculiX against the engine (rule ccx_friction; issue 30):
paper_figures/ccx_friction.md/.csv and results/verify/ccx_friction.checks.csv. An optional scene:
without a ccx built with the law (`roughcontact ccx build`, `make ccx-build`) it writes every
declared output all the same — no checks, the work directory holding only a note of why — and
VERIFICATION.md, the gate and the gallery report it as skipped."""

from pathlib import Path

from roughcontact import io
from roughcontact.ccx.build import find_build
from roughcontact.paper import ccx_friction, report, verify


def run(cfg, workdir, out, log):
    with io.log_to(log) as logger:
        build = find_build()
        if build is None:
            why = ccx_friction.skipped_line()
            logger.info("no ccx with the interface law: %s", why)
            Path(workdir).mkdir(parents=True, exist_ok=True)  # every declared output, the directory() too
            io.write_text(Path(workdir) / "SKIPPED.txt", why.replace("`", "") + "\n")
            io.write_text(out["md"], ccx_friction.render_markdown([], [], {}, {}, skipped_reason=why))
            io.write_text(out["csv"], "")
            io.write_text(out["checks"], verify.checks_to_csv([]))
            return
        rows, checks, timings = ccx_friction.run_scene(cfg, workdir, build.executable, progress=logger.info)
        for c in checks:
            logger.info("%s: %s %s", c.id, c.verdict, c.detail)
        io.write_text(out["md"], ccx_friction.render_markdown(rows, checks, timings, build.info))
        flat = [{k: (" ".join(f"{x:.7g}" for x in v) if isinstance(v, list) else v) for k, v in r.items()} for r in rows]
        keys = list(dict.fromkeys(k for r in flat for k in r))
        io.write_text(out["csv"], report.render_rows_csv([{k: r.get(k, "") for k in keys} for r in flat]))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.cfg, sm.output.workdir, {"md": sm.output.md, "csv": sm.output.csv, "checks": sm.output.checks},
        sm.log[0])
