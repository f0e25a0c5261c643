"""roughcontact plot (issue 29): `--label a b` says the flag repeats; a label matplotlib cannot
typeset, a full disk under -o and a RESULT.json too deep or not a file are each one line (exit 2),
with nothing left under the figure's name."""

from __future__ import annotations

import errno
import json
import os

import pytest

pytest.importorskip("matplotlib")

from roughcontact import io  # noqa: E402
from roughcontact.plots import style  # noqa: E402

#: a contact result as `roughcontact elastic --json` writes it (only what plot reads)
RESULT = {"s": [1.0, 2.0, 3.0], "area_fraction": [0.1, 0.02, 0.002], "pressure": [2000.0, 300.0, 20.0],
          "stiffness": [1.9e4, 2.6e3, 200.0], "length_unit": "um"}
NESTED_SQRT = "$" + r"\sqrt{" * 60 + "x" + "}" * 60 + "$"


@pytest.fixture
def results(tmp_path):
    paths = []
    for name in ("a.json", "b.json"):
        (tmp_path / name).write_text(json.dumps(RESULT))
        paths.append(tmp_path / name)
    return paths


def _leftovers(folder):
    return sorted(p.name for p in folder.iterdir() if p.suffix in (".png", ".pdf", ".svg", ".part"))


def test_label_with_two_words_says_the_flag_repeats(cli_run, results, tmp_path):
    out = tmp_path / "f.png"
    code, _, err = cli_run("plot", *results, "-o", out, "--label", "a", "b")
    assert code == 2 and len(err.splitlines()) == 1, err
    assert "--label a --label b" in err and "repeat" in err, err  # before: "unrecognized arguments: b"
    code, _, err = cli_run("plot", *results, "-o", out, "--label=a", "b")
    assert code == 2 and "--label a --label b" in err, err
    assert not out.exists()
    code, _, err = cli_run("plot", *results, "-o", out, "--label", "a", "--label", "b")
    assert code == 0 and out.stat().st_size > 0, err


@pytest.mark.parametrize("label, match", [(NESTED_SQRT, "nested too deeply"), (r"$\frac{a$", "not valid mathtext")])
def test_a_label_that_cannot_be_typeset_is_one_line_naming_it(cli_run, results, tmp_path, label, match):
    """Before: a RecursionError traceback (nested \\sqrt) or a bare pyparsing message, while saving."""
    out = tmp_path / "f.png"
    code, _, err = cli_run("plot", results[0], "-o", out, "--label", label)
    assert code == 2 and len(err.splitlines()) == 1, err
    assert err.startswith("roughcontact: error: --label '$") and match in err, err
    assert "Traceback" not in err and _leftovers(tmp_path) == []


def test_a_unit_that_cannot_be_typeset_names_its_option(cli_run, results, tmp_path):
    code, _, err = cli_run("plot", results[0], "-o", tmp_path / "f.png", "--stress-unit", r"$\frac{N$")
    assert code == 2 and "--stress-unit" in err and len(err.splitlines()) == 1, err


def _disk_full(monkeypatch):
    """Figure.savefig writes part of the file, then the disk is full (OSError 28), as on a real full disk."""
    from matplotlib.figure import Figure

    def savefig(self, fname, **kwargs):
        with open(fname, "wb") as f:
            f.write(b"\x89PNG partial")
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(fname))

    monkeypatch.setattr(Figure, "savefig", savefig)


def test_a_full_disk_under_o_is_one_line_naming_the_option(cli_run, results, tmp_path, monkeypatch):
    out = tmp_path / "f.png"
    out.write_bytes(b"the figure of an earlier run")
    _disk_full(monkeypatch)
    code, _, err = cli_run("plot", *results, "-o", out)
    assert code == 2 and len(err.splitlines()) == 1, err  # before: an OSError traceback
    assert f"-o: figure {out}" in err and "No space left on device" in err and "the disk is full" in err, err
    assert out.read_bytes() == b"the figure of an earlier run"  # nothing half-written under the name
    assert [p.name for p in tmp_path.iterdir() if p.name.endswith(".part")] == []


@pytest.mark.parametrize("saver", ["save_figure", "save"])
def test_the_save_helpers_raise_one_line_write_errors(tmp_path, monkeypatch, saver):
    """What `moments --plot` relies on: the helper's OSError is a one-line ValueError (io.WriteError)
    naming the file, and nothing is left under its name."""
    fig = style.new_figure()
    fig.add_subplot(1, 1, 1).plot([0, 1], [0, 1])
    _disk_full(monkeypatch)
    with pytest.raises(io.WriteError, match="the disk is full") as info:
        getattr(style, saver)(fig, tmp_path / "m.png")
    assert isinstance(info.value, ValueError) and "\n" not in str(info.value)
    assert str(tmp_path / "m.png") in str(info.value)
    assert list(tmp_path.iterdir()) == []


def test_a_result_nested_50000_deep_is_one_line(cli_run, results, tmp_path):
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 50_000 + "]" * 50_000)
    code, _, err = cli_run("plot", deep, "-o", tmp_path / "f.png")
    assert code == 2 and len(err.splitlines()) == 1 and "nested deeper than" in err, err  # before: RecursionError
    assert "ROUGHCONTACT_MAX_NESTING" in err


def test_a_result_that_is_a_fifo_or_nan_is_one_line(cli_run, results, tmp_path):
    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)
    code, _, err = cli_run("plot", fifo, "-o", tmp_path / "f.png")  # before: blocked on the pipe
    assert code == 2 and "not a regular file" in err and len(err.splitlines()) == 1, err
    nan = tmp_path / "nan.json"
    nan.write_text(json.dumps(RESULT).replace("2000.0", "NaN"))
    code, _, err = cli_run("plot", nan, "-o", tmp_path / "f.png")
    assert code == 2 and "NaN is not JSON" in err, err


def test_units_valid_alone_but_not_together_are_one_line(cli_run, results, tmp_path):
    """'$\\frac{N' and 'um$' are plain text each, '$\\frac{N/um$' in the stiffness axis is not."""
    out = tmp_path / "f.png"
    code, _, err = cli_run("plot", results[0], "-o", out, "--stress-unit", r"$\frac{N", "--length-unit", "um$")
    assert code == 2 and len(err.splitlines()) == 1 and "cannot be typeset" in err, err
    assert not out.exists()


def test_a_file_name_that_is_bad_mathtext_asks_for_label(cli_run, tmp_path):
    path = tmp_path / "$\\frac{a$.json"
    path.write_text(json.dumps(RESULT))
    code, _, err = cli_run("plot", path, "-o", tmp_path / "f.png")
    assert code == 2 and "give --label" in err and len(err.splitlines()) == 1, err
    code, _, err = cli_run("plot", path, "-o", tmp_path / "f.png", "--label", "plain")
    assert code == 0, err


@pytest.mark.parametrize("key, value", [("s", [1.0, True, 3.0]), ("pressure", ["1", "2", "3"]), ("stiffness", [1.0]),
                                        ("area_fraction", True), ("length_unit", ["um"])])
def test_a_result_with_non_numbers_names_the_file_and_key(cli_run, tmp_path, key, value):
    path = tmp_path / "r.json"
    path.write_text(json.dumps({**RESULT, key: value}))
    code, _, err = cli_run("plot", path, "-o", tmp_path / "f.png")
    assert code == 2 and len(err.splitlines()) == 1 and f"{path}: {key} must be" in err, err
