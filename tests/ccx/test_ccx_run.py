"""The interface law inside CalculiX (`roughcontact ccx build`, `ccx run`) against the engine
(`fe run`) on the same decks. Needs the cached build (CI makes it with `roughcontact ccx build`
before the tests; without it these skip with one line, and tests/ccx/test_build.py runs the
absent path)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from roughcontact.ccx.build import find_build

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"
BUILD = find_build()
pytestmark = pytest.mark.skipif(BUILD is None, reason="no ccx with the interface law: run `roughcontact ccx build`")


def _both(deck, laws, tmp_path, **kw):
    from roughcontact.ccx.run import run_deck_in_ccx
    from roughcontact.fe.deck_run import run_deck_file

    ccx = run_deck_in_ccx(deck, laws, BUILD.executable, keep=tmp_path / "job", progress=lambda m: None, **kw)
    engine = run_deck_file(deck, laws).summary()
    return ccx, engine


def _mean_u(run, step, name):
    return np.mean(np.asarray(run["steps"][step]["node_sets"][name]["u"]), axis=0)


def test_the_own_model_example_in_ccx_as_in_the_engine(tmp_path):
    """docs/own-model.md's block (the quarter, orthotropic hardening friction, loaded then unloaded)."""
    ccx, engine = _both(EXAMPLES / "block.inp", EXAMPLES / "block.yaml", tmp_path)
    assert set(engine) - {"vtu"} <= set(ccx)  # the fe run contract
    assert [s["step"] for s in ccx["steps"]] == [1, 2]
    for k in range(2):
        a, b = _mean_u(ccx, k, "TOP"), _mean_u(engine, k, "TOP")
        assert abs(a[2] - b[2]) <= 0.03 * abs(b[2]), (k, a, b)
        # the closure averaged over the interface: both integrate the same law over the same faces
        wa, wb = np.mean(ccx["steps"][k]["interface"]["u_N_um"]), np.mean(engine["steps"][k]["interface"]["u_N_um"])
        assert abs(wa - wb) <= 0.03 * abs(wb)
    assert (tmp_path / "job" / "block_ccx.inp").is_file()  # kept for one's own ccx
    assert ccx["E_star"] == pytest.approx(engine["E_star"], rel=1e-15)


def test_eccentric_load_then_shear_with_orthotropic_hardening_friction(tmp_path):
    """Issue 30's acceptance in the open: two C3D20 bodies, conforming faces, an eccentric load, then
    a tangential step; mean displacement of the loaded face within 3 %, the relative tangential
    displacement of the contact faces within 5 % of the engine's largest."""
    from roughcontact.examples.block_on_base import BlockOnBase, block_on_base_deck
    from roughcontact.fe.laws import Orthotropic

    spec = BlockOnBase(refine=1, pressure=10.0, increments=4, seating_pressure=0.1, shear=2.5,
                       friction=Orthotropic((0.5, 0.3), (0.5, 0.3), (275.0, 275.0), (0.7, 1.0)))
    deck, laws = tmp_path / "shear.inp", tmp_path / "shear.yaml"
    deck.write_text(block_on_base_deck(spec))
    laws.write_text(spec.law_file().to_yaml())
    ccx, engine = _both(deck, laws, tmp_path)
    for k in range(2):
        a, b = _mean_u(ccx, k, "LOADED"), _mean_u(engine, k, "LOADED")
        assert np.linalg.norm(a - b) <= 0.03 * np.linalg.norm(b), (k, a, b)

    def slips(run, k):
        ns = run["steps"][k]["node_sets"]
        s, m = (dict(zip(ns[n]["nodes"], np.asarray(ns[n]["u"]))) for n in ("CONTACTSLAVE", "CONTACTMASTER"))
        return s, m

    s_c, m_c = slips(ccx, 1)
    s_e, m_e = slips(engine, 1)
    from roughcontact.fe.deck import read_deck

    d = read_deck(deck)
    xyz = {n: x for n, x in zip(d.node_ids.tolist(), d.coords)}
    pairs = [(s, m) for s in s_e for m in m_e if np.allclose(xyz[s], xyz[m])]
    assert len(pairs) == len(s_e)
    rel_c = np.array([s_c[s][:2] - m_c[m][:2] for s, m in pairs])
    rel_e = np.array([s_e[s][:2] - m_e[m][:2] for s, m in pairs])
    largest = np.abs(rel_e).max()
    assert largest > 0.0
    assert np.abs(rel_c - rel_e).max() <= 0.05 * largest
    # the friction state: both slip somewhere, and dissipate
    assert "slip" in ccx["steps"][1]["interface"]["status"]


def test_the_command_prints_the_json_of_fe_run(tmp_path, capsys):
    from roughcontact.cli import main

    code = main(["ccx", "run", str(EXAMPLES / "block.inp"), "--interface", str(EXAMPLES / "block.yaml"), "--json",
                 "--quiet", "--keep", str(tmp_path / "kept")])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ccx"]["job"] == str(tmp_path / "kept") and out["interface_points"] == 4 * 9
    assert len(out["steps"][0]["interface"]["p_N"]) == out["interface_points"]


def test_a_c3d10_deck_in_ccx_is_the_closed_form(tmp_path):
    """The two tetrahedral blocks of tests/fe/test_tetra_run.py (6 + 6 user elements, URCT6):
    frictionless, uniform pressure: the top moves by the law's closure c(p) plus p H/E of both
    bodies, which quadratic tetrahedra represent exactly; to the 7 digits ccx prints."""
    import importlib.util

    import yaml

    from roughcontact.ccx.run import run_deck_in_ccx
    from roughcontact.fe.laws import read_law_file

    spec = importlib.util.spec_from_file_location("tetra_run", Path(__file__).parents[1] / "fe" / "test_tetra_run.py")
    tetra = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tetra)
    law = yaml.safe_load((EXAMPLES / "block.yaml").read_text())
    law["interactions"]["ROUGH"]["friction"] = "none"
    (tmp_path / "law.yaml").write_text(yaml.safe_dump(law))
    out = run_deck_in_ccx(tetra._deck(tmp_path), tmp_path / "law.yaml", BUILD.executable, progress=lambda m: None)
    normal = read_law_file(tmp_path / "law.yaml").interactions["ROUGH"].material("mm", 58605.1963274077).normal
    c_um = normal.h_ref - normal.table.separation_at(tetra.PRESSURE)
    expected = -(c_um * 1e-3 + tetra.PRESSURE * tetra.H / tetra.STEEL_E + tetra.PRESSURE * tetra.H / tetra.ALUMINIUM_E)
    u = np.asarray(out["steps"][0]["node_sets"]["TOP"]["u"])
    np.testing.assert_allclose(u[:, 2], expected, rtol=2e-6)
    # the pressure at the points carries ccx's own equilibrium tolerance (its Newton stops at a residual
    # of 0.5 % of the average force, *CONTROLS R_n^alpha = 0.005): 7e-6 here
    np.testing.assert_allclose(out["steps"][0]["interface"]["p_N"], tetra.PRESSURE, rtol=1e-5)
    assert out["elements"].endswith("URCT6")
