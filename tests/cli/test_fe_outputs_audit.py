"""Issue 29 (B2): what `roughcontact fe run --vtu` and `fe beam` write and refuse.

* The .pvd's timesteps are plain numbers (``float()`` and ParaView read them), each the deck
  time of its increment.
* The series is whole or absent: an interrupted writer (Ctrl-C) leaves no folder or .pvd under
  the final names and keeps an earlier series intact, exit 130 and one line; a re-run with
  fewer increments leaves exactly its own files; concurrent writers into one OUT.pvd leave one
  run's series, whole; a temporary folder of a killed run is removed by the next run.
* `fe beam --moments FILE` gives the run of the same five numbers (converted from the file's
  unit); `fe beam --n-x 100000` is refused before anything is built.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import threading
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from roughcontact import cli
from roughcontact.fe import pvd
from roughcontact.fe.deck_run import run_deck_file

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "docs" / "examples"
SURFACE = {"m00": 0.625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}  # µm
COARSE = ["--n-x", "6", "--n-z", "2", "--elements", "quadratic", "--quiet", "--json"]


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    """The docs' block (4 + 2 increments) and a copy whose first step has 2 increments."""
    tmp = tmp_path_factory.mktemp("block")
    for f in EXAMPLES.iterdir():
        shutil.copy(f, tmp / f.name)
    text = (tmp / "block.inp").read_text()
    short = text.replace("*STATIC\n0.25, 1.", "*STATIC\n0.5, 1.")
    assert short != text
    (tmp / "short.inp").write_text(short)
    return tmp


@pytest.fixture(scope="module")
def results(model):
    return (run_deck_file(model / "block.inp", model / "block.yaml"),
            run_deck_file(model / "short.inp", model / "block.yaml"))


def _datasets(path: Path) -> list[dict]:
    return [dict(e.attrib) for e in ET.parse(path).getroot().iter("DataSet")]


def _assert_whole(path: Path, result) -> None:
    """The .pvd lists exactly the files of its folder, two per increment of ``result``, with
    its increments' times; nothing else (no temporaries) next to it."""
    sets = _datasets(path)
    folder = path.with_suffix("")
    listed = sorted(Path(s["file"]).name for s in sets)
    assert all(Path(s["file"]).parent.name == folder.name for s in sets)
    assert listed == sorted(p.name for p in folder.iterdir())
    assert len(listed) == 2 * len(result.increments)
    times = [float(s["timestep"]) for s in sets[::2]]
    assert times == [float(inc.time) for inc in result.increments]
    assert not [p for p in path.parent.iterdir() if p.name.startswith(".")]


def test_timesteps_are_plain_numbers_equal_to_the_deck_time(results, tmp_path):
    res, _ = results
    path = pvd.write_series(tmp_path / "out.pvd", res)
    text = path.read_text()
    assert "np." not in text
    stamps = re.findall(r'timestep="([^"]*)"', text)
    assert len(stamps) == 2 * len(res.increments)
    for k, inc in enumerate(res.increments):
        for stamp in stamps[2 * k: 2 * k + 2]:
            assert float(stamp) == float(inc.time)  # float() reads it, and it is the increment's time
    # the deck's times: step 1 in 4 increments of 0.25, step 2 (period 1) in 2 of 0.5
    assert [float(s) for s in stamps[::2]] == [0.25, 0.5, 0.75, 1.0, 1.5, 2.0]
    _assert_whole(path, res)


def test_an_interrupted_series_leaves_nothing_under_the_final_names(model, results, tmp_path, monkeypatch, capsys):
    calls = {"n": 0}
    real = pvd.write_points

    def interrupted(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 3:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(pvd, "write_points", interrupted)
    out = tmp_path / "out.pvd"
    code, stdout, err = run(capsys, "fe", "run", model / "block.inp", "--interface", model / "block.yaml", "--quiet",
                            "--vtu", out)
    assert code == 130 and stdout == ""
    assert err == f"roughcontact: error: interrupted; nothing written to {out}\n"
    assert list(tmp_path.iterdir()) == []  # no out.pvd, no out/, no temporary


def test_an_interrupted_rerun_keeps_the_earlier_series(results, tmp_path, monkeypatch):
    full, short = results
    path = pvd.write_series(tmp_path / "out.pvd", full)
    before = {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir()}

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(pvd, "write_mesh", interrupted)
    with pytest.raises(KeyboardInterrupt):
        pvd.write_series(path, short)
    _assert_whole(path, full)
    assert {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir()} == before


def test_ctrl_c_during_the_solve_is_exit_130(model, monkeypatch, capsys):
    from roughcontact.fe import deck_run

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(deck_run, "run_deck_file", interrupted)
    code, out, err = run(capsys, "fe", "run", model / "block.inp", "--interface", model / "block.yaml", "--quiet")
    assert (code, out, err) == (130, "", "roughcontact: error: interrupted\n")


def test_a_rerun_with_fewer_increments_leaves_exactly_its_own_files(model, results, tmp_path, capsys):
    full, short = results
    out = tmp_path / "out.pvd"
    for deck, result in (("block.inp", full), ("short.inp", short)):
        code, _, err = run(capsys, "fe", "run", model / deck, "--interface", model / "block.yaml", "--quiet",
                           "--vtu", out)
        assert code == 0, err
        _assert_whole(out, result)
    assert len(short.increments) == 4 < len(full.increments) == 6


def test_concurrent_writers_leave_one_whole_series(results, tmp_path):
    full, short = results
    path = tmp_path / "out.pvd"
    for _ in range(3):
        threads = [threading.Thread(target=pvd.write_series, args=(path, r)) for r in (full, short, full, short)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        n = len(_datasets(path)) // 2
        _assert_whole(path, full if n == len(full.increments) else short)


def test_the_temporary_folder_of_a_killed_run_is_removed_by_the_next(results, tmp_path):
    full, _ = results
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    pid = int(dead.stdout)  # a process that has ended: its pid is (almost surely) not reused yet
    stale = tmp_path / f".out.{pid}.0123abcd.part"
    stale.mkdir()
    (stale / "0001.vtu").write_text("half")
    other = tmp_path / ".other.part"  # not a series temporary of out.pvd: left alone
    other.mkdir()
    pvd.write_series(tmp_path / "out.pvd", full)
    assert not stale.exists() and other.exists()


# ---------------------------------------------------------------------------------------------
# fe beam
# ---------------------------------------------------------------------------------------------
def _numbers():
    return [a for name, value in SURFACE.items() for a in (f"--{name}", repr(value))]


def test_beam_moments_file_is_the_run_of_the_same_numbers(capsys, tmp_path):
    code, out, err = run(capsys, "fe", "beam", *_numbers(), *COARSE)
    assert code == 0, err
    by_hand = json.loads(out)
    (tmp_path / "um.json").write_text(json.dumps({**SURFACE, "unit": "um"}))
    # the same surface in nm: m00 × 10⁶, m40, m04 × 10⁻⁶ (slopes unchanged)
    nm = {"m00": SURFACE["m00"] * 1e6, "m20": SURFACE["m20"], "m02": SURFACE["m02"],
          "m40": SURFACE["m40"] * 1e-6, "m04": SURFACE["m04"] * 1e-6, "unit": "nm"}
    (tmp_path / "nm.json").write_text(json.dumps(nm))
    for name in ("um.json", "nm.json"):
        code, out, err = run(capsys, "fe", "beam", "--moments", tmp_path / name, *COARSE)
        assert code == 0, err
        by_file = json.loads(out)
        for key, value in SURFACE.items():
            assert by_file["moments"][key] == pytest.approx(value, rel=1e-12)
        for key in ("u_N_um", "p_N"):
            assert by_file[key] == pytest.approx(by_hand[key], rel=1e-9, abs=1e-12)
        assert by_file["u_N_centre_um"] == pytest.approx(by_hand["u_N_centre_um"], rel=1e-9)


def test_beam_without_moments_says_which(capsys):
    code, out, err = run(capsys, "fe", "beam", "--quiet")
    assert code == 2 and err == ("roughcontact: error: the moments are missing: --m00 --m20 --m02 --m40 --m04 "
                                 "(or --moments FILE.json)\n")


def test_beam_size_is_bounded_before_building(capsys, monkeypatch):
    from roughcontact.examples import beam

    def never(*args, **kwargs):
        raise AssertionError("the model was built")

    monkeypatch.setattr(beam, "run_beam", never)
    code, out, err = run(capsys, "fe", "beam", *_numbers(), "--n-x", "100000", "--quiet")
    assert code == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("roughcontact: error: --n-x 100000 --n-z 6: the model's unknowns (at most): ")
    assert "exceed the limit of 2000000" in err and "ROUGHCONTACT_MAX_FE_DOFS" in err
    monkeypatch.setenv("ROUGHCONTACT_MAX_FE_DOFS", "100")
    code, out, err = run(capsys, "fe", "beam", *_numbers(), "--n-x", "6", "--n-z", "2", "--quiet")
    assert code == 2 and "exceed the limit of 100 " in err


@pytest.mark.parametrize("command", [["beam", "--m00", "0.625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6",
                                      "--m04", "1.04e-4"], ["punch", "--case", "a"]])
def test_increments_beyond_a_steps_limit_name_the_option(capsys, command):
    """Not the example's generated deck (/tmp/beam.inp:2006, a file the user never wrote)."""
    code, out, err = run(capsys, "fe", *command, "--increments", "1000000000", "--quiet")
    assert (code, out) == (2, "")
    assert err == "roughcontact: error: --increments 1000000000: must lie in 1 ... 100000 (the increments of a step)\n"
