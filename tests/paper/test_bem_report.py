"""The BEM report (roughcontact.paper.bem) on made-up runs, and the verification's handling of a
scene computed only by its own target (expected_checks: {target: bem})."""

import math

import numpy as np
import pytest

from roughcontact.bem.compare import model_at_pressures
from roughcontact.paper import bem as report
from roughcontact.paper import verify
from roughcontact.statistics.surface import SpectralMoments

M = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
P = np.array([1.0, 5.0, 20.0, 100.0])


def _runs(factor_by_seed):
    """Runs whose BEM area is the model's times a factor per seed, gaps from an exponential law."""
    model = model_at_pressures(M, P, 1.14e5)
    return [{"family": "table1", "n": 256, "seed": i, "pressure": P, "area_fraction": f * model.area_fraction,
             "mean_gap": -0.1 * np.log(P / 1e3), "iterations": np.full(P.size, 10), "solve_time": np.ones(P.size)}
            for i, f in enumerate(factor_by_seed)]


def test_summary_rows_ratio_and_sem():
    rows = report.summary_rows(_runs([1.1, 1.3]), {"table1": M}, 1.14e5, 32)
    assert len(rows) == P.size and set(report.SUMMARY_COLUMNS) <= set(rows[0])
    for r in rows:
        assert r["A_ratio"] == pytest.approx(1.2) and r["A_ratio_sem"] == pytest.approx(0.1)
        assert r["seeds"] == 2 and r["px_per_shortest_wavelength"] == 8
        assert r["K_BEM"] == pytest.approx(r["W_over_A0"] / 0.1)  # -dp/dg of p = 1e3 exp(-g/0.1)
        assert r["kappa_BEM"] / r["kappa_BGK"] == pytest.approx(1.2)
        assert r["alpha"] == pytest.approx(M.alpha1)


def test_summary_refuses_seeds_at_different_pressures():
    runs = _runs([1.0, 1.0])
    runs[1] = {**runs[1], "pressure": P * 2}
    with pytest.raises(ValueError, match="different pressures"):
        report.summary_rows(runs, {"table1": M}, 1.14e5, 32)


def test_holding_and_markdown():
    rows = report.summary_rows(_runs([1.05, 1.05]), {"table1": M}, 1.14e5, 32)
    ranges = report.holding(rows)[("table1", 256)]
    assert [(r.p_low, r.p_high) for r in ranges[0.10]] == [(1.0, 100.0)]
    checks = report.check_rows([{"case": "hertz_sphere", "n": 256, "size": 1.003, "size_exact": 1.0, "p_max": 0.98,
                                 "p_max_exact": 1.0, "pixels_across": 64}], 0.01, "the issue's bound")
    assert [c.verdict for c in checks] == [verify.REPRODUCED, verify.NOT_REPRODUCED]
    assert checks[0].id == "numerics:bem/hertz_sphere/size/n=256"
    md = report.render_markdown(rows, [], checks, scale="ci", grids={256: {"seeds": 2, "max_pressure": 100.0}},
                                E_star=1.14e5, units={"length": "um", "stress": "N/mm^2"}, timing=[])
    assert "## Where the model holds" in md and "within 10 %: W/A0 = 1–100 N/mm^2" in md


def test_summary_dataset_has_cf_units():
    from roughcontact.io import check_cf_metadata

    rows = report.summary_rows(_runs([1.0, 1.1]), {"table1": M}, 1.14e5, 32)
    ds = report.summary_dataset(rows, {"length": "um", "stress": "N/mm^2"})
    assert check_cf_metadata(ds) == []
    assert ds["K_BEM"].attrs["units"] == "N/mm^2 um-1"


def test_figure_draws_every_grid():
    rows = report.summary_rows(_runs([1.0, 1.1]), {"table1": M}, 1.14e5, 32)
    fig = report.figure(rows, {("table1", 256): [np.ones(P.size), 1.1 * np.ones(P.size)]})
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and "table1" in ax.get_title()


def test_coverage_of_a_scene_with_its_own_target():
    data = {"expected_checks": {"bem": {"checks": 2, "target": "bem"}}}
    assert verify.check_coverage([], data)["skipped"] == [{"scene": "bem", "requires": "target bem", "checks": 2,
                                                                    "install": "snakemake bem"}]
    one = verify.Check(id="numerics:bem/x/size/n=256", kind="numerics", scene="bem", verdict="reproduced", detail="")
    assert verify.check_coverage([one], data)["missing"] == [{"scene": "bem", "expected": 2, "found": 1}]
    assert verify.check_coverage([one] * 5, data) == {"missing": [], "skipped": [], "unexpected": []}
    assert math.isnan(one.value)
