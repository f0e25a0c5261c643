"""roughcontact.contact.validity: the model's range of validity, warned about and enforced
(issue #12: `elastic --s -5` gave A/A0 = 1.43, a NormalLawTable up to 1e5 N/mm² A/A0 = 10)."""

import math
import warnings

import numpy as np
import pytest

from roughcontact import SpectralMoments
from roughcontact.asperity import AsperityMaterial
from roughcontact.contact import elastic_contact, elastoplastic_contact, validity
from roughcontact.contact.sweep import SweepSpec, run_sweep
from roughcontact.contact.validity import AccuracyWarning, ModelValidityWarning, check_validity
from roughcontact.interface.normal_law import NormalLawTable

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
E_STAR = 1.14e5


def _caught(fn, *args, **kwargs):
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        out = fn(*args, **kwargs)
    return out, [x for x in w if issubclass(x.category, (ModelValidityWarning, AccuracyWarning))]


def test_check_validity_warns_and_refuses():
    _, w = _caught(check_validity, [1.0, 2.0], [0.05, 0.01])
    assert w == []
    _, w = _caught(check_validity, [0.5], [0.2])
    assert len(w) == 1 and "exceeds 0.1" in str(w[0].message)
    _, w = _caught(check_validity, [0.5], [0.2], area_ratio_limit=0.3)  # the limit is a setting
    assert w == []
    _, w = _caught(check_validity, [-0.1], [0.05])
    assert len(w) == 1 and "s = -0.1 < 0" in str(w[0].message)
    with pytest.raises(ValueError, match=r"A/A0 = 1\.5 > 1 at s = -3"):
        check_validity([-3.0, 1.0], [1.5, 0.05])
    _, w = _caught(check_validity, [-3.0], [1.5], mode="warn")
    assert any("> 1" in str(x.message) for x in w)
    _, w = _caught(check_validity, [-3.0], [1.5], mode="off")
    assert w == []
    with pytest.raises(ValueError, match="area_ratio_limit"):
        check_validity([1.0], [0.01], area_ratio_limit=2.0)
    assert validity.AREA_RATIO_LIMIT == 0.1  # the messages above quote it


def test_the_area_limit_is_the_measured_one():
    """AREA_RATIO_LIMIT is the smallest A/A0 up to which the model stayed within 20 % of the BEM
    (BEM_AGREEMENT_20, from `snakemake bem`), rounded down to two decimals; docs/bem.md quotes
    the same numbers."""
    import math
    from pathlib import Path

    inside = [v[0] for v in validity.BEM_AGREEMENT_20.values()]
    assert validity.AREA_RATIO_LIMIT == math.floor(100 * min(inside)) / 100
    for low, high in validity.BEM_AGREEMENT_20.values():
        assert 0 < low < 1 and (high is None or low < high <= 1)
    doc = (Path(__file__).resolve().parents[2] / "docs" / "bem.md").read_text()
    for family, (low, high) in validity.BEM_AGREEMENT_20.items():
        assert f"| {family} | {low:g} |" in doc, family


def test_elastic_contact_refuses_more_than_the_nominal_area():
    with pytest.raises(ValueError, match=r"A/A0 = 1\.42\d* > 1 at s = -5"):
        elastic_contact(TABLE1, [1.0, -5.0], E_STAR)
    with pytest.raises(ValueError, match="> 1"):
        elastic_contact(TABLE1, [-50.0], E_STAR, model="gw")
    c, w = _caught(elastic_contact, TABLE1, [-5.0], E_STAR, validity="warn")
    assert c.area_fraction[0] == pytest.approx(1.4268, rel=1e-4) and w
    c, w = _caught(elastic_contact, TABLE1, [-1.0, 2.0], E_STAR)
    assert {str(x.message).split(":")[0] for x in w} >= {"A/A0 = 0.422 at s = -1 exceeds 0.1"}
    c, w = _caught(elastic_contact, TABLE1, [1.5, 3.0], E_STAR)  # the printed table rows: quiet
    assert w == []


def test_elastoplastic_contact_and_sweeps():
    mat = AsperityMaterial(E_STAR, 2070.0)
    with pytest.raises(ValueError, match="> 1"):
        elastoplastic_contact(TABLE1, [-6.0], mat)
    _, w = _caught(elastoplastic_contact, TABLE1, [-0.5], mat)
    assert any("s = -0.5 < 0" in str(x.message) for x in w)
    # a sweep over the paper's figure range warns at its heavy corner instead of failing
    spec = SweepSpec(axes={"psi": [0.5]}, s=[-6.0, 2.0], fixed={**TABLE1.as_dict(), "E_star": E_STAR},
                     with_elastic=False)
    ds, w = _caught(run_sweep, spec)
    assert float(ds.area_fraction.max()) > 1.0 and any("> 1" in str(x.message) for x in w)
    with pytest.raises(ValueError, match="> 1"):
        run_sweep(SweepSpec(**{**spec.__dict__, "validity": "refuse"}))


def test_normal_law_table_refuses_pressures_past_full_contact():
    with pytest.raises(ValueError, match="> 1"):
        NormalLawTable.build(TABLE1, "elastic", E_star=E_STAR, pressure_range=(1e-3, 1e5))
    _, w = _caught(NormalLawTable.build, TABLE1, "elastic", E_star=E_STAR, pressure_range=(1e-3, 1e3))
    assert any("exceeds 0.1" in str(x.message) for x in w)
    _, w = _caught(NormalLawTable.build, TABLE1, "elastic", E_star=E_STAR, pressure_range=(1e-3, 10.0))
    assert w == []


def test_accuracy_warning_below_the_tested_bandwidth():
    """As alpha -> 2 (mu -> 0) the production quadrature degrades (2.8e-7 at mu = 1e-4): warned."""
    alpha = 2.0 / (1.0 - 1e-4)
    narrow = SpectralMoments(1.0, 1.0, 1.0, alpha, alpha)
    _, w = _caught(elastic_contact, narrow, [2.0], 1.0)
    assert len(w) == 1 and issubclass(w[0].category, AccuracyWarning) and "mu = 0.0001" in str(w[0].message)
    tested = SpectralMoments(1.0, 1.0, 1.0, 2.03, 2.03)  # mu = 0.0148 > MU_ACCURATE = 0.0099
    _, w = _caught(elastic_contact, tested, [2.0], 1.0)
    assert w == []
    _, w = _caught(elastic_contact, narrow, [2.0], 1.0, model="gw")  # closed form: no warning
    assert w == []
    assert validity.MU_ACCURATE == pytest.approx(1 - 2 / 2.02)
    assert dict(validity.MU_DEGRADATION)[1e-4] == 2.8e-7


# -- the m22 term against what the BEM comparison measured (issue 29) ----------------------------
def test_m22_effect_isotropic_summits_are_nayaks():
    """rho^2 = 1/9 (an elliptically stretched isotropic surface, the BEM's): the Gaussian surface
    has 2 pi/(3 sqrt 3) = 1.2092 times the summits of (17) (Nayak 1971: D = m4/(6 pi sqrt3 m2)
    against (17)'s m4/(4 pi^2 m2)) — inside the 1.18-1.24 the BEM maps had; no message."""
    from roughcontact.contact.validity import BEM_M22, m22_effect
    from roughcontact.statistics import SpectralMoments

    m = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    e = m22_effect(m, math.sqrt(m.m40 * m.m04) / 3.0)
    assert e["rho2"] == pytest.approx(1 / 9) and e["summit_ratio"] == pytest.approx(2 * math.pi / (3 * math.sqrt(3)), rel=1e-9)
    assert e["within_bem_measured"] is True and e["message"] is None
    assert BEM_M22["summit_ratio"][0] <= e["summit_ratio"] <= BEM_M22["summit_ratio"][1]
    assert m22_effect(m, 0.0)["summit_ratio"] == pytest.approx(1.0, rel=1e-9)


def test_m22_effect_of_a_ground_surface_states_the_bem_numbers():
    """rho^2 = 1/3 (a Gaussian spread of the lay angle): beyond the BEM's range, a message with the
    summit ratio, the BEM's measured area errors and the extrapolation 1 - 1/ratio; an uncertainty
    that reaches the BEM's rho^2 keeps it within."""
    from roughcontact.contact.validity import m22_effect
    from roughcontact.statistics import SpectralMoments

    m = SpectralMoments(0.01, 0.001, 0.01, 3e-4, 0.03)
    m22 = math.sqrt(m.m40 * m.m04 / 3.0)
    e = m22_effect(m, m22)
    assert e["within_bem_measured"] is False and 1.44 < e["summit_ratio"] < 1.47
    assert e["area_deficit_extrapolated"] == pytest.approx(1 - 1 / e["summit_ratio"])
    assert "8.9-20.3 %" in e["message"] and "docs/bem.md" in e["message"] and "1.18-1.24" in e["message"]
    assert m22_effect(m, m22, m22_uncertainty=0.25 * m22)["within_bem_measured"] is True
