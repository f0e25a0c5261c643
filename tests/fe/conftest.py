"""Decks of a block on a base for the tests of the deck path (written with fe.deck_writer), and
law files of the issue's schema."""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines, number

#: the Table 1 surface [µm units]
MOMENTS = {"m00": 0.0625, "m20": 8.0e-5, "m02": 8.0e-4, "m40": 1.04e-6, "m04": 1.04e-4, "unit": "um"}


def _block_deck(*, n=2, nz=1, block=(10.0, 10.0, 8.0), base_scale=1.0, base_depth=6.0, symmetry="quarter",
               support="roller", steps=({"pressure": 1.0, "increments": 2},), rotation=None,
               materials=((2.1e5, 0.3), (2.1e5, 0.3)), extra_model=(), contact=("S1", "S2")) -> str:
    """A block (x, y ∈ [0, bx] × [0, by] for symmetry "quarter", centred otherwise) on a base of
    base_scale × its footprint, depth ``base_depth``; C3D20, n × n × nz elements in the block
    (the base has the block's grid under it, extended by whole elements). ``steps``: each a
    pressure on the block top (*DLOAD P2), optional ``cloads`` [(node set, (fx, fy, fz))], the
    increments. ``rotation`` (3 × 3) turns every coordinate and force. Node sets: BLOCKTOPNODES,
    LOADNODE (a top corner), BASEBOTTOM, XSYM, YSYM; surfaces BLOCKBOTTOM (slave), BASETOP (master)."""
    bx, by, bz = block
    if symmetry == "quarter":
        xb, yb = np.linspace(0, bx, n + 1), np.linspace(0, by, n + 1)
        grow = lambda e: np.concatenate([e, e[-1] + np.diff(e)[0] * np.arange(1, int(round((base_scale - 1) * n)) + 1)])  # noqa: E731
        xs, ys = grow(xb), grow(yb)
    else:
        xb, yb = np.linspace(-bx / 2, bx / 2, n + 1), np.linspace(-by / 2, by / 2, n + 1)
        k = int(round((base_scale - 1) * n / 2))
        h = np.diff(xb)[0]
        xs = np.concatenate([xb[0] - h * np.arange(k, 0, -1), xb, xb[-1] + h * np.arange(1, k + 1)])
        ys = np.concatenate([yb[0] - h * np.arange(k, 0, -1), yb, yb[-1] + h * np.arange(1, k + 1)])
    base = box_part(xs, ys, [-base_depth, 0.0])
    top = box_part(xb, yb, np.linspace(0.0, bz, nz + 1), first_node=int(base.node_ids[-1]) + 1,
                   first_element=int(base.element_ids[-1]) + 1)
    if rotation is not None:
        for part in (base, top):
            part.coords[:] = part.coords @ np.asarray(rotation).T
    corner = top.face_nodes["ZMAX"][np.argmax(top.coords[top.face_nodes["ZMAX"] - top.node_ids[0]] @ [1, 2, 0])]
    lines = ["*HEADING", "block on base", *node_lines(base, "BASENODES"), *node_lines(top, "BLOCKNODES"),
             *element_lines(base, "BASE"), *element_lines(top, "BLOCK"),
             *id_lines("*NSET, NSET=BLOCKTOPNODES", top.face_nodes["ZMAX"]), *id_lines("*NSET, NSET=LOADNODE", [corner]),
             *id_lines("*NSET, NSET=BASEBOTTOM", base.face_nodes["ZMIN"]),
             *id_lines("*ELSET, ELSET=BLOCKTOP", top.face_elements["ZMAX"])]
    if symmetry == "quarter":
        lines += id_lines("*NSET, NSET=XSYM", np.concatenate([base.face_nodes["XMIN"], top.face_nodes["XMIN"]]))
        lines += id_lines("*NSET, NSET=YSYM", np.concatenate([base.face_nodes["YMIN"], top.face_nodes["YMIN"]]))
    lines += ["*SURFACE, NAME=BLOCKBOTTOM", *(f"{e}, {contact[0]}" for e in top.face_elements["ZMIN"]),
              "*SURFACE, NAME=BASETOP", *(f"{e}, {contact[1]}" for e in base.face_elements["ZMAX"])]
    for name, (E, nu) in zip(("BASEMAT", "BLOCKMAT"), materials):
        lines += [f"*MATERIAL, NAME={name}", "*ELASTIC", f"{number(E)}, {number(nu)}"]
    lines += ["*SOLID SECTION, ELSET=BASE, MATERIAL=BASEMAT", "*SOLID SECTION, ELSET=BLOCK, MATERIAL=BLOCKMAT",
              "*SURFACE INTERACTION, NAME=ROUGH", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.0e6, 0.",
              "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=SURFACE TO SURFACE", "BLOCKBOTTOM, BASETOP", *extra_model,
              "*BOUNDARY", "BASEBOTTOM, 3, 3" if support == "roller" else "BASEBOTTOM, ENCASTRE"]
    if symmetry == "quarter":
        lines += ["XSYM, XSYMM", "YSYM, YSYMM"]
    for step in steps:
        lines += ["*STEP", "*STATIC", f"{number(1.0 / step['increments'])}, 1.", "*DLOAD",
                  f"BLOCKTOP, P2, {number(step['pressure'])}"]
        for nset, force in step.get("cloads", ()):
            f = np.asarray(force, dtype=float) if rotation is None else np.asarray(rotation) @ force
            lines += ["*CLOAD", *(f"{nset}, {d + 1}, {number(v)}" for d, v in enumerate(f) if v != 0.0)]
        lines += ["*NODE PRINT, NSET=BLOCKTOPNODES", "U", "*END STEP"]
    return "\n".join(lines) + "\n"


def _law_file(path, *, friction="none", lay=(1, 0, 0), seating=1e-3, length_unit="mm", law="elastic", **extra) -> str:
    """A LAW.yaml of the issue's schema for interaction ROUGH; returns its path."""
    body = {"moments": dict(MOMENTS), "lay_direction": list(lay), "law": law, "seating_pressure": seating,
            "friction": friction, **extra}
    path.write_text(yaml.safe_dump({"length_unit": length_unit, "interactions": {"ROUGH": body}}, sort_keys=False))
    return str(path)


@pytest.fixture
def block_deck():
    """block_deck(**options) -> deck text (:func:`_block_deck`)."""
    return _block_deck


@pytest.fixture
def write_deck(tmp_path):
    """write_deck(text, name="model.inp") -> path of the deck in tmp_path."""
    def write(text, name="model.inp"):
        p = tmp_path / name
        p.write_text(text)
        return str(p)
    return write


@pytest.fixture
def law_file(tmp_path):
    """law_file(name="law.yaml", **options) -> path of a law file in tmp_path (:func:`_law_file`)."""
    def write(name="law.yaml", **options):
        return _law_file(tmp_path / name, **options)
    return write
