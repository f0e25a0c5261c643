"""From a scan to the contact commands without copying numbers: --moments FILE (one, or two rough
surfaces) wherever the five moments are asked, and k_Tx, k_Ty next to K_N."""

from __future__ import annotations

import json

import numpy as np
import pytest

from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.synthetic import synthetic_surface

TABLE1 = {"m00": 0.0625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}
ARGS = [x for k, v in TABLE1.items() for x in (f"--{k}", str(v))]


@pytest.fixture
def surface_json(tmp_path, cli_json):
    """What `roughcontact moments scan --json > surface.json` writes."""
    z = synthetic_surface(SpectralMoments(0.01, 0.001, 0.01, 3e-4, 0.03), (96, 128), 0.25, seed=1, lay_angle_deg=10.0)
    np.save(tmp_path / "scan.npy", z)
    d = cli_json("moments", tmp_path / "scan.npy", "--dx", "0.25")
    (tmp_path / "surface.json").write_text(json.dumps(d))
    return tmp_path / "surface.json", d


@pytest.mark.parametrize("command, extra", [
    ("surface", []),
    ("elastic", ["--E-star", "1.14e5", "--s", "1", "2"]),
    ("elastoplastic", ["--E-star", "1.14e5", "--psi", "0.5", "--s", "1", "2"]),
    ("export", ["--format", "csv", "--E-star", "1.14e5", "--pressure-range", "1e-3", "10"]),
])
def test_moments_file_equals_the_numbers(cli_run, cli_json, surface_json, command, extra):
    path, d = surface_json
    numbers = [x for k in TABLE1 for x in (f"--{k}", repr(d[k]))]
    by_file = cli_json(command, "--moments", path, *extra)
    by_hand = cli_json(command, *numbers, *extra)
    for key in ("pressure", "stiffness", "k_Tx", "mu", "table"):
        if key in by_hand:
            assert by_file[key] == by_hand[key], key
    if command in ("elastic", "elastoplastic"):
        assert by_file["length_unit"] == "um" and by_hand["length_unit"] is None
    if command == "export":
        assert by_file["moments_unit"] == "um"


def test_two_files_are_two_rough_surfaces(cli_run, cli_json, tmp_path):
    other = {"m00": 0.01, "m20": 2e-5, "m02": 3e-4, "m40": 4e-7, "m04": 2e-5}
    (tmp_path / "a.json").write_text(json.dumps({**TABLE1, "unit": "um"}))
    (tmp_path / "b.json").write_text(json.dumps({"moments": {**{k: v * 1e-6 if k == "m00" else v * 1e6 if k in ("m40", "m04")
                                                              else v for k, v in other.items()}, "unit": "mm"}}))
    second = [str(other[k]) for k in TABLE1]
    by_files = cli_json("elastic", "--moments", tmp_path / "a.json", tmp_path / "b.json",
                        "--E-star", "1e5", "--s", "1.5")
    by_flag = cli_json("elastic", *ARGS, "--second-surface", *second, "--E-star", "1e5", "--s", "1.5")
    assert by_files["moments"] == pytest.approx(by_flag["moments"], rel=1e-12)  # b converted from mm to um
    assert by_files["pressure"] == pytest.approx(by_flag["pressure"], rel=1e-12)


@pytest.mark.parametrize("argv, match", [
    (["--moments", "NOFILE.json", "--m00", "1"], "replaces --m00"),
    (["--m00", "0.0625"], "the moments are missing: --m20"),
    (["--moments", "NOFILE.json"], "no such moments file"),
    (["--moments", "a", "b", "c"], "one file, or two"),
])
def test_moments_errors(cli_run, cli_json, argv, match):
    code, out, err = cli_run("elastic", *argv, "--E-star", "1e5", "--s", "1")
    assert code == 2 and len(err.splitlines()) == 1 and match in err, err


def test_tangential_stiffness_is_mindlin_at_the_representative_aspect(cli_run, cli_json):
    """For equal rms curvatures (m40 = m04) the representative contact is a circle: k_T/k_N =
    2(1 - nu)/(2 - nu) in both directions (Mindlin 1949; Table 3 at B = A)."""
    circle = ["--m00", "0.0625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1e-4", "--m04", "1e-4"]
    d = cli_json("elastic", *circle, "--E-star", "1e5", "--s", "1", "2", "--nu", "0.25")
    ratio = 2 * (1 - 0.25) / (2 - 0.25)
    assert d["tangential"]["ay2_over_ax2"] == pytest.approx(1.0)
    assert d["k_Tx"] == pytest.approx([ratio * k for k in d["stiffness"]], rel=1e-12)
    assert d["k_Ty"] == pytest.approx(d["k_Tx"], rel=1e-12)
    # an elongated ellipse (m40 << m04: long along the lay, x): a force along its minor axis (y) meets
    # the stiffer response (Table 3: k_N/k_T -> 1 for B/A -> 0, -> 1/(1 - nu) for B/A -> infinity)
    e = cli_json("elastoplastic", *ARGS, "--E1", "2.1e5", "--nu1", "0.3", "--psi", "0.5", "--s", "1")
    t = e["tangential"]
    assert t["nu"] == 0.3 and t["nu_source"] == "--nu1" and t["ay2_over_ax2"] < 1
    assert e["k_Ty"][0] > e["k_Tx"][0] and "k_Tx" in e["units"]
    code, out, err = cli_run("elastic", *ARGS, "--E-star", "1e5", "--s", "1")
    assert "tangential: k_Tx = " in out and "default (give --nu)" in out
