"""The exported table in CalculiX: decks (always), the block and the beam in ccx (where ccx is
installed; skipped cleanly elsewhere)."""

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from roughcontact.examples.beam import BeamSpec
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


def test_beam_deck_load_weights():
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
    from roughcontact.examples.beam import run_beam
    from roughcontact.examples.runs import beam_run

    case = "3"
    ours = run_beam(beam_run(BEAM, "quadratic", case))
    spec = ours.spec
    points = ours.point_fields()
    f = calculix.engine_deflections_um(points["x"][:, 0], points["x"][:, 1], points["u_N_um"], spec)
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


def test_node_prints_stop_at_the_next_print():
    """A *CONTACT PRINT after the *NODE PRINT has 4-column rows too: they are not displacements."""
    dat = """
 displacements (vx,vy,vz) for set BOTTOM and time  0.1000000E+01

        11  0.000000E+00  0.000000E+00 -4.328515E-04
        12  1.428571E-06  0.000000E+00 -4.328515E-04

 contact stress (slave node,press,tang1,tang2) for all contact elements and time 0.1000000E+01

        11  1.000000E+00  0.000000E+00  0.000000E+00
"""
    (t, rows), = calculix.node_prints(dat, "BOTTOM")
    assert t == 1.0 and sorted(rows) == [11, 12] and rows[11][2] == -4.328515e-4


# ---------------------------------------------------------------------------------------------
# one deck in both codes (roughcontact.paper.calculix_deck, examples.block_on_base)
# ---------------------------------------------------------------------------------------------
def test_first_order_extrapolation():
    from roughcontact.paper.calculix_deck import extrapolated

    # u = u_inf + c h: exact for a first-order error
    assert extrapolated([1, 2], [3.0 + 0.5, 3.0 + 0.25]) == pytest.approx(3.0, rel=1e-15)
    assert extrapolated([1, 2, 3], [9.0, 3.0 + 0.25, 3.0 + 0.5 / 3]) == pytest.approx(3.0, rel=1e-14)


def test_block_on_base_deck_is_one_deck_for_both_codes():
    """The deck reads here with the table in place (replaced by the law, a note says so), has
    what ccx reads (numbered dofs, no Abaqus-only shorthands, fields <= 20 characters), two
    materials, a base larger than the block and a load on part of the block's top."""
    from roughcontact.examples.block_on_base import BlockOnBase, block_on_base_deck
    from roughcontact.fe.deck import read_deck
    from roughcontact.fe.deck_mesh import deck_mesh

    table = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n0.0, -1.0e-4\n100.0, 1.0e-3"
    text = block_on_base_deck(BlockOnBase(refine=1), table)
    d = read_deck("bob.inp", text)
    assert set(d.materials) == {"STEEL", "ALUMINIUM"} and any("replaced by the law ROUGH" in n for n in d.notes)
    assert not any(k in text for k in ("XSYMM", "YSYMM", "ENCASTRE"))
    data = [line for line in text.splitlines() if line[:1].isdigit() or line[:1] == "-"]
    assert data and all(len(f.strip()) <= 20 for line in data for f in line.split(","))
    base = d.coords[d.node_index(d.nsets["BOTTOM"])]
    loaded = d.coords[d.node_index(d.nsets["LOADED"])]
    assert np.ptp(base[:, 0]) == 40.0 and loaded[:, 0].min() == -5.0 and loaded[:, 0].max() == 10.0
    dm = deck_mesh(d, "quadratic")
    assert len(dm.mesh.interfaces[0].cells) == 4  # the block's bottom; the base's other top faces stay free


@needs_ccx
@pytest.mark.slow
def test_block_on_base_in_both_codes(tmp_path):
    """Refinement 1 only (the scene refines; `snakemake fe_calculix`): ccx and the engine run the
    same deck; their loaded faces move within 5 % (measured 4.0 %: both first order, from
    opposite sides; the scene extrapolates)."""
    from roughcontact.paper.calculix_deck import run_refinement

    row = run_refinement(CFG, 1, tmp_path)
    assert abs(row["rel_difference"]) < 0.05 and row["ccx_um"] < row["engine_um"] < 0
