"""Example 9.1 of Buczkowski & Kleiber (2009) as an input deck: a prismatic beam on a rigid base
(Fig. 10, Table 4, Fig. 13), run through the engine's deck reader (:mod:`roughcontact.fe.deck`).

The beam, 500 × 10 × 120 mm (x along it, y across its 10 mm thickness, z up), lies on its
500 × 10 face on a rigid base through the statistical interface and carries a load at
mid-length: first the initial (seating) load, then the load in ``increments`` equal steps.

The deck (:func:`beam_deck`; ``src/roughcontact/examples/decks/beam.inp`` with the defaults)
states what the paper leaves open:

* a quarter of the beam, x ∈ [0, 250], y ∈ [0, 5]: the paper's half model (x ≥ 0, symmetry
  u_x = 0 on x = 0) halved once more by the symmetry of the beam, its load and the
  (orthotropic, axis-aligned) interface law about the mid-plane y = 5 of the thickness
  (u_y = 0 there). That plane is the "contact centre line" of the output;
* the base is rigid: a layer of C3D20 elements under the beam (the master surface) whose
  nodes are all held (the paper's foundation 10⁵ × stiffer is rigid to 1e-5 relative);
* C3D20 elements, the contact layer becoming transition elements (HEX21 or HEX28, the reader's
  ``family``) with 18- or 32-node interface elements, integrated at their nodes; the
  z-element sizes grow geometrically from the contact face (``z_ratio``);
* the load: a line load across the width at x = 0 on the top face (``*CLOAD`` on the three top
  nodes there, 1/6, 4/6, 1/6 of the quarter's share), or with ``load_patch`` > 0 a uniform
  pressure (``*DLOAD``) on a centred patch of that length (full beam) across the width;
* step 1 the initial load (one increment), step 2 the load (``increments``); the law's
  reference state is the mean seating pressure initial_load / (length × width);
* u_N is the change of the interface gap from the seated state (the end of step 1), negative =
  approach (the paper's sign in Table 4), in µm.

The law (:meth:`BeamRun.law_file`): the surface of the Table 4 case in µm, E* = E1/(1 − ν1²)
(text), elastic or elasto-plastic (ψ or the printed Y), tangential restraint free, stick or a
Coulomb limit with k_T from Mindlin's ratio (96) of the surface's representative summit ellipse.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field, replace

import numpy as np

from ..fe.deck import read_deck
from ..fe.deck_run import DeckResult, run_deck_file
from ..fe.deck_writer import box_part, element_lines, id_lines, node_lines, number
from ..fe.laws import Coulomb, InteractionLaw, LawFile, NoFriction, Stick
from ..fe.mesh import graded
from ..fe.solver import NewtonOptions
from ..interface import friction
from ..validation import choice, positive
from .section9 import BEAM, BEAM_E_STAR, SURFACE, OnSurface
from ..limits import describe

__all__ = ["BeamSpec", "BeamRun", "BeamResult", "beam_deck", "beam_mesh", "run_beam", "ELEMENT_FAMILIES", "TANGENTIAL",
           "PRESSURE_RANGE", "INTERACTION"]

ELEMENT_FAMILIES = ("quadratic", "cubic")
#: tangential restraints of the interface (section 9.1 leaves it open)
TANGENTIAL = ("free", "stick", "coulomb")
#: the tabulated range of the normal law [N/mm²]: below the seating pressure, far above the
#: largest interface pressure of the beam (~1.5 N/mm²)
PRESSURE_RANGE = (1e-12, 100.0)
INTERACTION = "ROUGH"
_NU_MINDLIN = 0.25  # Poisson's ratio of Mindlin's k_T/k_N (96): the beam's ν1


@dataclass(frozen=True)
class BeamSpec:
    """Geometry [mm], bulk material [N/mm²], loads [N, full beam] and discretisation."""

    length: float = BEAM["length"]
    width: float = BEAM["width"]
    height: float = BEAM["height"]
    E: float = BEAM["E"]
    nu: float = BEAM["nu"]
    load: float = BEAM["load"]
    initial_load: float = BEAM["initial_load"]
    increments: int = BEAM["increments"]
    elements: str = "cubic"
    n_x: int = 25
    n_z: int = 6
    z_ratio: float = 4.0
    x_ratio: float = 1.0
    load_patch: float = 0.0

    def __post_init__(self):
        for name in ("length", "width", "height", "E", "load", "initial_load", "z_ratio", "x_ratio"):
            positive(name, getattr(self, name))
        positive("load_patch", self.load_patch, allow_zero=True)
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"nu must lie in (-1, 0.5), got {describe(self.nu)}")
        if self.initial_load >= self.load:
            raise ValueError("initial_load must be smaller than load")
        choice("elements", self.elements, ELEMENT_FAMILIES)
        for name in ("increments", "n_x", "n_z"):
            v = getattr(self, name)
            if isinstance(v, bool) or int(v) != v or v < 1:
                raise ValueError(f"{name} must be a positive integer, got {describe(v)}")
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

    def x_edges(self) -> np.ndarray:
        """Element boundaries along the quarter beam [mm] (an edge at the end of a load patch)."""
        half = self.length / 2.0
        if self.load_patch > 0.0:
            a = self.load_patch / 2.0
            return (np.concatenate([[0.0], graded(a, half, self.n_x - 1, self.x_ratio if self.n_x > 2 else 1.0)])
                    if self.n_x > 1 else np.array([0.0, half]))
        return graded(0.0, half, self.n_x, self.x_ratio if self.n_x > 1 else 1.0)

    def z_edges(self) -> np.ndarray:
        """Element boundaries over the height [mm], growing by ``z_ratio`` from the contact face
        (one element: no grading)."""
        return graded(0.0, self.height, self.n_z, self.z_ratio if self.n_z > 1 else 1.0)


def beam_deck(spec: BeamSpec = BeamSpec(), digits: int | None = None) -> str:
    """The deck of the quarter beam on its rigid base (module docstring), numbers in full
    precision (``digits`` None) or ``digits`` significant digits."""
    x, y, z = spec.x_edges(), np.array([0.0, spec.width / 2.0]), spec.z_edges()
    beam = box_part(x, y, z)
    base = box_part(x, y, [-z[1], 0.0], first_node=int(beam.node_ids[-1]) + 1,
                    first_element=int(beam.element_ids[-1]) + 1)
    top = beam.face_nodes["ZMAX"]
    line = top[np.isclose(beam.coords[top - 1, 0], 0.0)]
    line = line[np.argsort(beam.coords[line - 1, 1])]  # y = 0, b/4, b/2
    lines = ["*HEADING", "Example 9.1 (Buczkowski & Kleiber 2009): quarter of a beam on a rigid base, mm N",
             "** generated by roughcontact.examples.beam.beam_deck", *node_lines(beam, "BEAMNODES", digits),
             *node_lines(base, "BASENODES", digits), *element_lines(beam, "BEAM"), *element_lines(base, "BASE"),
             *id_lines("*NSET, NSET=XSYMMETRY", beam.face_nodes["XMIN"]),
             *id_lines("*NSET, NSET=YSYMMETRY", beam.face_nodes["YMIN"]),
             *id_lines("*NSET, NSET=BOTTOM", beam.face_nodes["ZMIN"]),
             *id_lines("*NSET, NSET=LOADLINE", line),
             "*SURFACE, NAME=BEAMBOTTOM", *(f"{e}, S1" for e in beam.face_elements["ZMIN"]),
             "*SURFACE, NAME=BASETOP", *(f"{e}, S2" for e in base.face_elements["ZMAX"]),
             "*MATERIAL, NAME=BEAMMAT", "*ELASTIC", f"{number(spec.E, digits)}, {number(spec.nu, digits)}",
             "** the base: 1e5 times stiffer (section 9.1), and held at every node: rigid",
             "*MATERIAL, NAME=BASEMAT", "*ELASTIC", f"{number(1e5 * spec.E, digits)}, {number(spec.nu, digits)}",
             "*SOLID SECTION, ELSET=BEAM, MATERIAL=BEAMMAT", "*SOLID SECTION, ELSET=BASE, MATERIAL=BASEMAT",
             f"*SURFACE INTERACTION, NAME={INTERACTION}", "** the law: LAW.yaml (roughcontact fe run --interface)",
             f"*CONTACT PAIR, INTERACTION={INTERACTION}, TYPE=NODE TO SURFACE", "BEAMBOTTOM, BASETOP",
             "*BOUNDARY", "BASENODES, 1, 3", "XSYMMETRY, XSYMM", "YSYMMETRY, YSYMM"]
    for k, (total, n) in enumerate(((spec.initial_load, 1), (spec.load, spec.increments))):
        lines += [f"** step {k + 1}: {'the initial (seating) load' if k == 0 else 'the load'}, {total:g} N on the "
                  "full beam", "*STEP", "*STATIC", f"{number(1.0 / n, digits)}, 1."]
        if spec.load_patch > 0.0:  # a uniform pressure on the patch's top faces, across the width
            centre = beam.coords[beam.connectivity[:, :8] - 1].mean(axis=1)
            patch = beam.element_ids[np.isin(beam.element_ids, beam.face_elements["ZMAX"])
                                     & (centre[:, 0] < spec.load_patch / 2.0)]
            lines += ["*DLOAD", *(f"{e}, P2, {number(total / (spec.load_patch * spec.width), digits)}" for e in patch)]
        else:  # line load at x = 0: 1/6, 4/6, 1/6 of the quarter's share on its three top nodes
            quarter = 0.25 * total
            lines += ["*CLOAD", *(f"{n_id}, 3, {number(-quarter * w / 6.0, digits)}"
                                  for n_id, w in zip(line.tolist(), (1.0, 4.0, 1.0)))]
        lines += ["*NODE PRINT, NSET=BOTTOM", "U", "*END STEP"]
    return "\n".join(lines) + "\n"


def beam_mesh(spec: BeamSpec = BeamSpec()):
    """The engine's mesh of the beam's deck with ``spec.elements`` transition elements (Fig. 10)."""
    from ..fe.deck_mesh import deck_mesh

    return deck_mesh(read_deck("beam.inp", beam_deck(spec)), spec.elements).mesh


@dataclass(frozen=True)
class BeamRun(OnSurface):
    """One run of example 9.1: the spec (geometry, loads, mesh, element family), the Table 4
    case, the surface (m00 [µm²] and the other moments), the normal law (``law``; ``psi`` or
    ``Y`` [N/mm²] for the elasto-plastic one: closures yield-from-psi or material), E*
    [N/mm²], the tangential restraint (``free`` | ``stick`` | ``coulomb`` with ``mu``)."""

    spec: BeamSpec = field(default_factory=BeamSpec)
    m00: float = 0.625
    law: str = "elastic"
    psi: float | None = None
    Y: float | None = None
    E_star: float = BEAM_E_STAR
    tangential: str = "free"
    mu: float | None = None
    surface: tuple = tuple(SURFACE.items())
    case: str = ""

    def __post_init__(self):
        choice("tangential", self.tangential, TANGENTIAL)
        choice("law", self.law, ("elastic", "elastoplastic"))
        if (self.mu is not None) != (self.tangential == "coulomb"):
            raise ValueError(f"mu is needed with tangential='coulomb' and only used there (got mu={describe(self.mu)})")
        if self.law == "elastic" and (self.psi is not None or self.Y is not None):
            raise ValueError("psi and Y belong to the elasto-plastic law")
        if self.law == "elastoplastic" and (self.psi is None) == (self.Y is None):
            raise ValueError("the elasto-plastic law needs exactly one of psi and Y")
        positive("E_star", self.E_star)
        self._freeze_surface()

    @property
    def family(self) -> str:
        """The element family (spec.elements)."""
        return self.spec.elements

    def law_file(self) -> LawFile:
        """The interface law of the run as a law file (the deck's interaction ROUGH)."""
        from ..interface import mindlin_kT_over_kN
        from ..interface.tangential import representative_aspect

        moments = self.moments
        kT = tuple(float(a) for a in mindlin_kT_over_kN(representative_aspect(moments), _NU_MINDLIN))
        restraint = (NoFriction() if self.tangential == "free" else Stick(kT) if self.tangential == "stick"
                     else Coulomb(self.mu, kT))
        law = InteractionLaw(moments, "um", (1.0, 0.0, 0.0), self.law, self.spec.seating_pressure, restraint,
                             E_star=self.E_star, psi=self.psi, yield_strength=self.Y, pressure_range=PRESSURE_RANGE)
        return LawFile("mm", {INTERACTION: law})

    def with_(self, **changes) -> "BeamRun":
        """A copy with run fields or, under ``spec``, spec fields changed."""
        spec = replace(self.spec, **changes.pop("spec", {}))
        return replace(self, spec=spec, **changes)


@dataclass(frozen=True, eq=False)
class BeamResult:
    """Example 9.1 results. x_mm: stations along the contact centre line y = b/2 (full beam);
    u_N_um: interface deflection there at the final load, from the seated state, negative =
    approach [µm]; p_N: interface pressure there [N/mm²]; open_x_mm: x of the interface points
    open at the final load; per increment: load [N], Newton iterations, cut-backs;
    equilibrium_error: |Σ w p_N − applied| / applied at the final load; sizes and timings; the
    deck run itself."""

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
    deck: DeckResult = field(repr=False)

    @property
    def u_N_centre_um(self) -> float:
        return float(self.u_N_um[0])

    @property
    def u_N_end_um(self) -> float:
        return float(self.u_N_um[-1])

    @property
    def mesh(self):
        return self.deck.problem.mesh

    def point_fields(self) -> dict[str, np.ndarray]:
        """Per interface point at the final load: x (n, 3) [mm], u_N_um (from the seated state,
        negative = approach), p_N, t_x, t_y [N/mm²], status (0 stick, 1 slip, 2 open)."""
        seated, final = (self.deck.interface_fields(self.deck.step_end(k)) for k in (1, 2))
        return {"x": self.deck.problem.points.x, "u_N_um": -(final["u_N_um"] - seated["u_N_um"]),
                "p_N": final["p_N"], "t_x": final["t_1"], "t_y": final["t_2"], "status": final["status"]}

    def write_vtu(self, path):
        """The beam and its base with the displacements of the final load to ``path`` and the
        interface points with :meth:`point_fields` to path's stem + "_interface.vtu"."""
        from ..fe.vtu import write_solution

        return write_solution(path, self.mesh, self.deck.increments[-1].u, self.point_fields())

    def to_dataset(self):
        """An ``xarray.Dataset``: u_N_um, p_N along the centre line (coordinate x), per interface
        point the final fields (dimension point), per load level the load, Newton iterations and
        cut-backs (dimension level); sizes, timings, equilibrium error and the spec as attributes."""
        import xarray as xr

        f = self.point_fields()
        w = self.deck.problem.points.weights
        ds = xr.Dataset(
            {
                "u_N_um": ("x", self.u_N_um, {"units": "um", "long_name": "interface deflection from the seated state, negative = approach"}),
                "p_N": ("x", self.p_N, {"units": "N/mm^2", "long_name": "interface pressure at the final load"}),
                "point_x": ("point", f["x"][:, 0], {"units": "mm", "long_name": "x of the interface point"}),
                "point_y": ("point", f["x"][:, 1], {"units": "mm", "long_name": "y of the interface point"}),
                "point_u_N_um": ("point", f["u_N_um"], {"units": "um", "long_name": "deflection from the seated state"}),
                "point_p_N": ("point", f["p_N"], {"units": "N/mm^2", "long_name": "interface pressure"}),
                "point_t_x": ("point", f["t_x"], {"units": "N/mm^2", "long_name": "tangential traction along x"}),
                "point_t_y": ("point", f["t_y"], {"units": "N/mm^2", "long_name": "tangential traction along y"}),
                "point_status": ("point", f["status"], {"units": "1", "long_name": "0 stick, 1 slip, 2 open"}),
                "point_weight": ("point", w, {"units": "mm^2", "long_name": "area of the point"}),
                "load": ("level", self.loads, {"units": "N", "long_name": "load on the full beam"}),
                "newton_iterations": ("level", self.newton_iterations, {"units": "1", "long_name": "Newton iterations"}),
                "cutbacks": ("level", self.cutbacks, {"units": "1", "long_name": "cut-backs of the load step"}),
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


def run_beam(run: BeamRun, *, options: NewtonOptions | None = None, progress=None) -> BeamResult:
    """Solve example 9.1: the run's deck and law through the deck reader and the solver."""
    t0 = time.perf_counter()
    spec = run.spec
    deck = read_deck("beam.inp", beam_deck(spec))
    report = None if progress is None else (lambda s, n_s, k, n, inc: progress(
        k if s == 1 else 1 + k, 1 + spec.increments, inc))
    res = run_deck_file(deck, run.law_file(), spec.elements, options, report)
    seated, final = res.step_end(1), res.step_end(2)
    pts = res.problem.points
    line = np.flatnonzero(np.isclose(pts.x[:, 1], 0.0))
    line = line[np.argsort(pts.x[line, 0])]
    closure = res.problem.materials.closure_mm(np.stack([seated.state, final.state]))[:, line]
    applied = -float(res.problem.loads[-1].reshape(-1, 3)[:, 2].sum())
    resultant = float(np.sum(final.state[:, friction.T_N] * pts.weights))
    return BeamResult(
        spec=spec, x_mm=pts.x[line, 0], u_N_um=-(closure[1] - closure[0]) * 1000.0,
        p_N=final.state[line, friction.T_N], open_x_mm=np.unique(np.round(pts.x[final.status == friction.OPEN, 0], 9)),
        loads=spec.levels, newton_iterations=np.array([i.iterations for i in res.increments]),
        cutbacks=np.array([i.cutbacks for i in res.increments]),
        equilibrium_error=abs(resultant - applied) / abs(applied), n_dofs=res.n_dofs, n_points=pts.n_points,
        seconds=time.perf_counter() - t0, deck=res)
