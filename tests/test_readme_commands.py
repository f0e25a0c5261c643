"""Every command of the README runs (issue 33: "a test keeps every command of the README runnable").

Each line of the README's code blocks is a command (a trailing ``\\`` continues it, ``#`` starts a
comment). A ``make X`` has its target (``make -n X`` succeeds: the Makefile plans it without
running it); a ``roughcontact ...`` runs for real, in the README's order (the later commands read
what the earlier wrote), in a scratch directory that sees the repository's docs/examples/, and
exits 0 with the outputs its redirections and ``-o`` name. Any other command in a code block of
the README fails the test: add it here, with a way to run it, or leave it out of the README.
The example inputs are shipped: docs/examples/scan.npy (docs/examples/make_scan.py writes it,
checked here) and docs/examples/block.inp with block.yaml.
"""

import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"


def code_blocks(text: str) -> list[tuple[str, list[str]]]:
    """(language, lines) of every fenced block of a Markdown text."""
    blocks, current, language = [], None, ""
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            if current is None:
                current, language = [], line.strip()[3:].strip()
            else:
                blocks.append((language, current))
                current = None
        elif current is not None:
            current.append(line)
    assert current is None, "an unclosed code block"
    return blocks


def _without_comment(line: str) -> str:
    """The line up to a ``#`` that starts a word outside quotes (the shell's comment)."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1].isspace()):
            return line[:i]
    return line


def commands(text: str) -> list[str]:
    """Every command line of the text's code blocks, continuations joined, comments removed."""
    out = []
    for _language, lines in code_blocks(text):
        pending = ""
        for line in lines:
            line = pending + line
            if line.rstrip().endswith("\\"):
                pending = line.rstrip()[:-1] + " "
                continue
            pending = ""
            line = _without_comment(line)
            if line.strip():
                out.append(" ".join(line.split()))
        assert not pending, "a continuation ends the block"
    return out


README_COMMANDS = commands(README.read_text())
MAKE = [c for c in README_COMMANDS if c.split()[0] == "make"]
ROUGHCONTACT = [c for c in README_COMMANDS if c.split()[0] == "roughcontact"]


def test_the_extraction_sees_what_it_should():
    text = ("# t\n\n```sh\nmake a   # comment\nroughcontact p 'a # b' > o.json  # c\nroughcontact x \\\n    --y 1 > out.json\n```\n\ntext `make b`\n\n"
            "```\n# a comment line\nmake c\n```\n")
    assert commands(text) == ["make a", "roughcontact p 'a # b' > o.json", "roughcontact x --y 1 > out.json", "make c"]


def test_the_readme_starts_with_the_two_commands_and_has_only_commands_this_test_runs():
    blocks = code_blocks(README.read_text())
    assert blocks[0] == ("sh", ["make reproduce", "make test"])
    assert README.read_text().split("\n")[2:6] == ["```sh", "make reproduce", "make test", "```"]
    assert all(language == "sh" for language, _ in blocks), [language for language, _ in blocks]
    assert set(README_COMMANDS) == set(MAKE) | set(ROUGHCONTACT), README_COMMANDS
    assert len(ROUGHCONTACT) >= 5 and any(" fe run " in f" {c} " for c in ROUGHCONTACT)


@pytest.mark.parametrize("command", sorted(set(MAKE)))
def test_every_make_target_of_the_readme_exists(command):
    if shutil.which("make") is None:
        pytest.skip("make is not installed here")
    words = command.split()
    assert all(not w.startswith("-") for w in words[1:]), command
    r = subprocess.run(["make", "-n", *words[1:]], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, f"{command}: {r.stderr[-2000:]}"


def _shell_env(tmp_path: Path) -> dict:
    """`roughcontact` as installed beside this interpreter, else `python -m roughcontact`."""
    env = dict(os.environ)
    bindir = tmp_path / "bin"
    bindir.mkdir()
    script = Path(sys.executable).parent / "roughcontact"
    wrapper = bindir / "roughcontact"
    target = shlex.quote(str(script)) if script.exists() else f"{shlex.quote(sys.executable)} -m roughcontact"
    wrapper.write_text(f'#!/bin/sh\nexec {target} "$@"\n')
    wrapper.chmod(0o755)
    env["PATH"] = f"{bindir}{os.pathsep}{env.get('PATH', '')}"
    env["MPLBACKEND"] = "Agg"
    return env


def _outputs(command: str) -> list[str]:
    """The files a command names as its output: `> FILE` and `-o FILE`."""
    words = shlex.split(command)
    return [words[i + 1] for i, w in enumerate(words[:-1]) if w in (">", "-o", "--output")]


def test_every_roughcontact_command_of_the_readme_runs(tmp_path):
    """In the README's order, in a scratch directory whose docs/ is the repository's."""
    if shutil.which("bash") is None:
        pytest.skip("bash is not installed here")
    work = tmp_path / "work"
    work.mkdir()
    (work / "docs").symlink_to(ROOT / "docs", target_is_directory=True)
    env = _shell_env(tmp_path)
    for command in ROUGHCONTACT:
        r = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=work, env=env, capture_output=True,
                           text=True, timeout=300)
        assert r.returncode == 0, f"{command}\nexit {r.returncode}\n{r.stdout[-2000:]}\n{r.stderr[-3000:]}"
        for name in _outputs(command):
            assert (work / name).is_file() and (work / name).stat().st_size > 0, (command, name)
        if "--json" in command.split() and ">" not in command.split():
            import json

            json.loads(r.stdout)


def test_the_example_scan_is_what_its_script_writes():
    sys.path.insert(0, str(ROOT / "docs" / "examples"))
    try:
        import make_scan
    finally:
        sys.path.pop(0)
    shipped = np.load(ROOT / "docs" / "examples" / "scan.npy")
    assert shipped.dtype == np.float32 and shipped.shape == (128, 128)
    np.testing.assert_allclose(shipped, make_scan.scan(), rtol=0, atol=1e-6)
    # the README reads it with the sampling interval it was written with
    assert any(c.startswith("roughcontact moments docs/examples/scan.npy --dx 1 ") for c in README_COMMANDS)
