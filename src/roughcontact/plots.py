"""Figure styles shared by all figures, and the plotting functions of the paper's figures.

Functions take plain arrays and return a ``matplotlib.figure.Figure`` drawn on an Agg canvas:
no pyplot state, no global backend switch, so importing this module never changes how a
user's interactive session plots. :func:`save` writes a PNG without a timestamp.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path
from typing import Iterator, Mapping, Sequence

import numpy as np

__all__ = ["STYLE", "style", "new_figure", "save", "fig3", "fig4"]

#: rcParams of every figure of the project.
STYLE: dict = {
    "figure.figsize": (6.0, 4.2),
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "font.size": 10,
    "axes.labelsize": 10,
    "axes.titlesize": 10,
    "legend.fontsize": 9,
    "legend.frameon": False,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.6,
    "lines.linewidth": 1.4,
    "lines.markersize": 5,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "svg.hashsalt": "roughcontact",
    "path.simplify": False,
}

_COLORS = ("#1b4f72", "#b03a2e", "#1e8449", "#7d3c98", "#b9770e")


@contextlib.contextmanager
def style() -> Iterator[None]:
    """The project's rcParams for the duration of the block."""
    import matplotlib

    with matplotlib.rc_context(STYLE):
        yield


def new_figure(**kwargs):
    """A Figure on an Agg canvas (no pyplot), with the project's style applied."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    with style():
        fig = Figure(**kwargs)
        FigureCanvasAgg(fig)
    return fig


def save(fig, path: str | os.PathLike, *, dpi: int | None = None) -> Path:
    """Write ``fig`` as PNG (no creation-time metadata) and return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with style():
        fig.savefig(path, format="png", dpi=dpi or STYLE["savefig.dpi"], metadata={"Software": None})
    return path


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
        fig.tight_layout()
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
        fig.tight_layout()
    return fig
