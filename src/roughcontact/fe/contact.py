"""The interface law at the FE engine's integration points: the library's law, in the engine's
units and sign convention.

The engine works in mm and N (stresses N/mm², interface stiffness N/mm³) with the local jump
δ = (slip t1, slip t2, opening n) [mm] and tractions s = (t_x, t_y, σ_N) [N/mm²] conjugate to
it (σ_N = −p_N, tension positive). The physics is the library's and only the library's:
:func:`roughcontact.interface.friction.update` with an
:class:`~roughcontact.interface.InterfaceLaw` (the statistical normal law p_N(u_N), k_N(u_N),
k_T = a k_N, in the moments' length unit, µm for the paper's surfaces) or constant
stiffnesses, and one of the friction models (``Frictionless``, ``NoSlip``,
``IsotropicHardening``, ``OrthotropicHardening``). This module only

* converts lengths: the law's unit is ``length_per_mm`` of the engine's (1000: µm), so
  Δu_law = 1000 Δδ and D_engine = 1000 D_law (N/(mm²·µm) → N/mm³);
* converts the sign with :data:`~roughcontact.interface.friction.OPENING_SIGN`
  (the friction module owns the convention: u_N closes, p_N ≥ 0);
* keeps the committed state of every point and the trial state of the current iteration;
* gives the solver's trial states a response past the heavy end of a tabulated law
  (``respond(..., extrapolate=True)``: the law's tangent tail, InterfaceLaw.extrapolated) and
  says which converged states lie beyond it (:meth:`InterfaceMaterial.beyond_table`).

The state columns are friction's (T_X, T_Y, T_N = p_N, U_N = closure in the law's unit, …);
u_N = 0 is the law's reference state (the seating pressure p0 of the InterfaceLaw).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..interface import InterfaceLaw, friction
from ..validation import positive
from ..limits import describe

__all__ = ["InterfaceMaterial", "LawResponse", "MICROMETRES_PER_MM", "TANGENTIAL", "statistical_interface"]

#: the paper's surfaces have their moments in µm: the law's length unit per engine mm
MICROMETRES_PER_MM = 1000.0
_S = friction.OPENING_SIGN


class LawResponse(NamedTuple):
    """The law at every point for one trial jump increment: tractions (n, 3) [N/mm²]
    (t_x, t_y, σ_N), tangent ∂s/∂δ (n, 3, 3) [N/mm³], new friction states (n, 9), status (n,)
    (friction.STICK, SLIP, OPEN)."""

    tractions: np.ndarray
    tangent: np.ndarray
    state: np.ndarray
    status: np.ndarray


@dataclass(frozen=True, eq=False)
class InterfaceMaterial:
    """What the interface is made of: a normal law and a tangential (friction) model.

    normal          an InterfaceLaw (statistical law at its reference state), or a constant
                    normal stiffness k_N [stress per law length unit] (then give k_T).
    model           friction model: Frictionless(), NoSlip(), IsotropicHardening(...),
                    OrthotropicHardening(...) (slip-hardening n in 1/[law length unit]).
    k_T             (k_Tx, k_Ty) constant tangential stiffnesses, only with a constant k_N.
    length_per_mm   law length units per mm (1000 for moments in µm; 1 for a law in mm).
    closure0        initial closure u_N [law unit] of every point (a constant-k_N interface
                    pre-compressed by p = k_N·closure0; 0 = the InterfaceLaw's reference state).
    tangential_form reading of the elastic tangential law (93) with k_T = a k_N(u_N), one of
                    friction.TANGENTIAL_FORMS (friction.py, "Tangential forms"); passed to
                    friction.update; all coincide for constant stiffnesses.
    """

    normal: object
    model: object
    k_T: tuple[float, float] | None = None
    length_per_mm: float = MICROMETRES_PER_MM
    closure0: float = 0.0
    tangential_form: str = "incremental-end"

    def __post_init__(self):
        friction._as_model(self.model)  # TypeError for anything else
        if self.tangential_form not in friction.TANGENTIAL_FORMS:
            raise ValueError(f"tangential_form must be one of {', '.join(friction.TANGENTIAL_FORMS)}, "
                             f"got {describe(self.tangential_form)}")
        object.__setattr__(self, "length_per_mm", positive("length_per_mm", self.length_per_mm))
        if isinstance(self.normal, InterfaceLaw):
            if self.k_T is not None:
                raise ValueError("with an InterfaceLaw, k_T comes from the law (k_T = a k_N); do not pass k_T")
        else:
            positive("k_N", self.normal)
            if self.k_T is None or len(self.k_T) != 2:
                raise ValueError("a constant k_N needs k_T = (k_Tx, k_Ty)")
            for name, k in zip(("k_Tx", "k_Ty"), self.k_T):
                positive(name, k)

    @property
    def _stiffness(self) -> tuple:
        if isinstance(self.normal, InterfaceLaw):
            return (self.normal,)
        return (float(self.normal), float(self.k_T[0]), float(self.k_T[1]))

    def initial_state(self, n_points: int) -> np.ndarray:
        """Virgin states (n_points, 9) at closure ``closure0`` (p_N from the normal law)."""
        return friction.initial_state(n_points, u_N=self.closure0, k_N=self._stiffness[0])

    def respond(self, committed: np.ndarray, d_jump, *, extrapolate: bool = False) -> LawResponse:
        """The law for the jump increment d_jump (n, 3) [mm] since the committed states.
        ``extrapolate``: past the heavy end of a tabulated law its tangent tail instead of a
        ValueError (for trial states; judge converged ones with :meth:`beyond_table`)."""
        du = np.asarray(d_jump, dtype=float) * _S * self.length_per_mm
        stiffness = self._stiffness
        if extrapolate and isinstance(self.normal, InterfaceLaw):
            stiffness = (self._extrapolated,)
        new = friction.update(self.model, committed, du, *stiffness, tangential=self.tangential_form)
        tractions = new.state[:, :3] * _S
        tangent = new.D * (_S[:, None] * _S[None, :]) * self.length_per_mm
        return LawResponse(tractions, tangent, new.state, new.status)

    @functools.cached_property
    def _extrapolated(self):
        return self.normal.extrapolated()

    def beyond_table(self, state: np.ndarray) -> np.ndarray:
        """(n,) True where a state's closure lies past the heavy end of the tabulated law
        (u_N > u_max, p_N > p_max); all False for a constant k_N."""
        closure = np.asarray(state)[..., friction.U_N]
        if not isinstance(self.normal, InterfaceLaw):
            return np.zeros(closure.shape, dtype=bool)
        return closure > self.normal.u_max

    def closure_mm(self, state: np.ndarray) -> np.ndarray:
        """Closure u_N (n,) [mm] of states (relative to the law's reference state)."""
        return state[..., friction.U_N] / self.length_per_mm


#: tangential restraints of the statistical interface (section 9.1 leaves it open)
TANGENTIAL = ("free", "stick", "coulomb")


def statistical_interface(surface, p0: float, *, E_star: float | None = None, material=None,
                          tangential: str = "free", mu: float | None = None, kT_over_kN=None,
                          nu: float = 0.25, model=None, pressure_range=(1e-12, 100.0),
                          length_per_mm: float = MICROMETRES_PER_MM,
                          tangential_form: str = "incremental-end", validity: str = "refuse") -> InterfaceMaterial:
    """The interface of the paper: the statistical normal law of ``surface`` (elastic with
    ``E_star``, or elasto-plastic with an AsperityMaterial ``material``), seated at the pressure
    ``p0`` [N/mm²] (u_N = 0 there), with a tangential restraint:

    * ``"free"``    no tangential traction (Frictionless);
    * ``"stick"``   k_T = a k_N(u_N) without slip (NoSlip), (95)-(96);
    * ``"coulomb"`` k_T = a k_N(u_N) with a constant Coulomb limit μ (IsotropicHardening, μ_o = 1);
    * or ``model``: any friction model (e.g. the orthotropic hardening law of section 8.1).

    a = k_T/k_N: ``kT_over_kN`` (a factor or a pair (x, y)) or, by default, Mindlin's ratio
    (96)/Table 3 for the representative summit ellipse of the surface
    (:func:`roughcontact.interface.tangential.representative_aspect`) and Poisson's ratio ``nu``.
    ``pressure_range`` [N/mm²]: the tabulated range (below it the law's tail to open contact).
    Lengths of the law in the moments' unit (µm: ``length_per_mm`` = 1000).
    ``tangential_form``: the reading of (93) with k_T = a k_N(u_N) (InterfaceMaterial).
    ``validity``: the table's heavy end against the model's range (NormalLawTable.build)."""
    from ..interface import NormalLawTable, mindlin_kT_over_kN
    from ..interface.tangential import representative_aspect

    if model is None:
        if tangential not in TANGENTIAL:
            raise ValueError(f"tangential must be one of {', '.join(TANGENTIAL)}, got {describe(tangential)}")
        if tangential == "coulomb":
            model = friction.IsotropicHardening(mu_m=positive("mu", mu if mu is not None else math.nan))
        elif mu is not None:
            raise ValueError(f"mu is only used with tangential='coulomb' (got tangential={describe(tangential)})")
        else:
            model = friction.Frictionless() if tangential == "free" else friction.NoSlip()
    if (E_star is None) == (material is None):
        raise ValueError("give exactly one of E_star (elastic law) and material (elasto-plastic law)")
    if material is None:
        table = NormalLawTable.build(surface, "elastic", E_star=E_star, pressure_range=pressure_range, accuracy="plot",
                                     validity=validity)
    else:
        table = NormalLawTable.build(surface, "elastoplastic", material=material, pressure_range=pressure_range,
                                     accuracy="plot", validity=validity)
    if kT_over_kN is None:
        kT_over_kN = mindlin_kT_over_kN(representative_aspect(surface), nu)
    law = InterfaceLaw.from_pressure(table, p0, kT_over_kN)
    return InterfaceMaterial(law, model, length_per_mm=length_per_mm, tangential_form=tangential_form)
