"""A law file's BEM normal law: ``normal: {table: FILE}`` in LAW.yaml (issue 32; docs/own-model.md,
"A law from the BEM"). The reader is :mod:`.laws`; this module reads the table the key names and
makes its material.

FILE is a load ladder written by ``roughcontact bem ... --law-table`` (the JSON of
:mod:`roughcontact.bem.law_table`), relative to the law file. Its law is
:meth:`roughcontact.interface.NormalLawTable.from_samples` through the ladder (level "bem"):

* lengths stay in the table's ``length_unit`` (the law's unit, converted to the deck's as the
  moments' are: InteractionLaw.law_per_deck); moments given in the law file are converted to
  it (:func:`moments_in`), else the table's measured moments are the law's;
* pressures: in the deck's stress unit. A table that names its ``stress_unit`` is converted
  (laws.STRESS_UNITS, N/``length_unit``² the deck's); one that does not is taken to be in the
  deck's, and its E* then meets the deck run's check against the bodies' (deck_run.check_law_file,
  within laws.UNIT_RTOL) — a table in another unit fails there;
* E*: the table's; a stated ``E_star`` must agree with it within UNIT_RTOL;
* the pressure range is the ladder's [p_light, p_max]: the seating pressure must lie in it, a
  converged pressure beyond p_max is refused by the solver, and below p_light the table's
  light-end tail (interface.normal_law_samples) is an extrapolation.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..limits import describe
from ..statistics import SpectralMoments
from .laws import LENGTH_UNITS, STRESS_UNITS, UNIT_RTOL, LawError, _fail, _keys, _named

__all__ = ["TableFile", "moments_in", "bem_table", "bem_material"]

_NORMAL = {"required": ("table",), "optional": ()}


@dataclass(frozen=True)
class TableFile:
    """``normal: {table: FILE}``: the file as written (relative to the law file), its samples
    (roughcontact.bem.law_table.BEMLawSamples) and the normal law tabulated from them in the
    table's length unit and the deck's stress unit (a NormalLawTable of level "bem")."""

    file: str
    samples: object = field(compare=False, repr=False)
    law: object = field(compare=False, repr=False)


def moments_in(moments: SpectralMoments, unit: str, to: str) -> SpectralMoments:
    """The moments in another length unit: m00 ∝ L², m20, m02 ∝ 1, m40, m04 ∝ L⁻² (eq. (8))."""
    f = 10.0 ** (LENGTH_UNITS[unit] - LENGTH_UNITS[to])  # units of ``to`` per unit
    return SpectralMoments(moments.m00 * f * f, moments.m20, moments.m02, moments.m40 / (f * f), moments.m04 / (f * f))


def bem_table(d, where: str, base: Path | None, length_unit: str, moments):
    """``normal: {table: FILE}`` at ``where``: (TableFile, the law's moments in the table's
    unit, that unit, E* in the deck's stress unit); ``moments`` (SpectralMoments, unit) as the law
    file gives them, or None (module docstring). LawError naming the key otherwise."""
    from ..bem.law_table import normal_law_table, read_law_table

    d = _keys(d, where, **_NORMAL)
    file = d["table"]
    if not isinstance(file, str) or not file.strip():
        _fail(f"{where}.table", f"must be the path of a BEM law table, got {describe(file)}")
    path = (base / file) if base is not None else Path(file)
    try:
        samples = read_law_table(path)
    except ValueError as exc:
        _fail(f"{where}.table", str(exc))
    unit = samples.length_unit
    factor = 1.0  # deck stress per table stress: the deck's unit unless the table names its own
    if samples.stress_unit is not None:
        if not _named(samples.stress_unit, STRESS_UNITS):
            _fail(f"{where}.table", f"{path}: stress_unit {describe(samples.stress_unit)} is not one of "
                                    f"{', '.join(STRESS_UNITS)}")
        factor = STRESS_UNITS[samples.stress_unit] / 10.0 ** (-2 * LENGTH_UNITS[length_unit])
    surface = samples.moments if moments is None else moments_in(*moments, unit)
    try:
        law = normal_law_table(samples, moments=surface, stress_factor=factor)
    except ValueError as exc:
        _fail(f"{where}.table", f"{path}: {exc}")
    return TableFile(file, samples, law), surface, unit, law.E_star


def bem_material(law, length_unit: str, E_star: float, factors):
    """InteractionLaw.material of a BEM law (an InteractionLaw with ``table``): its table at the
    seating pressure (within the ladder's pressures), E* the table's (another is refused: the
    ladder was solved with it); k_T = ``factors`` × k_N(BEM)."""
    from .laws import _interface_material

    table = law.table.law
    if abs(E_star / table.E_star - 1.0) > UNIT_RTOL:
        raise LawError(f"E* = {E_star:g} differs from the BEM table's {table.E_star:g} ({law.table.file}) by more "
                       f"than {100 * UNIT_RTOL:g} %: solve the ladder with the deck's E*")
    if not table.p_light <= law.seating_pressure <= table.p_max:
        raise LawError(f"seating_pressure {law.seating_pressure:g} lies outside the BEM table's pressures "
                       f"{table.p_light:g} ... {table.p_max:g} ({law.table.file}): solve the ladder from below it")
    return _interface_material(law, length_unit, table, factors)
