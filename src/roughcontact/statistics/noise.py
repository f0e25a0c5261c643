"""The noise floor of measured moments (statistics.measure, ``noise_floor``): the part white
height noise — quantisation in steps Δ (variance Δ²/12) or an instrument's noise (a flat tail of
the spectrum) — adds to each moment, in closed form for the estimator used (the comment below),
estimated from the data, and the dx-vs-k·dx ratios of the moments with that part taken away.
"""

from __future__ import annotations

import math

import numpy as np

from .derivatives import stencil_weights

__all__ = ["NOISE_LIMIT", "NOISE_DOMINATES", "height_step", "white_noise_moments", "noise_floor",
           "noise_removed_ratios"]


# White noise n of variance σ² on the heights (uncorrelated between points) adds to each moment
# the variance of the estimator's linear filter applied to n: for a filter Σ_j w_j n_j that is
# σ² Σ_j w_j² (the variance of a sum of uncorrelated variables). For the fd estimator's central
# stencil w_o (o = −r … r, divided by h; :mod:`.derivatives`) and its self-convolution c = w * w
# (z_xx = D_x D_x z), with S1 = Σ w_o², S2 = Σ c_k² and c_0 = −S1 (w is odd):
#     Var n_x = σ² S1/dx²,  Var n_xx = σ² S2/dx⁴,  Var n_xy = Cov(n_xx, n_yy) = σ² S1²/(dx² dy²),
#     Cov(n_x, n_y) = Cov(n_xx, n_xy) = Cov(n_yy, n_xy) = 0 (w_0 = 0),
# and in the lay frame (c = cos θ, s = sin θ; the fields rotated as in _rotated):
#     m20 += c² Vx + s² Vy,  m02 += s² Vx + c² Vy,
#     m40 += c⁴ Vxx + s⁴ Vyy + 6 c² s² Vxy,  m04 += s⁴ Vxx + c⁴ Vyy + 6 c² s² Vxy,
#     m22 += c² s² (Vxx + Vyy − 2 Vxy) + (c² − s²)² Vxy.
# At k dx the same stencils at spacing k h: the slope parts fall by k², the curvature parts by k⁴.
# For the periodogram (Parseval) white noise adds σ²/N to every bin: m_pq += σ² mean_k(q_a^p q_c^q)
# over the grid's wavenumbers (the window's power is normalised out). Uniform quantisation in steps
# Δ is such noise with σ² = Δ²/12 when the heights spread over many steps between neighbouring points
# (Widrow's quantisation theorem: B. Widrow & I. Kollár, Quantization Noise, Cambridge 2008,
# chapters 4–5); tests/statistics/test_noise_floor.py checks the estimate against the measured inflation.

#: the noise part of a moment above this fraction of the measured moment is warned about: 10 % of
#: m40 or m04 is 5 % on the summit density (17) and the mean summit curvature (70), both ∝ √m40, √m04,
#: beyond their batch-means uncertainty on a 256² map (3.4–7 % for the surface of test_noise_floor.py,
#: 12 maps) — a bias the stated uncertainty does not show; the same 10 % as RESOLUTION_TOL
NOISE_LIMIT = 0.10
#: the spectrum's tail: the corner |q_x|, |q_y| in (0.75, 1] of the Nyquist wavenumbers against the
#: band (0.5, 0.75]; a white floor has equal medians there, a surface's spectrum falls (a power law
#: C ∝ q^-3.6, Hurst 0.8, by 0.3 between the two; even C ∝ q^-2 by 0.5): a corner within TAIL_FLAT of the
#: band is read as a floor of white noise
TAIL_BANDS = ((0.75, 1.0), (0.5, 0.75))
TAIL_FLAT = 0.7
#: the noise part above this fraction of a moment: its dx-vs-2dx ratio is not judged (NaN). Where the
#: noise part is large the estimate is within 10 % of it (m40: 0.96–1.09 of the measured inflation,
#: test_noise_floor.py), which leaves 0.1 f/(1 − f) of the noise-free moment uncertain at a fraction
#: f: RESOLUTION_TOL (10 %) at f = 0.5
NOISE_DOMINATES = 0.5
_NOISE_MOMENTS = ("m00", "m20", "m02", "m40", "m04", "m22")


def height_step(z) -> float | None:
    """The height resolution Δ [unit of z]: the smallest step between distinct measured heights,
    if every step is an integer multiple of it (to 1 %: the heights lie on a lattice, as
    instruments and vendor exports quantise them); None otherwise (steps below 1e-9 of the range,
    the round-off of a unit conversion, do not count)."""
    v = np.unique(np.asarray(z, dtype=float)[np.isfinite(z)])
    if v.size < 3:
        return None
    steps = np.diff(v)
    steps = steps[steps > 1e-9 * (v[-1] - v[0])]
    if steps.size == 0:
        return None
    delta = float(steps.min())
    k = steps / delta
    return delta if np.all(np.abs(k - np.round(k)) <= 0.01) else None


def _tail_floor(residual, dx, dy):
    """(σ² of a white floor read from the spectrum's tail [L²], whether the tail is flat): the
    median Hann-windowed periodogram in the corner band of TAIL_BANDS, N/ln 2 times (white noise's
    periodogram is exponentially distributed, median = mean ln 2: Priestley 1981, Spectral
    Analysis and Time Series, chapter 6), and whether it is within TAIL_FLAT of the inner
    band's. (None, None) for an incomplete map."""
    if not np.isfinite(residual).all():
        return None, None
    ny, nx = residual.shape
    w = np.outer(np.hanning(ny + 2)[1:-1], np.hanning(nx + 2)[1:-1])
    power = np.abs(np.fft.fft2((residual - residual.mean()) * w)) ** 2 / (residual.size**2 * np.mean(w**2))
    fx = np.abs(np.fft.fftfreq(nx))[np.newaxis, :] * 2  # |q_x| / Nyquist
    fy = np.abs(np.fft.fftfreq(ny))[:, np.newaxis] * 2
    medians = []
    for lo, hi in TAIL_BANDS:
        band = (fx > lo) & (fx <= hi) & (fy > lo) & (fy <= hi)
        medians.append(float(np.median(np.broadcast_to(power, band.shape)[band])) if band.any() else math.nan)
    corner, inner = medians
    variance = corner * residual.size / math.log(2.0)
    flat = bool(inner > 0 and corner >= TAIL_FLAT * inner)
    return variance, flat


def white_noise_moments(variance, dx, dy, theta, *, estimator="fd", order=6, shape=None, step=1) -> dict:
    """The part of each moment (m00, m20, m02, m40, m04, m22, in the frame at ``theta`` [rad]
    from the map's x axis) that white height noise of ``variance`` [L²] adds, for the estimator
    used (the closed forms in the comment above: fd stencils of ``order`` at spacing step·dx, or
    the periodogram of a map of ``shape``)."""
    c, s = math.cos(theta), math.sin(theta)
    if estimator == "fd":
        r = order // 2
        w = stencil_weights(range(-r, r + 1))
        S1, S2 = float(np.sum(w**2)), float(np.sum(np.convolve(w, w) ** 2))
        hx, hy = step * dx, step * dy
        Vx, Vy = variance * S1 / hx**2, variance * S1 / hy**2
        Vxx, Vyy, Vxy = variance * S2 / hx**4, variance * S2 / hy**4, variance * S1**2 / (hx**2 * hy**2)
        return {"m00": variance, "m20": c * c * Vx + s * s * Vy, "m02": s * s * Vx + c * c * Vy,
                "m40": c**4 * Vxx + s**4 * Vyy + 6 * c * c * s * s * Vxy,
                "m04": s**4 * Vxx + c**4 * Vyy + 6 * c * c * s * s * Vxy,
                "m22": c * c * s * s * (Vxx + Vyy - 2 * Vxy) + (c * c - s * s) ** 2 * Vxy}
    ny, nx = -(-shape[0] // step), -(-shape[1] // step)  # the subsampled map z[::step, ::step]
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=step * dx)[np.newaxis, :]
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=step * dy)[:, np.newaxis]
    qa, qc = c * qx + s * qy, -s * qx + c * qy
    powers = {"m00": (0, 0), "m20": (2, 0), "m02": (0, 2), "m40": (4, 0), "m04": (0, 4), "m22": (2, 2)}
    return {k: float(variance * np.mean(np.broadcast_to(qa**p * qc**q, (ny, nx)))) for k, (p, q) in powers.items()}


def noise_floor(z_measured, residual, dx, dy, theta, estimator, order, values) -> dict:
    """The noise floor of the moments (MeasuredMoments.noise_floor): the height step and the
    tail's floor, the variance taken (the larger of Δ²/12 and a flat tail's), and each moment's
    noise part, absolute [units of the moment] and as a fraction of the measured moment."""
    delta = height_step(z_measured)
    tail, flat = _tail_floor(residual, dx, dy)
    candidates = []
    if delta is not None:
        candidates.append((delta * delta / 12.0, "quantisation: heights in steps of the height_step, variance step^2/12"))
    if flat:
        candidates.append((tail, "a white floor in the spectrum's tail (instrument noise and quantisation)"))
    variance, source = max(candidates, key=lambda t: t[0]) if candidates else (0.0, "none detected")
    if tail is None:  # dropouts: the periodogram needs a complete map
        source += "; the spectrum's tail not read (the map has missing points; --fill harmonic reads it)"
    parts = white_noise_moments(variance, dx, dy, theta, estimator=estimator, order=order, shape=residual.shape)
    return {"height_step": delta, "tail_variance": tail, "tail_flat": flat, "variance": variance,
            "source": source, "contribution": parts,
            "fraction": {k: (parts[k] / values[k] if values[k] > 0 else math.nan) for k in _NOISE_MOMENTS},
            "limit": NOISE_LIMIT}


def noise_removed_ratios(scales, variance, dx, dy, theta, estimator, order, shape):
    """``scales`` with "fine_over_this_noise_removed" at each coarser factor k: the ratio of the
    moments at dx and k dx after the estimated white-noise part is taken from each (the part
    falls by k² for slopes, k⁴ for curvatures); NaN where the noise part reaches the moment."""
    fine = white_noise_moments(variance, dx, dy, theta, estimator=estimator, order=order, shape=shape)
    out = [scales[0]]
    for sc in scales[1:]:
        coarse = white_noise_moments(variance, dx, dy, theta, estimator=estimator, order=order, shape=shape,
                                     step=sc["factor"])
        ratios = {}
        for n, r in sc["fine_over_this"].items():
            top, bottom = r * sc[n] - fine[n], sc[n] - coarse[n]
            judged = top > (1.0 - NOISE_DOMINATES) * r * sc[n] and bottom > 0
            ratios[n] = top / bottom if judged else math.nan
        out.append({**sc, "fine_over_this_noise_removed": ratios})
    return out
