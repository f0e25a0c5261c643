"""Tabulated normal interface law for the FE engine: p_N(u_N), k_N(u_N) and k_T of section 8.

Equation numbers are those of Buczkowski & Kleiber (2009). The law feeds the friction update
(:func:`roughcontact.interface.friction.update`), whose docstring section "Normal contact, sign
convention and reference state" is the one owner of the sign convention (u_N closure, positive
closes; p_N ≥ 0 pressure) and of the reference state used here; docs/interface.md is the
user's page (with the reasons for the choices below and the measured errors).

What is tabulated
-----------------
The statistical model of the surface gives, per unit nominal area and versus the separation h
of the flat from the mean plane [L, the length unit of the moments]:

* ``level="elastic"``: W/A0 of (53) and K/A0 = −d(W/A0)/dh of (55) = the k_N of (95)
  (:func:`roughcontact.contact.elastic_contact`, BGK model);
* ``level="elastoplastic"``: W/A0 of (82)-(85) and K/A0 = −d(W/A0)/dh (replaces (88), errata
  E17) (:func:`roughcontact.contact.elastoplastic.elastoplastic_contact`).

Both come from the production integrators ("direct integration" below), W/A0 in the unit of
E*, K/A0 in that unit per L. :meth:`NormalLawTable.from_samples` puts the nodes at given
samples instead (a BEM load ladder, level "bem"; :mod:`.normal_law_samples`). A :class:`NormalLawTable` is built once per (surface, level,
E* or material, Hertz option) over a stated pressure (or separation) range; the FE loop only
evaluates it — it never integrates.

Interpolant
-----------
q(h) = ln(W/A0) is interpolated by a C² piecewise quintic Hermite polynomial with, at each
node, q (from W), the exact slope q' = −K/W (from K) and q'' from the quintic through the
(q, q') data of the node and its two neighbours (one-sided at the two ends; O(Δ⁴)). Then
p_N = exp(q) and k_N = dp_N/du_N = −p_N q'(h), the exact derivative of the pressure
interpolant (consistent Newton tangent); K has no interpolant of its own, the derivative is
checked against it.

Error bound and how it is enforced (``rtol``, default 1e-6)
-----------------------------------------------------------
Nodes start uniform with spacing ≤ √m00/2 and are refined adaptively: on every interval the
interpolated p_N and k_N are compared with direct integration at t = 1/4, 1/2, 3/4 of the
interval, and intervals where either relative error exceeds rtol/4 (or where q' is not proven
negative, see below) are split at their midpoint (which becomes a node). The factor 4 covers
the error between check points (the error vanishes at the nodes, where p_N and k_N are exact
to the integrator's accuracy). The largest errors measured at the check points are stored
(``max_error_pressure``, ``max_error_stiffness``); tests/interface/test_normal_law.py checks the bound
independently at random points between the nodes. An interval still failing below a width
of 1e-3 √m00 means the direct integration is not smooth to rtol/4: RuntimeError.

Monotone: on every interval q' (a quartic) is proven negative by its Bernstein coefficients,
so p_N increases strictly with u_N and k_N > 0 in the table range.

Outside the table
-----------------
* Light end (h > h_light, p_N < p_light): the statistical W never vanishes (Gaussian heights),
  so the open state is a modelling choice. The tail is the quadratic
  p_N = p_light z², z = 1 + q'(h_light)(h − h_light)/2, which continues p_N and k_N
  continuously (C¹), decreases monotonically and reaches p_N = k_N = 0 at
  h_open = h_light + 2/|q'(h_light)|; beyond h_open the contact is open (p_N = k_N = 0).
  In the tail |p_N − W/A0| ≤ p_light: choose p_light below every pressure of interest.
* Heavy end (h < h_min, p_N > p_max): not extrapolated. The Python API raises ValueError; the
  numba kernel returns a flag (``beyond``) that friction.update turns into a ValueError.
  For the trial states of a nonlinear solver only, :meth:`InterfaceLaw.extrapolated` continues
  the heavy end by its tangent, p_N = p_max + k_max (u_N − u_max) (k_N held at k_max: what FE
  codes do beyond a table's last row), so that an iterate overshooting the table still gets a
  finite, monotone, C¹ response and a Newton step back; the tail is extra nodes of the same
  interpolant (``_heavy_tail``) up to p_N = 10⁶ p_max, with q' proven negative on every interval.
  A converged state must still lie in the table: the FE solver judges the range on it.

Tangential stiffness
--------------------
k_Tx = a_x k_N(u_N), k_Ty = a_y k_N(u_N) with a given factor (the punch of section 9.2 uses
a_x = a_y = 0.7) or Mindlin's ratio (96)/Table 3 for a contact ellipse
(:func:`mindlin_kT_over_kN`).

Numba form
----------
:meth:`NormalLawTable.kernel_table` is a (n, 4) float64 array of (h, q, q', q'') at the nodes
(h ascending); :func:`closure_law` (``njit(cache=True)``, plain loops, no fastmath) evaluates
(p_N, dp_N/du_N, d²p_N/du_N², beyond) at a closure u_N for a reference separation h_ref. Its
slow twin :func:`reference_closure_law` (power-basis polynomials from the Hermite conditions,
NumPy, complex-step capable) is what friction.reference_update uses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..asperity import AsperityMaterial
from ..contact import elastic_contact, elastoplastic_contact
from ..contact.elastic import HERTZ
from ..contact.validity import check_validity
from ..statistics.surface import SpectralMoments
from ..validation import choice, instance, positive
from .kernels import _closure_law_array, closure_law
from .tangential import kn_over_kt
from ..limits import describe

__all__ = ["LEVELS", "NormalLawTable", "InterfaceLaw", "mindlin_kT_over_kN"]

LEVELS = ("elastic", "elastoplastic")
#: check points of the adaptive build, as fractions of an interval
_CHECK_T = (0.25, 0.5, 0.75)
#: the check points must meet rtol/_SAFETY (the error between them is covered by the margin)
_SAFETY = 4.0
#: initial node spacing in units of √m00
_DS0 = 0.5
#: the table ends are placed this far (relative in p) beyond the requested pressures
_END_MARGIN = 1e-6
#: narrowest interval [√m00]: the interpolation error there is ~(2e-3)^5 of that at the initial
#: spacing, so a check that still fails measures the noise of the direct integration
_MIN_WIDTH = 1e-3
#: the trial tail past the heavy end (InterfaceLaw.extrapolated): 1 + k_max d / p_max grows by
#: this factor from node to node, up to _TAIL_SPAN
_TAIL_RATIO = math.exp(0.5)
_TAIL_SPAN = 1e6


# ---------------------------------------------------------------------------------------------
# building the table
# ---------------------------------------------------------------------------------------------
def _second_derivatives(h, q, dq) -> np.ndarray:
    """q'' at each node: the second derivative of the quintic through (q, q') at the node and
    its two neighbours (the nearest three nodes at the ends)."""
    n = h.size
    d2 = np.empty(n)
    for i in range(n):
        j = min(max(i - 1, 0), n - 3)
        idx = np.arange(j, j + 3)
        scale = h[j + 2] - h[j]
        x = (h[idx] - h[i]) / scale
        m = np.arange(6)
        A = np.empty((6, 6))
        b = np.empty(6)
        A[0::2] = x[:, None] ** m
        A[1::2] = m * x[:, None] ** np.maximum(m - 1, 0)
        b[0::2] = q[idx]
        b[1::2] = dq[idx] * scale
        d2[i] = 2.0 * np.linalg.solve(A, b)[2] / scale ** 2
    return d2


def _hermite_power_coefficients(tab) -> np.ndarray:
    """(n − 1, 6) power-basis coefficients of q on each interval in t = (h − h_i)/Δ_i, solved
    from the six Hermite conditions (q, Δq', Δ²q'' at t = 0 and 1)."""
    conditions = np.array([
        [1, 0, 0, 0, 0, 0],  # value, slope, curvature at t = 0
        [0, 1, 0, 0, 0, 0],
        [0, 0, 2, 0, 0, 0],
        [1, 1, 1, 1, 1, 1],  # value, slope, curvature at t = 1
        [0, 1, 2, 3, 4, 5],
        [0, 0, 2, 6, 12, 20],
    ], dtype=float)
    width = np.diff(tab[:, 0])
    rhs = np.column_stack([tab[:-1, 1], width * tab[:-1, 2], width ** 2 * tab[:-1, 3],
                           tab[1:, 1], width * tab[1:, 2], width ** 2 * tab[1:, 3]])
    return np.linalg.solve(conditions, rhs.T).T


def _slope_is_negative(tab) -> np.ndarray:
    """Per interval: True when q'(t) < 0 on all of it (all Bernstein coefficients of the quartic
    dq/dt negative: a sufficient condition)."""
    c = _hermite_power_coefficients(tab)
    a = c[:, 1:] * np.arange(1, 6)  # dq/dt in the power basis, degree 4
    binom = [math.comb(4, j) for j in range(5)]
    bern = np.stack([sum(math.comb(k, j) / binom[j] * a[:, j] for j in range(k + 1)) for k in range(5)], axis=1)
    return np.all(bern < 0.0, axis=1)


def _heavy_tail(tab) -> np.ndarray:
    """The kernel table ``tab`` with rows (h, q, q', q'') prepended that continue it past its
    heavy end h₀ = h_min by its tangent: p_N = p_max (1 + a d), d = h₀ − h, a = −q'(h₀), i.e.
    q = q₀ + ln x, q' = −a/x, q'' = −a²/x² with x = 1 + a d (exact at the nodes, x = ρ^k up to
    _TAIL_SPAN). The interval next to h₀ joins the table's q''(h₀) to the tail's −a²: it is
    narrowed (nodes at x = 1 + (ρ − 1) 2^−j) until q' is proven negative on it."""
    h0, q0, dq0, _ = tab[0]
    a = -dq0
    if not a > 0.0:
        raise ValueError("the table's slope at its heavy end is not negative")
    x = _TAIL_RATIO ** np.arange(1, math.ceil(math.log(_TAIL_SPAN) / math.log(_TAIL_RATIO)) + 1)
    for j in range(60):
        d = (x - 1.0) / a
        rows = np.column_stack([h0 - d, q0 + np.log(x), -a / x, -(a / x) ** 2])[::-1]
        out = np.ascontiguousarray(np.vstack([rows, tab]))
        if np.all(_slope_is_negative(out[:x.size + 1])):
            return out
        x = np.concatenate([[1.0 + (x[0] - 1.0) / 2.0], x])
    raise RuntimeError("no monotone tail past the heavy end of the table")  # pragma: no cover


def _pair(name, value):
    try:
        a, b = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair of numbers, got {describe(value)}") from None
    if not (math.isfinite(a) and math.isfinite(b) and a < b):
        raise ValueError(f"{name} must be two finite numbers in increasing order, got {describe(value)}")
    return a, b


@dataclass(frozen=True, eq=False)
class NormalLawTable:
    """Tabulated W/A0(h), K/A0(h) of one surface and model level (see the module docstring).

    h, q, dq, d2q : node separations h [L] (ascending), q = ln(W/A0), q' = −K/W [1/L], q'' [1/L²].
    level, hertz, surface, E_star, material, accuracy : what was tabulated (material is None
        for the elastic level; E_star is the material's for the elasto-plastic one).
    rtol : the stated bound on the relative interpolation error of p_N and k_N in range.
    max_error_pressure, max_error_stiffness : the largest relative errors measured at the
        check points of the build; n_evaluations : direct integrations spent on the build.
    """

    h: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    d2q: np.ndarray
    level: str
    hertz: str
    surface: SpectralMoments
    E_star: float
    material: AsperityMaterial | None
    accuracy: object
    rtol: float
    max_error_pressure: float
    max_error_stiffness: float
    n_evaluations: int

    # -- construction --------------------------------------------------------------------------
    @classmethod
    def build(cls, surface, level, *, E_star=None, material=None, hertz="exact",
              pressure_range=None, s_range=None, rtol=1e-6, accuracy="table",
              validity="refuse") -> "NormalLawTable":
        """Build the table once from the production integrators.

        surface        SpectralMoments (lengths in L).
        level          "elastic" (give E_star [stress]) or "elastoplastic" (give an
                       AsperityMaterial; for a prescribed plasticity index ψ use
                       ``AsperityMaterial(E, asperity.yield_strength_for_plasticity_index(ψ, surface, E))``).
        hertz          "exact" | "paper" (as in contact.elastic_contact).
        pressure_range (p_light, p_max) [unit of E*]: the table spans the separations where
                       W/A0 runs from p_light to p_max (ends placed 1e-6 relative beyond them);
        s_range        or (s_min, s_max) in s = h/√m00: exactly one of the two.
        rtol           bound on the relative interpolation error of p_N and k_N, in [1e-9, 1e-2].
        accuracy       production preset ("table") or QuadratureSettings.
        validity       the heavy end against the model's range (contact.validity): "refuse"
                       (ModelValidityWarning past A/A0 = 0.1 or s < 0, ValueError past
                       A/A0 = 1), "warn" (a range kept as headroom: warn only), "off".
        """
        instance("surface", surface, SpectralMoments)
        choice("level", level, LEVELS)
        choice("hertz", hertz, HERTZ)
        if level == "elastic":
            if material is not None or E_star is None:
                raise ValueError("level 'elastic' takes E_star (and no material)")
            E = positive("E_star", E_star)
        else:
            if not isinstance(material, AsperityMaterial) or E_star is not None:
                raise ValueError("level 'elastoplastic' takes material=AsperityMaterial(...) (and no E_star)")
            E = material.E_star
        rtol = float(rtol)
        if not (1e-9 <= rtol <= 1e-2):
            raise ValueError(f"rtol must lie in [1e-9, 1e-2], got {describe(rtol)}")
        if (pressure_range is None) == (s_range is None):
            raise ValueError("give exactly one of pressure_range=(p_light, p_max) and s_range=(s_min, s_max)")

        direct = _DirectIntegration(surface, level, E, material, hertz, accuracy)
        if s_range is not None:
            s_min, s_max = _pair("s_range", s_range)
            h_min, h_max = s_min * surface.height_std, s_max * surface.height_std
            direct([h_min, h_max])  # fail fast where W/A0 is not representable
        else:
            p_light, p_max = _pair("pressure_range", pressure_range)
            if p_light <= 0.0:
                raise ValueError(f"pressure_range must be positive, got {describe(pressure_range)}")
            h_min = direct.separation_for(p_max * (1.0 + _END_MARGIN))
            h_max = direct.separation_for(p_light * (1.0 - _END_MARGIN))
        # A/A0 is largest at the heavy end: warn past the model's quantitative range, refuse A/A0 > 1
        check_validity(h_min / surface.height_std, direct.area[h_min], mode=validity)
        tab, err_p, err_k = _refine(direct, h_min, h_max, rtol)
        return cls(*tab.T.copy(), level=level, hertz=hertz, surface=surface, E_star=E,
                   material=material, accuracy=accuracy, rtol=rtol, max_error_pressure=err_p,
                   max_error_stiffness=err_k, n_evaluations=direct.count)

    @classmethod
    def from_samples(cls, h, p, k, *, surface, E_star, level="bem") -> "NormalLawTable":
        """The table through samples of a law (a BEM load ladder: h = ḡ [L], p = W/A0, k = K/A0)
        instead of the integrators, with an estimated (not enforced) error and the same tails:
        :func:`roughcontact.interface.normal_law_samples.sampled_table`."""
        from .normal_law_samples import sampled_table

        return sampled_table(cls, h, p, k, surface=surface, E_star=E_star, level=level)

    # -- properties ----------------------------------------------------------------------------
    @property
    def kernel_table(self) -> np.ndarray:
        """(n, 4) C-contiguous float64 rows (h, q, q', q'') for :func:`closure_law`."""
        return np.ascontiguousarray(np.column_stack([self.h, self.q, self.dq, self.d2q]))

    @property
    def n_nodes(self) -> int:
        return int(self.h.size)

    @property
    def h_min(self) -> float:
        """Heavy end [L]: the smallest tabulated separation (p_N = p_max there)."""
        return float(self.h[0])

    @property
    def h_light(self) -> float:
        """Light end [L]: the largest tabulated separation (p_N = p_light there)."""
        return float(self.h[-1])

    @property
    def h_open(self) -> float:
        """End of the light-end tail [L]: p_N = k_N = 0 for h ≥ h_open."""
        return float(self.h[-1] - 2.0 / self.dq[-1])

    @property
    def p_max(self) -> float:
        return float(np.exp(self.q[0]))

    @property
    def p_light(self) -> float:
        return float(np.exp(self.q[-1]))

    # -- evaluation ----------------------------------------------------------------------------
    def evaluate(self, h):
        """(p_N, k_N) at separations h [L] (vectorised): W/A0 [unit of E*] and K/A0 =
        −dp_N/dh [unit of E*/L] from the table (tail beyond h_light; ValueError below h_min)."""
        h = _finite_array("h", h)
        p, k, _ = _evaluate(self.kernel_table, 0.0, -h, lambda bad: (
            f"h = {float(h.reshape(-1)[bad]):g} is below the heavy end of the table h_min = "
            f"{self.h_min:g} (p_max = {self.p_max:g}); rebuild with a larger p_max"))
        return _out(p, h), _out(k, h)

    def separation_at(self, p) -> float:
        """The separation h [L] where the table's p_N equals p (p_light ≤ p ≤ p_max), to
        round-off: Newton on ln p_N(h) − ln p (slope q' = −k_N/p_N, from the table) inside the
        table interval that brackets it, bisecting where a step would leave the bracket.

        (Newton rather than scipy's brentq: the interpolant is smooth and strictly decreasing
        with its derivative at hand, and ``scipy.optimize`` costs 0.1–0.16 s to import, a
        twentieth of a small FE run's wall time, for this one root.)"""
        p = float(p)
        if not (self.p_light <= p <= self.p_max):
            raise ValueError(f"pressure {describe(p)} is outside the table range [{self.p_light:g}, {self.p_max:g}]")
        target = math.log(p)
        # q decreases with h: the interval whose end values bracket ln p
        i = min(int(np.searchsorted(-self.q, -target, side="right")) - 1, self.n_nodes - 2)
        i = max(i, 0)
        tab = self.kernel_table

        def f(h):
            p_h, k_h = closure_law(-h, 0.0, tab)[:2]
            return math.log(p_h) - target, -k_h / p_h

        a, b = float(self.h[i]), float(self.h[i + 1])  # f(a) ≥ 0 ≥ f(b)
        xtol = 1e-15 * max(abs(a), abs(b), self.surface.height_std)
        h = 0.5 * (a + b)
        for _ in range(200):  # Newton converges in a few steps; bisection alone in ~60
            r, slope = f(h)
            if r == 0.0:
                return h
            if r > 0.0:
                a = h
            else:
                b = h
            new = h - r / slope
            if not (a < new < b):
                new = 0.5 * (a + b)
            if abs(new - h) <= xtol or b - a <= xtol:
                return float(new)
            h = new
        raise RuntimeError(f"no root of p_N(h) = {p:g} found in [{a:g}, {b:g}]")  # pragma: no cover

    def direct(self, h):
        """(W/A0, K/A0) at separations h [L] by direct (production) integration, the reference
        of the interpolation error (a sampled table, :meth:`from_samples`, has none: ValueError)."""
        if self.level not in LEVELS:
            raise ValueError(f"a table of {self.level} samples has no direct integration")
        d = _DirectIntegration(self.surface, self.level, self.E_star, self.material, self.hertz, self.accuracy)
        return d(_finite_array("h", h).reshape(-1))


class _DirectIntegration:
    """(W/A0, K/A0) at separations h [L] from the production integrators, with a cache."""

    def __init__(self, surface, level, E_star, material, hertz, accuracy):
        self.surface, self.level, self.E_star = surface, level, E_star
        self.material, self.hertz, self.accuracy = material, hertz, accuracy
        self.cache: dict[float, tuple[float, float]] = {}
        self.area: dict[float, float] = {}  # A/A0 at the evaluated separations
        self.count = 0

    def __call__(self, h):
        h = np.asarray(h, dtype=float).reshape(-1)
        missing = sorted({float(x) for x in h} - self.cache.keys())
        if missing:
            s = self.surface.s_from_h(np.array(missing))
            if self.level == "elastic":
                c = elastic_contact(self.surface, s, self.E_star, model="bgk", hertz=self.hertz,
                                    accuracy=self.accuracy, validity="off")
            else:
                c = elastoplastic_contact(self.surface, s, self.material, hertz=self.hertz,
                                          accuracy=self.accuracy, validity="off")
            self.count += len(missing)
            # the range is checked once, at its heavy end (NormalLawTable.build), not at every
            # trial separation of the searches
            self.area.update(zip(missing, map(float, c.area_fraction)))
            for x, p, k in zip(missing, c.pressure, c.stiffness):
                if not (p > 0.0 and k > 0.0 and math.isfinite(p) and math.isfinite(k)):
                    raise ValueError(
                        f"W/A0 = {describe(p)}, K/A0 = {describe(k)} at h = {x:g} (s = {x / self.surface.height_std:g}): "
                        "not positive and finite, the range reaches too far (light end too light?)")
                self.cache[x] = (float(p), float(k))
        vals = np.array([self.cache[float(x)] for x in h])
        return vals[:, 0], vals[:, 1]

    def separation_for(self, p_target) -> float:
        """h with W(h)/A0 = p_target: safeguarded Newton on ln W (slope −K/W), from h = 0."""
        sigma = self.surface.height_std
        h, lo, hi = 0.0, -math.inf, math.inf
        target = math.log(p_target)
        for _ in range(100):
            p, k = self([h])
            r = math.log(p[0]) - target
            if abs(r) <= 1e-10:
                return h
            if r > 0.0:
                lo = h
            else:
                hi = h
            new = h + min(max(r * p[0] / k[0], -3.0 * sigma), 3.0 * sigma)
            if not (lo < new < hi):
                new = 0.5 * (lo + hi)
            h_last, h = h, new
        # not a numerical breakdown (Newton with bisection brackets any reachable pressure):
        # the target lies beyond what the integrators represent, a bad range (ValueError)
        raise ValueError(f"the pressure {p_target:g} is not reached by the model (after 100 steps: h = {h_last:g}, "
                         f"W/A0 = {p[0]:g}): choose a pressure range the law can reach")


def _refine(direct, h_min, h_max, rtol):
    """Adaptive nodes on [h_min, h_max]: split every interval whose check points miss rtol/4
    or whose slope is not proven negative. Returns (kernel table, max p error, max k error)."""
    n0 = max(3, math.ceil((h_max - h_min) / (_DS0 * direct.surface.height_std)) + 1)
    nodes = list(np.linspace(h_min, h_max, n0))
    target = rtol / _SAFETY
    while True:
        h = np.array(nodes)
        width = np.diff(h)
        checks = (h[:-1, None] + width[:, None] * np.array(_CHECK_T)).reshape(-1)
        p_all, k_all = direct(np.concatenate([h, checks]))  # one batch for all new points
        p_n, k_n, p_c, k_c = p_all[:h.size], k_all[:h.size], p_all[h.size:], k_all[h.size:]
        q = np.log(p_n)
        dq = -k_n / p_n
        tab = np.ascontiguousarray(np.column_stack([h, q, dq, _second_derivatives(h, q, dq)]))
        p_i, k_i, _ = _evaluate(tab, 0.0, -checks, None)
        err_p = np.abs(p_i / p_c - 1.0).reshape(-1, len(_CHECK_T)).max(axis=1)
        err_k = np.abs(k_i / k_c - 1.0).reshape(-1, len(_CHECK_T)).max(axis=1)
        bad = (err_p > target) | (err_k > target) | ~_slope_is_negative(tab)
        if not bad.any():
            return tab, float(err_p.max()), float(err_k.max())
        narrow = bad & (width < _MIN_WIDTH * direct.surface.height_std)
        if narrow.any():
            i = int(np.flatnonzero(narrow)[0])
            raise RuntimeError(
                f"the direct integration is not smooth to rtol/{_SAFETY:g} = {target:g} near "
                f"s = {h[i] / direct.surface.height_std:g} (relative errors p {err_p[i]:.1e}, "
                f"k {err_k[i]:.1e} on an interval of {width[i]:.1e} L): use a more accurate "
                "preset or a larger rtol")
        mids = checks.reshape(-1, len(_CHECK_T))[bad, _CHECK_T.index(0.5)]  # already integrated
        nodes = sorted(nodes + list(mids))


def _finite_array(name, x) -> np.ndarray:
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be real numbers, got {describe(x)}") from None
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {a[~np.isfinite(a)].reshape(-1)[:3]}")
    return a


def _evaluate(tab, h_ref, u, message):
    """Run the kernel on the closures u; ``message(i)`` builds the ValueError for the first
    point beyond the heavy end (None: no check, used inside the build)."""
    flat = np.ascontiguousarray(np.asarray(u, dtype=float).reshape(-1))
    p, k, dk = (np.empty(flat.size) for _ in range(3))
    beyond = np.empty(flat.size, dtype=np.bool_)
    _closure_law_array(flat, float(h_ref), tab, p, k, dk, beyond)
    if message is not None and beyond.any():
        raise ValueError(message(int(np.flatnonzero(beyond)[0])))
    return p, k, dk


def _out(values, like):
    return float(values[0]) if np.ndim(like) == 0 else values.reshape(np.shape(like))


# ---------------------------------------------------------------------------------------------
# the law at a reference state, with the tangential stiffness
# ---------------------------------------------------------------------------------------------
def mindlin_kT_over_kN(ay2_over_ax2, nu) -> tuple[float, float]:
    """(k_Tx/k_N, k_Ty/k_N) from Mindlin's ratio, corrected (96)/Table 3
    (:func:`roughcontact.interface.tangential.kn_over_kt`), for a contact ellipse with semi-axes a_x
    (along x) and a_y (along y): the force along y has B²/A² = a_y²/a_x², along x the inverse."""
    r = float(ay2_over_ax2)
    return 1.0 / kn_over_kt(1.0 / r, nu), 1.0 / kn_over_kt(r, nu)


def _factor_pair(kT_over_kN):
    """(a_x, a_y) from one factor or a pair."""
    if np.ndim(kT_over_kN) == 0:
        return kT_over_kN, kT_over_kN
    try:
        ax, ay = kT_over_kN
    except ValueError:
        raise ValueError(f"kT_over_kN must be a factor or a pair (x, y), got {describe(kT_over_kN)}") from None
    return ax, ay


@dataclass(frozen=True, eq=False)
class InterfaceLaw:
    """The normal law of a :class:`NormalLawTable` at a reference state, with k_T = a k_N.

    Closure u_N = h_ref − h [L] (> 0 closes; friction.py's convention): u_N = 0 is the
    reference state, the separation h_ref at which the interface carries the initial pressure
    p0 = p_N(0) (the paper applies an initial load first, section 9.1). k_Tx = kT_over_kN_x·k_N,
    k_Ty = kT_over_kN_y·k_N. Pass it as ``k_N`` to friction.update / initial_state / normal_law.
    Build with :meth:`from_pressure` or :meth:`from_separation`. ``extrapolate``: past the heavy
    end (u_N > u_max) the tangent tail of the module docstring instead of a ValueError, for the
    trial states of a solver (:meth:`extrapolated`); ``u_max`` stays the table's end.
    """

    table: NormalLawTable
    h_ref: float
    kT_over_kN_x: float
    kT_over_kN_y: float
    extrapolate: bool = False

    def __post_init__(self):
        if not isinstance(self.table, NormalLawTable):
            raise TypeError(f"table must be a NormalLawTable, got {type(self.table).__name__}")
        h_ref = float(self.h_ref)
        if not (self.table.h_min <= h_ref <= self.table.h_light):
            raise ValueError(f"h_ref = {describe(self.h_ref)} is outside the table [{self.table.h_min:g}, "
                             f"{self.table.h_light:g}]")
        object.__setattr__(self, "h_ref", h_ref)
        object.__setattr__(self, "kT_over_kN_x", positive("kT_over_kN_x", self.kT_over_kN_x))
        object.__setattr__(self, "kT_over_kN_y", positive("kT_over_kN_y", self.kT_over_kN_y))
        tab = self.table.kernel_table
        object.__setattr__(self, "_tab", _heavy_tail(tab) if self.extrapolate else tab)

    @classmethod
    def from_pressure(cls, table, p0, kT_over_kN=(0.7, 0.7)) -> "InterfaceLaw":
        """Reference state at the initial pressure p0 [unit of E*] (solved on the table:
        p_N(0) = p0 to rounding). kT_over_kN: a factor or a pair (x, y), e.g. 0.7 (section 9.2)
        or :func:`mindlin_kT_over_kN`."""
        if not isinstance(table, NormalLawTable):
            raise TypeError(f"table must be a NormalLawTable, got {type(table).__name__}")
        return cls.from_separation(table, table.separation_at(positive("p0", p0)), kT_over_kN)

    @classmethod
    def from_separation(cls, table, h_ref, kT_over_kN=(0.7, 0.7)) -> "InterfaceLaw":
        """Reference state at the separation h_ref [L] (h_min ≤ h_ref ≤ h_light)."""
        return cls(table, h_ref, *_factor_pair(kT_over_kN))

    def extrapolated(self) -> "InterfaceLaw":
        """The same law continued past the heavy end by its tangent (module docstring, "Outside
        the table"): for trial states only; judge a converged state by :attr:`u_max`."""
        return self if self.extrapolate else replace(self, extrapolate=True)

    def with_tangential(self, kT_over_kN) -> "InterfaceLaw":
        """The same normal law with other k_T/k_N factors (one factor or a pair (x, y))."""
        ax, ay = _factor_pair(kT_over_kN)
        return replace(self, kT_over_kN_x=ax, kT_over_kN_y=ay)

    # -- numbers -------------------------------------------------------------------------------
    @property
    def p0(self) -> float:
        """Pressure in the reference state u_N = 0 [unit of E*]."""
        return self.normal(0.0)[0]

    @property
    def u_max(self) -> float:
        """Closure at the heavy end of the table [L]; larger closures raise ValueError."""
        return self.h_ref - self.table.h_min

    @property
    def u_light(self) -> float:
        """Closure at the light end of the table [L]; the tail starts below it."""
        return self.h_ref - self.table.h_light

    @property
    def u_open(self) -> float:
        """Closure at which the tail reaches open contact [L]: p_N = k_N = 0 for u_N ≤ u_open."""
        return self.h_ref - self.table.h_open

    def kernel_data(self):
        """(tab (n, 4), h_ref, (k_Tx/k_N, k_Ty/k_N)) for the numba kernels."""
        return self._tab, self.h_ref, (self.kT_over_kN_x, self.kT_over_kN_y)

    def normal(self, u_N):
        """(p_N, k_N = dp_N/du_N) at closures u_N [L] (vectorised): [unit of E*], [unit of E*/L].
        Open (0, 0) for u_N ≤ u_open; ValueError for u_N > u_max."""
        u = _finite_array("u_N", u_N)
        p, k, _ = _evaluate(self._tab, self.h_ref, u, lambda bad: (
            f"u_N = {float(u.reshape(-1)[bad]):g} exceeds the heavy end of the table u_max = "
            f"{self.u_max:g} (p_max = {self.table.p_max:g})"
            f"{' and its extrapolated tail' if self.extrapolate else ''}; rebuild the table with a larger p_max"))
        return _out(p, u), _out(k, u)

    def tangential(self, u_N):
        """(k_Tx, k_Ty) at closures u_N [L] (vectorised) [unit of E*/L]."""
        k = self.normal(u_N)[1]
        return self.kT_over_kN_x * k, self.kT_over_kN_y * k
