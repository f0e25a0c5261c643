"""A model of one's own, not the paper's: an aluminium block on a larger steel base under an
eccentric load, as one CalculiX/Abaqus deck that runs in ccx (with the exported pressure–
overclosure table in its *SURFACE BEHAVIOR) and in roughcontact (with the statistical law of
LAW.yaml in its place) — the example of docs/own-model.md and the CalculiX scene's deck.

Geometry [mm] (half model, y ≥ 0; the plane y = 0 a symmetry plane of the bodies and the load):
the base x ∈ [−20, 20], y ∈ [0, 20], z ∈ [−10, 0], steel E = 210000 N/mm², ν = 0.3, held at
its bottom; the block x ∈ [−10, 10], y ∈ [0, 10], z ∈ [0, 10], aluminium E = 70000 N/mm²,
ν = 0.33, its bottom on the base's top (node-matching grids), held in x at its top centre node
(the frictionless interface holds nothing tangentially; with ``friction`` the interface holds it
and the top is free). The load: a pressure on the block's top with x ≥ −5 mm (node set LOADED),
raised in ``increments``; with ``shear`` a second step adds a force along x spread evenly over the
LOADED nodes (``shear`` × the loaded area, *CLOAD), the pressure held. C3D20 elements, ``refine``
× (2, 1, 2) in the block and (4, 2, 2) in the base along x, y, z.

The interface: the Table 1 surface (m00 = 0.0625 µm² …), elastic, E* of the two materials
(eq. (42), from the deck's *ELASTIC), seated at ``seating_pressure`` (0.1 N/mm²: from
1e-3 N/mm² ccx needs five times the increments), frictionless or with ``friction`` (a
:mod:`roughcontact.fe.laws` friction, e.g. the orthotropic hardening law of section 8.1).
Node sets CONTACTSLAVE / CONTACTMASTER: the block's bottom and the base's top nodes under it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..fe.deck_writer import box_part, element_lines, id_lines, node_lines, number
from ..fe.laws import InteractionLaw, LawFile, NoFriction
from ..statistics import SpectralMoments
from ..validation import positive
from ..limits import describe

__all__ = ["BlockOnBase", "block_on_base_deck", "MOMENTS", "STEEL", "ALUMINIUM"]

#: the Table 1 surface [µm units]
MOMENTS = {"m00": 0.0625, "m20": 8.0e-5, "m02": 8.0e-4, "m40": 1.04e-6, "m04": 1.04e-4}
STEEL = (2.1e5, 0.3)
ALUMINIUM = (7.0e4, 0.33)
#: the loaded part of the block's top: x ≥ −5 mm (the resultant 2.5 mm off the centre)
LOADED_FROM = -5.0


@dataclass(frozen=True)
class BlockOnBase:
    """The model's numbers (module docstring): refinement, pressure [N/mm²] on the loaded half
    of the top, increments, seating pressure [N/mm²] (the law's reference state)."""

    refine: int = 1
    pressure: float = 10.0
    increments: int = 4
    seating_pressure: float = 0.1
    friction: object = field(default_factory=NoFriction)
    shear: float = 0.0

    def __post_init__(self):
        for name in ("refine", "increments"):
            v = getattr(self, name)
            if isinstance(v, bool) or int(v) != v or v < 1:
                raise ValueError(f"{name} must be a positive integer, got {describe(v)}")
        positive("pressure", self.pressure)
        positive("seating_pressure", self.seating_pressure)
        if not (self.shear >= 0.0 and np.isfinite(self.shear)):
            raise ValueError(f"shear must be >= 0 and finite, got {describe(self.shear)}")
        if self.shear > 0.0 and isinstance(self.friction, NoFriction):
            raise ValueError("a shear step needs friction (a frictionless interface holds nothing tangentially)")

    def law_file(self) -> LawFile:
        """The interface law (interaction ROUGH): E* from the deck's materials (42)."""
        law = InteractionLaw(SpectralMoments(**MOMENTS), "um", (1.0, 0.0, 0.0), "elastic", self.seating_pressure,
                             self.friction)
        return LawFile("mm", {"ROUGH": law})


def block_on_base_deck(spec: BlockOnBase = BlockOnBase(), table: str | None = None, digits: int = 12) -> str:
    """The deck (module docstring). ``table``: the *SURFACE BEHAVIOR lines for ccx (an exported
    table, roughcontact.interface.export, format calculix, mm), None: a linear placeholder (the
    reader replaces it by the law either way). Numbers with ``digits`` significant digits (ccx
    reads 20 characters per field)."""
    r = spec.refine

    def edges(a, b, n):
        return np.linspace(a, b, n * r + 1)

    base = box_part(edges(-20.0, 20.0, 8), edges(0.0, 20.0, 2), edges(-10.0, 0.0, 2))
    block = box_part(edges(-10.0, 10.0, 4), edges(0.0, 10.0, 1), edges(0.0, 10.0, 2),
                     first_node=int(base.node_ids[-1]) + 1, first_element=int(base.element_ids[-1]) + 1)
    bx = block.coords[block.node_ids - block.node_ids[0]]
    top = block.face_nodes["ZMAX"]
    top_x = bx[top - block.node_ids[0], 0]
    centre = top[np.argmin(np.abs(top_x) + bx[top - block.node_ids[0], 1])]
    corners = block.coords[block.connectivity[:, :8] - block.node_ids[0]]
    top_elements = block.face_elements["ZMAX"]
    loaded = top_elements[corners[top_elements - block.element_ids[0]][:, :, 0].min(axis=1) >= LOADED_FROM - 1e-9]
    behaviour = table if table is not None else "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.0e6, 0."
    loaded_nodes = top[top_x >= LOADED_FROM - 1e-9]
    under = base.face_nodes["ZMAX"]
    ux = base.coords[under - base.node_ids[0]]
    under = under[(np.abs(ux[:, 0]) <= 10.0 + 1e-9) & (ux[:, 1] <= 10.0 + 1e-9)]
    holding = isinstance(spec.friction, NoFriction)
    shear_step = []
    if spec.shear > 0.0:
        force = spec.shear * (10.0 - LOADED_FROM) * 10.0 / len(loaded_nodes)  # N per node, the half model
        shear_step = ["*STEP, INC=1000", "*STATIC", f"{number(1.0 / spec.increments, digits)}, 1., 1e-6, 1.",
                      "*CLOAD", *(f"{n}, 1, {number(force, digits)}" for n in loaded_nodes),
                      "*NODE PRINT, NSET=LOADED", "U", "*END STEP"]
    lines = [
        "*HEADING", "aluminium block on a steel base, eccentric load (roughcontact.examples.block_on_base), mm N",
        f"** refinement {r}: C3D20; contact: the block's bottom (slave) on the base's top (master)",
        *node_lines(base, "BASENODES", digits), *node_lines(block, "BLOCKNODES", digits),
        *element_lines(base, "BASE"), *element_lines(block, "BLOCK"),
        *id_lines("*NSET, NSET=BOTTOM", base.face_nodes["ZMIN"]),
        *id_lines("*NSET, NSET=SYMMETRY", np.concatenate([base.face_nodes["YMIN"], block.face_nodes["YMIN"]])),
        *id_lines("*NSET, NSET=LOADED", loaded_nodes), *id_lines("*NSET, NSET=HOLD", [centre]),
        *id_lines("*NSET, NSET=CONTACTSLAVE", block.face_nodes["ZMIN"]), *id_lines("*NSET, NSET=CONTACTMASTER", under),
        *id_lines("*ELSET, ELSET=LOADEDTOP", loaded),
        "*SURFACE, NAME=BLOCKBOTTOM", *(f"{e}, S1" for e in block.face_elements["ZMIN"]),
        "*SURFACE, NAME=BASETOP", *(f"{e}, S2" for e in base.face_elements["ZMAX"]),
        "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{number(STEEL[0], digits)}, {number(STEEL[1], digits)}",
        "*MATERIAL, NAME=ALUMINIUM", "*ELASTIC", f"{number(ALUMINIUM[0], digits)}, {number(ALUMINIUM[1], digits)}",
        "*SOLID SECTION, ELSET=BASE, MATERIAL=STEEL", "*SOLID SECTION, ELSET=BLOCK, MATERIAL=ALUMINIUM",
        "** in roughcontact the law ROUGH of LAW.yaml replaces this interaction's *SURFACE BEHAVIOR",
        "*SURFACE INTERACTION, NAME=ROUGH", *behaviour.strip("\n").splitlines(),
        "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=NODE TO SURFACE", "BLOCKBOTTOM, BASETOP",
        "*BOUNDARY", "BOTTOM, 1, 3", "SYMMETRY, 2, 2", *(["HOLD, 1, 1"] if holding else []),
        "*STEP, INC=1000", "*STATIC", f"{number(1.0 / spec.increments, digits)}, 1., 1e-6, 1.",
        "*DLOAD", f"LOADEDTOP, P2, {number(spec.pressure, digits)}",
        "*NODE PRINT, NSET=LOADED", "U", "*END STEP", *shear_step]
    return "\n".join(lines) + "\n"
