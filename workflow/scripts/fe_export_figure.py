"""The figure of docs/fe-export.md (rule fe_export_figure): the beam's three elastic surfaces
exported as in the CalculiX scene; PNG and the per-row errors as CSV."""

from roughcontact import io
from roughcontact.examples.beam import BeamSpec
from roughcontact.interface.export import overclosure_table
from roughcontact.paper import export_figure, plots, report
from roughcontact.statistics import SpectralMoments


def tables_and_rows(cfg, beam_cfg, logger=None):
    """({label: exported table}, CSV rows of the per-row errors) of the beam's elastic surfaces."""
    p0 = BeamSpec(**beam_cfg["spec"]).seating_pressure
    tables, rows = {}, []
    for case in cfg["cases"]:
        m00 = beam_cfg["cases"][case]["m00"]
        surface = SpectralMoments(m00=m00, **beam_cfg["surface"])
        table = overclosure_table(surface, pressure_range=tuple(cfg["pressure_range"]), E_star=beam_cfg["E_star"],
                                  rtol=cfg["rtol"], reference="seating", seating_pressure=p0)
        tables[f"m00 = {m00:g} µm²"] = table
        idx, err, _ = export_figure.table_error_profile(table)
        rows += [{"m00_um2": m00, "row_interval": int(i), "overclosure_um": float(table.overclosure[i]),
                  "pressure_N_per_mm2": float(table.pressure[i]), "max_rel_error": float(e)} for i, e in zip(idx, err)]
        if logger is not None:
            logger.info("m00 = %g: %d rows, max error %.3g", m00, table.n_rows, err.max())
    return tables, rows


def csv_text(cfg, beam_cfg):
    """paper_figures/fe_export.csv (what run writes), without drawing."""
    return report.render_rows_csv(tables_and_rows(cfg, beam_cfg)[1])


def run(cfg, beam_cfg, out, log):
    with io.log_to(log) as logger:
        tables, rows = tables_and_rows(cfg, beam_cfg, logger)
        plots.save(export_figure.export_figure(tables), out["png"])
        io.write_text(out["csv"], report.render_rows_csv(rows))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.cfg, sm.params.beam_cfg, {"png": sm.output.png, "csv": sm.output.csv}, sm.log[0])
