"""The summit table: elasto-plastic columns at any separation from one table per material (issue 33).

In the polar variables of docs/derivation.md the summit measure of the elasto-plastic
integrals (78)–(85) is cos θ sin θ · r³ e^{−r²/2} φ(t + l − r g(θ)) dt dr dθ, and the
per-asperity law depends on the interference t and on the curvature r c(θ), not on l. With
y = g r − t the Gaussian is φ(l − y), so every column (A^e, A^ep, A^p, W^e, W^ep, W^p, dW/dω and
the load-jump density) is a Gaussian convolution

    column(l) = ∫ φ(l − y) ρ(y) dy,
    ρ(y) = Σ_θ w_θ ∫_{r ≥ max(0, y/g)} law(σ (g r − y), r c) r³ e^{−r²/2} dr        (1)

(Fubini; for the load jump, the density of y = g r − t_c1/r at the first-yield hyperbola,
errata E17). ρ depends on the surface and the material, not on the separation: it is built
once (:class:`SummitTable`) and every separation of a curve, a sweep or a law table is the
1-D quadrature (1) over it.

Construction and error bound
----------------------------
* ρ(y_i) at Chebyshev–Lobatto nodes on panels of y (split at y = 0, where ρ is not analytic:
  the corner r = t = 0 of the domain), by the numba kernel ``kernels._st_rho_array``: θ by the
  preset's nested tanh-sinh levels until the estimated θ-error ≤ theta_tol (relative per
  column, parts floored at 1e-3 of their total); r by Gauss–Legendre in w = √(r − r0) on
  regime pieces, graded towards the corner (kernels.py, "The summit table").
* ln ρ is interpolated per panel; a panel is bisected until the last two Chebyshev
  coefficients of every column are ≤ ``interp_tol`` (absolute in ln ρ = relative in ρ; for a
  part below 1e-3 of its total, relative to that floor). A part that is exactly 0 at some
  nodes of a panel (a regime beyond the r-range's e^{−55} end) is interpolated there as its
  fraction of its total, with ln of the total (:func:`_panel_fit`). The largest accepted tail is the
  table's measured interpolation bound (``SummitTable.interp_error``).
* (1) by Gauss–Legendre on panels of width ≤ ``conv_width`` (split at y = 0) over
  [min(l, 0) − 11, max(l, 0) + 11]: φ(11)/φ(0) = 6e-27.

A pointwise relative error ε of ρ gives at most ε relative error of every column (φ > 0,
ρ > 0), so the θ- and interpolation tolerances bound the columns directly. The whole chain is
checked against the τ = r t route and the scipy twin, and by refinement
(tests/integrals/test_summit_table.py).

The shared build (:func:`build_tables`)
---------------------------------------
Eq. (65) gives t_c1(θ) = β T(θ) with β = (K_Y Y/E*)² the only material factor, so in
u = τ/T(θ) (τ = r t) the regime boundaries are u = β and u = Rβ (R = ω_p/ω_c) for every θ,
and each law piece is a material-free density of v = ln u times a function of u and the
material's constants (kernels.py, "The shared summit table"). Per y the seven densities
D_q(y, v) (θ-sums at fixed v on the curve g r − t = y) are tabulated once on Chebyshev panels
of v (ln D_q, tails ≤ the interpolation tolerance); every material's ρ(y) is then cumulative
integrals of D at ln β and ln(Rβ), a Gauss–Legendre integral of the elasto-plastic law (76),
(75), (77) over [ln β, ln Rβ] and, with a load jump, a θ-sum at v = ln β. The y-panels are
refined until every material's ln ρ meets the tolerance, and each material's table is built
as above. For a sweep over ψ (or Y, E*, c_h, ω_p/ω_c) at fixed moments: one build per surface
(tests/integrals/test_summit_table_shared.py: against the per-material build, the τ route and
the scipy twin).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from .kernels import _sh_rho_array, _st_columns, _st_rho_array
from .rules import elastoplastic_settings_for, gauss_legendre

__all__ = ["TableSettings", "table_settings_for", "SummitTable", "build_table", "build_tables", "shared_scale"]

#: the convolution range beyond the separations: φ(11)/φ(0) = e^{−60.5}
Y_MARGIN = 11.0
#: initial interpolation panels: edges at ±1, ±4, then every PANEL_WIDTH (the last within 1 of the end dropped)
PANEL_WIDTH = 8.0
#: initial edges |y| of the shared build, graded towards the corner y = 0
GRADED = (0.125, 0.25, 0.5, 1.0, 2.5, 4.0)
MAX_BISECTIONS = 6
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)


@dataclass(frozen=True)
class TableSettings:
    """Rules of the summit table. theta_levels, theta_tol: the θ rule (as the τ-route's preset);
    r_nodes, dr_max: Gauss–Legendre nodes per r-piece and the longest piece in r; degree,
    interp_tol: Chebyshev degree of a y-panel and the tolerance of its last coefficients (ln ρ);
    conv_nodes, conv_width: the Gauss–Legendre rule of the convolution (1) per y-panel."""

    theta_levels: tuple[int, int]
    theta_tol: float
    r_nodes: int
    dr_max: float
    degree: int
    interp_tol: float
    conv_nodes: int
    conv_width: float


def table_settings_for(accuracy) -> TableSettings:
    """The table's rules for an elasto-plastic accuracy (preset name, ElastoPlasticSettings or
    QuadratureSettings): θ as the preset; the interpolation tolerance its θ-tolerance (a
    Chebyshev tail below the θ-rule's own noise cannot be asked for: a tenth of it forced
    bisections to the limit); the r-rule finer (measured: 1e-11–1e-13 at "plot") ("plot": θ-tol
    1e-9, "table": 1e-12). The convolution: 14 Gauss–Legendre nodes on panels ≤ 2 wide at both
    presets. Measured against the τ route at QuadratureSettings(6, 6, 6) (issue 33,
    2026-11-28): the former "plot" rule, 10 nodes on panels ≤ 3, left 2.2e-8 on K at s = 6 of
    the m04/m40 = 1e4 surface (1.2e-8 on A; 6.7e-9 at s = 3 against the mpmath elastic limit),
    above the "plot" bound; 14 on ≤ 2 leaves ≤ 1.1e-12 there and on Table 1, Table 2, the
    α1 = 4, α2 = 5 and the α = 2.2 surfaces for ψ = 0.05 … 50, s = −1 … 6
    (tests/integrals/test_summit_table_references.py). The rule costs the warm separation
    only (the table's ρ-nodes are the y-panels', not the convolution's)."""
    st = elastoplastic_settings_for(accuracy)
    tol = st.theta_tol if st.theta_tol > 0.0 else 1e-9
    fine = tol < 1e-10
    return TableSettings(
        theta_levels=st.theta_levels,
        theta_tol=tol,
        r_nodes=20 if fine else 14,
        dr_max=0.8 if fine else 1.2,
        degree=24 if fine else 16,
        interp_tol=max(tol, 1e-14),
        conv_nodes=14,  # both presets: 10 on panels ≤ 3 wide left 2.2e-8 at "plot" (m04/m40 = 1e4, s = 6)
        conv_width=2.0,
    )


def _lobatto(lo, hi, n):
    return 0.5 * (hi + lo) + 0.5 * (hi - lo) * np.cos(np.pi * np.arange(n + 1) / n)


def _cheb_coefficients(values: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients of the interpolant through values at the Lobatto nodes
    cos(πk/n), k = 0…n (first axis), the other axes independent (DCT-I)."""
    n = values.shape[0] - 1
    k = np.arange(n + 1)
    T = np.cos(np.pi * np.outer(k, k) / n)
    w = np.ones(n + 1)
    w[0] = w[-1] = 0.5
    c = ((2.0 / n) * (T * w[None, :]) @ values.reshape(n + 1, -1)).reshape(values.shape)
    c[0] *= 0.5
    c[-1] *= 0.5
    return c


def _group_log_totals(L: np.ndarray) -> np.ndarray:
    """ln of the area and load totals (parts 0–2, 3–5) and of K (column 6, the load jump's total)
    at the nodes, shape (m, n_mat, 3)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.stack([np.logaddexp.reduce(L[..., 0:3], axis=-1), np.logaddexp.reduce(L[..., 3:6], axis=-1),
                         L[..., 6]], axis=-1)


def _panel_fit(L: np.ndarray, ks):
    """The interpolants of one panel for n materials from ln ρ at its Lobatto nodes (L: (n+1,
    n_mat, 8), −inf where a column is 0; ks: the columns in use per material) and their errors:
    the largest of the last two Chebyshev coefficients, per column relative to its floor (a part
    below 1e-3 of its total needs only 1e-3 of the total: parts A^e, A^ep, A^p; W^e, W^ep, W^p;
    the rest alone).

    A column is interpolated in ln ρ where it is positive at every node. A part that is 0 at
    some nodes (the r-range ends e^{−55} beyond the summit bulk, so a regime out of reach is
    exactly 0) is dropped where it stays below 1e-30 of its total on the whole panel, else
    interpolated as the fraction ρ_q/ρ_total (absolute error relative to the 1e-3 floor)
    together with ln ρ_total; so is the load jump (its total K, floor 1e-3 of K: the parts'
    convention for the part of K it is) where it is 0 at some nodes (first yield beyond the
    exponent range: e^{−r²/2} underflows). Returns per material (error, fit) with fit =
    (ln-coefficients (n+1, 8), ln-total coefficients (n+1, 3), fraction coefficients (n+1, 8),
    kind per column: 0 ln, 1 zero, 2 fraction); error inf and fit None when K is 0 at some
    nodes only."""
    floored = ~np.isfinite(L).all(axis=0)  # (n_mat, 8)
    Lt = _group_log_totals(L)
    tot = np.concatenate([Lt[..., [0, 0, 0]], Lt[..., [1, 1, 1]], L[..., 6:]], axis=-1)
    with np.errstate(invalid="ignore"):
        rel = np.where(np.isfinite(tot), np.exp(L - tot), 0.0)  # part / its total (1 for K and the jump)
        jump = np.where(np.isfinite(Lt[..., 2]), np.exp(L[..., 7] - Lt[..., 2]), 0.0)  # jump / K
    rel[..., 7] = np.where(floored[None, :, 7], jump, rel[..., 7])
    Lf = np.where(np.isfinite(L), L, -745.0)  # the ln-interpolant of a floored column is not used
    Lt = np.where(np.isfinite(Lt), Lt, -745.0)
    coef_ln = _cheb_coefficients(Lf)
    coef_tot = _cheb_coefficients(Lt)
    coef_fr = _cheb_coefficients(rel) if floored.any() else np.zeros_like(coef_ln)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        relief = np.maximum(1.0, 1e-3 / rel)
    tail_ln = np.abs(coef_ln[-2:]).max(axis=0) / relief.min(axis=0)  # (n_mat, 8)
    tail_fr = np.abs(coef_fr[-2:]).max(axis=0) / 1e-3
    tail_tot = np.abs(coef_tot[-2:]).max(axis=0)  # (n_mat, 3)
    zero = (rel < 1e-30).all(axis=0)
    out = []
    for m, k in enumerate(ks):
        kind = np.zeros(8, dtype=int)
        kind[k:] = 1
        err = 0.0
        fit_ok = True
        for q in range(k):
            if not floored[m, q]:
                err = max(err, float(tail_ln[m, q]))
            elif zero[m, q]:
                kind[q] = 1
            elif q != 6:  # a part, or the load jump as a part of K (floor 1e-3 of K)
                kind[q] = 2
                err = max(err, float(tail_fr[m, q]), float(tail_tot[m, q // 3]))
            else:
                fit_ok = False
                break
        if not fit_ok:
            out.append((math.inf, None))
            continue
        fr = np.where(kind[None, :] == 2, coef_fr[:, m], 0.0)
        out.append((err, (coef_ln[:, m], coef_tot[:, m], fr, kind)))
    return out


def _panel_eval(fits, x: np.ndarray) -> np.ndarray:
    """ln ρ at x ∈ [−1, 1] from one panel's fits of n materials (:func:`_panel_fit`), shape
    (x.size, n_mat, 8)."""
    cheb = np.polynomial.chebyshev.chebval
    coef_ln = np.stack([f[0] for f in fits], axis=1)
    kind = np.stack([f[3] for f in fits])
    L = np.moveaxis(cheb(x, coef_ln), -1, 0)
    if (kind == 2).any():
        Lt = np.moveaxis(cheb(x, np.stack([f[1] for f in fits], axis=1)), -1, 0)
        fr = np.moveaxis(cheb(x, np.stack([f[2] for f in fits], axis=1)), -1, 0)
        with np.errstate(divide="ignore"):
            for m, q in zip(*np.nonzero(kind == 2)):
                L[:, m, q] = np.log(np.maximum(fr[:, m, q], 0.0)) + Lt[:, m, q // 3]
    L[:, kind == 1] = -np.inf
    return L


@dataclass
class SummitTable:
    """ρ of (1) for one surface and material: Gauss–Legendre nodes ``y`` of the convolution with
    ``log_scale`` (max over the columns of ln ρ) and ``weights`` (n_y, 8) = w_j ρ_q(y_j)
    e^{−log_scale}/√(2π). ``interp_error``: the largest accepted Chebyshev tail (ln ρ);
    ``theta_error``: the largest estimated θ-error; ``evaluations``: ρ-nodes computed."""

    y: np.ndarray
    log_scale: np.ndarray
    weights: np.ndarray
    y_range: tuple[float, float]
    interp_error: float
    theta_error: float
    evaluations: int

    @property
    def nbytes(self) -> int:
        """Memory held by the table's arrays [bytes]."""
        return int(self.y.nbytes + self.log_scale.nbytes + self.weights.nbytes)

    def covers(self, l_lo: float, l_hi: float) -> bool:
        return self.y_range[0] <= min(l_lo, 0.0) - Y_MARGIN and self.y_range[1] >= max(l_hi, 0.0) + Y_MARGIN

    def columns(self, l_values) -> np.ndarray:
        """The eight columns at each l, shape (n_l, 8): (1) by the table's quadrature."""
        l_values = np.atleast_1d(np.asarray(l_values, dtype=float))
        if not np.all(np.isfinite(l_values)):
            raise ValueError("separations must be finite")
        if l_values.size and not self.covers(float(l_values.min()), float(l_values.max())):
            raise ValueError(f"l in [{l_values.min():g}, {l_values.max():g}] is outside the table's range {self.y_range}")
        out = np.empty((l_values.size, self.weights.shape[1]))
        _st_columns(np.ascontiguousarray(l_values), self.y, self.log_scale, self.weights, out)
        return out


def build_table(nodes, tc1, sigma, constants, accuracy, l_lo: float, l_hi: float) -> SummitTable:
    """The summit table of one material over separations l ∈ [l_lo, l_hi].

    ``nodes``: the θ-node dict of contact.elastoplastic (g, c, f1, f2, f3, counts, weights);
    ``tc1``: t_c1 per θ-node; ``constants``: (E*, ω_p/ω_c, c_h H, H (c_h − (2/3) K_v),
    (2/3) K_v H, with_jump) as for the τ-route (contact.elastoplastic._material_constants)."""
    st = table_settings_for(accuracy)
    g = np.ascontiguousarray(nodes["g"], dtype=float)
    arr = [np.ascontiguousarray(nodes[k], dtype=float) for k in ("c", "f1", "f2", "f3")]
    tc1 = np.ascontiguousarray(tc1, dtype=float)
    counts = np.ascontiguousarray(nodes["counts"], dtype=np.int64)
    weights = np.ascontiguousarray(nodes["weights"], dtype=float)
    E_star, ratio, cH, dp, pv, with_jump = constants
    yq, wq = gauss_legendre(st.r_nodes)
    g_max = float(g.max())
    y_lo = min(l_lo, 0.0) - Y_MARGIN
    y_hi = max(l_hi, 0.0) + Y_MARGIN
    evaluations = [0]
    theta_err = [0.0]

    def rho(y):
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty((y.size, 8))
        info = np.empty((y.size, 2))
        _st_rho_array(y, g, *arr, tc1, weights, counts, float(sigma), float(E_star), float(ratio), float(cH),
                      float(dp), float(pv), bool(with_jump), g_max, yq, wq, st.dr_max, st.theta_tol, out, info)
        evaluations[0] += y.size
        finite = info[:, 1][np.isfinite(info[:, 1])]
        if finite.size:
            theta_err[0] = max(theta_err[0], float(finite.max()))
        # the kernel returns −745 − S for a column that is 0 (S = y²/(2 g_max²) for y > 0 its scale)
        S = np.where(y > 0.0, 0.5 * y * y / (g_max * g_max), 0.0)
        out[out <= (-745.0 - S + 1e-9)[:, None]] = -np.inf
        if not with_jump:
            out[:, 7] = -np.inf
        return out

    panels, worst = _adaptive_panels(lambda y: rho(y)[:, None, :], y_lo, y_hi, st, [8 if with_jump else 7])
    return _tables(panels, st, [bool(with_jump)], y_lo, y_hi, worst, theta_err[0], evaluations[0])[0]


def _next_edge(x: float, graded: bool) -> float:
    if graded and x < GRADED[-1]:
        return GRADED[GRADED.index(x) + 1]
    return 4.0 if x < 4.0 else x + PANEL_WIDTH


def _adaptive_panels(rho_many, y_lo: float, y_hi: float, st: TableSettings, ks, graded: bool = False):
    """The y-panels of ln ρ for n materials at once: ``rho_many(y)`` → ln ρ, shape (y.size, n, 8)
    (−inf where a column is 0); ``ks``: the columns in use per material. A panel is bisected
    until every material's fit (:func:`_panel_fit`) is within ``st.interp_tol``. Initial edges
    0, ±1, ±4, then every PANEL_WIDTH; ``graded``: 0, ±GRADED, then as before (the grading
    towards the corner y = 0 that the bisections of a sweep's materials reach: measured on
    Table 1, ψ = 0.05 … 50, it saves the evaluations of the panels they reject). Returns
    (the accepted panels (lo, hi, fits per material) sorted, per material the largest accepted error)."""
    edges = [0.0]
    for side, end in ((-1.0, y_lo), (1.0, y_hi)):
        x = GRADED[0] if graded else 1.0
        while x < abs(end) - 1.0:  # no sliver panel at the end
            edges.append(side * x)
            x = _next_edge(x, graded)
        edges.append(end)
    edges = np.unique(edges)
    todo = [(a, b, 0) for a, b in zip(edges[:-1], edges[1:])]
    n = len(ks)
    panels = []
    worst = np.zeros(n)
    while todo:
        ys = np.concatenate([_lobatto(a, b, st.degree) for a, b, _ in todo])
        vals = rho_many(ys).reshape(len(todo), st.degree + 1, n, 8)
        nxt = []
        for (a, b, depth), L in zip(todo, vals):
            fits = _panel_fit(L, ks)
            if all(err <= st.interp_tol or (depth >= MAX_BISECTIONS and fit is not None) for err, fit in fits):
                worst = np.maximum(worst, [err for err, _ in fits])
                panels.append((a, b, [fit for _, fit in fits]))
            elif depth >= MAX_BISECTIONS:
                raise ArithmeticError(f"summit table: K is 0 at some y in [{a:g}, {b:g}] only")
            else:
                m = 0.5 * (a + b)
                nxt += [(a, m, depth + 1), (m, b, depth + 1)]
        todo = nxt
    panels.sort(key=lambda x: x[0])
    return panels, worst


def _tables(panels, st: TableSettings, jumps, y_lo, y_hi, worst, theta_err, evaluations) -> list[SummitTable]:
    """The convolution's Gauss–Legendre nodes over the panels and ln ρ there from the panels'
    interpolants: one :class:`SummitTable` per material (jumps: with a load jump, per material)."""
    gy, gw = gauss_legendre(st.conv_nodes)
    ys, ws, Ls = [], [], []
    for a, b, fits in panels:
        m = max(1, int(math.ceil((b - a) / st.conv_width)))
        h = (b - a) / m
        y = (a + h * (np.arange(m)[:, None] + gy[None, :])).ravel()
        ys.append(y)
        ws.append(np.tile(h * gw, m))
        Ls.append(_panel_eval(fits, (2.0 * y - a - b) / (b - a)))
    y = np.concatenate(ys)
    w = np.concatenate(ws)
    L = np.concatenate(Ls)  # (n_y, n_mat, 8)
    L[:, ~np.asarray(jumps, dtype=bool), 7] = -np.inf
    scale = L.max(axis=2)
    scale = np.where(np.isfinite(scale), scale, -745.0)  # every column 0 there
    V = np.exp(L - scale[:, :, None]) * (w * _INV_SQRT_2PI)[:, None, None]
    return [SummitTable(y, np.ascontiguousarray(scale[:, k]), np.ascontiguousarray(V[:, k]), (float(y_lo), float(y_hi)),
                        float(worst[k]), theta_err, evaluations) for k in range(L.shape[1])]


#: Gauss–Legendre nodes of the v-integrals of the shared build (a panel's ln D varies by ≤ 8:
#: the integrals of e^{ln D} are exact to rounding with 20 nodes)
SHARED_GL_NODES = 20


def shared_scale(tc1s) -> np.ndarray | None:
    """β_k with t_c1 of material k = β_k · t_c1 of material 0 at every θ-node (eq. (65): the
    material enters ω_c only through (K_Y Y/E*)²), or None if some material's t_c1 is not such
    a multiple (then the materials cannot share a build)."""
    tc1s = np.asarray(tc1s, dtype=float)
    ratio = tc1s / tc1s[0][None, :]
    beta = np.median(ratio, axis=1)
    if not np.allclose(ratio, beta[:, None], rtol=1e-12, atol=0.0):
        return None
    return beta


def build_tables(nodes, tc1s, sigma, constants, accuracy, l_lo: float, l_hi: float) -> list[SummitTable]:
    """The summit tables of several materials of one surface from one build (the "shared build").

    ``tc1s``: t_c1 per material and θ-node, each a multiple β_k of the first (:func:`shared_scale`);
    ``constants``: per material as for :func:`build_table`. With T(θ) = t_c1 of the first
    material, every law piece is a material-free density of v = ln(τ/T(θ)) times a function of
    the material (kernels.py, "The shared summit table"): per y the seven densities D_q(y, v)
    are θ-sums at fixed v (the θ rule of the preset, levels added to θ-tol relative per
    density, floored at 1e-4 of its bulk value), ln D_q is interpolated on Chebyshev panels of v
    (tails ≤ the table's interpolation tolerance, relieved below 1e-3 of D_q's largest), and each
    material's ρ(y) is the cumulative integral of D up to ln β, from ln(Rβ) on, and a Gauss–
    Legendre integral over [ln β, ln Rβ] of the elasto-plastic law (76), (75), (77) against D.
    The y-panels are bisected until every material's ln ρ meets the tolerance; each material's
    table is then that of :func:`build_table` (same convolution). Cost: one set of densities
    per y for all materials instead of one r-quadrature per (y, θ, material)."""
    st = table_settings_for(accuracy)
    beta = shared_scale(tc1s)
    if beta is None:
        raise ValueError("build_tables: the materials' critical interferences are not multiples of one another "
                         "(eq. (65)); build one table per material")
    g = np.ascontiguousarray(nodes["g"], dtype=float)
    c = np.asarray(nodes["c"], dtype=float)
    T = np.asarray(tc1s[0], dtype=float)
    f1, f2, f3 = (np.asarray(nodes[k], dtype=float) for k in ("f1", "f2", "f3"))
    h1 = np.ascontiguousarray(f1 / c)
    h3 = np.ascontiguousarray(f3 / c)
    h2 = np.ascontiguousarray(f2 / np.sqrt(c))
    h2t = np.ascontiguousarray(h2 * np.sqrt(T))
    lnT = np.ascontiguousarray(np.log(T))
    counts = np.ascontiguousarray(nodes["counts"], dtype=np.int64)
    weights = np.ascontiguousarray(nodes["weights"], dtype=float)
    cons = np.array([[E, math.log(ratio), cH, dp, pv] for E, ratio, cH, dp, pv, _ in constants], dtype=float)
    jumps = np.array([bool(j) for *_, j in constants], dtype=np.bool_)
    lnb = np.ascontiguousarray(np.log(beta))
    lnR, E_star, cHs, dps, pvs = (np.ascontiguousarray(cons[:, k]) for k in (1, 0, 2, 3, 4))
    xg, wg = gauss_legendre(SHARED_GL_NODES)
    g_max = float(g.max())
    y_lo = min(l_lo, 0.0) - Y_MARGIN
    y_hi = max(l_hi, 0.0) + Y_MARGIN
    v_tol = st.interp_tol
    n = len(constants)
    evaluations = [0]
    theta_err = [0.0]

    def rho_many(y):
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty((y.size, n, 8))
        info = np.empty((y.size, 5))
        n_blocks = max(1, min(y.size, 4 * numba.get_num_threads()))  # as before; an argument: the kernel caches
        _sh_rho_array(n_blocks, y, g, h1, h3, h2, h2t, lnT, weights, counts, g_max, st.theta_tol, v_tol, xg, wg, lnb,
                      lnR, float(sigma), E_star, cHs, dps, pvs, jumps, out, info)
        evaluations[0] += int(info[:, 1].sum())
        theta_err[0] = max(theta_err[0], float(info[:, 0].max()))
        if not np.all(info[:, 2] <= v_tol):
            bad = y[~(info[:, 2] <= v_tol)]
            raise ArithmeticError(f"summit table (shared build): the v-panels missed the tolerance {v_tol:g} "
                                  f"at y = {bad[0]:g} (largest tail {info[:, 2].max():g})")
        S = np.where(y > 0.0, 0.5 * y * y / (g_max * g_max), 0.0)
        out[out <= (-745.0 - S + 1e-9)[:, None, None]] = -np.inf
        out[:, ~jumps, 7] = -np.inf
        return out

    panels, worst = _adaptive_panels(rho_many, y_lo, y_hi, st, [8 if j else 7 for j in jumps], graded=True)
    return _tables(panels, st, jumps, y_lo, y_hi, worst, theta_err[0], evaluations[0])
