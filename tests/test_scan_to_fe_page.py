"""docs/scan-to-fe.md runs end to end: its code blocks (python, then the shell commands) are
extracted from the page and run in order in an empty directory, so the page cannot drift from
the code (issue 20). The `roughcontact` lines run the command's entry point in this process (the
console script calls the same ``roughcontact.cli.main``; one import instead of ten), with the
page's ``> FILE`` redirections; other lines run in a shell."""

from __future__ import annotations

import contextlib
import io
import re
import shlex
import subprocess
from pathlib import Path

import pytest

from roughcontact import cli
from roughcontact.interface.export import parse_table

PAGE = Path(__file__).resolve().parents[1] / "docs" / "scan-to-fe.md"
BLOCK = re.compile(r"^```(python|sh)\n(.*?)^```", re.MULTILINE | re.DOTALL)


def blocks():
    return BLOCK.findall(PAGE.read_text())


def test_the_page_has_the_whole_chain():
    text = "\n".join(code for _, code in blocks())
    for step in ("to_x3p(", "roughcontact moments scan.x3p --json > surface.json", "--moments surface.json",
                 "roughcontact plot", "roughcontact export --format calculix"):
        assert step in text, step
    figures = re.findall(r"\]\((figures/[^)]+)\)", PAGE.read_text())
    assert figures and all((PAGE.parent / f).is_file() for f in figures)


def run_line(line: str, cwd: Path) -> None:
    """One shell line of the page: ``roughcontact ARGS [> FILE]`` through cli.main, else bash."""
    words = shlex.split(line)
    if words[0] != "roughcontact":
        r = subprocess.run(line, shell=True, cwd=cwd, capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, (line, r.stderr)
        return
    target = None
    if ">" in words:
        words, target = words[:words.index(">")], words[words.index(">") + 1]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main(words[1:])
    assert code == 0, (line, err.getvalue())
    if target:
        (cwd / target).write_text(out.getvalue())


def test_every_command_of_the_page_runs(tmp_path, monkeypatch):
    pytest.importorskip("SurfaceTopography")  # the page's scan is an .x3p (the measure extra)
    monkeypatch.chdir(tmp_path)
    for kind, code in blocks():
        if kind == "python":
            exec(compile(code, str(PAGE), "exec"), {"__name__": "__page__"})
            continue
        for line in code.splitlines():
            if line.strip():
                run_line(line, tmp_path)
    assert (tmp_path / "scales.png").stat().st_size > 0 and (tmp_path / "curves.png").stat().st_size > 0
    pressure, overclosure = parse_table((tmp_path / "contact.inp").read_text())
    assert pressure[0] == 0.0 and pressure[-1] == pytest.approx(100.0, rel=1e-6) and len(pressure) > 50
