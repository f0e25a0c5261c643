"""roughcontact moments: files of every kind in, the moments in a stated unit out, warnings instead
of refusals where the moments are measurable, one-line errors where they are not."""

from __future__ import annotations

import math

import numpy as np
import pytest

from roughcontact.cli import moments as moments_command
from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.measure import ESTIMATORS, measure_heights
from roughcontact.statistics.synthetic import synthetic_surface

M = SpectralMoments(0.01, 0.001, 0.01, 3e-4, 0.03)  # µm; slopes ~0.1, m02/m20 = 10
Z = synthetic_surface(M, (96, 128), 0.25, seed=2, lay_angle_deg=25.0)


def test_choices_match_library():
    assert set(moments_command.ESTIMATORS) == set(ESTIMATORS)


@pytest.mark.parametrize("suffix", [".npy", ".csv", ".txt"])
def test_moments_of_a_file_equal_the_library(cli_run, cli_json, tmp_path, suffix):
    path = tmp_path / f"map{suffix}"
    if suffix == ".npy":
        np.save(path, Z)
    else:
        np.savetxt(path, Z, delimiter="," if suffix == ".csv" else " ", fmt="%.17g")
    d = cli_json("moments", path, "--dx", "0.25")
    ref = measure_heights(Z, 0.25)
    for k in ("m00", "m20", "m02", "m40", "m04"):
        assert d[k] == pytest.approx(ref.values[k], rel=1e-12), k
        assert d["uncertainty"][k] == pytest.approx(ref.uncertainty[k], rel=1e-12)
    assert d["lay_angle_deg"] == pytest.approx(ref.lay_angle_deg, rel=1e-12)
    assert d["unit"] == "um" and d["units"]["m40"] == "1/um^2" and d["source"]["units_read"]["assumed"]
    assert [s["factor"] for s in d["scales"]] == [1, 2, 4] and d["scales"][1]["dx"] == 0.5
    assert d["model"]["model_applies"] and d["warnings"] == [] and d["shape"] == [96, 128]
    code, out, err = cli_run("moments", path, "--dx", "0.25")
    assert code == 0 and "lay_angle_deg" in out and "at 2x dx" in out and "+- " in out


def test_units_from_a_gsf_file(cli_run, cli_json, tmp_path):
    """A .gsf with heights in nm and spacing in µm: converted to the output unit (um)."""
    ny, nx = Z.shape
    header = (f"Gwyddion Simple Field 1.0\nXRes = {nx}\nYRes = {ny}\nXReal = {nx * 0.25}\nYReal = {ny * 0.25}\n"
              "XYUnits = um\nZUnits = nm\n").encode()
    (tmp_path / "a.gsf").write_bytes(header + b"\0" * (4 - len(header) % 4) + (Z * 1000).astype("<f4").tobytes())
    d = cli_json("moments", tmp_path / "a.gsf")
    ref = measure_heights((Z * 1000).astype(np.float32).astype(float) * 1e-3, 0.25)
    assert d["m04"] == pytest.approx(ref.values["m04"], rel=1e-9) and d["dx"] == pytest.approx(0.25)
    assert d["source"]["units_in_file"] == {"xy": "um", "z": "nm"} and d["warnings"] == []


def test_an_x3p_file(cli_run, cli_json, tmp_path):
    st = pytest.importorskip("SurfaceTopography")
    st.Topography(Z.T.copy(), physical_sizes=(128 * 0.25, 96 * 0.25), unit="um").to_x3p(str(tmp_path / "a.x3p"))
    d = cli_json("moments", tmp_path / "a.x3p")
    assert d["source"]["format"] == "x3p" and d["source"]["units_in_file"] == {"xy": "m", "z": "m"}
    assert d["m40"] == pytest.approx(measure_heights(Z, 0.25).values["m40"], rel=1e-6)
    # --dx is in --unit (not in the file's metres) unless --xy-unit says otherwise, and overrides it
    given = cli_json("moments", tmp_path / "a.x3p", "--dx", "0.5")
    assert given["dx"] == 0.5 and "overrides the file's spacing" in given["source"]["notes"][0]
    assert cli_json("moments", tmp_path / "a.x3p", "--dx", "500", "--xy-unit", "nm")["dx"] == pytest.approx(0.5)


def test_heights_in_nm_with_dx_in_um(cli_run, cli_json, tmp_path):
    """nm heights read as µm gave an rms slope of 83 degrees without a word: now a warning with
    the likely factor, and --z-unit nm measures them right."""
    np.save(tmp_path / "z.npy", Z * 1000.0)
    d = cli_json("moments", tmp_path / "z.npy", "--dx", "0.25")
    assert any("scale factor 0.001" in w for w in d["warnings"])
    right = cli_json("moments", tmp_path / "z.npy", "--dx", "0.25", "--z-unit", "nm")
    assert right["warnings"] == [] and right["m00"] == pytest.approx(measure_heights(Z, 0.25).values["m00"])
    mm = cli_json("moments", tmp_path / "z.npy", "--dx", "0.25", "--z-unit", "nm", "--xy-unit", "um",
                  "--unit", "mm")
    assert mm["m00"] == pytest.approx(right["m00"] * 1e-6) and mm["m04"] == pytest.approx(right["m04"] * 1e6)
    assert mm["dx"] == pytest.approx(0.25e-3) and mm["m20"] == pytest.approx(right["m20"])


def test_dropouts_and_the_fill(cli_run, cli_json, tmp_path):
    z = Z.copy()
    z[40:46, 60:70] = np.nan
    np.save(tmp_path / "z.npy", z)
    d = cli_json("moments", tmp_path / "z.npy", "--dx", "0.25")
    assert d["missing_fraction"] == pytest.approx(60 / z.size) and d["fill"] == "none"
    f = cli_json("moments", tmp_path / "z.npy", "--dx", "0.25", "--fill", "harmonic", "--estimator", "spectral")
    assert f["fill"] == "harmonic" and f["estimator"] == "spectral"
    code, out, err = cli_run("moments", tmp_path / "z.npy", "--dx", "0.25", "--estimator", "spectral")
    assert code == 2 and len(err.splitlines()) == 1 and "complete map" in err


def test_narrow_band_map_gets_its_moments(cli_run, cli_json, tmp_path):
    """mu <= 0 was exit 2 with no moments; the moments are well defined: exit 0 and a warning."""
    y, x = np.mgrid[0:128, 0:128] * 0.25
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    np.save(tmp_path / "z.npy", 0.1 * np.cos(x * c + y * s) + 0.1 * np.cos(x * c - y * s + 0.3))
    d = cli_json("moments", tmp_path / "z.npy", "--dx", "0.25")
    assert d["model"]["mu"] < 0 and not d["model"]["model_applies"] and d["m04"] > 0
    assert any("mu = " in w for w in d["warnings"])


def test_the_scale_figure(cli_run, cli_json, tmp_path):
    np.save(tmp_path / "z.npy", Z)
    d = cli_json("moments", tmp_path / "z.npy", "--dx", "0.25", "--plot", tmp_path / "scales.png")
    assert d["plot"].endswith("scales.png") and (tmp_path / "scales.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("content, args, match", [
    (None, ["--dx", "1"], "no such file"),
    ("1,2,3\n4,x,6\n", ["--dx", "1"], "line 2: not a number"),
    ("1,2,3\n4,5,6\n", ["--dx", "1"], "at least 5"),
    ("\n".join(",".join(["3.5"] * 8) for _ in range(8)), ["--dx", "1"], "flat"),
    ("\n".join(",".join(str(i * j % 7) for i in range(8)) for j in range(8)), [], "pass --dx"),
    ("\n".join(",".join(str(i * j % 7) for i in range(8)) for j in range(8)), ["--dx", "1", "--unit", "parsec"],
     "unknown length unit"),
])
def test_errors_are_one_line(cli_run, cli_json, tmp_path, content, args, match):
    path = tmp_path / "bad.csv"
    if content is not None:
        path.write_text(content)
    code, out, err = cli_run("moments", path, *args)
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and match in err, err


def test_a_tall_point_table(cli_run, cli_json, tmp_path):
    """A 50000 x 6 XYZ file was read as a 50000 x 6 height grid with exit 0."""
    rng = np.random.default_rng(1)
    np.savetxt(tmp_path / "cloud.xyz", rng.random((50000, 6)))
    code, out, err = cli_run("moments", tmp_path / "cloud.xyz", "--dx", "1")
    assert code == 2 and len(err.splitlines()) == 1 and "nor x y z points on a grid" in err
    y, x = np.mgrid[0:96, 0:128]
    np.savetxt(tmp_path / "grid.xyz", np.column_stack([x.ravel() * 0.25, y.ravel() * 0.25, Z.ravel(),
                                                       rng.random((Z.size, 3))]), header="x y z r g b")
    d = cli_json("moments", tmp_path / "grid.xyz")
    assert d["shape"] == [96, 128] and d["dx"] == pytest.approx(0.25) and d["source"]["format"] == "xyz"
    assert d["m02"] == pytest.approx(measure_heights(Z, 0.25).values["m02"], rel=1e-9)


def test_an_instrument_file_without_the_extra(cli_run, cli_json, tmp_path, monkeypatch):
    """SurfaceTopography absent (the import fails as if not installed): one line, exit 2."""
    import sys

    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)
    (tmp_path / "scan.sur").write_bytes(b"DIGITAL SURF")
    code, out, err = cli_run("moments", tmp_path / "scan.sur")
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and "pip install '.[measure]'" in err
