"""Fixtures of the command-line tests: run ``roughcontact ARGS`` in this process."""

from __future__ import annotations

import json

import pytest

from roughcontact import cli


@pytest.fixture
def cli_run(capsys):
    """cli_run(*argv) -> (exit code, stdout, stderr)."""
    def run(*argv):
        code = cli.main([str(a) for a in argv])
        out, err = capsys.readouterr()
        return code, out, err
    return run


@pytest.fixture
def cli_json(cli_run):
    """cli_json(*argv) -> the JSON printed with --json (the exit code must be 0)."""
    def run(*argv):
        code, out, err = cli_run(*argv, "--json")
        assert code == 0, err
        return json.loads(out)
    return run
