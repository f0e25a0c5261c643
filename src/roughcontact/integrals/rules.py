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
    "ELASTOPLASTIC_PRESETS",
    "elastoplastic_settings_for",
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
#: Presets of the elasto-plastic kernel. Measured against the scipy twin and against finer
#: settings (tests/contact/test_elastoplastic.py, test_hard_cases.py, docs/performance.md):
#: "table" ≤ 1e-11 relative on totals and on parts above 1e-3 of their total; "plot" ≤ 1e-8 —
#: for s ≥ −0.5 on every tested surface. Deeper, where the model is out of its range already
#: (s < 0, A/A0 ≈ 0.66), the bounds do not hold on the α = 2.2 surface at ψ = 5, s = −1: "plot"
#: 6.4e-7, "table" 6.2e-10 against QuadratureSettings(6, 6, 6).
ELASTOPLASTIC_PRESETS: dict[str, QuadratureSettings] = {
    "table": QuadratureSettings(theta_level=3, r_level=5, t_level=5),
    "plot": QuadratureSettings(theta_level=3, r_level=3, t_level=4),
}


def elastoplastic_settings_for(accuracy) -> QuadratureSettings:
    """Resolve an elasto-plastic accuracy preset name (or pass a QuadratureSettings through)."""
    return settings_for(accuracy, ELASTOPLASTIC_PRESETS)
