"""roughcontact.plots.style: units typeset from UDUNITS strings, legends as a person writes
them, PNG and PDF saved together."""

import pytest

from roughcontact.paper import gallery
from roughcontact.plots import style


@pytest.mark.parametrize("units, shown", [
    ("um", "µm"), ("N/mm^2", "N/mm²"), ("N/mm^2/um", "N/(mm²·µm)"), ("N mm-2 um-1", "N/(mm²·µm)"),
    ("um^2", "µm²"), ("um-1", "1/µm"), ("N mm", "N·mm"), ("1", "–"),
])
def test_pretty_unit(units, shown):
    assert style.pretty_unit(units) == shown


def test_labels_read_as_written():
    assert style.parameter_label("psi", 0.35) == r"$\psi$ = 0.35"
    assert style.parameter_label("m00", 0.0625, "um^2") == r"$m_{00}$ = 0.0625 µm²"
    assert style.axis_label("W/A0", "N/mm^2") == "W/A0 [N/mm²]" and style.axis_label("A/A0", "1") == "A/A0"


def test_save_writes_png_and_pdf(tmp_path):
    fig = style.new_figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1], label="a line")
    style.legend_outside(fig, ax)
    png = style.save(fig, tmp_path / "f.png")
    assert png.read_bytes()[:4] == b"\x89PNG" and (tmp_path / "f.pdf").read_bytes()[:4] == b"%PDF"
    assert fig.get_layout_engine() is not None  # constrained layout


def test_gallery_verdicts():
    assert gallery.verdict_of([]) == ("none", "no numerical claim")
    rows = [{"verdict": "reproduced"}, {"verdict": "not reproduced"}]
    assert gallery.verdict_of(rows)[0] == "partly" and "1 of 2" in gallery.verdict_of(rows)[1]
    assert gallery.verdict_of(rows[:1])[0] == "reproduced"


def test_nothing_is_clipped_in_the_fig18_point_panels():
    """The review of issue 15 saw Fig. 18's point figure cut its right x-label at the edge
    ("[um"): the three panels share one x-label now, and no text leaves the figure."""
    import numpy as np

    from roughcontact.paper import plots

    u = np.linspace(0.0, 10.0, 50)
    panels = {f"case ({c})": (u, np.sin(u), np.cos(u), u, u) for c in "abc"}
    fig = plots.friction_cases(panels, xlabel=style.axis_label("imposed slip path, loading then unloading", "um"),
                               ylabel=style.axis_label("traction", "N/mm^2"))
    assert style.texts_outside(fig) == []
    renderer = fig.canvas.get_renderer()  # and the legend does not cover the shared x-label
    legend, label = fig.legends[0].get_window_extent(renderer), fig._supxlabel.get_window_extent(renderer)
    assert not legend.overlaps(label)


def test_texts_outside_sees_a_clipped_label():
    fig = style.new_figure(figsize=(2.0, 2.0))
    ax = fig.add_subplot()
    ax.set_xlabel("a label much longer than the two inches of this figure can hold [um]")
    assert style.texts_outside(fig) == ["a label much longer than the two inches of this figure can hold [um]"]
