"""Example 9.1 of Buczkowski & Kleiber (2009): a prismatic beam on a rigid base (Fig. 10,
Table 4, Fig. 13).

The beam, 500 × 10 × 120 mm (x along it, y across its 10 mm thickness, z up), lies on its
500 × 10 face on a rigid base through the statistical interface and carries a load at
mid-length: first the initial (seating) load, then the load in ``increments`` equal steps.

Model (what the paper leaves open is a stated, switchable choice):
* a quarter of the beam, x ∈ [0, 250], y ∈ [0, 5]: the paper's half model (x ≥ 0, symmetry
  u_x = 0 on x = 0) halved once more by the symmetry of the beam, its load and the
  (orthotropic, axis-aligned) interface law about the mid-plane y = 5 of the thickness
  (u_y = 0 there). That plane is the "contact centre line" of the output;
* the base is rigid: side A of every interface element is fixed (not the paper's foundation
  10⁵ × stiffer, which is rigid to 1e-5 relative);
* hex20 elements, with a layer of transition elements (HEX21 or HEX28) on the contact face and
  the 18- or 32-node interface elements below it (``elements`` "quadratic" | "cubic"),
  integrated at their nodes (Lobatto, :mod:`.interface_points`); the z-element sizes grow
  geometrically from the contact face (``z_ratio``);
* the load is a line load across the width at x = 0 on the top face (consistent nodal forces
  of the quadratic top edges), or with ``load_patch`` > 0 a uniform pressure on a centred
  patch of that length (full beam) across the width;
* loads: the total on the full beam (``load`` 1962 N, ``initial_load`` 4.9 N); levels
  initial_load, then ``increments`` equal steps up to ``load``;
* u_N is the change of the interface gap from the seated state (after the initial load),
  negative = approach (the paper's sign in Table 4), in µm.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from typing import Any, Mapping

import numpy as np

from ..interface import friction
from ..validation import choice, positive
from . import assembly
from .contact import InterfaceMaterial
from .mesh import Mesh, box, dofs, graded, rigid_base_interface
from .solver import ContactModel, NewtonOptions, Solution, solve

__all__ = ["BeamSpec", "BeamResult", "beam_mesh", "beam_model", "run_beam", "interface_fields", "beam_case"]

ELEMENT_FAMILIES = ("quadratic", "cubic")


@dataclass(frozen=True)
class BeamSpec:
    """Geometry [mm], bulk material [N/mm²], loads [N, full beam] and discretisation."""

    length: float = 500.0
    width: float = 10.0
    height: float = 120.0
    E: float = 1.057e5
    nu: float = 0.25
    load: float = 1962.0
    initial_load: float = 4.9
    increments: int = 16
    elements: str = "cubic"
    n_x: int = 25
    n_z: int = 6
    z_ratio: float = 4.0
    x_ratio: float = 1.0
    load_patch: float = 0.0
    rule: str = "lobatto"

    def __post_init__(self):
        for name in ("length", "width", "height", "E", "load", "initial_load", "z_ratio", "x_ratio"):
            positive(name, getattr(self, name))
        positive("load_patch", self.load_patch, allow_zero=True)
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"nu must lie in (-1, 0.5), got {self.nu!r}")
        if self.initial_load >= self.load:
            raise ValueError("initial_load must be smaller than load")
        choice("elements", self.elements, ELEMENT_FAMILIES)
        choice("rule", self.rule, ("lobatto", "gauss"))
        for name in ("increments", "n_x", "n_z"):
            if int(getattr(self, name)) != getattr(self, name) or getattr(self, name) < 1:
                raise ValueError(f"{name} must be a positive integer, got {getattr(self, name)!r}")
        if self.load_patch >= self.length:
            raise ValueError("load_patch must be shorter than the beam")

    @property
    def contact_area(self) -> float:
        """Nominal contact area of the full beam [mm²]."""
        return self.length * self.width

    @property
    def seating_pressure(self) -> float:
        """Mean interface pressure under the initial load [N/mm²] (the law's reference state)."""
        return self.initial_load / self.contact_area

    @property
    def levels(self) -> np.ndarray:
        """Load levels [N, full beam]: the initial load, then ``increments`` equal steps."""
        return np.concatenate([[self.initial_load],
                               np.linspace(self.initial_load, self.load, self.increments + 1)[1:]])


def beam_mesh(spec: BeamSpec) -> Mesh:
    """The quarter beam (x ∈ [0, L/2], y ∈ [0, b/2], z ∈ [0, h]) with its transition layer and
    the rigid-base interface (node set "base")."""
    half = spec.length / 2.0
    if spec.load_patch > 0.0:  # an element edge at the end of the loaded patch
        a = spec.load_patch / 2.0
        x = np.concatenate([[0.0], graded(a, half, spec.n_x - 1, spec.x_ratio)]) if spec.n_x > 1 else [0.0, half]
    else:
        x = graded(0.0, half, spec.n_x, spec.x_ratio)
    y = [0.0, spec.width / 2.0]
    z = graded(0.0, spec.height, spec.n_z, spec.z_ratio)
    return rigid_base_interface(box(x, y, z, contact_face="bottom", family=spec.elements, name="beam"))


def _load_pattern(spec: BeamSpec, mesh: Mesh) -> np.ndarray:
    """Nodal forces on the quarter model of a unit load on the full beam, pressing −z: they sum
    to −1/4 (checked in :func:`beam_model`)."""
    F = np.zeros(3 * mesh.n_nodes)
    top = mesh.face_sets["zmax"]
    if spec.load_patch > 0.0:
        x_mid = mesh.points[top.face_nodes].mean(axis=1)[:, 0]
        faces = top.face_nodes[x_mid < spec.load_patch / 2.0]
        pressure = 1.0 / (spec.load_patch * spec.width)
        return assembly.surface_traction(mesh.points, top.face_element, faces, (0.0, 0.0, -pressure))
    # line load at x = 0: the quadratic top edges of the faces touching x = 0, weights 1/6, 2/3, 1/6;
    # half of the line lies on the symmetry plane's side x ≥ 0 of the model
    per_length = 0.5 / spec.width  # N per mm across the width, for a unit total load
    on_line = np.flatnonzero(np.isclose(mesh.points[:, 0], 0.0) & np.isclose(mesh.points[:, 2], spec.height))
    ys = mesh.points[on_line, 1]
    order = on_line[np.argsort(ys)]
    ys = np.sort(ys)
    for k in range(0, len(order) - 1, 2):  # consecutive (corner, mid, corner) triples
        ell = ys[k + 2] - ys[k]
        F[3 * order[k:k + 3] + 2] -= per_length * ell * np.array([1.0, 4.0, 1.0]) / 6.0
    return F


def beam_model(spec: BeamSpec, material: InterfaceMaterial, mesh: Mesh | None = None) -> ContactModel:
    """The discrete quarter beam: bulk stiffness, interface points, supports (rigid base, the
    two symmetry planes), load pattern of a unit load on the full beam."""
    mesh = beam_mesh(spec) if mesh is None else mesh
    fixed = np.concatenate([
        dofs(mesh.node_sets["base"], (0, 1, 2)),
        dofs(mesh.node_sets["beam.xmin"] if "beam.xmin" in mesh.node_sets else mesh.node_sets["xmin"], (0,)),
        dofs(mesh.node_sets["beam.ymin"] if "beam.ymin" in mesh.node_sets else mesh.node_sets["ymin"], (1,)),
    ])
    load = _load_pattern(spec, mesh)
    total = load.reshape(-1, 3).sum(axis=0)
    if not np.allclose(total, (0.0, 0.0, -0.25), rtol=1e-12, atol=1e-15):  # the quarter carries 1/4
        raise AssertionError(f"load pattern sums to {total}, not a quarter of the unit load")
    return ContactModel.assemble(mesh, assembly.isotropic_elasticity(spec.E, spec.nu), material, fixed, load,
                                 rule=spec.rule)


@dataclass(frozen=True, eq=False)
class BeamResult:
    """Example 9.1 results. x_mm: stations along the contact centre line y = b/2 (full beam);
    u_N_um: interface deflection there at the final load, from the seated state, negative =
    approach [µm]; p_N: interface pressure there [N/mm²]; open_points: interface points open at
    the final load (x_mm of each); per increment: load [N], Newton iterations, cut-backs;
    equilibrium_error: |Σ w p_N − applied| / applied at the final load; sizes and timings."""

    spec: BeamSpec
    x_mm: np.ndarray
    u_N_um: np.ndarray
    p_N: np.ndarray
    open_x_mm: np.ndarray
    loads: np.ndarray
    newton_iterations: np.ndarray
    cutbacks: np.ndarray
    equilibrium_error: float
    n_dofs: int
    n_points: int
    seconds: float
    solution: Solution = field(repr=False)
    mesh: Mesh = field(repr=False)

    @property
    def u_N_centre_um(self) -> float:
        return float(self.u_N_um[0])

    @property
    def u_N_end_um(self) -> float:
        return float(self.u_N_um[-1])

    def to_dataset(self):
        """An ``xarray.Dataset``: u_N_um, p_N along the centre line (coordinate x), per interface
        point the final fields (dimension point), per load level the load, Newton iterations and
        cut-backs (dimension level); sizes, timings, equilibrium error and the spec as attributes."""
        import xarray as xr

        f = interface_fields(self)
        pts = self.solution.model.points
        ds = xr.Dataset(
            {
                "u_N_um": ("x", self.u_N_um, {"units": "um", "long_name": "interface deflection from the seated state, negative = approach"}),
                "p_N": ("x", self.p_N, {"units": "N/mm^2", "long_name": "interface pressure at the final load"}),
                "point_x": ("point", pts.x[:, 0], {"units": "mm", "long_name": "x of the interface point, along the beam from mid-length"}),
                "point_y": ("point", pts.x[:, 1], {"units": "mm", "long_name": "y of the interface point, across the beam"}),
                "point_u_N_um": ("point", f["u_N_um"], {"units": "um", "long_name": "deflection from the seated state"}),
                "point_p_N": ("point", f["p_N"], {"units": "N/mm^2", "long_name": "contact pressure p_N at the final load"}),
                "point_t_x": ("point", f["traction"][:, 0], {"units": "N/mm^2", "long_name": "tangential traction t_x at the final load"}),
                "point_t_y": ("point", f["traction"][:, 1], {"units": "N/mm^2", "long_name": "tangential traction t_y at the final load"}),
                "point_status": ("point", f["status"], {"units": "1", "long_name": "0 stick, 1 slip, 2 open"}),
                "point_weight": ("point", pts.weights, {"units": "mm^2", "long_name": "area of the point"}),
                "load": ("level", self.loads, {"units": "N", "long_name": "load on the full beam"}),
                "newton_iterations": ("level", self.newton_iterations, {"units": "1", "long_name": "Newton iterations of the load level"}),
                "cutbacks": ("level", self.cutbacks, {"units": "1", "long_name": "cut-backs of the load level"}),
            },
            coords={"x": ("x", self.x_mm, {"units": "mm", "long_name": "position along the beam from mid-length"})},
        )
        ds.attrs.update(u_N_centre_um=self.u_N_centre_um, u_N_end_um=self.u_N_end_um,
                        open_points=int(self.open_x_mm.size), equilibrium_error=self.equilibrium_error,
                        dofs=self.n_dofs, interface_points=self.n_points, seconds=self.seconds,
                        seating_pressure=self.spec.seating_pressure, **{f"spec_{k}": v for k, v in asdict(self.spec).items()})
        return ds

    def summary(self) -> dict:
        """The numbers a user or a script wants, JSON-ready (the CLI prints it)."""
        return {
            "u_N_centre_um": self.u_N_centre_um,
            "u_N_end_um": self.u_N_end_um,
            "x_mm": self.x_mm.tolist(),
            "u_N_um": self.u_N_um.tolist(),
            "p_N": self.p_N.tolist(),
            "open_points": int(self.open_x_mm.size),
            "open_x_mm": self.open_x_mm.tolist(),
            "newton_iterations": self.newton_iterations.tolist(),
            "cutbacks": int(self.cutbacks.sum()),
            "equilibrium_error": self.equilibrium_error,
            "dofs": self.n_dofs,
            "interface_points": self.n_points,
            "seconds": self.seconds,
            "spec": asdict(self.spec),
            "units": {"x_mm": "mm", "u_N_um": "um (negative = approach, from the seated state)",
                      "p_N": "N/mm^2", "loads": "N (full beam)", "seconds": "s"},
        }


def run_beam(spec: BeamSpec, material: InterfaceMaterial, *, options: NewtonOptions | None = None,
             progress=None) -> BeamResult:
    """Solve example 9.1 with the interface ``material`` (e.g. :func:`.contact.statistical_interface`
    seated at ``spec.seating_pressure``) and return the :class:`BeamResult`."""
    t0 = time.perf_counter()
    mesh = beam_mesh(spec)
    model = beam_model(spec, material, mesh)
    sol = solve(model, spec.levels, options, progress)
    pts = model.points
    line = np.flatnonzero(np.isclose(pts.x[:, 1], 0.0))
    line = line[np.argsort(pts.x[line, 0])]
    closure = material.closure_mm(np.stack([sol.increments[0].state[line], sol.final.state[line]]))
    u_N_um = -(closure[1] - closure[0]) * 1000.0
    open_ = np.flatnonzero(sol.final.status == friction.OPEN)
    return BeamResult(
        spec=spec,
        x_mm=pts.x[line, 0],
        u_N_um=u_N_um,
        p_N=-sol.final.tractions[line, 2],
        open_x_mm=np.unique(np.round(pts.x[open_, 0], 9)),
        loads=np.array([inc.level for inc in sol.increments]),
        newton_iterations=np.array([inc.iterations for inc in sol.increments]),
        cutbacks=np.array([inc.cutbacks for inc in sol.increments]),
        equilibrium_error=sol.equilibrium_error(),
        n_dofs=model.n_dofs,
        n_points=pts.n_points,
        seconds=time.perf_counter() - t0,
        solution=sol,
        mesh=mesh,
    )


def interface_fields(result: BeamResult) -> dict[str, np.ndarray]:
    """Per interface point at the final load: the solver's fields with the closure from the
    seated state [mm] and u_N [µm] (negative = approach) for files."""
    fields = result.solution.point_fields(-1, reference=0)
    fields["u_N_um"] = -fields["closure_mm"] * 1000.0
    fields["x"] = result.solution.model.points.x
    return fields


def beam_case(run: Mapping[str, Any], progress=None) -> BeamResult:
    """Solve one run of example 9.1 described by a plain dict (the workflow's configuration):
    ``family`` (cubic | quadratic), ``case`` (a Table 4 row, not used here), ``m00`` [µm²],
    ``law`` (elastic | elastoplastic), ``psi``, ``E_star`` [N/mm²], ``tangential`` (free | stick
    | coulomb), ``mu``, ``surface`` (m20, m02, m40, m04), ``spec`` (BeamSpec fields); optionally
    ``Y`` [N/mm²]: an elasto-plastic law with a given yield strength (closure "material", ψ an
    output) instead of ψ (closure "yield-from-psi")."""
    from ..contact import resolve_material
    from ..statistics import SpectralMoments
    from .contact import statistical_interface

    surface = SpectralMoments(m00=run["m00"], **run["surface"])
    spec = BeamSpec(elements=run["family"], **run["spec"])
    if run["law"] == "elastic":
        law = {"E_star": run["E_star"]}
    else:
        by = {"Y": run["Y"]} if run.get("Y") is not None else {"psi": run["psi"]}
        law = {"material": resolve_material(surface, E_star=run["E_star"], **by)}
    material = statistical_interface(surface, spec.seating_pressure, tangential=run["tangential"],
                                     mu=run.get("mu"), **law)
    return run_beam(spec, material, progress=progress)
