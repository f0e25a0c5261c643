"""The judge of example 9.2 (roughcontact.paper.fe_punch) on synthetic datasets whose answers are
known by construction: each prose claim of section 9.2 reproduced by a set built to satisfy it and
refuted when the one property it needs is broken; the printed D against a bound; Table 5's
columns from run names; the FE speed report and the CSV renderer."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest
import xarray as xr

from roughcontact.examples.punch import PunchRun
from roughcontact.paper import fe_punch, fe_speed
from roughcontact.paper.report import render_rows_csv
from roughcontact.paper.verify import NOT_REPRODUCED, REPRODUCED

GRID = np.array([(x, y) for y in (0.0, 5.0, 10.0) for x in (0.0, 5.0, 10.0)])
LOADS = np.array([0.0, 250.0, 125.0, 0.0])  # seated, maximum, half-way down, unloaded (quarter, N)
CFG = {"symmetry": {"rtol": 1e-9, "asymmetry": 1e-3, "why": "test"}, "unloading": {"why": "test"},
       "d_attr": "D_max_area_whole"}


def dataset(slip=1.0, y_factor=1.0, D=1.0, reverses_at=3, slipping=True):
    """A 3 x 3 quarter with the edge points slipping outward (|u^p| = slip, u_y^p scaled by
    y_factor), t_x outward at the maximum load and reversed from level ``reverses_at`` on, the
    relative displacements keeping their sign."""
    x, y = GRID.T
    edge = np.maximum(x, y) == 10.0
    L, P = LOADS.size, x.size
    sx = np.where(edge & slipping, slip * x / 10.0, 0.0)
    sy = np.where(edge & slipping, slip * y_factor * y / 10.0, 0.0)
    tx = np.zeros((L, P))
    tx[1] = 0.1 * x
    tx[2] = 0.02 * x
    tx[reverses_at:] = -0.05 * x
    jump = np.outer([0.0, 1.0, 0.8, 0.5], x / 10.0)
    status = np.zeros((L, P), dtype=int)
    status[1] = np.where(edge & slipping, 1, 0)
    per_level = lambda v: np.broadcast_to(v, (L, P)).copy()  # noqa: E731
    data = {"slip_x_um": per_level(sx), "slip_y_um": per_level(sy), "t_x": tx, "t_y": tx.copy(),
            "p_N": np.full((L, P), 2.5), "jump_x_um": jump, "jump_y_um": jump.copy(), "status": status}
    ds = xr.Dataset({k: (("level", "point"), v) for k, v in data.items()},
                    coords={"x": ("point", x), "y": ("point", y)})
    ds["point_weight"] = ("point", np.ones(P))
    ds["load_quarter"] = ("level", LOADS)
    ds.attrs.update(max_index=1, D_max_area_whole=D)
    return ds


def good():
    """Cases a, b, c as the paper describes them."""
    return {"a": dataset(slip=2.0, D=1.0, reverses_at=2), "b": dataset(D=2.0), "c": dataset(y_factor=1.5, D=1.5)}


def verdicts(data):
    return {c.id.split("/")[-1]: c.verdict for c in fe_punch.punch_claims("table5", "quadratic", data, CFG)}


def test_every_claim_holds_on_a_set_built_to_satisfy_it():
    v = verdicts(good())
    assert len(v) == 7 and set(v.values()) == {REPRODUCED}, v


@pytest.mark.parametrize("change, claim", [
    ({"c": dataset(D=1.5)}, "symmetry-a-b-not-c"),                          # c symmetric
    ({"a": dataset(slip=2.0, y_factor=1.2, D=1.0, reverses_at=2)}, "symmetry-a-b-not-c"),  # a asymmetric
    ({"a": dataset(slip=0.5, D=1.0, reverses_at=2)}, "smaller-slip-for-larger-mu"),
    ({"c": dataset(y_factor=0.8, D=1.5)}, "larger-slip-for-larger-axial-stiffness"),
    ({"a": dataset(slip=2.0, D=3.0, reverses_at=2)}, "largest-D-in-b"),
    ({"a": dataset(slip=2.0, D=1.0, reverses_at=3)}, "earlier-reversal-for-smaller-mu"),  # same load as b
    ({"b": dataset(D=2.0, slipping=False)}, "unloading-reverses-tractions"),
    ({"b": dataset(D=2.0, slipping=False)}, "stick-centre-slip-edge"),
])
def test_each_claim_fails_when_its_property_is_broken(change, claim):
    v = verdicts({**good(), **change})
    assert v[claim] == NOT_REPRODUCED


def test_unloading_fails_when_the_tractions_do_not_reverse():
    data = good()
    data["b"]["t_x"].values[2:] = 0.05 * GRID[:, 0]
    assert verdicts(data)["unloading-reverses-tractions"] == NOT_REPRODUCED


PAPER = {"rows": ["a", "b", "c"], "columns": {"21-node": {"D": [0.2478, 0.2540, 0.0150]}}}
MODELS = fe_punch.reading_models(["quadratic"], ["main", "quarter"])


def test_reading_models_name_the_columns():
    assert set(MODELS) == {"fe-quadratic", "fe-quadratic-quarter"}
    assert all(m["paper_column"] == "21-node" for m in MODELS.values())


def test_printed_D_above_the_bound_is_not_reproduced():
    checks = fe_punch.bound_checks("table5", {"fe-quadratic": {"a": 0.03, "b": 0.3, "c": 0.015}}, PAPER, MODELS)
    assert [c.verdict for c in checks] == [NOT_REPRODUCED, REPRODUCED, REPRODUCED]  # 0.015 <= 0.015
    assert "0.2478" in checks[0].detail and checks[0].value == 0.03


def test_table5_results_put_each_case_in_its_cell():
    runs = {f"quadratic-{r}-{c}": PunchRun(case=c) for r in ("main", "quarter", "sens-patch-10")
            for c in ("a", "b", "c", "frictionless")}
    attrs = {n: {"D": 10.0 * "abc".index(r.case) + (1 if "quarter" in n else 0)}
             for n, r in runs.items() if r.case != "frictionless"}
    out = fe_punch.table5_results(attrs, runs, "D", ["main", "quarter"])
    assert set(out) == set(MODELS)  # the sensitivity variant is not a Table 5 column
    np.testing.assert_array_equal(out["fe-quadratic"]["D"], [0.0, 10.0, 20.0])
    np.testing.assert_array_equal(out["fe-quadratic-quarter"]["D"], [1.0, 11.0, 21.0])


def test_run_bounds_use_the_frictionless_slips_in_mm_from_the_unloaded_start():
    ds, free = dataset(), dataset()
    free["jump_x_um"].values[1] = 2.0
    free["jump_y_um"].values[1] = 4.5
    free["seating_jump_x_um"] = ("point", np.full(9, 1.0))  # the seating's own relative displacement
    free["seating_jump_y_um"] = ("point", np.full(9, -0.5))  # |delta_T| = |(3, 4)| = 5 um at every point
    bounds = fe_punch.run_bounds({"r": ds, "f": free}, {"r": PunchRun(case="b", bound="f"),
                                                        "f": PunchRun(case="frictionless")})
    # mu_max(b) = 0.5, 9 points of 1 mm^2 at 2.5 N/mm^2, 5e-3 mm, whole punch
    assert bounds == {"r": pytest.approx(4 * 0.5 * 9 * 2.5 * 5e-3, rel=1e-14)}


def test_slip_rows_and_csv_round_trip():
    rows = fe_punch.slip_rows(dataset(), case="b")
    assert len(rows) == 9 and rows[0]["case"] == "b" and rows[-1]["status"] == 1
    back = list(csv.DictReader(io.StringIO(render_rows_csv(rows))))
    assert list(back[0]) == list(rows[0])
    assert [float(r["slip_x_um"]) for r in back] == [r["slip_x_um"] for r in rows]  # shortest round-trip floats
    assert render_rows_csv([{"v": np.float64(0.1)}]) == "v\n0.1\n"


def test_speed_report_names_the_slowest_paper_run():
    rows = [fe_speed.run_row(n, {"dofs": 5265, "interface_points": 81, "seconds": s}, [3, 4])
            for n, s in (("quadratic-main-a", 1.5), ("quadratic-main-b", 2.0), ("sens-x", 9.0))]
    assert rows[0]["iterations_total"] == 7
    jobs = [{"job": "j1", "example": "punch", "runs": 3, "wall_s": 10.0, "cpu_s": 12.0, "max_rss_mb": 300.0}]
    md = fe_speed.render_benchmark_markdown(
        {"punch": {"rows": rows, "main": ["quadratic-main-a", "quadratic-main-b"], "goal": 60, "what": "3 runs"}},
        jobs, {"cpu": "test", "cores": 2})
    assert "at most 2.00 s of solve per case (quadratic-main-b, goal ≤ 60 s)" in md
    assert "| quadratic-main-a | 5265 | 81 | 7 (3 4) | 1.50 |" in md
    assert "All FE jobs: 10 s of wall time, 12 s of CPU." in md
