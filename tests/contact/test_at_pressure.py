"""contact_at_pressure against the separation route: solving W(s)/A0 = p and evaluating at the
solution reproduces the separation and every field of the separation route."""

import warnings

import numpy as np
import pytest

from roughcontact.contact import at_pressure, elastic_contact, elastoplastic_contact, resolve_material
from roughcontact.contact.at_pressure import contact_at_pressure
from roughcontact.statistics import SpectralMoments

TABLE1 = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)  # µm
E_STAR = 1.14e5  # N/mm²
S = np.array([-0.5, 0.3, 1.0, 2.0, 3.5, 5.0])


@pytest.mark.parametrize("model", ["bgk", "gw"])
def test_elastic_inverts_the_separation_route(model):
    with warnings.catch_warnings(record=True) as direct_warnings:
        warnings.simplefilter("always")
        direct = elastic_contact(TABLE1, S, E_STAR, model=model)
    with pytest.warns(UserWarning):
        r = contact_at_pressure(TABLE1, direct.pressure, E_star=E_STAR, model=model)
    np.testing.assert_allclose(r.s, S, rtol=0, atol=1e-9)  # |dW/W| = 1e-10 -> ds ~ 1e-10/(slope)
    np.testing.assert_allclose(r.h, S * TABLE1.height_std, rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.curves.pressure, direct.pressure, rtol=1e-10)
    np.testing.assert_allclose(r.area_fraction, direct.area_fraction, rtol=1e-8)
    np.testing.assert_allclose(r.stiffness, direct.stiffness, rtol=1e-8)
    # the warnings of the solution are those of the separation route (s = -0.5 < 0, A/A0 > 0.1),
    # none from the Newton iterates
    assert set(r.warnings) == {f"{w.category.__name__}: {w.message}" for w in direct_warnings}


def test_elastoplastic_inverts_the_separation_route():
    material = resolve_material(TABLE1, E_star=E_STAR, psi=1.5)
    s = np.array([0.0, 1.0, 2.5])
    direct = elastoplastic_contact(TABLE1, s, material)
    r = contact_at_pressure(TABLE1, direct.pressure, material=material)
    np.testing.assert_allclose(r.s, s, rtol=0, atol=1e-9)
    for name in ("area_fraction", "stiffness", "plastic_area_fraction", "elastoplastic_pressure"):
        np.testing.assert_allclose(getattr(r.curves, name), getattr(direct, name), rtol=1e-8, atol=1e-300)


def test_warnings_are_recorded_and_relayed(monkeypatch):
    real = at_pressure.elastic_contact

    def warns(*args, **kwargs):
        warnings.warn("outside the validity of the asperity model (test)", UserWarning)
        return real(*args, **kwargs)

    monkeypatch.setattr(at_pressure, "elastic_contact", warns)
    with pytest.warns(UserWarning, match="validity"):
        r = contact_at_pressure(TABLE1, 10.0, E_star=E_STAR)
    assert r.warnings == ("UserWarning: outside the validity of the asperity model (test)",)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"p": -1.0, "E_star": E_STAR}, "positive"),
        ({"p": [1.0, float("nan")], "E_star": E_STAR}, "positive and finite"),
        ({"p": 1.0}, "exactly one"),
        ({"p": 1.0, "E_star": E_STAR, "rtol": 0.5}, "rtol"),
        ({"p": 1e-320, "E_star": E_STAR}, "no separation"),
    ],
)
def test_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        contact_at_pressure(TABLE1, **kwargs)
