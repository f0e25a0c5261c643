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
  evaluated through :class:`~roughcontact.interface.NormalLawTable` built to rtol/100 — or
  any NormalLawTable given (``law=``: a BEM law, whose own stated error then adds to rtol);
* rows: the first at exactly zero pressure, at c_0 = c_min − p_min/k_N(c_min) (the tangent at
  the light end p_min reaches zero there: the table continues the law with its stiffness);
  then p_min … p_max. Between consecutive rows from p_min on, the relative error
  |p_table(c) − p(c)|/p(c) is at most ``rtol`` (checked at 15 interior points of every row
  interval; the row spacing is the largest that passes, found by bisection);
* outside the table the codes differ: CalculiX holds the last pressure (a larger load finds no
  equilibrium: "increment size smaller than minimum", tests/paper/test_calculix_deck.py),
  Abaqus continues the last segment's slope (Abaqus manual, *SURFACE BEHAVIOR): neither is the
  law, so choose p_max far above any pressure the model reaches; the header says which;
* units: overclosures are written in the output unit, ``length_scale`` times the moments'
  unit (:func:`length_scale_between` derives it from the two unit names where both are known,
  :data:`LENGTH_UNITS`); unit names go into the header and are checked (:func:`unit_name`: no
  control characters or line breaks, nothing that could start a keyword line);
* friction: the codes take one stick stiffness; :func:`friction_block` writes k_T = a k_N at a
  chosen pressure (default :func:`representative_pressure`) and states the range of k_T(p) over
  the table's pressures;
* what a table cannot express: k_T(p) (the stick stiffness varies with p through k_N; codes
  take one constant or one elastic slip), orthotropic or hardening friction (section 8.1),
  unloading along another path (the elasto-plastic law is exported as a loading curve).
"""

from __future__ import annotations

import math
import unicodedata
from dataclasses import dataclass

import numpy as np

from .. import limits
from ..asperity import AsperityMaterial
from ..statistics.surface import SpectralMoments
from ..validation import choice, instance, positive
from .normal_law import NormalLawTable

__all__ = ["REFERENCES", "FORMATS", "NonFiniteTableError", "OverclosureTable", "overclosure_table", "format_table",
           "friction_block", "parse_table", "CALCULIX_MAX_ROWS", "LENGTH_UNITS", "BEYOND_LAST_ROW",
           "unit_name", "length_scale_between", "representative_pressure", "stick_stiffness"]

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
#: length units the export converts between without a stated scale, in metres
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "micron": 1e-6, "nm": 1e-9}
#: what each target code does with a pressure beyond the last row (module docstring)
BEYOND_LAST_ROW = {
    "calculix": "beyond the last row CalculiX holds the last pressure (a larger load finds no equilibrium)",
    "abaqus": "beyond the last row Abaqus continues the last segment's slope (not the law)",
    "csv": "beyond the last row CalculiX holds the last pressure, Abaqus continues the last slope",
}
#: longest unit name accepted (a name, not a sentence)
_MAX_UNIT_NAME = 40


class NonFiniteTableError(ValueError):
    """A row of the table (or the stick stiffness) is not finite once scaled, e.g. pressures
    times a ``stress_scale`` beyond the largest double: nothing of it may reach a deck."""


def unit_name(option: str, name) -> str:
    """A unit name checked for the header of a deck: a string of at most 40 characters without
    control characters or line breaks (a line break would start a line of its own — in Abaqus
    or CalculiX a live keyword such as ``*INCLUDE``) and not starting with ``*``. ValueError
    naming ``option`` otherwise."""
    if not isinstance(name, str) or not name.strip():
        raise ValueError(f"{option}: a unit name must be a non-empty string, got {name!r}")
    bad = [c for c in name if unicodedata.category(c) in ("Cc", "Cf", "Cs", "Co", "Cn", "Zl", "Zp")]
    if bad:
        raise ValueError(f"{option}: a unit name may not contain control characters or line breaks, got {name!r}")
    if name.lstrip().startswith("*") or len(name) > _MAX_UNIT_NAME:
        raise ValueError(f"{option}: a unit name (at most {_MAX_UNIT_NAME} characters, not starting with '*'), "
                         f"got {name!r}")
    return name


def length_scale_between(moments_unit: str, output_unit: str, length_scale=None) -> float:
    """The factor taking overclosures from the moments' unit to the output unit.

    Both units in :data:`LENGTH_UNITS`: their ratio (e.g. um → mm: 1e-3); a ``length_scale``
    given as well must equal it (ValueError otherwise: a µm table in an mm deck is 1000 × off).
    Otherwise ``length_scale`` as given, or 1 when the two names are the same; ValueError when
    the names differ and nothing says how to convert."""
    unit_name("moments unit", moments_unit)
    unit_name("output length unit", output_unit)
    given = None if length_scale is None else positive("length_scale", length_scale)
    if moments_unit in LENGTH_UNITS and output_unit in LENGTH_UNITS:
        factor = LENGTH_UNITS[moments_unit] / LENGTH_UNITS[output_unit]
        if given is not None and not math.isclose(given, factor, rel_tol=1e-9):
            raise ValueError(f"length scale {given:g} contradicts the units: {moments_unit} -> {output_unit} is "
                             f"{factor:g} (give the right scale, or none)")
        return factor
    if given is not None:
        return given
    if moments_unit == output_unit:
        return 1.0
    raise ValueError(f"cannot convert {moments_unit!r} to {output_unit!r}: give the length scale (units known: "
                     f"{', '.join(LENGTH_UNITS)})")


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
        row, the last pressure beyond the last as CalculiX holds it; Abaqus would continue the
        last slope)."""
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


def overclosure_table(surface: SpectralMoments | None, *, pressure_range, E_star=None,
                      material: AsperityMaterial | None = None, rtol=1e-3, reference="seating",
                      seating_pressure=None, hertz="exact", max_rows=None,
                      law: NormalLawTable | None = None) -> OverclosureTable:
    """Choose the rows of a pressure–overclosure table (module docstring).

    surface : the five moments (length unit L); E_star (elastic law) or material
        (elasto-plastic law, :class:`~roughcontact.asperity.AsperityMaterial`).
    law : instead of the three, a NormalLawTable already made (e.g. a BEM law,
        NormalLawTable.from_samples): the rows follow it, within its own range and error.
    pressure_range : (p_min, p_max) [unit of E*], 0 < p_min < p_max: the range in which the
        table is within rtol of the law. rtol in [1e-5, 0.1].
    reference : "seating" (give seating_pressure p0 within the range: c = 0 there) or
        "mean-plane" (c = −h).
    max_rows : ValueError if more rows are needed (e.g. CALCULIX_MAX_ROWS for CalculiX).
    """
    if law is None:
        instance("surface", surface, SpectralMoments)
    elif surface is not None or E_star is not None or material is not None:
        raise ValueError("give either law or surface with E_star or material, not both")
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
    if law is not None:
        instance("law", law, NormalLawTable)
    elif (E_star is None) == (material is None):
        raise ValueError("give exactly one of E_star (elastic law) and material (elasto-plastic law)")
    else:
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
    """The rows in the output units; NonFiniteTableError naming the first row that is not finite
    (checked before any text is made, so a caller never writes part of a table)."""
    ls = positive("length_scale", length_scale)
    ss = positive("stress_scale", stress_scale)
    with np.errstate(over="ignore", invalid="ignore"):  # reported below, row by row
        p, c = table.pressure * ss, table.overclosure * ls
    bad = ~(np.isfinite(p) & np.isfinite(c))
    if bad.any():
        i = int(np.argmax(bad))
        raise NonFiniteTableError(
            f"row {i + 1} of {p.size} is not finite: pressure {limits.describe(p[i])} = {table.pressure[i]:.6g} "
            f"(unit of E*) x stress scale {ss:g}, overclosure {limits.describe(c[i])} = {table.overclosure[i]:.6g} "
            f"(moments' unit) x length scale {ls:g}")
    return p, c


def format_table(table: OverclosureTable, fmt: str, *, length_scale=1.0, stress_scale=1.0,
                 length_unit="L", stress_unit="unit of E*", moments_unit="L", friction: str = "") -> str:
    """The table in the syntax of ``fmt`` ("abaqus", "calculix": ``*SURFACE BEHAVIOR,
    PRESSURE-OVERCLOSURE=TABULAR`` with one ``pressure, overclosure`` pair a line; "csv": a
    header, then ``pressure,overclosure``). Overclosures are multiplied by ``length_scale``
    (e.g. 1e-3 for µm → mm, :func:`length_scale_between`), pressures by ``stress_scale``; the
    unit names (checked by :func:`unit_name`) go in the comment, with what the code does beyond
    the last row (:data:`BEYOND_LAST_ROW`).
    ``friction``: a block from :func:`friction_block` to append (abaqus, calculix)."""
    choice("format", fmt, FORMATS)
    unit_name("length_unit", length_unit)
    unit_name("stress_unit", stress_unit)
    unit_name("moments_unit", moments_unit)
    if fmt == "calculix" and table.n_rows > CALCULIX_MAX_ROWS:
        raise ValueError(f"CalculiX resamples tables of more than {CALCULIX_MAX_ROWS} rows; this one "
                         f"has {table.n_rows}: raise rtol or narrow the pressure range")
    p, c = _rows(table, length_scale, stress_scale)
    ref = ("the seating pressure p0 = " + _FMT.format(table.seating_pressure * stress_scale)
           if table.reference == "seating" else "the mean planes (c = -h)")
    about = [
        f"roughcontact pressure-overclosure table: {table.law.level} law, E* = {table.law.E_star:.8g}",
        f"moments (length unit {moments_unit}): "
        + ", ".join(f"{k} = {v:.8g}" for k, v in table.law.surface.as_dict().items()),
        f"pressure [{stress_unit}], overclosure [{length_unit}] (positive closes), zero at {ref}",
        f"within rtol = {table.rtol:g} of the law for pressures {table.pressure_range[0] * stress_scale:.6g}"
        f" ... {table.pressure_range[1] * stress_scale:.6g} (max measured {table.max_error:.3g})",
        "first row: zero pressure on the law's tangent at the light end",
        f"{BEYOND_LAST_ROW[fmt]}:", "keep every pressure of the model far below the last row",
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


def _law_at_pressure(table: OverclosureTable, p: float) -> float:
    """k_N = dp/dc [unit of E* per L] of the table's law at the pressure p."""
    return float(table.law.evaluate(table.law.separation_at(p))[1])


def representative_pressure(table: OverclosureTable) -> float:
    """The default pressure of the stick stiffness: where k_N(p) equals √(k_N(p_min) k_N(p_max))
    over the table's pressure range. A code keeps k_T constant while the law's k_T = a k_N(p)
    grows with p (about in proportion); the constant with the smallest largest factor error over
    [p_min, p_max] is the geometric mean of the ends' values (k_N is monotone), and this is the
    pressure where the law has it."""
    lo, hi = table.pressure_range
    target = math.sqrt(_law_at_pressure(table, lo) * _law_at_pressure(table, hi))
    a, b = math.log(lo), math.log(hi)
    for _ in range(80):  # bisection in ln p: k_N increases with p
        mid = 0.5 * (a + b)
        if _law_at_pressure(table, math.exp(mid)) < target:
            a = mid
        else:
            b = mid
        if b - a <= 1e-10:
            break
    return math.exp(0.5 * (a + b))


def stick_stiffness(table: OverclosureTable, kT_over_kN, pressure=None, *, length_scale=1.0,
                    stress_scale=1.0) -> dict:
    """The stick stiffness k_T = a k_N(p) [output stress per output length] at ``pressure``
    (unit of E*, within the table's pressure range; default :func:`representative_pressure`),
    and the range of k_T(p) over the table's pressures: {"pressure", "k_T", "range":
    [(p_min, k_T(p_min)), (p_max, k_T(p_max))], "factor": k_T(p_max)/k_T(p_min)} (pressures
    times ``stress_scale``)."""
    a = positive("kT_over_kN", kT_over_kN)
    lo, hi = table.pressure_range
    p = representative_pressure(table) if pressure is None else positive("the k_T pressure", pressure)
    if not lo <= p <= hi:
        raise ValueError(f"the k_T pressure {p:g} must lie in the table's pressure range [{lo:g}, {hi:g}]")
    to_out = a * positive("stress_scale", stress_scale) / positive("length_scale", length_scale)
    k_lo, k_hi = (_law_at_pressure(table, x) * to_out for x in (lo, hi))
    k_p = _law_at_pressure(table, p) * to_out
    for name, value in (("k_T", k_p), (f"k_T at p_min = {lo:g}", k_lo), (f"k_T at p_max = {hi:g}", k_hi),
                        (f"pressure of k_T, {p:g} x stress scale", p * stress_scale)):
        if not math.isfinite(value):
            raise NonFiniteTableError(f"the friction's {name} is not finite ({limits.describe(value)}) with "
                                      f"k_T/k_N = {a:g}, stress scale {stress_scale:g}, length scale {length_scale:g}")
    return {"pressure": p * stress_scale, "k_T": k_p,
            "range": [(lo * stress_scale, k_lo), (hi * stress_scale, k_hi)], "factor": k_hi / k_lo}


def friction_block(table: OverclosureTable, fmt: str, mu, kT_over_kN, *, kt_at=None, length_scale=1.0,
                   stress_scale=1.0) -> str:
    """A ``*FRICTION`` block: Coulomb μ and the stick stiffness k_T(P) = a·k_N(P) at the
    pressure P = ``kt_at`` [unit of E*] (default :func:`representative_pressure`; section 8,
    k_T = a k_N). CalculiX takes μ and the stick slope λ [stress/length] directly; Abaqus takes
    an elastic slip γ, written as γ = μ P/k_T(P) (its stick stiffness μp/γ then grows with p
    and matches k_T at P). Neither expresses k_T(p) (the note states its range over the table's
    pressures) or the paper's hardening friction (section 8.1)."""
    choice("format", fmt, ("abaqus", "calculix"))
    mu = positive("mu", mu)
    k = stick_stiffness(table, kT_over_kN, kt_at, length_scale=length_scale, stress_scale=stress_scale)
    (p_lo, k_lo), (p_hi, k_hi) = k["range"]
    note = (f"** friction: mu = {mu:g}, k_T = {kT_over_kN:g} k_N at p = {k['pressure']:.6g}: {_FMT.format(k['k_T'])}\n"
            f"** the law's k_T(p) runs from {k_lo:.4g} at p = {p_lo:.4g} to {k_hi:.4g} at p = {p_hi:.4g}; "
            "the code keeps one value")
    if fmt == "calculix":
        return f"{note}\n*FRICTION\n{_FMT.format(mu)}, {_FMT.format(k['k_T'])}"
    gamma = mu * k["pressure"] / k["k_T"]
    if not math.isfinite(gamma):
        raise NonFiniteTableError(f"the elastic slip mu p/k_T = {limits.describe(gamma)} is not finite")
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
