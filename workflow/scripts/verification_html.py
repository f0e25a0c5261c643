"""paper_figures/VERIFICATION.html and the pages it links (rule verification_html): thin, reads
the Markdown files, renders with roughcontact.paper.html, writes the HTML."""

import os
from pathlib import Path

from roughcontact import io
from roughcontact.paper import html

REPORT = "paper_figures/VERIFICATION.md"


def out_of(path, report_html, pages_dir):
    """Where a Markdown file's page goes: the report beside the gallery, the rest under
    ``pages_dir`` (paper_figures/<name>.md as <name>.html, a guide under docs/ in a docs/ folder there)."""
    if path == REPORT:
        return report_html
    rel = Path(path).relative_to("paper_figures") if path.startswith("paper_figures/") else Path(path)
    return str(Path(pages_dir) / rel.with_suffix(".html"))


def read(path):
    p = Path(path)
    return p.read_text(encoding="utf-8") if p.is_file() and not os.path.relpath(p).startswith("..") else None


def run(report_html, pages_dir, log):
    with io.log_to(log) as logger:
        plan = html.plan_site(REPORT, read, lambda path: out_of(path, report_html, pages_dir))
        Path(pages_dir).mkdir(parents=True, exist_ok=True)
        for src, out in plan.items():
            text = read(src)
            title = next((line[2:].strip() for line in text.splitlines() if line.startswith("# ")), src)
            here = Path(out).parent
            nav = {"gallery": os.path.relpath("paper_figures/index.html", here),
                   "verification report": os.path.relpath(report_html, here)}
            io.write_text(out, html.render_page(text, title=title, rewrite=html.link_rewriter(src, plan), nav=nav))
            logger.info("%s -> %s", src, out)


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.output.html, sm.output.pages, sm.log[0])
