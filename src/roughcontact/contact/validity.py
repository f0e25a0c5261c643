"""Where the asperity contact model means something, and where its numbers can be trusted.

The model of the paper (sections 3–7; Bush, Gibson & Keogh 1975/1979; Greenwood & Williamson
1966) sums independent asperity contacts: no interaction between neighbouring contacts, no
merging of contact spots, a bulk that does not deform between them. Its range of validity
(docs/derivation.md, "Range of validity"):

* **A/A0 ≤ 1** always: the real contact area cannot exceed the nominal one. Beyond, the numbers
  have no meaning and the API refuses them (``ValueError``).
* **A/A0 ≤ AREA_RATIO_LIMIT** (0.1) for quantitative use, **measured** against an elastic
  boundary-element solution on surfaces with the same five moments (issue 21, target ``bem``,
  docs/bem.md; ContactMechanics on 512² periodic maps, 6 seeds per surface, E* = 1.14e5 N/mm²):
  the model's A/A0 stays within 20 % of the BEM's up to the loads in :data:`BEM_AGREEMENT_20`
  (Table 1's surface: to A/A0 = 0.109 at W/A0 = 200 N/mm², 20.3 % below at 0.200; the α = 3
  surface: 8.9–11.2 % below up to 0.150, the largest load solved) — the limit is the smallest of
  them, rounded down. Beyond it the model's area falls further below the
  exact one as neighbouring contacts interact and merge (Greenwood & Williamson 1966, section 4;
  Johnson, *Contact Mechanics* 1985, section 13.2). Results there come with a
  :class:`ModelValidityWarning`. Below it the model is not exact either: where the seeds agree
  its area is 17.5–20.3 % below the BEM's for Table 1's surface (never within 10 %) and 8.9–11.2 %
  below for α = 3 (the model drops m22: the maps have 1.2 times the summits of (17),
  statistics.summits); on the finer 1024² grid the BEM's areas are 2–6 % smaller still.
* **m22**: the model drops the cross moment m22 = E[z_xy²] (section 2): a Gaussian surface with
  m22 > 0 has more summits than (17) counts, by a factor that depends on ρ² = m22²/(m40 m04) only
  (the Rice formula, statistics.summits: 1.21 at ρ² = 1/9, 1.46 at 1/3). The BEM surfaces had
  ρ² = 1/9 (elliptically stretched isotropic) and 1.18–1.24 times the summits of (17) on the maps;
  there the model's area was 17.5–20.3 % (table1) and 8.9–11.2 % (alpha3) below the BEM's
  (:data:`BEM_M22`, docs/bem.md "Results" and "Why"). That is the measured effect of the m22 term
  (with asperity interaction); a surface beyond the BEM's ρ² (a ground surface: a Gaussian spread of
  the lay angle gives ρ² = 1/3) is outside what was measured — :func:`m22_effect` says so with
  its numbers, and does not make the model inapplicable (it neglects m22 for every surface).
* **s ≥ 0**: a flat below the mean plane of the heights (s = h/√m00 < 0) touches most summits;
  the model is applied far from its assumptions (ModelValidityWarning).

Numerically, the production quadrature keeps its stated accuracy ("table" ≤ 1e-13 relative to
the mpmath reference) for bandwidths μ = 1 − 1/α1 − 1/α2 ≥ ``MU_ACCURATE`` (α1 = α2 ≥ 2.02,
where the tests stop). As μ → 0 (α → 2) the summit density concentrates and the agreement
degrades (measured: 2.4e-13 at μ = 3e-3, 1.7e-10 at 1e-3, 2.8e-7 at 1e-4, 4.9e-6 at 1e-7); below
``MU_ACCURATE`` the production integrators emit an :class:`AccuracyWarning` stating this bound.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..statistics.summits import BEM_M22, m22_effect  # noqa: F401  (part of this module's API)
from ..validation import choice

__all__ = [
    "relay_warnings",
    "BEM_M22",
    "m22_effect",
    "AREA_RATIO_LIMIT",
    "BEM_AGREEMENT_20",
    "MU_ACCURATE",
    "VALIDITY_MODES",
    "ModelValidityWarning",
    "AccuracyWarning",
    "check_validity",
    "check_bandwidth",
]

#: the BEM comparison (docs/bem.md, "Results"; paper_figures/bem.md of `snakemake bem`): per
#: surface family, the model's A/A0 at the last load of the ladder where |A_model/A_BEM - 1| <= 20 %
#: and at the first load beyond it (None: still inside at the largest load solved)
BEM_AGREEMENT_20 = {"table1": (0.109, 0.200), "alpha3": (0.150, None)}
#: A/A0 above which asperity interaction (neglected by the model) puts the model's area more than
#: 20 % below the exact one: the smallest last-inside value of BEM_AGREEMENT_20, rounded down
AREA_RATIO_LIMIT = 0.1
#: smallest μ = 1 − 1/α1 − 1/α2 at which the production presets' accuracy is tested (α = 2.02)
MU_ACCURATE = 1.0 - 2.0 / 2.02
#: measured worst production ("table") vs mpmath relative difference at small μ, α1 = α2,
#: s = 1, 2, 3 (docs/derivation.md, "Range of validity"; 1e-7 from the review of issue #12)
MU_DEGRADATION = ((3e-3, 2.4e-13), (1e-3, 1.7e-10), (1e-4, 2.8e-7), (1e-7, 4.9e-6))
#: what the contact API does with results outside the range of validity:
#: "refuse" warns outside the quantitative range and raises for A/A0 > 1; "warn" only warns
#: (the paper's figures plot loads past A/A0 = 1; the workflow's sweeps say so); "off" checks
#: nothing (internal searches that check their final result themselves)
VALIDITY_MODES = ("refuse", "warn", "off")


class ModelValidityWarning(UserWarning):
    """A result lies outside the range where the asperity model is quantitative."""


class AccuracyWarning(UserWarning):
    """The production quadrature is used where its stated accuracy is not guaranteed."""


def check_validity(separation, area_ratio, *, area_ratio_limit: float = AREA_RATIO_LIMIT,
                   mode: str = "refuse") -> None:
    """Warn (:class:`ModelValidityWarning`) where s = h/√m00 < 0 or A/A0 > ``area_ratio_limit``;
    raise ``ValueError`` where A/A0 > 1 (with ``mode="warn"``: warn instead; ``"off"``: nothing).

    separation  s = h/√m00 [–], array-like; area_ratio  A/A0 [–] at the same points.
    """
    if mode not in VALIDITY_MODES:
        choice("mode", mode, VALIDITY_MODES)
    if mode == "off":
        return
    limit = float(area_ratio_limit)
    if not 0.0 < limit <= 1.0:
        raise ValueError(f"area_ratio_limit must lie in (0, 1], got {area_ratio_limit!r}")
    s = np.asarray(separation, dtype=float).reshape(-1)
    a = np.asarray(area_ratio, dtype=float).reshape(-1)
    # the fast path of every call inside the range (a few µs: Python's max beats a numpy
    # reduction on the short arrays of single calls)
    a_max, s_min = (max(a.tolist()), min(s.tolist())) if a.size <= 16 else (a.max(), s.min())
    if a_max <= limit and s_min >= 0.0:
        return
    i = int(np.argmax(a))
    if a_max > 1.0:
        message = (f"A/A0 = {a_max:.4g} > 1 at s = {s[i % s.size]:g}: the real contact area would "
                   "exceed the nominal one, the asperity model has no meaning there (give larger "
                   "separations or smaller loads)")
        if mode == "refuse":
            raise ValueError(message)
        warnings.warn(message, ModelValidityWarning, stacklevel=3)
    elif a_max > limit:
        warnings.warn(
            f"A/A0 = {a_max:.3g} at s = {s[i % s.size]:g} exceeds {limit:g}: asperity interaction, "
            "which the model neglects, is no longer small (contact.validity.AREA_RATIO_LIMIT; against a "
            "boundary-element solution the model's area is more than 20 % low beyond it, docs/bem.md)",
            ModelValidityWarning, stacklevel=3)
    if s_min < 0.0:
        warnings.warn(
            f"separation s = {s_min:g} < 0: the flat lies below the mean plane of the heights, far "
            "from the independent-asperity assumptions of the model", ModelValidityWarning, stacklevel=3)


def check_bandwidth(mu: float, method: str) -> None:
    """Warn (:class:`AccuracyWarning`) when the production integrators run at μ < MU_ACCURATE."""
    if method == "production" and mu < MU_ACCURATE:
        measured = ", ".join(f"{e:.1e} at mu = {m:g}" for m, e in MU_DEGRADATION)
        warnings.warn(
            f"mu = 1 - 1/alpha1 - 1/alpha2 = {mu:.3g} < {MU_ACCURATE:.3g} (alpha near 2): the "
            f"production quadrature's stated accuracy is tested down to mu = {MU_ACCURATE:.3g} only; "
            f"below it the agreement with the mpmath reference degrades (measured {measured}); "
            "use method='reference' to check", AccuracyWarning, stacklevel=3)


def relay_warnings(caught, *, stacklevel: int = 3) -> list[str]:
    """The warnings recorded by ``warnings.catch_warnings(record=True)`` as messages
    "Category: message", each once, in order; each is also re-emitted once, ``stacklevel``
    counted as for :func:`warnings.warn` from the caller's caller (3: the code that called the
    function recording them), so that results can carry their warnings and callers still see them."""
    first: dict = {}
    for w in caught:
        first.setdefault(f"{w.category.__name__}: {w.message}", w)
    for w in first.values():
        warnings.warn(w.message, w.category, stacklevel=stacklevel)
    return list(first)
