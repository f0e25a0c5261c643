"""A C3D10 deck from text to result (issue 31): two tetrahedral blocks (hexahedral grid cells
split into six tetrahedra, roughcontact.fe.tetra) in contact through 6+6 interface elements on
conforming triangles, read by `fe run`'s reader and solved by the engine with the statistical
law. Frictionless, a uniaxial block on a uniaxial base has the closed form of
docs/own-model.md: the top moves by the law's closure c(p) plus p H/E of both bodies, which
quadratic tetrahedra represent exactly (a linear displacement field). Mixed C3D10/C3D20 pairs
are refused (tests/fe/test_tetra_deck.py)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from roughcontact.fe.deck_run import run_deck_file
from roughcontact.fe.element import TET10_FACES
from roughcontact.fe.tetra import box_tets

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"
H, STEEL_E, ALUMINIUM_E = 10.0, 2.1e5, 7.0e4  # mm, N/mm²: block (steel) and base (aluminium), as block.inp
PRESSURE = 5.0  # N/mm² on the top


def _faces_on(mesh, plane: str):
    """(cell index, S number) of the tetrahedra's faces on one of box_tets' planes."""
    cells = mesh.blocks[0].cells
    on = np.zeros(len(mesh.points), bool)
    on[mesh.node_sets[plane]] = True
    out = []
    for s in range(1, 5):
        hit = np.flatnonzero(np.all(on[cells[:, list(TET10_FACES[s])]], axis=1))
        out += [(int(c), s) for c in hit]
    return sorted(out)


def _body(z_edges, node0: int, elem0: int, name: str):
    """Deck lines (nodes, elements) of a 10 × 10 mm box split into tetrahedra, its node ids by
    box_tets' node index, and its element ids."""
    mesh = box_tets([0.0, 5.0, 10.0], [0.0, 5.0, 10.0], z_edges)
    ids = node0 + np.arange(len(mesh.points))
    lines = [f"*NODE, NSET={name}NODES"] + [f"{i}, {float(x)!r}, {float(y)!r}, {float(z)!r}" for i, (x, y, z) in zip(ids, mesh.points)]
    lines.append(f"*ELEMENT, TYPE=C3D10, ELSET={name}")
    cells = mesh.blocks[0].cells
    lines += [f"{elem0 + e}, " + ", ".join(str(ids[n]) for n in cell) for e, cell in enumerate(cells)]
    return mesh, ids, lines


def _nset(name: str, ids) -> list[str]:
    ids = [str(int(i)) for i in ids]
    return [f"*NSET, NSET={name}"] + [", ".join(ids[k:k + 16]) for k in range(0, len(ids), 16)]


def _deck(tmp_path: Path) -> Path:
    base, base_ids, base_lines = _body([-10.0, -5.0, 0.0], 1, 1, "BASE")
    block, block_ids, block_lines = _body([0.0, 5.0, 10.0], 10001, 1001, "BLOCK")
    both = lambda plane: np.concatenate([base_ids[base.node_sets[plane]], block_ids[block.node_sets[plane]]])  # noqa: E731
    lines = ["*HEADING", "two C3D10 blocks (issue 31)", *base_lines, *block_lines,
             *_nset("BOTTOM", base_ids[base.node_sets["zmin"]]),
             *_nset("XSYM", both("xmin")), *_nset("YSYM", both("ymin")),
             *_nset("TOP", block_ids[block.node_sets["zmax"]]),
             "*SURFACE, NAME=BLOCKBOTTOM", *[f"{1001 + c}, S{s}" for c, s in _faces_on(block, "zmin")],
             "*SURFACE, NAME=BASETOP", *[f"{1 + c}, S{s}" for c, s in _faces_on(base, "zmax")],
             "*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3",
             "*MATERIAL, NAME=ALUMINIUM", "*ELASTIC", "70000., 0.33",
             "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL", "*SOLID SECTION, ELSET=BASE, MATERIAL=ALUMINIUM",
             "*SURFACE INTERACTION, NAME=ROUGH", "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=SURFACE TO SURFACE",
             "BLOCKBOTTOM, BASETOP",
             "*BOUNDARY", "BOTTOM, 3, 3", "XSYM, 1, 1", "YSYM, 2, 2",
             "*STEP", "*STATIC", "0.25, 1.", "*DLOAD",
             *[f"{1001 + c}, P{s}, {PRESSURE}" for c, s in _faces_on(block, "zmax")], "*END STEP"]
    path = tmp_path / "tets.inp"
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("tets")
    law = yaml.safe_load((EXAMPLES / "block.yaml").read_text())
    law["interactions"]["ROUGH"]["friction"] = "none"
    (tmp / "law.yaml").write_text(yaml.safe_dump(law))
    return run_deck_file(_deck(tmp), tmp / "law.yaml")


def test_a_c3d10_deck_is_the_closed_form(result):
    """The top's u_z is c(p) + p H/E of both bodies at every top node, to 1e-9 (the hexahedral
    deck's bound in tests/fe/test_own_model_doc.py)."""
    law = result.problem.materials.parts[0][0].normal
    c_um = law.h_ref - law.table.separation_at(PRESSURE)
    expected = -(c_um * 1e-3 + PRESSURE * H / STEEL_E + PRESSURE * H / ALUMINIUM_E)
    _, u = result.node_sets(result.step_end(1))["TOP"]
    np.testing.assert_allclose(u[:, 2], expected, rtol=1e-9)


def test_the_interface_carries_the_load(result):
    """Every interface point at the applied pressure (uniform contact), the points on the 6+6
    elements of the eight contact triangles."""
    import roughcontact.interface.friction as friction

    state = result.step_end(1).state
    np.testing.assert_allclose(state[:, friction.T_N], PRESSURE, rtol=1e-9)
    assert result.problem.points.n_points % 8 == 0 and result.problem.points.n_points > 0


def test_the_tetrahedral_result_writes_for_paraview(result, tmp_path):
    """--vtu of a C3D10 model: VTK's quadratic tetra (its node order is C3D10's) and the 6-node
    interface triangles, read back by meshio with the displacement at every node."""
    import meshio

    from roughcontact.fe import vtu

    mesh = result.problem.dm.mesh
    u = result.step_end(1).u
    volume, _ = vtu.write_solution(tmp_path / "tets.vtu", mesh, u, {"x": np.zeros((1, 3))})
    back = meshio.read(volume)
    assert {c.type for c in back.cells} == {"tetra10"}  # meshio joins blocks of one type
    assert sum(len(c.data) for c in back.cells) == sum(len(b.cells) for b in mesh.blocks)
    np.testing.assert_allclose(back.point_data["displacement_mm"], np.asarray(u).reshape(-1, 3))
    faces = meshio.read(vtu.write_interfaces(tmp_path / "faces.vtu", mesh))
    assert {c.type for c in faces.cells} == {"triangle6"}
