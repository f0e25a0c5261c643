"""The 2D plane-stress code of example 9.1 (roughcontact.paper.plane_stress), the gate's
engine-free anchor of the beam: separate from the 3D engine, checked against Hetényi's finite
beam on a Winkler foundation, in equilibrium, converging with its mesh."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

from roughcontact.examples.beam import BeamRun, BeamSpec
from roughcontact.fe.closed_forms import hetenyi_finite_beam
from roughcontact.paper import plane_stress
from roughcontact.paper.plane_stress import (PlaneStressBeam, plane_stress_beam, reference_solution,
                                             solve_plane_stress_beam)

SURFACE = {"m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}  # um units, Table 4
E_STAR = 1.1274666666666667e5  # N/mm^2, the text's E* of example 9.1
GEOMETRY = {"length": 500.0, "height": 120.0, "width": 10.0, "E": 1.057e5, "nu": 0.25}
SPEC = {"load": 1962.0, "initial_load": 4.9, "increments": 16, "z_ratio": 4.0}


def test_imports_nothing_of_the_engine():
    """Independent of the 3D engine: no import from roughcontact.fe, nor from roughcontact.examples
    (whose runs are the engine's decks; the run's numbers are read from its fields, the law comes
    from the interface layer)."""
    tree = ast.parse(Path(plane_stress.__file__).read_text())
    modules = [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    modules += [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    engine = ("fe", "examples")
    assert not [m for m in modules if m.split(".")[0] in engine
                or any(f"roughcontact.{e}" in m for e in engine)], modules


class LinearLaw:
    """p = p0 + k u (no opening): the interface of Hetényi's Winkler foundation."""

    def __init__(self, p0, k):
        self.p0, self.k = p0, k

    def normal(self, u):
        u = np.asarray(u, dtype=float)
        return self.p0 + self.k * u, np.full_like(u, self.k)


@pytest.mark.parametrize("lam_L", [2.0, 4.0])
def test_slender_beam_on_a_linear_interface_is_hetenyis(lam_L):
    """A slender beam (L/H = 50, ν = 0) on a linear interface k [N/mm³]: the deflection increment
    from the seated state is Hetényi's finite free–free beam under the load increment, Winkler
    modulus k_b = k b. The 2D solution includes shear: Timoshenko adds P/(2 κ G A) × (the
    fraction of the shear load near the centre) ~ 0.1-0.3 % here; measured within 0.4 % at the
    centre and 1 % of the centre value along the beam (the check's thresholds)."""
    L, H, b, E = 1000.0, 20.0, 10.0, 2e5
    EI = E * b * H**3 / 12.0
    k_b = 4.0 * EI * (lam_L / L) ** 4
    beam = PlaneStressBeam(length=L, height=H, width=b, E=E, nu=0.0, load=100.0, initial_load=1.0, increments=1,
                           n_x=100, n_z=4, z_ratio=1.0)
    r = solve_plane_stress_beam(beam, LinearLaw(beam.seating_pressure, k_b / b), length_per_mm=1.0)
    w = hetenyi_finite_beam(beam.load - beam.initial_load, L, EI, k_b, r.x_mm) * 1000.0  # mm -> um, + = down
    assert -r.u_N_um[0] == pytest.approx(w[0], rel=4e-3)
    assert np.max(np.abs(-r.u_N_um - w)) <= 1e-2 * w[0]
    # every residual force ≤ 1e-10 of the internal ones, which exceed the load (the stiff beam of
    # λL = 2 bends against the soft interface): the sum is ≤ 1e-7 of the load (measured 1.2e-8)
    assert r.equilibrium_error <= 1e-7


def _run(m00, **spec):
    """A beam run of example 9.1 (elastic law, the text's E*), as the workflow builds them."""
    return BeamRun(spec=BeamSpec(**GEOMETRY, **SPEC, **spec), m00=m00, surface=tuple(SURFACE.items()), law="elastic",
                   E_star=E_STAR)


def _law(m00):
    return plane_stress.beam_run_law(_run(m00), SPEC["initial_load"] / (500.0 * 10.0))


def test_statistical_beam_converges_with_the_mesh():
    """Example 9.1, m00 = 0.0625: the centre and the end deflections change little from 25×6 to
    50×12 (measured 2.9e-5 / 1.0e-3 um), and 50×12 is the converged value (100×24, measured
    once: -0.454272, +0.712818 um); the interface carries the load (Newton's tolerance)."""
    law, out = _law(0.0625), {}
    for n in ((25, 6), (50, 12)):
        beam = PlaneStressBeam(**GEOMETRY, **SPEC, n_x=n[0], n_z=n[1])
        out[n] = r = solve_plane_stress_beam(beam, law)
        assert r.equilibrium_error <= 1e-8
        assert r.u_N_centre_um < 0.0 < r.u_N_end_um  # the centre approaches, the ends open (Table 4's signs)
    d_centre = abs(out[(25, 6)].u_N_centre_um - out[(50, 12)].u_N_centre_um)
    d_end = abs(out[(25, 6)].u_N_end_um - out[(50, 12)].u_N_end_um)
    assert d_centre <= 1e-4 and d_end <= 2e-3
    assert out[(50, 12)].u_N_centre_um == pytest.approx(-0.454272, abs=1e-5)
    assert out[(50, 12)].u_N_end_um == pytest.approx(0.712818, abs=2e-4)


@pytest.mark.slow
def test_configured_mesh_is_converged():
    """m00 = 0.625: the workflow's 2D mesh (50×12) against one twice as fine: within 2e-5 um
    (centre) and 1e-4 um (end; measured 9e-6, 4.9e-5; 200×48 moves them by 1e-6 more), far
    below the anchor's tolerances (config fe_anchors.beam)."""
    law = _law(0.625)
    a, b = (solve_plane_stress_beam(PlaneStressBeam(**GEOMETRY, **SPEC, n_x=n[0], n_z=n[1]), law)
            for n in ((50, 12), (100, 24)))
    assert abs(a.u_N_centre_um - b.u_N_centre_um) <= 2e-5
    assert abs(a.u_N_end_um - b.u_N_end_um) <= 1e-4


def test_the_2d_problem_is_the_runs():
    """The 2D beam takes the run's geometry, material and loads, not its 3D mesh; a load patch
    (not modelled in 2D) is refused."""
    run = _run(0.0625, n_x=7, n_z=3, elements="quadratic")
    beam = plane_stress_beam(run, 50, 12)
    assert beam == PlaneStressBeam(**GEOMETRY, **SPEC, n_x=50, n_z=12)
    assert plane_stress_beam(run.with_(spec={"n_x": 50}), 50, 12) == beam
    assert plane_stress_beam(run.with_(spec={"load": 981.0}), 50, 12) != beam
    with pytest.raises(ValueError, match="load patch"):
        plane_stress_beam(run.with_(spec={"load_patch": 20.0}), 50, 12)


def test_reference_solution_reports_its_error_estimate():
    r = reference_solution(_run(0.0625), (25, 6), (12, 3))
    assert r["x_mm"][0] == 0.0 and r["x_mm"][-1] == 250.0 and r["u_N_um"].shape == r["x_mm"].shape
    assert 0.0 < r["error_centre_um"] < 1e-2 and 0.0 < r["error_end_um"] < 2e-2
    assert r["u_N_centre_um"] == r["u_N_um"][0]


def test_bad_beams_are_refused():
    with pytest.raises(ValueError, match="n_x"):
        PlaneStressBeam(**GEOMETRY, **SPEC, n_x=0)
    with pytest.raises(ValueError, match="initial_load"):
        PlaneStressBeam(**GEOMETRY, **{**SPEC, "load": 1.0, "initial_load": 2.0})
    with pytest.raises(ValueError, match="height"):
        PlaneStressBeam(**{**GEOMETRY, "height": -1.0}, **SPEC)
