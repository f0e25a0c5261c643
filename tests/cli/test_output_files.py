"""Every file a command writes goes through one helper (roughcontact.cli.output_file / writing):
a bad name is one line with exit 2 before anything is computed, nothing is created on the way,
and the file is written atomically under exactly the name given (issue 22)."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

from roughcontact import cli
from roughcontact.readers import read_height_map
from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.synthetic import synthetic_surface

TABLE1 = ["--m00", "0.0625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6", "--m04", "1.04e-4"]
EXPORT = ["export", "--format", "csv", *TABLE1, "--E-star", "1.127e5", "--pressure-range", "1e-3", "10"]
BEAM = ["fe", "beam", "--m00", "0.625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6", "--m04", "1.04e-4"]
PUNCH = ["fe", "punch", "--case", "a"]


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def height_map(tmp_path_factory):
    z = synthetic_surface(SpectralMoments(1.0, 1.0, 9.0, 2.0, 243.0), (48, 64), 0.4, 0.4, seed=3, lay_angle_deg=20.0)
    path = tmp_path_factory.mktemp("map") / "map.npy"
    np.save(path, z)
    return path


def _commands(height_map):
    return {"export -o": [*EXPORT, "-o"], "moments --save-rotated": ["moments", height_map, "--dx", "0.4",
                                                                     "--save-rotated"],
            "fe beam --vtu": [*BEAM, "--vtu"], "fe punch --vtu": [*PUNCH, "--vtu"]}


@pytest.mark.parametrize("command", ["export -o", "moments --save-rotated", "fe beam --vtu", "fe punch --vtu"])
@pytest.mark.parametrize("target, message", [
    ("{missing}/x.out", "no such directory"),     # -o /nonexistent/x.csv: a traceback before
    ("{tmp}", "is a directory"),                  # -o /tmp: a traceback before
    ("", "an empty file name"),                   # -o '': "wrote 78 rows" and nothing written before
    ("{tmp}/sub/", "is a directory"),
    ("/dev/null", "not a regular file"),          # an atomic rename onto it would replace the device
])
def test_bad_output_names_are_one_line_before_any_computation(capsys, tmp_path, height_map, monkeypatch, command,
                                                             target, message):
    # nothing may be computed first: the FE runs would take seconds, and fail loudly here
    monkeypatch.setattr("roughcontact.examples.beam.run_beam", lambda *a, **k: pytest.fail("computed before checking"))
    monkeypatch.setattr("roughcontact.examples.punch.run_punch", lambda *a, **k: pytest.fail("computed before checking"))
    path = target.format(missing=tmp_path / "nonexistent", tmp=tmp_path)
    code, out, err = run(capsys, *_commands(height_map)[command], path)
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and message in err, err
    assert err.startswith("roughcontact: error: argument")
    assert not (tmp_path / "nonexistent").exists() and not (tmp_path / "sub").exists()  # nothing created


def test_unwritable_directory_is_one_line(capsys, tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        if os.access(locked, os.W_OK):
            pytest.skip("running as a user who may write anywhere (root)")
        code, out, err = run(capsys, *EXPORT, "-o", locked / "t.csv")
        assert code == 2 and len(err.splitlines()) == 1 and "not writable" in err
    finally:
        locked.chmod(0o700)


def test_write_failure_is_one_line(capsys, tmp_path, monkeypatch):
    """An OSError while writing (disk full, ...) is one line, and no partial file is left."""
    def full(self, *args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("pathlib.Path.write_text", full)
    code, out, err = run(capsys, *EXPORT, "-o", tmp_path / "t.csv")
    assert code == 2 and len(err.splitlines()) == 1 and "No space left on device" in err and "-o" in err
    assert list(tmp_path.iterdir()) == []


def test_export_writes_atomically_under_the_given_name(capsys, tmp_path, monkeypatch):
    seen = []
    real = cli.atomic_path

    def spy(path):
        seen.append(path)
        return real(path)

    monkeypatch.setattr(cli, "atomic_path", spy)
    target = tmp_path / "table.csv"
    code, out, err = run(capsys, *EXPORT, "-o", target)
    assert code == 0 and target.is_file() and seen == [target]
    assert out.startswith(f"wrote ") and str(target) in out
    assert [p.name for p in tmp_path.iterdir()] == ["table.csv"]  # no temporary left behind


@pytest.mark.parametrize("name", ["rot.npy", "rot.txt", "rot.csv", "rot"])
def test_save_rotated_writes_exactly_the_named_file_and_reads_back(capsys, tmp_path, height_map, name):
    """--save-rotated rot.txt wrote rot.txt.npy before; now the file is the name given: .npy as
    NumPy's format, any other name a text grid that `roughcontact moments` reads back."""
    target = tmp_path / name
    code, out, err = run(capsys, "moments", height_map, "--dx", "0.4", "--save-rotated", target, "--json")
    assert code == 0, err
    assert [p.name for p in tmp_path.iterdir()] == [name]
    back = read_height_map(target).heights if name != "rot" else np.loadtxt(target, ndmin=2)
    z = np.load(height_map)
    assert back.shape == z.shape and np.isnan(back).any() and np.isfinite(back).any()  # NaN outside the map
    assert oct(target.stat().st_mode & 0o777) == oct(0o666 & ~_umask())


def _umask():
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@pytest.mark.slow
def test_fe_vtu_writes_both_files_in_an_existing_directory(capsys, tmp_path):
    target = tmp_path / "beam.vtu"
    code, out, err = run(capsys, *BEAM, "--n-x", "4", "--n-z", "2", "--increments", "2", "--elements", "quadratic",
                         "--quiet", "--vtu", target, "--json")
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["beam.vtu", "beam_interface.vtu"]
    assert json.loads(out)["vtu"] == str(target)


def test_export_pressure_range_beyond_the_model_is_one_line(capsys):
    """--pressure-range 0.1 1e300 ended in a RuntimeError traceback."""
    code, out, err = run(capsys, *EXPORT[:-2], "0.1", "1e300")
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and "not reached by the model" in err, err
