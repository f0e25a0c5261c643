"""The scene ccx_friction (roughcontact.paper.ccx_friction) without CalculiX: its decks as the
configuration says, its checks and their count as config/expected_verdicts.yaml declares, the
skip line. The runs themselves: tests/ccx/test_ccx_run.py and the workflow."""

from __future__ import annotations

from pathlib import Path

import yaml

from roughcontact.fe.deck import read_deck
from roughcontact.fe.laws import read_law_file
from roughcontact.paper import ccx_friction

ROOT = Path(__file__).resolve().parents[2]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())["ccx_friction"]
EXPECTED = yaml.safe_load((ROOT / "config" / "expected_verdicts.yaml").read_text())


def test_the_decks_are_the_configured_ones(tmp_path):
    decks = ccx_friction.scene_decks(CONFIG, tmp_path)
    names = [d[0] for d in decks]
    assert names == ["block", "block-fixed", *(f"punch-{c}" for c in CONFIG["punch_cases"])]
    block = read_deck(decks[0][1])
    assert len(block.steps) == 2 and "HOLD" in block.nsets  # the set stays, its support goes with friction
    assert {"CONTACTSLAVE", "CONTACTMASTER", "LOADED"} <= set(block.nsets)
    friction = read_law_file(decks[0][2]).interactions["ROUGH"].friction
    assert friction.mu_m == tuple(CONFIG["block"]["friction"]["mu_m"])
    assert decks[1][4] == CONFIG["block"]["increments"] and decks[0][4] is None


def _row(deck, step, **kw):
    base = {"deck": deck, "step": step, "loaded": "LOADED", "fixed": deck == "block-fixed",
            "ccx_u_mean": [0.0, 0.0, -1.01], "engine_u_mean": [0.0, 0.0, -1.0], "u_rel_difference": 0.01,
            "ccx_dissipation": 1.001, "engine_dissipation": 1.0}
    return {**base, **kw}


def test_the_checks_are_as_many_as_declared():
    tol = CONFIG["tolerances"]
    rows = []
    for deck in ("block", "block-fixed"):
        rows += [_row(deck, 1), _row(deck, 2, tangential_difference=0.02, tangential_largest_um=0.9)]
    rows += [_row(f"punch-{c}", k) for c in CONFIG["punch_cases"] for k in (1, 2, 3)]
    last = {(r["deck"], r["step"]) for r in rows if r["step"] == (2 if r["deck"].startswith("block") else 3)}
    checks = [c for r in rows for c in ccx_friction._checks(r, (r["deck"], r["step"]) in last, tol)]
    assert len(checks) == EXPECTED["expected_checks"]["ccx_friction"]["checks"]
    assert all(c.scene == "ccx_friction" and c.verdict == "reproduced" for c in checks)
    bad = ccx_friction._checks(_row("block-fixed", 2, tangential_difference=0.2, tangential_largest_um=0.9,
                                    u_rel_difference=0.2, ccx_dissipation=1.5), True, tol)
    assert [c.verdict for c in bad] == ["not reproduced"] * 3


def test_the_skip_line_says_what_to_do(monkeypatch):
    monkeypatch.setattr("roughcontact.ccx.build.missing_tools", lambda: [])
    assert ccx_friction.skipped_line() == "skipped: ccx-with-the-law not installed — `make ccx-build`"
    monkeypatch.setattr("roughcontact.ccx.build.missing_tools", lambda: ["gfortran"])
    assert "apt-get install gfortran; make ccx-build" in ccx_friction.skipped_line()
