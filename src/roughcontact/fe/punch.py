"""Example 9.2 of Buczkowski & Kleiber (2009): an elastic flat punch on an elastic foundation with
orthotropic hardening friction (Figs 14, 15, 18, 19; Table 5), loaded and unloaded.

The punch (20 × 20 × 10 mm) and the foundation (100 × 100 × 50 mm), both E = 200 GPa, ν = 0.25,
meet through the statistical interface of the Fig. 18 surface; a quarter model by symmetry
(:mod:`.punch_mesh`). The loading: a seating pressure ``seating_pressure`` on the punch's whole
top face (a dead load, the interface law's reference state: every relative displacement is
measured from the seated state), then a uniform pressure on a centred patch of the top face
raised in ``increments`` equal steps to ``load`` and lowered in ``unload_increments`` to zero.

What the paper leaves open is a stated, switchable choice here:
* ``load_on`` "whole" (default): ``load`` is the load on the whole punch (the quarter carries a
  quarter of it) — or "quarter": on the quarter model;
* the patch side (``PunchGeometry.load_patch``, default the punch's central element);
* ``tangential_form``: how the load-dependent k_T enters the elastic tangential law (93)
  (:data:`roughcontact.interface.friction.TANGENTIAL_FORMS`);
* the dissipation D (:func:`dissipation`): at the maximum load or the end, per point
  t_T·u_T^p weighted by the point's area (N·mm) or not (N/mm), the quarter or the whole punch,
  and the dissipated work ∫ t_T·du_T^p;
* the foundation's base is supported normally (u_z = 0; the symmetry planes u_x = 0, u_y = 0 of
  both bodies fix its in-plane rigid motions), its outer lateral faces are free.

:func:`frictionless_bound` is the upper bound of D from the frictionless problem (friction can
only reduce the relative slip, and |t_T| ≤ μ p_N): D ≤ μ_max Σ_q w_q p_N,q |δ_T,free,q|.
"""

from __future__ import annotations

import functools
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from ..interface import friction
from ..validation import choice, positive
from . import assembly
from .contact import InterfaceMaterial
from .mesh import Mesh, dofs
from .punch_mesh import PunchGeometry, punch_mesh
from .solver import ContactModel, NewtonOptions, Solution, solve

__all__ = ["PunchSpec", "PunchResult", "punch_model", "run_punch", "punch_case", "dissipation", "bound",
           "frictionless_bound", "fig18_interface_model", "mu_max", "to_dataset", "LOAD_ON"]

LOAD_ON = ("whole", "quarter")


@dataclass(frozen=True)
class PunchSpec:
    """Example 9.2: geometry and discretisation, material [N/mm²], loads [N], increments."""

    geometry: PunchGeometry = field(default_factory=PunchGeometry)
    E: float = 2.0e5
    nu: float = 0.25
    load: float = 1000.0
    load_on: str = "whole"
    seating_pressure: float = 0.1
    increments: int = 16
    unload_increments: int = 16
    rule: str = "lobatto"

    def __post_init__(self):
        for name in ("E", "load", "seating_pressure"):
            positive(name, getattr(self, name))
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"nu must lie in (-1, 0.5), got {self.nu!r}")
        choice("load_on", self.load_on, LOAD_ON)
        choice("rule", self.rule, ("lobatto", "gauss"))
        for name in ("increments", "unload_increments"):
            v = getattr(self, name)
            if int(v) != v or v < (1 if name == "increments" else 0):
                raise ValueError(f"{name} must be a {'positive' if name == 'increments' else 'non-negative'} "
                                 f"integer, got {v!r}")

    @property
    def quarter_load(self) -> float:
        """The load on the quarter model at the maximum [N]."""
        return self.load / 4.0 if self.load_on == "whole" else self.load

    @property
    def levels(self) -> np.ndarray:
        """Patch load levels on the quarter [N]: 0 (seated), up in ``increments`` steps to the
        maximum, down in ``unload_increments`` steps to 0."""
        up = np.linspace(0.0, self.quarter_load, self.increments + 1)
        down = np.linspace(self.quarter_load, 0.0, self.unload_increments + 1)[1:]
        return np.concatenate([up, down])

    @property
    def max_index(self) -> int:
        """The index of the maximum load among the levels."""
        return self.increments


def fig18_interface_model(case: str, n_per_mm: float = 275.0, length_per_mm: float = 1000.0):
    """The friction model and k_T/k_N factors of Fig. 18/19 case "a", "b" or "c"
    (:data:`roughcontact.interface.friction.FIG18_CASES`: μ_m, μ_o, ν_x = ν_y (k = 0: circular
    potential), k_Tx, k_Ty), with n = 275 1/mm (section 9.2) in the law's length unit."""
    choice("case", case, tuple(friction.FIG18_CASES))
    c = friction.FIG18_CASES[case]
    n = n_per_mm / length_per_mm
    model = friction.OrthotropicHardening(c["mu_m"], c["mu_m"], c["mu_o"], c["mu_o"], n, n, k=0.0)
    return model, (c["kTx_over_kN"], c["kTy_over_kN"])


def mu_max(case: str) -> float:
    """The largest friction coefficient a Fig. 18 case reaches: (89) runs from μ_m μ_o (no slip)
    to μ_m (κ → ∞), so the largest is μ_m·max(1, μ_o) over both axes."""
    model, _ = fig18_interface_model(case)
    return max(model.mu_m_x * max(1.0, model.mu_o_x), model.mu_m_y * max(1.0, model.mu_o_y))


def punch_model(spec: PunchSpec, material: InterfaceMaterial) -> ContactModel:
    """The discrete quarter model: both bodies' stiffness, the interface, the supports, the
    seating pressure on the punch top as dead load and the patch load pattern (1 N on the
    quarter per unit level). Cases a, b, c and the frictionless run of one spec share one model
    (and its factorised bulk) with their own interface materials."""
    return _bulk_model(spec)[1].with_material(material)


@functools.lru_cache(maxsize=4)
def _bulk_model(spec: PunchSpec) -> tuple[Mesh, ContactModel]:
    """The mesh and model of a spec, with a placeholder material (replaced by :func:`punch_model`)."""
    mesh = punch_mesh(spec.geometry)
    material = InterfaceMaterial(1.0, friction.Frictionless(), k_T=(1.0, 1.0))
    ns = mesh.node_sets
    fixed = np.concatenate([
        dofs(ns["foundation.zmin"], (2,)),
        dofs(np.union1d(ns["foundation.xmin"], ns["punch.xmin"]), (0,)),
        dofs(np.union1d(ns["foundation.ymin"], ns["punch.ymin"]), (1,)),
    ])
    top, patch = mesh.face_sets["punch.zmax"], mesh.face_sets["punch.load_patch"]
    dead = assembly.surface_traction(mesh.points, top.face_element, top.face_nodes, (0.0, 0.0, -spec.seating_pressure))
    area = float(np.sum(assembly.face_area(mesh.points, patch.face_element, patch.face_nodes)))
    load = assembly.surface_traction(mesh.points, patch.face_element, patch.face_nodes, (0.0, 0.0, -1.0 / area))
    model = ContactModel.assemble(mesh, assembly.isotropic_elasticity(spec.E, spec.nu), material, fixed, load,
                                  dead_load=dead, rule=spec.rule)
    return mesh, model


@dataclass(frozen=True, eq=False)
class PunchResult:
    """Example 9.2 results: the solution (every load level), the mesh, sizes and time."""

    spec: PunchSpec
    solution: Solution
    mesh: Mesh
    n_dofs: int
    n_points: int
    seconds: float

    @property
    def max_increment(self):
        return self.solution.increments[self.spec.max_index]

    def slip_directions(self, k: int | None = None) -> dict[str, np.ndarray]:
        """Per contact point of the quarter at level k (default: the maximum load): x, y [mm],
        plastic slips u_x^p, u_y^p [µm], tractions t_x, t_y, p_N [N/mm²], status (0 stick,
        1 slip, 2 open) and, with a friction limit, the share of it used (utilisation) — Figs 18/19."""
        inc = self.solution.increments[self.spec.max_index if k is None else k]
        x = self.solution.model.points.x
        return {"x_mm": x[:, 0], "y_mm": x[:, 1], **_law_fields(inc.state, self.solution.model.material),
                "status": inc.status.astype(int)}

    def write_vtu(self, path, points_path=None):
        """Both bodies with their displacements at the maximum load to ``path`` and the contact
        points with :meth:`slip_directions` to ``points_path`` (default: path's stem +
        "_interface.vtu"), for ParaView."""
        from .vtu import write_solution

        fields = {k: np.asarray(v) for k, v in self.slip_directions().items() if k not in ("x_mm", "y_mm")}
        return write_solution(path, self.mesh, self.max_increment.u,
                              {"x": self.solution.model.points.x, **fields}, points_path)


def _law_fields(state: np.ndarray, material: InterfaceMaterial) -> dict[str, np.ndarray]:
    """From law states (..., NSTATE): tractions t_x, t_y, p_N [N/mm²], plastic slips slip_x_um,
    slip_y_um [µm] and, with a friction limit, the share of it used (utilisation)."""
    per_um = 1000.0 / material.length_per_mm  # law length unit → µm
    out = {"t_x": state[..., friction.T_X], "t_y": state[..., friction.T_Y], "p_N": state[..., friction.T_N],
           "slip_x_um": state[..., friction.UP_X] * per_um, "slip_y_um": state[..., friction.UP_Y] * per_um}
    if isinstance(material.model, friction.OrthotropicHardening):
        out["utilisation"] = friction.utilisation(material.model, state)
    return out


def _history(result: "PunchResult") -> dict[str, np.ndarray]:
    """(level, point) arrays of the whole load history."""
    sol = result.solution
    pts = sol.model.points
    seated = pts.jumps(sol.increments[0].u)
    jumps = np.stack([pts.jumps(inc.u) - seated for inc in sol.increments])
    return {**_law_fields(np.stack([inc.state for inc in sol.increments]), sol.model.material),
            "jump_x_um": jumps[..., 0] * 1000.0, "jump_y_um": jumps[..., 1] * 1000.0,
            "status": np.stack([inc.status for inc in sol.increments]).astype(np.int32)}


def to_dataset(result: "PunchResult"):
    """An ``xarray.Dataset`` of the whole history: per load level (the patch load on the quarter
    and on the whole punch) and contact point (x, y, weight) the tractions, plastic slips, relative
    tangential displacements from the seated state and status; D under every reading and the
    sizes as attributes."""
    import xarray as xr

    h = _history(result)
    pts = result.solution.model.points
    units = {"t_x": "N/mm^2", "t_y": "N/mm^2", "p_N": "N/mm^2", "slip_x_um": "um", "slip_y_um": "um",
             "jump_x_um": "um", "jump_y_um": "um", "status": "1", "utilisation": "1"}
    long = {"t_x": "tangential traction t_x", "t_y": "tangential traction t_y", "p_N": "contact pressure p_N",
            "slip_x_um": "plastic slip u_x^p", "slip_y_um": "plastic slip u_y^p",
            "jump_x_um": "relative displacement from the seated state, x", "jump_y_um": "idem, y",
            "status": "0 stick, 1 slip, 2 open",
            "utilisation": "share of the friction limit used, (f + p_N)/p_N of (91): 1 slip, < 1 stick"}
    data = {k: (("level", "point"), v, {"units": units[k], "long_name": long[k]}) for k, v in h.items()}
    levels = np.asarray([inc.level for inc in result.solution.increments])
    data["load_quarter"] = ("level", levels, {"units": "N", "long_name": "patch load on the quarter model"})
    data["newton_iterations"] = ("level", np.asarray([i.iterations for i in result.solution.increments]),
                                 {"units": "1", "long_name": "Newton iterations of the load level"})
    data["point_weight"] = ("point", pts.weights, {"units": "mm^2", "long_name": "area of the contact point"})
    ds = xr.Dataset(data, coords={"x": ("point", pts.x[:, 0], {"units": "mm", "long_name": "x of the contact point"}),
                                  "y": ("point", pts.x[:, 1], {"units": "mm", "long_name": "y of the contact point"})})
    for at in ("max", "end"):
        for weight in ("area", "none", "work"):
            ds.attrs[f"D_{at}_{weight}_whole"] = dissipation(result, at=at, weight=weight, whole=True)
    summ = summary_of(result)
    k = result.spec.max_index
    if "utilisation" in h:
        ds.attrs["utilisation_max"] = float(np.max(h["utilisation"][k]))
    ds.attrs["slipped_points"] = int(np.count_nonzero(np.hypot(h["slip_x_um"][k], h["slip_y_um"][k]) > 0.0))
    ds.attrs.update(dofs=summ["dofs"], interface_points=summ["interface_points"], seconds=summ["seconds"],
                    cutbacks=summ["cutbacks"], equilibrium_error_max_load=summ["equilibrium_error_max_load"],
                    max_index=result.spec.max_index, spec=summ["spec"])
    return ds


def run_punch(spec: PunchSpec, material: InterfaceMaterial, *, options: NewtonOptions | None = None,
              progress=None) -> PunchResult:
    """Solve example 9.2 through all load levels (seated, loading, unloading)."""
    t0 = time.perf_counter()
    model = punch_model(spec, material)
    sol = solve(model, spec.levels, options, progress)
    return PunchResult(spec, sol, _bulk_model(spec)[0], model.n_dofs, model.points.n_points,
                       time.perf_counter() - t0)


def dissipation(result: PunchResult, *, at: str = "max", weight: str = "area", whole: bool = True) -> float:
    """Frictional dissipation of the contact points.

    at      "max": at the maximum load; "end": after unloading.
    weight  "area": Σ_q w_q t_T·u_T^p [N·mm] (traction × the point's area × plastic slip: the
            paper's D = t_T·u_T^p of section 9.2 summed over the points, in its unit N·mm);
            "none": Σ_q t_T·u_T^p [N/mm] (the points unweighted);
            "work": Σ_q w_q ∫ t_T·du_T^p [N·mm] (the energy actually dissipated).
    whole   the whole punch (4 × the quarter) or the quarter model.
    """
    choice("at", at, ("max", "end"))
    choice("weight", weight, ("area", "none", "work"))
    inc = result.solution.increments[result.spec.max_index if at == "max" else -1]
    per_mm = 1.0 / result.solution.model.material.length_per_mm  # law length unit → mm
    s = inc.state
    if weight == "work":
        per_point = s[:, friction.DISSIPATION] * per_mm
    else:
        per_point = (s[:, friction.T_X] * s[:, friction.UP_X] + s[:, friction.T_Y] * s[:, friction.UP_Y]) * per_mm
    w = result.solution.model.points.weights if weight in ("area", "work") else 1.0
    return float(np.sum(w * per_point)) * (4.0 if whole else 1.0)


def bound(weights, p_N, free_slip, mu_max: float, *, whole: bool = True) -> float:
    """μ_max Σ_q w_q p_N,q |δ_T,free,q|: the upper bound of the area-weighted D [N·mm] from the
    points' areas w [mm²], the frictional run's pressures p_N [N/mm²] at the maximum load and the
    relative tangential displacements |δ_T,free| [mm] of the frictionless run there (friction
    only reduces the relative slip, and |t_T| ≤ μ p_N); × 4 for the whole punch."""
    positive("mu_max", mu_max)
    w, p, d = (np.asarray(v, dtype=float) for v in (weights, p_N, free_slip))
    if not (w.shape == p.shape == d.shape):
        raise ValueError("weights, p_N and free_slip must belong to the same contact points")
    return float(mu_max * np.sum(w * p * d)) * (4.0 if whole else 1.0)


def frictionless_bound(frictional: PunchResult, frictionless: PunchResult, mu_max: float, *,
                       whole: bool = True) -> float:
    """:func:`bound` of a frictional run from the frictionless run of the same mesh and loads."""
    free_sol, pts = frictionless.solution, frictionless.solution.model.points
    jump = pts.jumps(free_sol.increments[frictionless.spec.max_index].u) - pts.jumps(free_sol.increments[0].u)
    p = -frictional.max_increment.tractions[:, 2]
    return bound(pts.weights, p, np.hypot(jump[:, 0], jump[:, 1]), mu_max, whole=whole)


def summary_of(result: PunchResult) -> dict:
    """Sizes, iterations, times and the spec, JSON-ready."""
    incs = result.solution.increments
    return {"dofs": result.n_dofs, "interface_points": result.n_points, "seconds": result.seconds,
            "newton_iterations": [int(i.iterations) for i in incs], "cutbacks": int(sum(i.cutbacks for i in incs)),
            "equilibrium_error_max_load": result.solution.equilibrium_error(result.spec.max_index),
            "spec": {**{k: v for k, v in asdict(result.spec).items() if k != "geometry"},
                     "geometry": asdict(result.spec.geometry)}}


def punch_case(run, progress=None) -> PunchResult:
    """Solve one run of example 9.2 described by a plain dict (the workflow's configuration):
    ``case`` ("a" | "b" | "c": Fig. 18's friction parameters; "frictionless": no tangential
    restraint, for the bound), ``m00`` [µm²] and ``surface`` (m20, m02, m40, m04), ``law``
    (elastic | elastoplastic) with ``psi``, ``E_star`` [N/mm²] (None: two like bodies,
    E/(2(1 − ν²)), eq. (42)), ``tangential_form``, and the spec: ``load``, ``load_on``,
    ``seating_pressure``, ``increments``, ``unload_increments``, ``geometry`` (PunchGeometry
    fields: family, load_patch, mesh counts)."""
    from ..asperity import effective_modulus
    from ..contact import resolve_material
    from ..statistics import SpectralMoments
    from .contact import statistical_interface

    spec = PunchSpec(geometry=PunchGeometry(**run.get("geometry", {})),
                     **{k: run[k] for k in ("load", "load_on", "seating_pressure", "increments", "unload_increments")
                        if k in run})
    surface = SpectralMoments(m00=run["m00"], **run["surface"])
    E_star = run.get("E_star") or effective_modulus(spec.E, spec.nu, spec.E, spec.nu)  # eq. (42)
    law = ({"E_star": E_star} if run["law"] == "elastic"
           else {"material": resolve_material(surface, E_star=E_star, psi=run["psi"])})
    if run["case"] == "frictionless":
        model, factors = friction.Frictionless(), (0.7, 0.7)
    else:
        model, factors = fig18_interface_model(run["case"])
    material = statistical_interface(surface, spec.seating_pressure, model=model, kT_over_kN=factors,
                                     tangential_form=run.get("tangential_form", "incremental-end"),
                                     # headroom to 1e4 N/mm² for the punch's edges: past A/A0 = 1
                                     # (2.2 at s = -2.5 on the Fig. 18 surface) the law has no
                                     # meaning, so the build warns (contact.validity) instead of
                                     # refusing a range the runs need not reach
                                     pressure_range=(1e-12, 1e4), validity="warn", **law)
    return run_punch(spec, material, progress=progress)
