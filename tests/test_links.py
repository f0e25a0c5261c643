"""Nothing in the repository points at something that is not there (issue 22: NOTES.md and
ARCHITECTURE.md were cited but lived outside the repository; tests/test_cli.py and
contact._theta_nodes had been renamed; benchmarks/fe_beam.py never existed).

* every relative link — Markdown ``[…](…)`` and images, reST `` `…<…>`_ `` and image/figure
  targets, HTML ``href``/``src`` — of a tracked file resolves to a file of the repository, and a
  ``#anchor`` into a Markdown file to one of its headings (GitHub's anchors, as the built
  documentation and the rendered reports use them);
* every repository path named in text (``src/…``, ``tests/…``, ``docs/…``, ``config/…``,
  ``workflow/…``, ``benchmarks/…``, ``investigations/…``) exists — relative to the repository or to the
  naming file, with or without its suffix, or as ``module.attribute`` of an existing module;
* no file points outside the repository (a link escaping it, the shared notes of the
  project's start, absolute paths of the development machine).

The built documentation's links are checked in a browser (tests/test_browser.py).
"""

import re
from urllib.parse import unquote
import subprocess
from pathlib import Path

import pytest

from roughcontact.paper.html import markdown_links, slug

ROOT = Path(__file__).resolve().parents[1]
#: generated folders a text may name (they exist after a run, not in a clone)
GENERATED = ("results", "paper_figures", "logs", "docs/_build", ".snakemake", ".venv")
TEXT = {".md", ".rst", ".py", ".yaml", ".yml", ".smk", ".toml", ".txt", ".cfg", ".sh", ".html", ".ini", ""}
NAMED_PATH = re.compile(r"(?<![\w./-])((?:src|tests|docs|config|workflow|benchmarks|investigations|\.ci)/[\w./-]*\w)")
OUTSIDE = re.compile(r"NOTES\.md|ARCHITECTURE\.md|\.\./shared|/work/|/root/|/home/\w")


def _tracked() -> list[Path]:
    try:
        out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=ROOT,
                             capture_output=True, text=True, check=True).stdout.split("\n")
        files = [ROOT / f for f in out if f]
    except (OSError, subprocess.CalledProcessError):  # an exported tree without git
        files = [p for p in ROOT.rglob("*") if not any(part in GENERATED or part == ".git" for part in p.parts)]
    return sorted(p for p in files if p.is_file() and p.suffix in TEXT and p.name != "_browser.py")


FILES = _tracked()


def _text(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return ""


def _md_anchors(path: Path) -> set[str]:
    """The GitHub anchors of a Markdown file's headings (outside code blocks)."""
    anchors, fence = set(), False
    for line in _text(path).splitlines():
        if line.lstrip().startswith("```"):
            fence = not fence
        elif not fence and (m := re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)):
            anchors.add(slug(re.sub(r"[`*]", "", m.group(1))))
    return anchors


def _links(path: Path) -> list[str]:
    text = _text(path)
    if path.suffix == ".md":
        return markdown_links(text)
    if path.suffix == ".rst":
        return (re.findall(r"`[^`<]*<([^>`]+)>`__?", text)
                + re.findall(r"^\s*\.\. (?:image|figure|include|literalinclude)::\s*(\S+)", text, flags=re.M))
    if path.suffix == ".html":
        return re.findall(r"""(?:href|src)=["']([^"']+)["']""", text)
    return []


def _relative(href: str) -> bool:
    return bool(href) and not re.match(r"^[a-zA-Z][\w+.-]*:", href) and not href.startswith(("#", "/", "{"))


def broken_links(files=FILES, root=ROOT) -> list[str]:
    bad = []
    for path in files:
        where = path.relative_to(root)
        for href in _links(path):
            href = unquote(href or "")
            if href.startswith("#") and path.suffix == ".md":
                if href[1:] not in _md_anchors(path):
                    bad.append(f"{where}: no heading for {href}")
                continue
            if not _relative(href):
                continue
            target_text, _, anchor = href.partition("#")
            target = (path.parent / target_text).resolve()
            if root not in target.parents:
                bad.append(f"{where}: {href} points outside the repository")
            elif not target.exists():
                bad.append(f"{where}: {href} does not exist")
            elif anchor and target.suffix == ".md" and anchor not in _md_anchors(target):
                bad.append(f"{where}: no heading for #{anchor} in {target.relative_to(root)}")
    return bad


def _exists(token: str, near: Path, root: Path) -> bool:
    if token.startswith(GENERATED) or "__pycache__" in token:
        return True
    for base in (root, near.parent):
        p = base / token
        if p.exists() or any(p.with_name(p.name + s).exists() for s in (".md", ".rst", ".py", ".smk")):
            return True
        module, _, attribute = token.rpartition(".")  # benchmarks/references.ReferenceCache
        if attribute and (base / f"{module}.py").exists():
            return True
    return False


def missing_named_paths(files=tuple(p for p in FILES if p.name != "test_links.py"), root=ROOT) -> list[str]:
    bad = []
    for path in files:
        text = _text(path)
        for m in NAMED_PATH.finditer(text):
            if text[m.end():m.end() + 1] in "{<*":  # a pattern, not a path
                continue
            if not _exists(m.group(1), path, root):
                bad.append(f"{path.relative_to(root)}: {m.group(1)} does not exist")
    return sorted(set(bad))


def test_relative_links_resolve():
    assert broken_links() == []


def test_named_repository_paths_exist():
    assert missing_named_paths() == []


def test_nothing_points_outside_the_repository():
    bad = [f"{p.relative_to(ROOT)}:{i + 1}: {line.strip()[:100]}" for p in FILES if p.name != "test_links.py"
           for i, line in enumerate(_text(p).splitlines()) if OUTSIDE.search(line)]
    assert bad == []


def test_the_checks_catch_what_they_are_for(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "src" / "roughcontact").mkdir(parents=True)
    (tmp_path / "src" / "roughcontact" / "io.py").write_text("")
    (tmp_path / "docs" / "errata.md").write_text("# Errata\n\n## E1: (15)\n")
    page = tmp_path / "docs" / "page.md"
    page.write_text("# Example\n\n[gone](no-such-page.md) [anchor](errata.md#no-such-erratum) [ok](#example)\n"
                    "[e1](errata.md#e1-15) [out](../../outside.md)\n\nSee tests/test_nonexistent.py and "
                    "src/roughcontact/io.py.\n")
    links = broken_links([page], root=tmp_path)
    assert [b.split(": ", 1)[1] for b in links] == ["no-such-page.md does not exist", "no heading for #no-such-erratum in docs/errata.md",
                                                    "../../outside.md points outside the repository"]
    assert missing_named_paths([page], root=tmp_path) == ["docs/page.md: tests/test_nonexistent.py does not exist"]


@pytest.mark.parametrize("name", ["NOTES.md", "ARCHITECTURE.md"])
def test_the_shared_notes_are_not_cited(name):
    assert not [p for p in FILES if p.name != "test_links.py" and name in _text(p)]


#: ``pip install roughcontact`` / ``'roughcontact[workflow]'``: a name pip would look up on a registry
REGISTRY_INSTALL = re.compile(r"pip install (?:-U |--upgrade )?['\"]?roughcontact(?:\[[\w,]+\])?['\"]?(?![\w@ ]*@)")


def test_install_commands_work_from_a_clone():
    """Issue 22: the documentation's front page said ``pip install roughcontact``, but the package is
    on no registry. The commands given are ``pip install .`` (a clone) or a git URL."""
    assert REGISTRY_INSTALL.search("``pip install roughcontact`` installs") and REGISTRY_INSTALL.search(
        "pip install 'roughcontact[workflow]'")
    assert not REGISTRY_INSTALL.search("pip install 'roughcontact @ git+<repository URL>'")
    bad = [f"{p.relative_to(ROOT)}:{i + 1}" for p in FILES if p.name != "test_links.py"
           for i, line in enumerate(_text(p).splitlines()) if REGISTRY_INSTALL.search(line)]
    assert bad == []
    for page in ("docs/index.rst", "README.md"):
        assert "pip install ." in _text(ROOT / page), page


def _prose(path: Path) -> str:
    """What a reader reads: a Markdown/reST file whole, a Python file's comments and docstrings
    (not its code, where ``contact`` or ``fe`` may be a local variable)."""
    import io
    import tokenize

    text = _text(path)
    if path.suffix != ".py":
        return text if path.suffix in (".md", ".rst") else ""
    out = []
    try:
        for tok in tokenize.generate_tokens(io.StringIO(text).readline):
            if tok.type == tokenize.COMMENT or (
                    tok.type == tokenize.STRING and tok.string.lstrip("rbuRBU").startswith(('"""', "'''"))):
                out.append(tok.string)
    except (tokenize.TokenError, SyntaxError):
        return ""
    return "\n".join(out)


def _resolves(dotted: str) -> bool:
    """``contact.elastic._theta_nodes`` → roughcontact.contact.elastic has _theta_nodes."""
    import importlib

    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module("roughcontact." + ".".join(parts[:i]))
        except ImportError:
            continue
        for attribute in parts[i:]:
            if not hasattr(obj, attribute):
                return False
            obj = getattr(obj, attribute)
        return True
    return False


def missing_named_attributes(files=None, root=ROOT) -> list[str]:
    """A name like ``contact._theta_nodes`` or ``roughcontact.files.atomic_path`` in the prose of
    src/, tests/, workflow/ and docs/ (benchmarks/ uses the standard library's ``statistics``)
    names a module or attribute of the package that exists; a YAML key (``config.yaml
    fe.punch.claims``) and a file name (``interface.md``) are not such names."""
    import pkgutil

    import roughcontact

    subpackages = sorted({m.name for m in pkgutil.iter_modules(roughcontact.__path__)} - {"__main__"})
    named = re.compile(r"(?<![\w./-])(?:roughcontact\.)?((?:%s)(?:\.\w+)+)" % "|".join(subpackages))
    if files is None:
        files = [p for p in FILES if p.name != "test_links.py" and p.relative_to(ROOT).parts[0] in
                 ("src", "tests", "workflow", "docs", "README.md")]
    bad = []
    for path in files:
        text = _prose(path)
        for m in named.finditer(text):
            if re.search(r"\.(md|py|rst|smk|ya?ml|nc|png|pdf|json|csv|html|log|txt|inp|vtu|npy)$", m.group(1)) or \
                    "yaml" in text[max(0, m.start() - 12):m.start()]:
                continue
            if not _resolves(m.group(1)):
                bad.append(f"{path.relative_to(root)}: {m.group(1)}")
    return sorted(set(bad))


def test_named_attributes_exist(tmp_path):
    """Issue 22: contact/elastoplastic.py pointed at ``contact._theta_nodes`` (it is
    contact.elastic._theta_nodes)."""
    page = tmp_path / "page.md"
    page.write_text("as contact._theta_nodes; see contact.elastic._theta_nodes, roughcontact.files.atomic_path, "
                    "docs/fe.md, interface.md and config.yaml fe.punch.claims\n")
    assert missing_named_attributes([page], root=tmp_path) == ["page.md: contact._theta_nodes"]
    assert missing_named_attributes() == []
