"""Example 9.2 of Buczkowski & Kleiber (2009) as an input deck: an elastic flat punch on an elastic
foundation with orthotropic hardening friction (Figs 14, 15, 18, 19; Table 5), loaded and
unloaded, run through the engine's deck reader.

The punch (20 × 20 × 10 mm) and the foundation (100 × 100 × 50 mm), both E = 200 GPa, ν = 0.25,
meet through the statistical interface of the Fig. 18 surface; a quarter model by symmetry
(:mod:`.punch_geometry`). The deck (:func:`punch_deck`; ``src/roughcontact/examples/decks/punch.inp``):
step 1 a seating pressure ``seating_pressure`` on the punch's whole top face (one increment: the
interface law's reference state, every relative displacement is measured from it), step 2 a
uniform pressure on a centred patch of the top raised in ``increments`` equal increments to
``load`` (``*DLOAD`` on the patch: the seating pressure plus the patch's), step 3 back to the
seating pressure in ``unload_increments``.

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

The friction cases (a), (b), (c) of Fig. 18 are three law files of the same deck
(``decks/punch-a.yaml`` …), the orthotropic law of section 8.1 with n = 275 1/mm.

:func:`frictionless_bound` is an upper bound of D from the frictionless problem (friction can
only reduce the relative slip, and |t_T| ≤ μ p_N): D ≤ μ_max Σ_q w_q p_N,q |δ_T,free,q|, the
relative displacement δ taken from the unloaded start, where the plastic slips of D start too
(the seating increment may slip).
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field, replace

import numpy as np

from ..fe.deck import read_deck
from ..fe.deck_run import DeckResult, run_deck_file
from ..fe.deck_writer import box_part, element_lines, id_lines, node_lines, number
from ..fe.laws import InteractionLaw, LawFile, NoFriction, Orthotropic
from ..fe.solver import NewtonOptions
from ..interface import friction
from ..validation import choice, positive
from .punch_geometry import BASE, SYMMETRY_X, SYMMETRY_Y, PunchGeometry
from .section9 import FIG18_CASES, FIG18_NU, N_PER_MM, PUNCH, PUNCH_M00, PUNCH_PSI, SURFACE, OnSurface
from ..limits import describe

__all__ = ["PunchSpec", "PunchRun", "PunchResult", "punch_deck", "punch_mesh", "summary", "run_punch", "dissipation", "bound",
           "frictionless_bound", "mu_max", "to_dataset", "summary_of", "LOAD_ON", "CASES", "PRESSURE_RANGE"]

LOAD_ON = ("whole", "quarter")
CASES = ("a", "b", "c", "frictionless")
#: the tabulated range of the normal law [N/mm²], with headroom to 1e4 for the punch's edges:
#: past A/A0 = 1 the law has no meaning, which the run reports from its solved pressures
PRESSURE_RANGE = (1e-12, 1e4)
INTERACTION = "ROUGH"


@dataclass(frozen=True)
class PunchSpec:
    """Example 9.2: geometry and discretisation, material [N/mm²], loads [N], increments."""

    geometry: PunchGeometry = field(default_factory=PunchGeometry)
    E: float = PUNCH["E"]
    nu: float = PUNCH["nu"]
    load: float = PUNCH["load"]
    load_on: str = "whole"
    seating_pressure: float = 0.1
    increments: int = PUNCH["increments"]
    unload_increments: int = PUNCH["increments"]

    def __post_init__(self):
        for name in ("E", "load", "seating_pressure"):
            positive(name, getattr(self, name))
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"nu must lie in (-1, 0.5), got {describe(self.nu)}")
        choice("load_on", self.load_on, LOAD_ON)
        for name in ("increments", "unload_increments"):
            v = getattr(self, name)
            if isinstance(v, bool) or int(v) != v or v < (1 if name == "increments" else 0):
                raise ValueError(f"{name} must be a {'positive' if name == 'increments' else 'non-negative'} "
                                 f"integer, got {describe(v)}")

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


def punch_deck(spec: PunchSpec = PunchSpec(), digits: int | None = None) -> str:
    """The deck of the quarter punch on its foundation (module docstring)."""
    g = spec.geometry
    xy, fxy = g.punch_edges(), g.foundation_xy_edges()
    foundation = box_part(fxy, fxy, g.foundation_z_edges())
    punch = box_part(xy, xy, g.punch_z_edges(), first_node=int(foundation.node_ids[-1]) + 1,
                     first_element=int(foundation.element_ids[-1]) + 1)
    top = punch.face_elements["ZMAX"]
    centre = punch.coords[punch.connectivity[top - punch.element_ids[0], :8] - punch.node_ids[0]].mean(axis=1)
    patch = top[(centre[:, 0] < g.load_half) & (centre[:, 1] < g.load_half)]
    pressure = spec.quarter_load / g.load_half ** 2  # the patch's faces tile [0, load_half]²
    head = ["*HEADING", "Example 9.2 (Buczkowski & Kleiber 2009): quarter of a punch on a foundation, mm N",
            "** generated by roughcontact.examples.punch.punch_deck", *node_lines(foundation, "FOUNDATIONNODES", digits),
            *node_lines(punch, "PUNCHNODES", digits), *element_lines(foundation, "FOUNDATION"),
            *element_lines(punch, "PUNCH"),
            *id_lines(f"*NSET, NSET={SYMMETRY_X}", np.concatenate([foundation.face_nodes["XMIN"], punch.face_nodes["XMIN"]])),
            *id_lines(f"*NSET, NSET={SYMMETRY_Y}", np.concatenate([foundation.face_nodes["YMIN"], punch.face_nodes["YMIN"]])),
            *id_lines(f"*NSET, NSET={BASE}", foundation.face_nodes["ZMIN"]),
            *id_lines("*NSET, NSET=PUNCHBOTTOMNODES", punch.face_nodes["ZMIN"]),
            *id_lines("*ELSET, ELSET=PUNCHTOP", top), *id_lines("*ELSET, ELSET=LOADPATCH", patch),
            "*SURFACE, NAME=FOUNDATIONTOP", *(f"{e}, S2" for e in foundation.face_elements["ZMAX"]),
            "*SURFACE, NAME=PUNCHBOTTOM", *(f"{e}, S1" for e in punch.face_elements["ZMIN"]),
            "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{number(spec.E, digits)}, {number(spec.nu, digits)}",
            "*SOLID SECTION, ELSET=FOUNDATION, MATERIAL=STEEL", "*SOLID SECTION, ELSET=PUNCH, MATERIAL=STEEL",
            f"*SURFACE INTERACTION, NAME={INTERACTION}", "** the law: LAW.yaml (roughcontact fe run --interface)",
            f"*CONTACT PAIR, INTERACTION={INTERACTION}, TYPE=NODE TO SURFACE", "PUNCHBOTTOM, FOUNDATIONTOP",
            "*BOUNDARY", f"{BASE}, 3, 3", f"{SYMMETRY_X}, XSYMM", f"{SYMMETRY_Y}, YSYMM",
            "** step 1: the seating pressure on the punch top (the law's reference state)",
            "*STEP", "*STATIC", "1., 1.", "*DLOAD", f"PUNCHTOP, P2, {number(spec.seating_pressure, digits)}",
            "*NODE PRINT, NSET=PUNCHBOTTOMNODES", "U", "*END STEP",
            f"** step 2: the patch load, {spec.quarter_load:g} N on the quarter (on top of the seating pressure)",
            "*STEP", "*STATIC", f"{number(1.0 / spec.increments, digits)}, 1.", "*DLOAD",
            f"LOADPATCH, P2, {number(spec.seating_pressure + pressure, digits)}", "*END STEP"]
    if spec.unload_increments:
        head += ["** step 3: unloading, back to the seating pressure", "*STEP", "*STATIC",
                 f"{number(1.0 / spec.unload_increments, digits)}, 1.", "*DLOAD",
                 f"LOADPATCH, P2, {number(spec.seating_pressure, digits)}", "*END STEP"]
    return "\n".join(head) + "\n"


def punch_mesh(spec: PunchSpec = PunchSpec()):
    """The engine's mesh of the punch's deck with the geometry's transition elements (Figs 14, 15)."""
    from ..fe.deck_mesh import deck_mesh

    return deck_mesh(read_deck("punch.inp", punch_deck(spec)), spec.geometry.family).mesh


def summary(mesh) -> dict:
    """Sizes of a punch mesh: nodes, dofs (3 per node), cells per block, interface elements and
    contact points (the interface nodes: the points of the nodal rule)."""
    s = mesh.summary()
    (name,) = s["interface_elements"]
    return {"nodes": s["nodes"], "dofs": s["dofs"], "cells": s["cells"], "interface_elements": s["interface_elements"][name],
            "contact_points": s["interface_nodes"][name]}


@dataclass(frozen=True)
class PunchRun(OnSurface):
    """One run of example 9.2: the friction ``case`` ("a" | "b" | "c": Fig. 18's parameters;
    "frictionless": no tangential restraint, for the bound), the spec, the surface (m00 [µm²]
    and the other moments), the normal law (``law``, ``psi``), E* [N/mm²] (None: from the two
    bodies' *ELASTIC, eq. (42)), the reading of (93) and, for a frictional run, the name of the
    frictionless run of its bound (the workflow's)."""

    case: str = "b"
    spec: PunchSpec = field(default_factory=PunchSpec)
    m00: float = PUNCH_M00
    law: str = "elastoplastic"
    psi: float | None = PUNCH_PSI
    E_star: float | None = None
    tangential_form: str = "incremental-end"
    surface: tuple = tuple(SURFACE.items())
    bound: str | None = None

    def __post_init__(self):
        choice("case", self.case, CASES)
        choice("law", self.law, ("elastic", "elastoplastic"))
        choice("tangential_form", self.tangential_form, friction.TANGENTIAL_FORMS)
        if (self.psi is not None) != (self.law == "elastoplastic"):
            raise ValueError("psi is needed with the elasto-plastic law and only used there")
        if self.E_star is not None:
            positive("E_star", self.E_star)
        self._freeze_surface()

    @property
    def family(self) -> str:
        """The element family (spec.geometry.family)."""
        return self.spec.geometry.family

    def law_file(self) -> LawFile:
        """The law of the run (the deck's interaction ROUGH): Fig. 18's case, n in 1/mm."""
        if self.case == "frictionless":
            rough = NoFriction()
        else:
            c = FIG18_CASES[self.case]
            rough = Orthotropic((c["mu_m"], c["mu_m"]), (c["mu_o"], c["mu_o"]), (N_PER_MM, N_PER_MM),
                                (c["kTx_over_kN"], c["kTy_over_kN"]), 0.0, (FIG18_NU, FIG18_NU))  # k = 0: ν_x = ν_y
        law = InteractionLaw(self.moments, "um", (1.0, 0.0, 0.0), self.law, self.spec.seating_pressure, rough,
                             E_star=self.E_star, psi=self.psi, pressure_range=PRESSURE_RANGE,
                             tangential_form=self.tangential_form)
        return LawFile("mm", {INTERACTION: law})

    def with_(self, **changes) -> "PunchRun":
        """A copy with run fields, spec fields under ``spec`` and geometry fields under ``geometry`` changed."""
        geometry = replace(self.spec.geometry, **changes.pop("geometry", {}))
        spec = replace(self.spec, geometry=geometry, **changes.pop("spec", {}))
        return replace(self, spec=spec, **changes)


def mu_max(case: str) -> float:
    """The largest friction coefficient a Fig. 18 case reaches: (89) runs from μ_m μ_o (no slip)
    to μ_m (κ → ∞), so the largest is μ_m·max(1, μ_o)."""
    choice("case", case, tuple(FIG18_CASES))
    c = FIG18_CASES[case]
    return c["mu_m"] * max(1.0, c["mu_o"])


@dataclass(frozen=True, eq=False)
class PunchResult:
    """Example 9.2 results: the deck run (every load level), sizes and time."""

    run: PunchRun
    deck: DeckResult
    seconds: float

    @property
    def spec(self) -> PunchSpec:
        return self.run.spec

    @property
    def n_dofs(self) -> int:
        return self.deck.n_dofs

    @property
    def n_points(self) -> int:
        return self.deck.problem.points.n_points

    @property
    def points(self):
        return self.deck.problem.points

    @property
    def mesh(self):
        return self.deck.problem.mesh

    @property
    def max_increment(self):
        return self.deck.increments[self.spec.max_index]

    @property
    def material(self):
        """The interface material (one interaction)."""
        return self.deck.problem.materials.parts[0][0]

    def fields(self, k: int | None = None) -> dict[str, np.ndarray]:
        """Per contact point of the quarter at level k (default: the maximum load): x_mm, y_mm,
        plastic slips slip_x_um, slip_y_um [µm], tractions t_x, t_y, p_N [N/mm²], status (0 stick,
        1 slip, 2 open) and, with a friction limit, the share of it used (utilisation) — Figs 18/19."""
        inc = self.deck.increments[self.spec.max_index if k is None else k]
        f = self.deck.interface_fields(inc)
        out = {"x_mm": f["x"], "y_mm": f["y"], "slip_x_um": f["slip_1_um"], "slip_y_um": f["slip_2_um"],
               "t_x": f["t_1"], "t_y": f["t_2"], "p_N": f["p_N"], "status": f["status"].astype(int)}
        if isinstance(self.material.model, friction.OrthotropicHardening):
            out["utilisation"] = friction.utilisation(self.material.model, inc.state)
        return out

    def write_vtu(self, path, points_path=None):
        """Both bodies with their displacements at the maximum load to ``path`` and the contact
        points with :meth:`fields` to ``points_path`` (default: path's stem + "_interface.vtu")."""
        from ..fe.vtu import write_solution

        f = {k: np.asarray(v) for k, v in self.fields().items() if k not in ("x_mm", "y_mm")}
        return write_solution(path, self.mesh, self.max_increment.u, {"x": self.points.x, **f}, points_path)


def _history(result: PunchResult) -> dict[str, np.ndarray]:
    """(level, point) arrays of the whole load history; relative displacements from the seated state."""
    pts, incs = result.points, result.deck.increments
    seated = pts.jumps(incs[0].u)
    jumps = np.stack([pts.jumps(inc.u) - seated for inc in incs])
    per_level = [result.fields(k) for k in range(len(incs))]
    keys = ("t_x", "t_y", "p_N", "slip_x_um", "slip_y_um") + (("utilisation",) if "utilisation" in per_level[0] else ())
    out = {k: np.stack([f[k] for f in per_level]) for k in keys}
    out.update(jump_x_um=jumps[..., 0] * 1000.0, jump_y_um=jumps[..., 1] * 1000.0,
               status=np.stack([inc.status for inc in incs]).astype(np.int32))
    return out


def to_dataset(result: PunchResult):
    """An ``xarray.Dataset`` of the whole history: per load level (the patch load on the quarter)
    and contact point (x, y, weight) the tractions, plastic slips, relative tangential
    displacements from the seated state and status; D under every reading and the sizes as
    attributes."""
    import xarray as xr

    h = _history(result)
    pts = result.points
    units = {"t_x": "N/mm^2", "t_y": "N/mm^2", "p_N": "N/mm^2", "slip_x_um": "um", "slip_y_um": "um",
             "jump_x_um": "um", "jump_y_um": "um", "status": "1", "utilisation": "1"}
    long = {"t_x": "tangential traction along x", "t_y": "tangential traction along y", "p_N": "interface pressure",
            "slip_x_um": "plastic slip u_x^p", "slip_y_um": "plastic slip u_y^p",
            "jump_x_um": "relative displacement from the seated state, x",
            "jump_y_um": "relative displacement from the seated state, y", "status": "0 stick, 1 slip, 2 open",
            "utilisation": "share of the friction limit used, (f + p_N)/p_N of (91): 1 slip, < 1 stick"}
    data = {k: (("level", "point"), v, {"units": units[k], "long_name": long[k]}) for k, v in h.items()}
    data["load_quarter"] = ("level", result.spec.levels, {"units": "N", "long_name": "patch load on the quarter model"})
    data["newton_iterations"] = ("level", np.asarray([i.iterations for i in result.deck.increments]),
                                 {"units": "1", "long_name": "Newton iterations"})
    data["point_weight"] = ("point", pts.weights, {"units": "mm^2", "long_name": "area of the contact point"})
    seating = pts.jumps(result.deck.increments[0].u) * 1000.0
    for j, a in enumerate("xy"):
        data[f"seating_jump_{a}_um"] = ("point", seating[:, j], {
            "units": "um", "long_name": f"relative displacement {a} of the seating (from the unloaded start)"})
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
                    max_index=result.spec.max_index, E_star=summ["E_star"], spec=summ["spec"])
    return ds


def run_punch(run: PunchRun, *, options: NewtonOptions | None = None, progress=None) -> PunchResult:
    """Solve example 9.2 through all load levels (seated, loading, unloading): the run's deck and
    law through the deck reader and the solver. ``progress(k, n, increment)`` per level."""
    t0 = time.perf_counter()
    spec = run.spec
    deck = read_deck("punch.inp", punch_deck(spec))
    offsets = {1: 0, 2: 1, 3: 1 + spec.increments}
    report = None if progress is None else (lambda s, n_s, k, n, inc: progress(offsets[s] + k, len(spec.levels), inc))
    res = run_deck_file(deck, run.law_file(), spec.geometry.family, options, report)
    return PunchResult(run, res, time.perf_counter() - t0)


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
    inc = result.deck.increments[result.spec.max_index if at == "max" else -1]
    per_mm = 1.0 / result.material.length_per_mm  # law length unit → mm
    s = inc.state
    if weight == "work":
        per_point = s[:, friction.DISSIPATION] * per_mm
    else:
        per_point = (s[:, friction.T_X] * s[:, friction.UP_X] + s[:, friction.T_Y] * s[:, friction.UP_Y]) * per_mm
    w = result.points.weights if weight in ("area", "work") else 1.0
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
    """:func:`bound` of a frictional run from the frictionless run of the same mesh and loads,
    the relative displacements from the unloaded start (where the plastic slips start)."""
    jump = frictionless.points.jumps(frictionless.max_increment.u)
    p = frictional.max_increment.state[:, friction.T_N]
    return bound(frictionless.points.weights, p, np.hypot(jump[:, 0], jump[:, 1]), mu_max, whole=whole)


def summary_of(result: PunchResult) -> dict:
    """Sizes, iterations, times, E* and the spec, JSON-ready."""
    incs = result.deck.increments
    k = result.spec.max_index
    applied = result.spec.seating_pressure * result.spec.geometry.punch_half_width ** 2 + result.spec.levels[k]
    resultant = float(np.sum(incs[k].state[:, friction.T_N] * result.points.weights))
    spec = asdict(result.spec)
    return {"dofs": result.n_dofs, "interface_points": result.n_points, "seconds": result.seconds,
            "newton_iterations": [int(i.iterations) for i in incs], "cutbacks": int(sum(i.cutbacks for i in incs)),
            "equilibrium_error_max_load": abs(resultant - applied) / applied,
            "E_star": float(next(iter(result.deck.problem.E_star.values()))), "spec": spec}
