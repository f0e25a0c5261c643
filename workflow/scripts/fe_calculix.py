"""The exported table checked in CalculiX (rule fe_calculix): the block, the beam, and one deck in
both codes (a block on a base, refined); paper_figures/calculix.md/.csv and
results/verify/calculix.checks.csv. An optional scene: without ccx it writes every declared
output all the same — no checks, the work directory holding only a note of why — and
VERIFICATION.md, the gate and the gallery report it as skipped."""

from pathlib import Path

from roughcontact import io
from roughcontact.paper import calculix, calculix_deck, report, verify


def run(cfg, beam_cfg, paths, workdir, out, log):
    with io.log_to(log) as logger:
        exe = calculix.ccx_executable()
        if exe is None:
            why = calculix.skipped_line()
            logger.info("ccx not found on PATH: %s", why)
            # every declared output, also the directory(): Snakemake fails a job that lacks one
            Path(workdir).mkdir(parents=True, exist_ok=True)
            io.write_text(Path(workdir) / "SKIPPED.txt", why.replace("`", "") + "\n")
            io.write_text(out["md"], calculix.render_markdown([], [], {}, "", skipped_reason=why))
            io.write_text(out["csv"], "")
            io.write_text(out["checks"], verify.checks_to_csv([]))
            return
        engine = {}
        for case, path in paths.items():
            ds = io.read_netcdf(path)
            engine[case] = (ds["point_x"].values, ds["point_y"].values, ds["point_u_N_um"].values)
        rows, checks, timings = calculix.run_scene(cfg, beam_cfg, engine, workdir, exe=exe, progress=logger.info)
        deck_rows, deck_checks, deck_timings = calculix_deck.deck_scene(cfg, workdir, exe=exe, progress=logger.info)
        rows, checks, timings = rows + deck_rows, checks + deck_checks, {**timings, **deck_timings}
        for c in checks:
            logger.info("%s: %s %s", c.id, c.verdict, c.detail)
        md = calculix.render_markdown(rows, checks, timings, calculix.ccx_version(exe))
        io.write_text(out["md"], md + "\n".join(calculix_deck.render_deck_markdown(deck_rows)) + "\n")
        keys = list(dict.fromkeys(k for r in rows for k in r))  # block and beam rows: one header
        io.write_text(out["csv"], report.render_rows_csv([{k: r.get(k, "") for k in keys} for r in rows]))
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.cfg, sm.params.beam_cfg, sm.params.paths, sm.output.workdir,
        {"md": sm.output.md, "csv": sm.output.csv, "checks": sm.output.checks}, sm.log[0])
