"""The discrete problem of a deck: bulk stiffness, interface points and laws, and every step's
supports and loads on the engine's mesh (:mod:`.deck_mesh`); solved by :mod:`.deck_run`.

* Materials: the *ELASTIC of every element's section (isotropic, :func:`.assembly.isotropic_elasticity`).
* Interactions: each contact pair's interface elements get the law of its interaction
  (:class:`~.laws.InteractionLaw`): integration points (nodal, Lobatto) with t1 along the law's
  lay direction projected onto the master face, t2 = n × t1, n from master to slave; E* from the
  law or, if it gives none, from the *ELASTIC of the two bodies (eq. (42)).
* Loads: ``*CLOAD`` forces on nodes; ``*DLOAD`` pressures p on element faces, the consistent
  nodal forces f_a = −p ∫ N_a n dA (n the face's outward normal) on the faces of the engine's
  (possibly transition) element.
* Supports: ``*BOUNDARY`` values on nodes; a point made on a contact face inherits a support
  when every deck node of its edge or face has it with the same value (:mod:`.deck_mesh`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp

from ..limits import describe
from . import assembly
from .contact import LawResponse
from .deck import DeckError
from .deck_mesh import DeckMesh, face_of
from .interface_points import InterfacePoints, interface_points
from .laws import LawError, LawFile, mindlin_poisson
from .mesh import Mesh

__all__ = ["InterfaceLaws", "DeckProblem", "deck_problem", "pair_modulus", "pressure_forces"]


@dataclass(frozen=True, eq=False)
class InterfaceLaws:
    """The interface materials of several point ranges as one (the solver sees one material):
    ``parts`` ((InterfaceMaterial, start, stop), ...) in point order; ``start_state`` the
    committed states to continue from (a later step), None: every law's initial state."""

    parts: tuple
    start_state: np.ndarray | None = field(default=None, repr=False)

    def initial_state(self, n_points: int) -> np.ndarray:
        if self.start_state is not None:
            return self.start_state.copy()
        return np.concatenate([m.initial_state(b - a) for m, a, b in self.parts])

    def resumed(self, state: np.ndarray) -> "InterfaceLaws":
        """The same laws, starting from the committed ``state`` (the next step)."""
        return replace(self, start_state=np.array(state, copy=True))

    def respond(self, committed: np.ndarray, d_jump, *, extrapolate: bool = False) -> LawResponse:
        out = [m.respond(committed[a:b], d_jump[a:b], extrapolate=extrapolate) for m, a, b in self.parts]
        if len(out) == 1:
            return out[0]
        return LawResponse(*(np.concatenate([getattr(r, f) for r in out]) for f in LawResponse._fields))

    def beyond_table(self, state: np.ndarray) -> np.ndarray:
        """(n,) True where a converged state lies past the heavy end of its tabulated law."""
        return np.concatenate([m.beyond_table(state[a:b]) for m, a, b in self.parts])

    def normal_of(self, point: int):
        """The normal law of interface point ``point`` (the solver's range message)."""
        return next(m.normal for m, a, b in self.parts if a <= point < b)

    def closure_mm(self, state: np.ndarray) -> np.ndarray:
        """Closure from each law's reference state, in the deck's length unit."""
        return np.concatenate([m.closure_mm(state[a:b]) for m, a, b in self.parts])


def _concatenate(parts: list[InterfacePoints]) -> InterfacePoints:
    if len(parts) == 1:
        return parts[0]
    block = np.concatenate([p.block + k for k, p in enumerate(parts)])
    return InterfacePoints(sp.vstack([p.B for p in parts]).tocsr(), np.concatenate([p.weights for p in parts]),
                           np.concatenate([p.x for p in parts]), np.concatenate([p.frames for p in parts]),
                           np.concatenate([p.element for p in parts]), block,
                           np.concatenate([p.nodes for p in parts]), parts[0].rule)


def pressure_forces(points, face_element, face_cells, pressure) -> np.ndarray:
    """Consistent nodal forces [force] of pressures ``pressure`` (n_faces,) [stress] on faces
    (node lists in ``face_element`` order, ∂x/∂u × ∂x/∂v outward): f_a = −p ∫ N_a n dA."""
    rule = assembly.default_rule(face_element)
    x = np.asarray(points)[face_cells]
    T = np.einsum("qad,cai->cqdi", face_element.shape_gradients(rule.points), x)
    n_dA = np.cross(T[:, :, 0], T[:, :, 1])
    f = -np.einsum("qa,cqi,q,c->cai", face_element.shape(rule.points), n_dA, rule.weights, np.asarray(pressure))
    return np.bincount(assembly.cell_dofs(face_cells).ravel(), weights=f.ravel(), minlength=3 * len(points))


@dataclass(frozen=True, eq=False)
class DeckProblem:
    """A deck on the engine: mesh, bulk stiffness K, interface points, their laws (one range of
    points per contact pair), per interaction its law, E* and point range; per step the fixed
    dofs with their values (dof → value) and the load vector."""

    dm: DeckMesh
    laws: LawFile
    stiffness: sp.csr_matrix
    points: InterfacePoints
    materials: InterfaceLaws
    interaction_of_point: np.ndarray
    E_star: dict
    supports: tuple
    loads: tuple

    @property
    def mesh(self) -> Mesh:
        return self.dm.mesh


def surface_material(deck, surface: str):
    """The *MATERIAL (``deck.materials`` entry) of the elements under a contact surface, or None
    where its faces lie on several materials (E* of eq. (42) is then the law file's to give)."""
    names = {deck.element_material.get(eid) for eid, _ in deck.surfaces.get(surface, ())}
    return deck.materials[names.pop()] if len(names) == 1 and None not in names else None


def _body_modulus(deck, surface: str, where: str):
    m = surface_material(deck, surface)
    if m is None:
        mats = sorted({str(deck.element_material.get(eid)) for eid, _ in deck.surfaces[surface]})
        raise DeckError(where, f"surface {surface} lies on several materials ({', '.join(mats)}): give E_star "
                               "in the law file")
    return m.E, m.nu


def _pair_poisson(deck, pair):
    """ν of Mindlin's ratio for the pair's two bodies (laws.mindlin_poisson), None where a
    surface lies on several materials."""
    a, b = surface_material(deck, pair.slave), surface_material(deck, pair.master)
    return None if a is None or b is None else mindlin_poisson(a.E, a.nu, b.E, b.nu)


def pair_modulus(deck, laws: LawFile, pair) -> tuple[float, float | None]:
    """(E*, ν) of a contact pair: E* from its interaction's law or, if it gives none, eq. (42) of
    the two bodies' *ELASTIC; ν for Mindlin's ratio (None where a surface lies on several
    materials)."""
    from ..asperity import effective_modulus

    law = laws.interactions[pair.interaction]
    if law.E_star is not None:
        E_star = law.E_star
    else:
        E_star = effective_modulus(*_body_modulus(deck, pair.slave, pair.where),
                                   *_body_modulus(deck, pair.master, pair.where))  # eq. (42)
    return E_star, _pair_poisson(deck, pair)


def _interactions(dm: DeckMesh, laws: LawFile):
    deck = dm.deck
    missing = sorted(set(deck.interactions) - set(laws.interactions))
    used = {p.interaction for p in deck.contact_pairs}
    for name in missing:
        if name in used:
            raise DeckError(deck.interactions[name], f"interaction {name} has no law in the law file "
                                                     f"(it gives {', '.join(sorted(laws.interactions))})")
    points, parts, owner, E = [], [], [], {}
    start = 0
    for k, pair in enumerate(deck.contact_pairs):
        law = laws.interactions[pair.interaction]
        block = dm.mesh.interfaces[k]
        one = Mesh(dm.mesh.points, dm.mesh.blocks, {}, {}, (block,), "pair")
        try:
            # nodal (Lobatto) points on quadrilateral faces; on the 6+6 triangles the nodal rule has
            # zero weight at the corners (docs/fe.md, "Tetrahedra"): Dunavant's 6 Gauss points there
            rule = "gauss" if block.element.face.domain == "simplex" else "lobatto"
            pts = interface_points(one, rule, law.lay_direction)
        except ValueError as exc:  # the law's axis 1 is the lay projected on the faces: it must have one
            if "lay direction" not in str(exc):
                raise
            raise LawError(f"{laws.where}: interactions.{pair.interaction}.lay_direction: "
                           f"{describe(list(law.lay_direction))} is normal to a face of the contact pair "
                           f"{pair.slave}, {pair.master} ({pair.where}): give a direction along the faces "
                           "(the lay, the moments' x axis)") from None
        E_star, nu = pair_modulus(deck, laws, pair)  # nu: for kt_over_kn: mindlin
        key = (pair.interaction, E_star, nu)
        if key not in E:
            E[key] = law.material(laws.length_unit, E_star, nu)
        parts.append((E[key], start, start + pts.n_points))
        owner += [pair.interaction] * pts.n_points
        points.append(pts)
        start += pts.n_points
    E_star = {name: e for name, e, _ in E}
    return _concatenate(points), InterfaceLaws(tuple(parts)), np.array(owner), E_star


def _supports(dm: DeckMesh, boundary: dict, where: dict) -> dict[int, float]:
    """{engine dof: value} of a step's *BOUNDARY state, new points inheriting (module docstring)."""
    deck, out = dm.deck, {}
    ids = np.array(sorted({n for n, _ in boundary}), dtype=np.int64)
    engine = dict(zip(ids.tolist(), dm.engine_index(ids).tolist()))
    for (n, dof), value in boundary.items():
        if engine[n] >= 0:
            out[3 * engine[n] + dof - 1] = value
        elif n in dm.replaced:
            corners = [p for _, p in dm.parents if len(p) == 3 and n in p]  # its edge
            ok = all(boundary.get((c, dof)) == value for p in corners for c in p)
            if not ok:
                raise DeckError(where.get(("boundary", n, dof), deck.path),
                                f"node {n} is a mid-edge node that the 28-node elements replace; a support there "
                                "needs the same support on the edge's corner nodes (or use --elements quadratic)")
    for point, parent in dm.parents:
        for dof in (1, 2, 3):
            values = {boundary.get((p, dof)) for p in parent}
            if len(values) == 1 and None not in values:
                out[3 * point + dof - 1] = values.pop()
    return out


def _load_vector(dm: DeckMesh, cload: dict, dload: dict, where: dict) -> np.ndarray:
    deck, mesh = dm.deck, dm.mesh
    F = np.zeros(3 * mesh.n_nodes)
    ids = np.array(sorted({n for n, _ in cload}), dtype=np.int64)
    engine = dict(zip(ids.tolist(), dm.engine_index(ids).tolist()))
    for (n, dof), value in cload.items():
        if engine[n] < 0:
            why = ("a mid-edge node that the 28-node elements replace (load a corner node, or use --elements "
                   "quadratic)" if n in dm.replaced else "not a node of any element")
            raise DeckError(where.get(("cload", n, dof), deck.path), f"*CLOAD on node {n}: {why}")
        F[3 * engine[n] + dof - 1] += value
    groups = {}
    for (eid, face), p in dload.items():
        b, c, r = dm.cells[eid]
        block = mesh.blocks[b]
        face_element, idx = face_of(block.element, r, face)
        groups.setdefault(face_element.name, (face_element, [], []))
        groups[face_element.name][1].append(block.cells[c][list(idx)])
        groups[face_element.name][2].append(p)
    for face_element, cells, p in groups.values():
        F += pressure_forces(mesh.points, face_element, np.array(cells, dtype=np.int64), np.array(p))
    return F


def deck_problem(dm: DeckMesh, laws: LawFile) -> DeckProblem:
    """Assemble the problem of a deck mesh with its laws (module docstring)."""
    deck, mesh = dm.deck, dm.mesh
    D = [assembly.isotropic_elasticity(deck.materials[m].E, deck.materials[m].nu) for m in dm.materials]
    K = assembly.stiffness(mesh.points, [(b.element, b.cells) for b in mesh.blocks], D)
    points, materials, owner, E_star = _interactions(dm, laws)
    supports = tuple(_supports(dm, step.boundary, deck.where) for step in deck.steps)
    loads = tuple(_load_vector(dm, step.cload, step.dload, deck.where) for step in deck.steps)
    on_interface = set(points.dofs.tolist())
    for step, sup in zip(deck.steps, supports):
        moving = [d for d, v in sup.items() if v != 0.0 and d in on_interface]
        if moving:
            raise DeckError(step.where, f"step {step.index}: a prescribed non-zero displacement on a contact node "
                                        f"(point {moving[0] // 3}) is not supported; prescribe it away from the "
                                        "interface")
    if not supports[0] and not any(supports):
        raise DeckError(deck.path, "no *BOUNDARY: the bodies are free to move as rigid bodies")
    return DeckProblem(dm, laws, K, points, materials, owner, E_star, supports, loads)
