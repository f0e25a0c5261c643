"""A deck and its law file as one CalculiX deck with the interface as user elements
(``roughcontact ccx run``, docs/ccx.md).

The deck is read as ``fe run`` reads it (:func:`roughcontact.fe.deck.read_deck`,
:func:`~roughcontact.fe.deck_run.check_law_file`) and written back block by block, its
``*INCLUDE`` files inlined, with these changes:

* every ``*CONTACT PAIR`` whose interaction the law file names, and that ``*SURFACE INTERACTION``
  with its ``*SURFACE BEHAVIOR`` / ``*FRICTION``, are dropped;
* before the first ``*STEP``, per contact pair k: ``*USER ELEMENT`` (URCQ8: 8 + 8 nodes on the
  faces of C3D20; URCT6: 6 + 6 on the faces of C3D10), the elements ``*ELEMENT, ELSET=RC_PAIRk``
  joining the pair's faces as the engine joins them (:func:`roughcontact.fe.deck_mesh.deck_mesh`:
  side A the master face, ordered so that its normal points to the slave; side B the slave nodes
  facing them), ``*MATERIAL, NAME=RC_PAIRk`` with ``*DEPVAR`` 14 and ``*USER SECTION`` with the
  constants of :func:`section_values` (the face's shape functions at the points of its Gauss
  rule, :mod:`roughcontact.fe.element`; the law, :func:`~roughcontact.interface.fortran_export.law_constants`);
* in every step, before ``*END STEP``: ``*NODE PRINT`` of every ``*NSET`` (U) and ``*EL PRINT``
  of every RC_PAIRk (SDV), which :mod:`.results` reads;
* a ``*STATIC`` step the engine runs in fixed increments (``DIRECT``, or no maximum increment above
  the initial one: :func:`roughcontact.fe.deck_increments.grows`) gets ``DIRECT``, so that ccx
  takes the same increments (it would grow them up to the period). A step whose increments grow
  keeps ccx's own rule (×1.5 after fast convergence, where the engine doubles): friction is
  path-dependent, so such steps differ by the paths (``ccx run --increments N`` fixes both);
* a ``*BOUNDARY`` type of Abaqus (XSYMM, YSYMM, ZSYMM, PINNED, ENCASTRE), which CalculiX 2.20 does
  not read, is written as the dofs it holds (as the engine reads it).

The integration points are the engine's: the engine turns a C3D20 with a contact face into a
HEX21 (a node at the face's centre) and integrates the 9-node face at its nodes, the 3 × 3
Gauss–Lobatto points; ccx keeps the deck's C3D20, whose 8-node face is integrated at the same
points with the same weights (at the corners and mid-sides the jump is the node pair's, as in the
engine; at the centre it is the 8-node face's interpolation, where the engine has a node of its
own). On C3D10 both use Dunavant's 6-point rule.

Constants: CalculiX reads each from the first 20 characters of its field (usersections.f, format
f20.0), too few for the 17 digits of a double; every value is written as two constants
``hi = f"{v:.12e}"`` and ``lo = v − float(hi)`` (exact: Sterbenz), and the element adds them
back (rc_ccx_element.f90 ``value_at``): hi + lo rounds to v itself (|lo rounding| ≤ 1e-13 |lo|).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..fe.deck_syntax import Keyword
from ..fe.element import QUAD8, TRI6, Element
from ..fe.interface_element import InterfaceElement
from ..interface.fortran_export import LawConstants, law_constants

__all__ = ["UserType", "USER_TYPES", "NDEPVAR", "HEADER", "PairElements", "pair_elements", "section_values", "encode",
           "decode", "rewrite"]


@dataclass(frozen=True, eq=False)
class UserType:
    """A user element: its CalculiX type name, the face element of each side and the kind of
    rule its points follow (roughcontact.fe.interface_element.InterfaceElement.rule)."""

    name: str
    face: Element
    rule_kind: str

    def rule(self):
        return InterfaceElement(f"interface{2 * self.face.n_nodes}", self.face).rule(self.rule_kind)

    @property
    def n_points(self) -> int:
        return len(self.rule().weights)


#: the user element per face of the engine's interface (its face element's name): the 8-node face
#: of C3D20 at the 3 x 3 Lobatto points (the engine's points: its 9-node face's nodes), the 6-node
#: face of C3D10 at Dunavant's 6 points (the engine's)
USER_TYPES = {"quad9": UserType("URCQ8", QUAD8, "lobatto"), "tri6": UserType("URCT6", TRI6, "gauss")}
#: state variables per point (rc_ccx_element.f90: law state 1-9, jump 10-12, status 13, ready 14)
NDEPVAR = 14
#: the decoded constants' header, 1-based (rc_ccx_element.f90 H_*)
HEADER = ("version", "n_face", "n_points", "model", "form", "tol", "h_ref", "law_per_deck", "lay_x", "lay_y",
          "lay_z", "a_x", "a_y", "a_z", "n_par", "n_tab")
_VERSION = 1
#: keywords of a *SURFACE INTERACTION (dropped with it)
_INTERACTION_OPTIONS = {"SURFACE BEHAVIOR", "FRICTION", "CONTACT DAMPING", "GAP CONDUCTANCE", "GAP HEAT GENERATION"}
#: at most this many fields on one written line (CalculiX splits a line into 16 fields)
_FIELDS_PER_LINE = 16


@dataclass(frozen=True, eq=False)
class PairElements:
    """The user elements of one contact pair: ``elset`` name, user type, ``ids`` (n,), ``nodes``
    (n, 2 n_face) deck node ids (side A, then side B), the pair's law constants, E*, ν."""

    interaction: str
    elset: str
    user_type: str
    face: str
    ids: np.ndarray
    nodes: np.ndarray
    constants: LawConstants
    E_star: float
    nu: float | None


def pair_elements(dm, laws) -> list[PairElements]:
    """The user elements of every contact pair of a deck mesh (:func:`~roughcontact.fe.deck_mesh.deck_mesh`,
    family "quadratic") with the pair's law (E* as the engine takes it, deck_model.pair_modulus)."""
    from ..fe.deck_model import pair_modulus

    deck = dm.deck
    next_id = int(deck.element_ids.max()) + 1
    out = []
    for k, (pair, block) in enumerate(zip(dm.pairs, dm.mesh.interfaces), start=1):
        user = USER_TYPES[block.element.face.name]
        nf = user.face.n_nodes
        # the first nf nodes of a QUAD9 face are its QUAD8 nodes (fe.element: corners, mid-sides, centre)
        sides = np.hstack([block.side("A")[:, :nf], block.side("B")[:, :nf]])
        if np.any(sides >= len(dm.deck_nodes)):
            raise ValueError(f"contact pair {pair.slave}/{pair.master}: a face node is not a deck node")
        E_star, nu = pair_modulus(deck, laws, pair)
        law = laws.interactions[pair.interaction]
        material = law.material(laws.length_unit, E_star, nu)
        constants = law_constants(material.normal, material.model, law_per_deck=material.length_per_mm,
                                  lay_direction=law.lay_direction, tangential_form=material.tangential_form)
        ids = np.arange(next_id, next_id + len(sides), dtype=np.int64)
        next_id += len(sides)
        out.append(PairElements(pair.interaction, f"RC_PAIR{k}", user.name, block.element.face.name, ids,
                                dm.deck_nodes[sides], constants, E_star, nu))
    return out


def section_values(c: LawConstants, face_name: str) -> list[float]:
    """The decoded *USER SECTION constants of one pair (HEADER, the model's parameters, the
    table's rows, then per integration point: weight, N_a, ∂N_a/∂ξ, ∂N_a/∂η)."""
    user = USER_TYPES[face_name]
    face = user.face
    xi, w = user.rule()
    N, G = face.shape(xi), face.shape_gradients(xi)  # (q, a), (q, a, 2)
    head = [_VERSION, face.n_nodes, len(w), c.model, c.form, c.tol, c.h_ref, c.law_per_deck, *c.lay, *c.stiff,
            c.par.size, c.tab.shape[0]]
    points = [v for q in range(len(w)) for v in (w[q], *N[q], *G[q, :, 0], *G[q, :, 1])]
    return [float(v) for v in (*head, *c.par, *c.tab.ravel(), *points)]


def _short(x: float) -> str:
    text = f"{x:.12e}"
    assert len(text) <= 20
    return text


def encode(values) -> list[str]:
    """Each value as two ≤ 20-character constants (hi, lo) whose sum is the value (module docstring)."""
    out = []
    for v in values:
        v = float(v)
        if not math.isfinite(v):
            raise ValueError(f"a *USER SECTION constant is not finite ({v})")
        hi = _short(v)
        out += [hi, _short(v - float(hi))]
    return out


def decode(texts) -> np.ndarray:
    """The values of :func:`encode`'s constants (as rc_ccx_element.f90 reads them)."""
    x = np.array([float(t) for t in texts])
    return x[0::2] + x[1::2]


def _lines(fields) -> list[str]:
    fields = list(fields)
    chunks = [fields[i:i + _FIELDS_PER_LINE] for i in range(0, len(fields), _FIELDS_PER_LINE)] or [[]]
    return [", ".join(chunk) + ("," if i < len(chunks) - 1 else "") for i, chunk in enumerate(chunks)]


def _ccx_fields(kw: Keyword, fields) -> tuple:
    """A data line as CalculiX 2.20 reads it: a *BOUNDARY type (XSYMM, ENCASTRE, ...; Abaqus'),
    which ccx does not know, as its dofs (fe.deck.BOUNDARY_TYPES, as the engine reads it)."""
    from ..fe.deck import BOUNDARY_TYPES

    if kw.name == "BOUNDARY" and len(fields) == 2 and fields[1].upper() in BOUNDARY_TYPES:
        first, last = BOUNDARY_TYPES[fields[1].upper()]
        return (fields[0], str(first), str(last))
    return tuple(fields)


def _keyword_line(kw: Keyword) -> str:
    params = "".join(f", {name}" if value is None else f", {name}={value}" for name, value in kw.params.items())
    return f"*{kw.name}{params}"


def _pair_lines(p: PairElements) -> list[str]:
    nf = p.nodes.shape[1] // 2
    n_points = USER_TYPES[p.face].n_points
    lines = [f"** contact pair of interaction {p.interaction}: roughcontact interface elements (docs/ccx.md)",
             f"*USER ELEMENT, TYPE={p.user_type}, INTEGRATION POINTS={n_points}, MAXDOF=3, NODES={2 * nf}",
             f"*ELEMENT, TYPE={p.user_type}, ELSET={p.elset}"]
    for eid, row in zip(p.ids.tolist(), p.nodes.tolist()):
        lines += _lines([str(eid), *map(str, row)])
    constants = encode(section_values(p.constants, p.face))
    # *USER MATERIAL makes the step materially nonlinear (CalculiX's iperturb 3, small displacements):
    # without it a *STATIC step is solved once, linearly (linstatic.c), without the elements' state
    lines += [f"*MATERIAL, NAME={p.elset}", "*USER MATERIAL, CONSTANTS=1", "0.", "*DEPVAR", str(NDEPVAR),
              f"*USER SECTION, ELSET={p.elset}, MATERIAL={p.elset}, CONSTANTS={len(constants)}"]
    lines += [", ".join(constants[i:i + 8]) for i in range(0, len(constants), 8)]
    return lines


def _output_lines(nsets, pairs) -> list[str]:
    lines = ["** roughcontact ccx run: the prints it reads (docs/ccx.md)"]
    for name in nsets:
        lines += [f"*NODE PRINT, NSET={name}", "U"]
    for p in pairs:
        lines += [f"*EL PRINT, ELSET={p.elset}", "SDV"]
    return lines


def _static_lines(kw: Keyword, step) -> list[str]:
    """*STATIC as the engine reads it (fe.deck_increments): a step the engine runs in fixed
    increments gets DIRECT (CalculiX would otherwise grow them up to the period)."""
    from ..fe.deck_increments import grows

    if grows(step):
        return [_keyword_line(kw), *(line for d in kw.data for line in _lines(d.fields))]
    params = {k: v for k, v in kw.params.items() if k != "DIRECT"}
    line = _keyword_line(Keyword(kw.name, {**params, "DIRECT": None}, (), kw.where))
    return [line, f"{_short(step.fractions[0] * step.period)}, {_short(step.period)}"]


def rewrite(blocks, pairs: list[PairElements], nsets, header=(), steps=None) -> str:
    """The CalculiX deck (module docstring) of ``blocks`` (:func:`~roughcontact.fe.deck_syntax.read_blocks`);
    ``steps`` (the read deck's, with the command line's incrementation): each *STATIC as the
    engine reads it (:func:`_static_lines`), None: as written."""
    replaced = {p.interaction for p in pairs}
    out = [f"** {line}" for line in header]
    dropping, inserted = False, False
    n_static = 0
    for kw in blocks:
        if kw.name == "SURFACE INTERACTION":
            dropping = (kw.params.get("NAME") or "").strip('"').upper() in replaced
        elif kw.name not in _INTERACTION_OPTIONS:
            dropping = False
        if dropping or (kw.name == "CONTACT PAIR"
                        and (kw.params.get("INTERACTION") or "").strip('"').upper() in replaced):
            continue
        if kw.name == "STEP" and not inserted:
            for p in pairs:
                out += _pair_lines(p)
            inserted = True
        if kw.name == "END STEP":
            out += _output_lines(nsets, pairs)
        if kw.name == "STATIC" and steps is not None:
            out += _static_lines(kw, steps[n_static])
            n_static += 1
            continue
        out.append(_keyword_line(kw))
        for line in kw.data:
            out += _lines(_ccx_fields(kw, line.fields))
    if not inserted:
        raise ValueError("the deck has no *STEP")
    return "\n".join(out) + "\n"
