"""The production integrators: the Python side of the numba kernels (:mod:`.kernels`).

Each function validates and lays out its arrays (C-contiguous, writable float64: one numba
signature per kernel), picks the rules of an accuracy preset (:mod:`.rules`) and runs the
serial or threaded kernel. Callers: :mod:`roughcontact.contact` (which applies θ-weights,
prefactors and D_sum) and the tests.
"""

from __future__ import annotations

import functools
import math

import numba
import numpy as np

from . import normal_moments
from .kernels import (
    _asperity_law_array,
    _elastic_inner_array,
    _elastic_rows,
    _elastic_rows_parallel,
    _ep_rows,
    _ep_rows_parallel,
    _ep_grid_values,
    _hyperbola_at_zero_array,
    _hyperbola_moments_array,
    _moments_array,
)
from .rules import elastoplastic_settings_for, gauss_legendre, settings_for

__all__ = [
    "gaussian_moments",
    "normal_moment",
    "elastic_inner_integrals",
    "polar_elastic_integrals",
    "asperity_law",
    "hyperbola_moments",
    "hyperbola_moments_at_zero",
    "hyperbola_grid_values",
    "polar_elastoplastic_integrals",
]

#: the batch is split over threads only above this many separations (a parallel region
#: costs 10–500 µs on a loaded 2-core machine; one separation is 20–100 µs of work)
PARALLEL_MIN = 8


# ---------------------------------------------------------------------------------------
# J_ν(a) from the polynomial tables (Chebyshev interpolants, normal_moments.py)
# ---------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=1)
def _moment_table() -> np.ndarray:
    """normal_moments.table(), shape (piece, ν, power); passed to the kernels as an argument
    (numba would freeze a global array into its cache, which is invalidated only when this
    file changes, not the data file)."""
    return normal_moments.table()


def gaussian_moments(a) -> np.ndarray:
    """J_ν(a) = E[(Z + a)₊^ν] for ν = 0, 1/2, 1, 3/2 (columns), Z ~ N(0, 1), from the
    Chebyshev tables of normal_moments.py: ≤ 7e-16 relative for every a (measured against
    mpmath, tests/integrals/test_normal_moments.py); exactly 0 below a ≈ −38.6, where J_ν < φ(a)
    underflows."""
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(a, dtype=float)))
    if not np.all(np.isfinite(a)):
        raise ValueError("normal_moment: arguments must be finite")
    out = np.empty((a.shape[0], 4))
    _moments_array(a, _moment_table(), out)
    return out


def normal_moment(a, accuracy=None) -> np.ndarray:
    """J_ν(a) for ν = 1/2, 1, 3/2 (columns) — :func:`gaussian_moments` without J_0. GW's
    F_ν(d) = J_ν(−d). ``accuracy`` is accepted for compatibility and ignored (closed form)."""
    return gaussian_moments(a)[:, 1:]


def _use_threads(n_rows: int) -> bool:
    return n_rows >= PARALLEL_MIN and numba.get_num_threads() > 1


def polar_elastic_integrals(l_values, w_area, w_load, g, accuracy="table", *, interpolate=True,
                            return_used=False):
    """The dimensionless (θ, r, t) integrals at each l; columns (area, load, stiffness).

    ``w_area``, ``w_load``, ``g`` are per θ-node: θ-weight × cos θ sin θ × f1/c (resp. f2/√c)
    and g(θ) (see contact/elastic.py for how they are built). ``interpolate=False`` skips the
    Chebyshev interpolation in g (the slow path, for tests). ``return_used``: also return
    a bool array, True where the interpolation converged (else the direct θ-sum was used)."""
    l_values = np.ascontiguousarray(np.atleast_1d(np.asarray(l_values, dtype=float)))
    if not np.all(np.isfinite(l_values)):
        raise ValueError("separations must be finite")
    st = settings_for(accuracy)
    y, w = gauss_legendre(st.r_nodes)
    args = (
        l_values,
        np.ascontiguousarray(w_area, dtype=float),
        np.ascontiguousarray(w_load, dtype=float),
        np.ascontiguousarray(g, dtype=float),
        y,
        w,
        float(st.g_tol),
        bool(interpolate),
        _moment_table(),
    )
    out = np.empty((l_values.shape[0], 3))
    used = np.zeros(l_values.shape[0], dtype=np.int64)
    if _use_threads(l_values.shape[0]):
        _elastic_rows_parallel(numba.get_num_threads(), *args, out, used)
    else:
        _elastic_rows(np.arange(l_values.shape[0]), *args, out, used)
    return (out, used.astype(bool)) if return_used else out


def elastic_inner_integrals(g, l, accuracy="table") -> np.ndarray:
    """The inner r-integrals (I_area, I_load, I_stiffness) at pairs (g, l), as the kernels
    compute them (for the tests: a twin with scipy.integrate.quad checks the r-rule)."""
    g, l = np.broadcast_arrays(np.asarray(g, dtype=float), np.asarray(l, dtype=float))
    g = np.array(g.reshape(-1))  # writable copies (broadcast views would type as read-only)
    l = np.array(l.reshape(-1))
    if not (np.all(np.isfinite(g)) and np.all(g > 0) and np.all(np.isfinite(l))):
        raise ValueError("g must be finite and positive, l finite")
    y, w = gauss_legendre(settings_for(accuracy).r_nodes)
    out = np.empty((g.shape[0], 3))
    _elastic_inner_array(g, l, y, w, _moment_table(), out)
    return out


def asperity_law(omega, kappa, f1, f2, f3, wc, E_star, ratio, cH, dp) -> np.ndarray:
    """The numba per-asperity law at arrays of points; columns (A, W, dW/dω, regime).
    Mirrors asperity.respond (used by the tests to compare the two)."""
    arrs = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (omega, kappa, f1, f2, f3, wc)))
    flat = [np.array(a.reshape(-1)) for a in arrs]  # writable copies: one kernel signature
    out = np.empty((flat[0].shape[0], 4))
    _asperity_law_array(*flat, float(E_star), float(ratio), float(cH), float(dp), math.log(ratio), out)
    return out


def hyperbola_moments(tau, g, l, accuracy="table") -> np.ndarray:
    """(ln G_0, ln G_1) at arrays of (τ, g, l), G_k(τ) = ∫_0^∞ r^k e^{−r²/2} φ(τ/r + l − g r) dr:
    the summit measure on the hyperbola r t = τ, as the elasto-plastic kernel computes it (for
    the tests: a twin with scipy.integrate.quad checks it)."""
    arrs = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (tau, g, l)))
    tau, g, l = (np.array(a.reshape(-1)) for a in arrs)  # writable copies: one kernel signature
    if not (np.all(tau > 0) and np.all(g > 0) and np.all(np.isfinite(l)) and np.all(np.isfinite(tau))
            and np.all(np.isfinite(g))):
        raise ValueError("tau and g must be finite and positive, l finite")
    st = elastoplastic_settings_for(accuracy)
    out = np.empty((tau.shape[0], 2))
    _hyperbola_moments_array(tau, g, l, float(st.hyperbola_step), float(st.hyperbola_width_fraction), out)
    return out


def hyperbola_moments_at_zero(g, l) -> np.ndarray:
    """(ln G_0, ln G_1) at τ = 0 in closed form (the kernel's normal-moment formula), at arrays of
    (g, l)."""
    g, l = (np.array(a.reshape(-1)) for a in np.broadcast_arrays(np.asarray(g, float), np.asarray(l, float)))
    out = np.empty((g.shape[0], 2))
    _hyperbola_at_zero_array(g, l, _moment_table(), out)
    return out


def hyperbola_grid_values(l, g_range, tau, g, accuracy="table"):
    """ln G_0, ln G_1 at (τ, g) from the interpolation grid the elasto-plastic kernel builds for
    one separation l over ``g_range`` = (g_lo, g_hi) (below the grid: its small-τ model); and
    the grid's info (hyperbola integrals computed, converged, panels, g-intervals, ln τ where the
    grid starts). For the
    tests: a twin of the interpolation against :func:`hyperbola_moments`."""
    st = elastoplastic_settings_for(accuracy)
    y_t, w_t = gauss_legendre(st.tau_nodes)
    tau, g = (np.array(a.reshape(-1)) for a in np.broadcast_arrays(np.asarray(tau, float), np.asarray(g, float)))
    out = np.empty((tau.shape[0], 2))
    info = np.empty(5)
    _ep_grid_values(float(l), float(g_range[0]), float(g_range[1]), int(st.panel_degree),
                    float(st.panel_width), float(st.grid_tol), float(st.hyperbola_step),
                    float(st.hyperbola_width_fraction), y_t, w_t, _moment_table(), tau, g, out, info)
    return out, info


def polar_elastoplastic_integrals(l_values, nodes, sigma, material_constants, accuracy="table",
                                  *, tc1=None, return_info=False):
    """The θ-summed (r, t)-integrals of the elasto-plastic laws at each l; shape (n_l, 8):
    A^e, A^ep, A^p, W^e, W^ep, W^p, dW/dω, load-jump term (elastoplastic.py applies D_sum and
    adds the jump to the stiffness).

    ``nodes``: dict of per-θ-node arrays g, c, f1, f2, f3 and tc1 (tc1 = ω_c(θ, κ_m = c(θ))/σ),
    ordered by tanh-sinh level, with ``counts`` (nodes of each level) and ``weights`` (one row per
    level: θ-weight × cos θ sin θ), as rules.nested_theta_rule makes them;
    ``material_constants``: (E*, ω_p/ω_c, c_h H, H (c_h − (2/3) K_v), (2/3) K_v H, with_jump).
    Several materials on one surface: ``material_constants`` a list of such tuples and ``tc1``
    their (n_materials, n_nodes) array; the result is then (n_l, n_materials, 8), and the
    hyperbola integrals — the surface's, not the material's — are computed once per l.
    ``return_info``: also (…, 4): hyperbola integrals computed, 1 if the grid reached its
    tolerance (else 0), the θ-level used (index into the levels), the estimated θ-error."""
    l_values = np.ascontiguousarray(np.atleast_1d(np.asarray(l_values, dtype=float)))
    if not np.all(np.isfinite(l_values)):
        raise ValueError("separations must be finite")
    single = tc1 is None
    consts = [material_constants] if single else list(material_constants)
    tc1 = np.ascontiguousarray(np.atleast_2d(nodes["tc1"] if single else tc1), dtype=float)
    if tc1.shape != (len(consts), np.shape(nodes["g"])[0]):
        raise ValueError(f"tc1 must have shape (materials, θ-nodes) = {(len(consts), np.shape(nodes['g'])[0])}")
    st = elastoplastic_settings_for(accuracy)
    y_t, w_t = gauss_legendre(st.tau_nodes)
    arr = {k: np.ascontiguousarray(nodes[k], dtype=float) for k in ("g", "c", "f1", "f2", "f3")}
    counts = np.ascontiguousarray(nodes["counts"], dtype=np.int64)
    weights = np.ascontiguousarray(nodes["weights"], dtype=float)
    columns = [np.ascontiguousarray([float(m[q]) for m in consts]) for q in range(5)]
    with_jump = np.array([bool(m[5]) for m in consts])
    out = np.empty((l_values.shape[0], len(consts), 8))
    info = np.empty((l_values.shape[0], len(consts), 4))
    args = (l_values, arr["g"], arr["c"], arr["f1"], arr["f2"], arr["f3"], tc1, weights, counts, float(sigma),
            *columns, with_jump, int(st.panel_degree), float(st.panel_width), float(st.grid_tol),
            float(st.hyperbola_step), float(st.hyperbola_width_fraction), float(st.theta_tol), y_t, w_t,
            _moment_table(), out, info)
    # separations over the threads in one parallel region; a single separation runs serially
    # (splitting its few milliseconds costs parallel regions, each a thread wake-up: measured
    # slower than serial on the shared 2-core machine, and the elastic single call is serial too)
    threads = min(numba.get_num_threads(), l_values.shape[0])
    if threads > 1:
        _ep_rows_parallel(threads, *args)
    else:
        _ep_rows(np.arange(l_values.shape[0]), *args)
    if single:
        out, info = out[:, 0], info[:, 0]
    return (out, info) if return_info else out
