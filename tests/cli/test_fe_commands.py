"""``roughcontact fe beam`` and ``fe punch`` (the paper's examples as decks): the documented JSON
fields and units, exit codes (2 bad input with one stderr line, 1 no convergence naming the
increment), progress on stderr, the VTU files, and the audit of issue 22 (no silent defaults, E*
recorded, the bound's premise, warnings from the solved state, a discretisation estimate)."""

import json

import meshio
import numpy as np
import pytest

from roughcontact import cli
from roughcontact.cli import fe as fe_cli
from roughcontact.examples import beam
from roughcontact.fe import deck_mesh

SURFACE = ["--m00", "0.625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6", "--m04", "1.04e-4"]
COARSE = ["--n-x", "6", "--n-z", "2", "--elements", "quadratic"]


def run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_choices_match_library():
    assert fe_cli.TANGENTIAL == beam.TANGENTIAL
    assert fe_cli.FAMILIES == beam.ELEMENT_FAMILIES == tuple(deck_mesh.FAMILIES)


def test_beam_json_has_the_documented_fields(capsys, tmp_path):
    vtu = tmp_path / "beam.vtu"
    code, out, err = run(capsys, "fe", "beam", *SURFACE, *COARSE, "--json", "--vtu", str(vtu))
    assert code == 0
    data = json.loads(out)
    for key in ("u_N_centre_um", "u_N_end_um", "x_mm", "u_N_um", "open_points", "newton_iterations", "units"):
        assert key in data
    assert data["u_N_centre_um"] == data["u_N_um"][0] < 0.0 < data["u_N_end_um"] == data["u_N_um"][-1]
    assert len(data["newton_iterations"]) == 17 and data["equilibrium_error"] < 1e-10
    assert data["x_mm"][0] == 0.0 and data["x_mm"][-1] == 250.0
    assert "increment 17/17" in err  # progress on stderr, JSON alone on stdout
    d = data["discretisation"]  # against 3 x 1 elements
    assert d["coarse_mesh"] == [3, 1] and d["estimate_um"] == pytest.approx(
        max(abs(data["u_N_centre_um"] - d["u_N_centre_um"]), abs(data["u_N_end_um"] - d["u_N_end_um"])))
    volume, points = meshio.read(vtu), meshio.read(tmp_path / "beam_interface.vtu")
    assert volume.point_data["displacement_mm"].shape[1] == 3
    np.testing.assert_allclose(points.point_data["u_N_um"][np.isclose(points.points[:, 1], 0.0)].min(),
                               data["u_N_centre_um"], rtol=1e-12)


@pytest.mark.parametrize("argv, message", [
    (["--m04", "-1e-4"], "m04"),
    (["--law", "elastoplastic"], "--psi"),
    (["--psi", "0.35"], "--psi"),
    (["--tangential", "coulomb"], "mu"),
    (["--mu", "0.1"], "mu"),
    (["--increments", "0"], "increments"),
    (["--increments", "2.5"], "integer"),
    (["--load", "1"], "initial_load"),
])
def test_bad_input_is_exit_2_with_one_line(capsys, argv, message):
    surface = SURFACE[:-2] + argv[:2] if argv[0] == "--m04" else SURFACE + argv
    code, out, err = run(capsys, "fe", "beam", *surface, *COARSE, "--quiet")
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and message in err


def test_no_convergence_is_exit_1_naming_the_increment(capsys, monkeypatch):
    from roughcontact.fe import solver

    from roughcontact.fe import deck_run

    real = solver.solve
    monkeypatch.setattr(deck_run, "solve", lambda model, levels, options=None, progress=None: real(
        model, levels, solver.NewtonOptions(max_iterations=1, max_cutbacks=1), progress))
    code, out, err = run(capsys, "fe", "beam", *SURFACE, *COARSE, "--quiet")
    assert code == 1 and out == ""
    assert "step 1" in err and "increment" in err and "residual" in err and len(err.splitlines()) == 1


def test_a_too_coarse_beam_is_said_to_be_too_coarse(capsys):
    """Issue 22: `--n-x 1 --n-z 2` gave an end deflection 141 % off the converged one silently;
    now the estimate against 1 x 1 elements (0.34 um, 25 % of the centre) warns."""
    code, out, err = run(capsys, "fe", "beam", *SURFACE, "--n-x", "1", "--n-z", "2", "--quiet", "--json")
    assert code == 0 and "warning: discretisation error" in err and "refine" in err
    assert json.loads(out)["discretisation"]["estimate_um"] > 0.01 * abs(json.loads(out)["u_N_centre_um"])
    code, out, err = run(capsys, "fe", "beam", *SURFACE, *COARSE, "--quiet", "--json")
    assert "7.2 % of the centre deflection" in err  # 6 x 2 against 3 x 1 (its true error: 1.5 %)
    code, out, err = run(capsys, "fe", "beam", *SURFACE, "--elements", "quadratic", "--increments", "2", "--quiet")
    assert code == 0 and "discretisation" not in err  # the main mesh 25 x 6 against 13 x 3: 0.5 %


PUNCH_POINT_FIELDS = ("x_mm", "y_mm", "slip_x_um", "slip_y_um", "t_x", "t_y", "p_N", "status", "utilisation")


def test_punch_json_has_the_documented_fields(capsys, tmp_path):
    """The paper's mesh (81 points), two increments each way to keep the test short."""
    vtu = tmp_path / "punch.vtu"
    code, out, err = run(capsys, "fe", "punch", "--case", "b", "--increments", "2", "--json", "--vtu", str(vtu))
    assert code == 0
    data = json.loads(out)
    for key in ("dissipation_quarter_Nmm", "dissipation_full_Nmm", "frictionless_bound_quarter_Nmm",
                "frictionless_bound_full_Nmm", "newton_iterations", "points", "units"):
        assert key in data
    assert data["interface_points"] == 81 and len(data["newton_iterations"]) == 5
    assert data["dissipation_full_Nmm"] == pytest.approx(4.0 * data["dissipation_quarter_Nmm"], rel=1e-14)
    assert 0.0 <= data["dissipation_quarter_Nmm"] <= data["frictionless_bound_quarter_Nmm"]
    pts = data["points"]
    assert all(len(pts[k]) == 81 for k in PUNCH_POINT_FIELDS)
    assert set(pts["status"]) <= {"stick", "slip", "open"}
    # the contact points cover the quarter punch's face [0, 10]² mm
    assert max(pts["x_mm"]) == max(pts["y_mm"]) == 10.0
    assert "increment 5/5" in err
    assert data["E_star"] == pytest.approx(2.0e5 / (2 * (1 - 0.25 ** 2)), rel=1e-14)  # two like bodies, (42)
    assert data["law"] == "elastoplastic" and data["psi"] == 0.35
    points = meshio.read(tmp_path / "punch_interface.vtu")
    np.testing.assert_allclose(np.sort(points.point_data["p_N"]), np.sort(pts["p_N"]), rtol=1e-12)
    assert meshio.read(vtu).point_data["displacement_mm"].shape[1] == 3


def test_punch_text_lists_every_point(capsys):
    code, out, _ = run(capsys, "fe", "punch", "--case", "a", "--increments", "1", "--quiet")
    assert code == 0 and "frictionless bound" in out
    assert sum(line.rstrip().endswith(("stick", "slip", "open")) for line in out.splitlines()) == 81


@pytest.mark.parametrize("argv, message", [
    (["--increments", "0"], "increments"),
    (["--load", "-1"], "load"),
    (["--load-patch", "25"], "load_patch"),
    (["--seating-pressure", "0"], "seating_pressure"),
    (["--m00", "nan"], "m00"),
    (["--E-star", "0"], "E_star"),  # issue 22: fell back to (42) silently
    (["--load-patch", "0"], "load_patch"),  # issue 22: fell back to the central element silently
    (["--law", "elastic", "--psi", "0.35"], "--psi"),  # issue 22: ignored --psi
    (["--law", "elastic", "--E-star", "1e-3"], "E*"),  # issue 22: a traceback from the table's build
    (["--increments", "2.5"], "integer"),
])
def test_punch_bad_input_is_exit_2_with_one_line(capsys, argv, message):
    code, out, err = run(capsys, "fe", "punch", "--case", "b", *argv, "--quiet")
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and message in err


def test_punch_bound_holds_under_a_large_seating_pressure(capsys):
    """Issue 22: `--seating-pressure 100` gave D = 5.60 N mm above the bound 1.148: the seating
    increment slips, and the bound measured the relative slip from the seated state only. From
    the unloaded start (where D's plastic slips start) the bound holds (23.7 N mm)."""
    code, out, err = run(capsys, "fe", "punch", "--case", "a", "--seating-pressure", "100", "--increments", "1",
                         "--law", "elastic", "--quiet", "--json")  # the elastic law: the same D to 1e-4, cheaper
    data = json.loads(out)
    assert code == 0 and data["dissipation_full_Nmm"] > 1.0  # the seating slips
    assert data["dissipation_full_Nmm"] <= data["frictionless_bound_full_Nmm"]
    assert "exceeds the frictionless bound" not in err
    # validity is judged on the solved pressures (the punch edge: A/A0 above 0.1), once each
    assert "at the largest solved pressure" in err and len(err.splitlines()) == len(set(err.splitlines()))
