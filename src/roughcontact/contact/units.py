"""CF metadata of the contact results: UDUNITS units from a stated unit system, long names.

The library is unit-agnostic: lengths in one unit L (the moments' unit), E* in any stress
unit S. A result only knows its units when the user states them, ``units={"length": "um",
"stress": "N/mm^2"}`` (UDUNITS strings, as in ``config/config.yaml``). Without them the
dimensional variables carry no ``units`` attribute (their ``long_name`` says "in the unit of
E*"), so :func:`roughcontact.io.write_netcdf` refuses to store them: a file never claims a
unit nobody stated. Dimensionless quantities are ``"1"`` (CF). Meanings go in ``long_name``,
never in ``units``.
"""

from __future__ import annotations

from typing import Mapping

__all__ = ["LONG_NAMES", "PARAMETER_LONG_NAMES", "quantity_units", "parameter_units", "attrs", "check_units"]

#: long_name of each contact quantity (the equation it evaluates)
LONG_NAMES = {
    "s": "separation s = h/sqrt(m00) of the mean planes, eq. (23)",
    "area_fraction": "real contact area fraction A/A0, eq. (52) (elastic) / (78) (elasto-plastic)",
    "pressure": "nominal pressure W/A0, eq. (53) (elastic) / (82) (elasto-plastic)",
    "stiffness": "normal stiffness per nominal area K/A0 = -d(W/A0)/dh, eq. (55) (Leibniz form, not (88))",
    "stiffness_jump": "part of K/A0 due to a load jump at first yield",
    "elastic_area_fraction": "A^e/A0, eq. (79)",
    "elastoplastic_area_fraction": "A^ep/A0, eq. (80)",
    "plastic_area_fraction": "A^p/A0, eq. (81)",
    "elastic_pressure": "W^e/A0, eq. (83)",
    "elastoplastic_pressure": "W^ep/A0, eq. (84)",
    "plastic_pressure": "W^p/A0, eq. (85)",
    "elastic_model_area_fraction": "A/A0 of the purely elastic model, eq. (52)",
    "elastic_model_pressure": "W/A0 of the purely elastic model, eq. (53)",
    "elastic_model_stiffness": "K/A0 of the purely elastic model, eq. (55)",
}

#: long_name of each sweepable parameter (a sweep's coordinates)
PARAMETER_LONG_NAMES = {
    "m00": "spectral moment m00 (variance of the heights), eq. (3)",
    "m20": "spectral moment m20 (variance of the slopes along x), eq. (3)",
    "m02": "spectral moment m02 (variance of the slopes along y), eq. (3)",
    "m40": "spectral moment m40 (variance of the curvatures along x), eq. (3)",
    "m04": "spectral moment m04 (variance of the curvatures along y), eq. (3)",
    "psi": "plasticity index psi, eq. (74)",
    "Y": "yield strength Y",
    "E_star": "effective elastic modulus E*, eq. (42)",
    "c_h": "hardness coefficient c_h = H/Y, eq. (66)",
    "wp_over_wc": "interference ratio omega_p/omega_c of full plasticity",
    "yield_coefficient": "yield coefficient K_Y of the first yield, eq. (63)",
    "H": "hardness H, eq. (68)",
    "K_v": "hardness factor K_v of eq. (75)",
}

_DIMENSIONLESS = ("s", "area_fraction", "elastic_area_fraction", "elastoplastic_area_fraction",
                  "plastic_area_fraction", "elastic_model_area_fraction")


def quantity_units(units: Mapping[str, str] | None) -> dict[str, str | None]:
    """UDUNITS units of each quantity of :data:`LONG_NAMES` in the unit system ``units``
    ({"length": L, "stress": S}); ``None`` where a unit depends on a system not stated."""
    length = stress = None
    if units is not None:
        length, stress = units.get("length"), units.get("stress")
    out: dict[str, str | None] = {}
    for name in LONG_NAMES:
        if name in _DIMENSIONLESS:
            out[name] = "1"
        elif "stiffness" in name:
            out[name] = f"{stress}/{length}" if stress and length else None
        else:
            out[name] = stress
    return out


def parameter_units(length: str, stress: str) -> dict[str, str]:
    """Units of the sweepable parameters (and of H, K_v) for the given length and stress units."""
    return {
        "m00": f"{length}^2", "m20": "1", "m02": "1", "m40": f"{length}^-2", "m04": f"{length}^-2",
        "psi": "1", "Y": stress, "E_star": stress, "c_h": "1", "wp_over_wc": "1",
        "yield_coefficient": "1", "H": stress, "K_v": "1",
    }


def attrs(name: str, units: Mapping[str, str] | None) -> dict[str, str]:
    """``{"units": ..., "long_name": ...}`` of quantity ``name``; without a stated unit system the
    long name says the unit in words and ``units`` is absent."""
    unit = quantity_units(units)[name]
    long_name = LONG_NAMES[name]
    if unit is None:
        return {"long_name": long_name + (" (in the unit of E* per length unit of the moments)"
                                          if "stiffness" in name else " (in the unit of E*)")}
    return {"units": unit, "long_name": long_name}


def check_units(units: Mapping[str, str] | None) -> Mapping[str, str] | None:
    """``units`` if it is None or names ``length`` and ``stress`` (non-empty strings), else
    ValueError naming what is missing."""
    if units is None:
        return None
    missing = [k for k in ("length", "stress") if not isinstance(units.get(k), str) or not units.get(k).strip()]
    if missing:
        raise ValueError(f"units must give 'length' and 'stress' as UDUNITS strings (e.g. 'um', 'N/mm^2'); "
                         f"missing: {', '.join(missing)}")
    return units
