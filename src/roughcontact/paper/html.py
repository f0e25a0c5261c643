"""The reports as pages a browser shows: paper_figures/VERIFICATION.md and the Markdown pages it
links (docs/errata.md, …) rendered as HTML beside the gallery, and the paper's formulas typeset
for the gallery and those pages (no script, no network: a page opens offline as it is).

* :func:`typeset` — plain text with ASCII mathematics (``delta = (pi m00/2)^(1/2)``, ``A_G/A_B``,
  ``sqrt(beta1)``) as HTML with Unicode Greek letters, √ and ``<sub>``/``<sup>``;
* :func:`render_page` — one Markdown text as a whole HTML page (markdown-it-py: CommonMark and
  tables), headings carrying GitHub's anchors (the ones the reports link to), formulas typeset,
  every link and image passed through a ``rewrite`` function;
* :func:`plan_site` — which Markdown files a page reaches through relative links, and where each
  one's HTML goes, so that links between the rendered pages stay links between HTML pages and
  links to any other file of the repository still resolve.

Pure functions: the workflow script reads the files and writes what these return.
"""

from __future__ import annotations

import html as _html
import os
import re
from pathlib import PurePosixPath
from typing import Callable, Mapping

__all__ = ["STYLE", "typeset", "slug", "markdown_links", "render_page", "plan_site", "link_rewriter"]

#: the pages' look (shared by the gallery)
STYLE = """
body { font-family: sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em; color: #222; line-height: 1.45; }
figure { margin: 0; }
img { max-width: 100%; border: 1px solid #ddd; }
section { border-top: 1px solid #ccc; padding: 1em 0; }
.verdict { font-weight: bold; }
.reproduced { color: #1e8449; } .not { color: #b03a2e; } .partly { color: #b9770e; } .none { color: #555; }
table { border-collapse: collapse; font-size: 0.9em; margin: 0.5em 0; }
td, th { border: 1px solid #ddd; padding: 0.2em 0.5em; vertical-align: top; text-align: left; }
code { font-size: 0.92em; background: #f4f4f4; padding: 0 0.2em; }
pre { background: #f4f4f4; padding: 0.6em; overflow-x: auto; }
sub, sup { font-size: 0.75em; line-height: 0; }
nav { font-size: 0.9em; color: #555; }
"""

_GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "kappa": "κ", "lambda": "λ", "mu": "μ",
    "nu": "ν", "omega": "ω", "phi": "φ", "pi": "π", "psi": "ψ", "sigma": "σ", "theta": "θ",
}
_LETTER = r"[A-Za-zα-ω]"
# a Greek name as a whole symbol: alone, or followed by an index digit or a subscript
_GREEK_WORD = re.compile(r"(?<![A-Za-z0-9])(" + "|".join(_GREEK) + r")(?=\d|_|(?![\w]))")
# the paper's indexed symbols: m00 … m04 (moments), A0, f1 … f4, α1, β2, …
_INDEXED = re.compile(r"(?<![\w.])(m)(00|20|02|40|04|11|22|31|13)(?![\w])|(?<![\w.])(A)(0)(?![\w])"
                      r"|(?<![\w.])(f)([1-4])(?![\w])|(?<![\w.])([α-ω])([0-9])(?![\w])")
# sqrt(x) with x free of parentheses
_SQRT = re.compile(r"(?<![\w])sqrt\(([^()]*)\)")
_SIMPLE = re.compile(r"^[\w.]+(<sub>[\w.]+</sub>)?$")
# a subscript of a one-letter symbol: A_G, u_N, μ_x, k_Ty, p_m (not fe_punch or fig18_point)
_SUB = re.compile(r"(?<![\w])(" + _LETTER + r")_([A-Za-z0-9α-ω]{1,3})(?![\w])")
# a superscript: ^(1/2), ^{…}, ^2, ^p
_SUP = re.compile(r"\^(?:\(([^()]*)\)|\{([^{}]*)\}|([A-Za-z0-9α-ω]+))")


def typeset(text: str) -> str:
    """``text`` (plain, ASCII mathematics) as HTML: escaped, Greek names as letters, the paper's
    indexed symbols and ``x_y`` with subscripts, ``x^y`` and ``x^(…)`` with superscripts,
    ``sqrt(x)`` as √x. Names of files, scenes and variables (``fig18_point``) stay as they are."""
    out = _html.escape(str(text), quote=False)
    out = _GREEK_WORD.sub(lambda m: _GREEK[m.group(1)], out)
    out = _INDEXED.sub(lambda m: "".join(f"{b}<sub>{i}</sub>" for b, i in zip(m.groups()[::2], m.groups()[1::2]) if b),
                       out)
    out = _SUB.sub(r"\1<sub>\2</sub>", out)

    def root(m):
        arg = m.group(1).strip()
        return f"√{arg}" if _SIMPLE.match(arg) else f"√({arg})"

    out = _SQRT.sub(root, out)
    out = re.sub(r"(?<=[\w>]) \. (?=[\w&])", " · ", out)  # a dot product: t_T . u_T^p
    return _SUP.sub(lambda m: f"<sup>{next(g for g in m.groups() if g is not None)}</sup>", out)


def slug(heading: str) -> str:
    """GitHub's anchor of a Markdown heading's text (lower case, punctuation but - and _ dropped,
    spaces → -); the reports' links use it."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def _parser():
    from markdown_it import MarkdownIt

    return MarkdownIt("commonmark", {"html": False}).enable("table")


def _inline_text(token) -> str:
    return "".join(c.content for c in (token.children or []) if c.type in ("text", "code_inline"))


def markdown_links(text: str) -> list[str]:
    """Every link target and image source of a Markdown text (not those inside code)."""
    out = []
    for token in _parser().parse(text):
        for child in token.children or []:
            if child.type == "link_open":
                out.append(child.attrGet("href"))
            elif child.type == "image":
                out.append(child.attrGet("src"))
    return out


def render_page(text: str, *, title: str, rewrite: Callable[[str], str] = lambda href: href,
                nav: Mapping[str, str] | None = None) -> str:
    """A Markdown text as a complete HTML page: headings with GitHub's anchors (duplicates
    numbered -1, -2, … as GitHub does), formulas in the text typeset (code stays verbatim),
    every link and image source passed through ``rewrite``; ``nav`` {label: href} links on top."""
    md = _parser()
    tokens = md.parse(text)
    seen: dict[str, int] = {}
    for i, token in enumerate(tokens):
        if token.type == "heading_open":
            anchor = slug(_inline_text(tokens[i + 1]))
            n = seen.get(anchor, 0)
            seen[anchor] = n + 1
            token.attrSet("id", anchor if n == 0 else f"{anchor}-{n}")
        for child in token.children or []:
            if child.type == "link_open":
                child.attrSet("href", rewrite(child.attrGet("href")))
            elif child.type == "image":
                child.attrSet("src", rewrite(child.attrGet("src")))

    renderer = md.renderer
    renderer.rules["text"] = lambda tokens, idx, options, env: typeset(tokens[idx].content)
    body = renderer.render(tokens, md.options, {})
    links = " · ".join(f"<a href='{_html.escape(h)}'>{_html.escape(label)}</a>" for label, h in (nav or {}).items())
    return "\n".join([
        "<!DOCTYPE html>", "<html lang='en'><head><meta charset='utf-8'>",
        f"<title>{_html.escape(title)}</title>", f"<style>{STYLE}</style></head><body>",
        f"<nav>{links}</nav>" if links else "", body, "</body></html>", ""])


def _split(href: str) -> tuple[str, str]:
    path, _, fragment = href.partition("#")
    return path, fragment


def _is_relative(href: str | None) -> bool:
    return bool(href) and not re.match(r"^[a-zA-Z][\w+.-]*:", href) and not href.startswith(("/", "#"))


def plan_site(start: str, read: Callable[[str], str | None], out_of: Callable[[str], str]) -> dict[str, str]:
    """{Markdown file: its HTML file} of ``start`` and every Markdown file it reaches through
    relative links (paths relative to the repository, POSIX). ``read(path)`` gives a file's
    text or None where it does not exist; ``out_of(path)`` where its HTML goes."""
    plan, todo = {}, [start]
    while todo:
        src = todo.pop()
        if src in plan:
            continue
        text = read(src)
        if text is None:
            continue
        plan[src] = out_of(src)
        for href in markdown_links(text):
            path, _ = _split(href)
            if _is_relative(path) and path.endswith(".md"):
                target = os.path.normpath(str(PurePosixPath(src).parent / path))
                if not target.startswith(".."):
                    todo.append(target)
    return plan


def link_rewriter(src: str, plan: Mapping[str, str]) -> Callable[[str], str]:
    """How the page of ``src`` rewrites a link: to a rendered page → its HTML (the anchor kept);
    to any other file of the repository → a path relative to the HTML page; the rest as is."""
    out_dir = PurePosixPath(plan[src]).parent

    def rewrite(href: str) -> str:
        path, fragment = _split(href or "")
        if not _is_relative(path):
            return href
        target = os.path.normpath(str(PurePosixPath(src).parent / path))
        new = os.path.relpath(plan.get(target, target), out_dir)
        return new + (f"#{fragment}" if fragment else "")

    return rewrite
