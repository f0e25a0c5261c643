"""Decks solved through the reader (roughcontact.fe.deck_run), against closed forms and symmetries:

* patch test: a block on a base under uniform pressure (two materials, frictionless, rollers
  and symmetry planes: uniaxial stress in both bodies) closes uniformly by the law's inverse
  c(p) = h_ref − h(p) (NormalLawTable.separation_at, independent of the engine) to 1e-9, through
  three steps with Abaqus semantics; the top moves by c(p) + p H/E of both bodies; a prescribed
  top displacement in its place gives back the pressure;
* a deck turned by an arbitrary rotation (lay direction, forces and coordinates with it) gives
  the same results in the turned axes;
* an orthotropic law with the lay along x, then along y, swaps the slip components;
* the run's JSON and ParaView series.
"""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from roughcontact.asperity import effective_modulus
from roughcontact.fe.deck import read_deck
from roughcontact.fe.deck_run import run_deck_file
from roughcontact.fe.deck_syntax import DeckError
from roughcontact.fe.laws import read_law_file

STEEL, ALUMINIUM = (2.1e5, 0.3), (7.0e4, 0.33)
BLOCK, BASE_DEPTH = (10.0, 10.0, 8.0), 6.0
PRESSURES = (1.0, 5.0, 0.5)  # N/mm², the three steps: load, more, unload


def expected_closure_um(law, p) -> float:
    """c(p) = h_ref − h(p) [µm] of the law's table (root finding on the tabulated law)."""
    return law.h_ref - law.table.separation_at(p)


@pytest.fixture(scope="module")
def patch_runs(tmp_path_factory):
    from roughcontact.fe.deck_writer import box_part  # noqa: F401

    tmp = tmp_path_factory.mktemp("patch")
    import importlib.util
    import pathlib

    spec = importlib.util.spec_from_file_location("deck_conftest", pathlib.Path(__file__).with_name("conftest.py"))
    cf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cf)
    steps = tuple({"pressure": p, "increments": k} for p, k in zip(PRESSURES, (2, 3, 1)))
    (tmp / "m.inp").write_text(cf._block_deck(n=2, block=BLOCK, base_depth=BASE_DEPTH, steps=steps,
                                              materials=(STEEL, ALUMINIUM)))
    law = cf._law_file(tmp / "law.yaml")
    return {family: run_deck_file(tmp / "m.inp", law, family) for family in ("quadratic", "cubic")}, cf, tmp


@pytest.mark.parametrize("family", ["quadratic", "cubic"])
def test_patch_uniform_closure_is_the_laws_inverse(patch_runs, family):
    runs, _, _ = patch_runs
    res = runs[family]
    law = res.problem.materials.parts[0][0].normal
    assert res.problem.E_star["ROUGH"] == effective_modulus(*STEEL, *ALUMINIUM)  # eq. (42) from *ELASTIC
    for step, p in enumerate(PRESSURES, start=1):
        inc = res.step_end(step)
        f = res.interface_fields(inc)
        c = expected_closure_um(law, p)
        np.testing.assert_allclose(f["u_N_um"], c, rtol=1e-9, atol=0)
        np.testing.assert_allclose(f["p_N"], p, rtol=1e-9)
        assert set(f["status"].tolist()) == {1}  # frictionless, closed: slip
        # uniaxial stress in both bodies: the top moves down by c + p H/E (block, base)
        ids, u = res.node_sets(inc)["BLOCKTOPNODES"]
        top = -(c * 1e-3 + p * BLOCK[2] / ALUMINIUM[0] + p * BASE_DEPTH / STEEL[0])
        np.testing.assert_allclose(u[:, 2], top, rtol=1e-9)
    assert [s.index for s in res.problem.dm.deck.steps] == [1, 2, 3]
    assert [sum(1 for i in res.increments if i.step == k) for k in (1, 2, 3)] == [2, 3, 1]


def test_prescribed_top_displacement_gives_back_the_pressure(patch_runs, tmp_path):
    """Step 2 removes the pressure (*DLOAD, OP=NEW) and prescribes the top's u_z that 5 N/mm²
    gives (closed form): the interface carries 5 N/mm² again, to 1e-8."""
    runs, cf, tmp = patch_runs
    law = runs["quadratic"].problem.materials.parts[0][0].normal
    p = 5.0
    top = -(expected_closure_um(law, p) * 1e-3 + p * BLOCK[2] / ALUMINIUM[0] + p * BASE_DEPTH / STEEL[0])
    text = cf._block_deck(n=2, block=BLOCK, base_depth=BASE_DEPTH, steps=({"pressure": 1.0, "increments": 1},),
                          materials=(STEEL, ALUMINIUM))
    text += f"*STEP\n*STATIC\n0.5, 1.\n*DLOAD, OP=NEW\n*BOUNDARY\nBLOCKTOPNODES, 3, 3, {top!r}\n*END STEP\n"
    (tmp_path / "m.inp").write_text(text)
    res = run_deck_file(tmp_path / "m.inp", tmp / "law.yaml", "quadratic")
    np.testing.assert_allclose(res.interface_fields(res.step_end(2))["p_N"], p, rtol=1e-8)
    ids, u = res.node_sets(res.step_end(2))["BLOCKTOPNODES"]
    np.testing.assert_allclose(u[:, 2], top, rtol=1e-14)


def test_the_solver_gets_the_node_coordinates(patch_runs, monkeypatch):
    """run_deck gives the solver the mesh's node coordinates, so that its linear solvers factor
    in nested-dissection order as ContactModel.assemble's models do (without them the solvers
    fall back to reverse Cuthill–McKee: docs/performance.md, "FE engine", has the fill and the
    times of both on the benchmark's decks)."""
    from roughcontact.fe import deck_run

    runs, _, _ = patch_runs
    problem, seen = runs["quadratic"].problem, []
    solve = deck_run.solve
    monkeypatch.setattr(deck_run, "solve", lambda model, *a, **k: seen.append(model) or solve(model, *a, **k))
    deck_run.run_deck(problem)
    assert len(seen) == 1  # the three steps share one load path
    np.testing.assert_array_equal(seen[0].coordinates, problem.mesh.points)


def test_an_interaction_without_a_law(patch_runs, tmp_path):
    _, cf, tmp = patch_runs
    (tmp_path / "law.yaml").write_text((tmp / "law.yaml").read_text().replace("ROUGH:", "SMOOTH:"))
    with pytest.raises(DeckError, match=r"m\.inp:\d+: interaction ROUGH has no law in the law file \(it gives SMOOTH\)"):
        run_deck_file(tmp / "m.inp", tmp_path / "law.yaml")


def test_the_json_and_the_series(patch_runs, tmp_path):
    from roughcontact.fe.pvd import write_series

    runs, _, _ = patch_runs
    res = runs["cubic"]
    s = json.loads(json.dumps(res.summary(), allow_nan=False))
    assert s["dofs"] == res.n_dofs and s["interface_points"] == 49 and s["seconds"] > 0
    assert s["newton_iterations"] == sum(i.iterations for i in res.increments)
    assert [st["step"] for st in s["steps"]] == [1, 2, 3] and s["steps"][1]["time"] == 2.0
    step = s["steps"][1]
    assert set(step["interface"]) == {"x", "y", "z", "u_N_um", "p_N", "t_1", "t_2", "slip_1_um", "slip_2_um", "status"}
    assert set(step["interface"]["status"]) == {"slip"} and len(step["interface"]["p_N"]) == 49
    assert set(step["node_sets"]) == {"BASENODES", "BLOCKNODES", "BLOCKTOPNODES", "LOADNODE", "BASEBOTTOM", "XSYM", "YSYM"}
    ns = step["node_sets"]["XSYM"]
    assert len(ns["nodes"]) == len(ns["u"]) and np.allclose(np.asarray(ns["u"])[:, 0], 0.0)
    assert np.allclose(s["interface_axes"]["e_1"], [1, 0, 0]) and np.allclose(s["interface_axes"]["n"], [0, 0, 1])
    # the series: two files per increment, the JSON's names and the status legend
    pvd = write_series(tmp_path / "run.pvd", res)
    text = pvd.read_text()
    assert "status: 0 stick, 1 slip, 2 open" in text
    sets = ET.fromstring(text).findall(".//DataSet")
    assert len(sets) == 2 * len(res.increments) and {d.get("part") for d in sets} == {"0", "1"}
    last = [d for d in sets if d.get("part") == "1"][-1]
    pts = meshio.read(tmp_path / last.get("file"))
    for name in ("u_N_um", "p_N", "t_1", "t_2", "slip_1_um", "slip_2_um", "status", "e_1", "e_2", "n"):
        assert name in pts.point_data
    np.testing.assert_allclose(np.sort(pts.point_data["p_N"]), np.sort(s["steps"][-1]["interface"]["p_N"]))
    body = meshio.read(tmp_path / [d for d in sets if d.get("part") == "0"][-1].get("file"))
    assert body.point_data["displacement"].shape[1] == 3
    stress = np.concatenate(body.cell_data["stress"])
    np.testing.assert_allclose(stress[:, 2], -PRESSURES[-1], rtol=1e-8)  # uniaxial: σ_zz = −p everywhere
    with pytest.raises(ValueError, match=".pvd"):
        write_series(tmp_path / "run.vtu", res)


# ---------------------------------------------------------------------------------------------
# rotation invariance and the lay direction
# ---------------------------------------------------------------------------------------------
ORTHO = {"orthotropic": {"mu_m": [0.3, 0.6], "mu_o": 1.0, "nu_x": 0.125, "nu_y": 0.125, "n_x": 0.0, "n_y": 0.0,
                         "kt_over_kn": [0.5, 1.0]}}


def _deck(cf, tmp, name, rotation=None, force=(30.0, 10.0, 0.0)):
    steps = ({"pressure": 2.0, "increments": 2}, {"pressure": 2.0, "increments": 3, "cloads": [("LOADNODE", force)]})
    (tmp / name).write_text(cf._block_deck(n=2, symmetry="none", support="encastre", base_scale=2.0, steps=steps,
                                           rotation=rotation))
    return tmp / name


def test_a_turned_deck_gives_the_same_results(patch_runs, tmp_path):
    """Q turns the coordinates, the forces and the lay direction: u_Q = Q u at every node and
    the interface fields (in the law's own axes) equal point by point, to 1e-9."""
    _, cf, _ = patch_runs
    Q = Rotation.from_rotvec(0.7 * np.array([1.0, 2.0, 3.0]) / math.sqrt(14.0)).as_matrix()
    plain = run_deck_file(_deck(cf, tmp_path, "a.inp"), cf._law_file(tmp_path / "a.yaml", friction=ORTHO), "quadratic")
    turned = run_deck_file(_deck(cf, tmp_path, "b.inp", Q),
                           cf._law_file(tmp_path / "b.yaml", friction=ORTHO, lay=(Q @ [1.0, 0.0, 0.0]).tolist()),
                           "quadratic")
    a, b = plain.increments[-1], turned.increments[-1]
    fa, fb = plain.interface_fields(a), turned.interface_fields(b)
    assert np.any(fa["status"] == 1) and np.any(fa["status"] == 0)  # some points slip, some stick
    xa = plain.problem.points.x
    xb = turned.problem.points.x @ Q  # back to the plain deck's axes
    match = [int(np.argmin(np.linalg.norm(xb - x, axis=1))) for x in xa]
    assert np.allclose(xb[match], xa, atol=1e-9)
    for k in ("u_N_um", "p_N", "t_1", "t_2", "slip_1_um", "slip_2_um"):
        scale = np.abs(fa[k]).max()
        np.testing.assert_allclose(fb[k][match], fa[k], rtol=0, atol=1e-9 * scale, err_msg=k)
    np.testing.assert_array_equal(fb["status"][match], fa["status"])
    ua = plain.node_sets(a)["BLOCKNODES"][1]
    ub = turned.node_sets(b)["BLOCKNODES"][1]
    np.testing.assert_allclose(ub @ Q, ua, rtol=0, atol=1e-9 * np.abs(ua).max())


def test_the_lay_along_y_swaps_the_slip_components(patch_runs, tmp_path):
    """A square block pulled along the diagonal (mirror-symmetric under x <-> y) with an
    orthotropic law: the lay along y gives the mirror image of the lay along x — the global slip
    at the mirrored point is the mirrored slip, i.e. the x and y components swap — while the
    lay along x alone is not symmetric."""
    _, cf, _ = patch_runs
    deck = _deck(cf, tmp_path, "d.inp", force=(45.0, 45.0, 0.0))
    runs = {lay: run_deck_file(deck, cf._law_file(tmp_path / f"{lay}.yaml", friction=ORTHO, lay=vec), "quadratic")
            for lay, vec in (("x", (1, 0, 0)), ("y", (0, 1, 0)))}
    slip = {}
    for lay, r in runs.items():
        f = r.interface_fields(r.increments[-1])
        e1, e2 = r.problem.points.frames[:, 0], r.problem.points.frames[:, 1]
        slip[lay] = f["slip_1_um"][:, None] * e1 + f["slip_2_um"][:, None] * e2  # global (x, y, z)
    x = runs["x"].problem.points.x
    mirror = [int(np.argmin(np.linalg.norm(x[:, [1, 0, 2]] - p, axis=1))) for p in x]
    scale = np.abs(slip["x"]).max()
    assert scale > 0
    np.testing.assert_allclose(slip["y"][mirror][:, [1, 0, 2]], slip["x"], rtol=0, atol=1e-8 * scale)
    assert np.abs(slip["x"][mirror][:, [1, 0, 2]] - slip["x"]).max() > 0.05 * scale  # x alone is not symmetric


def test_two_interactions_in_one_deck(tmp_path):
    """A stack of three bodies (quarter, rollers, symmetry planes) with two contact pairs of two
    interactions: each interface closes by its own law's inverse, E* of each from its bodies (the
    middle body two elements thick: an element touches on one face only)."""
    from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines

    xy = [0.0, 5.0, 10.0]
    parts = [box_part(xy, xy, [-4.0, 0.0]), box_part(xy, xy, [0.0, 2.0, 4.0], first_node=1001, first_element=101),
             box_part(xy, xy, [4.0, 8.0], first_node=2001, first_element=201)]
    names = ("LOW", "MID", "TOP")
    mats = {"LOW": (2.1e5, 0.3), "MID": (7.0e4, 0.33), "TOP": (1.2e5, 0.34)}
    lines = ["*HEADING", "a stack of three"]
    for p, n in zip(parts, names):
        lines += node_lines(p, f"{n}NODES")
    for p, n in zip(parts, names):
        lines += element_lines(p, n)
    lines += id_lines("*NSET, NSET=XSYM", np.concatenate([p.face_nodes["XMIN"] for p in parts]))
    lines += id_lines("*NSET, NSET=YSYM", np.concatenate([p.face_nodes["YMIN"] for p in parts]))
    lines += id_lines("*NSET, NSET=FLOOR", parts[0].face_nodes["ZMIN"])
    lines += id_lines("*ELSET, ELSET=TOPFACES", parts[2].face_elements["ZMAX"])
    for p, n in zip(parts, names):
        lines += [f"*SURFACE, NAME={n}DOWN", *(f"{e}, S1" for e in p.face_elements["ZMIN"]),
                  f"*SURFACE, NAME={n}UP", *(f"{e}, S2" for e in p.face_elements["ZMAX"]),
                  f"*MATERIAL, NAME={n}MAT", "*ELASTIC", f"{mats[n][0]}, {mats[n][1]}",
                  f"*SOLID SECTION, ELSET={n}, MATERIAL={n}MAT"]
    lines += ["*SURFACE INTERACTION, NAME=SMOOTH", "*SURFACE INTERACTION, NAME=ROUGH",
              "*CONTACT PAIR, INTERACTION=SMOOTH", "MIDDOWN, LOWUP", "*CONTACT PAIR, INTERACTION=ROUGH", "TOPDOWN, MIDUP",
              "*BOUNDARY", "FLOOR, 3, 3", "XSYM, 1, 1", "YSYM, 2, 2",
              "*STEP", "*STATIC", "0.5, 1.", "*DLOAD", "TOPFACES, P2, 3.", "*END STEP"]
    (tmp_path / "stack.inp").write_text("\n".join(lines) + "\n")
    laws = {"length_unit": "mm", "interactions": {
        "smooth": {"moments": {"m00": 0.0625, "m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4, "unit": "um"},
                   "lay_direction": [1, 0, 0], "law": "elastic", "seating_pressure": 1e-3},
        "rough": {"moments": {"m00": 0.625e-6, "m20": 8e-5, "m02": 8e-4, "m40": 1.04, "m04": 104.0, "unit": "mm"},
                  "lay_direction": [0, 1, 0], "law": "elastic", "seating_pressure": 1e-2}}}
    (tmp_path / "laws.yaml").write_text(__import__("yaml").safe_dump(laws))
    res = run_deck_file(tmp_path / "stack.inp", tmp_path / "laws.yaml", "cubic")
    f = res.interface_fields(res.increments[-1])
    assert list(res.problem.E_star) == ["SMOOTH", "ROUGH"]
    assert res.problem.E_star["SMOOTH"] == effective_modulus(*mats["MID"], *mats["LOW"])
    assert res.problem.E_star["ROUGH"] == effective_modulus(*mats["TOP"], *mats["MID"])
    for k, (material, a, b) in enumerate(res.problem.materials.parts):
        law = material.normal
        um_per_unit = 1.0 if k == 0 else 1000.0  # the second law is in mm: its closure reported in µm
        np.testing.assert_allclose(f["u_N_um"][a:b], expected_closure_um(law, 3.0) * um_per_unit, rtol=1e-9)
        np.testing.assert_allclose(f["p_N"][a:b], 3.0, rtol=1e-9)
    axes = res.summary()["interface_axes"]
    assert axes["interaction"][0] == "SMOOTH" and axes["interaction"][-1] == "ROUGH"
    assert np.allclose(axes["e_1"][-1], [0, 1, 0]) and np.allclose(axes["e_2"][-1], [-1, 0, 0])


def test_validity_is_judged_on_the_solved_pressures(block_deck, write_deck, law_file):
    """Issue 22: the FE runs printed the law table's validity warnings (A/A0 = 2.19 at its end),
    the same lines for every load. Now the largest solved pressure of each interaction decides:
    the same deck and law (m00 = 0.625 um², E* 1.07e5, table to 1000 N/mm²) say nothing at
    100 N/mm² and the area-ratio warning at 300 N/mm² (A/A0 = 0.117 there, limit 0.1)."""
    moments = {"m00": 0.625, "m20": 8.0e-5, "m02": 8.0e-4, "m40": 1.04e-6, "m04": 1.04e-4, "unit": "um"}
    # E* apart from the deck's steel (eq. (42): 1.154e5) on purpose, so the law is given as a LawFile
    # object, which run_deck_file does not check against the deck (a law file read from a path
    # for it would be refused since issue 29)
    law = read_law_file(law_file(moments=moments, E_star=1.0667e5, pressure_range=[1e-4, 1000.0]))
    said = {}
    for p in (100.0, 300.0):
        res = run_deck_file(write_deck(block_deck(n=1, steps=({"pressure": p, "increments": 1},)), f"p{p:g}.inp"),
                            law, "quadratic")
        assert np.allclose(res.interface_fields(res.increments[-1])["p_N"], p, rtol=1e-9)
        said[p] = res.validity_warnings()
    assert said[100.0] == []
    assert len(said[300.0]) == 1 and "interaction ROUGH: at the largest solved pressure 300" in said[300.0][0]
    assert "A/A0 = 0.117" in said[300.0][0]


def test_a_converged_state_past_the_table_names_its_law(block_deck, write_deck, law_file):
    """The robust Newton's range check on a deck's laws (InterfaceLaws.beyond_table, normal_of):
    a load whose solved pressure lies past the table's heavy end is a clear error naming that
    law's p_max, not an answer resting on the extrapolated tail."""
    from roughcontact.fe.deck_run import DeckConvergenceError

    law = law_file(pressure_range=[1e-4, 10.0])
    with pytest.raises(DeckConvergenceError, match=r"step 1 .*p_N up to 50 .*\(p_max = 10\)"):
        run_deck_file(write_deck(block_deck(n=1, steps=({"pressure": 50.0, "increments": 1},))), law, "quadratic")
