"""roughcontact.files: atomic writes with the mode the umask allows (issue #12)."""

import os
import stat

import pytest

from roughcontact import io
from roughcontact.files import atomic_path
from roughcontact.paper import plots


@pytest.fixture
def umask_022():
    old = os.umask(0o022)
    yield 0o022
    os.umask(old)


def _mode(path):
    return stat.S_IMODE(path.stat().st_mode)


def test_written_files_honour_the_umask(tmp_path, umask_022):
    """Reports were 0600 (tempfile.mkstemp's mode kept by os.replace): unreadable to others."""
    text = io.write_text(tmp_path / "VERIFICATION.md", "x\n")
    assert _mode(text) == 0o644
    fig = plots.new_figure()
    fig.add_subplot().plot([0, 1])
    png = plots.save(fig, tmp_path / "fig.png")
    assert _mode(png) == 0o644 and png.read_bytes()[:4] == b"\x89PNG"
    os.umask(0o077)
    assert _mode(io.write_text(tmp_path / "private.md", "y\n")) == 0o600


def test_a_failed_write_leaves_neither_the_target_nor_a_temporary(tmp_path):
    target = tmp_path / "out.md"
    target.write_text("old\n")
    with pytest.raises(RuntimeError):
        with atomic_path(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("killed")
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["out.md"]


def test_png_is_written_under_a_temporary_name_first(tmp_path, monkeypatch):
    """plots.save goes through atomic_path: savefig never sees the final name."""
    seen = []
    fig = plots.new_figure()
    original = fig.savefig
    monkeypatch.setattr(fig, "savefig", lambda p, **kw: (seen.append(str(p)), original(p, **kw)))
    plots.save(fig, tmp_path / "f.png")
    assert seen and seen[0].endswith(".part") and (tmp_path / "f.png").exists()


def test_a_hard_kill_leaves_a_temporary_that_the_next_run_removes(tmp_path):
    """Issue 22: SIGKILL inside atomic_path (no cleanup runs) left paper_figures/.fig18.pdf.*.part;
    the workflow's onstart calls remove_partial_files on its output folders."""
    import signal
    import subprocess
    import sys

    from roughcontact.files import remove_partial_files

    (tmp_path / "paper_figures").mkdir()
    code = ("import sys, time\nfrom roughcontact.files import atomic_path\n"
            f"with atomic_path({str(tmp_path / 'paper_figures' / 'fig18.pdf')!r}) as tmp:\n"
            "    tmp.write_bytes(b'%PDF half'); print(tmp, flush=True); time.sleep(600)\n")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    part = proc.stdout.readline().strip()
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=60)
    assert os.path.basename(part).startswith(".fig18.pdf.") and os.path.exists(part)
    keep = tmp_path / "paper_figures" / "fig18.png"
    keep.write_bytes(b"png")
    assert remove_partial_files(tmp_path / "paper_figures", tmp_path / "absent") == [tmp_path / "paper_figures" / os.path.basename(part)]
    assert sorted(p.name for p in (tmp_path / "paper_figures").iterdir()) == ["fig18.png"]
