"""What a CalculiX/Abaqus input deck means, for the subset this engine runs (docs/own-model.md).

:func:`read_deck` turns the keyword blocks of :mod:`.deck_syntax` into a :class:`Deck`: nodes,
elements, sets, element-face surfaces, materials and sections, surface interactions, contact
pairs, and the steps with the state of every support and load at the end of each step.

The subset (keywords case-insensitive; names of sets, materials, surfaces and interactions
upper-cased, as both codes do):

=========================  ==================================================================
``*HEADING``               the title
``*NODE``                  ``NSET=``; id (1 … 2⁶³ − 1, the engine's int64), x[, y[, z]] (missing
                           coordinates are 0; reals as Fortran reads them, E or D exponent)
``*ELEMENT``               ``TYPE=C3D20`` or ``C3D20R`` (both the 20-node serendipity hexahedron,
                           integrated fully here), ``ELSET=``; connectivity over several lines
``*NSET``, ``*ELSET``      ids or names of sets; ``GENERATE`` (first, last[, step]; at most
                           ``ROUGHCONTACT_MAX_DECK_ITEMS`` ids a line, checked before they are made);
                           ``*NSET, ELSET=``: the nodes of those elements
``*SURFACE``               ``NAME=``, ``TYPE=ELEMENT``; element or elset, ``S1`` … ``S6``
``*MATERIAL``/``*ELASTIC`` ``NAME=``; E, ν (isotropic)
``*SOLID SECTION``         ``ELSET=``, ``MATERIAL=``
``*SURFACE INTERACTION``   ``NAME=``: the law of that name in LAW.yaml; its ``*SURFACE BEHAVIOR``
                           and ``*FRICTION`` are replaced by it (noted)
``*CONTACT PAIR``          ``INTERACTION=``; slave surface, master surface
``*BOUNDARY``              node or nset, first dof[, last dof[, value]], or node/nset, XSYMM,
                           YSYMM, ZSYMM, PINNED, ENCASTRE; in the model (every step) or a step
``*STEP`` … ``*END STEP``  with ``*STATIC``: initial increment (positive, normal, at most the
                           period, as ccx requires), period, minimum and maximum increment;
                           ``INC=`` the maximum number of increments; ``DIRECT``: fixed
                           increments (its minimum/maximum ignored, a note each; ``SOLVER=``
                           too) — docs/own-model.md, "Incrementation";
                           ``NLGEOM`` (bare: YES) an error but ``NLGEOM=NO``
``*CLOAD``                 node or nset, dof, force
``*DLOAD``                 element or elset, P1 … P6, pressure on that face
=========================  ==================================================================

Steps follow Abaqus: a load or a prescribed displacement keeps its value until a later step
changes it (``OP=MOD``, the default, changes the entries named; ``OP=NEW`` on ``*CLOAD`` or
``*DLOAD`` first removes every earlier load of that kind); within a step every value moves
linearly from the previous step's end to the new one (the ``RAMP`` amplitude of a static step).
Output requests (``*NODE PRINT``, ``*EL PRINT``, ``*NODE FILE``, ``*EL FILE``, ``*CONTACT PRINT``,
``*CONTACT FILE``, ``*OUTPUT`` …) are ignored with a note; any other keyword is an error
naming its line. ``*BOUNDARY, OP=NEW`` (removing supports) is an error too.
"""

from __future__ import annotations

import math
import re
import sys
from dataclasses import dataclass, field

import numpy as np

from ..limits import describe
from .deck_syntax import DeckError, Keyword, check_count, read_blocks, shown

__all__ = ["Deck", "Material", "ContactPair", "Step", "read_deck", "ELEMENT_TYPES", "IGNORED", "DeckError"]

#: element types and their node counts: the 20-node hexahedron (C3D20R's reduced integration is
#: not used) and the 10-node tetrahedron (deck_mesh: TET10, issue 31)
ELEMENT_TYPES = {"C3D20": 20, "C3D20R": 20, "C3D10": 10}
_UNSUPPORTED_ELEMENTS = {
    "C3D8": "8-node hexahedra cannot carry the paper's transition and interface elements (quadratic or cubic "
            "faces): mesh with C3D20 (e.g. gmsh -order 2)",
}
#: output requests: ignored with a note (with their data lines)
IGNORED = ("NODE PRINT", "EL PRINT", "NODE FILE", "EL FILE", "CONTACT PRINT", "CONTACT FILE", "NODE OUTPUT",
           "ELEMENT OUTPUT", "CONTACT OUTPUT", "OUTPUT", "SECTION PRINT", "ENERGY PRINT", "FACE PRINT", "MONITOR")
#: the Abaqus boundary types a *BOUNDARY line may name, as (first dof, last dof) of a solid
BOUNDARY_TYPES = {"XSYMM": (1, 1), "YSYMM": (2, 2), "ZSYMM": (3, 3), "PINNED": (1, 3), "ENCASTRE": (1, 3)}
MAX_INCREMENTS = 100_000
#: the largest id (node, element) the engine indexes: its id arrays are 64-bit integers
MAX_ID = int(np.iinfo(np.int64).max)
_INTEGER = re.compile(r"[+-]?[0-9]+")
#: a real as Fortran reads it: digits with an optional point and an exponent E or D (no "inf",
#: "nan", "1_000" or non-ASCII digits, which float() would accept)
_REAL = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eEdD][+-]?[0-9]+)?")


@dataclass(frozen=True)
class Material:
    """An isotropic elastic material: Young's modulus E and Poisson's ratio ν (deck units)."""

    name: str
    E: float
    nu: float
    where: str


@dataclass(frozen=True)
class ContactPair:
    """A contact pair: its interaction's name, the slave and master surfaces."""

    interaction: str
    slave: str
    master: str
    where: str


@dataclass(frozen=True)
class Step:
    """A static step: its period (deck time) and increments (fractions of the step, the last 1),
    and at its end the prescribed displacements {(node id, dof 1-3): value}, forces
    {(node id, dof): value} and face pressures {(element id, face 1-6): value} in force
    (Abaqus persistence applied)."""

    index: int
    where: str
    period: float
    fractions: tuple[float, ...]
    boundary: dict
    cload: dict
    dload: dict
    #: *STATIC's minimum and maximum increment (deck time; None: not given or DIRECT),
    #: *STEP, INC= and DIRECT, and the *STATIC data line (deck_run: the incrementation)
    minimum: float | None = None
    maximum: float | None = None
    max_increments: int | None = None
    direct: bool = False
    static_where: str = ""


@dataclass(frozen=True, eq=False)
class Deck:
    """A read deck (module docstring). Nodes: ``node_ids`` (N,), ``coords`` (N, 3); elements:
    ``element_ids`` (M,), ``connectivity`` (M, 20) node ids in C3D20 order, ``element_types``;
    ``nsets``/``elsets`` name → sorted ids; ``surfaces`` name → ((element id, face 1-6), ...);
    ``sections`` element id → material name; ``notes``: what was ignored, and where."""

    path: str
    heading: str
    node_ids: np.ndarray
    coords: np.ndarray
    element_ids: np.ndarray
    element_types: tuple[str, ...]
    connectivity: np.ndarray
    nsets: dict[str, np.ndarray]
    elsets: dict[str, np.ndarray]
    surfaces: dict[str, tuple[tuple[int, int], ...]]
    materials: dict[str, Material]
    element_material: dict[int, str]
    interactions: dict[str, str]
    contact_pairs: tuple[ContactPair, ...]
    steps: tuple[Step, ...]
    notes: tuple[str, ...] = ()
    where: dict = field(default_factory=dict, repr=False)

    def node_index(self, ids) -> np.ndarray:
        """Row indices of node ids in ``coords``."""
        ids = np.asarray(ids, dtype=np.int64)
        order = np.argsort(self.node_ids)
        pos = np.searchsorted(self.node_ids, ids, sorter=order)
        return order[np.minimum(pos, len(order) - 1)]


def _int(text: str, where: str, what: str) -> int:
    """A positive integer of at most :data:`MAX_ID` (ids, dofs, increments of a deck line)."""
    if not _INTEGER.fullmatch(text):
        raise DeckError(where, f"{what} must be an integer, got {describe(text)}")
    if len(text.lstrip("+-").lstrip("0")) > len(str(MAX_ID)):  # before int(): no huge conversions
        raise DeckError(where, f"{what} must be a positive integer of at most {MAX_ID} (the engine indexes with "
                               f"64-bit integers), got {describe(text)}")
    value = int(text)
    if value <= 0:
        raise DeckError(where, f"{what} must be positive, got {value}")
    if value > MAX_ID:
        raise DeckError(where, f"{what} must be a positive integer of at most {MAX_ID} (the engine indexes with "
                               f"64-bit integers), got {value}")
    return value


def _real(text: str, where: str, what: str) -> float:
    if not _REAL.fullmatch(text):
        raise DeckError(where, f"{what} must be a number, got {describe(text)}")
    value = float(text.replace("d", "e").replace("D", "E"))
    if not math.isfinite(value):
        raise DeckError(where, f"{what} must be finite, got {describe(text)}")
    return value


def _face_number(line, prefix: str, message: str) -> int:
    """The face k of a data line's second field ``<prefix>k`` (S1 ... S6 of *SURFACE, P1 ... P6
    of *DLOAD: the CalculiX face numbering), else DeckError(message)."""
    label = line.fields[1].upper()
    if label not in {f"{prefix}{k}" for k in range(1, 7)}:
        raise DeckError(line.where, message)
    return int(label[1])


class _Reader:
    """Walks the blocks once, keeping the definitions in order (a name must be defined before
    it is used, as CalculiX requires)."""

    def __init__(self, path):
        self.path = str(path)
        self.heading = ""
        self.nodes: dict[int, tuple[float, float, float]] = {}
        self.elements: dict[int, tuple[str, tuple[int, ...]]] = {}
        self.nsets: dict[str, set] = {}
        self.elsets: dict[str, set] = {}
        self.surfaces: dict[str, list] = {}
        self.materials: dict[str, Material] = {}
        self.element_material: dict[int, str] = {}
        self.interactions: dict[str, str] = {}
        self.pairs: list[ContactPair] = []
        self.steps: list[Step] = []
        self.notes: list[str] = []
        self.where: dict = {}
        self.state = {"boundary": {}, "cload": {}, "dload": {}}
        self.step_open: dict | None = None
        self.context: tuple[str, str] | None = None  # ("MATERIAL", name) or ("INTERACTION", name)

    # -- names and sets ---------------------------------------------------------------------
    def _name(self, kw: Keyword, param: str) -> str:
        return kw.param(param, required=True).strip('"').upper()

    def _refs(self, text: str, where: str, kind: str) -> list[int]:
        """The ids of a set (kind "node": *NSET, "element": *ELSET) named ``text``, or the one id."""
        sets, defined, keyword = ((self.nsets, self.nodes, "*NSET") if kind == "node"
                                  else (self.elsets, self.elements, "*ELSET"))
        name = text.strip('"').upper()
        if name in sets:
            return sorted(sets[name])
        if text.lstrip("-").isdigit():
            i = _int(text, where, f"a {kind} id")
            if i not in defined:
                raise DeckError(where, f"{kind} {i} is not defined")
            return [i]
        raise DeckError(where, f"missing set: no {keyword} {shown(name)} (nor {'an' if kind == 'element' else 'a'} "
                               f"{kind} id)")

    def _node_refs(self, text: str, where: str) -> list[int]:
        return self._refs(text, where, "node")

    def _element_refs(self, text: str, where: str) -> list[int]:
        return self._refs(text, where, "element")

    def _generate(self, kw: Keyword, line, what: str) -> range:
        """The ids of a GENERATE line (first, last[, increment]), their count checked against
        the limit "deck_items" before anything is built."""
        if len(line.fields) not in (2, 3):
            raise DeckError(line.where, f"*{kw.name}, GENERATE needs: first, last[, increment]")
        first, last = (_int(f, line.where, what) for f in line.fields[:2])
        step = _int(line.fields[2], line.where, "the increment") if len(line.fields) == 3 else 1
        if last < first:
            raise DeckError(line.where, f"GENERATE: last {last} < first {first}")
        ids = range(first, last + 1, step)
        check_count(len(ids), "deck_items", line.where, f"*{kw.name}, GENERATE {first}, {last}, {step}: the ids")
        return ids

    # -- keywords ---------------------------------------------------------------------------
    def heading_(self, kw):
        self.heading = " ".join(", ".join(line.fields) for line in kw.data)

    def node(self, kw):
        nset = kw.param("NSET")
        ids = []
        for line in kw.data:
            if not 2 <= len(line.fields) <= 4:
                raise DeckError(line.where, "*NODE data: id, x[, y[, z]]")
            nid = _int(line.fields[0], line.where, "a node id")
            if nid in self.nodes:
                raise DeckError(line.where, f"node {nid} is defined twice")
            xyz = [_real(f, line.where, "a coordinate") for f in line.fields[1:]]
            self.nodes[nid] = tuple(xyz + [0.0] * (3 - len(xyz)))
            self.where[("node", nid)] = line.where
            ids.append(nid)
        if nset:
            self.nsets.setdefault(nset.strip('"').upper(), set()).update(ids)

    def element(self, kw):
        etype = kw.param("TYPE", required=True).upper()
        if etype not in ELEMENT_TYPES:
            why = _UNSUPPORTED_ELEMENTS.get(etype[:4] if etype.startswith("C3D8") else etype,
                                            "the engine runs 20-node hexahedra (C3D20, C3D20R) and 10-node tetrahedra (C3D10)")
            raise DeckError(kw.where, f"unknown element type {shown(etype)}: {why}")
        n = ELEMENT_TYPES[etype]
        elset = kw.param("ELSET")
        ids, fields, start = [], [], ""
        for line in kw.data:
            if not fields:
                start = line.where
            fields += list(line.fields)
            if len(fields) < n + 1:
                continue  # a connectivity continued on the next line without a trailing comma
            if len(fields) > n + 1:
                before = len(fields) - len(line.fields)  # fields of the element's lines before this one
                if before:  # a short element, or a line with too many nodes: say both counts
                    raise DeckError(start, f"{etype} element {shown(fields[0])} with {before - 1} nodes, and the next "
                                           f"line ({line.where}) has {len(line.fields)} fields, more than the "
                                           f"{n + 1 - before} missing ({etype} needs {n})")
                raise DeckError(start, f"{etype} element {shown(fields[0])} with {len(fields) - 1} nodes "
                                       f"({etype} needs {n})")
            eid = _int(fields[0], start, "an element id")
            if eid in self.elements:
                raise DeckError(start, f"element {eid} is defined twice")
            conn = tuple(_int(f, start, "a node id") for f in fields[1:])
            missing = [c for c in conn if c not in self.nodes]
            if missing:
                raise DeckError(start, f"element {eid} refers to node {missing[0]}, which is not defined")
            if len(set(conn)) != n:
                raise DeckError(start, f"element {eid} repeats a node")
            self.elements[eid] = (etype, conn)
            self.where[("element", eid)] = start
            ids.append(eid)
            fields = []
        if fields:
            raise DeckError(start, f"{etype} element {shown(fields[0])} with {len(fields) - 1} nodes "
                                   f"({etype} needs {n})")
        if elset:
            self.elsets.setdefault(elset.strip('"').upper(), set()).update(ids)

    def nset(self, kw):
        name = self._name(kw, "NSET")
        members = self.nsets.setdefault(name, set())
        if kw.param("ELSET"):
            for eid in self._element_refs(kw.param("ELSET"), kw.where):
                members.update(self.elements[eid][1])
        self._add_members(kw, members, "node", self.nodes, self._node_refs)
        self.where[("nset", name)] = kw.where

    def elset(self, kw):
        name = self._name(kw, "ELSET")
        self._add_members(kw, self.elsets.setdefault(name, set()), "element", self.elements, self._element_refs)

    def _add_members(self, kw, members: set, what: str, defined, refs):
        """The data lines of *NSET/*ELSET into ``members``: ids and set names, or GENERATE ranges."""
        for line in kw.data:
            if kw.flag("GENERATE"):
                ids = self._generate(kw, line, f"a{'n' if what == 'element' else ''} {what} id")
                # lazily: a missing id turns up within the first len(defined) + 1 ids
                missing = next((i for i in ids if i not in defined), None)
                if missing is not None:
                    raise DeckError(line.where, f"GENERATE: {what} {missing} is not defined")
                members.update(ids)
            else:
                for f in line.fields:
                    members.update(refs(f, line.where))

    def surface(self, kw):
        name = self._name(kw, "NAME")
        kind = (kw.param("TYPE") or "ELEMENT").upper()
        if kind != "ELEMENT":
            raise DeckError(kw.where, f"*SURFACE, TYPE={kind} is not supported: give element faces "
                                      "(TYPE=ELEMENT; the interface elements join element faces)")
        faces = self.surfaces.setdefault(name, [])
        for line in kw.data:
            if len(line.fields) != 2:
                raise DeckError(line.where, "*SURFACE data: element or elset, S1 ... S6")
            face = _face_number(line, "S", f"face {describe(line.fields[1])} is not one of S1 ... S6")
            faces += [(eid, face) for eid in self._element_refs(line.fields[0], line.where)]
        self.where[("surface", name)] = kw.where

    def material(self, kw):
        self.context = ("MATERIAL", self._name(kw, "NAME"))

    def elastic(self, kw):
        if not self.context or self.context[0] != "MATERIAL":
            raise DeckError(kw.where, "*ELASTIC outside a *MATERIAL")
        kind = (kw.param("TYPE") or "ISO").upper()
        if kind not in ("ISO", "ISOTROPIC"):
            raise DeckError(kw.where, f"*ELASTIC, TYPE={kind} is not supported (isotropic only)")
        if len(kw.data) != 1 or len(kw.data[0].fields) != 2:
            raise DeckError(kw.where, "*ELASTIC needs one data line: E, nu (no temperature dependence)")
        line = kw.data[0]
        E, nu = (_real(f, line.where, w) for f, w in zip(line.fields, ("Young's modulus E", "Poisson's ratio")))
        if not E > 0.0:
            raise DeckError(line.where, f"Young's modulus must be positive, got {E:g}")
        if not -1.0 < nu < 0.5:
            raise DeckError(line.where, f"Poisson's ratio must lie in (-1, 0.5), got {nu:g}")
        name = self.context[1]
        self.materials[name] = Material(name, E, nu, line.where)

    def solid_section(self, kw):
        elset, material = self._name(kw, "ELSET"), self._name(kw, "MATERIAL")
        if material not in self.materials:
            raise DeckError(kw.where, f"*SOLID SECTION: material {material} is not defined (or has no *ELASTIC)")
        for eid in self._element_refs(elset, kw.where):
            if eid in self.element_material:
                raise DeckError(kw.where, f"element {eid} has two sections")
            self.element_material[eid] = material

    def surface_interaction(self, kw):
        name = self._name(kw, "NAME")
        self.interactions[name] = kw.where
        self.context = ("INTERACTION", name)

    def interaction_option(self, kw):
        if not self.context or self.context[0] != "INTERACTION":
            raise DeckError(kw.where, f"*{kw.name} outside a *SURFACE INTERACTION")
        self.notes.append(f"{kw.where}: *{kw.name} of interaction {self.context[1]} replaced by the law "
                          f"{self.context[1]} of the law file")

    def contact_pair(self, kw):
        name = self._name(kw, "INTERACTION")
        kind = (kw.param("TYPE") or "NODE TO SURFACE").upper()
        kw.flag("ADJUST")
        kw.flag("SMALL SLIDING")
        if name not in self.interactions:
            raise DeckError(kw.where, f"*CONTACT PAIR: interaction {name} is not defined (*SURFACE INTERACTION)")
        self.notes.append(f"{kw.where}: *CONTACT PAIR, TYPE={shown(kind)}: conforming faces joined by interface "
                          "elements "
                          "whatever the type")
        for line in kw.data:
            if len(line.fields) != 2:
                raise DeckError(line.where, "*CONTACT PAIR data: slave surface, master surface")
            slave, master = (f.strip('"').upper() for f in line.fields)
            for s in (slave, master):
                if s not in self.surfaces:
                    raise DeckError(line.where, f"surface {s} is not defined (*SURFACE)")
            if slave == master:
                raise DeckError(line.where, "the slave and the master surface are the same")
            self.pairs.append(ContactPair(name, slave, master, line.where))

    # -- history ----------------------------------------------------------------------------
    def boundary(self, kw):
        if (kw.param("OP") or "MOD").upper() == "NEW":
            raise DeckError(kw.where, "*BOUNDARY, OP=NEW (removing supports between steps) is not supported")
        kw.flag("FIXED")
        target = self.state["boundary"]
        for line in kw.data:
            nodes = self._node_refs(line.fields[0], line.where)
            if len(line.fields) == 2 and line.fields[1].upper() in BOUNDARY_TYPES:
                first, last = BOUNDARY_TYPES[line.fields[1].upper()]
                value = 0.0
            elif 2 <= len(line.fields) <= 4:
                first = _int(line.fields[1], line.where, "the first dof")
                last = _int(line.fields[2], line.where, "the last dof") if len(line.fields) > 2 and line.fields[2] else first
                value = _real(line.fields[3], line.where, "the value") if len(line.fields) == 4 else 0.0
            else:
                raise DeckError(line.where, "*BOUNDARY data: node or nset, first dof[, last dof[, value]]")
            if not 1 <= first <= last <= 3:
                raise DeckError(line.where, f"dofs {first}-{last}: solid elements have the displacements 1-3 only")
            for n in nodes:
                for dof in range(first, last + 1):
                    target[(n, dof)] = value
                    self.where[("boundary", n, dof)] = line.where

    def _op(self, kw, kind: str) -> dict:
        if self.step_open is None:
            raise DeckError(kw.where, f"*{kw.name} outside a *STEP")
        target = self.state[kind]
        if (kw.param("OP") or "MOD").upper() == "NEW":
            target.clear()
        return target

    def cload(self, kw):
        target = self._op(kw, "cload")
        for line in kw.data:
            if len(line.fields) != 3:
                raise DeckError(line.where, "*CLOAD data: node or nset, dof, magnitude")
            dof = _int(line.fields[1], line.where, "the dof")
            if dof > 3:
                raise DeckError(line.where, f"dof {dof}: solid elements carry the forces 1-3 only")
            value = _real(line.fields[2], line.where, "the force")
            for n in self._node_refs(line.fields[0], line.where):
                target[(n, dof)] = value
                self.where[("cload", n, dof)] = line.where

    def dload(self, kw):
        target = self._op(kw, "dload")
        for line in kw.data:
            if len(line.fields) != 3:
                raise DeckError(line.where, "*DLOAD data: element or elset, P1 ... P6, pressure")
            face = _face_number(line, "P", f"load type {describe(line.fields[1])}: only face pressures P1 ... P6")
            value = _real(line.fields[2], line.where, "the pressure")
            for eid in self._element_refs(line.fields[0], line.where):
                target[(eid, face)] = value
                self.where[("dload", eid, face)] = line.where

    def step(self, kw):
        if self.step_open is not None:
            raise DeckError(kw.where, "*STEP inside a step (missing *END STEP)")
        if kw.flag("NLGEOM"):
            value = (kw.params["NLGEOM"] or "").strip('"').upper()
            if value not in ("NO", "NONE"):
                given = f"NLGEOM={shown(value)}" if value else "NLGEOM (without a value: YES, as Abaqus reads it)"
                raise DeckError(kw.where, f"*STEP, {given}: geometric nonlinearity (large displacements and rotations) "
                                          "is not supported: the engine is geometrically linear (give NLGEOM=NO or "
                                          "leave it out)")
        inc = kw.param("INC")
        kw.param("NAME")
        self.step_open = {"where": kw.where, "fractions": None,
                          "inc": _int(inc, kw.where, "*STEP, INC= (the maximum number of increments)") if inc else None}

    #: *STATIC's data fields beyond the initial increment and the period (Abaqus, CalculiX)
    _STATIC_LIMITS = ("the minimum increment", "the maximum increment")

    def static(self, kw):
        if self.step_open is None:
            raise DeckError(kw.where, "*STATIC outside a *STEP")
        direct = kw.flag("DIRECT")
        solver = kw.param("SOLVER")
        if solver:
            self.notes.append(f"{kw.where}: *STATIC, SOLVER={shown(solver)} ignored: the engine chooses its own "
                              "linear solver")
        if len(kw.data) > 1:
            raise DeckError(kw.data[1].where, "*STATIC takes one data line: initial increment, period[, minimum, "
                                              "maximum increment]")
        fields = kw.data[0].fields if kw.data else ()
        where = kw.data[0].where if kw.data else kw.where
        initial = _real(fields[0], where, "the initial increment") if len(fields) > 0 and fields[0] else 1.0
        period = _real(fields[1], where, "the step period") if len(fields) > 1 and fields[1] else 1.0
        if not period > 0.0:
            raise DeckError(where, f"*STATIC: the step period must be positive, got {period:g}")
        if not initial > 0.0:
            raise DeckError(where, f"*STATIC with zero increments: the initial increment must be positive, got {initial:g}")
        if initial < sys.float_info.min:  # subnormal: period / initial overflows, and no increment is that small
            raise DeckError(where, f"*STATIC: the initial increment {initial:g} is subnormal: it must be positive and "
                                   f"normal (at least {sys.float_info.min:g}) and at most the step period {period:g}")
        if initial > period:  # as ccx: "initial increment size exceeds step size"
            raise DeckError(where, f"*STATIC: the initial increment {initial:g} exceeds the step period {period:g} "
                                   "(it must be positive, normal and at most the period)")
        ratio = period / initial  # finite and >= 1 (inf only beyond MAX_INCREMENTS, refused first)
        if not ratio <= MAX_INCREMENTS * (1.0 + 1e-12):
            raise DeckError(where, f"*STATIC: {ratio:.4g} increments (period {period:g} / initial increment "
                                   f"{initial:g}) exceed {MAX_INCREMENTS}")
        n = max(1, math.ceil(ratio * (1.0 - 1e-12)))
        limits = [None, None]
        for k, text in enumerate(fields[2:], start=3):
            if not text:
                continue
            what = self._STATIC_LIMITS[k - 3] if k - 3 < len(self._STATIC_LIMITS) else f"field {k}"
            value = _real(text, where, f"*STATIC {what}")
            if k > 4 or direct:
                why = "DIRECT runs" if direct else "the step runs"
                self.notes.append(f"{where}: *STATIC {what} {value:g} ignored: {why} {n} fixed increments "
                                  "(period / initial increment), each halved when Newton fails (up to six times)")
            elif not 0.0 < value < math.inf or (k == 3 and value > initial) or (k == 4 and value < initial):
                rule = "at most the initial increment" if k == 3 else "at least the initial increment"
                raise DeckError(where, f"*STATIC {what} {value:g}: it must be positive and {rule} {initial:g}")
            else:
                limits[k - 3] = value
        self.step_open.update(fractions=tuple((k + 1) * initial / period for k in range(n - 1)) + (1.0,),
                              period=period, minimum=limits[0], maximum=limits[1], direct=direct, static_where=where)

    def end_step(self, kw):
        if self.step_open is None:
            raise DeckError(kw.where, "*END STEP without *STEP")
        if self.step_open["fractions"] is None:
            raise DeckError(self.step_open["where"], "a step needs *STATIC (the only procedure supported)")
        o = self.step_open
        self.steps.append(Step(len(self.steps) + 1, o["where"], o["period"], o["fractions"],
                               dict(self.state["boundary"]), dict(self.state["cload"]), dict(self.state["dload"]),
                               o["minimum"], o["maximum"], o["inc"], o["direct"], o["static_where"]))
        self.step_open = None


_HANDLERS = {
    "HEADING": "heading_", "NODE": "node", "ELEMENT": "element", "NSET": "nset", "ELSET": "elset",
    "SURFACE": "surface", "MATERIAL": "material", "ELASTIC": "elastic", "SOLID SECTION": "solid_section",
    "SURFACE INTERACTION": "surface_interaction", "SURFACE BEHAVIOR": "interaction_option",
    "FRICTION": "interaction_option", "CONTACT PAIR": "contact_pair", "BOUNDARY": "boundary",
    "CLOAD": "cload", "DLOAD": "dload", "STEP": "step", "STATIC": "static", "END STEP": "end_step",
}
#: the keywords that keep the *MATERIAL / *SURFACE INTERACTION context open
_OPTIONS = {"ELASTIC", "SURFACE BEHAVIOR", "FRICTION"}


#: keywords with data lines (the others take none)
_TAKES_DATA = {"HEADING", "NODE", "ELEMENT", "NSET", "ELSET", "SURFACE", "ELASTIC", "BOUNDARY", "CLOAD", "DLOAD",
               "STATIC", "CONTACT PAIR", "SURFACE BEHAVIOR", "FRICTION", "SOLID SECTION"}


def _padded(conn: tuple[int, ...]) -> tuple[int, ...]:
    """A connectivity as a row of 20 ids: a C3D10's 10 then its first id repeated (deck_mesh reads
    the first ELEMENT_TYPES[type] of a row)."""
    return conn + (conn[0],) * (20 - len(conn))


def read_deck(path, text: str | None = None) -> Deck:
    """Read the deck at ``path`` (module docstring), or the deck ``text`` under that name;
    DeckError naming file and line otherwise."""
    r = _Reader(path)
    for kw in read_blocks(path, text):
        if kw.name in IGNORED:
            r.notes.append(f"{kw.where}: *{kw.name} ignored (output requests: use --json / --vtu)")
            continue
        if kw.name not in _HANDLERS:
            raise DeckError(kw.where, f"unsupported keyword *{shown(kw.name)} (docs/own-model.md lists the subset)")
        if kw.name not in _OPTIONS:
            r.context = None
        if kw.data and kw.name not in _TAKES_DATA:
            raise DeckError(kw.data[0].where, f"*{kw.name} takes no data lines")
        getattr(r, _HANDLERS[kw.name])(kw)
        kw.check_params(kw.params if kw.name in ("SURFACE BEHAVIOR", "FRICTION") else ())
    return _finish(r)


def _finish(r: _Reader) -> Deck:
    if r.step_open is not None:
        raise DeckError(r.step_open["where"], "*STEP without *END STEP")
    where = f"{r.path}:1"
    if not r.elements:
        raise DeckError(where, "the deck defines no elements")
    if not r.steps:
        raise DeckError(where, "the deck has no *STEP")
    missing = sorted(set(r.elements) - set(r.element_material))
    if missing:
        raise DeckError(r.where[("element", missing[0])], f"element {missing[0]} has no *SOLID SECTION")
    node_ids = np.array(sorted(r.nodes), dtype=np.int64)
    element_ids = np.array(sorted(r.elements), dtype=np.int64)
    return Deck(
        path=r.path, heading=r.heading, node_ids=node_ids,
        coords=np.array([r.nodes[i] for i in node_ids], dtype=float).reshape(-1, 3),
        element_ids=element_ids, element_types=tuple(r.elements[i][0] for i in element_ids),
        connectivity=np.array([_padded(r.elements[i][1]) for i in element_ids], dtype=np.int64),
        nsets={k: np.array(sorted(v), dtype=np.int64) for k, v in r.nsets.items()},
        elsets={k: np.array(sorted(v), dtype=np.int64) for k, v in r.elsets.items()},
        surfaces={k: tuple(v) for k, v in r.surfaces.items()}, materials=dict(r.materials),
        element_material=dict(r.element_material), interactions=dict(r.interactions),
        contact_pairs=tuple(r.pairs), steps=tuple(r.steps), notes=tuple(r.notes), where=r.where)
