"""Draw an element figure of section 9 (Figs 11, 12, 16, 17) from the engine's own element
definitions: the PNG and the node table (label, local index, reference coordinates, kind) as CSV."""

from roughcontact import io
from roughcontact.fe.element import ELEMENTS
from roughcontact.fe.interface_element import INTERFACES
from roughcontact.paper import drawings, plots, report


def _element(element_name):
    if element_name in INTERFACES:
        return INTERFACES[element_name]
    if element_name in ELEMENTS:
        return ELEMENTS[element_name]
    raise ValueError(f"unknown element {element_name!r} (have {sorted(ELEMENTS) + sorted(INTERFACES)})")


def csv_text(element_name):
    """The node table of the element named ``element_name`` as CSV (what run writes)."""
    return report.render_rows_csv(drawings.node_table(_element(element_name)),
                                  units={"xi": "1", "eta": "1", "zeta": "1"})  # natural coordinates


def draw(element_name, title):
    """(Figure, CSV text) of the element or interface element named ``element_name``."""
    element = _element(element_name)
    if element_name in INTERFACES:
        fig = drawings.interface_figure(element, title=title)
    else:
        fig = drawings.element_figure(element, title=title)
    return fig, csv_text(element_name)


def run(element_name, title, out, log):
    with io.log_to(log) as logger:
        fig, table = draw(element_name, title)
        plots.save(fig, out["png"])
        io.write_text(out["csv"], table)
        logger.info("%s: %s, %d nodes", out["png"], element_name, table.count("\n") - 1)


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.element, sm.params.title, {"png": sm.output.png, "csv": sm.output.csv}, sm.log[0])
