"""Elastic contact of a rough surface with a rigid flat, per unit nominal area, vs separation.

Public entry points:

* :func:`elastic_contact` — real-area fraction A/A0 (52), pressure W/A0 (53) and normal
  stiffness K/A0 (55) of the Bush–Gibson–Keogh model (``model="bgk"``) or of McCool's
  equivalent Greenwood–Williamson model (``model="gw"``);
* :func:`bearing_area` / :func:`bearing_area_ratio` — A_G of (22)/(24) and A_G/A_B (Fig. 3).

Two integrators stand behind one interface: ``method="production"`` (numba,
integrals.production) and ``method="reference"`` (mpmath, integrals.reference). The
separation is s = h/√m00 (23).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from ..asperity import ellipse
from ..integrals.polar import ElasticPrefactors, PolarGeometry
from ..integrals.production import normal_moment, polar_elastic_integrals
from ..integrals.rules import settings_for, theta_rule
from ..statistics.gw import EquivalentGW
from ..statistics.surface import SpectralMoments, gaussian_bearing_area
from ..validation import choice, instance, integer, positive, separations
from .validity import VALIDITY_MODES, check_bandwidth, check_validity
from .units import attrs, check_units

__all__ = ["ContactCurves", "elastic_contact", "bearing_area", "bearing_area_ratio"]

MODELS = ("bgk", "gw")
HERTZ = ("exact", "paper")
METHODS = ("production", "reference")
#: the reference's working digits: at dps = 8 it is within 1.2e-9 of dps = 20 (Table 1 surface,
#: s = 1, 3; 2e-11 at dps = 10), still inside the "plot" preset's 1e-8 (benchmarks/speed_vs_error.py
#: times mpmath at 8, 12, 20); below, the error grows about tenfold per digit unchecked (7.5e-7 at
#: 5, 9e-2 at 0; mpmath takes any number, even negative); above 60 digits a run takes hours. The
#: workflow's references use 10 or more (config/schema.yaml reference_dps)
REFERENCE_DPS = (8, 60)
S_MAX_RATIO = 37.0  # ½ erfc(37/√2) ≈ 6e-300, the last s where A_B is a normal double


def _units(length="L", stress="unit of E*"):
    return {
        "s": "1 (h/sqrt(m00))",
        "area_fraction": "1 (A/A0)",
        "pressure": f"{stress} (W/A0)",
        "stiffness": f"{stress} per {length} (K/A0)",
    }


@dataclass(frozen=True)
class ContactCurves:
    """Contact per unit nominal area at the separations ``s``.

    area_fraction A/A0 [–]; pressure W/A0 [unit of E*]; stiffness K/A0 = −d(W/A0)/dh
    [unit of E* per length unit of the moments].
    """

    s: np.ndarray
    area_fraction: np.ndarray
    pressure: np.ndarray
    stiffness: np.ndarray
    model: str
    hertz: str | None
    method: str
    E_star: float
    surface: SpectralMoments
    units: dict = field(default_factory=_units)

    def to_dataset(self, units: Mapping[str, str] | None = None):
        """An xarray.Dataset over ``s`` with CF metadata and the model in the attributes.

        ``units`` = {"length": L, "stress": S} (UDUNITS strings, e.g. ``{"length": "um",
        "stress": "N/mm^2"}``) states the unit system of the inputs: the moments in L, E* in
        S; then W/A0 is in S and K/A0 in S/L. Without it W/A0 and K/A0 carry no ``units``
        attribute (the library cannot know them) and :func:`roughcontact.io.write_netcdf`
        refuses to store them.
        """
        import xarray as xr

        units = check_units(units)
        ds = xr.Dataset(
            {name: ("s", getattr(self, name), attrs(name, units)) for name in ("area_fraction", "pressure", "stiffness")},
            coords={"s": ("s", self.s, attrs("s", units))},
        )
        ds.attrs.update(
            model=self.model,
            hertz=str(self.hertz),
            method=self.method,
            E_star=self.E_star,
            **self.surface.as_dict(),
        )
        return ds


# ---------------------------------------------------------------------------------------
# θ-node data (cached per surface, Hertz option and accuracy)
# ---------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def _theta_nodes(surface: SpectralMoments, hertz: str, accuracy):
    """θ-nodes and the per-node weights (w_area, w_load, w_bearing, g) of docs/derivation.md."""
    settings = settings_for(accuracy)
    geom = PolarGeometry(surface)
    theta, w = theta_rule(geom.theta_breaks(hertz), settings)
    lam = np.sqrt(geom.lambda_squared(theta))
    factors = ellipse.hertz_factors(lam, hertz)
    cs = np.cos(theta) * np.sin(theta)
    c = geom.c(theta)
    w_area = w * cs * factors.f1 / c
    w_load = w * cs * factors.f2 / np.sqrt(c)
    w_bearing = w * np.sqrt(cs)
    return w_area, w_load, w_bearing, geom.g(theta)


# ---------------------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------------------
def elastic_contact(
    surface: SpectralMoments,
    s,
    E_star: float,
    *,
    model: str = "bgk",
    hertz: str = "exact",
    method: str = "production",
    accuracy="table",
    dps: int = 20,
    validity: str = "refuse",
) -> ContactCurves:
    """Elastic contact per unit nominal area at separations ``s`` = h/√m00.

    model    "bgk": Bush–Gibson–Keogh elliptic asperities, eqs. (52), (53), (55);
             "gw": McCool's equivalent Greenwood–Williamson model (Tables 1–2).
    hertz    "exact": exact Hertz functions, exact inversion of (27);
             "paper": the paper's numerics, (33) clipped + polynomials (36)–(39).
    method   "production" (numba) or "reference" (mpmath at ``dps`` digits, an integer in
             [8, 60]: :data:`REFERENCE_DPS`).
    accuracy production preset name ("table" ≤1e-13, "plot" ≤1e-8 relative to the mpmath
             reference; measured in docs/performance.md) — see integrals.rules.PRESETS.
             Below μ = validity.MU_ACCURATE the promise is not tested: AccuracyWarning.
    validity what to do outside the model's range (contact.validity.check_validity):
             "refuse" (ModelValidityWarning for s < 0 or A/A0 > 0.1, ValueError for
             A/A0 > 1), "warn" (warnings only), "off".
    """
    instance("surface", surface, SpectralMoments)
    s_arr = separations(s)
    E = positive("E_star", E_star)
    choice("model", model, MODELS)
    choice("hertz", hertz, HERTZ)
    choice("method", method, METHODS)
    choice("validity", validity, VALIDITY_MODES)
    dps = integer("dps", dps, *REFERENCE_DPS)
    if model == "bgk":
        check_bandwidth(surface.mu, method)

    if model == "gw":
        gw = EquivalentGW(surface)
        minus_d = -gw.standardised_separation(s_arr)
        if method == "production":
            F = normal_moment(minus_d)  # closed form (tables): no accuracy setting
        else:
            from ..integrals.reference_functions import normal_moments_reference

            F = normal_moments_reference(minus_d, dps=dps)
        area, load, stiff = gw.per_unit_area(F)
        hertz_used = None
    else:
        pre = ElasticPrefactors.of(surface)
        l_values = surface.l_from_s(s_arr)
        if method == "production":
            w_area, w_load, _, g = _theta_nodes(surface, hertz, accuracy)
            I = polar_elastic_integrals(l_values, w_area, w_load, g, accuracy)
            I_area, I_load, I_stiff = I[:, 0], I[:, 1], I[:, 2]
        else:
            from ..integrals.reference import elastic_integrals

            vals = [elastic_integrals(surface, float(l), hertz=hertz, dps=dps) for l in l_values]
            I_area, I_load, I_stiff = (
                np.array([float(v[q].value) for v in vals]) for q in ("area", "load", "stiffness")
            )
        area = pre.area * I_area
        load = pre.load * I_load
        stiff = pre.stiffness * I_stiff
        hertz_used = hertz
    area = np.asarray(area, dtype=float)
    check_validity(s_arr, area, mode=validity)
    return ContactCurves(
        s=s_arr,
        area_fraction=area,
        pressure=E * np.asarray(load, dtype=float),
        stiffness=E * np.asarray(stiff, dtype=float),
        model=model,
        hertz=hertz_used,
        method=method,
        E_star=E,
        surface=surface,
    )


def bearing_area(surface: SpectralMoments, s, *, method="production", accuracy="plot", dps=20):
    """A_G(s): summit-model bearing area fraction, eqs. (22)/(24) (D_sum·E[πab]); ``dps`` as in
    :func:`elastic_contact`."""
    instance("surface", surface, SpectralMoments)
    dps = integer("dps", dps, *REFERENCE_DPS)
    s_arr = separations(s)
    choice("method", method, METHODS)
    pre = ElasticPrefactors.of(surface)
    l_values = surface.l_from_s(s_arr)
    if method == "production":
        _, _, w_bearing, g = _theta_nodes(surface, "exact", accuracy)
        # the bearing integrand has the area's r- and t-parts: reuse that column
        I = polar_elastic_integrals(l_values, w_bearing, w_bearing, g, accuracy)[:, 0]
    else:
        from ..integrals.reference import elastic_integrals

        I = np.array(
            [
                float(elastic_integrals(surface, float(l), dps=dps, quantities=("bearing",))["bearing"].value)
                for l in l_values
            ]
        )
    return pre.bearing * I


def bearing_area_ratio(surface: SpectralMoments, s, *, method="production", accuracy="plot", dps=20):
    """A_G/A_B vs s (Fig. 3): summit-model bearing area over the Gaussian one (25).

    Defined for s ≤ 37: beyond, A_B = ½ erfc(s/√2) underflows double precision."""
    s_arr = separations(s)
    if np.any(s_arr > S_MAX_RATIO):
        raise ValueError(
            f"A_G/A_B is not representable for s > {S_MAX_RATIO} (A_B underflows double "
            f"precision); got s = {s_arr.max():g}"
        )
    return bearing_area(surface, s_arr, method=method, accuracy=accuracy, dps=dps) / gaussian_bearing_area(s_arr)
