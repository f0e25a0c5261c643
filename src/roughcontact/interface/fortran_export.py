"""The interface law of section 8 for Fortran FE codes: the data of one law as a Fortran module.

The law itself is Fortran source shipped with the package (``interface/fortran/``):
``roughcontact_law.f90`` ports the numba kernels of :mod:`.kernels` line by line (the tabulated
normal law of :mod:`.normal_law` and the friction return mapping of :mod:`.friction`, whose
docstring owns the algorithm and the sign convention), ``uinter.f90`` wraps it as an Abaqus
UINTER (docs/fortran-law.md). What differs from law to law is data, written here by
:func:`law_data_module` as the module ``roughcontact_law_data`` from the very objects the FE
engine evaluates (an :class:`.InterfaceLaw` and a friction model):

* the kernel table of the *extrapolated* law (:meth:`.InterfaceLaw.extrapolated`: the rows
  (h, q, q', q'') of :attr:`.NormalLawTable.kernel_table` plus the tangent tail past the heavy
  end that the engine uses for its trial states), the reference separation h_ref and the
  tabulated end u_max, p_max (a state beyond them lies in the tail: the Fortran code cannot
  tell a trial state from a converged one, the user checks p_N ≤ p_max);
* the tangential factors (k_Tx/k_N, k_Ty/k_N), the model code and its parameters
  (``model.params()``: the layout of the kernels), the tangential form (friction.TANGENTIAL_FORMS)
  and the return-mapping tolerance (friction.update's default 1e-12);
* for the wrapper: the interaction name, the lay direction in the deck's axes and the law's
  length units per deck length unit (µm per mm = 1000).

Numbers are written with 17 significant digits (``%.17e`` with a ``d`` exponent): each reads
back to the same double. The table is one DATA statement per row, so that a long table needs no
continuation lines (Fortran 2008 allows 255).

Units: as the engine's law — lengths of the table, h_ref, u_max and n_x, n_y in the law's
length unit (the moments' unit); pressures and stiffnesses in the unit of E* (the deck's stress
unit) and per law length.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from importlib import resources

import numpy as np

from ..limits import describe
from .friction import (FORM_END, FORM_SECANT, FORM_START, Frictionless, IsotropicHardening, NoSlip,
                       OrthotropicHardening, TANGENTIAL_FORMS)
from .normal_law import InterfaceLaw

__all__ = ["MODEL_CODES", "SOURCES", "DATA_FILE", "LawConstants", "fortran_source", "law_constants", "law_data_module"]

#: the model codes of roughcontact_law.f90 (RC_NO_LIMIT, RC_ISOTROPIC, RC_ORTHOTROPIC)
MODEL_CODES = {Frictionless: 0, NoSlip: 0, IsotropicHardening: 1, OrthotropicHardening: 2}
_FORM_CODES = dict(zip(TANGENTIAL_FORMS, (FORM_END, FORM_START, FORM_SECANT)))
#: the static sources, in compilation order (the law, then the Abaqus wrapper; the generated
#: data module DATA_FILE goes between them)
SOURCES = ("roughcontact_law.f90", "uinter.f90")
DATA_FILE = "roughcontact_law_data.f90"
#: Abaqus passes names in CHARACTER*80, upper case
_NAME_LENGTH = 80


def fortran_source(name: str) -> str:
    """The text of a shipped Fortran source (one of :data:`SOURCES`)."""
    if name not in SOURCES:
        raise ValueError(f"no Fortran source {describe(name)} (the sources are {', '.join(SOURCES)})")
    return resources.files(__package__).joinpath("fortran", name).read_text(encoding="utf-8")


def _real(x, what: str) -> str:
    """A double-precision literal that reads back to the same double."""
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"{what} is not finite ({describe(x)}): no Fortran literal for it")
    return f"{x:.17e}".replace("e", "d")


def _array(values, what: str) -> str:
    """An array constructor, two values a line (free-form lines stay below 132 characters)."""
    items = [_real(v, what) for v in values]
    rows = [", ".join(items[i:i + 2]) for i in range(0, len(items), 2)]
    return "(/ " + ", &\n       ".join(rows) + " /)"


def _name(interaction: str) -> str:
    name = str(interaction).upper()
    if not name or len(name) > _NAME_LENGTH or not all(c.isalnum() or c in "_-." for c in name):
        raise ValueError(f"interaction name {describe(interaction)}: 1 to {_NAME_LENGTH} letters, digits, '_', '-', '.'")
    return name


@dataclass(frozen=True)
class LawConstants:
    """What roughcontact_law.f90's rc_update needs of one law (the module docstring's list):
    model and tangential-form codes, the return mapping's tolerance, h_ref [law length], the
    tangential factors stiff = (k_Tx/k_N, k_Ty/k_N, 1), the model's parameters ``par``, the
    kernel table ``tab`` (n, 4) of the extrapolated law, u_max, p_max, law_per_deck and the lay."""

    model: int
    form: int
    tol: float
    h_ref: float
    stiff: tuple
    par: np.ndarray
    tab: np.ndarray
    u_max: float
    p_max: float
    law_per_deck: float
    lay: tuple


def law_constants(law: InterfaceLaw, model, *, law_per_deck: float, lay_direction=(1.0, 0.0, 0.0),
                  tangential_form: str = "incremental-end", tol: float = 1e-12) -> LawConstants:
    """The :class:`LawConstants` of an engine law (arguments as :func:`law_data_module`),
    checked: one-line errors for anything the Fortran cannot take."""
    if not isinstance(law, InterfaceLaw):
        raise TypeError(f"law must be an InterfaceLaw, got {type(law).__name__}")
    if type(model) not in MODEL_CODES:
        raise TypeError("model must be Frictionless, NoSlip, IsotropicHardening or OrthotropicHardening, "
                        f"got {type(model).__name__}")
    if tangential_form not in _FORM_CODES:
        raise ValueError(f"tangential_form must be one of {', '.join(TANGENTIAL_FORMS)}, got {describe(tangential_form)}")
    if not (0.0 < float(tol) <= 1e-6):
        raise ValueError(f"tol must be in (0, 1e-6], got {describe(tol)}")
    if not (math.isfinite(float(law_per_deck)) and float(law_per_deck) > 0.0):
        raise ValueError(f"law_per_deck must be positive and finite, got {describe(law_per_deck)}")
    lay = [float(v) for v in lay_direction]
    if len(lay) != 3 or not all(map(math.isfinite, lay)) or math.hypot(*lay) == 0.0:
        raise ValueError(f"lay_direction must be a non-zero vector [x, y, z], got {describe(lay_direction)}")
    tab, h_ref, (ax, ay) = law.extrapolated().kernel_data()
    for what, values in (("the law table", tab), ("a friction parameter", model.params()), ("h_ref", [h_ref]),
                         ("k_T/k_N", [ax, ay])):
        bad = ~np.isfinite(np.asarray(values, dtype=float))
        if np.any(bad):
            raise ValueError(f"{what} is not finite ({describe(np.asarray(values, dtype=float)[bad][0])})")
    return LawConstants(MODEL_CODES[type(model)], _FORM_CODES[tangential_form], float(tol), float(h_ref),
                        (float(ax), float(ay), 1.0), np.asarray(model.params(), dtype=float), np.asarray(tab, dtype=float),
                        float(law.u_max), float(law.table.p_max), float(law_per_deck), tuple(lay))


def law_data_module(law: InterfaceLaw, model, *, interaction: str, law_per_deck: float,
                    lay_direction=(1.0, 0.0, 0.0), tangential_form: str = "incremental-end", tol: float = 1e-12,
                    header: tuple[str, ...] = ()) -> str:
    """The Fortran module ``roughcontact_law_data`` of one interaction's law (module docstring).

    law             the engine's InterfaceLaw (tabulated p_N(u_N), k_N(u_N), k_T = a k_N).
    model           Frictionless, NoSlip, IsotropicHardening or OrthotropicHardening (n in
                    1/law length, as the engine's InterfaceMaterial holds it).
    interaction     the *SURFACE INTERACTION name (UINTER checks CINAME against it).
    law_per_deck    law length units per deck length unit (fe.laws.InteractionLaw.law_per_deck).
    lay_direction   the lay (the law's x axis) in the deck's axes, for UINTER's local frame.
    tangential_form one of friction.TANGENTIAL_FORMS; tol: the return mapping's (0, 1e-6].
    header          comment lines (provenance) for the top of the file.
    """
    c = law_constants(law, model, law_per_deck=law_per_deck, lay_direction=lay_direction,
                      tangential_form=tangential_form, tol=tol)
    name = _name(interaction)
    tab, par, (ax, ay, _) = c.tab, c.par, c.stiff
    n = tab.shape[0]
    lines = [f"! {line}" for line in header]
    lines += [
        "! Generated by roughcontact (interface.fortran_export): the data of one interface law for",
        "! roughcontact_law.f90 and uinter.f90. Do not edit: regenerate from the law file.",
        "module roughcontact_law_data",
        "  use roughcontact_law, only: rc_dp",
        "  implicit none",
        "  private",
        f"  character(len=*), parameter, public :: rc_interaction = '{name}'",
        f"  integer, parameter, public :: rc_model = {c.model}"
        f"  ! {type(model).__name__}",
        f"  integer, parameter, public :: rc_npar = {par.size}",
        f"  real(rc_dp), parameter, public :: rc_par(rc_npar) = {_array(par, 'a friction parameter')}",
        "  ! (k_Tx/k_N, k_Ty/k_N, unused): k_T = a k_N(u_N)",
        f"  real(rc_dp), parameter, public :: rc_stiff(3) = {_array((ax, ay, 1.0), 'k_T/k_N')}",
        f"  integer, parameter, public :: rc_form = {c.form}  ! {tangential_form}",
        f"  real(rc_dp), parameter, public :: rc_tol = {_real(tol, 'tol')}",
        "  ! reference separation h_ref [law length]: u_N = h_ref - h, p_N(0) = the seating pressure",
        f"  real(rc_dp), parameter, public :: rc_h_ref = {_real(c.h_ref, 'h_ref')}",
        "  ! the tabulated heavy end: closures u_N > rc_u_max (p_N > rc_p_max) lie in the tangent tail",
        f"  real(rc_dp), parameter, public :: rc_u_max = {_real(c.u_max, 'u_max')}",
        f"  real(rc_dp), parameter, public :: rc_p_max = {_real(c.p_max, 'p_max')}",
        "  ! law length units per deck length unit; the lay (the law's x axis) in the deck's axes",
        f"  real(rc_dp), parameter, public :: rc_law_per_deck = {_real(law_per_deck, 'law_per_deck')}",
        f"  real(rc_dp), parameter, public :: rc_lay(3) = {_array(c.lay, 'lay_direction')}",
        f"  integer, parameter, public :: rc_ntab = {n}",
        "  ! rows (h, q = ln p_N, q', q''), h ascending: NormalLawTable.kernel_table with the heavy tail",
        "  real(rc_dp), public :: rc_tab(rc_ntab, 4)",
    ]
    for i, row in enumerate(tab, start=1):
        values = [_real(v, f"table row {i}") for v in row]
        lines.append(f"  data rc_tab({i}, :) / {values[0]}, {values[1]}, &")
        lines.append(f"       {values[2]}, {values[3]} /")
    lines.append("end module roughcontact_law_data")
    return "\n".join(lines) + "\n"
