"""A gmsh ``.msh`` mesh as the mesh part of a CalculiX/Abaqus deck (``roughcontact fe msh2inp``).

The file is read with meshio (any gmsh format meshio reads: 2.2, 4.1, ASCII or binary). gmsh's
physical groups become the deck's sets:

* every volume physical group: its elements in ``*ELEMENT, TYPE=C3D10|C3D20, ELSET=NAME``;
* every physical group of any dimension: ``*NSET, NSET=NAME`` with all the nodes of its elements;
* every surface physical group (quadratic faces: triangle6 or quad8): ``*SURFACE, NAME=NAME`` with
  the element face labels ``EID, Sk`` of the volume elements that own those faces, found by
  matching the face's corner nodes to the corners of every element face (S1-S4 of a C3D10,
  :data:`.element.TET10_FACES`; S1-S6 of a C3D20, :data:`.deck_mesh.FACES`).

Node orders: meshio converts gmsh's orders to VTK's. VTK's quadratic tetra (type 24) is
CalculiX's C3D10 (corners, then mid-edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4; CalculiX manual 6.2.2),
and VTK's quadratic hexahedron (type 25) is CalculiX's C3D20 (corners bottom 1-4 and top 5-8,
mid-edges 1-2, 2-3, 3-4, 4-1, then 5-6, 6-7, 7-8, 8-5, then the vertical 1-5, 2-6, 3-7, 4-8;
CalculiX manual 6.2.1) — the engine's :data:`.element.HEX20_NODES` — so both are written as
read. Node ids are meshio's point index + 1 (the nodes of the volume elements only); element
ids run from 1 in the file's order.

A ``.msh`` has no materials, sections, contact pairs nor steps: the deck ends with a commented
block naming what to add (:data:`MISSING`), or with the text of a template the user supplies.
Errors are one line (:class:`MshError`): no volume elements, element types other than tetra10 /
hexahedron20 ("mesh with gmsh -order 2"), a surface face that is no element's face, a face owned
by two elements (bodies that share nodes cannot slide on each other).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .deck_mesh import FACES
from .element import HEX20_NODES, TET10_FACES

__all__ = ["MshError", "msh_deck", "mesh_deck", "MISSING", "CALCULIX_TYPES"]

#: meshio cell type → CalculiX element type (the only volume elements written)
CALCULIX_TYPES = {"tetra10": "C3D10", "hexahedron20": "C3D20"}
#: face types of a surface group, by the volume type whose faces they are
_FACE_TYPES = {"triangle6": "tetra10", "quad8": "hexahedron20"}
_DIM = {"vertex": 0, "line": 1, "line3": 1, "triangle": 2, "triangle6": 2, "quad": 2, "quad8": 2, "quad9": 2,
        "tetra": 3, "tetra10": 3, "hexahedron": 3, "hexahedron20": 3, "hexahedron27": 3, "wedge": 3,
        "wedge15": 3, "wedge18": 3, "pyramid": 3, "pyramid13": 3, "pyramid14": 3}
#: the corners of every face: S1-S4 of a C3D10 (TET10_FACES) and S1-S6 of a C3D20, the corners of
#: HEX20 on the face's side of the reference cube (deck_mesh.FACES: axis, side; CalculiX manual:
#: 1-2-3-4, 5-8-7-6, 1-5-6-2, 2-6-7-3, 3-7-8-4, 4-8-5-1); matched as sets of nodes
_FACE_CORNERS = {"tetra10": {s: list(TET10_FACES[s][:3]) for s in TET10_FACES},
                 "hexahedron20": {s: [i for i in range(8) if HEX20_NODES[i, axis] == side]
                                  for s, (axis, side) in FACES.items()}}
_ORDER2 = "mesh with gmsh -order 2 (and Mesh.SecondOrderIncomplete = 1 for hexahedra)"
#: what a converted deck still needs (printed by the command when no template is given)
MISSING = ("the .msh has no materials, sections, contact pairs, boundary conditions nor steps: add *MATERIAL, "
           "*SOLID SECTION (one per ELSET), *SURFACE INTERACTION + *CONTACT PAIR, *BOUNDARY and *STEP "
           "(docs/own-model.md), or pass --template FILE")


class MshError(ValueError):
    """A .msh that cannot become a deck (one line, naming the file)."""


def _name(text: str) -> str:
    """A physical group's name as a deck set name: letters, digits and _ (others become _)."""
    return re.sub(r"[^A-Za-z0-9_]", "_", text.strip()) or "_"


def _lines(ids, per_line: int = 16) -> list[str]:
    ids = [str(int(i)) for i in ids]
    return [", ".join(ids[k:k + per_line]) + ("," if k + per_line < len(ids) else "") for k in range(0, len(ids), per_line)]


def msh_deck(path, template: str | None = None) -> str:
    """The deck text of the gmsh file ``path`` (module docstring); ``template`` is appended in
    place of the commented block of what to add."""
    import meshio.gmsh  # its reader itself: meshio.read exits the process on a file it cannot parse

    path = Path(path)
    try:
        mesh = meshio.gmsh.read(str(path))
    except OSError as exc:
        raise MshError(f"{path}: cannot read it ({exc.strerror or exc})") from None
    except Exception as exc:  # meshio's ReadError and the parsers' ValueErrors
        raise MshError(f"{path}: not a gmsh .msh file meshio reads ({str(exc).splitlines()[0] if str(exc) else type(exc).__name__})") from None
    return mesh_deck(mesh, str(path), template)


def _groups(mesh, source: str) -> dict[tuple[int, int], str]:
    """{(dim, tag): set name} of the physical groups; unnamed ones are PHYSICAL<dim>D<tag>."""
    names = {}
    for name, data in (mesh.field_data or {}).items():
        tag, dim = int(data[0]), int(data[1])
        names[(dim, tag)] = _name(name)
    if "gmsh:physical" not in mesh.cell_data:
        raise MshError(f"{source}: no physical groups (define Physical Volume/Surface in gmsh: only their elements are read)")
    for block, tags in zip(mesh.cells, mesh.cell_data["gmsh:physical"]):
        dim = _DIM.get(block.type)
        for tag in np.unique(tags):
            names.setdefault((dim, int(tag)), f"PHYSICAL{dim}D{int(tag)}")
    seen = {}
    for key, name in names.items():
        if name.upper() in seen and seen[name.upper()][0] == key[0]:
            raise MshError(f"{source}: two physical groups of dimension {key[0]} are both named {name} in the deck "
                           "(names are case-insensitive; only letters, digits and _ are kept)")
        seen[name.upper()] = key
    return names


def mesh_deck(mesh, source: str = "the mesh", template: str | None = None) -> str:
    """The deck text of a meshio mesh read from a gmsh file (``cell_data["gmsh:physical"]`` and
    ``field_data`` {name: [tag, dim]}); ``source`` names it in errors."""
    for block in mesh.cells:
        if block.type not in _DIM:
            raise MshError(f"{source}: element type {block.type} is not read; {_ORDER2}")
    volumes = [k for k, b in enumerate(mesh.cells) if _DIM[b.type] == 3 and len(b.data)]
    if not volumes:
        raise MshError(f"{source}: no volume elements (a Physical Volume for every body); {_ORDER2}")
    for k in volumes:
        if mesh.cells[k].type not in CALCULIX_TYPES:
            raise MshError(f"{source}: {len(mesh.cells[k].data)} {mesh.cells[k].type} elements; only tetra10 (C3D10) and "
                           f"hexahedron20 (C3D20) are read: {_ORDER2}")
    names = _groups(mesh, source)
    tags = mesh.cell_data["gmsh:physical"]

    out = ["*HEADING", f"from {source} (roughcontact fe msh2inp)"]
    used = np.unique(np.concatenate([mesh.cells[k].data.ravel() for k in volumes]))
    out.append("*NODE")
    out += [f"{i + 1}, {x!r}, {y!r}, {z!r}" for i, (x, y, z) in zip(used.tolist(), np.asarray(mesh.points, float)[used, :3].tolist())]

    # elements, one *ELEMENT block per (type, volume group); the owners of every face by corners
    owners: dict[frozenset, list[tuple[int, int, str]]] = {}
    eid = 0
    for k in volumes:
        block, ctype = mesh.cells[k], mesh.cells[k].type
        ids = eid + 1 + np.arange(len(block.data))
        eid += len(block.data)
        for tag in np.unique(tags[k]):
            sel = np.flatnonzero(tags[k] == tag)
            out.append(f"*ELEMENT, TYPE={CALCULIX_TYPES[ctype]}, ELSET={names[(3, int(tag))]}")
            for e, cell in zip(ids[sel].tolist(), block.data[sel].tolist()):
                out += _lines([e] + [n + 1 for n in cell])
        for s, corners in _FACE_CORNERS[ctype].items():
            for e, cell in zip(ids.tolist(), block.data[:, corners].tolist()):
                owners.setdefault(frozenset(cell), []).append((e, s, ctype))

    on_volume = np.zeros(len(mesh.points), bool)
    on_volume[used] = True
    for (dim, tag), name in sorted(names.items()):
        blocks = [(b, t == tag) for b, t in zip(mesh.cells, tags) if _DIM[b.type] == dim and np.any(t == tag)]
        if not blocks:
            continue
        nodes = np.unique(np.concatenate([b.data[sel].ravel() for b, sel in blocks]))
        if not np.all(on_volume[nodes]):
            raise MshError(f"{source}: physical group {name}: node {int(nodes[~on_volume[nodes]][0]) + 1} is on no volume element")
        out += [f"*NSET, NSET={name}", *_lines(nodes + 1)]
        if dim == 2:
            out += [f"*SURFACE, NAME={name}", *_surface(source, name, blocks, owners)]

    if template is None:
        out += ["**", "** add *MATERIAL, *SOLID SECTION, *CONTACT PAIR, *STEP here", "** " + MISSING,
                "** element sets: " + ", ".join(n for (d, _), n in sorted(names.items()) if d == 3),
                "** surfaces: " + (", ".join(n for (d, _), n in sorted(names.items()) if d == 2) or "none")]
    else:
        out += [template.rstrip("\n")]
    return "\n".join(out) + "\n"


def _surface(source: str, name: str, blocks, owners) -> list[str]:
    """``EID, Sk`` lines of a surface group's faces (matched by their corner nodes)."""
    lines = []
    for block, sel in blocks:
        if block.type not in _FACE_TYPES:
            raise MshError(f"{source}: surface group {name} has {block.type} faces; only triangle6 and quad8 are "
                           f"matched: {_ORDER2}")
        n_corners = 3 if block.type == "triangle6" else 4
        for face in block.data[sel]:
            found = owners.get(frozenset(face[:n_corners].tolist()), [])
            nodes = ", ".join(str(int(n) + 1) for n in face[:n_corners])
            if not found:
                raise MshError(f"{source}: surface group {name}: the face with corner nodes {nodes} is no face of a "
                               "volume element")
            if len(found) > 1:
                raise MshError(f"{source}: surface group {name}: the face with corner nodes {nodes} is shared by elements "
                               f"{found[0][0]} and {found[1][0]} (bodies in contact need their own nodes on the contact "
                               "faces: mesh them as separate volumes, not fragments)")
            lines.append(f"{found[0][0]}, S{found[0][1]}")
    return lines
