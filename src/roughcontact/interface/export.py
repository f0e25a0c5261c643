"""The statistical normal law as a pressure–overclosure table for FE codes (Abaqus, CalculiX).

FE codes take a contact law as a table of (pressure, overclosure) pairs and interpolate the
pressure linearly in the overclosure between them. This module chooses the rows so that that
interpolation stays within a requested relative tolerance ``rtol`` of the library's law over a
requested pressure range, and writes the table in each code's syntax (docs/fe-export.md).

Conventions
-----------
* overclosure c = h_ref − h [L, the moments' length unit], positive when the surfaces close;
  the reference h_ref is the separation at the seating pressure p0 (``reference="seating"``,
  c = 0 at p = p0, the state in which the FE model starts) or the mean planes
  (``reference="mean-plane"``, h_ref = 0, c = −h);
* the law p(c) is W/A0 of the elastic (53) or elasto-plastic (82) model at h = h_ref − c,
  evaluated through :class:`~roughcontact.interface.NormalLawTable` built to rtol/100;
* rows: the first at exactly zero pressure, at c_0 = c_min − p_min/k_N(c_min) (the tangent at
  the light end p_min reaches zero there: the table continues the law with its stiffness);
  then p_min … p_max. Between consecutive rows from p_min on, the relative error
  |p_table(c) − p(c)|/p(c) is at most ``rtol`` (checked at 15 interior points of every row
  interval; the row spacing is the largest that passes, found by bisection);
* outside the table FE codes hold the last slope (Abaqus) or the last pressure (CalculiX):
  choose p_max far above any pressure the model reaches;
* what a table cannot express: k_T(p) (the stick stiffness varies with p through k_N; codes
  take one constant or one elastic slip), orthotropic or hardening friction (section 8.1),
  unloading along another path (the elasto-plastic law is exported as a loading curve).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..asperity import AsperityMaterial
from ..statistics.surface import SpectralMoments
from ..validation import choice, instance, positive
from .normal_law import NormalLawTable

__all__ = ["REFERENCES", "FORMATS", "OverclosureTable", "overclosure_table", "format_table",
           "friction_block", "parse_table", "CALCULIX_MAX_ROWS"]

REFERENCES = ("seating", "mean-plane")
FORMATS = ("abaqus", "calculix", "csv")
#: CalculiX 2.20 resamples a table of more than 200 rows to 200 points evenly spaced in
#: overclosure (found by an independent run, issue 14), losing the light end of the law
CALCULIX_MAX_ROWS = 200
#: interior check points of a row interval (fractions)
_CHECK = np.linspace(0.0, 1.0, 17)[1:-1]
#: the rows meet rtol·_MARGIN at the check points (the law table's own error is ≤ rtol/100)
_MARGIN = 0.95
#: 20-character fields (CalculiX reads 20): 13 significant digits
_FMT = "{:.12e}"


@dataclass(frozen=True, eq=False)
class OverclosureTable:
    """Rows of a pressure–overclosure table (module docstring).

    pressure [unit of E*] (ascending, first exactly 0), overclosure [L] (ascending);
    reference, h_ref [L] (c = h_ref − h), seating_pressure p0 (None for the mean planes);
    pressure_range (p_min, p_max), rtol, max_error: the largest relative error measured at the
    check points; law: the NormalLawTable the rows were taken from.
    """

    pressure: np.ndarray
    overclosure: np.ndarray
    reference: str
    h_ref: float
    seating_pressure: float | None
    pressure_range: tuple[float, float]
    rtol: float
    max_error: float
    law: NormalLawTable

    @property
    def n_rows(self) -> int:
        return int(self.pressure.size)

    def law_pressure(self, overclosure):
        """p(c) of the law [unit of E*] at overclosures c [L] within the table's law range."""
        return self.law.evaluate(self.h_ref - np.asarray(overclosure, dtype=float))[0]

    def interpolate(self, overclosure):
        """The FE code's piecewise-linear pressure at overclosures c [L] (zero below the first
        row, the last pressure beyond the last as CalculiX holds it)."""
        return np.interp(overclosure, self.overclosure, self.pressure, left=0.0)

    def summary(self) -> dict:
        return {"rows": self.n_rows, "rtol": self.rtol, "max_error": self.max_error,
                "pressure_range": list(self.pressure_range), "reference": self.reference,
                "seating_pressure": self.seating_pressure, "h_ref": self.h_ref,
                "zero_pressure_overclosure": float(self.overclosure[0]),
                "level": self.law.level, "E_star": self.law.E_star}


def _relative_error(law, h_ref, c0, c1, p0, p1) -> float:
    c = c0 + (c1 - c0) * _CHECK
    exact = law.evaluate(h_ref - c)[0]
    linear = p0 + (p1 - p0) * _CHECK
    return float(np.max(np.abs(linear / exact - 1.0)))


def overclosure_table(surface: SpectralMoments, *, pressure_range, E_star=None,
                      material: AsperityMaterial | None = None, rtol=1e-3, reference="seating",
                      seating_pressure=None, hertz="exact", max_rows=None) -> OverclosureTable:
    """Choose the rows of a pressure–overclosure table (module docstring).

    surface : the five moments (length unit L); E_star (elastic law) or material
        (elasto-plastic law, :class:`~roughcontact.asperity.AsperityMaterial`).
    pressure_range : (p_min, p_max) [unit of E*], 0 < p_min < p_max: the range in which the
        table is within rtol of the law. rtol in [1e-5, 0.1].
    reference : "seating" (give seating_pressure p0 within the range: c = 0 there) or
        "mean-plane" (c = −h).
    max_rows : ValueError if more rows are needed (e.g. CALCULIX_MAX_ROWS for CalculiX).
    """
    instance("surface", surface, SpectralMoments)
    choice("reference", reference, REFERENCES)
    rtol = float(rtol)
    if not (1e-5 <= rtol <= 0.1):
        raise ValueError(f"rtol must lie in [1e-5, 0.1], got {rtol!r}")
    try:
        p_min, p_max = (float(p) for p in pressure_range)
    except (TypeError, ValueError):
        raise ValueError(f"pressure_range must be two numbers, got {pressure_range!r}") from None
    if not (0.0 < p_min < p_max and math.isfinite(p_max)):
        raise ValueError(f"pressure_range must satisfy 0 < p_min < p_max, got {pressure_range!r}")
    if (E_star is None) == (material is None):
        raise ValueError("give exactly one of E_star (elastic law) and material (elasto-plastic law)")
    law = NormalLawTable.build(
        surface, "elastic" if material is None else "elastoplastic", E_star=E_star, material=material,
        hertz=hertz, pressure_range=(p_min, p_max), rtol=max(rtol / 100.0, 1e-7))
    if reference == "seating":
        if seating_pressure is None:
            raise ValueError("reference 'seating' needs the seating pressure p0")
        p0 = positive("seating_pressure", seating_pressure)
        if not p_min <= p0 <= p_max:
            raise ValueError(f"the seating pressure {p0:g} must lie in the pressure range [{p_min:g}, {p_max:g}]")
        h_ref = law.separation_at(p0)
    else:
        if seating_pressure is not None:
            raise ValueError("reference 'mean-plane' takes no seating pressure")
        p0, h_ref = None, 0.0
    c_lo, c_hi = h_ref - law.separation_at(p_min), h_ref - law.separation_at(p_max)
    cs, ps, worst = [c_lo], [p_min], 0.0
    target = rtol * _MARGIN
    while cs[-1] < c_hi:
        c0, pa = cs[-1], ps[-1]
        err_full = _relative_error(law, h_ref, c0, c_hi, pa, p_max)
        if err_full <= target:
            cs.append(c_hi), ps.append(p_max)
            worst = max(worst, err_full)
            break
        lo, hi = 0.0, c_hi - c0  # bisection on the interval width: the error grows with it
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            pm = float(law.evaluate(h_ref - (c0 + mid))[0])
            if _relative_error(law, h_ref, c0, c0 + mid, pa, pm) <= target:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 1e-6 * hi:
                break
        if lo <= 0.0:
            raise RuntimeError(f"no row interval meets rtol = {rtol:g} at c = {c0:g}")
        c1 = c0 + lo
        p1 = float(law.evaluate(h_ref - c1)[0])
        worst = max(worst, _relative_error(law, h_ref, c0, c1, pa, p1))
        cs.append(c1), ps.append(p1)
        if max_rows is not None and len(cs) + 1 > max_rows:
            raise ValueError(
                f"more than {max_rows} rows are needed for rtol = {rtol:g} over the pressure range "
                f"[{p_min:g}, {p_max:g}]: raise rtol or narrow the range")
    k_lo = float(law.evaluate(h_ref - c_lo)[1])  # K/A0 = dp/dc at the light end
    c_zero = c_lo - p_min / k_lo
    return OverclosureTable(
        pressure=np.array([0.0, *ps]), overclosure=np.array([c_zero, *cs]), reference=reference,
        h_ref=float(h_ref), seating_pressure=p0, pressure_range=(p_min, p_max), rtol=rtol,
        max_error=worst, law=law)


# ---------------------------------------------------------------------------------------------
# writing and reading the code's syntax
# ---------------------------------------------------------------------------------------------
def _rows(table, length_scale, stress_scale):
    ls = positive("length_scale", length_scale)
    ss = positive("stress_scale", stress_scale)
    return table.pressure * ss, table.overclosure * ls


def format_table(table: OverclosureTable, fmt: str, *, length_scale=1.0, stress_scale=1.0,
                 length_unit="L", stress_unit="unit of E*", friction: str = "") -> str:
    """The table in the syntax of ``fmt`` ("abaqus", "calculix": ``*SURFACE BEHAVIOR,
    PRESSURE-OVERCLOSURE=TABULAR`` with one ``pressure, overclosure`` pair a line; "csv": a
    header, then ``pressure,overclosure``). Overclosures are multiplied by ``length_scale``
    (e.g. 1e-3 for µm → mm), pressures by ``stress_scale``; the unit names go in the comment.
    ``friction``: a block from :func:`friction_block` to append (abaqus, calculix)."""
    choice("format", fmt, FORMATS)
    if fmt == "calculix" and table.n_rows > CALCULIX_MAX_ROWS:
        raise ValueError(f"CalculiX resamples tables of more than {CALCULIX_MAX_ROWS} rows; this one "
                         f"has {table.n_rows}: raise rtol or narrow the pressure range")
    p, c = _rows(table, length_scale, stress_scale)
    ref = ("the seating pressure p0 = " + _FMT.format(table.seating_pressure * stress_scale)
           if table.reference == "seating" else "the mean planes (c = -h)")
    about = [
        f"roughcontact pressure-overclosure table: {table.law.level} law, E* = {table.law.E_star:.8g}",
        f"moments: " + ", ".join(f"{k} = {v:.8g}" for k, v in table.law.surface.as_dict().items()),
        f"pressure [{stress_unit}], overclosure [{length_unit}] (positive closes), zero at {ref}",
        f"within rtol = {table.rtol:g} of the law for pressures {table.pressure_range[0] * stress_scale:.6g}"
        f" ... {table.pressure_range[1] * stress_scale:.6g} (max measured {table.max_error:.3g});"
        " first row: zero pressure on the law's tangent at the light end",
        "beyond the last row the code extrapolates: keep every pressure of the model far below it",
    ]
    if fmt == "csv":
        lines = [f"# {a}" for a in about] + ["pressure,overclosure"]
        lines += [f"{_FMT.format(a)},{_FMT.format(b)}" for a, b in zip(p, c)]
    else:
        lines = [f"** {a}" for a in about] + ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR"]
        lines += [f"{_FMT.format(a)}, {_FMT.format(b)}" for a, b in zip(p, c)]
        if friction:
            lines.append(friction)
    return "\n".join(lines) + "\n"


def friction_block(table: OverclosureTable, fmt: str, mu, kT_over_kN, *, length_scale=1.0,
                   stress_scale=1.0) -> str:
    """A ``*FRICTION`` block: Coulomb μ and the stick stiffness k_T(p0) = a·k_N(p0) at the
    seating pressure (section 8, k_T = a k_N). CalculiX takes μ and the stick slope λ
    [stress/length] directly; Abaqus takes an elastic slip γ, written as γ = μ p0/k_T(p0)
    (the stick stiffness μp/γ then matches k_T at p0 only). Neither expresses k_T(p) or the
    paper's hardening friction (section 8.1)."""
    choice("format", fmt, ("abaqus", "calculix"))
    mu = positive("mu", mu)
    a = positive("kT_over_kN", kT_over_kN)
    if table.reference != "seating":
        raise ValueError("the friction block needs the seating reference (k_T at p0)")
    p0 = table.seating_pressure
    kN = float(table.law.evaluate(table.h_ref)[1])
    kT = a * kN * positive("stress_scale", stress_scale) / positive("length_scale", length_scale)
    note = (f"** friction: mu = {mu:g}, k_T(p0) = {a:g} k_N(p0) = {_FMT.format(kT)} "
            "(the code keeps it constant; the law's k_T follows k_N(p))")
    if fmt == "calculix":
        return f"{note}\n*FRICTION\n{_FMT.format(mu)}, {_FMT.format(kT)}"
    gamma = mu * p0 * stress_scale / kT
    return f"{note}\n*FRICTION, ELASTIC SLIP={_FMT.format(gamma)}\n{_FMT.format(mu)}"


def parse_table(text: str) -> tuple[np.ndarray, np.ndarray]:
    """(pressure, overclosure) read back from any of the three formats (comments skipped)."""
    p, c = [], []
    lines = iter(text.splitlines())
    for line in lines:
        s = line.strip()
        if not s or s.startswith(("#", "**")) or s.lower().startswith("pressure,"):
            continue
        if s.startswith("*"):
            if s.upper().startswith("*SURFACE BEHAVIOR"):
                continue
            break  # the next keyword ends the table
        a, b = s.split(",")[:2]
        p.append(float(a)), c.append(float(b))
    return np.array(p), np.array(c)
