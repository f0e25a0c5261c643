"""The block-on-base problem of `make bench-fe`: one geometry, written as a CalculiX input deck
(C3D20) and built through the engine's API (`box`, `merge`, `interface_between`).

A steel block 20 × 20 × 10 mm stands in the middle of a cast-iron base 60 × 60 × 20 mm
(x, y, z in mm; the base's top at z = 0). The base is held at its bottom (u = 0); the block's
top is held in its plane (u_x = u_y = 0: a platen that presses without twisting or sliding,
which also removes the rigid sliding of the block on the frictionless interface) and carries a
uniform pressure on its third x ≥ 33.3 mm (an eccentric load: the interface pressure rises
towards the loaded edge). Interface: the statistical law of the surface ``MOMENTS`` (µm),
elastic, E* of the two bodies (eq. 42), seated at ``SEATING_PRESSURE``: CalculiX gets it as the
exported pressure–overclosure table (``roughcontact.interface.export``, node-to-surface contact,
block bottom = slave), the engine the law itself (nodal interface elements on the transition
faces of both bodies). Loaded from zero in ``increments`` equal steps.

Refinement r = 1, 2, 3: the block has 3r × 3r × r elements, the base 9r × 9r × 2r (its
middle 3r × 3r columns match the block's bottom node for node), so the deck has
3408, 21498, 66588 dofs (the issue's "3.4 k, 21.6 k, 65 k").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from roughcontact import SpectralMoments
from roughcontact.fe import assembly
from roughcontact.fe.contact import statistical_interface
from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines
from roughcontact.fe.mesh import box, dofs, interface_between, merge
from roughcontact.fe.solver import ContactModel
from roughcontact.paper.calculix import table_lines

#: the surface of the interface (µm): the moments of the issue's example law
MOMENTS = dict(m00=0.0625, m20=8.0e-5, m02=8.0e-4, m40=1.04e-6, m04=1.04e-4)
#: N/mm²: the law's reference state (u_N = 0)
SEATING_PRESSURE = 1.0e-3
#: N/mm²: the tables' range (the heavy end far above the ~35 N/mm² at the loaded edge; 180 rows
#: within 1e-3 for CalculiX, which takes at most 200)
PRESSURE_RANGE = (1.0e-5, 100.0)


@dataclass(frozen=True)
class BlockOnBase:
    """Geometry [mm], materials [N/mm²], the load [N/mm² on the loaded third of the top] and the
    refinement."""

    refine: int = 1
    block: tuple = (20.0, 20.0, 10.0)
    base: tuple = (60.0, 60.0, 20.0)
    E_block: float = 2.10e5
    nu_block: float = 0.30
    E_base: float = 1.10e5
    nu_base: float = 0.26
    pressure: float = 12.0
    increments: int = 16

    def __post_init__(self):
        if int(self.refine) != self.refine or self.refine < 1:
            raise ValueError(f"refine must be a positive integer, got {self.refine!r}")

    @property
    def E_star(self) -> float:
        """1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ (eq. 42) [N/mm²]."""
        return 1.0 / ((1.0 - self.nu_block ** 2) / self.E_block + (1.0 - self.nu_base ** 2) / self.E_base)

    def edges(self):
        """Element boundaries (x, y, z) of the block and of the base [mm]: uniform elements of
        block/(3r) in plan (the base's under the block match the block's node for node), r
        layers through the block, 2r through the base."""
        r = self.refine
        (bx, by, bz), (Bx, By, Bz) = self.block, self.base
        x0, y0 = (Bx - bx) / 2.0, (By - by) / 2.0
        nx, ny = 3 * r, 3 * r
        mx, my = round(x0 / (bx / nx)), round(y0 / (by / ny))  # base elements beside the block

        def around(lo, width, total, n, m):
            return np.concatenate([np.linspace(0.0, lo, m + 1)[:-1], np.linspace(lo, lo + width, n + 1),
                                   np.linspace(lo + width, total, m + 1)[1:]])

        block = (np.linspace(x0, x0 + bx, nx + 1), np.linspace(y0, y0 + by, ny + 1), np.linspace(0.0, bz, r + 1))
        base = (around(x0, bx, Bx, nx, mx), around(y0, by, By, ny, my), np.linspace(-Bz, 0.0, 2 * r + 1))
        return block, base

    @property
    def load_x(self) -> float:
        """The loaded third of the top: x ≥ load_x [mm] (an element boundary at every refinement)."""
        (x, _, _), _ = self.edges()
        return x[0] + 2.0 * (x[-1] - x[0]) / 3.0

    @property
    def levels(self) -> np.ndarray:
        """Load levels (fractions of ``pressure``): ``increments`` equal steps from zero."""
        return np.linspace(0.0, 1.0, self.increments + 1)[1:]


def interface_material(problem: BlockOnBase):
    """The engine's interface: the elastic statistical law, frictionless, seated at p0."""
    return statistical_interface(SpectralMoments(**MOMENTS), SEATING_PRESSURE, E_star=problem.E_star,
                                 pressure_range=PRESSURE_RANGE)


def calculix_table(problem: BlockOnBase, rtol: float = 1e-3) -> str:
    """The exported pressure–overclosure table (mm, N/mm²) of the same law."""
    from roughcontact.interface.export import CALCULIX_MAX_ROWS, format_table, overclosure_table

    table = overclosure_table(SpectralMoments(**MOMENTS), pressure_range=PRESSURE_RANGE, E_star=problem.E_star,
                              rtol=rtol, reference="seating", seating_pressure=SEATING_PRESSURE,
                              max_rows=CALCULIX_MAX_ROWS)
    return format_table(table, "calculix", length_scale=1e-3, length_unit="mm", stress_unit="N/mm^2")


# ---------------------------------------------------------------------------------------------
# the engine, through its API
# ---------------------------------------------------------------------------------------------
def engine_model(problem: BlockOnBase, material=None):
    """(mesh, ContactModel): both bodies, the interface (side A the base), supports and the
    load pattern (1 per unit level = ``pressure`` on the loaded third)."""
    (bx, by, bz), (Bx, By, Bz) = problem.edges()
    block = box(bx, by, bz, contact_face="bottom", name="block")
    base = box(Bx, By, Bz, contact_face="top", name="base")
    mesh = interface_between(merge(base, block), "base.contact", "block.contact")
    ns = mesh.node_sets
    fixed = np.concatenate([dofs(ns["base.zmin"], (0, 1, 2)), dofs(ns["block.zmax"], (0, 1))])
    top = mesh.face_sets["block.zmax"]
    centre_x = mesh.points[top.face_nodes].mean(axis=1)[:, 0]
    loaded = top.face_nodes[centre_x > problem.load_x]
    load = assembly.surface_traction(mesh.points, top.face_element, loaded, (0.0, 0.0, -problem.pressure))
    elasticity = {name: assembly.isotropic_elasticity(E, nu)
                  for prefix, E, nu in (("block", problem.E_block, problem.nu_block), ("base", problem.E_base, problem.nu_base))
                  for name in (f"{prefix}.bulk", f"{prefix}.transition")}
    material = interface_material(problem) if material is None else material
    return mesh, ContactModel.assemble(mesh, elasticity, material, fixed, load)


# ---------------------------------------------------------------------------------------------
# the CalculiX deck
# ---------------------------------------------------------------------------------------------
def calculix_deck(problem: BlockOnBase, table_text: str) -> str:
    """The deck (CalculiX/Abaqus syntax, mm, N): C3D20 bodies BLOCK and BASE, the contact pair
    (slave: the block's bottom, master: the base's top) with the *SURFACE INTERACTION ROUGH
    of ``table_text`` (:func:`calculix_table`), one *STEP of ``increments`` initial increments,
    node sets BLOCKBOTTOM and LOADED printed at the end."""
    block_edges, base_edges = problem.edges()
    base = box_part(*base_edges)
    block = box_part(*block_edges, first_node=len(base.node_ids) + 1, first_element=len(base.element_ids) + 1)
    # the loaded faces: the block's top layer, element centres at x > load_x
    x = block.edges[0]
    top = block.face_elements["ZMAX"]
    centre_x = 0.5 * (x[:-1] + x[1:])[block.element_ijk[top - block.element_ids[0], 0]]
    loaded_el = top[centre_x > problem.load_x]

    def lines(*blocks):
        return "\n".join(line for b in blocks for line in b)

    dt = 1.0 / problem.increments
    return f"""** roughcontact benchmark: block on base, refinement {problem.refine} (benchmarks/block_on_base.py)
** units mm, N, N/mm^2; the interface law exported by roughcontact.interface.export
*HEADING
block on base, refinement {problem.refine}
{lines(node_lines(base, "NALL", digits=12), node_lines(block, digits=12)[1:])}
{lines(element_lines(base, "BASE"), element_lines(block, "BLOCK"))}
{lines(id_lines("*ELSET, ELSET=BLOCKBOTTOMEL", block.face_elements["ZMIN"]),
       id_lines("*ELSET, ELSET=BASETOPEL", base.face_elements["ZMAX"]), id_lines("*ELSET, ELSET=LOADEDEL", loaded_el),
       id_lines("*NSET, NSET=BLOCKBOTTOM", block.face_nodes["ZMIN"]),
       id_lines("*NSET, NSET=BLOCKTOP", block.face_nodes["ZMAX"]),
       id_lines("*NSET, NSET=BASEBOTTOM", base.face_nodes["ZMIN"]))}
*MATERIAL, NAME=STEEL
*ELASTIC
{problem.E_block:.12e}, {problem.nu_block}
*MATERIAL, NAME=CASTIRON
*ELASTIC
{problem.E_base:.12e}, {problem.nu_base}
*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL
*SOLID SECTION, ELSET=BASE, MATERIAL=CASTIRON
*SURFACE, NAME=SLAVE, TYPE=ELEMENT
BLOCKBOTTOMEL, S1
*SURFACE, NAME=MASTER, TYPE=ELEMENT
BASETOPEL, S2
*SURFACE INTERACTION, NAME=ROUGH
{table_lines(table_text)}
*CONTACT PAIR, INTERACTION=ROUGH, TYPE=NODE TO SURFACE
SLAVE, MASTER
*BOUNDARY
BASEBOTTOM, 1, 3, 0.0
BLOCKTOP, 1, 2, 0.0
*STEP, INC=1000
*STATIC
{dt:.12g}, 1.0, {dt * 2.0 ** -10:.6g}, {dt:.12g}
*DLOAD
{chr(10).join(f"{e}, P2, {problem.pressure:.12e}" for e in loaded_el)}
*NODE PRINT, NSET=BLOCKBOTTOM
U
*END STEP
"""


def deck_dofs(problem: BlockOnBase) -> int:
    """Unknowns of the deck: 3 per C3D20 node of both bodies."""
    def nodes(e):  # corners and mid-edge nodes of a structured C3D20 mesh
        n = [len(a) - 1 for a in e]
        return ((2 * n[0] + 1) * (2 * n[1] + 1) - n[0] * n[1]) * (n[2] + 1) + (n[0] + 1) * (n[1] + 1) * n[2]

    block, base = problem.edges()
    return 3 * (nodes(block) + nodes(base))


__all__ = ["BlockOnBase", "MOMENTS", "SEATING_PRESSURE", "PRESSURE_RANGE", "interface_material", "calculix_table",
           "engine_model", "calculix_deck", "deck_dofs"]
