# The figure gallery: paper_figures/index.html shows every regenerated figure with the paper's
# caption, its claim and the verdict of its checks (config/gallery.yaml lists them).

import yaml

with open("config/gallery.yaml", encoding="utf-8") as _fh:
    GALLERY = yaml.safe_load(_fh)["figures"]


def gallery_inputs():
    pngs = [f"paper_figures/{name}.png" for name in GALLERY]
    checks = sorted({f"results/verify/{c}.checks.csv" for e in GALLERY.values() for c in e.get("checks", [])})
    geometry = [f"results/geometry/{e['geometry']}.json" for e in GALLERY.values() if "geometry" in e]
    return pngs + checks + geometry


rule gallery:
    """paper_figures/index.html: every figure beside its caption, claim and verdict, the
    verification's summary and skipped optional scenes on top, the HTML report linked."""
    localrule: True
    input:
        entries="config/gallery.yaml",
        code=library_sources("paper/gallery.py", "plots/style.py", "paper/html.py"),
        figures=gallery_inputs(),
        summary="results/verify/summary.json",
        report="paper_figures/VERIFICATION.html",
    output:
        "paper_figures/index.html",
    log:
        "logs/gallery.log",
    script:
        "../scripts/gallery.py"


def _markdown_pages(wildcards):
    """The guides a rendered report may link (every Markdown file under docs/)."""
    return sorted(str(p.relative_to(REPO)) for p in (REPO / "docs").rglob("*.md") if "_build" not in p.parts)


rule verification_html:
    """paper_figures/VERIFICATION.html and, under paper_figures/html/, every Markdown page it
    reaches through relative links (docs/errata.md, …), rendered with markdown-it-py, formulas
    typeset, links between them rewritten to the HTML (roughcontact.paper.html)."""
    localrule: True
    input:
        report="paper_figures/VERIFICATION.md",
        pages=_markdown_pages,
        code=library_sources("paper/html.py"),
    output:
        html="paper_figures/VERIFICATION.html",
        pages=directory("paper_figures/html"),
    log:
        "logs/verification_html.log",
    script:
        "../scripts/verification_html.py"
