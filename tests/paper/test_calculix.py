"""The exported table in CalculiX: decks (always), the block and the beam in ccx (where ccx is
installed; skipped cleanly elsewhere)."""

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from roughcontact.fe.beam import BeamSpec
from roughcontact.interface.export import format_table, overclosure_table
from roughcontact.paper import calculix
from roughcontact.statistics import SpectralMoments

CONFIG = yaml.safe_load((Path(__file__).resolve().parents[2] / "config" / "config.yaml").read_text())
CFG = CONFIG["calculix"]
BEAM = CONFIG["fe"]["beam"]
E_STAR = float(BEAM["E_star"])
needs_ccx = pytest.mark.skipif(calculix.ccx_executable() is None, reason="ccx (CalculiX) is not installed")


def _surface(case):
    return SpectralMoments(m00=BEAM["cases"][case]["m00"], **BEAM["surface"])


def _table(case, spec):
    table = overclosure_table(_surface(case), pressure_range=tuple(CFG["pressure_range"]), E_star=E_STAR,
                              rtol=CFG["rtol"], reference="seating", seating_pressure=spec.seating_pressure)
    return table, format_table(table, "calculix", length_scale=1e-3)


def test_hex20_grid_counts_and_load_weights():
    x, y, z = [0.0, 1.0, 2.0], [0.0, 1.0], [0.0, 1.0, 3.0]
    ids, coords, elements, _ = calculix._hex20_grid(x, y, z)
    # corners 3*2*3 + mid-edges along x 2*2*3, along y 3*1*3, along z 3*2*2 (no face or body centres)
    assert len(coords) == len(ids) == 18 + 12 + 9 + 12
    assert len(elements) == 4 and all(len(e) == 20 for e in elements)
    assert len({n for e in elements for n in e}) == len(ids)  # every node belongs to an element
    # C3D20 order: node 9 is the mid-point of the edge 1-2
    e = elements[0]
    np.testing.assert_allclose(coords[e[8] - 1], 0.5 * (coords[e[0] - 1] + coords[e[1] - 1]))
    np.testing.assert_allclose(coords[e[16] - 1], 0.5 * (coords[e[0] - 1] + coords[e[4] - 1]))
    deck = calculix.beam_deck("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n0.0, -1e-4\n1.0, 0.0\n",
                              BeamSpec(elements="quadratic", n_x=2, n_z=2))
    cloads = [line for line in deck.splitlines() if line.count(",") == 2 and ", 3, " in line]
    forces = [float(line.split(",")[2]) for line in cloads]
    spec = BeamSpec()
    assert sum(forces[:3]) == pytest.approx(-spec.initial_load / 4, rel=1e-12)
    assert sum(forces[3:]) == pytest.approx(-spec.load / 4, rel=1e-12)


def test_decks_refuse_what_ccx_cannot_read():
    rows = "\n".join(f"{i}.0, {i}.0" for i in range(201))
    with pytest.raises(ValueError, match="200 rows"):
        calculix.block_deck("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n" + rows, [1.0])
    with pytest.raises(ValueError, match="20 characters"):
        calculix.block_deck("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n0.0, 0.0\n1.0, 1.00000000000000000001", [1.0])


def test_width_and_half_element_average_cancels_a_ripple():
    """A smooth linear field plus an alternating corner/mid-side ripple: the average is the
    field's value at the quarter point, the ripple gone."""
    x = np.array([0, 0, 0, 5, 5], dtype=float)
    y = np.array([0, 2.5, 5, 0, 5], dtype=float)
    smooth = 1.0 + 0.01 * x
    ripple = np.where(np.isclose(x % 10, 0), 0.03, -0.03)
    got = calculix.width_and_half_element_average(x, y, smooth + ripple, 0.0, 5.0)
    assert got == pytest.approx(1.0 + 0.01 * 2.5, rel=1e-12)


@needs_ccx
def test_block_closure_is_the_inverse_of_the_law(tmp_path):
    """ccx's closure under uniform pressure: the table's pressure there equals the applied one to
    the 7 digits ccx prints, the law's within the table's rtol."""
    spec = BeamSpec(elements="quadratic", **BEAM["spec"])
    table, text = _table(CFG["block_surface"], spec)
    pressures = CFG["block_pressures"]
    dat, seconds = calculix.run_ccx(calculix.block_deck(text, pressures), "block", tmp_path)
    closures = calculix.block_closures_um(dat, len(pressures))
    for p, c in zip(pressures, closures):
        k = float(table.law.evaluate(table.h_ref - c)[1])  # dp/dc [N/mm² per µm]
        printed = 5e-7 * abs(c) * k / p + 5e-12 / p * k  # 7 printed digits of u (mm) -> relative p
        assert float(table.interpolate(c)) == pytest.approx(p, rel=max(printed, 1e-9) * 2)
        assert abs(float(table.law_pressure(c)) / p - 1.0) <= CFG["tolerances"]["block"]["rtol"]
    assert closures[1] == pytest.approx(0.0, abs=1e-3)  # the seating pressure: zero overclosure


@needs_ccx
@pytest.mark.slow
def test_beam_agrees_with_the_engine(tmp_path):
    """The frictionless beam of example 9.1 (m00 = 0.0625) in ccx with the exported table vs
    this project's engine on the same mesh lines: centre and end within the configured atol."""
    from roughcontact.fe.beam import beam_case

    case = "3"
    run = {"family": "quadratic", "case": case, "m00": BEAM["cases"][case]["m00"], "law": "elastic",
           "E_star": E_STAR, "tangential": "free", "surface": BEAM["surface"], "spec": BEAM["spec"]}
    ours = beam_case(run)
    spec = ours.spec
    f = calculix.engine_deflections_um(ours.solution.model.points.x[:, 0], ours.solution.model.points.x[:, 1],
                                       -ours.solution.point_fields(-1, reference=0)["closure_mm"] * 1000.0, spec)
    table, text = _table(case, spec)
    dat, seconds = calculix.run_ccx(calculix.beam_deck(text, spec), "beam", tmp_path)
    got = calculix.beam_deflections_um(dat, spec)
    for q in ("centre", "end"):
        assert abs(got[f"{q}_um"] - f[f"{q}_um"]) <= CFG["tolerances"]["beam"]["atol"], (q, got, f)
    assert got["centre_node_spread_um"] > 5 * abs(got["centre_um"] - f["centre_um"])  # the ripple is real


def test_skipped_scene_says_why():
    md = calculix.render_markdown([], [], {}, "", skipped_reason=calculix.skipped_line())
    assert "skipped: ccx not installed — `apt-get install calculix-ccx`" in md
    # the same install line as the gate's declaration of the optional scene
    data = yaml.safe_load((Path(__file__).resolve().parents[2] / "config" / "expected_verdicts.yaml").read_text())
    assert data["expected_checks"]["calculix"]["install"] == calculix.CCX_INSTALL
