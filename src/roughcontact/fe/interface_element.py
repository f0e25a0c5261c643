"""Zero-thickness interface elements (Buczkowski & Kleiber 2009, Figs 12 and 17) as data.

An interface element is two copies of a face element (QUAD9 → 18 nodes, QUAD16 → 32 nodes)
at the same place: nodes 0 … n−1 are side A (the lower body or the rigid base), nodes
n … 2n−1 side B (the upper body), node n + i facing node i. The relative displacement (jump)
at a point ξ of the face is [u](ξ) = Σ_a N_a(ξ) (u_B,a − u_A,a) (global components); its
components in the local frame (t1, t2, n) — n the unit normal of side A's face pointing from A
to B, t1 the projection of the lay direction (global x by default) onto the face — are the
tangential slips and the normal opening. Integration points: ``"gauss"`` (p + 1)² Gauss–Legendre
points or ``"lobatto"`` (p + 1)² Gauss–Lobatto points, which for these node sets are the nodes
themselves (nodal integration), p the face's polynomial degree.

The 12-node element between conforming 6-node triangles (TRI6, the faces of C3D10; Kratos'
``TriangleInterfaceGeometry3D6Plus6Noded``, code_aster's MEEI_PENTA15 between quadratic
triangles) has ``"gauss"``: Dunavant's 6-point degree-4 rule (positive weights, 18 conditions
on the 18 relative dofs: no spurious zero-energy jump modes) and ``"lobatto"``: the nodal rule of
the TRI6, whose weights are ∫N_a dA = 0 at the corners and A/3 at the mid-sides, i.e. the
3-point mid-edge rule (degree 2, :mod:`.quadrature`). It integrates N_a × a uniform traction
exactly (the consistent loads of a quadratic triangle under uniform pressure are zero at the
corners), so it passes the uniform-pressure patch test, but it samples the law at the mid-side
node pairs only: corner node pairs carry no contact force and the jump modes vanishing at the
mid-sides are held by the bulk alone. "gauss" is the robust choice for tetrahedra.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .element import QUAD9, QUAD16, TRI6, Element
from .quadrature import Rule, simplex_rule, tensor_rule
from ..limits import describe

__all__ = ["InterfaceElement", "INTERFACE12", "INTERFACE18", "INTERFACE32", "INTERFACES", "face_frame"]


@dataclass(frozen=True, eq=False)
class InterfaceElement:
    """Two faces of ``face`` (side A nodes first, then side B in the same order)."""

    name: str
    face: Element

    @property
    def n_nodes(self) -> int:
        return 2 * self.face.n_nodes

    @property
    def nodes(self) -> np.ndarray:
        """Reference nodes (2n, 2): side A, then side B (the same positions)."""
        return np.vstack([self.face.nodes, self.face.nodes])

    def rule(self, kind: str) -> Rule:
        """The interface's integration rule: (p + 1)² points of ``kind`` ("gauss" | "lobatto");
        on a triangle the 6-point Gauss rule or the 3 mid-side nodes (module docstring)."""
        if self.face.domain == "simplex":
            names = {"gauss": "tri6", "lobatto": "tri_midedge"}
            if kind not in names:
                raise ValueError(f"rule kind must be one of {sorted(names)}, got {describe(kind)}")
            return simplex_rule(names[kind])
        return tensor_rule(kind, self.face.gauss_counts)


INTERFACE18 = InterfaceElement("interface18", QUAD9)
INTERFACE32 = InterfaceElement("interface32", QUAD16)
INTERFACE12 = InterfaceElement("interface12", TRI6)
INTERFACES = {e.name: e for e in (INTERFACE12, INTERFACE18, INTERFACE32)}


def face_frame(face: Element, x_face: np.ndarray, xi: np.ndarray, lay=(1.0, 0.0, 0.0)):
    """Local frames of faces at reference points.

    face    the face element (QUAD9, QUAD16, QUAD8).
    x_face  (n_cells, n_face_nodes, 3) node coordinates of side A's faces.
    xi      (n_points, 2) reference points.
    lay     the direction t1 is aligned with (projected onto the tangent plane).

    Returns (R, dA): R (n_cells, n_points, 3, 3) with rows t1, t2, n (n = ∂x/∂ξ × ∂x/∂η
    normalised, t2 = n × t1) and dA (n_cells, n_points) the area element |∂x/∂ξ × ∂x/∂η|.
    """
    G = face.shape_gradients(xi)  # (p, a, 2)
    J = np.einsum("pad,cak->cpdk", G, x_face)  # (c, p, 2, 3): rows ∂x/∂ξ, ∂x/∂η
    cross = np.cross(J[..., 0, :], J[..., 1, :])
    dA = np.linalg.norm(cross, axis=-1)
    bad = ~(dA > 0.0)  # also catches NaN
    if np.any(bad):
        raise ValueError(f"interface face {int(np.argwhere(bad)[0, 0])}: degenerate (area element {describe(dA[bad][0])})")
    n = cross / dA[..., None]
    lay = np.asarray(lay, dtype=float)
    t1 = lay - np.einsum("cpk,k->cp", n, lay)[..., None] * n
    norm = np.linalg.norm(t1, axis=-1)
    if np.any(norm < 1e-8):
        raise ValueError(f"the lay direction {describe(lay.tolist())} is normal to an interface face")
    t1 /= norm[..., None]
    t2 = np.cross(n, t1)
    return np.stack([t1, t2, n], axis=-2), dA
