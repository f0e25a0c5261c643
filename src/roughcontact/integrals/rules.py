"""Integration rules and accuracy presets of the production integrators.

The θ rule is a composite tanh-sinh rule (split at the axis turn θ*, the peak of g and the
Hertz kinks); r and t use Gauss–Legendre pieces (:mod:`.kernels`). A preset names a
:class:`QuadratureSettings` whose error bound is measured against the mpmath reference
(elastic) or the slow twin (elasto-plastic) in the tests and docs/performance.md.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "TanhSinh",
    "gauss_legendre",
    "QuadratureSettings",
    "PRESETS",
    "settings_for",
    "theta_rule",
    "ElastoPlasticSettings",
    "ELASTOPLASTIC_PRESETS",
    "elastoplastic_settings_for",
    "nested_theta_rule",
]

@dataclass(frozen=True)
class TanhSinh:
    """Tanh-sinh rule on [0, 1]: nodes y_k = (1 + tanh(π/2 sinh(kh)))/2, |kh| ≤ half_width.

    Both y and 1 − y are formed without cancellation (y = expit(π sinh(kh))), so an
    integrand singular at either end point is evaluated at its true distance from it. The
    default half_width 3.1 keeps every node representable at both ends (1 − y ≥ 1e-16) and
    symmetric; it omits the end intervals y < 1e-16, which is harmless for bounded
    integrands (all of ours) but not for strong singularities such as y^{-1/2}
    (widen half_width for those).
    """

    level: int  # step h = 2^-level
    half_width: float = 3.1

    @property
    def nodes_weights(self) -> tuple[np.ndarray, np.ndarray]:
        h = 2.0**-self.level
        n = int(math.floor(self.half_width / h))
        k = np.arange(-n, n + 1) * h
        u = 0.5 * math.pi * np.sinh(k)
        y = 1.0 / (1.0 + np.exp(-2.0 * u))  # (1 + tanh u)/2
        w = h * 0.5 * math.pi * np.cosh(k) / np.cosh(u) ** 2 * 0.5
        return y, w


@functools.lru_cache(maxsize=32)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """n-point Gauss–Legendre nodes and weights on [0, 1] (cached: do not modify). Writable
    on purpose: numba types read-only arrays differently, and one signature per kernel keeps
    one entry per kernel in numba's on-disk cache (docs/performance.md, caching)."""
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


@dataclass(frozen=True)
class QuadratureSettings:
    """Refinement levels of the production rules (higher = finer in that dimension).

    theta_level  tanh-sinh level of the θ rule (step 2^-level, per θ sub-interval);
    r_level      Gauss–Legendre nodes per r-piece: ``r_nodes`` = 4·r_level + 4;
    t_level      elastic: tolerance of the Chebyshev interpolation in g,
                 ``g_tol`` = 10^-(2·t_level + 5) (absolute on ln I); elasto-plastic:
                 Gauss–Legendre nodes per numerical t-piece, ``t_nodes`` = 4·t_level + 4.
    """

    theta_level: int
    r_level: int
    t_level: int

    @property
    def r_nodes(self) -> int:
        return 4 * self.r_level + 4

    @property
    def t_nodes(self) -> int:
        return 4 * self.t_level + 4

    @property
    def g_tol(self) -> float:
        return 10.0 ** -(2 * self.t_level + 5)
#: Named accuracy presets of the elastic integrals. Measured against the mpmath reference
#: (docs/performance.md; tests/contact/test_elastic.py, tests/integrals/test_kernels.py): "table" ≤ 1e-13
#: relative for g(θ) ≤ 3 (all surfaces with μ ≳ 0.1), "plot" ≤ 1e-8.
PRESETS: dict[str, QuadratureSettings] = {
    "table": QuadratureSettings(theta_level=4, r_level=5, t_level=4),
    "plot": QuadratureSettings(theta_level=4, r_level=3, t_level=2),
}


def settings_for(accuracy, presets: dict[str, QuadratureSettings] | None = None) -> QuadratureSettings:
    """Resolve an accuracy preset name of ``presets`` (default: the elastic PRESETS), or pass a
    QuadratureSettings through."""
    if isinstance(accuracy, QuadratureSettings):
        return accuracy
    presets = PRESETS if presets is None else presets
    try:
        return presets[accuracy]
    except (KeyError, TypeError):
        raise ValueError(
            f"unknown accuracy preset {accuracy!r}; choose one of {sorted(presets)}"
        ) from None


def theta_rule(breakpoints, settings: QuadratureSettings) -> tuple[np.ndarray, np.ndarray]:
    """Composite tanh-sinh nodes and weights on (0, π/2), split at ``breakpoints``
    (where the integrand is not smooth: the axis turn θ*, the clip of eq. (33))."""
    y, w = TanhSinh(settings.theta_level).nodes_weights
    edges = np.unique(np.concatenate(([0.0], np.asarray(breakpoints, float), [0.5 * math.pi])))
    nodes, weights = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        nodes.append(a + (b - a) * y)
        weights.append((b - a) * w)
    return np.concatenate(nodes), np.concatenate(weights)
@dataclass(frozen=True)
class ElastoPlasticSettings:
    """Accuracy of the elasto-plastic kernel (the τ = r t route, :mod:`.kernels`).

    theta_levels  (first, last) tanh-sinh level of the θ rule; the levels nest, so each finer
                  level adds nodes only, and the coarser sum comes free: levels are added until
                  the estimated θ-error e·min(1, e/e_prev) ≤ ``theta_tol`` (e the change from the
                  previous level, relative per column with the parts' floor 1e-3 of their
                  total), or the last level is reached.
    grid_tol      the hyperbola integrals ln G_k(τ; g) are interpolated on panels in s = ln τ
                  (bisected) × Chebyshev nodes in g (doubled) until the last three Chebyshev
                  coefficients are ≤ grid_tol (absolute in ln G, i.e. relative in G).
    hyperbola_step, hyperbola_width_fraction  the trapezoidal step in ln r of G_k:
                  min(step, fraction × the narrowest Laplace width of the integrand).
    tau_nodes     Gauss–Legendre nodes per τ sub-piece (in s).
    panel_degree, panel_width  Chebyshev degree of a panel and the width in s it starts with.
    """

    theta_levels: tuple[int, int]
    theta_tol: float
    grid_tol: float
    hyperbola_step: float
    hyperbola_width_fraction: float
    tau_nodes: int
    panel_degree: int = 16
    panel_width: float = 4.0

    @classmethod
    def from_levels(cls, q: QuadratureSettings) -> "ElastoPlasticSettings":
        """The meaning of QuadratureSettings(θ, r, t) for the elasto-plastic kernel: θ level fixed
        (no adaptation); r sets the grid (tolerance 10^−(2r + 3), at least 1e-14) and the
        hyperbola step (0.5/(r + 1), width fraction min(0.8, 2.8/(r + 1))); t the τ-rule
        (4t + 4 nodes)."""
        r = q.r_level
        return cls(
            theta_levels=(q.theta_level, q.theta_level),
            theta_tol=0.0,
            grid_tol=max(10.0 ** -(2 * r + 3), 1e-14),
            hyperbola_step=0.5 / (r + 1),
            hyperbola_width_fraction=min(0.8, 2.8 / (r + 1)),
            tau_nodes=4 * q.t_level + 4,
        )


#: Presets of the elasto-plastic kernel. Measured against the scipy twin and against finer
#: settings (tests/contact/test_elastoplastic.py, test_hard_cases.py, docs/performance.md):
#: "table" ≤ 1e-11 relative on totals and on parts above 1e-3 of their total; "plot" ≤ 1e-8 —
#: for s ≥ −0.5 on every tested surface. The θ tolerance is a tenth of each bound.
ELASTOPLASTIC_PRESETS: dict[str, ElastoPlasticSettings] = {
    "table": ElastoPlasticSettings(theta_levels=(1, 6), theta_tol=1e-12, grid_tol=1e-10, hyperbola_step=0.08,
                                   hyperbola_width_fraction=0.5, tau_nodes=20, panel_width=6.0),
    "plot": ElastoPlasticSettings(theta_levels=(1, 5), theta_tol=1e-9, grid_tol=1e-7, hyperbola_step=0.12,
                                  hyperbola_width_fraction=0.7, tau_nodes=16, panel_width=8.0),
}


def elastoplastic_settings_for(accuracy) -> ElastoPlasticSettings:
    """Resolve an elasto-plastic accuracy preset name, an ElastoPlasticSettings, or a
    QuadratureSettings (:meth:`ElastoPlasticSettings.from_levels`)."""
    if isinstance(accuracy, ElastoPlasticSettings):
        return accuracy
    if isinstance(accuracy, QuadratureSettings):
        return ElastoPlasticSettings.from_levels(accuracy)
    return settings_for(accuracy, ELASTOPLASTIC_PRESETS)


def nested_theta_rule(breakpoints, levels: tuple[int, int]):
    """The composite tanh-sinh θ-rules of ``levels`` = (first, last) on (0, π/2), split at
    ``breakpoints``, sharing nodes: returns (theta, counts, weights) with the nodes ordered by
    the level they first appear in — level m (m = 0 for ``first``) uses theta[:counts[m]] with
    weights[m, :counts[m]] (zero beyond). theta_rule(breakpoints, level) holds the same
    nodes and weights."""
    first, last = levels
    if not (1 <= first <= last):
        raise ValueError(f"theta levels must satisfy 1 <= first <= last, got {levels}")
    edges = np.unique(np.concatenate(([0.0], np.asarray(breakpoints, float), [0.5 * math.pi])))
    index: dict[tuple[int, int], int] = {}
    theta: list[float] = []
    rows = []
    counts = []
    for L in range(first, last + 1):
        h = 2.0**-L
        n = int(math.floor(TanhSinh(L).half_width / h))
        y, w = TanhSinh(L).nodes_weights
        pos = np.arange(-n, n + 1) * 2 ** (last - L)  # the node's position on the finest level
        row = {}
        for i, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
            for k, yk, wk in zip(pos, y, w):
                key = (i, int(k))
                if key not in index:
                    index[key] = len(theta)
                    theta.append(a + (b - a) * yk)
                row[index[key]] = (b - a) * wk
        rows.append(row)
        counts.append(len(theta))
    weights = np.zeros((len(rows), len(theta)))
    for m, row in enumerate(rows):
        for j, wj in row.items():
            weights[m, j] = wj
    return np.array(theta), np.array(counts, dtype=np.int64), weights
