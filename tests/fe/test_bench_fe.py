"""The benchmark of `make bench-fe` (benchmarks/fe_block_on_base.py, benchmarks/block_on_base.py):
the CalculiX deck and the engine's model are the same problem, the harness reports both codes,
says when ccx is absent, and (slow tier, where ccx is installed) the 1× deck runs in both codes
to the same answer. Speeds are measured by the benchmark itself, never asserted here."""

from __future__ import annotations

import json
import re
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

import block_on_base as bob  # noqa: E402
import fe_block_on_base as bench  # noqa: E402


@pytest.fixture(scope="module")
def deck():
    problem = bob.BlockOnBase(refine=1)
    return problem, bob.calculix_deck(problem, bob.calculix_table(problem))


def _block(text: str, keyword: str) -> list[str]:
    """Data lines of the first block that starts with ``keyword`` (case-insensitive)."""
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.upper().startswith(keyword.upper()))
    out = []
    for line in lines[start + 1:]:
        if line.startswith("*"):
            break
        out.append(line)
    return out


def test_deck_and_engine_model_are_the_same_problem(deck):
    problem, text = deck
    nodes = {int(line.split(",")[0]): np.array([float(v) for v in line.split(",")[1:]])
             for line in _block(text, "*NODE")}
    assert 3 * len(nodes) == bob.deck_dofs(problem) == 3408
    assert len(re.findall(r"TYPE=C3D20", text)) == 2 and "*CONTACT PAIR, INTERACTION=ROUGH" in text
    rows = _block(text, "*SURFACE BEHAVIOR")
    assert 2 < len(rows) <= 200 and float(rows[0].split(",")[0]) == 0.0
    loaded = _block(text, "*DLOAD")
    assert len(loaded) == 3  # the last of the three element columns of the top (x ≥ 33.3 mm)
    mesh, model = bob.engine_model(problem)
    # the block's bottom and the base's top: the same coordinates in both
    bottom_ids = [int(v) for line in _block(text, "*NSET, NSET=BLOCKBOTTOM") for v in line.split(",")]
    deck_bottom = np.array(sorted(map(tuple, np.round([nodes[i] for i in bottom_ids], 9))))
    corner_mid = mesh.points[mesh.node_sets["block.contact"]]
    engine_bottom = np.array(sorted(map(tuple, np.round(corner_mid, 9))))
    # the engine's transition faces add the face centres (QUAD9): the deck's nodes are a subset
    assert set(map(tuple, deck_bottom)) < set(map(tuple, engine_bottom))
    assert len(engine_bottom) - len(deck_bottom) == 9
    # the same load: the pressure on the same area
    F = model.load.reshape(-1, 3).sum(axis=0)
    n_loaded = len(loaded)
    area = n_loaded * (20.0 / 3) ** 2
    assert F[2] == pytest.approx(-problem.pressure * area, rel=1e-12)
    assert abs(model.load.reshape(-1, 3)[:, :2]).max() == 0.0


def test_law_file_has_the_issues_schema():
    problem = bob.BlockOnBase()
    law = yaml.safe_load(bench.law_yaml(problem))
    assert law["length_unit"] == "mm"
    rough = law["interactions"]["ROUGH"]
    assert rough["moments"] == {**bob.MOMENTS, "unit": "um"}
    assert rough["E_star"] == pytest.approx(78065.86, rel=1e-7)  # eq. (42): steel on cast iron (the issue: 78065.86)
    assert rough["law"] == "elastic" and rough["seating_pressure"] == 1e-3 and rough["friction"] == "none"
    assert rough["lay_direction"] == [1, 0, 0]


def test_sta_parser_counts_attempts_and_iterations():
    sta = """SUMMARY OF JOB INFORMATION
  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME
     1          1     1U   12  0.000000E+00  0.000000E+00  0.625000E-01
     1          1     2    10  0.976562E-03  0.976562E-03  0.976562E-03
     1          2     1     5  0.195312E-02  0.195312E-02  0.976562E-03
"""
    assert bench.parse_sta(sta) == {"increments": 2, "attempts": 3, "cutbacks": 1, "newton_iterations": 27}


def test_without_ccx_its_rows_say_so(tmp_path, monkeypatch):
    """ccx hidden (a PATH without it): the ccx row is "skipped" with the reason, nothing fails
    (the exported table is replaced by a two-row one: the deck is written, not run)."""
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setattr(bob, "calculix_table", lambda problem: "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n"
                        "0.0, -1.0e-4\n100.0, 1.0e-3\n")
    assert shutil.which("ccx") is None
    assert bench.main(["--codes", "ccx", "--refine", "1", "--out", str(tmp_path / "out")]) == 0
    rows = json.loads((tmp_path / "out" / "results.json").read_text())["rows"]
    assert rows[0]["code"] == "ccx" and "not installed" in rows[0]["skipped"]
    assert "skipped: ccx is not installed" in (tmp_path / "out" / "results.md").read_text()
    assert (tmp_path / "out" / "decks" / "block_on_base_1x.inp").exists()


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason="ccx (CalculiX) is not installed")
def test_1x_deck_in_ccx_and_the_engine(tmp_path):
    """The reduced benchmark: the 1× deck in ccx (the exported table, node-to-surface) and in
    the engine through `roughcontact fe run ... --json` (the law, interface elements on the
    deck's contact faces). Both converge; the mean vertical displacement of the block's bottom
    (the deck's node set BLOCKBOTTOM in both) agrees within 3 % (the table is within 1e-3 of the
    law, the rest is the two contact discretisations on a coarse mesh)."""
    assert bench.main(["--refine", "1", "--engine", "cli", "--out", str(tmp_path)]) == 0
    rows = {r["code"]: r for r in json.loads((tmp_path / "results.json").read_text())["rows"]}
    for code in ("ccx", "engine"):
        r = rows[code]
        assert r["exit"] == 0 and r["wall_s"] > 0 and r["peak_rss_mb"] > 0 and r["newton_iterations"] > 0
    assert rows["ccx"]["dofs"] == 3408
    assert rows["engine"]["path"] == "cli" and rows["engine"]["interface_points"] == 49
    assert rows["engine"]["cutbacks"] == 0 and rows["engine"]["max_p_N"] < 100.0
    ccx, engine = rows["ccx"]["mean_uz_block_bottom_mm"], rows["engine"]["mean_uz_block_bottom_mm"]
    assert engine < 0.0 and abs(engine / ccx - 1.0) < 0.03
