"""Elasto-plastic contact of a rough surface with a rigid flat, per unit nominal area.

Sections 5–7 of Buczkowski & Kleiber (2009), eqs. (78)–(85), with the corrections of
docs/errata.md (E12–E17). Public entry point: :func:`elastoplastic_contact`.

The integrals
-------------
In the polar variables of docs/derivation.md (θ, r, t; ω = t √(m00 μ) the interference,
κ_m = r c(θ), summit measure cos θ sin θ · r³ e^{−r²/2} φ(t + l − r g(θ)) dt dr dθ):

    A/A0 = D_sum ∫∫∫ A_i(ω, κ_m, e) · (measure)          (78)–(81)
    W/A0 = D_sum ∫∫∫ W_i(ω, κ_m, e) · (measure)          (82)–(85)
    K/A0 = D_sum ∫∫∫ dW_i/dω · (measure) [+ jump term]   (replaces (88), errata E17)

with the per-asperity law A_i, W_i, dW_i/dω of :func:`roughcontact.asperity.respond`
(elastic ω ≤ ω_c, elasto-plastic ω_c < ω < ω_p, plastic ω ≥ ω_p). The parts A^e, A^ep, A^p
(and W^e, W^ep, W^p) are the same integrals restricted to one regime — the t-ranges
[0, t_c], (t_c, t_p), [t_p, ∞) of (79)–(81), (83)–(85). The ellipse factors f1, f2, f3 and
K(e)E(e) depend on θ only, so ω_c = K E (K_Y Y/E*)²/κ_m (65) is, in t units,
t_c(θ, r) = tc1(θ)/r with tc1 = ω_c(θ, κ_m = c(θ))/√(m00 μ) computed at the θ-nodes by
:func:`roughcontact.asperity.critical_interference`; t_p = (ω_p/ω_c) t_c.

K = −dW/dh: W(h) = D_sum ∫ W_i(ξ1 − h) p_sum over ξ1 > h; the lower limit contributes
W_i(0) = 0, so −dW/dh = D_sum ∫ dW_i/dω p_sum + (load jumps). With the default continuous
K_v = K_Y Y/H the per-asperity load is continuous and the jump term vanishes. With the
paper's K_v = 0.454 + 0.41ν (``AsperityMaterial.with_paper_K_v``) the load jumps at ω_c by
J = A_i(ω_c)·(2/3)(K_v H − K_Y Y) (errata E15), and −dW/dh gains
(D_sum/√(m00 μ)) ∫∫ J φ(t_c + l − r g) cs r³ e^{−r²/2} dr dθ, the density of summits sitting
exactly at first yield times the jump; it is included in ``stiffness`` (and reported
separately as ``stiffness_jump``), so ``stiffness`` is −dW/dh in both cases.

Integrators
-----------
``method="production"``: numba (integrals.kernels, the τ = r t route, docs/performance.md). In
τ = r t the regime boundaries are τ = t_c1 and (ω_p/ω_c) t_c1 and the law depends on τ alone
(times powers of r), so every column is ∫ F(τ) G_k(τ) dτ with G_k(τ) the summit measure on the
hyperbola r t = τ, which depends on θ only through g(θ). Per separation G_k is computed once
on a grid (Chebyshev nodes in g over the θ-nodes' range × panels in ln τ; trapezoidal rule in
ln r) and ln G_k interpolated; each θ-node then integrates its regime pieces in ln τ
(Gauss–Legendre) with the law evaluated there only. θ: nested tanh-sinh levels, added until the
estimated θ-error is below the preset's tolerance (integrals.rules.ELASTOPLASTIC_PRESETS).
Separations run in parallel; a single one splits its grid and θ-nodes over the threads.
That is ``route="tau"``. ``route="table"`` (integrals.summit_table, issue 33): per material one
table of ρ(y), y = g r − t, built once (~70 τ-route separations at "plot") and cached; every
separation is then a Gaussian convolution over it (~40–60 µs). ``route="auto"`` (the default)
takes the table where it is cached or where the call's τ-route cost reaches the build
(:func:`_auto_tables`, measured break-even in the constants below), else τ.
``method="reference"``: the slow twin
(:func:`roughcontact.integrals.reference_elastoplastic.reference_integrals`) — scipy
``integrate.cubature`` (adaptive Gauss–Kronrod 21) over θ (polynomially mapped to flatten
the end-point singularities) and, nested, over r; the inner t-integral by Gauss–Legendre
in u = √t on the regime pieces, with the law and its regime taken from asperity.respond
itself. Seconds per separation; used by the tests.
"""

from __future__ import annotations

import functools
import math
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import ClassVar, Mapping

import numpy as np

from ..asperity import AsperityMaterial, critical_interference, ellipse, plasticity_index
from ..integrals.polar import PolarGeometry
from ..integrals.production import polar_elastoplastic_integrals
from ..integrals.reference_elastoplastic import reference_integrals
from ..integrals.rules import elastoplastic_settings_for, nested_theta_rule
from ..integrals.summit_table import build_table, build_tables, shared_scale
from ..statistics.surface import SpectralMoments
from ..validation import choice, instance, separations
from .validity import VALIDITY_MODES, check_bandwidth, check_validity
from .units import attrs, check_units
from .s_interpolation import SInterpolation, interpolated_columns_many

__all__ = ["ElastoPlasticCurves", "elastoplastic_contact", "elastoplastic_contact_many", "clear_table_cache",
           "table_cache_bytes"]

HERTZ = ("exact", "paper")
METHODS = ("production", "reference")
#: production routes: "auto" (the default: "table" or "tau" per material by the rule of
#: :func:`_auto_tables`), "tau" (the τ = r t kernel, per separation) and "table" (one summit table
#: per material, integrals.summit_table; each separation a Gaussian convolution over it; the
#: materials of one call built together by the shared build, summit_table.build_tables)
ROUTES = ("auto", "tau", "table")
#: materials built together by the shared build (summit_table.build_tables) from this many on:
#: measured on Table 1 ("plot", load ~13), one shared build costs ~3 per-material builds for 1
#: material, ~4 for 5, ~8 for 50 (the y-panels of more materials refine more)
SHARED_MIN = 4
#: the in-process table cache (least recently used first): bounded by the tables' bytes
#: (SummitTable.nbytes; a Table 1 table at "plot" is 19 kB (238 convolution nodes), so ~3500
#: tables: a 50 × 50 sweep's 2500 fit; a table larger than the bound alone is used by its call
#: and not kept)
TABLE_CACHE_BYTES = 64 * 2**20
_TABLES: OrderedDict = OrderedDict()

# The rule of route="auto" (_auto_tables), in units of one τ-route separation of one material
# (measured with benchmarks/ep_cost.py's set-up, which prints these ratios again: Table 1, ψ = 0.05,
# 1, 50, s = 1, medians, load average 1.8–2.8 on 2 shared cores, 2026-11-28):
#   τ route, one material, n separations: 1.4–1.8 ms each at "plot" (3.4–4.4 ms at "table");
#     with interpolate_s and n ≥ 48 the curve costs 33 evaluations whatever n (56 ms "plot",
#     130 ms "table": contact.s_interpolation verified on its 32-interval grid);
#   τ route, k materials per separation: 1, 1.6, 3.8, 4.6, 8.5, 31 single-material costs for
#     k = 1, 2, 4, 8, 16, 50 (the hyperbola integrals shared): ≈ 0.4 + 0.6 k;
#   the cold build of one material's table: 59, 99, 125 ms at "plot" = 62, 70, 59 τ separations
#     (ψ = 0.05, 1, 50); 173, 352, 311 ms at "table" = 57, 88, 62;
#   the shared build of k ≥ SHARED_MIN materials: 266, 278, 387, 525 ms for k = 4, 8, 16, 50 at
#     "plot" = 2.7, 2.8, 3.9, 5.3 single-material builds: ≈ 2.5 + 0.06 k.
#: a cold single-material table build, in τ-route separations of that material
BUILD_IN_TAU_SEPARATIONS = {"plot": 70.0, "table": 80.0}
BUILD_IN_TAU_SEPARATIONS_OTHER = 80.0
#: model evaluations of a τ-route curve built by s-interpolation (n ≥ S_INTERPOLATION_MIN)
S_INTERPOLATION_EVALUATIONS = 33
S_INTERPOLATION_MIN = 48
_PARTS = ("elastic", "elastoplastic", "plastic")


def _units(length="L", stress="unit of E*"):
    u = {
        "s": "1 (h/sqrt(m00))",
        "area_fraction": "1 (A/A0)",
        "pressure": f"{stress} (W/A0)",
        "stiffness": f"{stress} per {length} (K/A0 = -d(W/A0)/dh)",
        "stiffness_jump": f"{stress} per {length} (load-jump part of K/A0)",
    }
    for p in _PARTS:
        u[f"{p}_area_fraction"] = f"1 (A^{p}/A0)"
        u[f"{p}_pressure"] = f"{stress} (W^{p}/A0)"
    return u


@dataclass(frozen=True)
class ElastoPlasticCurves:
    """Elasto-plastic contact per unit nominal area at the separations ``s`` = h/√m00.

    area_fraction A/A0 [–] (78); pressure W/A0 [unit of E*] (82); stiffness K/A0 = −d(W/A0)/dh
    [unit of E* per length unit of the moments]; the regime parts elastic_*, elastoplastic_*,
    plastic_* (79)–(81), (83)–(85) sum to the totals; stiffness_jump is the part of K due to
    a load jump at ω_c (0 unless K_v ≠ K_Y Y/H). ``psi`` is asperity.plasticity_index.
    """

    s: np.ndarray
    area_fraction: np.ndarray
    pressure: np.ndarray
    stiffness: np.ndarray
    elastic_area_fraction: np.ndarray
    elastoplastic_area_fraction: np.ndarray
    plastic_area_fraction: np.ndarray
    elastic_pressure: np.ndarray
    elastoplastic_pressure: np.ndarray
    plastic_pressure: np.ndarray
    stiffness_jump: np.ndarray
    hertz: str
    method: str
    material: AsperityMaterial
    surface: SpectralMoments
    psi: float
    units: dict = field(default_factory=_units)
    #: how the curve was obtained over s (contact.s_interpolation; None: direct)
    interpolation: SInterpolation | None = None
    #: the production route taken ("tau" | "table"; None: method "reference")
    route: str | None = None

    @property
    def mean_real_pressure(self) -> np.ndarray:
        """W/A [unit of E*] (nan where A = 0)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.pressure / self.area_fraction

    @property
    def plastic_area_ratio(self) -> np.ndarray:
        """A^p/A (Fig. 5's ordinate as captioned)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.plastic_area_fraction / self.area_fraction

    @property
    def yielded_area_ratio(self) -> np.ndarray:
        """(A^ep + A^p)/A: the part of the real area past first yield."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return (self.elastoplastic_area_fraction + self.plastic_area_fraction) / self.area_fraction

    FIELDS: ClassVar[tuple[str, ...]] = (
        "area_fraction",
        "pressure",
        "stiffness",
        "elastic_area_fraction",
        "elastoplastic_area_fraction",
        "plastic_area_fraction",
        "elastic_pressure",
        "elastoplastic_pressure",
        "plastic_pressure",
        "stiffness_jump",
    )

    def to_dataset(self, units: Mapping[str, str] | None = None):
        """An xarray.Dataset over ``s`` with CF metadata, material and surface in the
        attributes. ``units`` = {"length": L, "stress": S} (UDUNITS strings) states the unit
        system of the inputs, as in :meth:`ContactCurves.to_dataset`; without it the
        pressures and stiffnesses carry no ``units`` attribute."""
        import xarray as xr

        units = check_units(units)
        ds = xr.Dataset(
            {name: ("s", getattr(self, name), attrs(name, units)) for name in self.FIELDS},
            coords={"s": ("s", self.s, attrs("s", units))},
        )
        m = self.material
        ds.attrs.update(
            model="bgk-elastoplastic",
            hertz=self.hertz,
            method=self.method,
            E_star=m.E_star,
            Y=m.Y,
            H=m.H,
            yield_coefficient=m.yield_coefficient,
            c_h=m.c_h,
            wp_over_wc=m.wp_over_wc,
            K_v=m.K_v,
            psi=self.psi,
            **self.surface.as_dict(),
        )
        if self.interpolation is not None:
            ds.attrs.update(self.interpolation.as_attrs())
        if self.route is not None:
            ds.attrs["route"] = self.route
        return ds


# ---------------------------------------------------------------------------------------
# validation
# ---------------------------------------------------------------------------------------
def _check_inputs(surface, s, material, hertz, method) -> np.ndarray:
    instance("surface", surface, SpectralMoments)
    instance("material", material, AsperityMaterial)
    choice("hertz", hertz, HERTZ)
    choice("method", method, METHODS)
    return separations(s)


def _material_constants(material: AsperityMaterial):
    """(E*, ω_p/ω_c, c_h H, H(c_h − (2/3)K_v), (2/3) K_v H, with_jump) for the kernels."""
    m = material
    with_jump = m.has_load_jump
    return (
        m.E_star,
        m.wp_over_wc,
        m.c_h * m.H,
        m.H * (m.c_h - (2.0 / 3.0) * m.K_v),
        (2.0 / 3.0) * m.K_v * m.H,
        with_jump,
    )


# ---------------------------------------------------------------------------------------
# θ-node data (as contact.elastic._theta_nodes, plus f3 and the critical interference)
# ---------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def _theta_geometry(surface: SpectralMoments, hertz: str, accuracy):
    """Per-θ-node g, c, f1, f2, f3 and the Hertz factors on the nested θ-rules of the accuracy's
    levels (split at the axis turn θ*, the peak of g and the Hertz kinks; ordered by level),
    with ``counts`` and ``weights`` (θ-weight × cos θ sin θ per level):
    integrals.rules.nested_theta_rule. Material-free: shared by every material of a surface."""
    settings = elastoplastic_settings_for(accuracy)
    geom = PolarGeometry(surface)
    theta, counts, w = nested_theta_rule(geom.theta_breaks(hertz), settings.theta_levels)
    lam = np.sqrt(geom.lambda_squared(theta))
    factors = ellipse.hertz_factors(lam, hertz)
    nodes = dict(
        g=geom.g(theta),
        c=geom.c(theta),
        f1=np.asarray(factors.f1, float),
        f2=np.asarray(factors.f2, float),
        f3=np.asarray(factors.f3, float),
        counts=counts,
        weights=w * (np.cos(theta) * np.sin(theta))[None, :],
    )
    return nodes, factors


def _tc1(surface, hertz, accuracy, material) -> np.ndarray:
    """tc1 = ω_c(θ, κ_m = c(θ))/√(m00 μ) at the θ-nodes, eq. (65) (asperity.critical_interference)."""
    nodes, factors = _theta_geometry(surface, hertz, accuracy)
    sigma = math.sqrt(surface.m00 * surface.mu)
    return np.asarray(critical_interference(nodes["c"], factors, material, hertz=hertz), dtype=float) / sigma


def _theta_nodes(surface: SpectralMoments, hertz: str, accuracy, material: AsperityMaterial):
    """The θ-node data of :func:`_theta_geometry` with the material's ``tc1``."""
    return {**_theta_geometry(surface, hertz, accuracy)[0], "tc1": _tc1(surface, hertz, accuracy, material)}


def _production_many(surface, l_values, materials, hertz, accuracy, return_info=False):
    """Columns A^e, A^ep, A^p, W^e, W^ep, W^p, K, K_jump per unit nominal area, shape
    (n_l, n_materials, 8): the hyperbola integrals are the surface's, computed once per l."""
    nodes = _theta_geometry(surface, hertz, accuracy)[0]
    tc1 = np.array([_tc1(surface, hertz, accuracy, m) for m in materials])
    sigma = math.sqrt(surface.m00 * surface.mu)
    tot, info = polar_elastoplastic_integrals(l_values, nodes, sigma, [_material_constants(m) for m in materials],
                                              accuracy, tc1=tc1, return_info=True)
    out = tot * surface.summit_density
    out[..., 6] = out[..., 6] + out[..., 7]  # K = ∫ dW_i/dω p_sum + jump term
    return (out, info) if return_info else out


def _production(surface, l_values, material, hertz, accuracy, return_info=False):
    """:func:`_production_many` for one material: shape (n_l, 8)."""
    out, info = _production_many(surface, l_values, [material], hertz, accuracy, return_info=True)
    return (out[:, 0], info[:, 0]) if return_info else out[:, 0]


def _cached_table(key, lo: float, hi: float):
    """The cached table of ``key`` if it covers separations l ∈ [lo, hi] (marked recently used)."""
    table = _TABLES.get(key)
    if table is None or not table.covers(lo, hi):
        return None
    _TABLES.move_to_end(key)
    return table


def _store_table(key, table) -> None:
    """Keep ``table``; the least recently used tables leave while the cache exceeds TABLE_CACHE_BYTES."""
    _TABLES.pop(key, None)
    _TABLES[key] = table
    total = sum(t.nbytes for t in _TABLES.values())
    while total > TABLE_CACHE_BYTES and _TABLES:
        total -= _TABLES.popitem(last=False)[1].nbytes


def clear_table_cache() -> None:
    """Forget every cached summit table (route "table"/"auto"): the next call builds afresh."""
    _TABLES.clear()


def table_cache_bytes() -> int:
    """Bytes held by the in-process summit-table cache (at most TABLE_CACHE_BYTES)."""
    return int(sum(t.nbytes for t in _TABLES.values()))


def _table_many(surface, l_values, materials, hertz, accuracy):
    """:func:`_production_many` by the summit table (integrals.summit_table): one table per
    (surface, hertz, accuracy, material), cached (least recently used out beyond
    TABLE_CACHE_BYTES) and rebuilt over a wider range when the separations leave it. The
    materials without a table are built together when there are SHARED_MIN of them and their
    t_c1 are multiples of one another (eq. (65): every material differing in Y, E*, H, c_h,
    ω_p/ω_c, K_v), from one set of material-free densities (summit_table.build_tables, "the
    shared build"); a lone material by build_table, and so is every material when the shared
    build cannot meet its tolerance (ArithmeticError)."""
    nodes = _theta_geometry(surface, hertz, accuracy)[0]
    sigma = math.sqrt(surface.m00 * surface.mu)
    l_values = np.asarray(l_values, dtype=float)
    lo, hi = float(l_values.min()), float(l_values.max())
    out = np.empty((l_values.size, len(materials), 8))
    tables = {}
    missing = []
    for m in dict.fromkeys(materials):
        key = (surface, hertz, accuracy, m)
        table = _cached_table(key, lo, hi)
        if table is not None:
            tables[m] = table
        else:
            old = _TABLES.get(key)
            if old is not None:  # widened: the old range and the new one
                lo, hi = min(lo, old.y_range[0] + 11.0), max(hi, old.y_range[1] - 11.0)
            missing.append(m)
    if missing:
        tc1s = [_tc1(surface, hertz, accuracy, m) for m in missing]
        built = None
        if len(missing) >= SHARED_MIN and shared_scale(tc1s) is not None:
            try:
                built = build_tables(nodes, tc1s, sigma, [_material_constants(m) for m in missing], accuracy, lo, hi)
            except ArithmeticError:  # a v-panel short of its tolerance: the per-material builds (same bound)
                built = None
        if built is None:
            built = [build_table(nodes, t, sigma, _material_constants(m), accuracy, lo, hi)
                     for m, t in zip(missing, tc1s)]
        for m, table in zip(missing, built):
            tables[m] = table
            _store_table((surface, hertz, accuracy, m), table)
    for k, m in enumerate(materials):
        out[:, k] = tables[m].columns(l_values)
    out *= surface.summit_density
    out[..., 6] = out[..., 6] + out[..., 7]
    return out


def _tau_evaluations(n_separations: int, interpolate_s: bool) -> int:
    """Model evaluations of a τ-route curve of n distinct separations (per material)."""
    if interpolate_s and n_separations >= S_INTERPOLATION_MIN:
        return min(n_separations, S_INTERPOLATION_EVALUATIONS)
    return n_separations


def _build_cost(n_materials: int, accuracy) -> float:
    """The cold build of ``n_materials`` tables in τ-route separations of one material: lone
    builds below SHARED_MIN, else the shared build ≈ (2.5 + 0.06 k) lone builds (measured, above)."""
    one = BUILD_IN_TAU_SEPARATIONS.get(accuracy, BUILD_IN_TAU_SEPARATIONS_OTHER) if isinstance(accuracy, str) \
        else BUILD_IN_TAU_SEPARATIONS_OTHER
    return one * (n_materials if n_materials < SHARED_MIN else 2.5 + 0.06 * n_materials)


def _tau_cost(n_separations: int, n_materials: int, interpolate_s: bool) -> float:
    """The τ route's cost of a call in τ-route separations of one material: evaluations × the
    k-material cost ≈ 0.4 + 0.6 k (k = 1: 1; measured, above)."""
    return _tau_evaluations(n_separations, interpolate_s) * max(1.0, 0.4 + 0.6 * n_materials)


def _auto_tables(surface, s_arr, materials, hertz, accuracy, interpolate_s) -> np.ndarray:
    """route="auto": per material, True where the table route is taken. A material whose table
    is cached and covers the call's separations takes it; the materials without one all take it
    when the call's τ-route cost (its distinct separations, after s-interpolation, times its
    materials) is at least the cold build of their tables (:func:`_tau_cost` ≥
    :func:`_build_cost`), else the τ route. Measured break-even ("plot", Table 1): one material
    from ~70 separations evaluated (a curve without s-interpolation; with it a curve costs 33
    evaluations, so one curve of one material stays on τ and pays no build); a sweep's surface
    with ≥ 11 materials of one s-interpolated curve (a sweep over ψ), or 2 and 3 materials from
    88 and 96 separations evaluated."""
    lv = surface.l_from_s(s_arr)
    lo, hi = float(lv.min()), float(lv.max())
    cached = np.array([_cached_table((surface, hertz, accuracy, m), lo, hi) is not None for m in materials])
    missing = list(dict.fromkeys(m for m, c in zip(materials, cached) if not c))
    if missing:
        n_s = int(np.unique(s_arr).size)
        if _tau_cost(n_s, len(missing), interpolate_s) >= _build_cost(len(missing), accuracy):
            return np.ones(len(materials), dtype=bool)
    return cached


#: the column groups whose sum is each production column's total (s_interpolation's
#: relative-error floor): area parts, load parts, K (with its jump part)
_COLUMN_TOTALS = ((0, 1, 2),) * 3 + ((3, 4, 5),) * 3 + ((6,), (6,))
#: tolerance of the s-interpolation check per preset: a tenth of the preset's stated bound
#: (integrals.rules.ELASTOPLASTIC_PRESETS: "table" 1e-11, "plot" 1e-8), so interpolated
#: curves stay within it; QuadratureSettings given directly: a tenth of 1e-8 (issue 13's
#: accuracy target)
S_RTOL = {"table": 1e-12, "plot": 1e-9}
S_RTOL_OTHER = 1e-9


def _s_rtol(accuracy, s_rtol) -> float:
    if s_rtol is not None:
        s_rtol = float(s_rtol)
        if not (0.0 < s_rtol < 1.0):
            raise ValueError(f"s_rtol must be in (0, 1), got {s_rtol!r}")
        return s_rtol
    return S_RTOL.get(accuracy, S_RTOL_OTHER) if isinstance(accuracy, str) else S_RTOL_OTHER


# ---------------------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------------------
def elastoplastic_contact(
    surface: SpectralMoments,
    s,
    material: AsperityMaterial,
    *,
    hertz: str = "exact",
    accuracy="table",
    method: str = "production",
    validity: str = "refuse",
    interpolate_s: bool = True,
    s_rtol: float | None = None,
    route: str = "auto",
) -> ElastoPlasticCurves:
    """Elasto-plastic contact per unit nominal area at separations ``s`` = h/√m00 (23).

    surface   SpectralMoments (lengths in its unit L; D_sum per L²).
    material  AsperityMaterial (E*, Y, H, K_Y, c_h, ω_p/ω_c, K_v; stresses in one unit).
              To prescribe a plasticity index ψ use
              ``AsperityMaterial(E, asperity.yield_strength_for_plasticity_index(ψ, surface, E))``.
    hertz     "exact" | "paper" (ellipse factors as in contact.elastic_contact).
    accuracy  production preset of integrals.rules.ELASTOPLASTIC_PRESETS ("table", "plot"), an
              ElastoPlasticSettings or a QuadratureSettings.
    method    "production" (numba) or "reference" (the scipy slow twin; seconds per point).
    validity  "refuse" | "warn" | "off": outside the model's range (contact.validity): warnings
              for s < 0 or A/A0 > 0.1, ValueError for A/A0 > 1 unless "warn".
    interpolate_s  with ≥ 48 distinct separations, build the τ-route curve from a verified
              Chebyshev interpolant in s (contact.s_interpolation: the interpolant agrees with
              direct evaluation between its nodes to ``s_rtol``; falls back to every point when
              no grid with fewer nodes than points verifies). Production τ route only (the
              table route evaluates every separation directly).
    s_rtol    tolerance of that check; default a tenth of the preset's stated bound
              (S_RTOL), so that the curve stays within the preset's bound.
    route     production route (ROUTES):
              "tau"   per separation (the τ = r t kernel; 1.4–1.8 ms per separation at "plot");
              "table" one summit table per material (integrals.summit_table), cached in-process
                      (least recently used out beyond TABLE_CACHE_BYTES = 64 MiB; clear_table_cache);
                      every separation a quadrature over it (~40 µs), no s-interpolation; the
                      build costs ~70 τ separations ("plot"; ~100 ms); SHARED_MIN or more new
                      materials of a call are built together by one shared build
                      (summit_table.build_tables: a sweep over ψ at fixed moments);
              "auto"  (default) per material: "table" when its table is cached and covers the
                      separations; the materials without one take "table" when the call's
                      τ-route cost (distinct separations — 33 for an s-interpolated curve of ≥ 48 —
                      times ≈ 0.4 + 0.6 k for k materials) reaches the cold build's (70 τ
                      separations per material at "plot", 80 at "table"; the shared build
                      ≈ 2.5 + 0.06 k builds), else "tau". A single separation or one curve of one
                      material stays on "tau" (no build); a sweep's surface with ≥ 11 materials
                      takes "table". Both routes are within the preset's bound ("plot" 1e-8,
                      "table" 1e-11) of the references, so the route changes a value by at most
                      twice the bound; the curves record the route taken (``route``).

    Returns :class:`ElastoPlasticCurves`: A/A0, W/A0 (unit of E*), K/A0 = −d(W/A0)/dh (unit of
    E* per L) and the elastic / elasto-plastic / plastic parts of area and load.
    """
    return elastoplastic_contact_many(surface, s, [material], hertz=hertz, accuracy=accuracy, method=method,
                                      validity=validity, interpolate_s=interpolate_s, s_rtol=s_rtol, route=route)[0]


def elastoplastic_contact_many(surface: SpectralMoments, s, materials, *, hertz: str = "exact", accuracy="table",
                               method: str = "production", validity: str = "refuse", interpolate_s: bool = True,
                               s_rtol: float | None = None, route: str = "auto") -> list[ElastoPlasticCurves]:
    """:func:`elastoplastic_contact` for several materials on one surface (same arguments;
    ``materials`` a sequence of AsperityMaterial): one :class:`ElastoPlasticCurves` each, the
    same numbers as one call per material on the same route. Faster: the summit measure's
    hyperbola integrals (τ route) depend on the surface and the separation only, and are
    computed once for all materials; the table route builds new materials' tables together
    (what a sweep over ψ or Y at fixed moments needs). With route="auto" the rule is applied
    to the call as a whole (its materials without a cached table all take the same route)."""
    materials = list(materials)
    if not materials:
        raise ValueError("give at least one material")
    s_arr = _check_inputs(surface, s, materials[0], hertz, method)
    for m in materials[1:]:
        instance("material", m, AsperityMaterial)
    choice("validity", validity, VALIDITY_MODES)
    check_bandwidth(surface.mu, method)
    choice("route", route, ROUTES)
    n = len(materials)
    how = [None] * n
    taken = [None] * n
    if method == "production":
        elastoplastic_settings_for(accuracy)  # validates the preset name
        rtol = _s_rtol(accuracy, s_rtol)
        if route == "auto":
            use_table = _auto_tables(surface, s_arr, materials, hertz, accuracy, interpolate_s)
        else:
            use_table = np.full(n, route == "table")
        cols = np.empty((s_arr.size, n, 8))
        on_table, on_tau = np.flatnonzero(use_table), np.flatnonzero(~use_table)
        if on_table.size:
            cols[:, on_table] = _table_many(surface, surface.l_from_s(s_arr), [materials[k] for k in on_table],
                                            hertz, accuracy)
            for k in on_table:
                how[k], taken[k] = SInterpolation("direct", s_arr.size, 0, math.nan, rtol), "table"
        if on_tau.size:
            sub = [materials[k] for k in on_tau]

            def evaluate(x, which):
                return _production_many(surface, surface.l_from_s(x), [sub[k] for k in which], hertz, accuracy)
            if interpolate_s:
                c, h = interpolated_columns_many(evaluate, s_arr, len(sub), rtol, _COLUMN_TOTALS)
            else:
                c = evaluate(s_arr, np.arange(len(sub)))
                h = [SInterpolation("direct", s_arr.size, 0, math.nan, rtol)] * len(sub)
            cols[:, on_tau] = c
            for j, k in enumerate(on_tau):
                how[k], taken[k] = h[j], "tau"
    else:
        cols = np.array([[reference_integrals(surface, float(x), m, hertz=hertz) for m in materials] for x in s_arr])
    return [_curves(surface, s_arr, cols[:, k], materials[k], hertz, method, validity, how[k], taken[k])
            for k in range(n)]


def _curves(surface, s_arr, cols, material, hertz, method, validity, how, route) -> ElastoPlasticCurves:
    Ae, Aep, Ap, We, Wep, Wp, K, Kj = (np.asarray(cols[:, q], dtype=float) for q in range(8))
    check_validity(s_arr, Ae + Aep + Ap, mode=validity)
    return ElastoPlasticCurves(
        s=s_arr,
        area_fraction=Ae + Aep + Ap,
        pressure=We + Wep + Wp,
        stiffness=K,
        elastic_area_fraction=Ae,
        elastoplastic_area_fraction=Aep,
        plastic_area_fraction=Ap,
        elastic_pressure=We,
        elastoplastic_pressure=Wep,
        plastic_pressure=Wp,
        stiffness_jump=Kj,
        hertz=hertz,
        method=method,
        material=material,
        surface=surface,
        psi=plasticity_index(surface, material),
        interpolation=how,
        route=route,
    )
