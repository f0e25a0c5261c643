"""Figures of contact results, in the project's one style (:mod:`.style`, which the paper's figures
use too): what a researcher would publish from ``roughcontact elastic/elastoplastic ... --json`` and
``roughcontact moments ... --json``.

* :func:`contact_curves` — A/A0, W/A0, K_N/A0 and k_Tx, k_Ty (per unit nominal area) against the
  separation s = h/√m00 or against the nominal pressure, several results overlaid;
* :func:`moments_against_scale` — m20, m02, m40, m04 against the sampling interval (1×, 2×, 4×),
  with their standard uncertainties;
* :func:`save_figure` — one file, PNG or PDF (or SVG) by its suffix, without creation dates.

matplotlib comes with the ``workflow`` extra; without it every function here raises ImportError
with one line saying how to install it (the library itself needs no matplotlib).
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

from .style import axis_label, color, legend_outside, new_figure, note, require_matplotlib, save, save_figure
from .style import style as _styled  # not re-exported: roughcontact.plots.style is the module

__all__ = ["contact_curves", "moments_against_scale", "save_figure", "save", "new_figure", "require_matplotlib"]

#: what contact_curves can draw: key of the result -> (axis label, unit kind)
QUANTITIES = {
    "area_fraction": ("real contact area $A/A_0$", None),
    "pressure": ("nominal pressure $W/A_0$", "stress"),
    "stiffness": ("normal stiffness $K_N/A_0$", "stiffness"),
    "tangential": ("tangential stiffness $k_T/A_0$", "stiffness"),
}
XS = ("separation", "pressure")


def _unit(kind, length, stress):
    if kind == "stress":
        return stress
    if kind == "stiffness":
        return f"{stress}/{length}" if stress and length else None
    return None


def contact_curves(results: Sequence[Mapping], *, labels: Sequence[str] | None = None, x: str = "separation",
                   quantities: Sequence[str] = ("area_fraction", "pressure", "stiffness", "tangential"),
                   length_unit: str | None = None, stress_unit: str | None = None):
    """A/A0, W/A0, K_N/A0 and k_T/A0 of one or more contact results against the separation s (or the
    nominal pressure, ``x="pressure"``: then the W/A0 panel is left out), one panel per quantity,
    log scales for the quantities that span decades. ``results``: mappings with the lists ``s``,
    ``area_fraction``, ``pressure``, ``stiffness`` (and ``k_Tx``, ``k_Ty`` for "tangential"), as the
    command line's JSON has them. Units label the axes (UDUNITS, e.g. "um", "N/mm^2"); None: the
    axes say "unit of E*" / "L"."""
    require_matplotlib()
    if x not in XS:
        raise ValueError(f"x must be one of {', '.join(XS)}; got {x!r}")
    if not results:
        raise ValueError("no result to plot")
    unknown = [q for q in quantities if q not in QUANTITIES]
    if unknown:
        raise ValueError(f"unknown quantities {unknown}: use {', '.join(QUANTITIES)}")
    panels = [q for q in quantities if not (x == "pressure" and q == "pressure")]
    if "tangential" in panels and not any("k_Tx" in r for r in results):
        panels.remove("tangential")
    labels = list(labels) if labels is not None else [f"result {i + 1}" for i in range(len(results))]
    if len(labels) != len(results):
        raise ValueError(f"{len(labels)} labels for {len(results)} results")
    length, stress = length_unit or "L", stress_unit or "unit of E*"
    with _styled():
        fig = new_figure(figsize=(4.2 * min(len(panels), 2) + 1.8, 3.4 * ((len(panels) + 1) // 2)))
        axes = [fig.add_subplot((len(panels) + 1) // 2, min(len(panels), 2), i + 1) for i in range(len(panels))]
        for i, (r, label) in enumerate(zip(results, labels)):
            xs = np.asarray(r["s"] if x == "separation" else r["pressure"], dtype=float)
            # overlaid results stay visible where they coincide: own colour, marker and line style
            kw = {"color": color(i), "marker": "os^vD"[i % 5], "markersize": 4 + (i > 0),
                  "markerfacecolor": color(i) if i == 0 else "none", "linestyle": ("-", "--", "-.", ":")[i % 4]}
            for ax, q in zip(axes, panels):
                if q == "tangential":
                    ax.plot(xs, np.asarray(r["k_Tx"], float), label=label, **kw)
                    ax.plot(xs, np.asarray(r["k_Ty"], float), **{**kw, "marker": None, "linewidth": 0.8})
                else:
                    ax.plot(xs, np.asarray(r[q], float), label=label, **kw)
        for ax, q in zip(axes, panels):
            name, kind = QUANTITIES[q]
            unit = _unit(kind, length, stress)
            ax.set_ylabel(axis_label(name, unit) if unit and " " not in unit else f"{name} [{unit}]" if unit else name)
            ax.grid(True, which="major")
            ax.set_yscale("log")
            if x == "separation":
                ax.set_xlabel(r"separation $s = h/\sqrt{m_{00}}$")
            else:
                ax.set_xscale("log")
                ax.set_xlabel(axis_label("nominal pressure W/A0", stress) if " " not in stress
                              else f"nominal pressure W/A0 [{stress}]")
        if "tangential" in panels:
            note(axes[panels.index("tangential")], "with markers: $k_{Tx}$; thin: $k_{Ty}$ (Mindlin, eq. 96)",
                 loc="upper right")
        legend_outside(fig, where="bottom")
    return fig


def moments_against_scale(measured: Mapping):
    """m20, m02 (slopes) and m40, m04 (curvatures) against the sampling interval, log–log, from the
    JSON of ``roughcontact moments`` (``scales``, ``uncertainty``, ``unit``): how the moments depend
    on the scale at which the surface is seen (error bars: the standard uncertainty at 1×)."""
    require_matplotlib()
    from matplotlib.ticker import LogFormatterSciNotation, NullLocator

    scales = measured["scales"]
    unit = measured.get("unit") or "L"
    unc = measured.get("uncertainty") or {}
    h = np.array([s["dx"] for s in scales], dtype=float)
    with _styled():
        fig = new_figure(figsize=(8.4, 3.6))
        for k, (names, ylabel) in enumerate(((("m20", "m02"), "slope variance [–]"),
                                             (("m40", "m04"), f"curvature variance [1/{unit}²]"))):
            ax = fig.add_subplot(1, 2, k + 1)
            for i, name in enumerate(names):
                y = np.array([s[name] for s in scales], dtype=float)
                err = np.zeros_like(y)
                if unc.get(name) is not None:
                    err[0] = unc[name]
                ax.errorbar(h, y, yerr=err, color=color(i), marker="o", capsize=3,
                            label={"m20": "$m_{20}$ (along the lay)", "m02": "$m_{02}$ (across)",
                                   "m40": "$m_{40}$ (along the lay)", "m04": "$m_{04}$ (across)"}[name])
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xticks(h, [f"{v:.3g}" for v in h])
            ax.xaxis.set_minor_locator(NullLocator())
            ax.yaxis.set_minor_formatter(LogFormatterSciNotation(labelOnlyBase=False, minor_thresholds=(2, 0.5)))
            ax.set_xlabel(axis_label("sampling interval dx", unit))
            ax.set_ylabel(ylabel.replace("um", "µm"))
            ax.legend(loc="best")
        fig.suptitle(f"moments against scale (m00 = {measured['m00']:.4g} {unit}², Sq = {measured['m00'] ** 0.5:.4g} "
                     f"{unit})".replace("um", "µm"), fontsize=10)
    return fig
