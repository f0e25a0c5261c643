"""Spectral moments measured on a height map or on profiles: estimators, lay, anisotropy.

Definition (docs/fe-export.md, "Moments"; Longuet-Higgins 1957, Nayak 1971 eqs. (1)–(3)):
with angular wavenumbers q [rad/L] and the power spectral density Φ normalised to ∫∫Φ d²q = Var z,

    m_pq = ∫∫ q_x^p q_y^q Φ(q) d²q = E[∂^{p/2}_x ∂^{q/2}_y z ...]:
    m00 = Var z,  m20 = Var z_x,  m02 = Var z_y,  m11 = E[z_x z_y],
    m40 = Var z_xx, m04 = Var z_yy, m22 = E[z_xy²] = E[z_xx z_yy], m31 = E[z_xx z_xy], m13 = E[z_yy z_xy].

Two estimators of the same quantities:

* ``"spectral"`` — the periodogram of the detrended (optionally Hann-windowed) map, weighted
  by q_x^p q_y^q (Parseval); exact for a periodic band-limited map; on a non-periodic map the
  jump at the edges leaks power to high q, which the window suppresses (``window="hann"``,
  the default; use ``"none"`` for periodic maps);
* ``"fd"`` — central finite differences on the interior points: z_x ≈ (z_{j+1} − z_{j−1})/2Δx,
  z_xx ≈ (z_{j+1} − 2z_j + z_{j−1})/Δx², z_xy by the four-point cross; their transfer
  functions sin(qΔx)/Δx and 4 sin²(qΔx/2)/Δx² under-weight wavenumbers near Nyquist.

m40, m04 (and m20, m02 less so) depend on the band the instrument resolves: for a fractal-like
spectrum they grow without bound as Δx falls. Report the sampling interval with the moments,
compare both estimators and two sampling intervals (resample by 2), and take the moments at the
scale that matters for the contact (docs/fe-export.md).

The lay: the second-order moments rotate as a symmetric tensor; the angle θ from the map's x axis
to the lay (the direction of the smallest slope variance) makes m11 = 0:
tan 2θ = 2 m11/(m20 − m02) (Longuet-Higgins 1957, principal directions). The lay-frame moments
are computed with the wavenumbers (or derivatives) rotated by θ. The model of the paper assumes
a strongly anisotropic surface whose fourth-order cross moments do not enter; how far a surface
is from that is reported as m22/√(m40 m04) and m31/√(m40 m22), m13/√(m04 m22) in the lay frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .surface import SpectralMoments

__all__ = ["ESTIMATORS", "MeasuredMoments", "measure_heights", "measure_profiles", "rotate_map"]

ESTIMATORS = ("spectral", "fd")
WINDOWS = ("hann", "none")
DETRENDS = ("plane", "mean", "none")
_ALL = ("m00", "m20", "m02", "m11", "m40", "m04", "m22", "m31", "m13")


@dataclass(frozen=True)
class MeasuredMoments:
    """Moments measured on a map (or profiles), in the lay frame (x along the lay).

    moments : the five moments of the model [L², –, –, L⁻², L⁻²] (:class:`SpectralMoments`).
    lay_angle_deg : the angle from the map's x axis to the lay [deg], in (−90, 90].
    m11_map : E[z_x z_y] in the map frame, before rotation [–].
    lay : all nine moments (``_ALL``) in the lay frame (m11 ≈ 0 there).
    estimator, window, detrend, dx, dy : how they were measured (dx, dy [L]).
    """

    moments: SpectralMoments
    lay_angle_deg: float
    m11_map: float
    lay: dict
    estimator: str
    window: str
    detrend: str
    dx: float
    dy: float

    def anisotropy(self) -> dict[str, float]:
        """Distance from the model's assumptions: m22/√(m40 m04), m31/√(m40 m22), m13/√(m04 m22)
        (all 0 for the ideal strongly anisotropic surface), and m02/m20 (≫ 1 for it)."""
        m = self.lay
        return {
            "m22_over_sqrt_m40_m04": m["m22"] / math.sqrt(m["m40"] * m["m04"]),
            "m31_over_sqrt_m40_m22": m["m31"] / math.sqrt(m["m40"] * m["m22"]) if m["m22"] > 0 else 0.0,
            "m13_over_sqrt_m04_m22": m["m13"] / math.sqrt(m["m04"] * m["m22"]) if m["m22"] > 0 else 0.0,
            "m02_over_m20": m["m02"] / m["m20"],
        }


def _choice(name, value, options):
    if value not in options:
        raise ValueError(f"{name} must be one of {', '.join(options)}; got {value!r}")


def _length(name, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a positive length, got {value!r}") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a positive finite length, got {value!r}")
    return v


def _heights(z, ndim) -> np.ndarray:
    try:
        a = np.array(z, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("heights must be an array of real numbers") from None
    if a.ndim != ndim:
        raise ValueError(f"heights must be a {ndim}-d array, got shape {a.shape}")
    if min(a.shape) < 5:
        raise ValueError(f"heights need at least 5 points along each axis, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"heights must be finite: {int(np.sum(~np.isfinite(a)))} points are not "
                         "(fill or crop missing data first)")
    return a


def _detrend(z, dx, dy, how):
    """Subtract the least-squares plane (or the mean) of z[i, j] over x = j dx, y = i dy."""
    if how == "none":
        return z
    if how == "mean":
        return z - z.mean()
    ny, nx = z.shape
    y, x = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    A = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
    coef, *_ = np.linalg.lstsq(A, z.ravel(), rcond=None)
    return z - (A @ coef).reshape(z.shape)


def _rotation(theta):
    return math.cos(theta), math.sin(theta)


def _spectral(z, dx, dy, window, theta):
    """The nine moments in the frame rotated by theta from the periodogram (Parseval)."""
    ny, nx = z.shape
    w = np.ones_like(z)
    if window == "hann":
        w = np.outer(np.hanning(ny + 2)[1:-1], np.hanning(nx + 2)[1:-1])
    power = np.abs(np.fft.fft2(z * w)) ** 2 / (z.size**2 * np.mean(w**2))
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=dx)[np.newaxis, :]
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=dy)[:, np.newaxis]
    c, s = _rotation(theta)
    qa, qc = c * qx + s * qy, -s * qx + c * qy
    powers = {"m00": (0, 0), "m20": (2, 0), "m02": (0, 2), "m11": (1, 1), "m40": (4, 0),
              "m04": (0, 4), "m22": (2, 2), "m31": (3, 1), "m13": (1, 3)}
    return {k: float((qa**p * qc**q * power).sum()) for k, (p, q) in powers.items()}


def _fd(z, dx, dy, theta):
    """The nine moments in the frame rotated by theta from central differences (interior)."""
    zc = z[1:-1, 1:-1]
    zx = (z[1:-1, 2:] - z[1:-1, :-2]) / (2 * dx)
    zy = (z[2:, 1:-1] - z[:-2, 1:-1]) / (2 * dy)
    zxx = (z[1:-1, 2:] - 2 * zc + z[1:-1, :-2]) / dx**2
    zyy = (z[2:, 1:-1] - 2 * zc + z[:-2, 1:-1]) / dy**2
    zxy = (z[2:, 2:] - z[2:, :-2] - z[:-2, 2:] + z[:-2, :-2]) / (4 * dx * dy)
    c, s = _rotation(theta)
    za, zb = c * zx + s * zy, -s * zx + c * zy  # directional derivatives along/across
    zaa = c * c * zxx + 2 * c * s * zxy + s * s * zyy
    zbb = s * s * zxx - 2 * c * s * zxy + c * c * zyy
    zab = -c * s * zxx + (c * c - s * s) * zxy + c * s * zyy

    def cov(a, b):
        return float(np.mean((a - a.mean()) * (b - b.mean())))

    return {"m00": cov(zc, zc), "m20": cov(za, za), "m02": cov(zb, zb), "m11": cov(za, zb),
            "m40": cov(zaa, zaa), "m04": cov(zbb, zbb), "m22": cov(zab, zab),
            "m31": cov(zaa, zab), "m13": cov(zbb, zab)}


def _lay_angle(m) -> float:
    """θ in (−π/2, π/2] with m11 = 0 and m20 ≤ m02 in the rotated frame."""
    theta = 0.5 * math.atan2(2.0 * m["m11"], m["m20"] - m["m02"])
    # atan2 gives the direction of the largest slope variance; the lay is perpendicular to it
    theta += math.pi / 2
    if theta > math.pi / 2:
        theta -= math.pi
    return theta


def measure_heights(z, dx, dy=None, *, estimator="spectral", window="hann", detrend="plane",
                    lay_angle_deg=None) -> MeasuredMoments:
    """Measure the moments of a height map z[i, j] at x = j·dx, y = i·dy [L].

    estimator : "spectral" (periodogram) or "fd" (finite differences), module docstring.
    window : "hann" or "none" (spectral estimator only; "none" for periodic maps).
    detrend : "plane" (least-squares plane, default), "mean" or "none".
    lay_angle_deg : the lay angle if known [deg]; default: found from m11 = 0.
    """
    dx = _length("dx", dx)
    dy = dx if dy is None else _length("dy", dy)
    _choice("estimator", estimator, ESTIMATORS)
    _choice("window", window, WINDOWS)
    _choice("detrend", detrend, DETRENDS)
    z = _detrend(_heights(z, 2), dx, dy, detrend)
    if not np.ptp(z) > 0.0:
        raise ValueError("the detrended heights are constant: no roughness to measure")

    def moments_at(theta):
        return _spectral(z, dx, dy, window, theta) if estimator == "spectral" else _fd(z, dx, dy, theta)

    in_map = moments_at(0.0)
    if lay_angle_deg is None:
        theta = _lay_angle(in_map)
    else:
        theta = math.radians(float(lay_angle_deg))
    lay = moments_at(theta)
    return MeasuredMoments(
        moments=_model_moments(lay["m00"], lay["m20"], lay["m02"], lay["m40"], lay["m04"]),
        lay_angle_deg=math.degrees(theta), m11_map=in_map["m11"], lay=lay, estimator=estimator,
        window=window if estimator == "spectral" else "none", detrend=detrend, dx=dx, dy=dy,
    )


def _profile_moments(z, d, estimator, window, detrend):
    """(m0, m2, m4) of profiles (rows of z) sampled at interval d, averaged over the rows."""
    n = z.shape[1]
    x = np.arange(n) * d
    if detrend == "plane":  # a line per profile
        A = np.column_stack([np.ones(n), x])
        coef, *_ = np.linalg.lstsq(A, z.T, rcond=None)
        z = z - (A @ coef).T
    elif detrend == "mean":
        z = z - z.mean(axis=1, keepdims=True)
    if estimator == "spectral":
        w = np.hanning(n + 2)[1:-1] if window == "hann" else np.ones(n)
        power = np.abs(np.fft.fft(z * w, axis=1)) ** 2 / (n**2 * np.mean(w**2))
        q = 2 * np.pi * np.fft.fftfreq(n, d=d)
        return tuple(float((q**p * power).sum(axis=1).mean()) for p in (0, 2, 4))
    zc = z[:, 1:-1]
    d1 = (z[:, 2:] - z[:, :-2]) / (2 * d)
    d2 = (z[:, 2:] - 2 * zc + z[:, :-2]) / d**2
    return tuple(float(np.mean(np.var(a, axis=1))) for a in (zc, d1, d2))


def measure_profiles(along, across, dx, dy=None, *, estimator="spectral", window="hann",
                     detrend="plane") -> SpectralMoments:
    """The five moments from profiles along the lay (sampled at dx [L]) and across it (at dy):
    a profile along x has the 1-D moments (m00, m20, m40), one along y (m00, m02, m04)
    (Nayak 1971; the paper's eq. (12) counts their zero crossings and extrema). ``along``,
    ``across``: 1-d arrays or 2-d arrays of several profiles (one per row); m00 is the mean of
    both directions' estimates."""
    dx = _length("dx", dx)
    dy = dx if dy is None else _length("dy", dy)
    _choice("estimator", estimator, ESTIMATORS)
    _choice("window", window, WINDOWS)
    _choice("detrend", detrend, DETRENDS)
    a, c = (_heights(np.atleast_2d(_heights(p, np.ndim(p) if np.ndim(p) in (1, 2) else 2)), 2)
            for p in (along, across))
    a0, a2, a4 = _profile_moments(a, dx, estimator, window, detrend)
    c0, c2, c4 = _profile_moments(c, dy, estimator, window, detrend)
    return _model_moments(0.5 * (a0 + c0), a2, c2, a4, c4)


def _model_moments(*five) -> SpectralMoments:
    try:
        return SpectralMoments(*five)
    except ValueError as exc:
        raise ValueError(f"the measured moments are outside the model: {exc} (a narrow-band "
                         "surface, e.g. a few dominant wavelengths, has mu <= 0)") from None


def rotate_map(z, dx, dy, angle_deg, *, order=1) -> np.ndarray:
    """The map resampled on the same grid rotated by ``angle_deg`` [deg] (the new x axis at
    angle_deg from the old one), about the centre; points outside the map are NaN. For
    viewing and for profiles along the lay (crop the NaN border before measuring)."""
    from scipy.ndimage import map_coordinates

    z = _heights(z, 2)
    dx, dy = _length("dx", dx), _length("dy", dy)
    ny, nx = z.shape
    c, s = _rotation(math.radians(float(angle_deg)))
    yc, xc = (ny - 1) * dy / 2, (nx - 1) * dx / 2
    i, j = np.mgrid[0:ny, 0:nx]
    u, v = j * dx - xc, i * dy - yc  # coordinates in the rotated frame
    x, y = xc + c * u - s * v, yc + s * u + c * v
    return map_coordinates(z, [y / dy, x / dx], order=order, mode="constant", cval=np.nan)
