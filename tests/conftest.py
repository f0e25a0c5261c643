"""Shared fixtures.

``hide_programs``: an environment whose PATH lacks the named programs (issue 22: every optional
tool's absent path runs for real, also on a machine that has the tool). Each PATH directory that
holds one of them is replaced by a directory of symlinks to everything else in it; the other
directories (the venv's bin among them, whose python finds its pyvenv.cfg only from there) stay.
Nothing is uninstalled.
"""

import os
import shutil
from pathlib import Path

import pytest


def env_without(programs, where) -> dict[str, str]:
    """os.environ with a PATH on which none of ``programs`` is found (symlink dirs under ``where``)."""
    hidden = set(programs)
    parts = []
    for i, d in enumerate(os.environ.get("PATH", "").split(os.pathsep)):
        path = Path(d)
        if not d or not path.is_dir() or not any((path / p).exists() for p in hidden):
            parts.append(d)
            continue
        links = Path(where) / f"path{i}"
        links.mkdir(parents=True)
        for entry in path.iterdir():
            if entry.name not in hidden:
                (links / entry.name).symlink_to(entry)
        parts.append(str(links))
    env = {**os.environ, "PATH": os.pathsep.join(parts)}
    assert all(shutil.which(p, path=env["PATH"]) is None for p in hidden), env["PATH"]
    return env


@pytest.fixture
def hide_programs(tmp_path_factory):
    """``hide_programs("ccx", ...)`` → an environment (dict) whose PATH lacks those programs."""

    def make(*programs):
        return env_without(programs, tmp_path_factory.mktemp("hidden-path"))

    return make


@pytest.fixture(autouse=True)
def _no_cached_summit_tables():
    """Each test starts without cached summit tables: route="auto" (contact.elastoplastic, the
    default) takes the table route where a table of the same (surface, Hertz option, accuracy,
    material) is cached in the process, so a test's route — and with it attributes such as
    ``interpolation`` (the τ route's s-interpolation) — would depend on which tests ran before
    it. Values do not: both routes are within the preset's bound."""
    from roughcontact.contact.elastoplastic import clear_table_cache

    clear_table_cache()
    yield
