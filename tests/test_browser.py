"""The pages as a reader sees them, in a real headless browser (Debian's chromium, driven through
the DevTools protocol: tests/_browser.py): every link resolves, every #anchor exists, every image
loads — in the gallery with the HTML verification report and the guides it links, and in the
built documentation (issue 22: the gallery linked VERIFICATION.md as raw Markdown).

Marker ``browser`` (deselected by default; CI runs it after ``snakemake verify gallery`` and
``make docs``, which write what the last two tests check; the first renders a small fixture).
Skipped, with one line, where chromium is not installed.
"""

import importlib.util
import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("_browser", Path(__file__).with_name("_browser.py"))
browser = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(browser)

pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(browser.chromium() is None, reason="chromium is not installed (apt-get install chromium)")]

#: the guides the built documentation must contain (issue 22), each a page with text
GUIDES = ["fe", "fe-export", "interface", "errata", "derivation", "performance", "independent-studies",
          "architecture", "own-surface", "sweeps"]


@pytest.fixture(scope="module")
def chromium():
    with browser.Browser(browser.chromium()) as b:
        yield b


def _script(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "workflow" / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _fixture_site(tmp_path):
    """A gallery of two figures (real PNGs), a verification report with a skipped optional scene
    and errata links, rendered to HTML as the workflow renders them, in a copy of docs/."""
    from roughcontact.paper import gallery, plots, report, verify

    shutil.copytree(ROOT / "docs", tmp_path / "docs", ignore=shutil.ignore_patterns("_build"))
    figures = tmp_path / "paper_figures"
    figures.mkdir()
    for name in ("fig3", "fig5"):
        fig = plots.new_figure(figsize=(3, 2))
        fig.add_subplot().plot([0, 1], [1, 0])
        plots.save(fig, figures / f"{name}.png")  # the PNG and its PDF
    checks = [verify.Check(id="claim:fig5/psi", kind="claim", scene="fig5", verdict="reproduced",
                           detail="A^p/A = 1e-9 at psi = 0.35", description="At small psi the ratio A^p/A is very small")]
    checks = verify.apply_expectations(checks, {})
    data = {"expected_checks": {"fig5": 1, "calculix": {"checks": 11, "requires": "ccx", "install": "apt-get install calculix-ccx"}}}
    summary = verify.summarize(checks, verify.check_coverage(checks, data, tools=()))
    errata = report.parse_errata((ROOT / "docs" / "errata.md").read_text())
    (figures / "fe_benchmark.md").write_text("# FE speed\n\n| job | s |\n|---|---|\n| beam | 1.0 |\n")
    md = report.render_verification_markdown(checks, errata=errata, summary=summary,
                                             sections={"FE speed and size": "[fe_benchmark.md](fe_benchmark.md)"})
    (figures / "VERIFICATION.md").write_text(md)
    entries = {"fig3": {"caption": "A_G/A_B against s = h/sqrt(m00) for alpha1, alpha2"},
               "fig5": {"caption": "A^p/A vs W/(H A0) for psi", "claim": "delta = (pi m00/2)^(1/2)"}}
    rows = {"fig5": [{k: str(v) for k, v in c.__dict__.items()} for c in checks]}
    verdicts = {"fig3": gallery.verdict_of([]), "fig5": gallery.verdict_of(rows["fig5"])}
    (figures / "index.html").write_text(gallery.render(entries, rows, verdicts, "test", summary=summary))
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        _script("verification_html").run("paper_figures/VERIFICATION.html", "paper_figures/html", "log.txt")
    finally:
        os.chdir(cwd)
    return tmp_path


def test_gallery_and_html_report_of_a_fixture(chromium, tmp_path):
    site = _fixture_site(tmp_path)
    result = browser.crawl(chromium, site / "paper_figures" / "index.html", site)
    assert result["problems"] == []
    # the gallery, the report, fe_benchmark and the errata with the pages they link
    assert result["pages"] >= 5 and result["images"] == 2
    report = (site / "paper_figures" / "VERIFICATION.html").read_text()
    assert "<table>" in report and "../docs/errata.md" not in report and "html/docs/errata.html#e1-" in report
    assert "skipped: ccx not installed" in report
    # the checker sees what is broken
    (site / "paper_figures" / "fig5.png").unlink()
    (site / "paper_figures" / "html" / "docs" / "independent-studies.html").unlink()
    problems = browser.crawl(chromium, site / "paper_figures" / "index.html", site)["problems"]
    assert any("image did not load" in p and "fig5.png" in p for p in problems), problems
    assert any("missing file" in p and "independent-studies.html" in p for p in problems), problems


@pytest.mark.skipif(not (ROOT / "paper_figures" / "index.html").exists(),
                    reason="no gallery yet (snakemake verify gallery writes it)")
def test_the_workflows_gallery_and_report(chromium):
    result = browser.crawl(chromium, ROOT / "paper_figures" / "index.html", ROOT)
    assert result["problems"] == []
    assert result["images"] >= 20 and result["pages"] >= 3


@pytest.mark.skipif(not (ROOT / "docs" / "_build" / "html" / "index.html").exists(),
                    reason="no built documentation (make docs writes it)")
def test_the_built_documentation(chromium):
    html = ROOT / "docs" / "_build" / "html"
    result = browser.crawl(chromium, html / "index.html", html)
    assert result["problems"] == []
    for guide in GUIDES:
        page = chromium.inspect((html / f"{guide}.html").as_uri())
        assert page["title"] and page["text"] > 1000, guide  # rendered, not an empty shell
