"""The interface laws of a deck run: LAW.yaml, typed (docs/own-model.md).

One file gives the law of every ``*SURFACE INTERACTION`` of a deck by name::

    length_unit: mm            # the deck's length unit (m, mm, um, nm); forces in N, stresses N/mm^2
    interactions:
      ROUGH:                   # a *SURFACE INTERACTION name of the deck (case-insensitive)
        moments: {m00: 0.0625, m20: 8.0e-5, m02: 8.0e-4, m40: 1.04e-6, m04: 1.04e-4, unit: um}
        lay_direction: [1, 0, 0]       # the moments' x axis (along the lay) in the deck's axes
        E_star: 78065.86               # optional: else from the two bodies' *ELASTIC (eq. 42)
        law: elastic                   # or elastoplastic, with psi or yield_strength
        seating_pressure: 1.0e-3       # relative displacements are measured from this state
        friction: none                 # or {coulomb: {mu: 0.2, kt_over_kn: 0.7}}
                                       # or {orthotropic: {mu_m: 0.5, mu_o: 0.5, nu_x: 0.125, nu_y: 0.125,
                                       #     n_x: 275, n_y: 275, kt_over_kn: [0.7, 1.0]}}  (n in 1/length_unit)

Units: the deck's units are any consistent set (N, mm, N/mm²; or N, m, Pa): ``E_star``,
``seating_pressure``, ``yield_strength`` and ``pressure_range`` are in the deck's stress unit
(the unit of its *ELASTIC moduli), ``n_x``, ``n_y`` in 1/``length_unit``; the moments in their
own ``unit`` (converted to the deck's length by the ratio of the two units).

Beyond the issue's schema, optional keys: ``moments`` may be the path of a JSON file of
``roughcontact moments --json`` (m00 … m04 at its top level and its length unit in
``units.dx``; relative to the law file); ``mu_m``, ``mu_o`` and ``kt_over_kn`` take one value
or a pair (x, y); ``k`` (the potential's shape exponent, ν_y/ν_x = (μ_y/μ_x)^k) instead of
ν_x = ν_y (k = 0: a circular potential); ``friction: {stick: {kt_over_kn: a}}`` (tangential
springs without slip); ``tangential_form`` (interface.friction.TANGENTIAL_FORMS);
``pressure_range: [p_light, p_max]`` (the tabulated normal law's range; default
[1e-17, 0.1] × E*); ``stress_unit`` (the deck's stress unit, which must be N/``length_unit``²:
stating it lifts the deck run's plausibility range of E*, deck_run.check_law_file). Every key
with its unit: :data:`LAW_KEYS` and docs/own-model.md's table.

The BEM's law (issue 32): ``normal: {table: FILE}`` instead of ``law`` — FILE a load ladder
written by ``roughcontact bem ... --law-table`` (roughcontact.bem.law_table; relative to the law
file) — makes p_N(u_N), k_N(u_N) the BEM's (NormalLawTable.from_samples, level "bem"); its
pressure range is the ladder's, its lengths stay in the table's unit (converted to the deck's
as the moments' are), its pressures are converted from the table's ``stress_unit`` where it
states one, and its E* is the law's (a stated ``E_star`` must agree within UNIT_RTOL; the deck
run compares it with the bodies'). ``moments`` are then optional (default: the table's measured
ones). ``kt_over_kn: mindlin`` (any friction) is Mindlin's ratio (96) of the moments'
representative summit ellipse for the bodies' Poisson ratio (:func:`mindlin_poisson`): with a
BEM law k_T = ratio × k_N(BEM), the ratio being the statistical model's part.

The file is read through :mod:`roughcontact.limits` (a regular UTF-8 file within the size
limit) as plain YAML: anchors and aliases, a key given twice in a mapping and nesting beyond
the limit ``nesting`` are refused with the line(s); values are quoted in messages through
limits.describe.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from .. import limits
from ..interface import friction
from ..limits import describe
from ..statistics import SpectralMoments

__all__ = ["LENGTH_UNITS", "STRESS_UNITS", "LAW_KEYS", "LawError", "NoFriction", "Coulomb", "Stick", "Orthotropic", "InteractionLaw",
           "LawFile", "read_law_file", "law_file_from_dict", "DEFAULT_PRESSURE_RANGE"]

#: the length units: their power of ten in metres (unit = 10^k m), so that ratios are exact
LENGTH_UNITS = {"m": 0, "mm": -3, "um": -6, "µm": -6, "nm": -9}
#: the tabulated range of the normal law without ``pressure_range``, times E*
DEFAULT_PRESSURE_RANGE = (1e-17, 0.1)
#: the relative difference beyond which a stated unit or E* contradicts the deck's (issue 29)
UNIT_RTOL = 0.01
_MOMENTS = ("m00", "m20", "m02", "m40", "m04")
#: the optional ``stress_unit``: its size in Pa (N/m²); it must be N per ``length_unit`` squared
STRESS_UNITS = {"Pa": 1.0, "N/m^2": 1.0, "kPa": 1e3, "MPa": 1e6, "N/mm^2": 1e6, "GPa": 1e9, "N/um^2": 1e12,
                "N/µm^2": 1e12, "N/nm^2": 1e18}

# The keys the reader accepts, by their place in the file (``NAME`` an interaction's name):
# read by the functions below and listed, with their units, in docs/own-model.md's key table
# (tests/fe/test_law_file_audit.py checks that every one is there).
_TOP = {"required": ("length_unit", "interactions"), "optional": ("stress_unit",)}
_INTERACTION = {"required": ("lay_direction", "seating_pressure"),
                "optional": ("moments", "law", "normal", "E_star", "psi", "yield_strength", "friction", "pressure_range",
                             "tangential_form")}
#: the normal laws: the statistical model's (``law``) and a BEM table's (``normal: {table: FILE}``)
NORMAL_LAWS = ("elastic", "elastoplastic", "bem")
_FRICTION = {"coulomb": {"required": ("mu", "kt_over_kn"), "optional": ()},
             "stick": {"required": ("kt_over_kn",), "optional": ()},
             "orthotropic": {"required": ("mu_m", "mu_o", "n_x", "n_y", "kt_over_kn"), "optional": ("nu_x", "nu_y", "k")}}


def _law_keys() -> tuple[str, ...]:
    top = [*_TOP["required"], *_TOP["optional"]]
    inter = [f"interactions.NAME.{k}" for k in (*_INTERACTION["required"], *_INTERACTION["optional"])]
    moments = [f"interactions.NAME.moments.{k}" for k in (*_MOMENTS, "unit")]
    moments += ["interactions.NAME.normal.table"]  # bem_law
    fric = [f"interactions.NAME.friction.{kind}.{k}" for kind, keys in _FRICTION.items()
            for k in (*keys["required"], *keys["optional"])]
    return tuple(top + inter + moments + fric)


#: every key of a law file, as a dotted path (docs/own-model.md defines each with its unit)
LAW_KEYS = _law_keys()


class LawError(ValueError):
    """A law file that cannot be used: the message names the file and the key."""


def _fail(where: str, message: str):
    raise LawError(f"{where}: {message}")


def _named(value, choices) -> bool:
    """Whether ``value`` is one of the names ``choices`` (a list or a mapping from YAML is not a
    name: ``[0, 0, 1] in LENGTH_UNITS`` would raise TypeError, unhashable)."""
    return isinstance(value, str) and value in choices


def _number(value, where: str, *, positive=True, allow_zero=False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        _fail(where, f"must be a number, got {describe(value)}")
    x = float(value)
    if not math.isfinite(x) or (positive and not (x > 0 or (allow_zero and x == 0))):
        _fail(where, f"must be {'non-negative' if allow_zero else 'positive'} and finite, got {describe(value)}")
    return x


def _pair(value, where: str) -> tuple[float, float]:
    """One value for both axes, or a pair (x, y)."""
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            _fail(where, f"give one value or a pair [x, y], got {describe(value)}")
        return _number(value[0], f"{where}[0]"), _number(value[1], f"{where}[1]")
    x = _number(value, where)
    return x, x


def _kt(value, where: str):
    """kt_over_kn: one factor, a pair (x, y), or ``mindlin`` (resolved where ν is known)."""
    return "mindlin" if value == "mindlin" else _pair(value, where)


def _kt_yaml(value, fold=False):
    """kt_over_kn as written: ``mindlin``, a pair, or (``fold``) one value for equal ones."""
    if isinstance(value, str):
        return value
    return value[0] if fold and value[0] == value[1] else list(value)


def mindlin_poisson(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """The Poisson ratio ν of Mindlin's k_N/k_T (96) for two bodies of different materials:
    both compliances add (interface.tangential's derivation, per body δ_T ∝ [(1−ν)K + νX]/G and
    δ_N ∝ (1−ν)K/G), so k_N/k_T = 1 + (ν₁/G₁ + ν₂/G₂)/((1−ν₁)/G₁ + (1−ν₂)/G₂) · X/K, which is
    (96) with ν = (ν₁/G₁ + ν₂/G₂)/(1/G₁ + 1/G₂), G = E/(2(1 + ν)) (Johnson 1985, §7.2); ν₁ for
    equal materials."""
    c1, c2 = 2.0 * (1.0 + nu1) / E1, 2.0 * (1.0 + nu2) / E2  # 1/G
    return (nu1 * c1 + nu2 * c2) / (c1 + c2)


def _keys(d, where: str, required=(), optional=()) -> dict:
    if not isinstance(d, dict):
        _fail(where, f"must be a mapping, got {describe(d)}")
    for k in required:
        if k not in d:
            _fail(where, f"missing key {describe(k)}")
    extra = [k for k in d if k not in required and k not in optional]
    if extra:
        _fail(where, f"unknown key {describe(extra[0])} (expected {', '.join(list(required) + list(optional))})")
    return d


# ---------------------------------------------------------------------------------------------
# friction
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class NoFriction:
    """``friction: none``: free sliding (no tangential traction)."""

    def model(self, law_per_deck: float):
        return friction.Frictionless()

    def factors(self):
        return None  # k_T is not used

    def to_yaml(self):
        return "none"


@dataclass(frozen=True)
class Coulomb:
    """A constant Coulomb limit μ with tangential springs k_T = kt_over_kn·k_N (section 8.2 with μ_o = 1)."""

    mu: float
    kt_over_kn: tuple[float, float] | str  # or "mindlin"

    def model(self, law_per_deck: float):
        return friction.IsotropicHardening(mu_m=self.mu)

    def factors(self):
        return self.kt_over_kn

    def to_yaml(self):
        return {"coulomb": {"mu": self.mu, "kt_over_kn": _kt_yaml(self.kt_over_kn)}}


@dataclass(frozen=True)
class Stick:
    """Tangential springs k_T = kt_over_kn·k_N without a friction limit (friction.NoSlip)."""

    kt_over_kn: tuple[float, float] | str  # or "mindlin"

    def model(self, law_per_deck: float):
        return friction.NoSlip()

    def factors(self):
        return self.kt_over_kn

    def to_yaml(self):
        return {"stick": {"kt_over_kn": _kt_yaml(self.kt_over_kn)}}


@dataclass(frozen=True)
class Orthotropic:
    """The orthotropic slip-hardening law of section 8.1 (friction.OrthotropicHardening): μ_m, μ_o
    and n (1/deck length) per axis (x along the lay), the potential's exponent k, k_T/k_N per axis."""

    mu_m: tuple[float, float]
    mu_o: tuple[float, float]
    n: tuple[float, float]
    kt_over_kn: tuple[float, float] | str  # or "mindlin"
    k: float = 0.0
    nu: tuple[float, float] | None = None  # ν_x = ν_y as given (k = 0), kept for the file

    def model(self, law_per_deck: float):
        """n converted to the law's length unit (n per deck length / law units per deck length)."""
        return friction.OrthotropicHardening(self.mu_m[0], self.mu_m[1], self.mu_o[0], self.mu_o[1],
                                             self.n[0] / law_per_deck, self.n[1] / law_per_deck, k=self.k)

    def factors(self):
        return self.kt_over_kn

    def to_yaml(self):
        def one(pair):
            return pair[0] if pair[0] == pair[1] else list(pair)

        shape = {"nu_x": self.nu[0], "nu_y": self.nu[1]} if self.nu is not None else {"k": self.k}
        return {"orthotropic": {"mu_m": one(self.mu_m), "mu_o": one(self.mu_o), **shape, "n_x": self.n[0],
                                "n_y": self.n[1], "kt_over_kn": _kt_yaml(self.kt_over_kn, fold=True)}}


def _friction(value, where: str):
    if value in (None, "none"):
        return NoFriction()
    if not isinstance(value, dict) or len(value) != 1:
        _fail(where, f"must be none, {{coulomb: ...}}, {{orthotropic: ...}} or {{stick: ...}}, got {describe(value)}")
    (kind, body), = value.items()
    at = f"{where}.{kind}"
    if kind == "coulomb":
        d = _keys(body, at, **_FRICTION["coulomb"])
        return Coulomb(_number(d["mu"], f"{at}.mu"), _kt(d["kt_over_kn"], f"{at}.kt_over_kn"))
    if kind == "stick":
        d = _keys(body, at, **_FRICTION["stick"])
        return Stick(_kt(d["kt_over_kn"], f"{at}.kt_over_kn"))
    if kind == "orthotropic":
        d = _keys(body, at, **_FRICTION["orthotropic"])
        nu = None
        if "k" in d:
            if "nu_x" in d or "nu_y" in d:
                _fail(at, "give either k or nu_x = nu_y, not both")
            k = _number(d["k"], f"{at}.k", positive=False)
        else:
            if "nu_x" not in d or "nu_y" not in d:
                _fail(at, "give nu_x and nu_y (or the exponent k)")
            nu = (_number(d["nu_x"], f"{at}.nu_x"), _number(d["nu_y"], f"{at}.nu_y"))
            if nu[0] != nu[1]:
                _fail(at, f"nu_x = {nu[0]:g} != nu_y = {nu[1]:g}: the library's potential has nu_y/nu_x = "
                          "(mu_y/mu_x)^k (friction.OrthotropicHardening); give k instead")
            k = 0.0  # ν_x = ν_y: a circular potential (only the ratio matters)
        return Orthotropic(_pair(d["mu_m"], f"{at}.mu_m"), _pair(d["mu_o"], f"{at}.mu_o"),
                           (_number(d["n_x"], f"{at}.n_x", allow_zero=True),
                            _number(d["n_y"], f"{at}.n_y", allow_zero=True)),
                           _kt(d["kt_over_kn"], f"{at}.kt_over_kn"), k, nu)
    _fail(where, f"unknown friction {describe(kind)} (none, coulomb, orthotropic, stick)")


# ---------------------------------------------------------------------------------------------
# one interaction
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class InteractionLaw:
    """The law of one interaction (module docstring): surface moments in ``moments_unit``, the
    lay direction (deck axes), the normal law (``law``, ``psi`` or ``yield_strength``,
    ``E_star`` or None), the seating pressure, friction, the tabulated range and the reading
    of the tangential law (93). ``law == "bem"``: the normal law is ``table`` (a
    :class:`.bem_law.TableFile`; moments_unit its length unit, E_star its E*)."""

    moments: SpectralMoments
    moments_unit: str
    lay_direction: tuple[float, float, float]
    law: str
    seating_pressure: float
    friction: object = field(default_factory=NoFriction)
    E_star: float | None = None
    psi: float | None = None
    yield_strength: float | None = None
    pressure_range: tuple[float, float] | None = None
    tangential_form: str = "incremental-end"
    table: object = None  # a bem_law.TableFile

    def __post_init__(self):
        if not _named(self.moments_unit, LENGTH_UNITS):
            raise LawError(f"moments unit must be one of {', '.join(LENGTH_UNITS)}, got {describe(self.moments_unit)}")
        if not _named(self.law, NORMAL_LAWS):
            raise LawError(f"law must be elastic or elastoplastic, got {describe(self.law)}")
        if (self.law == "bem") != (self.table is not None):
            raise LawError("a BEM law (normal: {table: FILE}) takes its table, and only it")
        if self.law == "bem" and (self.psi, self.yield_strength, self.pressure_range) != (None, None, None):
            raise LawError("psi, yield_strength and pressure_range belong to law: elastic|elastoplastic (a BEM "
                           "table's range is its ladder's)")
        if self.law == "elastic" and (self.psi is not None or self.yield_strength is not None):
            raise LawError("psi and yield_strength belong to law: elastoplastic")
        if self.law == "elastoplastic" and (self.psi is None) == (self.yield_strength is None):
            raise LawError("law: elastoplastic needs exactly one of psi and yield_strength")
        if not _named(self.tangential_form, friction.TANGENTIAL_FORMS):
            raise LawError(f"tangential_form must be one of {', '.join(friction.TANGENTIAL_FORMS)}")

    def law_per_deck(self, length_unit: str) -> float:
        """Law (moments) length units per deck length unit, e.g. 1000 for µm moments in an mm deck."""
        return 10.0 ** (LENGTH_UNITS[length_unit] - LENGTH_UNITS[self.moments_unit])

    def material(self, length_unit: str, E_star: float, nu: float | None = None):
        """The engine's :class:`~.contact.InterfaceMaterial` (E_star: this law's, or the bodies';
        nu: the bodies' Poisson ratio for ``kt_over_kn: mindlin``, :func:`mindlin_poisson`);
        its table is built once per surface, law, E* and range in a process."""
        return _material(self, length_unit, float(E_star), nu)

    def to_yaml(self) -> dict:
        """The law as the mapping of the law file."""
        normal = {"law": self.law} if self.table is None else {"normal": {"table": self.table.file}}
        out = {"moments": {**{m: float(getattr(self.moments, m)) for m in _MOMENTS}, "unit": self.moments_unit},
               "lay_direction": list(self.lay_direction), **normal,
               "seating_pressure": self.seating_pressure, "friction": self.friction.to_yaml()}
        for key in ("E_star", "psi", "yield_strength"):
            if getattr(self, key) is not None:
                out[key] = getattr(self, key)
        if self.pressure_range is not None:
            out["pressure_range"] = list(self.pressure_range)
        if self.tangential_form != "incremental-end":
            out["tangential_form"] = self.tangential_form
        return out


@functools.lru_cache(maxsize=32)
def _table(moments, level: str, normal, pressure_range):
    """The tabulated normal law (interface.NormalLawTable, the FE accuracy "plot"), built once per
    surface, law, E* or material and range in a process (immutable; friction cases share it)."""
    from ..interface import NormalLawTable

    kw = {"E_star": normal} if level == "elastic" else {"material": normal}
    return NormalLawTable.build(moments, level, pressure_range=pressure_range, accuracy="plot", validity="off", **kw)


def _material(law: InteractionLaw, length_unit: str, E_star: float, nu=None):
    """:meth:`InteractionLaw.material`: the normal law tabulated and put in its reference state
    at the seating pressure, k_T = kt_over_kn · k_N (Mindlin's ratio (96) of the representative
    summit ellipse where the friction gives none: :func:`.contact.statistical_interface`'s rule)."""
    from ..contact import resolve_material

    if law.law == "bem":
        from .bem_law import bem_material

        return bem_material(law, length_unit, E_star, _tangential_factors(law, nu))
    if law.law == "elastic":
        normal = E_star
    else:
        by = {"psi": law.psi} if law.psi is not None else {"Y": law.yield_strength}
        normal = resolve_material(law.moments, E_star=E_star, **by)
    p_range = law.pressure_range or tuple(f * E_star for f in DEFAULT_PRESSURE_RANGE)
    if not p_range[0] < law.seating_pressure < p_range[1]:
        raise LawError(f"seating_pressure {law.seating_pressure:g} lies outside the tabulated pressures "
                       f"{p_range[0]:g} ... {p_range[1]:g} (E* = {E_star:g}): check the stress unit, or give "
                       "pressure_range")
    try:
        table = _table(law.moments, law.law, normal, tuple(p_range))
    except (RuntimeError, ValueError) as exc:  # a pressure of the range out of the model's reach (ValueError since issue 22)
        raise LawError(f"the normal law cannot be tabulated over the pressures {p_range[0]:g} ... {p_range[1]:g} "
                       f"with E* = {E_star:g} ({exc}): check E_star and the stress unit, or give a "
                       "pressure_range the law reaches") from None
    return _interface_material(law, length_unit, table, _tangential_factors(law, nu))


def _tangential_factors(law: InteractionLaw, nu):
    """(k_Tx/k_N, k_Ty/k_N): the friction's factors, or Mindlin's ratio (96) of the representative
    summit ellipse (interface.tangential.representative_aspect) for ``kt_over_kn: mindlin`` (with
    the bodies' ν) and where the friction gives none (ν = 1/4: k_T is not used then)."""
    from ..interface import mindlin_kT_over_kN
    from ..interface.tangential import representative_aspect

    factors = law.friction.factors()
    if factors == "mindlin":
        if nu is None:
            raise LawError("kt_over_kn: mindlin needs the bodies' Poisson ratio: put each contact surface on one "
                           "material of the deck, or give the factor")
        return mindlin_kT_over_kN(representative_aspect(law.moments), nu)
    return factors or mindlin_kT_over_kN(representative_aspect(law.moments), 0.25)


def _interface_material(law: InteractionLaw, length_unit: str, table, factors):
    from ..interface import InterfaceLaw
    from .contact import InterfaceMaterial

    per = law.law_per_deck(length_unit)
    return InterfaceMaterial(InterfaceLaw.from_pressure(table, law.seating_pressure, factors),
                             law.friction.model(per), length_per_mm=per, tangential_form=law.tangential_form)


def _moments(value, where: str, base: Path | None):
    if isinstance(value, str):  # a `roughcontact moments --json` file
        path = (base / value) if base is not None else Path(value)
        try:
            data = limits.parse_json(limits.read_text(path, "moments file"), f"moments file {path}")
        except ValueError as exc:  # not a regular file, too large, not UTF-8, not JSON, nested too deep
            _fail(where, str(exc))
        unit = (data.get("units") or {}).get("dx") if isinstance(data, dict) else None
        value = {**{m: data.get(m) for m in _MOMENTS}, "unit": unit}
        if unit in (None, "L"):
            _fail(where, f"{path} does not state its length unit (run `roughcontact moments --length-unit um ...`)")
    d = _keys(value, where, (*_MOMENTS, "unit"))
    unit = d["unit"]
    if not _named(unit, LENGTH_UNITS):
        _fail(f"{where}.unit", f"must be one of {', '.join(LENGTH_UNITS)}, got {describe(unit)}")
    values = {m: _number(d[m], f"{where}.{m}", positive=False) for m in _MOMENTS}
    try:
        return SpectralMoments(**values), unit
    except (ValueError, TypeError) as exc:
        _fail(where, f"invalid moments: {exc}")


def _interaction(d, where: str, base: Path | None, length_unit: str = "mm") -> InteractionLaw:
    d = _keys(d, where, **_INTERACTION)
    if ("law" in d) == ("normal" in d):
        _fail(where, "give law: elastic|elastoplastic (with moments) or normal: {table: FILE} (a BEM law), one of them")
    if "law" in d and "moments" not in d:
        _fail(where, "missing key 'moments'")
    moments = _moments(d["moments"], f"{where}.moments", base) if "moments" in d else None
    table = None
    if "normal" in d:
        from .bem_law import bem_table

        table, surface, unit, E_table = bem_table(d["normal"], f"{where}.normal", base, length_unit, moments)
        moments = (surface, unit)
    moments, unit = moments
    lay = d["lay_direction"]
    if not isinstance(lay, (list, tuple)) or len(lay) != 3:
        _fail(f"{where}.lay_direction", f"must be a vector [x, y, z], got {describe(lay)}")
    lay = tuple(_number(v, f"{where}.lay_direction", positive=False) for v in lay)
    if math.hypot(*lay) == 0.0:
        _fail(f"{where}.lay_direction", "must not be zero")
    opt = {}
    for key in ("E_star", "psi", "yield_strength"):
        if d.get(key) is not None:
            opt[key] = _number(d[key], f"{where}.{key}")
    if d.get("pressure_range") is not None:
        pr = d["pressure_range"]
        if not isinstance(pr, (list, tuple)) or len(pr) != 2:
            _fail(f"{where}.pressure_range", f"must be [p_light, p_max], got {describe(pr)}")
        lo, hi = (_number(v, f"{where}.pressure_range") for v in pr)
        if not lo < hi:
            _fail(f"{where}.pressure_range", f"needs p_light < p_max, got {describe(pr)}")
        opt["pressure_range"] = (lo, hi)
    if "tangential_form" in d:
        opt["tangential_form"] = d["tangential_form"]
    if table is not None:
        if "E_star" in opt and abs(opt["E_star"] / E_table - 1.0) > UNIT_RTOL:
            _fail(f"{where}.E_star", f"{opt['E_star']:g} differs from the BEM table's E* = {E_table:g} ({table.file}, "
                                     f"in the deck's stress unit) by more than {100 * UNIT_RTOL:g} %")
        opt.update(E_star=E_table, table=table)
    try:
        return InteractionLaw(moments, unit, lay, d.get("law", "bem"),
                              _number(d["seating_pressure"], f"{where}.seating_pressure"),
                              _friction(d.get("friction", "none"), f"{where}.friction"), **opt)
    except LawError as exc:
        if str(exc).startswith(where):
            raise
        _fail(where, str(exc))


# ---------------------------------------------------------------------------------------------
# the file
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class LawFile:
    """A law file: the deck's length unit, the law of every interaction (upper-case names), the
    deck's stress unit where the file states it (``stress_unit``, else None: N per
    ``length_unit`` squared) and where it was read from (``where``, for messages)."""

    length_unit: str
    interactions: dict[str, InteractionLaw]
    stress_unit: str | None = None
    where: str = field(default="law file", compare=False)

    def __post_init__(self):
        if not _named(self.length_unit, LENGTH_UNITS):
            raise LawError(f"length_unit must be one of {', '.join(LENGTH_UNITS)}, got {describe(self.length_unit)}")
        if self.stress_unit is not None and not _named(self.stress_unit, STRESS_UNITS):
            raise LawError(f"stress_unit must be one of {', '.join(STRESS_UNITS)}, got {describe(self.stress_unit)}")

    @property
    def pascal_per_stress_unit(self) -> float:
        """Pa per deck stress unit: N / length_unit² (forces in N), e.g. 10⁶ for mm."""
        return 10.0 ** (-2 * LENGTH_UNITS[self.length_unit])

    def to_yaml(self) -> str:
        import yaml

        data = {"length_unit": self.length_unit, **({"stress_unit": self.stress_unit} if self.stress_unit else {}),
                "interactions": {name: law.to_yaml() for name, law in self.interactions.items()}}
        return yaml.safe_dump(data, sort_keys=False, default_flow_style=None)


def law_file_from_dict(data, where: str = "law file", base: Path | None = None) -> LawFile:
    """A :class:`LawFile` from the parsed mapping (module docstring); LawError naming the key."""
    d = _keys(data, where, **_TOP)
    if not _named(d["length_unit"], LENGTH_UNITS):
        _fail(f"{where}: length_unit", f"must be one of {', '.join(LENGTH_UNITS)}, got {describe(d['length_unit'])}")
    stress_unit = d.get("stress_unit")
    if stress_unit is not None:
        if not _named(stress_unit, STRESS_UNITS):
            _fail(f"{where}: stress_unit", f"must be one of {', '.join(STRESS_UNITS)}, got {describe(stress_unit)}")
        # forces in N: the stress unit is N/length_unit²; a stated one that differs contradicts it
        implied = 10.0 ** (-2 * LENGTH_UNITS[d["length_unit"]])
        if abs(STRESS_UNITS[stress_unit] / implied - 1.0) > UNIT_RTOL:
            _fail(f"{where}: stress_unit", f"{stress_unit} = {STRESS_UNITS[stress_unit]:g} Pa contradicts "
                  f"length_unit {d['length_unit']}, whose stresses (forces in N) are N/{d['length_unit']}^2 = "
                  f"{implied:g} Pa: correct one of them")
    inter = d["interactions"]
    if not isinstance(inter, dict) or not inter:
        _fail(f"{where}: interactions", "must map at least one interaction name to its law")
    laws = {}
    for name, body in inter.items():
        key = str(name).upper()
        if key in laws:
            _fail(f"{where}: interactions", f"{describe(name)} is given twice (names are case-insensitive)")
        laws[key] = _interaction(body, f"{where}: interactions.{name}", base, d["length_unit"])
    return LawFile(d["length_unit"], laws, stress_unit, where)


def _loader(path: Path):
    """A yaml.SafeLoader class for one law file that refuses what YAML allows but a law file
    does not need and that would make the reader's memory or depth unbounded: anchors and
    aliases (a 1 KB "billion laughs" expands to gigabytes), nesting beyond the limit
    ``nesting`` (limits.LIMITS; the composer recurses, a 50 000-deep file would end in
    RecursionError), and a key given twice in one mapping (YAML keeps the last silently)."""
    import yaml

    depth_limit = limits.max_count("nesting")

    class Loader(yaml.SafeLoader):
        _depth = 0

        def compose_node(self, parent, index):
            event = self.peek_event()
            line = event.start_mark.line + 1
            if isinstance(event, yaml.AliasEvent) or getattr(event, "anchor", None) is not None:
                kind = "an alias *" if isinstance(event, yaml.AliasEvent) else "an anchor &"
                raise LawError(f"{path}: line {line}: {kind}{describe(event.anchor)[1:-1]}: YAML anchors and "
                               "aliases are not read in a law file (write each value out)")
            self._depth += 1
            try:
                if self._depth > depth_limit:
                    raise limits.InputLimitError(
                        f"{path}: line {line}: nested deeper than {depth_limit} levels ({limits.LIMITS['nesting'][0]} "
                        "raises the limit)")
                return super().compose_node(parent, index)
            finally:
                self._depth -= 1

        def construct_mapping(self, node, deep=False):
            seen = {}
            for key_node, _ in node.value:
                try:
                    key = self.construct_object(key_node, deep=True)
                    hash(key)
                except TypeError:
                    continue  # an unhashable key: SafeConstructor says so itself
                if key in seen:
                    raise LawError(f"{path}: key {describe(key)} is given twice in one mapping (lines {seen[key]} "
                                   f"and {key_node.start_mark.line + 1}): YAML would keep the last silently")
                seen[key] = key_node.start_mark.line + 1
            return super().construct_mapping(node, deep)

    return Loader


def read_law_file(path) -> LawFile:
    """Read LAW.yaml (module docstring): a regular UTF-8 file within the input size limit
    (limits.read_text), without YAML anchors/aliases, repeated keys or nesting beyond the
    limit ``nesting``; every problem one LawError naming the file (and the line or key)."""
    import yaml

    path = Path(path)
    try:
        text = limits.read_text(path, "law file")
    except ValueError as exc:  # missing, a FIFO or device, too large, not UTF-8
        raise LawError(f"cannot read the {exc}") from None
    loader = _loader(path)(text)
    try:
        data = loader.get_single_data()
    except yaml.YAMLError as exc:
        raise LawError(f"{path}: not YAML: {' '.join(str(exc).split())}") from None
    except RecursionError:  # a recursion the depth check above does not see (the constructor's)
        raise limits.InputLimitError(f"{path}: nested too deeply ({limits.LIMITS['nesting'][0]} bounds the "
                                     "nesting)") from None
    finally:
        loader.dispose()
    return law_file_from_dict(data, str(path), path.parent)
