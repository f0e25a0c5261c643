"""The plotting functions of the paper's figures.

Functions take plain arrays (and the units to show, from the configuration or the netCDF
``units`` attributes) and return a ``matplotlib.figure.Figure`` drawn on an Agg canvas with the
constrained layout: no pyplot state, no global backend switch, so importing this module never
changes how a user's interactive session plots. The look (rcParams, colours, unit and legend
typesetting, PNG + PDF saving) is owned by :mod:`roughcontact.plots.style`.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

from ..plots.style import STYLE, axis_label, color, legend_outside, new_figure, note, ordered_colors, save, style
from ..plots.style import pretty_unit as pretty

__all__ = [
    "STYLE", "style", "new_figure", "save", "fig3", "fig4", "fig5", "fig6", "stiffness_vs_pressure",
    "stiffness_sensitivity", "fig9", "slip_hardening", "friction_cases", "fig13", "punch_slips",
    "largest_gap", "fig1", "fig2",
]

_COLORS = [color(i) for i in range(5)]


def fig3(
    s: Sequence[float],
    ratios: Mapping[str, Sequence[float]],
    *,
    markers: Mapping[str, str] | None = None,
    title: str | None = None,
):
    """Fig. 3: A_G/A_B against s = h/√m00, one curve per surface (label → ratio array).
    Markers (square, triangle, cross in the paper) are drawn every few points."""
    s = np.asarray(s, dtype=float)
    markers = markers or {}
    with style():
        fig = new_figure()
        ax = fig.add_subplot(1, 1, 1)
        every = max(1, len(s) // 20)
        for i, (label, ratio) in enumerate(ratios.items()):
            ax.plot(
                s,
                np.asarray(ratio, dtype=float),
                color=_COLORS[i % len(_COLORS)],
                marker=markers.get(label, None),
                markevery=every,
                markerfacecolor="none",
                label=label,
            )
        ax.axhline(1.0, color="0.4", linewidth=0.8, linestyle=":")
        ax.set_xlabel(r"separation $s = h/\sqrt{m_{00}}$")
        ax.set_ylabel(r"$A_G/A_B$")
        ax.set_xlim(s.min(), s.max())
        if title:
            ax.set_title(title)
        ax.legend(loc="best")
    return fig


def fig4(
    e: Sequence[float],
    curves: Mapping[str, tuple[Sequence[float], Sequence[float]]],
    *,
    title: str | None = None,
):
    """Fig. 4: f1(e) (area) and f2(e) (load) against the eccentricity e; ``curves`` maps a
    label (e.g. the Hertz option) to (f1, f2). The first label is drawn solid, the others
    dashed with sparse open markers (the curves nearly coincide)."""
    e = np.asarray(e, dtype=float)
    styles = ("-", "--", ":", "-.")
    with style():
        fig = new_figure()
        ax = fig.add_subplot(1, 1, 1)
        for i, (label, (f1, f2)) in enumerate(curves.items()):
            kw = {"linestyle": styles[i % len(styles)]}
            if i:
                kw.update(marker="os^v"[(i - 1) % 4], markevery=max(1, len(e) // 12), markerfacecolor="none")
            ax.plot(e, np.asarray(f1, dtype=float), color=_COLORS[0], label=rf"$f_1$, {label}", **kw)
            ax.plot(e, np.asarray(f2, dtype=float), color=_COLORS[1], label=rf"$f_2$, {label}", **kw)
        ax.set_xlabel(r"eccentricity $e$")
        ax.set_ylabel(r"$f_1(e)$, $f_2(e)$")
        ax.set_xlim(e.min(), e.max())
        if title:
            ax.set_title(title)
        ax.legend(loc="upper left")
    return fig


def _within(x, y, xlim):
    """y with the points outside [xlim] masked (so the axes scale to what is shown)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if xlim is None:
        return x, y
    keep = (x >= xlim[0] / 1.5) & (x <= xlim[1] * 1.5)
    return x[keep], y[keep]


def fig5(load: Mapping[str, Sequence[float]], plastic: Mapping[str, Sequence[float]],
         yielded: Mapping[str, Sequence[float]], *, floor: float = 1e-6):
    """Fig. 5: (a) the fully plastic part A^p/A (the captioned ordinate, eq. (81); log scale,
    values below ``floor`` not drawn) and (b) the yielded part (A^ep + A^p)/A against the load
    W/(H A0), one curve per label (ψ)."""
    with style():
        fig = new_figure(figsize=(10.0, 4.2))
        ax1, ax2 = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
        colors = ordered_colors(len(load))
        for i, label in enumerate(load):
            x = np.asarray(load[label], dtype=float)
            yp = np.asarray(plastic[label], dtype=float)
            ax1.plot(x, np.where(yp >= floor, yp, np.nan), color=colors[i], label=label)
            ax2.plot(x, np.asarray(yielded[label], dtype=float), color=colors[i], label=label)
        for ax in (ax1, ax2):
            ax.set_xscale("log")
            ax.set_xlabel(r"load $W/(H A_0)$")
        ax1.set_yscale("log")
        ax1.set_ylim(floor, 1.5)
        ax1.set_ylabel(r"fully plastic part $A^p/A$ (eq. 81)")
        ax1.set_title(f"(a) as captioned (values < {floor:g} not drawn)")
        ax2.set_ylim(0.0, 1.0)
        ax2.set_ylabel(r"yielded part $(A^{ep} + A^p)/A$")
        ax2.set_title("(b) past first yield")
        legend_outside(fig, ax2)
    return fig


def fig6(load: Mapping[str, Sequence[float]], mean_pressure: Mapping[str, Sequence[float]],
         levels: Mapping[str, float]):
    """Fig. 6: the real mean pressure W/(A H) against the load W/(H A0), one curve per label
    (ψ), with horizontal reference ``levels`` (label → value, e.g. the prose's 0.354, c_h)."""
    with style():
        fig = new_figure()
        ax = fig.add_subplot(1, 1, 1)
        colors = ordered_colors(len(load))
        for i, label in enumerate(load):
            ax.plot(np.asarray(load[label], float), np.asarray(mean_pressure[label], float), color=colors[i], label=label)
        values = sorted(levels.values())
        for j, (name, value) in enumerate(levels.items()):
            ax.axhline(value, color="0.35", linewidth=0.8, linestyle=(0, (1 + 2 * j, 2)))
            # label above its line, unless the next level up is close: then below
            close = any(0 < v - value < 0.06 for v in values)
            # on the left, where the curves have not begun (they start at the first contact)
            ax.annotate(name, (0.0, value), xycoords=("axes fraction", "data"), xytext=(4, -2 if close else 2),
                        textcoords="offset points", ha="left", va="top" if close else "bottom",
                        fontsize=8, color="0.3")
        ax.set_xscale("log")
        ax.set_ylim(0.0, 1.05)
        ax.set_xlabel(r"load $W/(H A_0)$")
        ax.set_ylabel(r"real mean pressure $W/(A H)$")
        legend_outside(fig, ax)
    return fig


_MARKERS_78 = ("^", "x", "s", "o", "v")


def _stiffness_axes(ax, title, xlim, units, ylabel="normal stiffness"):
    """Log–log K/A0 against W/A0 axes (Figs 7–8 and the sensitivity scene); ``units`` =
    (pressure units, stiffness units), UDUNITS strings."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    if xlim is not None:
        ax.set_xlim(*xlim)
    ax.set_xlabel(axis_label(r"average pressure $W/A_0$", units[0]))
    ax.set_ylabel(axis_label(rf"{ylabel} $K/A_0$", units[1]))
    ax.set_title(title, fontsize=9)


def largest_gap(p_a, k_a, p_b, k_b, xlim=None) -> float:
    """The largest relative difference |K_b/K_a − 1| of two K(W) curves at equal pressure W,
    over the pressures both cover (and ``xlim``); interpolated in log–log."""
    p_a, k_a, p_b, k_b = (np.asarray(v, float) for v in (p_a, k_a, p_b, k_b))
    ok_a, ok_b = (p_a > 0) & (k_a > 0), (p_b > 0) & (k_b > 0)
    p_a, k_a, p_b, k_b = p_a[ok_a], k_a[ok_a], p_b[ok_b], k_b[ok_b]
    lo, hi = max(p_a.min(), p_b.min()), min(p_a.max(), p_b.max())
    if xlim is not None:
        lo, hi = max(lo, xlim[0]), min(hi, xlim[1])
    grid = np.geomspace(lo, hi, 200)
    oa, ob = np.argsort(p_a), np.argsort(p_b)
    ka = np.exp(np.interp(np.log(grid), np.log(p_a[oa]), np.log(k_a[oa])))
    kb = np.exp(np.interp(np.log(grid), np.log(p_b[ob]), np.log(k_b[ob])))
    return float(np.max(np.abs(kb / ka - 1.0)))


def stiffness_vs_pressure(panels: Mapping[str, Mapping[str, tuple]], *, units=("1", "1"), xlim=None,
                          coincide: float = 0.01):
    """Figs 7–8: K/A0 against W/A0 (log–log). ``panels`` maps a panel title to {curve label:
    (pressure_elastic, stiffness_elastic, pressure_ep, stiffness_ep)}: elastic as a broad pale
    line, elasto-plastic dashed on top of it, one colour and marker per curve (m00: triangles,
    crosses, squares as in the paper), so both stay visible where they coincide. Each panel
    states the largest elastic/elasto-plastic difference at equal pressure, and says the curves
    coincide when it is below ``coincide``. ``units``: (pressure, stiffness) UDUNITS strings."""
    n = len(panels)
    with style():
        fig = new_figure(figsize=(4.3 * n, 4.6))
        axes = fig.subplots(1, n, sharey=True, squeeze=False)[0]
        for k, (title, curves) in enumerate(panels.items()):
            ax = axes[k]
            gap = 0.0
            for i, (label, (pe, ke, pp, kp)) in enumerate(curves.items()):
                kw = dict(color=color(i), marker=_MARKERS_78[i % len(_MARKERS_78)], markerfacecolor="none")
                ax.plot(*_within(pe, ke, xlim), linestyle="-", linewidth=4.0, alpha=0.35, markevery=(0, 8),
                        label=f"{label}, elastic", **kw)
                ax.plot(*_within(pp, kp, xlim), linestyle=(0, (4, 2)), linewidth=1.2, markevery=(4, 8),
                        label=f"{label}, elasto-plastic", **kw)
                gap = max(gap, largest_gap(pe, ke, pp, kp, xlim))
            _stiffness_axes(ax, title, xlim, units)
            if k:
                ax.set_ylabel("")
            text = f"elasto-plastic vs elastic: ≤ {100 * gap:.2g} %"
            note(ax, text + ("\n(the curves coincide)" if gap < coincide else ""))
        legend_outside(fig, axes[0], where="bottom", ncol=3)
    return fig


def stiffness_sensitivity(variants: Mapping[str, tuple], by_psi: Mapping[str, tuple], *, units=("1", "1"),
                          xlim=None):
    """(a) elasto-plastic K/A0 against W/A0 for surface variants (label → (pressure,
    stiffness)); (b) the same for several ψ (label → (pressure, stiffness)). Log–log; each
    panel's legend beside it."""
    with style():
        fig = new_figure(figsize=(11.0, 4.4))
        axes = fig.subplots(1, 2)
        for k, (title, curves) in enumerate(((r"(a) moments varied, $m_{00}$ kept (and $m_{00}$ doubled)", variants),
                                             (r"(b) plasticity index $\psi$", by_psi))):
            ax = axes[k]
            colors = ordered_colors(len(curves)) if k else [color(i) for i in range(len(curves))]
            for i, (label, (p, s)) in enumerate(curves.items()):
                ax.plot(*_within(p, s, xlim), color=colors[i], linestyle=("-", "--")[k == 0 and i >= len(_COLORS)],
                        label=label)
            if k:  # the ψ curves lie on one another: say how close
                (first, (p0, s0)), *rest = curves.items()
                gap = max(largest_gap(p0, s0, p, s, xlim) for _, (p, s) in rest)
                note(ax, f"all within {100 * gap:.2g} % of {first}\nat equal pressure")
            _stiffness_axes(ax, title, xlim, units, "elasto-plastic stiffness")
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    return fig


def fig9(panels: Mapping[str, dict], *, units: str = "1"):
    """Fig. 9: per panel (title → dict with mu_x, mu_y, ratio = ν_y/ν_x, t_x, t_y, up_x, up_y at
    sliding points, p_N): the limit ellipse (91) (solid), the slip potential (98) scaled to the
    same x semi-axis (dashed) and the slip direction at each sliding traction (arrows).
    ``units``: of the tractions (UDUNITS)."""
    n = len(panels)
    with style():
        fig = new_figure(figsize=(3.6 * n, 3.8))
        phi = np.linspace(0.0, 2.0 * np.pi, 361)
        for k, (title, d) in enumerate(panels.items()):
            ax = fig.add_subplot(1, n, k + 1)
            a, b = d["mu_x"] * d["p_N"], d["mu_y"] * d["p_N"]
            ax.plot(a * np.cos(phi), b * np.sin(phi), color=_COLORS[0], label="limit surface f = 0 (91)")
            ax.plot(a * np.cos(phi), a * d["ratio"] * np.sin(phi), color=_COLORS[1], linestyle="--",
                    label="slip potential g (98)")
            up = np.hypot(d["up_x"], d["up_y"])
            scale = 0.25 * max(a, b)
            ax.quiver(d["t_x"], d["t_y"], scale * d["up_x"] / up, scale * d["up_y"] / up, angles="xy",
                      scale_units="xy", scale=1.0, color=_COLORS[2], width=0.006, label="slip direction")
            ax.plot(d["t_x"], d["t_y"], "o", color=_COLORS[0], markersize=2.5)
            if abs(a * d["ratio"] - b) <= 1e-12 * max(a, b):
                note(ax, "g coincides with f\n(associated slip)", loc="lower right")
            lim = 1.35 * max(a, b)
            ax.set_xlim(-lim, lim)
            ax.set_ylim(-lim, lim)
            ax.set_aspect("equal")
            ax.set_xlabel(axis_label(r"traction $t_x/p_N$" if units == "1" else r"traction $t_x$", units))
            ax.set_ylabel(axis_label(r"traction $t_y/p_N$" if units == "1" else r"traction $t_y$", units))
            ax.set_title(title, fontsize=9)
        legend_outside(fig, where="bottom", ncol=3, fontsize=8)
    return fig


def slip_hardening(kappa, ratio, mu_89, *, units: str = "1", title: str | None = None):
    """A material-point slip-hardening curve: t_x/p_N against the accumulated slip κ_x (in
    ``units``, a length) from the return mapping (solid) and μ_x(κ_x) of (89) (dashed on top:
    the two coincide, and the legend says so)."""
    with style():
        fig = new_figure()
        ax = fig.add_subplot(1, 1, 1)
        ax.plot(kappa, ratio, color=_COLORS[0], linewidth=4.0, alpha=0.35, label=r"return mapping: $t_x/p_N$")
        ax.plot(kappa, mu_89, color=_COLORS[1], linestyle="--", label=r"$\mu_x(\kappa_x)$, eq. (89) (coincides)")
        ax.set_xlabel(axis_label(r"accumulated slip $\kappa_x$", units))
        ax.set_ylabel(r"friction ratio $t_x/p_N$")
        if title:
            ax.set_title(title, fontsize=9)
        ax.legend(loc="lower right")
    return fig


def friction_cases(panels: Mapping[str, tuple], *, xlabel: str, ylabel: str):
    """Tractions against the imposed tangential displacement, one panel per case (title →
    (u along the path, t_x, t_y, up_x, up_y)); loading and unloading run along the same axis."""
    n = len(panels)
    with style():
        fig = new_figure(figsize=(3.8 * n, 3.6))
        for k, (title, (u, tx, ty, upx, upy)) in enumerate(panels.items()):
            ax = fig.add_subplot(1, n, k + 1)
            ax.plot(u, tx, color=_COLORS[0], label=r"$t_x$")
            ax.plot(u, ty, color=_COLORS[1], label=r"$t_y$")
            ax.axhline(0.0, color="0.5", linewidth=0.6)
            ax.set_ylabel(ylabel)
            ax.set_title(title, fontsize=9)
        fig.supxlabel(xlabel, fontsize=STYLE["axes.labelsize"])  # once for all panels: it is longer than one
        legend_outside(fig, where="right")  # not below: the shared x-label is there
    return fig


def fig13(profiles: Mapping[str, tuple], printed: Mapping[str, tuple] | None = None, *, title: str | None = None):
    """Fig. 13: interface deflection u_N [µm] along the beam, x [mm] from mid-length.
    ``profiles``: label → (x, u_N, marker); ``printed``: label → ((x_centre, u_centre), (x_end,
    u_end)) of Table 4, drawn as open markers of the same colour."""
    fig = new_figure(figsize=(8.0, 4.4))
    with style():
        ax = fig.add_subplot()
        for i, (label, (x, u, marker)) in enumerate(profiles.items()):
            c = color(i)
            ax.plot(x, u, "-", color=c, lw=1.2)
            ax.plot(x[::max(1, len(x) // 12)], u[::max(1, len(x) // 12)], marker, color=c, ls="none",
                    label=f"{label} (ours)")
            if printed and label in printed:
                px, pu = zip(*printed[label])
                ax.plot(px, pu, marker, color=c, mfc="none", ms=9, mew=1.5, ls="none",
                        label=f"{label}, Table 4 (paper)")
        ax.axhline(0.0, color="0.5", lw=0.8)
        ax.set_xlabel("x from mid-length [mm]")
        ax.set_ylabel("$u_N$ from the seated state [µm] (< 0: approach)")
        ax.set_title(title or "Fig. 13: interface deflection along the beam (elastic law)")
        legend_outside(fig, ax, fontsize=8)
    return fig


def punch_slips(panels: Mapping[str, Mapping[str, dict]], *, title: str):
    """Figs 18/19: directions of the plastic slips at the contact points of the quarter punch.
    ``panels``: row label → column label → dict(x, y [mm], ux, uy [µm], status). Slipped points
    are unit arrows coloured by |u_T^p| [µm] (a shared log scale); stick points are dots,
    open points crosses."""
    from matplotlib.colors import LogNorm

    rows, cols = list(panels), list(next(iter(panels.values())))
    mags = np.concatenate([np.hypot(p["ux"], p["uy"]) for r in panels.values() for p in r.values()])
    pos = mags[mags > 0]
    norm = LogNorm(vmin=pos.min(), vmax=pos.max()) if pos.size and pos.max() > pos.min() else None
    fig = new_figure(figsize=(3.1 * len(cols) + 1.2, 3.0 * len(rows) + 0.9))
    with style():
        axes = fig.subplots(len(rows), len(cols), squeeze=False, sharex=True, sharey=True)
        quiver = None
        for i, r in enumerate(rows):
            for j, c in enumerate(cols):
                ax, p = axes[i][j], panels[r][c]
                m = np.hypot(p["ux"], p["uy"])
                slip = m > 0
                stick = (~slip) & (p["status"] != 2)
                ax.plot(p["x"][stick], p["y"][stick], ".", color="0.45", ms=4, label="stick")
                ax.plot(p["x"][p["status"] == 2], p["y"][p["status"] == 2], "x", color="0.45", ms=4, label="open")
                if np.any(slip):
                    quiver = ax.quiver(p["x"][slip], p["y"][slip], p["ux"][slip] / m[slip], p["uy"][slip] / m[slip],
                                       m[slip], norm=norm, cmap="viridis", scale=22, width=0.012, pivot="tail")
                ax.set_aspect("equal")
                ax.set_xlim(-0.6, p["x"].max() + 1.2)
                ax.set_ylim(-0.6, p["y"].max() + 1.2)
                ax.grid(False)
                if i == 0:
                    ax.set_title(c)
                if j == 0:
                    ax.set_ylabel(f"{r}\ny [mm]")
                if i == len(rows) - 1:
                    ax.set_xlabel("x [mm]")
                n_slip = int(np.count_nonzero(slip))
                ax.text(0.02, 0.98, f"{n_slip} of {m.size} slip", transform=ax.transAxes, va="top", fontsize=8)
        handles, labels = axes[0][0].get_legend_handles_labels()
        fig.suptitle(title)
        if quiver is not None:
            from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

            bar = fig.colorbar(quiver, ax=axes, shrink=0.7, label=r"$|u_T^p|$ [µm]")
            bar.ax.yaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))  # a log range under a decade
            bar.ax.yaxis.set_major_formatter(FormatStrFormatter("%.2g"))
            bar.ax.yaxis.set_minor_formatter(NullFormatter())
        fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=8)
    return fig


def fig1(profile, *, length_unit: str = "um"):
    """Fig. 1: (a) a patch of the generated height map with the profile's line; (b) the profile
    across the lay with the surface's mean plane, the mean plane of the summits at δ (73), the
    mean height of the map's summits and the smooth flat at h (``profile``:
    :class:`roughcontact.paper.geometry.SurfaceProfile`)."""
    p = profile
    image, extent = p.patch, p.patch_extent
    with style():
        fig = new_figure(figsize=(10.0, 4.4))
        ax_map, ax = fig.subplots(1, 2, width_ratios=(1.0, 2.2))
        fig.get_layout_engine().set(wspace=0.08)  # room between the colour bar and panel (b)
        lim = float(np.max(np.abs(image)))
        im = ax_map.imshow(image, origin="lower", extent=extent, cmap="RdBu_r", vmin=-lim, vmax=lim,
                           interpolation="nearest")
        x_line = 0.5 * (extent[0] + extent[1])
        ax_map.plot([x_line, x_line], [p.y[0], p.y[-1]], color="k", lw=1.0)
        ax_map.set_xlabel(axis_label("x (along the lay)", length_unit))
        ax_map.set_ylabel(axis_label("y", length_unit))
        ax_map.set_title("(a) generated surface, profile line", fontsize=9)
        ax_map.grid(False)
        fig.colorbar(im, ax=ax_map, label=axis_label("height z", length_unit), shrink=0.8)
        ax.plot(p.y, p.z, color=color(0), lw=1.0, label="profile z(y)")
        u = pretty(length_unit)
        ax.plot(p.summit_y, p.summit_z, "^", color=color(0), ms=5, mfc="none",
                label=f"summits of the map within ±{p.band:g} {u} of the line")
        ax.axhline(0.0, color="0.3", lw=1.0, label="mean plane of the surface")
        ax.axhline(p.delta, color=color(1), lw=1.2, ls="--",
                   label=rf"mean plane of the summits, $\delta$ (73) = {p.delta:.3g} {u}")
        ax.axhline(p.map_summit_mean, color=color(2), lw=1.2, ls=":",
                   label=f"mean height of the map's {p.map_summits} summits = {p.map_summit_mean:.3g} {u} (coincides)")
        ax.axhline(p.flat, color="k", lw=2.5, label=f"smooth flat at h = {p.flat:.3g} {u}")
        x_arrow = p.y[0] + 0.03 * (p.y[-1] - p.y[0])
        ax.annotate("", (x_arrow, p.delta), (x_arrow, 0.0), arrowprops=dict(arrowstyle="<->", color=color(1), lw=1.0))
        ax.text(x_arrow, 0.5 * p.delta, rf" $\delta$", color=color(1), va="center", fontsize=10,
                bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8))
        ax.set_xlim(p.y[0], p.y[-1])
        ax.set_xlabel(axis_label("y (across the lay)", length_unit))
        ax.set_ylabel(axis_label("height z", length_unit))
        ax.set_title("(b) profile across the lay (heights exaggerated)", fontsize=9)
        legend_outside(fig, ax, where="bottom", ncol=2, fontsize=8)
    return fig


def _ellipse(ax, a, b, **kwargs):
    t = np.linspace(0.0, 2.0 * np.pi, 241)
    return ax.plot(a * np.cos(t), b * np.sin(t), **kwargs)


def fig2(g, *, length_unit: str = "um"):
    """Fig. 2: one elliptic-paraboloid asperity (19) cut by the plane at interference ω: (a) the
    cap above the plane with the geometric ellipse a, b; (b) plan view: the geometric ellipse
    (20)–(21) and the Hertz contact ellipse A, B of (26)–(27) (``g``:
    :class:`roughcontact.paper.geometry.AsperityGeometry`)."""
    u = pretty(length_unit)
    with style():
        fig = new_figure(figsize=(10.5, 4.6))
        ax3 = fig.add_subplot(1, 2, 1, projection="3d")
        r, t = np.meshgrid(np.linspace(0.0, 1.0, 25), np.linspace(0.0, 2.0 * np.pi, 73))
        x, y = r * g.a * np.cos(t), r * g.b * np.sin(t)
        z = g.height(x, y) + g.interference  # the cap above the cutting plane z = h
        ax3.plot_surface(x, y, z, cmap="viridis", alpha=0.55, linewidth=0, antialiased=True)
        side = 1.3 * max(g.a, g.b)
        px, py = np.meshgrid([-side, side], [-side, side])
        ax3.plot_surface(px, py, 0.0 * px, color="0.6", alpha=0.15, linewidth=0)  # the plane z = h
        tt = np.linspace(0.0, 2.0 * np.pi, 241)
        ax3.plot(g.a * np.cos(tt), g.b * np.sin(tt), 0.0 * tt, color=color(1), lw=2.0, label="geometric ellipse a, b")
        ax3.plot(g.A * np.cos(tt), g.B * np.sin(tt), 0.0 * tt, color="k", lw=1.5, label="contact ellipse A, B")
        ax3.plot([0, 0], [0, 0], [0, g.interference], color="k", lw=1.0, ls="--")
        ax3.text(0, 0, g.interference, rf"  summit $\xi_1$; $\omega$ = {g.interference:g} {u}", fontsize=8)
        ax3.set_xlabel(axis_label("x", length_unit), fontsize=8)
        ax3.set_ylabel(axis_label("y", length_unit), fontsize=8)
        ax3.set_zlabel(axis_label("z − h", length_unit), fontsize=8)
        ax3.set_title("(a) the asperity above the plane z = h", fontsize=9)
        ax3.view_init(elev=28, azim=-60)
        ax = fig.add_subplot(1, 2, 2)
        _ellipse(ax, g.a, g.b, color=color(1), lw=1.5, ls="--",
                 label=f"geometric ellipse (20): a = {g.a:.3g} {u}, b = {g.b:.3g} {u}")
        t = np.linspace(0.0, 2.0 * np.pi, 241)
        ax.fill(g.A * np.cos(t), g.B * np.sin(t), color="0.8", zorder=0)
        _ellipse(ax, g.A, g.B, color="k", lw=1.5,
                 label=f"contact ellipse (26)–(27): A = {g.A:.3g} {u}, B = {g.B:.3g} {u}")
        ax.annotate("", (g.A, 0.0), (0.0, 0.0), arrowprops=dict(arrowstyle="->", lw=0.8))
        ax.annotate("", (0.0, g.B), (0.0, 0.0), arrowprops=dict(arrowstyle="->", lw=0.8))
        ax.text(0.5 * g.A, 0.0, "A", va="bottom", ha="center", fontsize=9)
        ax.text(0.0, 0.5 * g.B, " B", va="center", ha="left", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlim(-1.15 * max(g.a, g.b), 1.15 * max(g.a, g.b))
        ax.set_xlabel(axis_label("x", length_unit))
        ax.set_ylabel(axis_label("y", length_unit))
        ax.set_title(rf"(b) plan view: $\lambda$ = b/a = {min(g.a, g.b) / max(g.a, g.b):.3f}, "
                     rf"$e_1$ = B/A = {g.e1:.3f}", fontsize=9)
        legend_outside(fig, ax, where="bottom", ncol=1, fontsize=8)
    return fig
