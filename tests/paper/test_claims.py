"""Prose-claim evaluators (claims.py) and the elasto-plastic scene data (scenes.py).

Tiers: exact answers on synthetic curves (W = A e^{−b s} has K = b W/√m00, so K at equal
pressure is known in closed form); the equal-pressure interpolation against direct evaluation
of the model; each evaluator's verdict flips where its criterion says; the scene datasets."""

import math

import numpy as np
import pytest
import xarray as xr

from roughcontact import SpectralMoments
from roughcontact import asperity as asp
from roughcontact.paper import claims, scenes
from roughcontact.contact.closures import resolve_material
from roughcontact.contact.elastoplastic import elastoplastic_contact

TABLE1 = dict(m00=0.0625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)
E_STAR = 1.14e5
S = np.linspace(-2.0, 5.0, 71)  # the figures' grid
S_SYN = np.linspace(-6.0, 8.0, 141)  # synthetic curves: wide enough for 1-1000 at every b used


def exp_curve(A, b, m00, s=S_SYN):
    """W/A0 = A e^{−b s}: then K/A0 = −dW/dh = b W/√m00 exactly (h = s √m00)."""
    w = A * np.exp(-b * s)
    return w, b * w / math.sqrt(m00)


def test_first_yield_mean_pressure_is_0382H():
    """Errata E23: the mean pressure at first yield is (2/3) K Y = 0.382 H with Tabor's H, for
    every shape and curvature — not the prose's 0.354 H (which is Y)."""
    mat = asp.AsperityMaterial(E_STAR, 2070.0)
    for e1, kappa in ((1.0, 0.01), (0.05, 0.3), (1e-4, 2.0)):
        wc = asp.critical_interference(kappa, e1, mat)
        assert asp.mean_pressure(wc, kappa, e1, mat) / mat.H == pytest.approx(2 / 3 * 1.62 * 0.354, rel=1e-13)
    assert 2 / 3 * 1.62 * 0.354 == pytest.approx(0.38232, abs=5e-6)


# --------------------------------------------------------------------------------------
# equal-pressure interpolation
# --------------------------------------------------------------------------------------
def test_stiffness_at_is_exact_on_exponential_curves():
    m00 = 0.3
    p, k = exp_curve(50.0, 1.7, m00)
    w = np.geomspace(1.0, 1000.0, 13)
    np.testing.assert_allclose(claims.stiffness_at(S_SYN, p, k, m00, w), 1.7 * w / math.sqrt(m00), rtol=1e-12)
    s_w = claims.separation_at(S_SYN, p, k, m00, w)
    np.testing.assert_allclose(50.0 * np.exp(-1.7 * s_w), w, rtol=1e-12)
    with pytest.raises(ValueError, match="outside the computed curve"):
        claims.stiffness_at(S_SYN, p, k, m00, [1e9])


@pytest.mark.parametrize("psi", [0.5, 5.0])
def test_stiffness_at_matches_direct_evaluation(psi):
    """On the figures' grid (Δs = 0.1, plot preset) the interpolated K at equal pressure is
    the model's own to ≤ 1e-7 (measured 2.5e-8), and the found s gives W = w to ≤ 1e-7:
    well inside claims.RESOLUTION."""
    surface = SpectralMoments(**TABLE1)
    mat = resolve_material(surface, E_star=E_STAR, psi=psi)
    c = elastoplastic_contact(surface, S, mat, accuracy="plot", validity="warn")
    w = np.geomspace(1.0, 1000.0, 9)
    s_w = claims.separation_at(S, c.pressure, c.stiffness, surface.m00, w)
    direct = elastoplastic_contact(surface, s_w, mat, accuracy="plot", validity="warn")  # psi = 5: A/A0 = 1.06 at 1000 N/mm²
    np.testing.assert_allclose(direct.pressure, w, rtol=1e-7)
    k = claims.stiffness_at(S, c.pressure, c.stiffness, surface.m00, w)
    np.testing.assert_allclose(k, direct.stiffness, rtol=1e-7)
    assert claims.RESOLUTION >= 10 * 1e-7


# --------------------------------------------------------------------------------------
# evaluators on synthetic data: the verdict flips where the criterion says
# --------------------------------------------------------------------------------------
def psi_dataset(yielded, plastic=None, s=np.array([0.0, 1.0, 2.0])):
    """Figs 5–6 style data: rows ψ = 0.35, 0.5, 2; area fraction 0.1 everywhere."""
    yielded = np.asarray(yielded, float)
    plastic = np.zeros_like(yielded) if plastic is None else np.asarray(plastic, float)
    area = np.full_like(yielded, 0.1)
    return xr.Dataset(
        {
            "area_fraction": (("psi", "s"), area),
            "plastic_area_fraction": (("psi", "s"), plastic * area),
            "elastoplastic_area_fraction": (("psi", "s"), (yielded - plastic) * area),
            "pressure": (("psi", "s"), np.array([[100.0, 10.0, 1.0]] * 3)),
            "material_H": (("psi",), [1e4, 8e3, 2e3]),
        },
        coords={"psi": [0.35, 0.5, 2.0], "s": s},
    )


def test_small_psi_and_light_load_evaluators():
    ds = psi_dataset([[0.01, 0.0, 0.0], [0.04, 0.02, 0.0], [0.9, 0.7, 0.5]])
    claim = dict(id="x", text="t", why="w", fraction="yielded", psi_max=0.5, bound=0.05)
    assert claims.evaluate("f", {**claim, "check": "small_psi_negligible"}, ds).verdict == "reproduced"
    assert claims.evaluate("f", {**claim, "check": "small_psi_negligible", "bound": 0.03}, ds).verdict == "not reproduced"
    light = dict(id="y", text="t", why="w", fraction="yielded", psi_min=1.0, bound=0.1, check="large_psi_plastic_at_light_load")
    c = claims.evaluate("f", light, ds)
    assert c.verdict == "reproduced" and c.value == pytest.approx(0.5)  # lightest load = largest s
    assert claims.evaluate("f", {**light, "fraction": "plastic"}, ds).verdict == "not reproduced"
    with pytest.raises(ValueError, match="no psi of the scene"):
        claims.evaluate("f", {**light, "psi_min": 10.0}, ds)


def test_plastic_share_grows_and_regimes():
    grows = dict(id="g", text="t", why="w", check="plastic_share_grows", fraction="yielded")
    ok = psi_dataset([[0.02, 0.01, 0.0], [0.2, 0.1, 0.05], [0.9, 0.7, 0.5]])
    assert claims.evaluate("f", grows, ok).verdict == "reproduced"
    falls_with_psi = psi_dataset([[0.3, 0.2, 0.1], [0.2, 0.1, 0.05], [0.9, 0.7, 0.5]])
    assert claims.evaluate("f", grows, falls_with_psi).verdict == "not reproduced"
    regimes = dict(id="r", text="t", why="w", check="deformation_regimes", elastic_below=0.4, plastic_above=1.0,
                   elastic_bound=0.1, plastic_bound=0.5, span=0.2)
    # ψ = 0.35 elastic (≤ 0.02), ψ = 2 plastic (≥ 0.5), ψ = 0.5 load-dependent: spans 0.15
    assert claims.evaluate("f", {**regimes, "span": 0.15}, ok).verdict == "reproduced"
    assert claims.evaluate("f", {**regimes, "span": 0.16}, ok).verdict == "not reproduced"
    assert claims.evaluate("f", {**regimes, "elastic_bound": 0.015}, ok).verdict == "not reproduced"


def test_mean_pressure_at_high_psi():
    ds = psi_dataset([[0.0] * 3] * 3)
    ds["pressure"] = (("psi", "s"), ds["area_fraction"].values * 0.967 * ds["material_H"].values[:, None])
    claim = dict(id="m", text="t", why="w", check="mean_pressure_at_high_psi", target=0.354, atol=0.02)
    c = claims.evaluate("f", claim, ds)
    assert c.verdict == "not reproduced" and c.value == pytest.approx(0.967)
    assert claims.evaluate("f", {**claim, "target": 0.967}, ds).verdict == "reproduced"


def stiffness_dataset(b_ep, b_el, m00=(0.1, 0.4), closures=("yield-from-psi", "material")):
    """Figs 7–8 style data: K = b W/√m00 per curve, b_ep/b_el[closure][m00 index]."""
    p = np.empty((len(closures), len(m00), S_SYN.size))
    data = {k: p.copy() for k in ("pressure", "stiffness", "elastic_model_pressure", "elastic_model_stiffness")}
    for i, _ in enumerate(closures):
        for j, m in enumerate(m00):
            data["pressure"][i, j], data["stiffness"][i, j] = exp_curve(80.0, b_ep[i][j], m)
            data["elastic_model_pressure"][i, j], data["elastic_model_stiffness"][i, j] = exp_curve(80.0, b_el[i][j], m)
    return xr.Dataset({k: (("closure", "m00", "s"), v) for k, v in data.items()},
                      coords={"closure": list(closures), "m00": list(m00), "s": S_SYN})


def test_figs78_evaluators():
    # K/√... : b/√m00 = 2/√0.1 = 6.3 and 2/√0.4 = 3.2: K falls with m00
    ds = stiffness_dataset(b_ep=[[1.9, 1.9], [1.7, 1.7]], b_el=[[2.0, 2.0], [2.0, 2.0]])
    base = dict(id="k", text="t", why="w", pressure_range=[1.0, 1000.0], closure="yield-from-psi")
    assert claims.evaluate("f", {**base, "check": "stiffness_decreases_with_m00"}, ds).verdict == "reproduced"
    assert claims.evaluate("f", {**base, "check": "elastoplastic_below_elastic"}, ds).verdict == "reproduced"
    gap = {**base, "check": "significant_gap_at_high_pressure", "bound": 0.1}
    c = claims.evaluate("f", gap, ds)
    assert c.verdict == "not reproduced" and c.value == pytest.approx(0.05, rel=1e-9)
    assert claims.evaluate("f", {**gap, "closure": "material"}, ds).verdict == "reproduced"  # 15 %
    above = stiffness_dataset(b_ep=[[2.1, 1.9], [1.7, 1.7]], b_el=[[2.0, 2.0], [2.0, 2.0]])
    assert claims.evaluate("f", {**base, "check": "elastoplastic_below_elastic"}, above).verdict == "not reproduced"
    # equal roughness, equal stiffness: the m00 ordering fails when b grows like √m00
    flat = stiffness_dataset(b_ep=[[1.0, 2.0]] * 2, b_el=[[1.0, 2.0]] * 2)
    assert claims.evaluate("f", {**base, "check": "stiffness_decreases_with_m00"}, flat).verdict == "not reproduced"


def sensitivity_dataset(b_variants, b_psi, m00=0.1):
    names = ["base", *b_variants]
    bs = [1.0, *b_variants.values()]
    p, k = zip(*(exp_curve(80.0, b, m00) for b in bs))
    pp, kp = zip(*(exp_curve(80.0, b, m00) for b in b_psi.values()))
    return xr.Dataset(
        {
            "pressure": (("variant", "s"), np.array(p)), "stiffness": (("variant", "s"), np.array(k)),
            "elastic_model_pressure": (("variant", "s"), np.array(p)),
            "elastic_model_stiffness": (("variant", "s"), np.array(k)),
            "variant_m00": (("variant",), [m00] * len(names)),
            "psi_pressure": (("psi", "s"), np.array(pp)), "psi_stiffness": (("psi", "s"), np.array(kp)),
        },
        coords={"variant": names, "psi": list(b_psi), "s": S_SYN},
    )


def test_sensitivity_evaluators():
    ds = sensitivity_dataset({"slopes_double": 1.05, "m00_double": 0.7}, {0.35: 1.2, 0.5: 1.0, 2.0: 0.9, 5.0: 0.95})
    base = dict(id="v", text="t", why="w", pressure_range=[1.0, 1000.0])
    noeff = {**base, "check": "no_effect_of_variants", "variants": ["slopes_double"], "models": ["elastic"],
             "reference_variant": "m00_double", "bound": 0.1}
    c = claims.evaluate("f", noeff, ds)
    assert c.verdict == "reproduced" and c.value == pytest.approx(0.05, rel=1e-9)
    assert claims.evaluate("f", {**noeff, "bound": 0.04}, ds).verdict == "not reproduced"
    sens = {**base, "check": "psi_sensitivity", "pair": [0.35, 0.5], "psi_range": [0.2, 1.0], "bound": 0.1}
    sharp = claims.evaluate("f", {**sens, "expect": "sharp"}, ds)
    slow = claims.evaluate("f", {**sens, "expect": "slow"}, ds)
    assert (sharp.verdict, slow.verdict) == ("reproduced", "not reproduced")  # +20 % from 0.5 to 0.35
    assert "psi 2 → 5: K rises with psi" in sharp.detail  # the inversion outside psi_range is reported
    # the inversion inside the range makes both fail
    wide = claims.evaluate("f", {**sens, "expect": "sharp", "psi_range": [0.2, 10.0]}, ds)
    assert wide.verdict == "not reproduced"


def test_unknown_check():
    with pytest.raises(ValueError, match="unknown claim check"):
        claims.evaluate("f", {"id": "u", "check": "vibes"}, None)


# --------------------------------------------------------------------------------------
# scene datasets
# --------------------------------------------------------------------------------------
def test_stiffness_curves_per_closure():
    s = np.array([0.0, 2.0])
    ds = scenes.stiffness_curves(TABLE1, [0.0625, 0.3125], E_STAR, 0.5, 2070.0,
                                 ["yield-from-psi", "paper-literal", "material"], s)
    assert dict(ds.sizes) == {"closure": 3, "m00": 2, "s": 2}
    psi = ds["material_psi"]
    np.testing.assert_allclose(psi.sel(closure="yield-from-psi"), 0.5, rtol=1e-14)
    np.testing.assert_allclose(psi.sel(closure="paper-literal"), 0.5, rtol=1e-14)
    np.testing.assert_allclose(psi.sel(closure="material"), [0.8806, 1.3490], rtol=1e-4)  # the captions' E*, Y
    # the elastic model is closure-independent
    el = ds["elastic_model_pressure"]
    np.testing.assert_array_equal(el.sel(closure="material"), el.sel(closure="yield-from-psi"))
    np.testing.assert_allclose(ds["material_H"].sel(closure="paper-literal"), 2070.0 / 0.354, rtol=1e-15)


def test_stiffness_sensitivity_variants_and_psi_series():
    ds = scenes.stiffness_sensitivity(TABLE1, E_STAR, 0.5, {"slopes_double": {"m20": 2.0, "m02": 2.0}},
                                      [0.35, 0.5], np.array([0.0, 2.0]))
    assert list(ds["variant"].values) == ["base", "slopes_double"]
    assert float(ds["variant_m20"].sel(variant="slopes_double")) == pytest.approx(1.6e-4)
    assert float(ds["variant_m00"].sel(variant="slopes_double")) == 0.0625
    np.testing.assert_array_equal(ds["psi_pressure"].sel(psi=0.5), ds["pressure"].sel(variant="base"))
    with pytest.raises(ValueError, match="unknown moments"):
        scenes.stiffness_sensitivity(TABLE1, E_STAR, 0.5, {"bad": {"alpha": 2.0}}, [0.5], [0.0])


# --------------------------------------------------------------------------------------
# friction law: the evaluators on material points driven through friction.update
# --------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def geometry():
    return scenes.slip_rule_geometry({"orthotropic": (0.2, 0.4), "isotropic": (0.3, 0.3)}, [0.0, 0.5, 1.0],
                                     directions=12)


def test_slip_rule_evaluators(geometry):
    base = dict(id="s", text="t", why="w", check="slip_rule", atol=1e-9)
    assert claims.evaluate("f", {**base, "rule": "coaxial", "set": "orthotropic", "k": 0.0}, geometry).verdict == "reproduced"
    assert claims.evaluate("f", {**base, "rule": "normal", "set": "orthotropic", "k": 1.0}, geometry).verdict == "reproduced"
    assert claims.evaluate("f", {**base, "rule": "eq118", "set": "orthotropic"}, geometry).verdict == "reproduced"
    assert claims.evaluate("f", {**base, "rule": "coaxial", "set": "isotropic"}, geometry).verdict == "reproduced"
    # the statements are not vacuous: the orthotropic slip is not coaxial for k = 1 (36.8°) and
    # not normal to f for k = 0
    c = claims.evaluate("f", {**base, "rule": "coaxial", "set": "orthotropic", "k": 1.0}, geometry)
    assert c.verdict == "not reproduced" and c.value > 0.5
    assert claims.evaluate("f", {**base, "rule": "normal", "set": "orthotropic", "k": 0.0}, geometry).verdict == "not reproduced"
    lim = claims.evaluate("f", dict(id="l", text="t", why="w", check="on_limit_surface", atol=1e-12), geometry)
    assert lim.verdict == "reproduced"


def test_hardening_evaluator():
    h = scenes.hardening_path(0.5, 0.5, 0.275, k_T=7.0, p_N=2.5, slip=20.0, steps=100)
    claim = dict(id="h", text="t", why="w", check="traction_follows_hardening", rtol=1e-12)
    assert claims.evaluate("f", claim, h).verdict == "reproduced"
    wrong = h.assign(mu_x_89=h["mu_x_89"] * (1 + 1e-6))  # a slightly different law fails
    assert claims.evaluate("f", claim, wrong).verdict == "not reproduced"


def test_fig18_path_evaluators():
    ds = scenes.fig18_paths(["a", "b", "c"], 10.0, 2.5, angle_deg=30.0, u_max=5.0, steps=40)
    sym = dict(id="m", text="t", why="w", check="mirror_symmetry", symmetric=["a", "b"], rtol=1e-12, asymmetry=1e-3)
    assert claims.evaluate("f", sym, ds).verdict == "reproduced"
    assert claims.evaluate("f", {**sym, "symmetric": ["a", "b", "c"]}, ds).verdict == "not reproduced"
    order = dict(id="o", text="t", why="w", check="plastic_slip_order", component="magnitude")
    assert claims.evaluate("f", {**order, "larger": "a", "smaller": "b"}, ds).verdict == "reproduced"
    assert claims.evaluate("f", {**order, "larger": "b", "smaller": "a"}, ds).verdict == "not reproduced"
    rev = dict(id="r", text="t", why="w", check="unloading_reverses_traction")
    assert claims.evaluate("f", rev, ds).verdict == "reproduced"
    # a path that stops before the traction can reverse (unload by less than 2 μ p/k_T) does not show it
    short = scenes.fig18_paths(["a"], 10.0, 2.5, angle_deg=30.0, u_max=0.05, steps=5)
    assert claims.evaluate("f", rev, short).verdict == "not reproduced"
    dis = dict(id="d", text="t", why="w", check="dissipation_nonnegative")
    assert claims.evaluate("f", dis, ds).verdict == "reproduced"
    assert claims.evaluate("f", dis, ds.assign(dissipation=-ds["dissipation"])).verdict == "not reproduced"


def test_elastoplastic_numerics_checks():
    """The numerics rows compare the totals (sums of the regime parts) of both integrators."""
    cols = ["elastic_area_fraction", "elastoplastic_area_fraction", "plastic_area_fraction",
            "elastic_pressure", "elastoplastic_pressure", "plastic_pressure", "stiffness"]
    ref = np.array([[0.1, 0.02, 0.0, 10.0, 3.0, 0.0, 50.0]])
    prod = ref * (1 + np.array([[1e-9, 0, 0, 0, 0, 0, 2e-8]]))
    ds = xr.Dataset({**{f"production_{c}": ("point", prod[:, j]) for j, c in enumerate(cols)},
                     **{f"reference_{c}": ("point", ref[:, j]) for j, c in enumerate(cols)}},
                    coords={"point": ["p1"]}, attrs={"reference_rtol": 1e-10, "columns": " ".join(cols)})
    checks = claims.elastoplastic_numerics_checks("ep", ds, 1e-8, "why")
    assert [c.quantity for c in checks] == ["area_fraction", "pressure", "stiffness"]
    assert [c.verdict for c in checks] == ["reproduced", "reproduced", "not reproduced"]
    assert checks[0].value == pytest.approx(0.12 + 1e-10, rel=1e-15) and checks[0].id.endswith("point=p1")
