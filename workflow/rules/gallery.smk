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
    """paper_figures/index.html: every figure beside its caption, claim and verdict."""
    localrule: True
    input:
        entries="config/gallery.yaml",
        code=["src/roughcontact/paper/gallery.py", "src/roughcontact/plots/style.py"],
        figures=gallery_inputs(),
    output:
        "paper_figures/index.html",
    log:
        "logs/gallery.log",
    script:
        "../scripts/gallery.py"
