"""The gate's anchors of issue 29 (roughcontact.paper.gate_anchors), without a workflow run: the
sampled points of the elasto-plastic curves and sweeps against the slow twins, and a published CSV
against the one re-derived from its result files. Each 5 % injection of the issue turns its check
red and names the file and the cell."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from roughcontact.paper import gate_anchors as ga
from roughcontact.paper.verify import NOT_REPRODUCED, REPRODUCED

ROOT = Path(__file__).resolve().parents[2]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
TOL = CONFIG["gate_anchors"]["curves"]["tolerance"]
TABLE1 = CONFIG["surfaces"]["table1"]


# ---------------------------------------------------------------------------------------------
# sample points
# ---------------------------------------------------------------------------------------------
def test_the_configured_samples_resolve_to_points_of_the_configured_grids():
    samples = CONFIG["gate_anchors"]["curves"]["samples"]
    for name, spec in samples.items():
        kind = "sweep" if name in CONFIG["sweeps"] else CONFIG["scenes"][name]["kind"]
        cfg = CONFIG["sweeps"][name] if kind == "sweep" else CONFIG["scenes"][name]
        points = ga.sample_points(kind, name, cfg, spec, CONFIG["surfaces"])
        assert len(points) == len(spec) and all(p.source == name for p in points)
    # the sweep's {index: 3} is the fourth m00 of its log grid, 0.0625 * 10^(3/7)
    sweep = ga.sample_points("sweep", "m00_psi", CONFIG["sweeps"]["m00_psi"], samples["m00_psi"])
    assert sweep[0].params["m00"] == pytest.approx(0.0625 * 10 ** (3 / 7), rel=1e-12)
    assert sweep[0].params["m20"] == 8.0e-5 and sweep[0].params["psi"] == 1.0
    # Fig. 7's "material" closure takes the caption's Y, not psi; m00 replaces the surface's
    fig7 = ga.sample_points("stiffness_pressure", "fig7", CONFIG["scenes"]["fig7"], samples["fig7"], CONFIG["surfaces"])
    material = next(p for p in fig7 if p.closure == "material")
    assert material.params["Y"] == 2070.0 and "psi" not in material.params and material.params["m00"] == 0.0625
    # a variant scales the moments it names
    sens = ga.sample_points("stiffness_sensitivity", "stiffness_sensitivity", CONFIG["scenes"]["stiffness_sensitivity"],
                            [{"variant": "curvatures_double", "s": -2.0}], CONFIG["surfaces"])[0]
    assert sens.params["m40"] == 2 * TABLE1["m40"] and sens.params["m04"] == 2 * TABLE1["m04"]
    assert sens.params["m00"] == TABLE1["m00"]


@pytest.mark.parametrize("sample, message", [
    ({"psi": 0.35, "s": 1.05}, r"samples\.fig5\[0\]: s = 1\.05 is not on the configured axis"),
    ({"psi": 0.4, "s": 1.0}, r"psi = 0\.4 is not on the configured axis"),
    ({"psi": 0.35}, r"samples\.fig5\[0\]: s is missing"),
    ({"psi": 0.35, "m00": 1.0, "s": 1.0}, r"give exactly psi and s"),
])
def test_a_sample_off_the_grid_is_refused_naming_it(sample, message):
    with pytest.raises((ValueError, TypeError), match=message):
        ga.sample_points("elastoplastic_psi", "fig5", CONFIG["scenes"]["fig5"], [sample], CONFIG["surfaces"])


# ---------------------------------------------------------------------------------------------
# curve checks on a constructed file
# ---------------------------------------------------------------------------------------------
def _fig5_file(values: dict[str, float], psi=(0.35, 5.0), s=(0.9, 1.0)) -> xr.Dataset:
    """A Fig. 5-like file whose every cell holds ``values`` (the twin's) at (psi = 5, s = 1)."""
    data = {}
    for v, x in values.items():
        a = np.full((len(psi), len(s)), np.nan)
        a[1, 1] = x
        data[v] = (("psi", "s"), a)
    return xr.Dataset(data, coords={"psi": list(psi), "s": list(s)})


TWIN = {"area_fraction": 0.02, "pressure": 30.0, "stiffness": 90.0, "elastic_area_fraction": 0.012,
        "elastoplastic_area_fraction": 0.002, "plastic_area_fraction": 0.006, "elastic_pressure": 20.0,
        "elastoplastic_pressure": 2.0, "plastic_pressure": 8.0}


def _point():
    return ga.sample_points("elastoplastic_psi", "fig5", CONFIG["scenes"]["fig5"], [{"psi": 5.0, "s": 1.0}],
                            CONFIG["surfaces"])[0]


def test_a_file_equal_to_the_twin_passes_every_sampled_cell():
    checks = ga.curve_anchor_checks([_point()], [TWIN], {"fig5": _fig5_file(TWIN)},
                                    {"fig5": "results/curves/fig5.nc"}, TOL, 1e-6, 12)
    assert len(checks) == 9 and all(c.verdict == REPRODUCED for c in checks)
    assert {c.quantity for c in checks} == set(TWIN)
    assert checks[0].id == "numerics:curve_anchors/fig5/area_fraction/point=psi=5,s=1"


@pytest.mark.parametrize("variables", [("area_fraction", "pressure", "stiffness"), tuple(TWIN)])
def test_a_five_percent_scale_of_the_curves_turns_every_scaled_cell_red_naming_it(variables):
    scaled = {k: v * (1.05 if k in variables else 1.0) for k, v in TWIN.items()}
    checks = ga.curve_anchor_checks([_point()], [TWIN], {"fig5": _fig5_file(scaled)},
                                    {"fig5": "results/curves/fig5.nc"}, TOL, 1e-6, 12)
    red = {c.quantity: c for c in checks if c.verdict == NOT_REPRODUCED}
    assert set(red) == set(variables)
    c = red["pressure"]
    assert c.error == pytest.approx(0.05, rel=1e-12)
    assert "results/curves/fig5.nc pressure[psi=5,s=1] = 31.5 vs 30" in c.detail
    if "plastic_pressure" in red:  # a part: its difference relative to the total W (8 * 0.05 / 30)
        assert red["plastic_pressure"].error == pytest.approx(0.4 / 30.0, rel=1e-12)


def test_a_missing_variable_or_coordinate_is_red_not_skipped():
    file = _fig5_file(TWIN).drop_vars("stiffness")
    checks = ga.curve_anchor_checks([_point()], [TWIN], {"fig5": file}, {"fig5": "f.nc"}, TOL, 1e-6, 12)
    (c,) = [c for c in checks if c.quantity == "stiffness"]
    assert c.verdict == NOT_REPRODUCED and math.isnan(c.value)
    moved = _fig5_file(TWIN, s=(0.9, 1.1))
    checks = ga.curve_anchor_checks([_point()], [TWIN], {"fig5": moved}, {"fig5": "f.nc"}, TOL, 1e-6, 12)
    assert all(c.verdict == NOT_REPRODUCED for c in checks)
    assert "s = 1 is not (once) on the file's axis" in checks[0].detail


def test_twin_values_take_the_twins_columns_and_the_elastic_model_times_E_star():
    """The quantities are assembled from the twins' outputs as documented: totals are the sums of
    the parts, K includes the load jump's column already (reference_integrals), the elastic model
    is E* times the dimensionless mpmath integrals."""
    calls = []

    def ep(surface, s, material, *, hertz, rtol):
        calls.append((s, hertz, rtol, material.E_star))
        return np.array([1.0, 2.0, 3.0, 10.0, 20.0, 30.0, 7.0, 0.5])

    def el(surface, s, *, hertz, dps, quantities):
        return {"area": np.array([0.1]), "load": np.array([2e-4]), "stiffness": np.array([3e-3])}

    point = ga.sample_points("stiffness_pressure", "fig7", CONFIG["scenes"]["fig7"],
                             [{"closure": "yield-from-psi", "m00": 0.625, "s": 0.0}], CONFIG["surfaces"])[0]
    out = ga.twin_values(point, rtol=1e-6, dps=12, ep_twin=ep, elastic_twin=el)
    assert calls == [(0.0, "exact", 1e-6, 1.14e5)]
    assert out["area_fraction"] == 6.0 and out["pressure"] == 60.0 and out["stiffness"] == 7.0
    assert out["plastic_pressure"] == 30.0
    assert out["elastic_model_pressure"] == pytest.approx(1.14e5 * 2e-4, rel=1e-15)
    assert out["elastic_model_stiffness"] == pytest.approx(1.14e5 * 3e-3, rel=1e-15)


@pytest.mark.mpmath
def test_the_real_twins_anchor_production_and_see_a_five_percent_error():
    """One real point (Fig. 5, psi = 5, s = 1, every regime present): the scipy twin at the
    configured rtol and the mpmath elastic integrals against production (~5 s of twins, plus the
    numba kernels' compilation in a fresh process: the slow tier)."""
    from roughcontact import SpectralMoments
    from roughcontact.contact import elastic_contact, elastoplastic_contact, resolve_material

    point = _point()
    rtol = CONFIG["gate_anchors"]["curves"]["twin_rtol"]
    twin = ga.twin_values(point, rtol=rtol, dps=12)
    surface = SpectralMoments(**TABLE1)
    mat = resolve_material(surface, E_star=1.14e5, psi=5.0, closure="yield-from-psi")
    c = elastoplastic_contact(surface, [1.0], mat, hertz="exact", accuracy="plot")
    prod = {k: float(getattr(c, k)[0]) for k in TWIN}
    file = _fig5_file(prod)
    checks = ga.curve_anchor_checks([point], [twin], {"fig5": file}, {"fig5": "f.nc"}, TOL, rtol, 12)
    assert all(c.verdict == REPRODUCED for c in checks), [c.detail for c in checks if c.verdict != REPRODUCED]
    assert twin["plastic_area_fraction"] > 0.05 * twin["area_fraction"]  # the plastic regime is in the sample
    scaled = _fig5_file({k: 1.05 * v for k, v in prod.items()})
    assert all(c.verdict == NOT_REPRODUCED for c in ga.curve_anchor_checks(
        [point], [twin], {"fig5": scaled}, {"fig5": "f.nc"}, TOL, rtol, 12) if c.quantity in ("area_fraction",
                                                                                               "pressure", "stiffness"))
    # the elastic model: mpmath integrals times E* against the production elastic curves
    el = ga.twin_values(ga.TwinPoint("x", {"s": 1.0}, point.params, "yield-from-psi", "exact",
                                     {v: v for v in ga.ELASTIC_MODEL}), rtol=rtol, dps=12)
    e = elastic_contact(surface, [1.0], 1.14e5, hertz="exact", accuracy="plot")
    assert el["elastic_model_pressure"] == pytest.approx(float(e.pressure[0]), rel=1e-8)
    assert el["elastic_model_stiffness"] == pytest.approx(float(e.stiffness[0]), rel=1e-8)


# ---------------------------------------------------------------------------------------------
# published CSVs
# ---------------------------------------------------------------------------------------------
CSV_TOL = CONFIG["gate_anchors"]["csv"]["tolerance"]
DERIVED = ("scene,model,column,quantity,unit,s,paper,ours,verdict\n"
           "table3,nu-0,nu = 0.0,kn_over_kt,1,1.0,1.4286,1.4285714285714286,reproduced\n"
           "table3,nu-0,nu = 0.0,kn_over_kt,1,10.0,1.2345,1.2345012345,reproduced\n")


def test_an_unchanged_csv_passes():
    c = ga.csv_cell_check("paper_figures/table3.csv", DERIVED, DERIVED, CSV_TOL)
    assert c.verdict == REPRODUCED and c.value == 0.0
    assert c.id == "numerics:published_csv/table3/cells/file=paper_figures/table3.csv"
    # the last digit formatted otherwise (1e-16 relative) is no difference
    c = ga.csv_cell_check("t.csv", DERIVED.replace("1.4285714285714286", "1.428571428571429"), DERIVED, CSV_TOL)
    assert c.verdict == REPRODUCED


@pytest.mark.parametrize("edit, where", [
    (("1.4285714285714286", "1.5"), "line 2 (table3,nu-0), column 'ours': published '1.5' vs derived '1.4285714285714286'"),
    (("1.2345012345", "1.29622629622"), "line 3 (table3,nu-0), column 'ours'"),          # x 1.05
    (("reproduced\ntable3,nu-0,nu = 0.0,kn_over_kt,1,10.0", "not reproduced\ntable3,nu-0,nu = 0.0,kn_over_kt,1,10.0"),
     "line 2 (table3,nu-0), column 'verdict'"),
])
def test_an_edited_cell_is_red_naming_the_file_and_the_cell(edit, where):
    c = ga.csv_cell_check("paper_figures/table3.csv", DERIVED.replace(*edit), DERIVED, CSV_TOL)
    assert c.verdict == NOT_REPRODUCED and c.value == 1.0
    assert c.detail.startswith("paper_figures/table3.csv differs from its result files in 1 place(s): ")
    assert where in c.detail


def test_a_dropped_row_or_a_changed_header_is_red():
    short = "\n".join(DERIVED.splitlines()[:2]) + "\n"
    c = ga.csv_cell_check("t.csv", short, DERIVED, CSV_TOL)
    assert c.verdict == NOT_REPRODUCED and "1 rows vs 2 derived" in c.detail
    c = ga.csv_cell_check("t.csv", DERIVED.replace("ours", "mine"), DERIVED, CSV_TOL)
    assert c.verdict == NOT_REPRODUCED and "header" in c.detail


# ---------------------------------------------------------------------------------------------
# the punch: slips and D against the work of its own tractions on its own jumps
# ---------------------------------------------------------------------------------------------
ENERGY = CONFIG["fe_anchors"]["punch"]["tolerances"]["energy"]


def _one_point_history(form):
    """One contact point (area 1 mm²) pushed along x through the levels of a hand-made history
    under the elastic law (93) of ``form`` with a friction limit |t_x| ≤ 3 N/mm², the stiffness
    k_T changing from level to level: (dataset, expected slips [µm], expected work [N mm])."""
    k = np.array([2.0, 2.0, 4.0, 1.0, 1.0])      # N/mm²/µm at levels 0..4; 2 at the unloaded start
    J = np.array([0.5, 1.0, 2.0, 3.0, 2.5])      # µm from the unloaded start
    t, up, t_prev, k_prev, up_prev, J_prev = [], [], 0.0, 2.0, 0.0, 0.0
    for kn, Jn in zip(k, J):
        kk = kn if form != "incremental-start" else k_prev
        if form == "secant":
            trial = kn * (t_prev / k_prev + (Jn - J_prev))
        else:
            trial = t_prev + kk * (Jn - J_prev)
        tn = float(np.clip(trial, -3.0, 3.0))
        stiff = kk if form != "secant" else kn
        dup = (trial - tn) / stiff            # the return to the limit: the excess is plastic slip
        t.append(tn)
        up.append(up_prev + dup)
        t_prev, k_prev, up_prev, J_prev = tn, kn, up_prev + dup, Jn
    t, up = np.array(t), np.array(up)
    work = 4.0 * float(np.sum(t * np.diff(np.concatenate([[0.0], up])))) / 1000.0
    zeros = np.zeros((k.size, 1))
    ds = xr.Dataset({"t_x": (("level", "point"), t[:, None]), "t_y": (("level", "point"), zeros),
                     "slip_x_um": (("level", "point"), up[:, None]), "slip_y_um": (("level", "point"), zeros),
                     "jump_x_um": (("level", "point"), J[:, None] - 0.5), "jump_y_um": (("level", "point"), zeros),
                     "seating_jump_x_um": ("point", [0.5]), "seating_jump_y_um": ("point", [0.0]),
                     "k_Tx": (("level", "point"), k[:, None]), "k_Ty": (("level", "point"), k[:, None]),
                     "cutbacks": ("level", np.zeros(k.size, dtype=int)), "point_weight": ("point", [1.0])},
                    coords={"x": ("point", [9.0]), "y": ("point", [1.0])},
                    attrs={"k_Tx_unloaded": 2.0, "k_Ty_unloaded": 2.0, "max_index": 3})
    ds.attrs["D_max_work_whole"] = 4.0 * float(np.sum((t * np.diff(np.concatenate([[0.0], up])))[:4])) / 1000.0
    ds.attrs["D_end_work_whole"] = work
    ds.attrs["D_max_area_whole"] = 4.0 * float(t[3] * up[3]) / 1000.0
    return ds, up, work


class _Run:
    def __init__(self, form, case="a"):
        self.tangential_form, self.case, self.family = form, case, "quadratic"


@pytest.mark.parametrize("form", ["incremental-end", "incremental-start", "secant"])
def test_the_slips_are_rebuilt_from_jumps_tractions_and_k_T_of_each_form(form):
    from roughcontact.paper import fe_anchors

    ds, up, work = _one_point_history(form)
    assert up[-2] > 0.0 and work > 0.0  # the point slips: the history tests the plastic branch
    rebuilt = fe_anchors.rebuilt_slips(ds, form)
    np.testing.assert_allclose(rebuilt["x"][:, 0], up, rtol=0, atol=1e-14)
    checks = fe_anchors.punch_energy_checks({"quadratic-quarter-a": _Run(form)}, {"quadratic-quarter-a": ds}, ENERGY)
    assert [c.quantity for c in checks] == ["slip_balance", "work_balance"]
    assert all(c.verdict == REPRODUCED for c in checks), [c.detail for c in checks]
    assert checks[0].id == "numerics:fe_punch_anchor/fe-quadratic/slip_balance/run=quarter-a"


@pytest.mark.parametrize("slips, d, red", [
    (1.05, 1.05, {"slip_balance", "work_balance"}),   # the audit's injection: slips and D together
    (1.05, 1.0, {"slip_balance"}),                    # the slips alone (D still the tractions' work)
    (1.0, 1.05, {"work_balance"}),                    # D alone
    (0.95, 0.95, {"slip_balance", "work_balance"}),
])
def test_slips_and_D_scaled_together_turn_the_punch_anchor_red(slips, d, red):
    from roughcontact.paper import fe_anchors

    ds, _, _ = _one_point_history("incremental-end")
    ds["slip_x_um"] = ds["slip_x_um"] * slips
    for attr in ("D_max_work_whole", "D_end_work_whole", "D_max_area_whole"):
        ds.attrs[attr] *= d
    checks = fe_anchors.punch_energy_checks({"q-quarter-a": _Run("incremental-end")}, {"q-quarter-a": ds}, ENERGY)
    assert {c.quantity for c in checks if c.verdict == NOT_REPRODUCED} == red
    bad = {c.quantity: c for c in checks}
    if "slip_balance" in red:
        assert "written u_x^p" in bad["slip_balance"].detail and "at level" in bad["slip_balance"].detail
    if "work_balance" in red:
        assert bad["work_balance"].error == pytest.approx(abs(d - 1.0) / max(d, 1.0), rel=1e-9)


def test_a_frictionless_run_has_no_energy_checks_and_a_run_without_k_T_is_red():
    from roughcontact.paper import fe_anchors

    ds, _, _ = _one_point_history("incremental-end")
    assert fe_anchors.punch_energy_checks({"q-f": _Run("incremental-end", "frictionless")}, {"q-f": ds}, ENERGY) == []
    checks = fe_anchors.punch_energy_checks({"q-a": _Run("incremental-end")}, {"q-a": ds.drop_vars(["k_Tx", "k_Ty"])},
                                            ENERGY)
    assert [c.verdict for c in checks] == [NOT_REPRODUCED] * 2 and "re-run it" in checks[0].detail


# ---------------------------------------------------------------------------------------------
# the declared counts (config/expected_verdicts.yaml expected_checks)
# ---------------------------------------------------------------------------------------------
EXPECTED = yaml.safe_load((ROOT / "config" / "expected_verdicts.yaml").read_text())["expected_checks"]


def test_the_declared_counts_are_the_configured_samples_csvs_and_punch_runs():
    samples = CONFIG["gate_anchors"]["curves"]["samples"]
    n = 0
    for name, spec in samples.items():
        kind = "sweep" if name in CONFIG["sweeps"] else CONFIG["scenes"][name]["kind"]
        cfg = CONFIG["sweeps"][name] if kind == "sweep" else CONFIG["scenes"][name]
        n += sum(len(p.variables) for p in ga.sample_points(kind, name, cfg, spec, CONFIG["surfaces"]))
    assert EXPECTED["curve_anchors"] == n == 104
    scenes = CONFIG["scenes"]
    figures = [s for s, sc in scenes.items() if sc["kind"] in (
        "bearing_ratio", "hertz_factors", "elastoplastic_psi", "stiffness_pressure", "stiffness_sensitivity",
        "friction_slip_rule", "friction_hardening", "friction_cases")]
    tables = [s for s, sc in scenes.items() if sc["kind"] in ("table", "mindlin_table")]
    numerics = [s for s, sc in scenes.items() if sc["kind"] == "elastoplastic_numerics"]
    fe = ["table4", "fig13", "fe_beam_study", "table5", "fe_punch_readings", "fig18", "fig19", "fe_export"]
    drawings = ["fig11", "fig12", "fig16", "fig17"]
    assert EXPECTED["published_csv"] == len(tables + figures + numerics + fe + drawings) + len(CONFIG["geometry_figures"])
    from roughcontact.examples import runs as fe_runs

    runs = {n: r for g in fe_runs.punch_groups(CONFIG["fe"]["punch"]).values() for n, r in g.items()}
    frictional = sum(r.case != "frictionless" for r in runs.values())
    assert EXPECTED["fe_punch_anchor"] == 6 * frictional + 2 * (len(runs) - frictional)


def test_the_gate_names_the_cell_of_each_regression(tmp_path):
    """The gate's message gives each regression's detail beside its id: the tampered file and its
    cell, not only the check's name."""
    import importlib.util
    import json

    from roughcontact.paper import verify

    bad = ga.csv_cell_check("paper_figures/table3.csv", DERIVED.replace("1.4285714285714286", "1.5"), DERIVED, CSV_TOL)
    checks = verify.apply_expectations([bad], {})
    summary = {**verify.summarize(checks), "regression_details": ga.regression_details(checks)}
    assert not summary["passed"] and summary["regression_ids"] == [bad.id]
    spec = importlib.util.spec_from_file_location("verify_gate", ROOT / "workflow" / "scripts" / "verify_gate.py")
    gate = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gate)
    (tmp_path / "summary.json").write_text(json.dumps(summary))
    with pytest.raises(SystemExit, match="1 verification regression"):
        gate.run(tmp_path / "summary.json", tmp_path / "passed", tmp_path / "gate.log")
    log = (tmp_path / "gate.log").read_text()
    assert ("REGRESSION numerics:published_csv/table3/cells/file=paper_figures/table3.csv: paper_figures/table3.csv "
            "differs from its result files in 1 place(s): line 2 (table3,nu-0), column 'ours'") in log
