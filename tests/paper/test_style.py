"""roughcontact.paper.style: units typeset from UDUNITS strings, legends as a person writes
them, PNG and PDF saved together."""

import pytest

from roughcontact.paper import gallery, style


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
