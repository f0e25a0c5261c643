"""The law checked against the converged BEM (roughcontact.paper.bem_law) on made-up runs with a
known continuum limit and order of convergence."""

import numpy as np
import pytest

from roughcontact.contact.at_pressure import contact_at_pressure
from roughcontact.paper import bem_law
from roughcontact.paper import verify
from roughcontact.statistics.surface import SpectralMoments

M = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
P = np.array([1.0, 2.0, 5.0, 10.0, 20.0, 50.0])
U0, P0 = 0.1, 1e3
FACTOR = {0: 1.0, 1: 1.1, 2: 0.95}  # seed -> its gap over the law's


def _runs(order=2.0, c=0.01):
    """Gaps ḡ = f_seed · u0 ln(p0/p) · (1 + c (256/n)^order), seed 0 on 256², 512², 1024², three
    seeds on 512²; areas (1 + c (256/n)^order) times a seed factor of 1e-3 p."""
    out = []
    for n, seeds in ((256, [0]), (512, [0, 1, 2]), (1024, [0])):
        e = c * (256 / n) ** order
        for s in seeds:
            out.append({"family": "table1", "n": n, "seed": s, "pressure": P,
                        "mean_gap": FACTOR[s] * U0 * np.log(P0 / P) * (1 + e),
                        "area_fraction": FACTOR[s] * 1e-3 * P * (1 + e)})
    return out


def test_law_rows_extrapolate_to_the_known_limit():
    rows = bem_law.law_rows(_runs(), {"table1": M}, 1.14e5)
    assert len(rows) == P.size and set(bem_law.LAW_COLUMNS) <= set(rows[0])
    mean_f = np.mean(list(FACTOR.values()))
    gap = np.array([r["gap_exact"] for r in rows])
    np.testing.assert_allclose(gap, mean_f * U0 * np.log(P0 / P), rtol=1e-10)
    np.testing.assert_allclose([r["gap_order"] for r in rows], 2.0, rtol=1e-8)
    np.testing.assert_allclose([r["A_exact"] for r in rows], mean_f * 1e-3 * P, rtol=1e-10)
    # K = -dp/dḡ = p/(u0 f (1 + e)) exactly on the ladder (ln p linear in ḡ); 1/(1 + e) is
    # Richardson's form to O(e²) = 1e-4
    k = np.array([r["K_exact"] for r in rows])
    np.testing.assert_allclose(k, P / U0 * np.mean([1 / f for f in FACTOR.values()]), rtol=2e-4)
    assert rows[0]["grids"] == "256,512,1024" and rows[0]["reference_N"] == 512 and rows[0]["seeds"] == 3
    # the model columns: the law of (53), (55), (52) at W/A0
    ref = contact_at_pressure(M, P, E_star=1.14e5, model="bgk", hertz="exact", validity="off")
    np.testing.assert_allclose([r["gap_model"] for r in rows], ref.h, rtol=1e-10)
    np.testing.assert_allclose([r["K_model"] for r in rows], ref.stiffness, rtol=1e-10)
    np.testing.assert_allclose([r["gap_ratio"] for r in rows], ref.h / gap, rtol=1e-10)


def test_law_rows_need_three_paired_grids():
    runs = [r for r in _runs() if r["n"] != 256]
    assert bem_law.law_rows(runs, {"table1": M}, 1.14e5) == []
    md = bem_law.render_law_markdown([], stress_unit="N/mm^2", length_unit="mm", scale="ci", min_order=0.5)
    assert "Not resolved at this scale (`ci`)" in md


def test_checks_findings_and_ranges():
    rows = bem_law.law_rows(_runs(order=2.0, c=0.04), {"table1": M}, 1.14e5)
    # the 1024² error is c/16 = 0.25 % of the limit for the gap and the area
    tight, loose = {q: 0.002 for q in bem_law.QUANTITIES}, {q: 0.003 for q in bem_law.QUANTITIES}
    checks = {c.id: c for c in bem_law.convergence_checks(rows, tight, "test")}
    assert checks["numerics:bem/converged/table1/gap"].value == pytest.approx(0.0025, rel=1e-6)
    assert checks["numerics:bem/converged/table1/gap"].verdict == verify.NOT_REPRODUCED
    assert {c.id: c.verdict for c in bem_law.convergence_checks(rows, loose, "test")}[
        "numerics:bem/converged/table1/area"] == verify.REPRODUCED
    findings = bem_law.law_findings(rows, 0.2)
    assert [c.id for c in findings] == [f"claim:bem/law/table1/{q}" for q in ("gap", "stiffness", "area")]
    for c in findings:
        q = {"gap": "gap", "stiffness": "K", "area": "A"}[c.quantity]
        dev = np.array([r[f"{q}_ratio"] for r in rows]) - 1
        assert c.error == pytest.approx(dev[np.argmax(np.abs(dev))])
        assert c.verdict == (verify.REPRODUCED if np.all(np.abs(dev) <= 0.2) else verify.NOT_REPRODUCED)
    ranges = bem_law.law_ranges(rows)["table1"]
    for q, by_tol in ranges.items():
        col = {"gap": "gap", "stiffness": "K", "area": "A"}[q]
        for tol, rs in by_tol.items():
            inside = {r["W_over_A0"] for r in rows if abs(r[f"{col}_ratio"] - 1) <= tol}
            covered = {p for x in rs for p in P if x.p_low <= p <= x.p_high}
            assert covered == inside
    table = bem_law.render_check_rows(findings)
    assert table.count("| `claim:bem/law/table1/") == 3 and bem_law.render_check_rows([]) == ""
    md = bem_law.render_law_markdown(rows, stress_unit="N/mm^2", length_unit="mm", scale="full", min_order=0.5)
    assert "within 5 %" in md and "**table1, stiffness**" in md and md.count("| table1 |") == P.size
    ds = bem_law.law_dataset(rows, {"length": "mm", "stress": "N/mm^2"})
    assert ds["K_exact"].attrs["units"] == "N/mm^2 mm-1" and ds["gap_exact"].attrs["units"] == "mm"


def test_range_text():
    from roughcontact.bem.compare import holding_ranges
    rs = holding_ranges([1, 2, 5], [1.0, 1.01, 1.5], [0.001, 0.002, 0.005], 0.05)
    assert bem_law.range_text(rs, "N/mm^2") == "W/A0 = 1–2 N/mm^2 (A/A0 = 0.1–0.2 %)"
    assert bem_law.range_text([], "N/mm^2") == "nowhere"
    one = holding_ranges([1, 2, 5], [1.0, 1.5, 1.5], [0.001, 0.002, 0.005], 0.05)
    assert bem_law.range_text(one, "N/mm^2") == "W/A0 = 1 N/mm^2 (A/A0 = 0.1 %)"


def test_an_empty_law_is_still_cf(tmp_path):
    """The CI scale has no law rows: the netCDF is written, with the string columns as strings."""
    from roughcontact import io

    ds = bem_law.law_dataset([], {"length": "mm", "stress": "N/mm^2"})
    assert ds["family"].dtype.kind == "U" and ds.sizes["row"] == 0
    io.write_netcdf(ds, tmp_path / "law.nc", config={})


def test_beyond_the_finest_ladder_two_grids_give_gap_and_stiffness_only():
    """256² and 512² go on to 100 and 200 N/mm², 1024² stops at 50: the two extra loads come from
    512²'s seed mean with seed 0's change from 256² as the error, and no area."""
    longer = np.append(P, [100.0, 200.0])
    runs = []
    for r in _runs(order=2.0, c=0.04):
        if r["n"] == 1024:
            runs.append(r)
            continue
        e = 0.04 * (256 / r["n"]) ** 2
        f = FACTOR[r["seed"]]
        runs.append({**r, "pressure": longer, "mean_gap": f * U0 * np.log(P0 / longer) * (1 + e),
                     "area_fraction": f * 1e-3 * longer * (1 + e)})
    rows = bem_law.law_rows(runs, {"table1": M}, 1.14e5)
    beyond = [r for r in rows if r["W_over_A0"] > 50]
    assert [r["W_over_A0"] for r in beyond] == [100.0, 200.0] and {r["grids"] for r in beyond} == {"256,512"}
    e256, e512 = 0.04, 0.01
    mean_f = np.mean(list(FACTOR.values()))
    for r in beyond:
        assert r["gap_exact"] == pytest.approx(mean_f * U0 * np.log(P0 / r["W_over_A0"]) * (1 + e512), rel=1e-12)
        assert r["gap_finest_error"] == pytest.approx((e256 - e512) / (1 + e512), rel=1e-10)
        assert np.isnan(r["A_exact"]) and np.isnan(r["A_ratio"])
        assert r["A_reference"] == pytest.approx(mean_f * 1e-3 * r["W_over_A0"] * (1 + e512), rel=1e-12)
    ids = [c.id for c in bem_law.convergence_checks(rows, {q: 0.05 for q in bem_law.QUANTITIES}, "t")]
    assert "numerics:bem/converged/table1/gap/beyond-finest" in ids
    assert "numerics:bem/converged/table1/area/beyond-finest" not in ids
    ranges = bem_law.law_ranges(rows)["table1"]
    assert all(x.p_high <= 50 for tol in ranges["area"].values() for x in tol)  # no area beyond
    # the gap's ranges do reach beyond: every load of the ladder is a point of them or outside them
    covered = {p for tol in ranges["gap"].values() for x in tol for p in longer if x.p_low <= p <= x.p_high}
    inside = {r["W_over_A0"] for r in rows if abs(r["gap_ratio"] - 1) <= 0.2}
    assert covered == inside
    md = bem_law.render_law_markdown(rows, stress_unit="N/mm^2", length_unit="mm", scale="full", min_order=0.5)
    assert "| table1 | 200 | 256,512 |" in md and "at 512²)" in md
