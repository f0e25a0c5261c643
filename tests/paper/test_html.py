"""roughcontact.paper.html: the formulas typeset for a reader (issue 22: the gallery printed
"delta = (pi m00/2)^(1/2)…"), the reports rendered as HTML pages with GitHub's anchors and
their links rewritten between the rendered pages."""

import re
from pathlib import Path

import yaml

from roughcontact.paper import gallery, html

ROOT = Path(__file__).resolve().parents[2]
ASCII_MATH = re.compile(r"sqrt\(|\^|\b(alpha|beta|delta|lambda|psi|pi|mu|nu|omega|kappa|sigma|theta)\d*\b|\bm(00|20|02|40|04)\b"
                        r"|\b[A-Za-z]_[A-Za-z0-9]")


def _visible(markup: str) -> str:
    """The text with each tag as one mark (m<sub>00</sub> → m§00§, no longer an "m00")."""
    return re.sub(r"<[^>]+>", "§", markup)


def test_typeset_the_papers_formulas():
    assert html.typeset("delta = (pi m00/2)^(1/2)(sqrt(beta1) + sqrt(beta2))") == (
        "δ = (π m<sub>00</sub>/2)<sup>1/2</sup>(√β<sub>1</sub> + √β<sub>2</sub>)")
    assert html.typeset("tan(beta) = tan(alpha) (nu_y/nu_x)^2") == "tan(β) = tan(α) (ν<sub>y</sub>/ν<sub>x</sub>)<sup>2</sup>"
    assert html.typeset("t_N mu_alpha; D = t_T . u_T^p") == "t<sub>N</sub> μ<sub>α</sub>; D = t<sub>T</sub> · u<sub>T</sub><sup>p</sup>"
    assert html.typeset("c = 1/sqrt(5), W/(H A0), f1(e)") == "c = 1/√5, W/(H A<sub>0</sub>), f<sub>1</sub>(e)"
    # names of scenes, files and variables, and markup in the text, stay as they are
    assert html.typeset("fig18_point fe_punch_readings.md E7 <b>") == "fig18_point fe_punch_readings.md E7 &lt;b&gt;"


def test_no_ascii_formula_reaches_the_gallery():
    """Every caption, claim and note of config/gallery.yaml and every prose claim of
    config/config.yaml, as the gallery shows them."""
    entries = yaml.safe_load((ROOT / "config" / "gallery.yaml").read_text())["figures"]
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    claims = [c["text"] for sc in config["scenes"].values() for c in sc.get("claims", [])]
    rows = {name: [{"description": text, "verdict": "reproduced", "detail": "psi = 0.35: A^p/A = 1e-9"}
                   for text in claims] if name == "fig5" else [] for name in entries}
    verdicts = {name: ("none", "—") for name in entries}
    page = gallery.render(entries, rows, verdicts, "test")
    body = page.split("<body>", 1)[1]
    shown = [_visible(m) for m in re.findall(r"<(?:figcaption|p|td)>(.*?)</(?:figcaption|p|td)>", body, flags=re.S)]
    leftovers = [s for s in shown if ASCII_MATH.search(s)]
    assert leftovers == []
    assert "δ = (π m<sub>00</sub>/2)<sup>1/2</sup>(√β<sub>1</sub> + √β<sub>2</sub>)" in page
    assert "VERIFICATION.md" not in page and "href='VERIFICATION.html'" in page


def test_gallery_says_which_optional_scenes_were_skipped():
    summary = {"passed": True, "checks": 3, "reproduced": 3, "not_reproduced": 0, "known": 0, "regressions": 0,
               "improved": 0, "skipped": 11,
               "coverage": {"skipped": [{"scene": "calculix", "requires": "ccx", "checks": 11,
                                         "install": "apt-get install calculix-ccx"}]}}
    page = gallery.render({}, {}, {}, "test", summary=summary)
    assert "Verification PASSED" in page and "11 skipped" in page
    assert "calculix</b> (11 checks): skipped: ccx not installed — <code>apt-get install calculix-ccx</code>" in page


def test_render_page_anchors_links_and_code():
    text = ("# Report\n\n## E11: R_m = (R' + R'')^1/2\n\n## Summary\n\n## Summary\n\n"
            "See [E11](../docs/errata.md#e11-r_m--r--r12), [the FE table](fe_benchmark.md) and "
            "[a test](../tests/test_io.py); `alpha1` stays code, alpha1 does not.\n\n"
            "| a | b |\n|---|---|\n| psi | 1 |\n")
    plan = {"paper_figures/VERIFICATION.md": "paper_figures/VERIFICATION.html",
            "docs/errata.md": "paper_figures/html/docs/errata.html",
            "paper_figures/fe_benchmark.md": "paper_figures/html/fe_benchmark.html"}
    page = html.render_page(text, title="Report", rewrite=html.link_rewriter("paper_figures/VERIFICATION.md", plan))
    assert 'id="e11-r_m--r--r12"' in page and 'id="summary"' in page and 'id="summary-1"' in page
    assert 'href="html/docs/errata.html#e11-r_m--r--r12"' in page
    assert 'href="html/fe_benchmark.html"' in page and 'href="../tests/test_io.py"' in page
    assert "<code>alpha1</code>" in page and "α<sub>1</sub> does not" in page
    assert "<table>" in page and "<td>ψ</td>" in page


def test_plan_site_follows_relative_markdown_links_only():
    files = {"paper_figures/VERIFICATION.md": "[e](../docs/errata.md) [x](https://doi.org/x) [f](fig.png)",
             "docs/errata.md": "[i](investigations/area_columns.md#top) [back](../paper_figures/VERIFICATION.md) [gone](gone.md)",
             "docs/investigations/area_columns.md": "# A\n"}
    plan = html.plan_site("paper_figures/VERIFICATION.md", files.get, lambda p: p.replace(".md", ".html"))
    assert sorted(plan) == ["docs/errata.md", "docs/investigations/area_columns.md", "paper_figures/VERIFICATION.md"]
