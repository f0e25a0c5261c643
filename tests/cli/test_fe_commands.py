"""``roughcontact fe beam``: the documented JSON fields and units, exit codes (2 bad input with one
stderr line, 1 no convergence naming the increment), progress on stderr, the VTU files."""

import json

import meshio
import numpy as np
import pytest

from roughcontact import cli
from roughcontact.cli import fe as fe_cli
from roughcontact.fe import beam, contact

SURFACE = ["--m00", "0.625", "--m20", "8e-5", "--m02", "8e-4", "--m40", "1.04e-6", "--m04", "1.04e-4"]
COARSE = ["--n-x", "6", "--n-z", "2", "--elements", "quadratic"]


def run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_choices_match_library():
    assert fe_cli.TANGENTIAL == contact.TANGENTIAL
    assert fe_cli.FAMILIES == beam.ELEMENT_FAMILIES
    assert fe_cli.BEAM_E_STAR == pytest.approx(1.127e5, rel=5e-4)  # the text's E* (42)


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
    (["--load", "1"], "initial_load"),
])
def test_bad_input_is_exit_2_with_one_line(capsys, argv, message):
    surface = SURFACE[:-2] + argv[:2] if argv[0] == "--m04" else SURFACE + argv
    code, out, err = run(capsys, "fe", "beam", *surface, *COARSE, "--quiet")
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and message in err


def test_no_convergence_is_exit_1_naming_the_increment(capsys, monkeypatch):
    from roughcontact.fe import solver

    real = solver.solve
    monkeypatch.setattr(beam, "solve", lambda model, levels, options=None, progress=None: real(
        model, levels, solver.NewtonOptions(max_iterations=1, max_cutbacks=1), progress))
    code, out, err = run(capsys, "fe", "beam", *SURFACE, *COARSE, "--quiet")
    assert code == 1 and out == ""
    assert "increment" in err and "residual" in err and len(err.splitlines()) == 1
