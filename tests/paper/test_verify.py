"""roughcontact.paper.verify: verdicts under tolerances, expectations → regressions, reports."""

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from roughcontact.paper import report, verify
from roughcontact.paper.verify import NOT_REPRODUCED, REPRODUCED

ROOT = Path(__file__).resolve().parents[2]

PAPER = {
    "rows": ["1.0", "2.0"],
    "row_key": "s",
    "quantities": {
        "area_fraction": {"symbol": "A/A0", "unit": "%", "factor": 100.0},
        "pressure": {"symbol": "W/A0", "unit": "N/mm^2", "factor": 1.0},
    },
    "columns": {
        "GW": {"area_fraction": ["5.1497", "0.0097"], "pressure": ["86.5534", "0.1114"]},
        "anisotropic": {"area_fraction": ["6.1222", "0.0093"], "pressure": ["93.3897", "0.1162"]},
    },
}
MODELS = {
    "gw": {"paper_column": "GW", "label": "GW"},
    "bgk": {"paper_column": "anisotropic", "label": "BGK"},
}
TOL = {
    "printed_rounding": True,
    "gw": {"area_fraction": {"rtol": 0.005, "why": "w"}, "pressure": {"rtol": 0.005, "why": "w"}},
    "bgk": {"area_fraction": {"rtol": 0.005, "why": "w"}, "pressure": {"rtol": 0.005, "why": "w"}},
}


def test_relative_error_and_rounding():
    assert verify.relative_error(101.0, 100.0) == pytest.approx(0.01)
    assert verify.relative_error(-1.0, -2.0) == pytest.approx(0.5)
    assert verify.relative_error(0.0, 0.0) == 0.0
    assert math.isinf(verify.relative_error(1.0, 0.0))
    assert math.isnan(verify.relative_error(math.nan, 1.0))
    assert verify.half_unit_of_last_digit("0.0097") == pytest.approx(5e-5)
    assert verify.half_unit_of_last_digit("2105.97") == pytest.approx(5e-3)
    assert verify.half_unit_of_last_digit("0.6470") == pytest.approx(5e-5)
    assert verify.half_unit_of_last_digit("1.04e-6") == pytest.approx(5e-9)
    with pytest.raises(ValueError):
        verify.half_unit_of_last_digit("n/a")
    # 0.0097 printed: half a unit is 0.52 % of it, wider than 0.5 %
    assert verify.effective_tolerance(0.005, "0.0097", True) == pytest.approx(5e-5 / 0.0097)
    assert verify.effective_tolerance(0.005, "0.0097", False) == 0.005
    assert verify.effective_tolerance(0.005, "86.5534", True) == 0.005


def test_table_cells_verdicts_units_and_ids():
    results = {
        "gw": {"area_fraction": [0.051497, 0.0000972], "pressure": [86.55, 0.1114]},
        "bgk": {"area_fraction": [0.0577, 0.0000850], "pressure": [93.15, 0.1159]},
    }
    checks = verify.table_cell_checks("t1", PAPER, results, MODELS, TOL)
    by_id = {c.id: c for c in checks}
    assert len(checks) == 8
    gw_area = by_id["cell:t1/gw/area_fraction/s=1.0"]
    assert gw_area.value == pytest.approx(5.1497)  # fraction → % via factor
    assert gw_area.verdict == REPRODUCED and gw_area.unit == "%"
    # 0.00972 % vs printed 0.0097: 0.21 %, within the widened tolerance
    assert by_id["cell:t1/gw/area_fraction/s=2.0"].verdict == REPRODUCED
    assert by_id["cell:t1/bgk/area_fraction/s=1.0"].verdict == NOT_REPRODUCED
    assert by_id["cell:t1/bgk/area_fraction/s=1.0"].error == pytest.approx(5.77 / 6.1222 - 1)
    assert by_id["cell:t1/bgk/pressure/s=1.0"].verdict == REPRODUCED  # −0.26 %


def test_table_cells_need_a_tolerance_and_matching_rows():
    results = {"gw": {"area_fraction": [0.05, 0.0001], "pressure": [86.0, 0.1]}}
    with pytest.raises(KeyError, match="no tolerance"):
        verify.table_cell_checks("t1", PAPER, results, MODELS, {"gw": {"pressure": {"rtol": 0.1}}})
    with pytest.raises(ValueError, match="printed rows"):
        verify.table_cell_checks("t1", PAPER, {"gw": {"pressure": [1.0]}}, MODELS, TOL)


def test_numerics_checks():
    prod = {"gw": {"pressure": np.array([1.0, 2.0])}}
    ref = {"gw": {"pressure": np.array([1.0 + 1e-12, 2.0 * (1 + 1e-6)])}}
    checks = verify.numerics_checks("t1", ["1.0", "2.0"], prod, ref, 1e-8, reference_dps=12)
    assert [c.verdict for c in checks] == [REPRODUCED, NOT_REPRODUCED]
    assert checks[0].id == "numerics:t1/gw/pressure/s=1.0"
    # a model without a reference is skipped, not failed
    assert verify.numerics_checks("t1", ["1.0"], {"x": {"p": [1.0]}}, {}, 1e-8) == []


def test_claim_checks():
    s = np.linspace(0, 5, 51)
    approaching = {"a": 1 + 0.5 * np.exp(-s), "b": 1 - 0.3 * np.exp(-s)}
    claim = {"id": "to-one", "text": "tends to 1", "check": "approaches", "target": 1.0,
             "tail_from": 3.0, "atol": 0.05, "why": "why"}
    c = verify.claim_check("fig3", claim, s, approaching)
    assert c.verdict == REPRODUCED and c.id == "claim:fig3/to-one"
    assert c.error == pytest.approx(0.5 * math.exp(-5))
    # far from the target at the end
    assert verify.claim_check("fig3", claim, s, {"a": 1.2 + 0 * s}).verdict == NOT_REPRODUCED
    # close at the end but not shrinking over the tail
    wiggle = 1 + 0.01 * np.sin(5 * s)
    assert verify.claim_check("fig3", claim, s, {"a": wiggle}).verdict == NOT_REPRODUCED
    start = {"id": "circle", "text": "f = 1 at e = 0", "check": "value_at_start", "target": 1.0,
             "atol": 1e-12, "why": "why"}
    e = np.linspace(0, 0.9, 10)
    assert verify.claim_check("fig4", start, e, {"f1": 1 + e, "f2": 1 + e**2}).verdict == REPRODUCED
    assert verify.claim_check("fig4", start, e, {"f1": 1 + 1e-6 + e}).verdict == NOT_REPRODUCED
    with pytest.raises(ValueError):
        verify.claim_check("fig4", {**start, "check": "bogus"}, e, {"f": e})


def _check(id_, verdict):
    return verify.Check(id=id_, kind="cell", scene=id_.split(":")[1].split("/")[0], verdict=verdict, detail="d")


def test_expectations_last_match_wins_and_statuses():
    data = {
        "default": "reproduced",
        "expectations": [
            {"match": "cell:t1/*", "expected": "reproduced", "reason": "general"},
            {"match": "cell:t1/bgk/area_fraction/*", "expected": "not reproduced", "reason": "areas"},
            {"match": "cell:t1/bgk/area_fraction/s=2.0", "expected": "reproduced", "reason": "flipped"},
        ],
    }
    checks = verify.apply_expectations(
        [
            _check("cell:t1/gw/pressure/s=1.0", REPRODUCED),  # ok
            _check("cell:t1/gw/pressure/s=2.0", NOT_REPRODUCED),  # regression
            _check("cell:t1/bgk/area_fraction/s=1.0", NOT_REPRODUCED),  # known
            _check("cell:t1/bgk/area_fraction/s=3.0", REPRODUCED),  # improved
            _check("cell:t1/bgk/area_fraction/s=2.0", NOT_REPRODUCED),  # flipped → regression
            _check("cell:t9/x/y/s=1", NOT_REPRODUCED),  # unmatched → default reproduced → regression
        ],
        data,
    )
    assert [c.status for c in checks] == ["ok", "regression", "known", "improved", "regression", "regression"]
    assert checks[2].reason == "areas" and checks[4].reason == "flipped"
    assert [c.id for c in verify.regressions(checks)] == [checks[i].id for i in (1, 4, 5)]
    assert [c.id for c in verify.improvements(checks)] == [checks[3].id]
    s = verify.summarize(checks)
    assert not s["passed"] and s["regressions"] == 3 and s["known"] == 1 and s["improved"] == 1
    assert s["by_scene"]["t1"]["checks"] == 5
    assert verify.summarize(checks[:1])["passed"]


def test_expectations_are_validated():
    with pytest.raises(ValueError):
        verify.load_expectations({"expectations": [{"match": "x", "expected": "maybe"}]})
    with pytest.raises(ValueError):
        verify.load_expectations({"expectations": [{"expected": "reproduced"}]})
    with pytest.raises(ValueError):
        verify.load_expectations({"default": "perhaps"})


def test_csv_round_trip():
    results = {"gw": {"area_fraction": [0.051497, 0.0000972], "pressure": [86.55, 0.1114]}}
    checks = verify.table_cell_checks("t1", PAPER, results, MODELS, TOL)
    checks.append(verify.Check(id="claim:f/x", kind="claim", scene="f", verdict=REPRODUCED, detail="a, \"b\"\nc"))
    back = verify.checks_from_csv(verify.checks_to_csv(checks))
    assert len(back) == len(checks)
    for a, b in zip(checks, back):
        for name in ("id", "verdict", "detail", "s", "unit", "description"):
            assert getattr(a, name) == getattr(b, name)
        for name in ("target", "value", "error", "tolerance"):
            x, y = getattr(a, name), getattr(b, name)
            assert (math.isnan(x) and math.isnan(y)) or x == y


def test_reports_render():
    results = {
        "gw": {"area_fraction": [0.051497, 0.0000972], "pressure": [86.55, 0.1114]},
        "bgk": {"area_fraction": [0.0577, 0.0000850], "pressure": [93.15, 0.1159]},
    }
    checks = verify.table_cell_checks("t1", PAPER, results, MODELS, TOL)
    checks += verify.numerics_checks("t1", PAPER["rows"], results, results, 1e-8)
    expected = yaml.safe_load((ROOT / "config" / "expected_verdicts.yaml").read_text())
    checks = verify.apply_expectations(checks, expected)
    md = report.render_table_markdown("Table X", checks, PAPER, MODELS, provenance={"commit": "abc"})
    assert md.startswith("# Table X")
    assert md.count("| 1.0 |") == 4 and "ref. diff" in md
    csv_text = report.render_table_csv(checks, MODELS)
    assert len(csv_text.strip().splitlines()) == 1 + 8
    errata = report.parse_errata("# Errata\n\n## E1 — pairing in (15)\ntext\n```\n## E9 not a heading\n```\n### E3: (17) exponent\n")
    assert [e["key"] for e in errata] == ["E1", "E3"]
    assert errata[0]["anchor"] == "e1--pairing-in-15"
    md = report.render_verification_markdown(checks, errata=errata, provenance={"commit": "abc"})
    assert "## Summary" in md and "## Errata" in md
    assert "../docs/errata.md#e1--pairing-in-15" in md
    assert md.count("`t1/") == 16  # one row per cell and per numerics check
    assert report.parse_errata("## Only a title\n") == [{"key": "", "title": "Only a title", "anchor": "only-a-title"}]


def test_format_number():
    assert verify.format_number(86.55340165) == "86.5534"
    assert verify.format_number(0.0097052851) == "0.00970529"
    assert verify.format_number(math.nan) == "–"
    assert verify.format_number(1.5e-7) == "1.50000e-07"


def test_config_expected_verdicts_are_well_formed():
    data = yaml.safe_load((ROOT / "config" / "expected_verdicts.yaml").read_text())
    default, exps = verify.load_expectations(data)
    assert default == REPRODUCED
    e = verify.expected_for("cell:table1/bgk-exact/area_fraction/s=1.0", exps, default)
    assert e.expected == NOT_REPRODUCED and e.reason
    assert verify.expected_for("cell:table2/gw/pressure/s=4.5", exps, default).expected == REPRODUCED
    assert verify.expected_for("cell:table1/bgk-paper/pressure/s=3.5", exps, default).expected == REPRODUCED
    assert verify.expected_for("cell:table1/bgk-exact/pressure/s=3.5", exps, default).expected == NOT_REPRODUCED
