"""The figure of docs/fe-export.md: the law and the exported table's rows (a), and the table's
relative error against the law in every row interval with the requested rtol (b)."""

from __future__ import annotations

import numpy as np

from . import plots

__all__ = ["table_error_profile", "export_figure"]


def table_error_profile(table, n_per_row: int = 41):
    """Per row interval from the light end p_min on: (row index, largest relative error of the
    piecewise-linear table against the law, sampled at n_per_row points), and the fine curve
    (c [L], law p, table p) for drawing."""
    c, p = table.overclosure[1:], table.pressure[1:]
    t = np.linspace(0.0, 1.0, n_per_row)
    errors, cc, pl, pt = [], [], [], []
    for i in range(c.size - 1):
        ci = c[i] + (c[i + 1] - c[i]) * t
        law = table.law_pressure(ci)
        lin = p[i] + (p[i + 1] - p[i]) * t
        errors.append(float(np.max(np.abs(lin / law - 1.0))))
        cc.append(ci), pl.append(law), pt.append(lin)
    return np.arange(1, c.size), np.array(errors), (np.concatenate(cc), np.concatenate(pl), np.concatenate(pt))


def export_figure(tables, *, length_unit="µm", stress_unit="N/mm²"):
    """tables: {label: OverclosureTable}. Returns the two-panel Figure."""
    fig = plots.new_figure(figsize=(10.0, 4.2))
    ax1, ax2 = fig.subplots(1, 2)
    with plots.style():
        for k, (label, table) in enumerate(tables.items()):
            color = f"C{k}"
            rows, err, (c, law, _) = table_error_profile(table)
            ax1.semilogy(c, law, color=color, lw=1.2, label=f"{label}: law")
            ax1.semilogy(table.overclosure[1:], table.pressure[1:], "o", ms=2.2, color=color,
                         label=f"{label}: {table.n_rows} rows")
            ax2.semilogy(rows, err, ".", ms=3, color=color, label=label)
        rtol = {t.rtol for t in tables.values()}
        for r in rtol:
            ax2.axhline(r, color="k", lw=0.8, ls="--", label=f"rtol = {r:g}")
        ax1.set_xlabel(f"overclosure c [{length_unit}] (0 at the seating pressure)")
        ax1.set_ylabel(f"pressure [{stress_unit}]")
        ax1.set_title("(a) law and exported rows (the zero-pressure row is off the log axis)")
        ax1.legend(fontsize=7)
        ax2.set_xlabel("row interval (from the light end)")
        ax2.set_ylabel("max |table − law| / law in the interval")
        ax2.set_title("(b) error of the FE code's linear interpolation")
        ax2.legend(fontsize=7)
        fig.tight_layout()
    return fig
