"""The gate sees the FE half (issue 22): the anchor checks of roughcontact.paper.fe_anchors, fed with
real runs of the engine, pass as configured, and a 5 % error injected into the engine's beam or
punch results turns them — and the gate — red, with ccx nowhere involved."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from roughcontact.examples import runs as fe_runs
from roughcontact.examples.beam import run_beam
from roughcontact.examples.punch import PunchRun, PunchSpec, run_punch, to_dataset
from roughcontact.examples.punch_geometry import PunchGeometry
from roughcontact.paper import fe_anchors, verify
from roughcontact.paper.fe_punch import run_bounds
from roughcontact.paper.plane_stress import reference_solution

ROOT = Path(__file__).resolve().parents[2]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
EXPECTED = yaml.safe_load((ROOT / "config" / "expected_verdicts.yaml").read_text())
BEAM = CONFIG["fe"]["beam"]
ANCHORS = CONFIG["fe_anchors"]


def beam_run(case="3", family="quadratic"):
    """A Table 4 run of the workflow, as common.smk builds it (main mesh and loads)."""
    return fe_runs.beam_run(BEAM, family, case)


@pytest.fixture(scope="module")
def beam_reference():
    run = beam_run()
    ps = ANCHORS["beam"]["plane_stress"]
    return {fe_anchors.law_key(run): reference_solution(run, ps["mesh"], ps["estimate_mesh"])}


@pytest.fixture(scope="module")
def beam_result():
    """The engine's real run of case 3 (21-node elements, main mesh)."""
    return run_beam(beam_run())


@pytest.fixture(scope="module")
def beam_dataset(beam_result):
    return beam_result.to_dataset()


def _beam_checks(reference, ds):
    return fe_anchors.beam_anchor_checks({"quadratic-3-main": beam_run()}, {"quadratic-3-main": ds}, reference,
                                         ANCHORS["beam"]["tolerances"])


def _gate(checks):
    checks = verify.apply_expectations(checks, EXPECTED)
    return verify.summarize(checks)


def _scaled_beam(ds, scale):
    """Every deflection of a beam run's dataset scaled (what the workflow's checks read)."""
    out = ds.copy(deep=True)
    for name in ("u_N_um", "point_u_N_um"):
        out[name] = out[name] * scale
    for name in ("u_N_centre_um", "u_N_end_um"):
        out.attrs[name] = out.attrs[name] * scale
    return out


def test_the_beam_anchors_hold_on_a_real_run(beam_reference, beam_dataset):
    checks = _beam_checks(beam_reference, beam_dataset)
    assert [c.quantity for c in checks] == ["u_N_centre", "u_N_end", "u_N_profile", "equilibrium"]
    assert all(c.verdict == verify.REPRODUCED for c in checks), [c.detail for c in checks]
    assert all(c.id.startswith("numerics:fe_beam_anchor/fe-quadratic/") for c in checks)
    summary = _gate(checks)
    assert summary["passed"] and summary["regressions"] == 0


@pytest.mark.parametrize("scale", [1.05, 0.95])
def test_a_five_percent_beam_error_turns_the_gate_red(beam_reference, beam_dataset, scale):
    """The audit scaled every beam deflection by 1.05 and the gate stayed green; now the centre,
    the end and the profile checks fail (and the gate with them)."""
    checks = _beam_checks(beam_reference, _scaled_beam(beam_dataset, scale))
    red = {c.quantity for c in checks if c.verdict != verify.REPRODUCED}
    assert red == {"u_N_centre", "u_N_end", "u_N_profile"}, [c.detail for c in checks]
    summary = _gate(checks)
    assert not summary["passed"] and summary["regressions"] == 3
    # the equilibrium of the written pressures is blind to a deflection error; a pressure error
    # is its job
    hit = beam_dataset.copy(deep=True)
    hit["point_p_N"] = hit["point_p_N"] * scale
    assert {c.quantity for c in _beam_checks(beam_reference, hit) if c.verdict != verify.REPRODUCED} == {"equilibrium"}


def test_the_audits_experiment_in_the_engines_result(beam_reference, beam_result):
    """The audit's own experiment: every beam deflection scaled by 1.05 in the engine's result
    (BeamResult.u_N_um, what run_beam returns; the audit did it inside the old fe/beam.py's
    run_beam), the dataset written from it as the workflow does: the anchors fail."""
    scaled = dataclasses.replace(beam_result, u_N_um=1.05 * beam_result.u_N_um)
    checks = _beam_checks(beam_reference, scaled.to_dataset())
    assert {c.quantity for c in checks if c.verdict != verify.REPRODUCED} == {"u_N_centre", "u_N_end", "u_N_profile"}
    assert not _gate(checks)["passed"]


def test_anchored_runs_are_the_free_ones_on_the_main_mesh_or_finer():
    base = beam_run("1")
    runs = {"q-1-main": base, "q-1-stick": base.with_(tangential="stick"),
            "q-1-mesh-6x2": base.with_(spec={"n_x": 6, "n_z": 2}),
            "q-1-mesh-50x12": base.with_(spec={"n_x": 50, "n_z": 12})}
    assert fe_anchors.anchored_beam_runs(runs, BEAM["spec"]) == ["q-1-main", "q-1-mesh-50x12"]
    ep = beam_run("4").with_(psi=None, Y=2070.0)
    assert fe_anchors.law_key(ep) != fe_anchors.law_key(beam_run("4")) != fe_anchors.law_key(beam_run("1"))


def test_the_workflows_anchored_runs():
    """The workflow's runs (examples.runs.beam_runs, as common.smk builds them): the 20 the
    expected_verdicts count (fe_beam_anchor: 80 = 20 x 4) stands on, sharing 2D solutions by law."""
    runs = fe_runs.beam_runs(BEAM)
    anchored = fe_anchors.anchored_beam_runs(runs, BEAM["spec"])
    assert len(anchored) * 4 == EXPECTED["expected_checks"]["fe_beam_anchor"]
    main = sorted(n for n in runs if n.endswith("-main"))
    assert set(main) <= set(anchored)  # Table 4's runs (free sliding, the main mesh), both families
    assert {fe_anchors.law_key(runs[n]) for n in anchored} >= {fe_anchors.law_key(runs[n]) for n in main}


# ---------------------------------------------------------------------------------------------
# the punch
# ---------------------------------------------------------------------------------------------
SURFACE = {"m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}
COARSE = {"family": "quadratic", "n_punch": 2, "n_outer": 2, "n_depth": 2}  # 25 contact points
D_ATTR = CONFIG["fe"]["punch"]["d_attr"]


def punch_run(case):
    """A coarse run under the quarter reading (1000 N on the quarter model: case a slips)."""
    spec = PunchSpec(geometry=PunchGeometry(**COARSE), load=1000.0, load_on="quarter", seating_pressure=0.1,
                     increments=4, unload_increments=4)
    return PunchRun(case=case, spec=spec, m00=0.625, surface=tuple(SURFACE.items()), law="elastic", psi=None,
                    bound=None if case == "frictionless" else "coarse-frictionless")


@pytest.fixture(scope="module")
def punch_data():
    runs = {f"coarse-{c}": punch_run(c) for c in ("a", "frictionless")}
    data = {name: to_dataset(run_punch(run)) for name, run in runs.items()}
    return runs, data


def _punch_checks(runs, data):
    bounds = run_bounds(data, runs)
    area = {name: 100.0 for name in runs}  # the quarter punch's top, 10 x 10 mm (independent of the run's geometry)
    return fe_anchors.punch_anchor_checks(runs, data, bounds, area, ANCHORS["punch"]["tolerances"], D_ATTR)


def _scaled(ds, names, factor=1.05, attrs=()):
    out = ds.copy(deep=True)
    for n in names:
        out[n] = out[n] * factor
    for a in attrs:
        out.attrs[a] = out.attrs[a] * factor
    return out


def test_the_punch_anchors_hold_on_real_runs(punch_data):
    runs, data = punch_data
    checks = _punch_checks(runs, data)
    assert sorted(c.quantity for c in checks) == ["bound", "dissipation", "equilibrium", "equilibrium",
                                                  "friction_limit", "friction_limit"]
    assert all(c.verdict == verify.REPRODUCED for c in checks), [c.detail for c in checks]
    assert float(data["coarse-a"].attrs[D_ATTR]) > 0.0  # the points slip: the checks see real slip
    assert _gate(checks)["passed"]


@pytest.mark.parametrize("names, attrs, red", [
    (["p_N"], (), {"equilibrium", "friction_limit"}),                # the pressures
    (["t_x", "t_y"], (), {"friction_limit", "dissipation"}),         # the tangential tractions
    (["t_x", "t_y", "p_N"], (), {"equilibrium", "dissipation"}),     # all tractions
    ([], ("D_max_area_whole", "D_end_area_whole"), {"dissipation"}),  # the dissipation reported
    (["slip_x_um", "slip_y_um"], (), {"dissipation"}),               # the plastic slips written
])
def test_a_five_percent_punch_error_turns_the_gate_red(punch_data, names, attrs, red):
    """What catches a 5 % error in the punch's written results (case a, the quarter reading)."""
    runs, data = punch_data
    hit = {**data, "coarse-a": _scaled(data["coarse-a"], names, attrs=attrs)}
    checks = _punch_checks(runs, hit)
    got = {c.quantity for c in checks if c.verdict != verify.REPRODUCED and c.s == "a"}
    assert got == red, [c.detail for c in checks]
    assert not _gate(checks)["passed"]
    down = {**data, "coarse-a": _scaled(data["coarse-a"], names, 0.95, attrs)}
    assert {c.quantity for c in _punch_checks(runs, down) if c.verdict != verify.REPRODUCED} == red


# ---------------------------------------------------------------------------------------------
# the punch's energy balance (issue 29): slips and D scaled together
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def punch_energy_data():
    """Coarse case-a runs under the quarter reading, one per tangential form, with the fields the
    workflow writes (fe_anchors.stiffness_fields, as workflow/scripts/fe_punch_run.py adds them)."""
    from dataclasses import replace

    runs, data = {}, {}
    for form in ("incremental-end", "incremental-start", "secant"):
        name = f"coarse-{form}-a"
        runs[name] = replace(punch_run("a"), tangential_form=form)
        result = run_punch(runs[name])
        variables, attrs = fe_anchors.stiffness_fields(result)
        data[name] = to_dataset(result).assign(variables)
        data[name].attrs.update(attrs)
    return runs, data


def test_the_punch_energy_balance_holds_on_real_runs_of_every_tangential_form(punch_energy_data):
    runs, data = punch_energy_data
    checks = fe_anchors.punch_energy_checks(runs, data, ANCHORS["punch"]["tolerances"]["energy"])
    assert len(checks) == 6 and all(c.verdict == verify.REPRODUCED for c in checks), [c.detail for c in checks]
    assert all(float(ds.attrs["D_max_work_whole"]) > 0.0 for ds in data.values())  # every form slips here


def test_slips_and_D_scaled_together_turn_the_punch_anchor_red_on_a_real_run(punch_energy_data):
    """The audit's injection that passed the issue-22 anchors: the written slips and every D by 1.05."""
    runs, data = punch_energy_data
    name = "coarse-incremental-end-a"
    attrs = [a for a in data[name].attrs if a.startswith("D_")]
    hit = {name: _scaled(data[name], ["slip_x_um", "slip_y_um"], attrs=attrs)}
    old = fe_anchors.punch_anchor_checks({name: runs[name]}, hit, {name: math.inf}, {name: 100.0},
                                         ANCHORS["punch"]["tolerances"], D_ATTR)
    assert all(c.verdict == verify.REPRODUCED for c in old)  # issue 22's anchors: blind to it
    checks = fe_anchors.punch_energy_checks({name: runs[name]}, hit, ANCHORS["punch"]["tolerances"]["energy"])
    assert {c.quantity for c in checks if c.verdict != verify.REPRODUCED} == {"slip_balance", "work_balance"}
    assert not _gate(checks)["passed"]
