# Element drawings of section 9 (Figs 11, 12, 16, 17): PNG + node table (CSV), drawn from the
# engine's own element definitions, so that editing an element (or the drawing code) redraws
# it. Self-contained: needs nothing from common.smk.

#: figure → (element name in fe.element.ELEMENTS or fe.interface_element.INTERFACES, caption)
DRAWINGS = {
    "fig11": ("hex28", "Fig. 11: 28-node hexahedral transition element; c = 1/√5"),
    "fig12": ("interface32", "Fig. 12: 32-node cubic interface element of zero-thickness"),
    "fig16": ("hex21", "Fig. 16: 21-node hexahedral transition element"),
    "fig17": ("interface18", "Fig. 17: 18-node quadratic interface element of zero-thickness"),
}

# the modules whose code decides what a drawing shows (quadrature: the interface's points)
DRAWING_SOURCES = [
    "src/roughcontact/fe/element.py",
    "src/roughcontact/fe/interface_element.py",
    "src/roughcontact/fe/quadrature.py",
    "src/roughcontact/paper/drawings.py",
    "src/roughcontact/paper/plots.py",
    "src/roughcontact/plots/style.py",
]


rule drawing:
    """An element figure (PNG) and its node table (CSV)."""
    input:
        code=DRAWING_SOURCES,
    output:
        png="paper_figures/{drawing}.png",
        pdf="paper_figures/{drawing}.pdf",  # vector, beside the PNG (plots.style.save)
        csv="paper_figures/{drawing}.csv",
    log:
        "logs/drawing/{drawing}.log",
    wildcard_constraints:
        drawing="|".join(DRAWINGS),
    params:
        element=lambda w: DRAWINGS[w.drawing][0],
        title=lambda w: DRAWINGS[w.drawing][1],
    localrule: True
    script:
        "../scripts/drawing.py"


# One target rule per drawing, named after it: `snakemake fig11`.
for _drawing in DRAWINGS:

    rule:
        name:
            _drawing
        localrule: True
        input:
            f"paper_figures/{_drawing}.png",
            f"paper_figures/{_drawing}.csv",


# Figs 1 and 2 (config `geometry_figures`): a generated anisotropic surface with its mean planes,
# one asperity with its contact ellipse, drawn from the library.
GEOMETRY_FIGURES = list(config.get("geometry_figures", {}))


rule geometry_figure:
    """Fig. 1 or Fig. 2 (PNG + PDF), the drawn data (CSV) and the figure's numbers (JSON)."""
    input:
        code=["src/roughcontact/paper/geometry.py", "src/roughcontact/paper/plots.py",
              "src/roughcontact/plots/style.py", "src/roughcontact/statistics/synthetic.py",
              "src/roughcontact/statistics/surface.py", "src/roughcontact/asperity/ellipse.py"],
    output:
        png="paper_figures/{fig}.png",
        pdf="paper_figures/{fig}.pdf",
        csv="paper_figures/{fig}.csv",
        json="results/geometry/{fig}.json",
    log:
        "logs/geometry/{fig}.log",
    wildcard_constraints:
        fig="|".join(GEOMETRY_FIGURES) or "none",
    params:
        cfg=lambda w: config["geometry_figures"][w.fig],
        surface=lambda w: dict(config["surfaces"][config["geometry_figures"][w.fig]["surface"]]),
    localrule: True
    script:
        "../scripts/geometry_figure.py"


for _fig in GEOMETRY_FIGURES:

    rule:
        name:
            _fig
        localrule: True
        input:
            f"paper_figures/{_fig}.png",
            f"paper_figures/{_fig}.csv",
