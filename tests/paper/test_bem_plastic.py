"""The elasto-plastic model against the BEM with a hardness cap (roughcontact.paper.bem_plastic)
on made-up plastic runs."""

import numpy as np
import pytest

from roughcontact.bem.compare import plastic_material
from roughcontact.contact.at_pressure import contact_at_pressure
from roughcontact.paper import bem_plastic
from roughcontact.paper import verify
from roughcontact.statistics.surface import SpectralMoments

M = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
P = np.array([1.0, 10.0, 100.0])
PSI = np.array([1.0, 5.0])
E = 1.14e5


def _runs():
    """BEM areas 1.1 and 1.3 times the model's at psi = 1 (seeds 0, 1) and equal at psi = 5;
    gaps twice the model's h; a fifth of the contact at the cap."""
    model = {psi: contact_at_pressure(M, P, material=plastic_material(M, E, psi), validity="off")
             for psi in PSI}
    out = []
    for seed, f in ((0, 1.1), (1, 1.3)):
        area = np.array([model[1.0].area_fraction * f, model[5.0].area_fraction])
        out.append({"family": "table1", "n": 256, "seed": seed, "psi": PSI, "pressure": P, "area_fraction": area,
                    "plastic_area_fraction": 0.2 * area,
                    "mean_gap": np.array([2 * model[psi].h for psi in PSI])})
    return out, model


def test_plastic_rows_against_the_model():
    runs, model = _runs()
    rows = bem_plastic.plastic_rows(runs, {"table1": M}, E)
    assert len(rows) == PSI.size * P.size and set(bem_plastic.PLASTIC_COLUMNS) <= set(rows[0])
    for r in rows:
        i = int(np.flatnonzero(P == r["W_over_A0"])[0])
        m = model[r["psi"]]
        assert r["A_model"] == pytest.approx(m.area_fraction[i], rel=1e-10)
        assert r["h_model"] == pytest.approx(m.h[i], rel=1e-10)
        assert r["A_ratio"] == pytest.approx(1 / 1.2 if r["psi"] == 1.0 else 1.0, rel=1e-10)
        assert r["gap_ratio"] == pytest.approx(0.5, rel=1e-10) and r["cap_over_A_BEM"] == pytest.approx(0.2)
        assert r["cap"] == pytest.approx(0.967 * r["H"]) and r["seeds"] == 2
        assert 0 <= r["plastic_over_A_model"] <= r["yielded_over_A_model"] <= 1
    assert bem_plastic.plastic_findings(rows, 0.2, min_seeds=3) == []  # two seeds only
    findings = {c.id: c for c in bem_plastic.plastic_findings(rows, 0.2)}
    assert findings["claim:bem/plastic/table1/psi=1/area"].verdict == verify.REPRODUCED  # 1/1.2: -16.7 %
    assert findings["claim:bem/plastic/table1/psi=1/area"].error == pytest.approx(1 / 1.2 - 1)
    assert findings["claim:bem/plastic/table1/psi=5/gap"].verdict == verify.NOT_REPRODUCED  # -50 %
    ranges = bem_plastic.plastic_ranges(rows)
    assert [(r.p_low, r.p_high) for r in ranges[("table1", 5.0)]["area"][0.05]] == [(1.0, 100.0)]
    assert ranges[("table1", 1.0)]["area"][0.10] == [] and ranges[("table1", 1.0)]["gap"][0.20] == []
    md = bem_plastic.render_plastic_markdown(rows, stress_unit="N/mm^2", length_unit="mm", scale="full")
    assert "**table1, ψ = 5, area**: within 5 %: W/A0 = 1–100" in md
    ds = bem_plastic.plastic_dataset(rows, {"length": "mm", "stress": "N/mm^2"})
    assert ds["gap_BEM"].attrs["units"] == "mm" and ds.sizes["row"] == len(rows)


def test_plastic_rows_refuse_mixed_ladders_and_say_when_absent():
    runs, _ = _runs()
    runs[1] = {**runs[1], "psi": PSI * 2}
    with pytest.raises(ValueError, match="different pressures or psi"):
        bem_plastic.plastic_rows(runs, {"table1": M}, E)
    assert "No plastic BEM runs at this scale" in bem_plastic.render_plastic_markdown(
        [], stress_unit="N/mm^2", length_unit="mm", scale="x")


def test_markdown_and_findings_use_the_finest_grid():
    runs, _ = _runs()
    fine = [{**r, "n": 512} for r in runs]
    rows = bem_plastic.plastic_rows(runs + fine, {"table1": M}, E)
    assert {r["N"] for r in rows} == {256, 512}
    md = bem_plastic.render_plastic_markdown(rows, stress_unit="N/mm^2", length_unit="mm", scale="full")
    assert md.count("| table1 | 1 |") == P.size and "| 256 |" not in md and "| 512 |" in md
    assert all("512²" in c.detail for c in bem_plastic.plastic_findings(rows, 0.2))
