"""A :class:`~.normal_law.NormalLawTable` through given samples of a normal law instead of the
statistical model's integrators: the boundary-element (BEM) load ladder of a measured or
synthetic surface (issue 32; roughcontact.bem.law_table), or any p(h), K(h) known only at points.

Nodes and interpolant
---------------------
At n ≥ 5 samples (h_i, p_i, K_i) — h the separation (the BEM's mean gap ḡ) [L], p = W/A0
[unit of E*], K = K/A0 = −dp/dh [unit of E* per L] — the nodes are the samples themselves,
h ascending, with q = ln p, q' = −K/p and q'' from the quintic through the (q, q') data of the
node and its two neighbours (normal_law._second_derivatives): the same C² quintic Hermite
interpolant as the statistical table's, evaluated by the same kernels (closure_law), so the FE
engine, InterfaceLaw and the export see no difference. Unlike the statistical table no node can
be added: the interpolant meets the samples exactly at the nodes, and between them its error is
what the samples' spacing allows.

Stated error (``rtol``, ``max_error_pressure``, ``max_error_stiffness``): an estimate, not an
enforced bound. The table is rebuilt on every other node (0, 2, 4, … and the last) and
evaluated at the nodes left out, where the samples are known: the largest relative errors of p
and of k there are stored, and rtol is the larger of the two. The half table's nodes are twice
as far apart and the interpolant's error falls about as Δ⁵ in p and Δ⁴ in k (q'' is O(Δ⁴)),
so for a smooth law the full table's error is well below the estimate: conservative (on
samples of the statistical law, Table 1, 3–10 a decade: the error 6–55 times below it;
tests/interface/test_normal_law_samples.py).
For samples that carry noise (a BEM's K from differences of the ladder) the estimate also
measures how far p and K of the samples disagree with each other — there is no better
reference between the samples.

Monotone: q' (a quartic on every interval) must be proven negative by its Bernstein
coefficients (normal_law._slope_is_negative) on every interval, as for the statistical table;
samples whose K is too noisy for that (a K that jumps between neighbours while p does not)
are refused with ValueError naming the interval: smooth K, or use fewer, farther pressures.

Outside the samples (as the module normal_law states for every table): lighter than the
lightest sample p_light the quadratic tail p_N = p_light z², z = 1 + q'(h_light)(h − h_light)/2,
which reaches p_N = k_N = 0 at h_open = h_light + 2/|q'(h_light)| — an extrapolation, not the
BEM (the BEM's ln p keeps falling about linearly in ḡ: Persson 2007, PRL 99, 125502; the tail
under-estimates p there by at most p_light); heavier than the heaviest sample p_max nothing
(ValueError; the FE solver's trial states get the tangent tail of InterfaceLaw.extrapolated,
and a converged state beyond p_max is refused). So the computed pressure range is the law's.
"""

from __future__ import annotations

import numpy as np

from ..limits import describe
from ..statistics.surface import SpectralMoments
from ..validation import instance, positive
from .normal_law import LEVELS, _evaluate, _second_derivatives, _slope_is_negative

__all__ = ["MIN_SAMPLES", "sampled_table", "leave_out_error"]

#: the error estimate needs a table on every other sample with ≥ 3 nodes of its own
MIN_SAMPLES = 5


def _samples(h, p, k):
    """(h, p, k) as float arrays sorted by h ascending, checked: finite, same length ≥ 5,
    p > 0 falling strictly with h, k > 0, h distinct."""
    arrays = []
    for name, x in (("h", h), ("p", p), ("k", k)):
        try:
            a = np.array(x, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            raise ValueError(f"samples {name} must be numbers, got {describe(x)}") from None
        if not np.all(np.isfinite(a)):
            raise ValueError(f"samples {name} must be finite, got {describe(a[~np.isfinite(a)][0])}")
        arrays.append(a)
    h, p, k = arrays
    if not (h.size == p.size == k.size) or h.size < MIN_SAMPLES:
        raise ValueError(f"h, p and k need one length >= {MIN_SAMPLES} (the error estimate leaves every other "
                         f"sample out), got {h.size}, {p.size}, {k.size}")
    if np.any(p <= 0.0) or np.any(k <= 0.0):
        raise ValueError("samples p and k must be positive")
    order = np.argsort(h, kind="stable")
    h, p, k = h[order], p[order], k[order]
    if np.any(np.diff(h) <= 0.0):
        i = int(np.flatnonzero(np.diff(h) <= 0.0)[0])
        raise ValueError(f"two samples at the same separation h = {h[i]:g}")
    if np.any(np.diff(p) >= 0.0):
        i = int(np.flatnonzero(np.diff(p) >= 0.0)[0])
        raise ValueError(f"p must fall as h grows: p = {p[i]:g} at h = {h[i]:g}, p = {p[i + 1]:g} at h = {h[i + 1]:g}")
    return h, p, k


def _kernel_table(h, p, k) -> np.ndarray:
    """(n, 4) rows (h, q, q', q'') of the samples (module docstring)."""
    q = np.log(p)
    dq = -k / p
    return np.ascontiguousarray(np.column_stack([h, q, dq, _second_derivatives(h, q, dq)]))


def leave_out_error(h, p, k) -> tuple[float, float]:
    """(largest relative error of p, of k) of the table on every other sample (0, 2, 4, … and
    the last), at the samples left out (module docstring: the stated error)."""
    h, p, k = _samples(h, p, k)
    keep = np.zeros(h.size, dtype=bool)
    keep[::2] = True
    keep[-1] = True
    half = _kernel_table(h[keep], p[keep], k[keep])
    p_i, k_i, _ = _evaluate(half, 0.0, -h[~keep], None)
    return float(np.max(np.abs(p_i / p[~keep] - 1.0))), float(np.max(np.abs(k_i / k[~keep] - 1.0)))


def sampled_table(cls, h, p, k, *, surface, E_star, level="bem"):
    """The :class:`~.normal_law.NormalLawTable` ``cls`` through the samples (module docstring).

    h [L], p [unit of E*], k [unit of E*/L]: arrays of one length ≥ 5 in any order of h.
    surface : the surface's SpectralMoments (in L; for Mindlin's ratio and the stated lay);
    E_star : the contact modulus the samples were computed with [unit of p];
    level : the name of the law's source (not one of the integrated LEVELS), e.g. "bem"."""
    instance("surface", surface, SpectralMoments)
    E = positive("E_star", E_star)
    if not isinstance(level, str) or not level.strip() or level in LEVELS:
        raise ValueError(f"level of a sampled law must name its source (not {', '.join(LEVELS)}), got {describe(level)}")
    h, p, k = _samples(h, p, k)
    tab = _kernel_table(h, p, k)
    monotone = _slope_is_negative(tab)
    if not monotone.all():
        i = int(np.flatnonzero(~monotone)[0])
        raise ValueError(
            f"the interpolant through the samples is not proven to fall between h = {h[i]:g} and {h[i + 1]:g} "
            f"(p = {p[i]:g} ... {p[i + 1]:g}, k = {k[i]:g} ... {k[i + 1]:g}): the stiffness samples are too "
            "noisy for their spacing; smooth them or use fewer, farther pressures")
    err_p, err_k = leave_out_error(h, p, k)
    return cls(*tab.T.copy(), level=level, hertz="none", surface=surface, E_star=E, material=None,
               accuracy="samples", rtol=max(err_p, err_k), max_error_pressure=err_p,
               max_error_stiffness=err_k, n_evaluations=int(h.size))
