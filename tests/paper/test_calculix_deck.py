"""What docs/fe-export.md says about CalculiX, run in ccx (issue 22): the documented minimal deck
works as written, and each stated behaviour of ccx 2.20 (node-based slave surfaces, the C3D20
ripple, surface-to-surface with a tabular law, the pressure beyond the last row) shows. Every
test needs the program `ccx` and skips cleanly without it."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import numpy as np
import pytest

from roughcontact import cli
from roughcontact.fe.deck_writer import box_part, id_lines
from roughcontact.interface.export import parse_table
from roughcontact.paper import calculix

ROOT = Path(__file__).resolve().parents[2]
DOC = (ROOT / "docs" / "fe-export.md").read_text()
needs_ccx = pytest.mark.skipif(calculix.ccx_executable() is None, reason="ccx (CalculiX) is not installed")
#: p = 1000 N/mm³ × c: the closure in µm equals the pressure in N/mm²
LINEAR_TABLE = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n0.0, 0.0\n1.0, 1.0e-3\n"


def _fenced_after(marker: str) -> str:
    """The fenced block that follows an HTML comment marker in docs/fe-export.md."""
    m = re.search(rf"<!-- {marker} -->\s*```[a-z]*\n(.*?)```", DOC, re.S)
    assert m, f"docs/fe-export.md has no block after <!-- {marker} -->"
    return m.group(1)


def block_deck(table: str, pressure: float, *, n: int = 1, quadratic: bool = False, slave: str = "face",
               contact: str = "NODE TO SURFACE", E: float = 2.1e5) -> tuple[str, dict]:
    """A block 1 × 1 × 1 mm of n × n C3D8 or C3D20 elements (E [N/mm²], ν = 0.3) on a rigid base
    through ``table`` under a uniform pressure; the bottom nodes printed. Returns the deck and
    {(i, j): node} of the bottom nodes on the doubled grid (corners at even i, j)."""
    x, z = np.linspace(0.0, 1.0, n + 1), np.array([0.0, 1.0])
    if quadratic:
        part = box_part(x, x, z)
        coords, elements = part.coords, part.connectivity.tolist()
        # keys on the doubled grid, as the C3D8 branch's
        ids = {tuple(int(v) for v in np.rint(c * [2 * n, 2 * n, 2])): int(node) for c, node in zip(coords, part.node_ids)}
    else:
        ids, coords = {}, []
        for k in range(2):
            for j in range(n + 1):
                for i in range(n + 1):
                    ids[(2 * i, 2 * j, 2 * k)] = len(coords) + 1
                    coords.append((x[i], x[j], z[k]))
        elements = [[ids[(2 * (i + a), 2 * (j + b), 2 * c)] for c in (0, 1) for a, b in ((0, 0), (1, 0), (1, 1), (0, 1))]
                    for j in range(n) for i in range(n)]
    nb = len(coords)
    bottom = {(i, j): node for (i, j, k), node in ids.items() if k == 0}
    x0 = [node for (i, j, k), node in ids.items() if i == 0]
    y0 = [node for (i, j, k), node in ids.items() if j == 0]
    base = [(-0.5, -0.5, -1.0), (1.5, -0.5, -1.0), (1.5, 1.5, -1.0), (-0.5, 1.5, -1.0),
            (-0.5, -0.5, 0.0), (1.5, -0.5, 0.0), (1.5, 1.5, 0.0), (-0.5, 1.5, 0.0)]
    lines = ["*NODE, NSET=NALL", *(f"{i + 1}, {a:.12g}, {b:.12g}, {c:.12g}" for i, (a, b, c) in enumerate(coords)),
             *(f"{nb + 1 + i}, {a}, {b}, {c}" for i, (a, b, c) in enumerate(base)),
             f"*ELEMENT, TYPE={'C3D20' if quadratic else 'C3D8'}, ELSET=BLOCK"]
    for e, conn in enumerate(elements):
        lines.append(f"{e + 1}, " + ", ".join(map(str, conn[:10])) + (",\n" + ", ".join(map(str, conn[10:]))
                                                                      if len(conn) > 10 else ""))
    lines += ["*ELEMENT, TYPE=C3D8, ELSET=BASE", f"{len(elements) + 1}, " + ", ".join(str(nb + 1 + i) for i in range(8)),
              *id_lines("*NSET, NSET=BOTTOM", sorted(bottom.values())), *id_lines("*NSET, NSET=BASENODES", range(nb + 1, nb + 9)),
              *id_lines("*NSET, NSET=X0", x0), *id_lines("*NSET, NSET=Y0", y0), "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:g}, 0.3", "*MATERIAL, NAME=RIGID",
              "*ELASTIC", "1e12, 0.0", "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
              "*SOLID SECTION, ELSET=BASE, MATERIAL=RIGID",
              *(["*SURFACE, NAME=SLAVE, TYPE=NODE", "BOTTOM"] if slave == "node" else ["*SURFACE, NAME=SLAVE", "BLOCK, S1"]),
              "*SURFACE, NAME=MASTER", "BASE, S2", "*SURFACE INTERACTION, NAME=ROUGH", table.strip(),
              f"*CONTACT PAIR, INTERACTION=ROUGH, TYPE={contact}", "SLAVE, MASTER", "*BOUNDARY", "BASENODES, 1, 3, 0.0",
              "X0, 1, 1, 0.0", "Y0, 2, 2, 0.0", "*STEP, INC=1000", "*STATIC", "0.1, 1.0, 1e-6, 0.25", "*DLOAD",
              *(f"{e + 1}, P2, {pressure:.12e}" for e in range(len(elements))),
              "*NODE PRINT, NSET=BOTTOM", "U", "*END STEP"]
    return "\n".join(lines) + "\n", bottom


def closures_um(dat: str) -> dict[int, float]:
    """−u_z [µm] of every printed bottom node at the end."""
    return {node: -1000.0 * u[2] for node, u in calculix.node_prints(dat, "BOTTOM")[-1][1].items()}


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    """The documented export command, run in a fresh directory: (the directory, contact.inp's text)."""
    argv = shlex.split(_fenced_after("export-command").replace("\\\n", " "))
    assert argv[0] == "roughcontact"
    where = tmp_path_factory.mktemp("export")
    argv[argv.index("-o") + 1] = str(where / "contact.inp")
    assert cli.main(argv[1:]) == 0
    return where, (where / "contact.inp").read_text()


@needs_ccx
def test_the_documented_deck_runs_as_written(exported):
    """Export as documented, save the documented deck, run ccx: the closure is the law's at
    1 N/mm² (the table's inverse, within its rtol of the law), the contact pressure 1 N/mm², and
    the numbers the page quotes are the ones ccx prints."""
    where, table_text = exported
    deck = _fenced_after("block-deck")
    dat, _ = calculix.run_ccx(deck, "block", where)  # next to contact.inp, as the page says
    u = calculix.node_prints(dat, "BOTTOM")[-1][1]
    uz = np.array([v[2] for v in u.values()])
    p, c = parse_table(table_text)
    c_table = np.interp(1.0, p, c)  # mm: the table's closure at 1 N/mm²
    np.testing.assert_allclose(-uz, c_table, rtol=1e-5)  # ccx prints 7 digits
    quoted = float(re.search(r"u_z = (−?[-\d.e+]+) mm", DOC).group(1).replace("−", "-"))
    assert uz.mean() == pytest.approx(quoted, rel=5e-5)
    stress = re.findall(r"^\s+\d+\s+(\S+)\s+\S+\s+\S+\s*$", dat.split("contact stress")[-1], re.M)
    np.testing.assert_allclose([float(v) for v in stress[:4]], 1.0, rtol=1e-5)


@needs_ccx
@pytest.mark.parametrize("quadratic, n, factor", [(False, 1, 1 / 3), (False, 2, 1 / 3), (True, 1, 0.061),
                                                  (True, 2, 0.021)])
def test_a_node_based_slave_surface_gets_the_pressure_wrong(tmp_path, quadratic, n, factor):
    """With TYPE=NODE the closure under 0.5 N/mm² is a fraction of the law's (the page: a third
    with C3D8 faces, 1/16 … 1/160 with C3D20), with element faces it is the law's."""
    got = {}
    for slave in ("face", "node"):
        deck, _ = block_deck(LINEAR_TABLE, 0.5, n=n, quadratic=quadratic, slave=slave)
        got[slave] = np.mean(list(closures_um(calculix.run_ccx(deck, slave, tmp_path)[0]).values()))
    assert got["face"] == pytest.approx(0.5, rel=2e-3)
    assert got["node"] / got["face"] == pytest.approx(factor, rel=0.1)


@needs_ccx
def test_c3d20_faces_ripple_c3d8_faces_do_not(tmp_path):
    """A soft 2 × 2 block on a stiff linear interface: the corner nodes of the C3D20 faces close
    5-12 % less than the mid-side nodes; the C3D8 faces close uniformly."""
    deck, bottom = block_deck(LINEAR_TABLE, 0.5, n=2, quadratic=True, E=1e3)
    c = closures_um(calculix.run_ccx(deck, "c3d20", tmp_path)[0])
    corner = [c[v] for (i, j), v in bottom.items() if i % 2 == 0 and j % 2 == 0]
    mid = [c[v] for (i, j), v in bottom.items() if (i % 2) + (j % 2) == 1]
    assert max(corner) < min(mid) and 1.0 - np.mean(corner) / np.mean(mid) > 0.05
    deck, _ = block_deck(LINEAR_TABLE, 0.5, n=2, E=1e3)
    v = np.array(list(closures_um(calculix.run_ccx(deck, "c3d8", tmp_path)[0]).values()))
    assert np.ptp(v) <= 1e-5 * v.mean()


@needs_ccx
def test_surface_to_surface_with_a_tabular_law_fails(tmp_path, exported):
    """TYPE=SURFACE TO SURFACE: a tabular law fails (a 3-row table: too many cutbacks; the
    exported one: a crash), a LINEAR law runs; NODE TO SURFACE runs with both tables."""
    short = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n0.0, -1.0e-4\n1.0, 1.0e-4\n2.0, 3.0e-4\n"
    for name, table in (("short", short), ("exported", calculix.table_lines(exported[1]))):
        deck, _ = block_deck(table, 0.5, contact="SURFACE TO SURFACE")
        with pytest.raises(RuntimeError, match="ccx failed"):
            calculix.run_ccx(deck, f"s2s-{name}", tmp_path)
        deck, _ = block_deck(table, 0.5)
        assert calculix.run_ccx(deck, f"n2s-{name}", tmp_path)[0]
    linear = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n5000.0, 1.0, 1.0e-4\n"
    deck, _ = block_deck(linear, 0.5, contact="SURFACE TO SURFACE")
    assert closures_um(calculix.run_ccx(deck, "s2s-linear", tmp_path)[0])


@needs_ccx
def test_calculix_holds_the_last_pressure(tmp_path):
    """The header's claim for CalculiX: beyond the last row the pressure does not grow (Abaqus
    would continue the last slope): below the last row the closure is the table's inverse, above
    it no closure carries the load."""
    table = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n0.0, -1.0e-4\n1.0, 1.0e-4\n2.0, 3.0e-4\n"
    deck, _ = block_deck(table, 1.9)
    c = closures_um(calculix.run_ccx(deck, "below", tmp_path)[0])
    np.testing.assert_allclose(list(c.values()), 0.28, rtol=1e-5)  # 1e-4 + 0.9 × 2e-4 mm
    deck, _ = block_deck(table, 2.5)  # the last slope would carry it at c = 0.4 µm
    with pytest.raises(RuntimeError, match="increment size smaller than minimum"):
        calculix.run_ccx(deck, "beyond", tmp_path)
