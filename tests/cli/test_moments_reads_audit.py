"""Issue 29 (A1) through the command: `roughcontact moments FILE` on files that were read silently
wrong or ended in a traceback. Right values are compared with the same map given in a form the
command always read right (.npy with --dx and the units stated)."""

from __future__ import annotations

import importlib.util
import os

import numpy as np
import pytest

RNG = np.random.default_rng(291)
Y, X = np.mgrid[0:48, 0:64]
Z = np.sin(0.3 * X) + 0.5 * np.cos(0.2 * Y) + 0.1 * RNG.normal(size=X.shape)  # rows along y


def one_line_error(cli_run, *args):
    code, out, err = cli_run("moments", *args)
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and err.startswith("roughcontact: error: "), err
    return err


def xyz(path, x, y, z, header):
    path.write_text(header + "\n" + "\n".join(f"{a:.17g} {b:.17g} {c:.17g}" for a, b, c in zip(x, y, z)) + "\n")


def test_a_map_in_metres_without_a_unit_is_warned_about(cli_run, cli_json, tmp_path):
    """m00 ~ 1e-13 "µm²", dx = 1.25e-6 "µm" with no warning: now a warning naming the file and the
    options; with them, the moments of the same map in µm."""
    xyz(tmp_path / "m.xyz", X.ravel() * 1.25e-6, Y.ravel() * 1.25e-6, Z.ravel() * 1e-7, "x y z")
    code, out, err = cli_run("moments", tmp_path / "m.xyz", "--json")
    assert code == 0
    warning = [line for line in err.splitlines() if "implausible" in line]
    assert len(warning) == 1 and str(tmp_path / "m.xyz") in warning[0] and "look like metres" in warning[0]
    assert warning[0].endswith("pass --xy-unit m --z-unit m")
    np.save(tmp_path / "um.npy", Z * 0.1)
    stated = cli_json("moments", tmp_path / "m.xyz", "--xy-unit", "m", "--z-unit", "m")
    reference = cli_json("moments", tmp_path / "um.npy", "--dx", "1.25")
    assert not any("implausible" in n for n in stated["source"]["notes"])
    assert stated["dx"] == pytest.approx(1.25) and stated["m00"] == pytest.approx(reference["m00"], rel=1e-9)
    assert stated["m40"] == pytest.approx(reference["m40"], rel=1e-9)


def test_a_vendor_csv_header(cli_json, tmp_path):
    lines = ['"Instrument","Profiler 3000"', '"XY calibration","1.25","um/pixel"', '"Z unit","nm"']
    (tmp_path / "v.csv").write_text("\n".join(lines) + "\n"
                                    + "\n".join(",".join(f'"{100 * v:.4f}"' for v in row) for row in Z) + "\n")
    d = cli_json("moments", tmp_path / "v.csv")
    np.save(tmp_path / "nm.npy", np.round(100 * Z, 4))
    reference = cli_json("moments", tmp_path / "nm.npy", "--dx", "1.25", "--z-unit", "nm")
    assert d["dx"] == d["dy"] == pytest.approx(1.25) and d["source"]["units_in_file"] == {"xy": "um", "z": "nm"}
    for k in ("m00", "m20"):
        assert d[k] == pytest.approx(reference[k], rel=1e-9)


def test_a_grid_with_a_coordinate_row_and_column(cli_json, tmp_path):
    head = "," + ",".join(f"{0.5 * j:g}" for j in range(64))
    body = "\n".join(f"{0.25 * i:g}," + ",".join(f"{v:.17g}" for v in row) for i, row in enumerate(Z))
    (tmp_path / "c.csv").write_text(head + "\n" + body + "\n")
    d = cli_json("moments", tmp_path / "c.csv")
    np.save(tmp_path / "z.npy", Z)
    reference = cli_json("moments", tmp_path / "z.npy", "--dx", "0.5", "--dy", "0.25")
    assert d["shape"] == [48, 64] and (d["dx"], d["dy"]) == (pytest.approx(0.5), pytest.approx(0.25))
    for k in ("m00", "m02"):
        assert d[k] == pytest.approx(reference[k], rel=1e-12)
    assert any("first row and column are coordinates" in n for n in d["source"]["notes"])


def test_xyz_with_x_in_mm_and_y_in_um(cli_json, tmp_path):
    xyz(tmp_path / "mixed.xyz", X.ravel() * 5e-4, Y.ravel() * 0.25, Z.ravel(), "x [mm] y [um] z [um]")
    d = cli_json("moments", tmp_path / "mixed.xyz")
    assert (d["dx"], d["dy"]) == (pytest.approx(0.5), pytest.approx(0.25))
    np.save(tmp_path / "z.npy", Z)
    reference = cli_json("moments", tmp_path / "z.npy", "--dx", "0.5", "--dy", "0.25")
    assert d["m02"] == pytest.approx(reference["m02"], rel=1e-9)


def write_gsf(path, xres):
    header = f"Gwyddion Simple Field 1.0\nXRes = {xres}\nYRes = 64\nXReal = 1e-5\nYReal = 1e-5\n".encode()
    path.write_bytes(header + b"\0" * (4 - len(header) % 4) + np.zeros(64 * 64, dtype="<f4").tobytes())


def test_bad_files_are_one_line(cli_run, tmp_path, monkeypatch):
    (tmp_path / "bad.x3p").write_bytes(np.random.default_rng(3).bytes(5000))
    if importlib.util.find_spec("SurfaceTopography") is not None:  # the measure extra
        assert "not a readable .x3p file" in one_line_error(cli_run, tmp_path / "bad.x3p")
    (tmp_path / "empty.npy").write_bytes(b"")
    assert "empty.npy: not a .npy array" in one_line_error(cli_run, tmp_path / "empty.npy", "--dx", "1")
    with open(tmp_path / "big.npy", "wb") as f:
        np.lib.format.write_array_header_1_0(f, {"descr": "<f8", "fortran_order": False, "shape": (10000, 10000)})
    assert "ROUGHCONTACT_MAX_CELLS" in one_line_error(cli_run, tmp_path / "big.npy", "--dx", "1")
    for xres in (0, -64):
        write_gsf(tmp_path / "x.gsf", xres)
        assert f"XRes = {xres}: the number of points" in one_line_error(cli_run, tmp_path / "x.gsf")
    os.mkfifo(tmp_path / "fifo.csv")
    assert "not a regular file" in one_line_error(cli_run, tmp_path / "fifo.csv", "--dx", "1")
    assert "/dev/zero: not a regular file" in one_line_error(cli_run, "/dev/zero", "--layout", "grid", "--dx", "1")
    x = X.ravel().astype(float)
    x[100] = 1e7
    xyz(tmp_path / "outlier.xyz", x, Y.ravel(), Z.ravel(), "x y z")
    assert "line 102: the point x = 1e+07, y = 1 lies far off" in one_line_error(cli_run, tmp_path / "outlier.xyz")
    np.savetxt(tmp_path / "big.csv", Z, delimiter=",")
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "0.01")
    assert "ROUGHCONTACT_MAX_INPUT_MB" in one_line_error(cli_run, tmp_path / "big.csv", "--dx", "1")


def test_a_spacing_given_in_metres_as_micrometres_is_warned_about(cli_run, tmp_path):
    """The plausibility check judges the spacing the command uses: --dx 1.25e-6 read in µm (a
    1.25 pm interval) on a .npy that states no unit, and the warning is in the JSON's warnings."""
    import json

    np.save(tmp_path / "m.npy", Z * 1e-7)
    code, out, err = cli_run("moments", tmp_path / "m.npy", "--dx", "1.25e-6", "--json")
    assert code == 0
    (warning,) = [line for line in err.splitlines() if "implausible" in line]
    assert "sampling interval of 1.25e-06 um" in warning and "rms height" in warning
    assert any("implausible" in w and "sampling interval" in w for w in json.loads(out)["warnings"])


def test_too_few_points_names_the_file(cli_run, tmp_path):
    np.save(tmp_path / "tiny.npy", Z[:2, :3])
    err = one_line_error(cli_run, tmp_path / "tiny.npy", "--dx", "1")
    assert str(tmp_path / "tiny.npy") in err and "at least" in err
