"""The process entry point (``roughcontact`` and ``python -m roughcontact``): cli.main, then
every object frozen out of the cyclic collector so that the interpreter's exit does not walk
them (cli.entry_point's docstring has the measurement); tests call cli.main, which does not."""

import importlib.metadata
import subprocess
import sys

from roughcontact import __version__, cli


def test_entry_point_runs_main_then_freezes(monkeypatch):
    calls = []
    monkeypatch.setattr(cli, "main", lambda: calls.append("main") or 7)
    monkeypatch.setattr(cli.gc, "freeze", lambda: calls.append("freeze"))
    assert cli.entry_point() == 7
    assert calls == ["main", "freeze"]


def test_main_does_not_freeze(monkeypatch):
    monkeypatch.setattr(cli.gc, "freeze", lambda: (_ for _ in ()).throw(AssertionError("froze")))
    assert cli.main(["--version"]) == 0


def test_console_script_and_module_use_the_entry_point():
    scripts = importlib.metadata.entry_points(group="console_scripts")
    assert scripts["roughcontact"].value == "roughcontact.cli:entry_point"
    r = subprocess.run([sys.executable, "-m", "roughcontact", "--version"], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0 and r.stdout.strip() == f"roughcontact {__version__}"


def test_ctrl_c_in_any_command_is_one_line_and_exit_130(monkeypatch, capsys):
    """Issue 29: Ctrl-C printed a traceback (only `fe run` caught it)."""
    from roughcontact.statistics.surface import SpectralMoments

    def interrupted(self):
        raise KeyboardInterrupt

    monkeypatch.setattr(SpectralMoments, "summary", interrupted)
    code = cli.main(["surface", "--m00", "1", "--m20", "1e-4", "--m02", "1e-3", "--m40", "1e-6", "--m04", "1e-4"])
    out, err = capsys.readouterr()
    assert code == cli.EXIT_INTERRUPTED == 130
    assert out == "" and err == "roughcontact: error: interrupted\n"


def test_an_arithmetic_error_of_the_computation_is_one_line_and_exit_1(capsys):
    """Issue 29's audit kind, found by a sweep of extreme options: m00 = 1e23 um^2 with --psi 1
    derives a yield strength 2e4 times E*, and the elasto-plastic kernel divided by zero
    (a ZeroDivisionError traceback)."""
    code = cli.main(["elastoplastic", "--m00", "99999999999999999999999", "--m20", "8e-5", "--m02", "8e-4",
                     "--m40", "1.04e-6", "--m04", "1.04e-4", "--E-star", "114000", "--psi", "1", "--s", "1"])
    out, err = capsys.readouterr()
    assert code == 1 and out == "" and len(err.splitlines()) == 1
    assert err.startswith("roughcontact: error: the computation failed for these inputs (ZeroDivisionError")
