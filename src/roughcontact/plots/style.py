"""The one owner of how the project's figures look: rcParams, colours, the layout engine,
units in axis labels, legends as a person writes them, and saving (PNG and PDF).

* Every figure is a ``matplotlib.figure.Figure`` on an Agg canvas with the *constrained*
  layout engine (:func:`new_figure`): nothing overlaps and nothing is clipped at the edge.
* Units come from the configuration (``units: {length: um, stress: N/mm^2}``) or from a
  netCDF variable's ``units`` attribute and are shown as typeset (:func:`pretty_unit`:
  ``um`` → µm, ``N/mm^2`` → N/mm², ``N mm-2 um-1`` → N/(mm²·µm)).
* Legends read ``ψ = 0.35``, ``m₀₀ = 0.0625 µm²`` (:func:`parameter_label`), and sit outside
  the data (:func:`legend_outside`) where the data fill the axes.
* :func:`save` writes the PNG and a vector PDF beside it, both without creation dates, so two
  runs of the same data give the same files. A failed write (a full disk: OSError 28) is one
  line, :class:`roughcontact.write_errors.WriteError` (a ValueError) naming the file; nothing is left
  under its name.
* :func:`check_text` refuses a text (a legend entry, a unit) matplotlib cannot typeset
  (unbalanced or too deeply nested mathtext) with one line naming it, before anything is drawn.

No pyplot: importing this module never changes a user's interactive backend.
"""

from __future__ import annotations

import contextlib
import os
import re
from pathlib import Path
from typing import Iterator

import numpy as np

from ..files import atomic_path
from ..write_errors import write_error

__all__ = [
    "STYLE", "COLORS", "style", "new_figure", "save", "save_figure", "color", "ordered_colors", "pretty_unit",
    "axis_label", "parameter_label", "legend_outside", "note", "require_matplotlib", "check_text",
]

#: how to get matplotlib (one line for the error message)
INSTALL = "pip install '.[workflow]' in the roughcontact checkout (or pip install matplotlib)"

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
    "pdf.fonttype": 42,  # TrueType in the PDF: text stays text (searchable, editable)
}

#: the qualitative colours (curves that are not ordered by a parameter)
COLORS = ("#1b4f72", "#b03a2e", "#1e8449", "#7d3c98", "#b9770e")

#: how a parameter name of the configuration is written on a figure (mathtext)
SYMBOLS = {
    "psi": r"$\psi$", "m00": r"$m_{00}$", "m20": r"$m_{20}$", "m02": r"$m_{02}$", "m40": r"$m_{40}$",
    "m04": r"$m_{04}$", "E_star": r"$E^*$", "Y": r"$Y$", "mu": r"$\mu$", "mu_m": r"$\mu_m$",
    "mu_o": r"$\mu_o$", "n": r"$n$", "k": r"$k$", "c_h": r"$c_h$", "s": r"$s$", "e": r"$e$",
}

_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def require_matplotlib() -> None:
    """ImportError with one line saying how to install matplotlib, where it is missing (the
    library's figures need it; the rest of the library does not)."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise ImportError(f"figures need matplotlib, which is not installed: {INSTALL}") from None


@contextlib.contextmanager
def style() -> Iterator[None]:
    """The project's rcParams for the duration of the block."""
    require_matplotlib()
    import matplotlib

    with matplotlib.rc_context(STYLE):
        yield


def new_figure(**kwargs):
    """A Figure on an Agg canvas (no pyplot), the project's style, the constrained layout
    engine (pass ``layout=None`` to place axes by hand)."""
    require_matplotlib()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    kwargs.setdefault("layout", "constrained")
    with style():
        fig = Figure(**kwargs)
        FigureCanvasAgg(fig)
    return fig


def save(fig, path: str | os.PathLike, *, dpi: int | None = None) -> Path:
    """Write ``fig`` as PNG at ``path`` and as PDF beside it (same stem), neither with a
    creation date, each atomically (files.atomic_path); return the PNG's path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with style():
        _write(fig, path, "png", dpi or STYLE["savefig.dpi"], {"Software": None})
        _write(fig, path.with_suffix(".pdf"), "pdf", None,
               {"CreationDate": None, "ModDate": None, "Producer": None, "Creator": "roughcontact"})
    return path


def _write(fig, path: Path, fmt: str, dpi, metadata) -> None:
    """``fig.savefig`` to ``path`` atomically; an OSError (a full disk) as a one-line WriteError
    naming the file, raised while the partial file still exists (write_errors.write_error measures the
    free space then) and removed by atomic_path."""
    with atomic_path(path) as tmp:
        try:
            fig.savefig(tmp, format=fmt, dpi=dpi, metadata=metadata)
        except OSError as exc:
            raise write_error(path, exc, "figure") from None


def save_figure(fig, path: str | os.PathLike) -> Path:
    """Write ``fig`` as one file in the format of its suffix (.png, .pdf, .svg), without a
    creation date, atomically (files.atomic_path); return its path."""
    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in ("png", "pdf", "svg"):
        raise ValueError(f"{path}: the figure's format comes from its suffix: .png, .pdf or .svg")
    metadata = {"png": {"Software": None}, "svg": {"Date": None},
                "pdf": {"CreationDate": None, "ModDate": None, "Producer": None, "Creator": "roughcontact"}}[fmt]
    with style():
        _write(fig, path, fmt, STYLE["savefig.dpi"], metadata)
    return path


def check_text(text: str, what: str) -> str:
    """``text`` if matplotlib can typeset it, else ValueError (one line) naming ``what``.

    Text between ``$`` is mathtext; matplotlib parses it only when the figure is drawn, and a
    malformed one (``$\\frac{a$``) or one nested deeper than its recursive parser reaches
    (sixty ``\\sqrt{`` raise RecursionError) would fail in the middle of saving. Typesetting
    it once on a scratch figure finds that before anything is written."""
    require_matplotlib()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(1, 1))
    FigureCanvasAgg(fig)
    try:
        fig.text(0, 0, text).get_window_extent(renderer=fig.canvas.get_renderer())
    except RecursionError:
        raise ValueError(f"{what}: nested too deeply to typeset (write it as plain text, "
                         "without $...$)") from None
    except ValueError as exc:
        first = " ".join(str(exc).split())[:200]
        raise ValueError(f"{what}: not valid mathtext ({first}); write it without $...$ or escape $ as \\$") from None
    return text


def texts_outside(fig) -> list[str]:
    """What a PNG of ``fig`` would clip once laid out: the axes' labels, titles, drawn tick
    labels and legends, and the figure's own texts and legends, that reach beyond its edges
    (each named by its text, or "ticks of <axis label>")."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox

    def outside(artist):
        ext = artist.get_tightbbox(renderer)
        return ext is not None and (ext.x0 < box.x0 - 0.5 or ext.x1 > box.x1 + 0.5
                                    or ext.y0 < box.y0 - 0.5 or ext.y1 > box.y1 + 0.5)

    out = []
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if axis.label.get_visible() and axis.label.get_text() and outside(axis.label):
                out.append(axis.label.get_text())
            labels = [t for t in axis.get_ticklabels() if t.get_visible()]
            if any(outside(t) for t in labels) and outside(axis):  # axis: only the ticks drawn
                out.append(f"ticks of {axis.label.get_text() or axis.axis_name}")
        out += [a.get_text() for a in (ax.title, *ax.texts) if a.get_text() and outside(a)]
        out += ["legend" for leg in [ax.get_legend()] if leg is not None and outside(leg)]
    out += [t.get_text() for t in fig.texts if t.get_text() and outside(t)]
    out += [t.get_text() for t in (getattr(fig, "_supxlabel", None), getattr(fig, "_suptitle", None))
            if t is not None and t.get_text() and outside(t)]
    out += ["legend" for leg in fig.legends if outside(leg)]
    return out


def color(i: int) -> str:
    """The i-th qualitative colour (cycling)."""
    return COLORS[i % len(COLORS)]


def ordered_colors(n: int) -> list:
    """n distinct colours for an ordered parameter (ψ): viridis without its pale yellow end."""
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.85, max(n, 2))][:n]


def _factor(name: str, power: int) -> str:
    """One unit factor typeset: µ for micro, the power as a superscript."""
    name = {"um": "µm", "micron": "µm", "ohm": "Ω", "deg": "°"}.get(name, name)
    return name + (str(power).translate(_SUPERSCRIPT) if power != 1 else "")


def pretty_unit(units: str) -> str:
    """A UDUNITS string as typeset: ``"um"`` → ``"µm"``, ``"N/mm^2"`` → ``"N/mm²"``,
    ``"N/mm^2/um"`` and ``"N mm-2 um-1"`` → ``"N/(mm²·µm)"``, ``"um^2"`` → ``"µm²"``,
    ``"1"`` → ``"–"``. Factors are read left to right (UDUNITS: ``a/b/c`` = a/(b·c)); a
    string it cannot read is returned with ``um`` → ``µm`` only."""
    u = str(units).strip()
    if u in ("1", ""):
        return "–"
    num, den = [], []
    for op, token in re.findall(r"(/?)\s*([^\s*./]+)", u):
        m = re.fullmatch(r"([A-Za-z]+)(?:\^?\(?(-?\d+)\)?)?", token)
        if not m:
            return re.sub(r"\bum\b", "µm", u)
        power = int(m.group(2) or 1) * (-1 if op else 1)
        (num if power > 0 else den).append(_factor(m.group(1), abs(power)))
    top = "·".join(num) or "1"
    if not den:
        return top
    return f"{top}/({'·'.join(den)})" if len(den) > 1 else f"{top}/{den[0]}"


def axis_label(quantity: str, units: str | None = None) -> str:
    """``"W/A0 [N/mm²]"``: the quantity and its typeset unit (none for a pure number)."""
    if units is None or str(units).strip() in ("1", ""):
        return quantity
    return f"{quantity} [{pretty_unit(units)}]"


def parameter_label(name: str, value, units: str | None = None, *, fmt: str = "g") -> str:
    """A legend entry as a person writes it: ``parameter_label("psi", 0.35)`` → ``ψ = 0.35``,
    ``parameter_label("m00", 0.0625, "um^2")`` → ``m₀₀ = 0.0625 µm²``."""
    symbol = SYMBOLS.get(name, name)
    text = value if isinstance(value, str) else format(float(value), fmt)
    unit = "" if units is None or str(units).strip() in ("1", "") else " " + pretty_unit(units)
    return f"{symbol} = {text}{unit}"


def legend_outside(fig, ax=None, *, where: str = "right", **kwargs):
    """The legend outside the data: beside the axes (``where="right"``) or below the figure
    (``"bottom"``); the constrained layout makes room for it. Entries come from ``ax``, or
    from every axes of the figure (each label once) when ``ax`` is None."""
    entries: dict = {}
    for a in ([ax] if ax is not None else fig.axes):
        for handle, label in zip(*a.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    labels, handles = list(entries), list(entries.values())
    if where == "right":
        kwargs.setdefault("loc", "outside right upper")
    else:
        kwargs.setdefault("loc", "outside lower center")
        kwargs.setdefault("ncol", min(len(labels), 4) or 1)
    return fig.legend(handles, labels, **kwargs)


def note(ax, text: str, *, loc: str = "lower right", **kwargs):
    """A short note inside the axes, in a corner, on a white box (e.g. "curves coincide")."""
    x, ha = (0.98, "right") if "right" in loc else (0.02, "left")
    y, va = (0.02, "bottom") if "lower" in loc else (0.98, "top")
    kwargs.setdefault("fontsize", 8)
    return ax.text(x, y, text, transform=ax.transAxes, ha=ha, va=va,
                   bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.7", lw=0.6), **kwargs)
