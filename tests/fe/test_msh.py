"""From gmsh to a run (issue 31, roughcontact.fe.msh): a .msh with physical groups (two stacked
C3D10 boxes, each with its own nodes on the contact plane, written by meshio as gmsh 2.2) becomes a
deck whose *ELSET, *NSET and *SURFACE sets the engine runs once materials, the contact pair and
the step are appended. Frictionless, the top settles by docs/own-model.md's closed form: the
law's closure c(p) plus p H/E of both bodies (exact for quadratic tetrahedra: a linear field)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np
import pytest
import yaml

from roughcontact.fe.deck_run import run_deck_file
from roughcontact.fe.element import HEX20_NODES, TET10_FACES
from roughcontact.fe.msh import MshError, msh_deck
from roughcontact.fe.tetra import box_tets

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"
H, STEEL_E, ALUMINIUM_E, PRESSURE = 10.0, 2.1e5, 7.0e4, 5.0  # mm, N/mm², N/mm², N/mm²
#: physical groups: name → (tag, dim)
GROUPS = {"BASE": (1, 3), "BLOCK": (2, 3), "BASE_TOP": (3, 2), "BLOCK_BOTTOM": (4, 2), "TOP": (5, 2),
          "BOTTOM": (6, 2), "XSYM": (7, 2), "YSYM": (8, 2)}


def _two_boxes():
    """meshio mesh of a 10 × 10 × 10 mm block on a base of the same size (box_tets, the block's
    nodes after the base's), triangle6 faces of the named planes as surface groups."""
    base = box_tets([0.0, 5.0, 10.0], [0.0, 5.0, 10.0], [-10.0, -5.0, 0.0])
    block = box_tets([0.0, 5.0, 10.0], [0.0, 5.0, 10.0], [0.0, 5.0, 10.0])
    shift = len(base.points)
    faces = lambda m, plane, off: m.face_sets[plane].face_nodes + off  # noqa: E731
    cells = [("tetra10", base.blocks[0].cells, "BASE"), ("tetra10", block.blocks[0].cells + shift, "BLOCK"),
             ("triangle6", faces(base, "zmax", 0), "BASE_TOP"), ("triangle6", faces(block, "zmin", shift), "BLOCK_BOTTOM"),
             ("triangle6", faces(block, "zmax", shift), "TOP"), ("triangle6", faces(base, "zmin", 0), "BOTTOM"),
             ("triangle6", np.vstack([faces(base, "xmin", 0), faces(block, "xmin", shift)]), "XSYM"),
             ("triangle6", np.vstack([faces(base, "ymin", 0), faces(block, "ymin", shift)]), "YSYM")]
    tags = [np.full(len(c), GROUPS[g][0]) for _, c, g in cells]
    return meshio.Mesh(np.vstack([base.points, block.points]), [(t, c) for t, c, _ in cells],
                       cell_data={"gmsh:physical": tags, "gmsh:geometrical": tags},
                       field_data={g: np.array(v) for g, v in GROUPS.items()})


def _sets(text: str, keyword: str) -> dict[str, list[list[str]]]:
    """{name: data fields} of every ``*KEYWORD`` block of a deck text, named by its NAME=, NSET= or
    ELSET= ("" without); a line ending with a comma continues on the next (a reader of the test's
    own, for what the deck says)."""
    out, current = {}, None
    for line in text.splitlines():
        if line.startswith("*"):
            head = [f.strip().split("=") for f in line.split(",")]
            name = next((kv[1] for kv in head[1:] if kv[0].upper() in ("NAME", "NSET", "ELSET")), "")
            current = out.setdefault(name, []) if head[0][0].upper() == keyword else None
        elif current is not None and line.strip():
            fields = [f.strip() for f in line.split(",") if f.strip()]
            if current and current[-1][-1] == ",":
                current[-1] = current[-1][:-1] + fields + ([","] if line.rstrip().endswith(",") else [])
            else:
                current.append(fields + ([","] if line.rstrip().endswith(",") else []))
    return out


@pytest.fixture(scope="module")
def msh(tmp_path_factory):
    path = tmp_path_factory.mktemp("msh") / "two.msh"
    meshio.write(path, _two_boxes(), file_format="gmsh22", binary=False)
    return path


def test_the_sets_are_the_groups(msh):
    """Every face of a surface group becomes the one element face with the same corners, S1-S4 in
    TET10_FACES' order: checked against the node coordinates (all on the group's plane)."""
    text = msh_deck(msh)
    nodes = {int(r[0]): np.array([float(v) for v in r[1:]]) for r in _sets(text, "*NODE")[""]}
    elements = {int(r[0]): [int(v) for v in r[1:]] for name in ("BASE", "BLOCK") for r in _sets(text, "*ELEMENT")[name]}
    assert all(len(c) == 10 for c in elements.values())
    assert len(elements) == 2 * 8 * 6 and len(nodes) == 2 * 125  # two 2×2×2 grids, 6 tets a cell, 5³ nodes each
    surfaces = _sets(text, "*SURFACE")
    plane = {"BASE_TOP": (2, 0.0), "BLOCK_BOTTOM": (2, 0.0), "TOP": (2, 10.0), "BOTTOM": (2, -10.0)}
    for name, (axis, value) in plane.items():
        assert len(surfaces[name]) == 8  # 4 grid squares, 2 triangles each
        for eid, s in surfaces[name]:
            corners = [elements[int(eid)][i] for i in TET10_FACES[int(s[1:])][:3]]
            np.testing.assert_allclose([nodes[n][axis] for n in corners], value, atol=1e-12)
    top = {int(r[0]) for r in surfaces["TOP"]}
    assert top <= {e for e in elements if e > 48} and {int(r[0]) for r in surfaces["BASE_TOP"]} <= set(range(1, 49))
    nsets = _sets(text, "*NSET")
    assert len([v for r in nsets["XSYM"] for v in r]) == 2 * 25 and "add *MATERIAL" in text


def _template(text: str) -> str:
    """Materials, contact pair, supports and a step with the pressure on the TOP faces."""
    top = _sets(text, "*SURFACE")["TOP"]
    return "\n".join(["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3", "*MATERIAL, NAME=ALUMINIUM", "*ELASTIC",
                      "70000., 0.33", "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
                      "*SOLID SECTION, ELSET=BASE, MATERIAL=ALUMINIUM", "*SURFACE INTERACTION, NAME=ROUGH",
                      "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=SURFACE TO SURFACE", "BLOCK_BOTTOM, BASE_TOP",
                      "*BOUNDARY", "BOTTOM, 3, 3", "XSYM, 1, 1", "YSYM, 2, 2", "*STEP", "*STATIC", "0.25, 1.",
                      "*DLOAD", *[f"{e}, P{s[1:]}, {PRESSURE}" for e, s in top], "*END STEP"])


def test_the_converted_deck_runs_to_the_closed_form(msh, tmp_path):
    """The .msh's deck + the appended model: u_z of every TOP node = −(c(p) + p H/E_steel +
    p H/E_aluminium) to 1e-9 (tests/fe/test_tetra_run.py's bound for the same model)."""
    law = yaml.safe_load((EXAMPLES / "block.yaml").read_text())
    law["interactions"]["ROUGH"]["friction"] = "none"
    (tmp_path / "law.yaml").write_text(yaml.safe_dump(law))
    deck = tmp_path / "two.inp"
    deck.write_text(msh_deck(msh, _template(msh_deck(msh))))
    result = run_deck_file(deck, tmp_path / "law.yaml")
    normal = result.problem.materials.parts[0][0].normal
    c_um = normal.h_ref - normal.table.separation_at(PRESSURE)
    _, u = result.node_sets(result.step_end(1))["TOP"]
    assert len(u) == 25
    np.testing.assert_allclose(u[:, 2], -(c_um * 1e-3 + PRESSURE * H / STEEL_E + PRESSURE * H / ALUMINIUM_E), rtol=1e-9)


def test_the_command_writes_the_deck_and_says_what_to_add(msh, tmp_path):
    out = tmp_path / "two.inp"
    run = subprocess.run([sys.executable, "-m", "roughcontact", "fe", "msh2inp", str(msh), "-o", str(out)],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert out.read_text() == msh_deck(msh) and "*SOLID SECTION" in run.stderr


def test_hexahedron20_is_c3d20_in_vtk_order(tmp_path):
    """One quadratic hexahedron: the VTK order meshio gives is C3D20's (HEX20_NODES, CalculiX 6.2.1),
    written as read; its bottom quad8 face is S1, its top S2."""
    points = (HEX20_NODES + 1.0) / 2.0
    quad = lambda idx: np.array([idx])  # noqa: E731
    mesh = meshio.Mesh(points, [("hexahedron20", np.arange(20)[None]), ("quad8", quad([0, 3, 2, 1, 11, 10, 9, 8])),
                                ("quad8", quad([4, 5, 6, 7, 12, 13, 14, 15]))],
                       cell_data={"gmsh:physical": [np.array([1]), np.array([2]), np.array([3])],
                                  "gmsh:geometrical": [np.array([1]), np.array([2]), np.array([3])]},
                       field_data={"CUBE": np.array([1, 3]), "LOW": np.array([2, 2]), "HIGH": np.array([3, 2])})
    meshio.write(tmp_path / "hex.msh", mesh, file_format="gmsh22", binary=False)
    text = msh_deck(tmp_path / "hex.msh")
    assert "*ELEMENT, TYPE=C3D20, ELSET=CUBE\n1, " + ", ".join(str(i) for i in range(1, 16)) + ",\n16, 17, 18, 19, 20\n" in text
    surfaces = _sets(text, "*SURFACE")
    assert surfaces == {"LOW": [["1", "S1"]], "HIGH": [["1", "S2"]]}


def _write(tmp_path, cells, groups) -> Path:
    points = box_tets([0.0, 1.0], [0.0, 1.0], [0.0, 1.0]).points
    tags = [np.full(len(c), t) for (_, c), t in zip(cells, [g[0] for g in groups.values()])]
    path = tmp_path / "bad.msh"
    meshio.write(path, meshio.Mesh(points, cells, cell_data={"gmsh:physical": tags, "gmsh:geometrical": tags},
                                   field_data={k: np.array(v) for k, v in groups.items()}), file_format="gmsh22", binary=False)
    return path


def test_one_line_errors(tmp_path):
    tets = box_tets([0.0, 1.0], [0.0, 1.0], [0.0, 1.0]).blocks[0].cells
    faces = box_tets([0.0, 1.0], [0.0, 1.0], [0.0, 1.0]).face_sets["zmin"].face_nodes
    with pytest.raises(MshError, match=r"no volume elements.*gmsh -order 2"):
        msh_deck(_write(tmp_path, [("triangle6", faces)], {"S": (1, 2)}))
    with pytest.raises(MshError, match=r"6 tetra elements; only tetra10.*gmsh -order 2"):
        msh_deck(_write(tmp_path, [("tetra", tets[:, :4])], {"V": (1, 3)}))
    odd = faces.copy()
    odd[0, :3] = tets[0, 4:7]  # the mid-edge nodes of a tetrahedron: no face's corners
    with pytest.raises(MshError, match=r"surface group S: the face with corner nodes .* is no face of a volume element"):
        msh_deck(_write(tmp_path, [("tetra10", tets), ("triangle6", odd)], {"V": (1, 3), "S": (2, 2)}))
    (tmp_path / "junk.msh").write_text("not a mesh\n")
    with pytest.raises(MshError, match="not a gmsh .msh file"):
        msh_deck(tmp_path / "junk.msh")
