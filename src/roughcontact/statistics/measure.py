"""Spectral moments measured on a height map or on profiles: the moments of the measured window
itself, the lay, how they change with scale, their uncertainty, and whether the model applies.

Definition (docs/fe-export.md, "Moments"; Longuet-Higgins 1957, Nayak 1971 eqs. (1)–(3)):
with angular wavenumbers q [rad/L] and the power spectral density Φ normalised to ∫∫Φ d²q = Var z,

    m_pq = ∫∫ q_x^p q_y^q Φ(q) d²q = E[∂^{p/2}_x ∂^{q/2}_y z ...]:
    m00 = Var z,  m20 = Var z_x,  m02 = Var z_y,  m11 = E[z_x z_y],
    m40 = Var z_xx, m04 = Var z_yy, m22 = E[z_xy²] = E[z_xx z_yy], m31 = E[z_xx z_xy], m13 = E[z_yy z_xy].

The default estimator (``"fd"``) measures these of the window itself, unweighted:

* m00 = Sq², the mean square of the heights about their least-squares plane;
* m20 … m13 the (co)variances, about their means over the window, of the derivative *fields*
  z_x, z_y, z_xx, z_xy, z_yy (:mod:`.derivatives`: central differences of order 6 by default,
  off-centre stencils at the edges and at dropouts, second derivatives as the first applied
  twice), at every measured point where a stencil can be built;
* the lay angle θ from the slopes' covariances, tan 2θ = 2 m11/(m20 − m02) (Longuet-Higgins 1957,
  principal directions), the root with the smaller slope variance along the lay; the *fields* are
  then rotated (z_a = c z_x + s z_y, z_aa = c² z_xx + 2cs z_xy + s² z_yy, …) and their
  covariances taken — no rotation of moment tensors measured with different biases.

Tested against the exact moments of windows cut from larger periodic surfaces (their derivative
fields from the spectrum): within 2 % and the lay within 0.3° at lays 0–75°, m02/m20 up to 100,
with dropouts (tests/statistics/test_window_moments.py; errors before and after in docs/fe-export.md).

``"spectral"`` is the periodogram of the detrended (optionally Hann-windowed) map weighted by
q_x^p q_y^q (Parseval): exact for a periodic band-limited map (``window="none"``,
``detrend="mean"``), biased on a measured one (the window's own slope ~ m00·4π²/(3L²) is added to
m20; m00 is Hann-weighted).

Scale and uncertainty: m20 … m04 depend on the sampling interval (for a fractal-like spectrum they
grow without bound as it falls; https://contact.engineering shows them as functions of scale), so the
moments are also given at 2× and 4× the interval (the same stencils at spacing 2h, 4h, from every
point); their standard uncertainty is the batch-means estimate over 4 × 4 sub-windows (the
derivative fields' products summed per sub-window about the global means: the spread of those
ratios, /√16). It is the uncertainty of the surface's moments estimated from this map — of
the window's own moments the estimator's error is the tested bias above.

Noise floor: white height noise (quantisation in steps Δ: variance Δ²/12; an instrument's noise:
a flat tail of the spectrum) adds to each moment the variance of the estimator's filter applied to
it, in closed form (:mod:`.noise`); ``noise_floor`` reports it per moment,
a warning fires above NOISE_LIMIT of a moment, and the dx-vs-2dx resolution check compares the
moments after their noise part is taken away (the part falls by k² for slopes and k⁴ for
curvatures at k dx), so that it speaks of the surface, not of the noise.

Form: ``detrend`` removes the mean, the plane, a polynomial of degree 2–4 or a sphere (its radius
in ``form``) by least squares before the moments; a sphere's or a cylinder's curvature otherwise
stays in m00 and m20 (the derivative fields are centred, so a constant curvature leaves m40, m04).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from ..limits import describe
from ..validation import choice, positive
from .derivatives import ORDERS, derivative_fields, first_derivative
from .dropouts import FILLS, MAX_MISSING, fill_harmonic, missing_fraction
from .form import remove_form
from .noise import NOISE_LIMIT, height_step, noise_floor, noise_removed_ratios, white_noise_moments
from .summits import m22_effect
from .surface import SpectralMoments

__all__ = ["ESTIMATORS", "DETRENDS", "NOISE_LIMIT", "MeasurementWarning", "MeasuredMoments", "measure_heights",
           "measure_profiles", "rotate_map", "height_step", "white_noise_moments"]

ESTIMATORS = ("fd", "spectral")
WINDOWS = ("hann", "none")
#: form removal: the mean, the least-squares plane, a polynomial of total degree 2–4 (curvature
#: form, e.g. of a ground or turned part), a sphere (a ball or lens; its radius is reported)
DETRENDS = ("plane", "mean", "none", "poly2", "poly3", "poly4", "sphere")
#: profiles (measure_profiles): a line per profile, the mean, or nothing
PROFILE_DETRENDS = ("plane", "mean", "none")
FIVE = ("m00", "m20", "m02", "m40", "m04")
_ALL = ("m00", "m20", "m02", "m11", "m40", "m04", "m22", "m31", "m13")
#: sampling intervals (multiples of dx, dy) at which the moments are also reported
SCALES = (1, 2, 4)
#: sub-windows per axis of the batch-means uncertainty
BATCHES = 4
#: m40 or m04 changing by more than this between dx and 2 dx, after their estimated noise part is
#: taken from both (noise_floor): the curvatures are not resolved. On synthetic maps that resolve
#: their spectrum the ratio is 1.000–1.005 (12 maps, lays 0° and 25°; test_noise_floor.py checks < 1 %);
#: with 1–30 nm steps on a 0.1 µm surface 1.00–1.08 once the noise part is removed (where it is judged:
#: noise below NOISE_DOMINATES of the moment), against 1.05–14.5 with it
RESOLUTION_TOL = 0.10
#: an rms slope above this (45°) or below the floor is a unit mismatch more often than a surface
SLOPE_LIMIT, SLOPE_FLOOR = 1.0, 1e-5
#: slope variances differing by less than this fraction: the map has no lay
ISOTROPY_LIMIT = 0.05
#: a derivative field's mean square at the off-centre points (edges, dropouts) more than this
#: times that at the central points: the off-centre stencils amplify unresolved wavenumbers and
#: are dropped (on maps that resolve their spectrum the two differ by sampling only, a few tens of %)
OFF_CENTRE_RATIO = 2.0


class MeasurementWarning(UserWarning):
    """A measured map whose moments are computed but should be read with care (units, scale,
    model assumptions, missing data)."""


@dataclass(frozen=True)
class MeasuredMoments:
    """Moments measured on a map, in the lay frame (x along the lay).

    values : the nine moments ``_ALL`` in the lay frame (m11 = 0 there) [L², –, L⁻²]; always
        given, also where they lie outside the model (μ ≤ 0).
    lay_angle_deg : the angle from the map's x axis to the lay [deg], in (−90, 90].
    m11_map : E[z_x z_y] in the map frame, before rotation [–].
    uncertainty : standard uncertainties of ``values`` and of ``lay_angle_deg`` (batch means), or
        None (spectral estimator).
    scales : per sampling interval factor k in SCALES, {"factor", "dx", "dy", m00 … m04,
        "fine_over_this": m20 … m04 at dx over those at k dx, both over the points where the
        coarser stencils fit}.
    missing_fraction, fill : the fraction of the map not measured, and how it was filled.
    estimator, order, window, detrend, dx, dy : how they were measured (dx, dy [L]).
    notes : the warnings issued (MeasurementWarning), as text.
    form : what ``detrend`` removed ({"removed", "form_rms" [L], and a sphere's "radius",
        "centre_x", "centre_y" [L], "shape"}).
    noise_floor : the estimated part of each moment that height noise adds (white noise: the
        quantisation step and the spectrum's tail; :func:`white_noise_moments`), absolute and as a
        fraction of the measured moment; None when not estimated.
    """

    values: dict
    lay_angle_deg: float
    m11_map: float
    uncertainty: dict | None
    scales: tuple
    missing_fraction: float
    fill: str
    estimator: str
    order: int | None
    window: str
    detrend: str
    dx: float
    dy: float
    notes: tuple = ()
    form: dict | None = None
    noise_floor: dict | None = None

    @property
    def lay(self) -> dict:
        """The nine lay-frame moments (alias of ``values``)."""
        return self.values

    @property
    def moments(self) -> SpectralMoments:
        """The five moments as the model's :class:`SpectralMoments`; ValueError naming the
        condition where they lie outside it (a moment ≤ 0, or μ ≤ 0: a narrow-band surface) —
        ``values`` and :meth:`validity` have them either way."""
        try:
            return SpectralMoments(*(self.values[k] for k in FIVE))
        except ValueError as exc:
            raise ValueError(f"the measured moments are outside the model of the paper: {exc} (they are in "
                             "MeasuredMoments.values; a narrow-band surface, e.g. a few dominant wavelengths, "
                             "has mu <= 0)") from None

    def anisotropy(self) -> dict[str, float]:
        """Distance from the model's assumptions: m22/√(m40 m04), m31/√(m40 m22), m13/√(m04 m22)
        (all 0 for the ideal strongly anisotropic surface), and m02/m20 (≫ 1 for it)."""
        m = self.values
        return {
            "m22_over_sqrt_m40_m04": _ratio(m["m22"], math.sqrt(max(m["m40"] * m["m04"], 0.0))),
            "m31_over_sqrt_m40_m22": _ratio(m["m31"], math.sqrt(max(m["m40"] * m["m22"], 0.0))),
            "m13_over_sqrt_m04_m22": _ratio(m["m13"], math.sqrt(max(m["m04"] * m["m22"], 0.0))),
            "m02_over_m20": _ratio(m["m02"], m["m20"]),
        }

    def validity(self) -> dict:
        """Whether the model of the paper applies to these moments (the moments are measured
        either way): all five positive and μ = 1 − 1/α1 − 1/α2 > 0 (eq. 10), and the curvatures
        resolved (m40, m04 at dx vs 2 dx within RESOLUTION_TOL, after the estimated noise part is
        taken from both: ``noise_floor``). The neglected m22 is stated, not a condition: ``m22``
        compares its effect with what the BEM comparison measured (statistics.summits.m22_effect)."""
        m = self.values
        positive_ = all(m[k] > 0 for k in FIVE)
        mu = 1.0 - m["m20"] ** 2 / (m["m00"] * m["m40"]) - m["m02"] ** 2 / (m["m00"] * m["m04"]) if positive_ else None
        rho2 = m["m22"] ** 2 / (m["m40"] * m["m04"]) if positive_ else None
        ratios, raw = {}, {}
        if len(self.scales) > 1:  # dx against 2 dx over the same points
            s1 = self.scales[1]
            raw = {k: s1["fine_over_this"][k] for k in ("m40", "m04")}
            ratios = {k: s1.get("fine_over_this_noise_removed", s1["fine_over_this"])[k] for k in ("m40", "m04")}
        # NaN: the noise part dominates the moment (NOISE_DOMINATES), which is then not measured either
        resolved = all(abs(r - 1.0) <= RESOLUTION_TOL for r in ratios.values()) if ratios else None
        effect = None
        if positive_ and mu > 0:
            u = self.uncertainty["m22"] if self.uncertainty else 0.0
            effect = m22_effect(SpectralMoments(*(m[k] for k in FIVE)), m["m22"], u)
        return {
            "model_applies": bool(positive_ and mu > 0 and resolved is not False),
            "mu": mu, "m22_squared_over_m40_m04": rho2,
            "m40_ratio_dx_to_2dx": ratios.get("m40"), "m04_ratio_dx_to_2dx": ratios.get("m04"),
            "m40_ratio_dx_to_2dx_with_noise": raw.get("m40"), "m04_ratio_dx_to_2dx_with_noise": raw.get("m04"),
            "curvatures_resolved": resolved,
            "m22": None if effect is None else {k: v for k, v in effect.items() if k != "bem"},
        }


def _checked_options(dx, dy, estimator, window, detrend, order) -> tuple[float, float]:
    """(dx, dy) as positive lengths (dy defaults to dx); ValueError for an unknown option."""
    dx = positive("dx", dx)
    dy = dx if dy is None else positive("dy", dy)
    choice("estimator", estimator, ESTIMATORS)
    choice("window", window, WINDOWS)
    choice("detrend", detrend, DETRENDS)
    choice("order", order, ORDERS)
    return dx, dy


def spacing_fits(n: int, d: float) -> bool:
    """Whether ``n`` points at spacing ``d`` give a finite extent n·d and a finite curvature scale
    d⁻⁴ in doubles (dx = 1e308 overflowed in the plane's fit: "SVD did not converge")."""
    return math.isfinite(n * d) and d > 1e-77  # (1e-77)⁻⁴ = 1e308, near the largest double


def _checked_extent(shape, dx, dy, lay_angle_deg):
    """ValueError unless the map's spacing fits (:func:`spacing_fits`) and the lay angle is finite."""
    for name, d, n in (("dx", dx, shape[1]), ("dy", dy, shape[0])):
        if not spacing_fits(n, d):
            raise ValueError(f"{name} = {d:g}: the map's extent ({n} x {name}) or its curvatures (~1/{name}^4) are not "
                             "finite double-precision numbers; give the spacing in a unit in which it is near 1")
    if lay_angle_deg is not None:
        try:
            angle = float(lay_angle_deg)
        except (TypeError, ValueError):
            raise ValueError(f"lay_angle_deg must be a real number of degrees, got {describe(lay_angle_deg)}") from None
        if not math.isfinite(angle):
            raise ValueError(f"lay_angle_deg = {describe(angle)}: the lay angle must be a finite number of degrees")


def _ratio(a, b):
    return a / b if b else math.nan


def _heights(z, ndim) -> np.ndarray:
    """z as a float array of ``ndim`` dimensions, NaN for missing points (±inf refused)."""
    try:
        a = np.array(z, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("heights must be an array of real numbers") from None
    if a.ndim != ndim:
        raise ValueError(f"heights must be a {ndim}-d array, got shape {a.shape}")
    if min(a.shape) < 5:
        raise ValueError(f"heights need at least 5 points along each axis, got shape {a.shape}")
    if np.isinf(a).any():
        raise ValueError(f"heights must be finite or NaN (missing): {int(np.isinf(a).sum())} are infinite")
    return a


def _rotated(f, theta):
    """The derivative fields in the frame whose x axis is at theta from the map's (fields, not
    tensors: module docstring)."""
    c, s = math.cos(theta), math.sin(theta)
    return {
        "za": c * f["zx"] + s * f["zy"], "zc": -s * f["zx"] + c * f["zy"],
        "zaa": c * c * f["zxx"] + 2 * c * s * f["zxy"] + s * s * f["zyy"],
        "zcc": s * s * f["zxx"] - 2 * c * s * f["zxy"] + c * c * f["zyy"],
        "zac": -c * s * f["zxx"] + (c * c - s * s) * f["zxy"] + c * s * f["zyy"],
    }


#: moment -> the two rotated fields whose covariance it is
_PAIRS = {"m20": ("za", "za"), "m02": ("zc", "zc"), "m11": ("za", "zc"), "m40": ("zaa", "zaa"),
          "m04": ("zcc", "zcc"), "m22": ("zac", "zac"), "m31": ("zaa", "zac"), "m13": ("zcc", "zac")}


def _products(residual, fields, theta):
    """Per moment: (the centred products as a map, NaN where not estimated)."""
    r = _rotated(fields, theta)
    first = np.isfinite(r["za"]) & np.isfinite(r["zc"])
    second = np.isfinite(r["zaa"]) & np.isfinite(r["zcc"]) & np.isfinite(r["zac"])
    centred = {}
    for k, v in r.items():
        keep = first if k in ("za", "zc") else second
        centred[k] = np.where(keep, v - (v[keep].mean() if keep.any() else 0.0), np.nan)
    out = {"m00": residual**2}
    for k, (a, b) in _PAIRS.items():
        out[k] = centred[a] * centred[b]
    return out


def _means(products):
    out = {}
    for k, p in products.items():
        ok = np.isfinite(p)
        if not ok.any():
            raise ValueError("no point of the map has the derivative stencils it needs: the map is too "
                             "small or too sparse for this order (try a lower --order or --fill harmonic)")
        out[k] = float(p[ok].mean())
    return out


def _batch_uncertainty(products, batches):
    """Standard uncertainty of each mean in ``products`` by batch means over batches² blocks
    (ratio estimator: Σ c_b² (v_b − V)² / (Σ c_b)² · B/(B − 1))."""
    ny, nx = next(iter(products.values())).shape
    rows, cols = np.array_split(np.arange(ny), batches), np.array_split(np.arange(nx), batches)
    out = {}
    for k, p in products.items():
        sums, counts = [], []
        for r in rows:
            for c in cols:
                block = p[np.ix_(r, c)]
                ok = np.isfinite(block)
                sums.append(block[ok].sum())
                counts.append(ok.sum())
        s, n = np.array(sums), np.array(counts, dtype=float)
        used = n > 0
        B = int(used.sum())
        if B < 2:
            out[k] = math.nan
            continue
        V = s[used].sum() / n[used].sum()
        v = s[used] / n[used]
        out[k] = float(math.sqrt(np.sum(n[used] ** 2 * (v - V) ** 2) / n[used].sum() ** 2 * B / (B - 1)))
    return out


def _lay_angle(m) -> float:
    """θ in (−π/2, π/2] with m11 = 0 and m20 ≤ m02 in the rotated frame."""
    theta = 0.5 * math.atan2(2.0 * m["m11"], m["m20"] - m["m02"])
    # atan2 gives the direction of the largest slope variance; the lay is perpendicular to it
    theta += math.pi / 2
    if theta > math.pi / 2:
        theta -= math.pi
    return theta


def _spectral(z, dx, dy, window, theta):
    """The nine moments in the frame rotated by theta from the periodogram (Parseval)."""
    ny, nx = z.shape
    w = np.ones_like(z)
    if window == "hann":
        w = np.outer(np.hanning(ny + 2)[1:-1], np.hanning(nx + 2)[1:-1])
    power = np.abs(np.fft.fft2(z * w)) ** 2 / (z.size**2 * np.mean(w**2))
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=dx)[np.newaxis, :]
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=dy)[:, np.newaxis]
    c, s = math.cos(theta), math.sin(theta)
    qa, qc = c * qx + s * qy, -s * qx + c * qy
    powers = {"m00": (0, 0), "m20": (2, 0), "m02": (0, 2), "m11": (1, 1), "m40": (4, 0),
              "m04": (0, 4), "m22": (2, 2), "m31": (3, 1), "m13": (1, 3)}
    return {k: float((qa**p * qc**q * power).sum()) for k, (p, q) in powers.items()}


def _check_flat(z, residual):
    ok = np.isfinite(residual)
    sq = math.sqrt(float(np.mean(residual[ok] ** 2)))
    scale = float(np.max(np.abs(z[ok])))
    if not sq > 1e-12 * scale:
        raise ValueError(f"the map is flat: the heights about their fitted plane have Sq = {sq:.3g} "
                         f"(max |z| = {scale:.3g}), so there is no roughness to measure and no lay")


def measure_heights(z, dx, dy=None, *, estimator="fd", order=6, window="hann", detrend="plane",
                    lay_angle_deg=None, fill="none") -> MeasuredMoments:
    """Measure the moments of a height map z[i, j] at x = j·dx, y = i·dy [L]; NaN marks missing
    points (dropouts).

    estimator : "fd" (derivative fields, default) or "spectral" (periodogram; complete maps only).
    order : accuracy order of the fd stencils, one of ORDERS (default 6; :mod:`.derivatives`).
    window : "hann" or "none" (spectral estimator only; "none" for periodic maps).
    detrend : the form removed (least squares over the measured points): "plane" (default),
        "mean", "none", "poly2", "poly3", "poly4" (a polynomial of that total degree: curvature
        form) or "sphere" (its radius in ``form``).
    lay_angle_deg : the lay angle if known [deg]; default: found from m11 = 0.
    fill : "none" (default; the fd stencils avoid the dropouts) or "harmonic"
        (:func:`.dropouts.fill_harmonic`). A map more than half missing is refused.

    Warnings (:class:`MeasurementWarning`, also in ``notes``): moments outside the model (μ ≤ 0),
    an m22 beyond what the BEM comparison measured, height noise above NOISE_LIMIT of a moment,
    curvatures not resolved beyond the noise, an rms slope that suggests a unit mismatch, no lay.
    """
    dx, dy = _checked_options(dx, dy, estimator, window, detrend, order)
    choice("fill", fill, FILLS)
    z = _heights(z, 2)
    _checked_extent(z.shape, dx, dy, lay_angle_deg)
    measured_heights = z
    missing = missing_fraction(z)
    if missing > MAX_MISSING:
        raise ValueError(f"{100 * missing:.1f} % of the map is missing (more than {100 * MAX_MISSING:g} %): "
                         "its moments would describe the holes' rims; crop the measured part")
    if fill == "harmonic":
        z = fill_harmonic(z)
    elif estimator == "spectral" and missing > 0:
        raise ValueError(f"the periodogram needs a complete map, {100 * missing:.2g} % is missing: "
                         "use the fd estimator (it works around dropouts) or fill the holes (--fill harmonic)")
    residual, form = remove_form(z, dx, dy, detrend)
    _check_flat(z, residual)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if estimator == "fd":
            result = _measure_fd(residual, dx, dy, order, lay_angle_deg)
        else:
            result = _measure_spectral(residual, dx, dy, window, lay_angle_deg)
        values, theta, m11_map, uncertainty, scales = result
        noise = noise_floor(measured_heights, residual, dx, dy, theta, estimator, order, values)
        scales = noise_removed_ratios(scales, noise["variance"], dx, dy, theta, estimator, order, residual.shape)
        measured = MeasuredMoments(
            values=values, lay_angle_deg=math.degrees(theta), m11_map=m11_map, uncertainty=uncertainty,
            scales=tuple(scales), missing_fraction=missing, fill=fill, estimator=estimator,
            order=order if estimator == "fd" else None, window=window if estimator == "spectral" else "none",
            detrend=detrend, dx=dx, dy=dy, form=form, noise_floor=noise,
        )
        _warn_about(measured, lay_angle_deg is None)
    notes = []
    for w in caught:
        notes.append(str(w.message))
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return replace(measured, notes=tuple(notes)) if notes else measured


def _measure_fd(residual, dx, dy, order, lay_angle_deg):
    fields = derivative_fields(residual, dx, dy, order=order)
    central = derivative_fields(residual, dx, dy, order=order, off_centre=False)
    ratios = {}
    for k in ("zx", "zy", "zxx", "zyy"):
        off = np.isfinite(fields[k]) & np.isnan(central[k])
        inner = np.isfinite(central[k])
        if off.any() and inner.any():
            ratios[k] = float(np.mean(fields[k][off] ** 2) / np.mean(central[k][inner] ** 2))
    if ratios and max(ratios.values()) > OFF_CENTRE_RATIO:
        worst = max(ratios, key=ratios.get)
        warnings.warn(MeasurementWarning(
            f"the off-centre stencils (edges, dropouts) give {worst} a mean square {ratios[worst]:.3g} times that "
            "of the central stencils: the map does not resolve its spectrum at dx; only the central stencils are "
            "used"), stacklevel=4)
        fields = central
    in_map = _means(_products(residual, fields, 0.0))
    theta = _lay_angle(in_map) if lay_angle_deg is None else math.radians(float(lay_angle_deg))
    products = _products(residual, fields, theta)
    values = _means(products)
    uncertainty = _batch_uncertainty(products, BATCHES)
    spread = values["m02"] - values["m20"]
    uncertainty["lay_angle_deg"] = math.degrees(uncertainty["m11"] / abs(spread)) if spread else math.inf
    scales = [{"factor": 1, "dx": dx, "dy": dy, **{k: values[k] for k in FIVE}}]
    for k in SCALES[1:]:
        if min(residual.shape) < 2 * order * k + 16:  # central D(D) reaches order*k points each way
            break
        coarse_fields = derivative_fields(residual, dx, dy, order=order, step=k, off_centre=False)
        coarse_products = _products(residual, coarse_fields, theta)
        coarse = _means(coarse_products)
        # the fine moments over the same points: the ratio shows the scale, not the points left out
        same = {n: float(np.mean(products[n][np.isfinite(coarse_products[n])]) / coarse[n]) if coarse[n] else math.nan
                for n in FIVE[1:]}
        scales.append({"factor": k, "dx": k * dx, "dy": k * dy, **{n: coarse[n] for n in FIVE},
                       "fine_over_this": same})
    return values, theta, in_map["m11"], uncertainty, scales


def _measure_spectral(residual, dx, dy, window, lay_angle_deg):
    in_map = _spectral(residual, dx, dy, window, 0.0)
    theta = _lay_angle(in_map) if lay_angle_deg is None else math.radians(float(lay_angle_deg))
    values = _spectral(residual, dx, dy, window, theta)
    scales = [{"factor": 1, "dx": dx, "dy": dy, **{k: values[k] for k in FIVE}}]
    for k in SCALES[1:]:
        coarse = residual[::k, ::k]
        if min(coarse.shape) < 16:
            break
        c = _spectral(coarse - coarse.mean(), k * dx, k * dy, window, theta)
        scales.append({"factor": k, "dx": k * dx, "dy": k * dy, **{n: c[n] for n in FIVE},
                       "fine_over_this": {n: _ratio(values[n], c[n]) for n in FIVE[1:]}})
    return values, theta, in_map["m11"], None, scales


def _warn_about(m: MeasuredMoments, lay_found: bool) -> None:
    """MeasurementWarning for each reason to read these moments with care."""
    v = m.values
    slope = math.sqrt(max(v["m20"] + v["m02"], 0.0))
    if slope > SLOPE_LIMIT or 0 < slope < SLOPE_FLOOR:
        # the power of 1000 (a unit prefix) that brings the slope below 1 / above 1e-3
        k = math.ceil(math.log10(slope) / 3) if slope > SLOPE_LIMIT else -math.ceil(math.log10(1e-3 / slope) / 3)
        warnings.warn(MeasurementWarning(
            f"the rms slope is {slope:.3g} ({math.degrees(math.atan(slope)):.3g} deg): the heights and the lateral "
            f"spacing are probably in different units (likely scale factor {10.0 ** (-3 * k):g} on the heights, "
            f"e.g. {'nm heights with um spacing' if k > 0 else 'm heights with um spacing'}); state the units "
            "(--z-unit, --xy-unit) or rescale the heights"), stacklevel=3)
    total = v["m20"] + v["m02"]
    if lay_found and total > 0 and math.hypot(v["m02"] - v["m20"], 2 * m.m11_map) < ISOTROPY_LIMIT * total:
        warnings.warn(MeasurementWarning(
            f"the slope variances differ by less than {100 * ISOTROPY_LIMIT:g} % between directions: the map has "
            "no lay (isotropic), and the lay angle is arbitrary"), stacklevel=3)
    noise = m.noise_floor
    if noise is not None and noise["variance"] > 0:
        worst = sorted(((f, k) for k, f in noise["fraction"].items() if k != "m00" and math.isfinite(f)), reverse=True)
        if worst and worst[0][0] > NOISE_LIMIT:
            parts = ", ".join(f"{100 * f:.3g} % of {k}" for f, k in worst if f > NOISE_LIMIT)
            how = (f"heights quantised in steps of {noise['height_step']:.3g} in their length unit (white noise of variance "
                   "step^2/12)"
                   if noise["source"].startswith("quantisation") else
                   f"a white floor in the spectrum's tail (noise variance {noise['variance']:.3g} in the heights' unit squared)")
            warnings.warn(MeasurementWarning(
                f"height noise is an estimated {parts} ({how}; more than {100 * NOISE_LIMIT:g} %, "
                "statistics.noise.NOISE_LIMIT): these moments are inflated by it; 'noise_floor' has each moment's "
                "noise part, and at 2 dx the curvatures' part is 16 times smaller (see 'scales')"), stacklevel=3)
    ok = m.validity()
    if ok["mu"] is None:
        warnings.warn(MeasurementWarning("a measured moment is not positive: the model of the paper does not "
                                          "apply"), stacklevel=3)
    elif ok["mu"] <= 0:
        warnings.warn(MeasurementWarning(
            f"mu = 1 - 1/alpha1 - 1/alpha2 = {ok['mu']:.4g} <= 0 (eq. 10): a narrow-band surface (a few dominant "
            "wavelengths); the moments are measured, but the model of the paper does not apply"), stacklevel=3)
    if ok["m22"] is not None and ok["m22"]["message"]:
        warnings.warn(MeasurementWarning(ok["m22"]["message"]), stacklevel=3)
    # a NaN ratio (the noise dominates that moment) is the noise warning's, not this one's
    ratios = [r for r in (ok["m40_ratio_dx_to_2dx"], ok["m04_ratio_dx_to_2dx"]) if r is not None and math.isfinite(r)]
    if any(abs(r - 1.0) > RESOLUTION_TOL for r in ratios):
        worst = max(ratios, key=lambda r: abs(r - 1.0))
        removed = "" if noise is None or noise["variance"] == 0 else ", after the estimated noise part is taken from both"
        warnings.warn(MeasurementWarning(
            f"the curvature moments change by {100 * (worst - 1):+.0f} % between dx and 2 dx{removed}: they depend on "
            "the sampling interval (the spectrum is not resolved at this scale, or it is fractal-like); see "
            "'scales' and report the moments with their sampling interval"), stacklevel=3)


def _profile_moments(z, d, estimator, window, detrend, order):
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
    d1 = first_derivative(z, d, 1, order=order)
    d2 = first_derivative(d1, d, 1, order=order)
    return (float(np.mean(z**2)), *(float(np.mean(np.nanvar(a, axis=1))) for a in (d1, d2)))


def measure_profiles(along, across, dx, dy=None, *, estimator="fd", order=6, window="hann",
                     detrend="plane") -> SpectralMoments:
    """The five moments from profiles along the lay (sampled at dx [L]) and across it (at dy):
    a profile along x has the 1-D moments (m00, m20, m40), one along y (m00, m02, m04)
    (Nayak 1971; the paper's eq. (12) counts their zero crossings and extrema). ``along``,
    ``across``: 1-d arrays or 2-d arrays of several profiles (one per row); m00 is the mean of
    both directions' estimates."""
    dx, dy = _checked_options(dx, dy, estimator, window, detrend, order)
    choice("detrend", detrend, PROFILE_DETRENDS)
    profiles = []
    for p in (along, across):
        a = _heights(np.atleast_2d(np.asarray(p, dtype=float)), 2) if np.ndim(p) in (1, 2) else _heights(p, 2)
        if not np.isfinite(a).all():
            raise ValueError("profiles must be complete (no NaN): crop or fill the missing points")
        profiles.append(a)
    a0, a2, a4 = _profile_moments(profiles[0], dx, estimator, window, detrend, order)
    c0, c2, c4 = _profile_moments(profiles[1], dy, estimator, window, detrend, order)
    try:
        return SpectralMoments(0.5 * (a0 + c0), a2, c2, a4, c4)
    except ValueError as exc:
        raise ValueError(f"the measured moments are outside the model: {exc} (a narrow-band surface, e.g. a "
                         "few dominant wavelengths, has mu <= 0)") from None


def rotate_map(z, dx, dy, angle_deg, *, order=1) -> np.ndarray:
    """The map resampled on the same grid rotated by ``angle_deg`` [deg] (the new x axis at
    angle_deg from the old one), about the centre; points outside the map are NaN. For
    viewing and for profiles along the lay (crop the NaN border before measuring)."""
    from scipy.ndimage import map_coordinates

    z = _heights(z, 2)
    dx, dy = positive("dx", dx), positive("dy", dy)
    ny, nx = z.shape
    c, s = math.cos(math.radians(float(angle_deg))), math.sin(math.radians(float(angle_deg)))
    yc, xc = (ny - 1) * dy / 2, (nx - 1) * dx / 2
    i, j = np.mgrid[0:ny, 0:nx]
    u, v = j * dx - xc, i * dy - yc  # coordinates in the rotated frame
    x, y = xc + c * u - s * v, yc + s * u + c * v
    return map_coordinates(z, [y / dy, x / dx], order=order, mode="constant", cval=np.nan)
