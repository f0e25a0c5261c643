"""The BEM of a measured (or synthetic) height map beside the statistical model of the same
surface (issue 32): what ``roughcontact bem SCAN`` computes, free of I/O.

At each nominal pressure W/A0 of an increasing ladder:

* the BEM (:func:`.solver.solve_pressures`, ContactMechanics) on the map with its form removed
  (statistics.form.remove_form, as the moments see it): A/A0, the mean gap ḡ, K/A0 = −dp/dḡ
  (central differences at p·e^(±ε), :data:`.solver.STIFFNESS_STEP`) and the solver's residuals;
  periodic cell or free boundary (a measured scan is not periodic);
* the statistical model (BGK, exact Hertz; :func:`.compare.model_at_pressures`) from the map's
  measured moments in the lay frame (statistics.measure.measure_heights, eqs. (1)–(5)): A/A0 (52),
  the separation h = s√m00 (53) — the counterpart of ḡ, docs/bem.md — and K/A0 (55);
* their ratios BEM/model.

Units: lengths (heights, dx, dy, ḡ, the moments) in one unit L; pressures and E* in one stress
unit; K/A0 in that stress unit per L.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import limits
from ..statistics.dropouts import fill_harmonic
from ..statistics.form import remove_form
from ..statistics.measure import measure_heights
from ..statistics.surface import SpectralMoments
from .compare import model_at_pressures
from .solver import BOUNDARIES, STIFFNESS_STEP, SolverSettings, solve_pressures

__all__ = ["ScanBEM", "bem_of_scan", "check_bem_size", "pressure_ladder", "BYTES_PER_POINT", "POINTS_PER_DECADE",
           "MAX_PRESSURES"]

#: the BEM's peak memory per map point [B] (measured, 1024², ContactMechanics bb5a881): periodic
#: ~250 B, free boundary ~620 B (its grid is padded to 2nx × 2ny); roughcontact.limits' "cells"
#: is sized for the moments' ~100 B per point, so a BEM point counts as this many cells
BYTES_PER_POINT = {True: 250, False: 620}
_CELL_BYTES = 100
#: the default density of a --pressure-range ladder: enough for a law table (a law interpolates
#: p(ḡ) between samples; ln p is nearly linear in ḡ, Persson 2007, so 4 per decade suffice)
POINTS_PER_DECADE = 4
#: the most pressures of one ladder (each is three BEM solves: ~10 s each on 512²)
MAX_PRESSURES = 1000


@dataclass(frozen=True)
class ScanBEM:
    """The BEM and the model at the pressures (arrays over them).

    pressure W/A0 [stress]; area_fraction A/A0 [–]; mean_gap ḡ [L]; stiffness K/A0 [stress/L];
    penetration_residual, force_residual : the solver's residuals at convergence (largest
    penetration inside the contact / rms height; largest tensile force outside / p·dx·dy) [–];
    iterations, seconds : per pressure (with the stiffness's side solves);
    periodic, E_star, settings, stiffness_step : how it was solved;
    moments : the measured moments (lay frame) [L², –, –, L⁻², L⁻²]; lay_angle_deg [°];
    model : {"area_fraction", "s", "mean_gap" (h = s√m00 [L]), "stiffness"} arrays, or None where
    the measured moments lie outside the model (then ``model_error`` says why);
    ratio : BEM/model of area_fraction, mean_gap, stiffness (None without a model);
    notes : the measurement's warnings; model_warnings : the model's (validity) warnings (text); form : what remove_form removed;
    missing_fraction, filled : the map's dropouts and whether they were filled (harmonic).
    """

    pressure: np.ndarray
    area_fraction: np.ndarray
    mean_gap: np.ndarray
    stiffness: np.ndarray
    penetration_residual: np.ndarray
    force_residual: np.ndarray
    iterations: np.ndarray
    seconds: np.ndarray
    periodic: bool
    E_star: float
    settings: SolverSettings
    stiffness_step: float
    moments: SpectralMoments | None
    moment_values: dict
    lay_angle_deg: float
    model: dict | None
    model_error: str | None
    ratio: dict | None
    notes: tuple
    model_warnings: tuple
    form: dict
    missing_fraction: float
    filled: bool

    @property
    def boundary(self) -> str:
        """'periodic' or 'free boundary (padded)'."""
        return BOUNDARIES[self.periodic]


def pressure_ladder(low: float, high: float, n: int | None = None) -> np.ndarray:
    """n pressures spaced evenly in ln p from ``low`` to ``high`` (0 < low < high); default n:
    POINTS_PER_DECADE per decade, at least 3."""
    if not (math.isfinite(low) and math.isfinite(high) and 0 < low < high):
        raise ValueError(f"the pressure range needs 0 < LO < HI, got {limits.describe(low)} {limits.describe(high)}")
    if n is None:
        n = max(3, math.ceil(POINTS_PER_DECADE * math.log10(high / low)) + 1)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 2 <= n <= MAX_PRESSURES:
        raise ValueError(f"the number of pressures must be an integer in [2, {MAX_PRESSURES}], got {limits.describe(n)}")
    return np.geomspace(low, high, int(n))


def check_bem_size(shape, periodic: bool) -> None:
    """InputLimitError (a ValueError) before solving when the BEM's memory on a map of ``shape``
    (BYTES_PER_POINT) exceeds what roughcontact.limits allows a map (``cells``, ~100 B each)."""
    ny, nx = shape
    cells = ny * nx * math.ceil(BYTES_PER_POINT[bool(periodic)] / _CELL_BYTES)
    limits.check_count(cells, "cells", f"the BEM of a {ny} x {nx} map ({BOUNDARIES[bool(periodic)]}, "
                                       f"~{BYTES_PER_POINT[bool(periodic)]} B per point) in cells of ~{_CELL_BYTES} B")


def _model(moments, pressures, E_star):
    """The model's arrays at the pressures, or (None, why) where the moments are outside it."""
    m = model_at_pressures(moments, pressures, E_star)
    return {"area_fraction": m.area_fraction, "s": m.s, "mean_gap": m.s * math.sqrt(moments.m00),  # h = s√m00
            "stiffness": m.stiffness}, m.warnings


def bem_of_scan(heights, dx: float, dy: float, *, E_star: float, pressures, periodic: bool,
                settings: SolverSettings = SolverSettings(), detrend: str = "plane", fill: str = "none",
                stiffness_step: float = STIFFNESS_STEP, progress=None) -> ScanBEM:
    """The BEM of the map heights[i, j] [L] (x = j·dx, y = i·dy) with a rigid flat at the
    increasing ``pressures`` [stress], and the model from its measured moments.

    detrend : the form removed before both (statistics.measure.DETRENDS); fill : "none" (a map
    with dropouts is refused: the BEM needs every point) or "harmonic" (filled first, as the
    moments fill it); periodic : the map is one cell of a periodic surface, else free boundary.
    progress(i, p, info) after each pressure. ValueError (one line) on bad input; the size is
    checked (:func:`check_bem_size`) before the BEM allocates anything."""
    z = np.asarray(heights, dtype=float)
    if z.ndim != 2:
        raise ValueError(f"heights must be a 2-d map, got shape {z.shape}")
    missing = int(np.count_nonzero(~np.isfinite(z)))
    if missing and fill != "harmonic":
        raise ValueError(f"{missing} of the map's {z.size} points are missing: the BEM needs a complete grid "
                         "(fill them: fill='harmonic')")
    check_bem_size(z.shape, periodic)
    measured = measure_heights(z, dx, dy, detrend=detrend, fill=fill)
    if missing:
        z = fill_harmonic(z)
    residual, form = remove_form(z, measured.dx, measured.dy, detrend)
    model_warnings = ()
    try:
        moments = measured.moments
    except ValueError as exc:  # outside the model (e.g. mu <= 0): the BEM still runs
        moments, model, model_error = None, None, str(exc)
    bem = solve_pressures(residual, measured.dx, measured.dy, E_star, pressures, settings=settings,
                          progress=progress, periodic=periodic, stiffness_step=stiffness_step)
    ratio = None
    if moments is not None:
        model, model_warnings = _model(moments, bem.pressure, E_star)
        model_error = None
        bem_values = {"area_fraction": bem.area_fraction, "mean_gap": bem.mean_gap, "stiffness": bem.stiffness}
        ratio = {k: v / model[k] for k, v in bem_values.items()}
    return ScanBEM(pressure=bem.pressure, area_fraction=bem.area_fraction, mean_gap=bem.mean_gap,
                   stiffness=bem.stiffness, penetration_residual=bem.penetration_residual,
                   force_residual=bem.force_residual, iterations=bem.iterations, seconds=bem.seconds,
                   periodic=bem.periodic, E_star=float(E_star), settings=settings,
                   stiffness_step=float(stiffness_step), moments=moments, moment_values=dict(measured.values),
                   lay_angle_deg=measured.lay_angle_deg, model=model, model_error=model_error, ratio=ratio,
                   notes=tuple(measured.notes), model_warnings=tuple(model_warnings), form=form, missing_fraction=measured.missing_fraction,
                   filled=bool(missing))
