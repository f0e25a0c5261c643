"""The integration points of the interface elements as one sparse jump operator.

For every interface element and every point ξ_q of its rule ("gauss" or "lobatto",
:meth:`~.interface_element.InterfaceElement.rule`), the local jump

    δ_q = R_q Σ_a N_a(ξ_q) (u_B,a − u_A,a)       [mm]   (slip t1, slip t2, opening n)

is one row-triple of a sparse matrix ``B`` (3·n_points × 3·n_nodes) acting on the global
displacement vector (dof 3·node + component). R_q has rows t1, t2, n of
:func:`~.interface_element.face_frame` at side A's face (n from A to B). With tractions s_q
conjugate to δ_q [N/mm²] and weights w_q dA_q [mm²], the interface forces are Bᵀ (w ⊙ s) [N]
and the tangent Bᵀ diag(w_q D_q) B [N/mm] (:func:`interface_tangent`). Nothing here knows a
contact law: :mod:`.contact` supplies s and D.

Nodal rule. With "lobatto" the points of an element are its nodes; neighbouring elements then
put a point on every shared node, with the same jump (the same node pair) and the same frame
on a flat interface. Such coincident points are merged into one point whose weight is the sum
(the node's tributary area of the consistent Lobatto integration), so that the contact points
are the interface nodes: 9 × 9 = 81 for 4 × 4 quadratic elements, 10 × 10 = 100 for 3 × 3
cubic ones (the paper's counts, section 9.2). A state (friction) per point is then a state per
node pair, exactly as the unmerged points would evolve (they see identical jumps).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .interface_element import face_frame
from .mesh import Mesh

__all__ = ["InterfacePoints", "interface_points", "interface_forces", "interface_tangent"]


@dataclass(frozen=True, eq=False)
class InterfacePoints:
    """All interface integration points of a mesh (every interface block, in block order).

    B : csr (3 n_points, 3 n_nodes) jump operator [–] (rows 3q, 3q + 1, 3q + 2: t1, t2, n).
    weights : (n_points,) w_q dA_q [mm²], the area each point stands for.
    x : (n_points, 3) positions on side A [mm].
    frames : (n_points, 3, 3) rows t1, t2, n.
    element : (n_points,) index of the interface element within its block; block : block index.
    nodes : (n_points,) for a nodal (Lobatto) rule, the side-B node each point sits on; −1 otherwise.
    rule : the rule kind.
    """

    B: sp.csr_matrix
    weights: np.ndarray
    x: np.ndarray
    frames: np.ndarray
    element: np.ndarray
    block: np.ndarray
    nodes: np.ndarray
    rule: str

    @property
    def n_points(self) -> int:
        return int(self.weights.shape[0])

    @property
    def dofs(self) -> np.ndarray:
        """Sorted global dofs the interface touches (both sides)."""
        return np.unique(self.B.indices)

    def jumps(self, u) -> np.ndarray:
        """Local jumps δ (n_points, 3) [mm] of a displacement vector u (3 n_nodes,) [mm]."""
        return (self.B @ np.asarray(u, dtype=float)).reshape(-1, 3)


def interface_points(mesh: Mesh, rule: str = "lobatto", lay=(1.0, 0.0, 0.0)) -> InterfacePoints:
    """The :class:`InterfacePoints` of every interface block of ``mesh`` with the rule
    ``rule`` ("lobatto": nodal, the default; "gauss") and t1 along ``lay`` (global x)."""
    if not mesh.interfaces:
        raise ValueError("the mesh has no interface elements")
    rows, cols, vals = [], [], []
    weights, xs, frames, elements, blocks, nodes = [], [], [], [], [], []
    offset = 0
    for b, block in enumerate(mesh.interfaces):
        face = block.element.face
        xi, w = block.element.rule(rule)
        N = face.shape(xi)  # (p, a)
        N[np.abs(N) < 1e-12] = 0.0  # nodal rules: exact zeros off the node keep B sparse
        A, Bn = block.side("A"), block.side("B")
        R, dA = face_frame(face, mesh.points[A], xi, lay)  # (c, p, 3, 3), (c, p)
        n_cells, n_pts, n_face = A.shape[0], xi.shape[0], face.n_nodes
        # δ_{c,q,i} = Σ_a N_qa Σ_k R_{c,q,i,k} (u_{B_ca,k} − u_{A_ca,k})
        coef = np.einsum("qa,cqik->cqiak", N, R)  # (c, q, 3, a, 3)
        row = offset + (np.arange(n_cells)[:, None] * n_pts + np.arange(n_pts)[None, :])  # (c, q)
        row = 3 * row[:, :, None, None, None] + np.arange(3)[None, None, :, None, None]
        for nodes_of_side, sign in ((Bn, 1.0), (A, -1.0)):
            col = 3 * nodes_of_side[:, None, None, :, None] + np.arange(3)[None, None, None, None, :]
            shape = (n_cells, n_pts, 3, n_face, 3)
            rows.append(np.broadcast_to(row, shape).ravel())
            cols.append(np.broadcast_to(col, shape).ravel())
            vals.append((sign * coef).ravel())
        weights.append((dA * w[None, :]).ravel())
        xs.append(np.einsum("qa,cak->cqk", N, mesh.points[A]).reshape(-1, 3))
        frames.append(R.reshape(-1, 3, 3))
        elements.append(np.repeat(np.arange(n_cells), n_pts))
        blocks.append(np.full(n_cells * n_pts, b))
        nodal = rule == "lobatto" and np.allclose(xi, face.nodes[_nodal_order(face.nodes, xi)])
        nodes.append(Bn[:, _nodal_order(face.nodes, xi)].ravel() if nodal else np.full(n_cells * n_pts, -1))
        offset += n_cells * n_pts
    n = 3 * mesh.n_nodes
    B = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(3 * offset, n))
    B.eliminate_zeros()
    pts = InterfacePoints(B, np.concatenate(weights), np.concatenate(xs), np.concatenate(frames),
                          np.concatenate(elements), np.concatenate(blocks), np.concatenate(nodes), rule)
    return _merge_coincident(pts) if np.all(pts.nodes >= 0) else pts


def _merge_coincident(pts: InterfacePoints) -> InterfacePoints:
    """One point per side-B node (module docstring, "Nodal rule"); left as is where the frames
    of coincident points differ (a kinked interface)."""
    keys, first, inverse = np.unique(pts.nodes, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    if not np.allclose(pts.frames, pts.frames[first][inverse], atol=1e-12):
        return pts
    rows = (3 * first[:, None] + np.arange(3)).ravel()
    return InterfacePoints(pts.B[rows], np.bincount(inverse, weights=pts.weights), pts.x[first],
                           pts.frames[first], pts.element[first], pts.block[first], keys, pts.rule)


def _nodal_order(nodes: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """For each point of xi, the index of the nearest face node (an identity map when the rule
    is nodal; the caller checks that the points coincide)."""
    d = np.linalg.norm(xi[:, None, :] - nodes[None, :, :], axis=-1)
    return np.argmin(d, axis=1)


def interface_forces(points: InterfacePoints, tractions) -> np.ndarray:
    """Nodal forces Bᵀ (w ⊙ s) [N] (3 n_nodes,) of local tractions s (n_points, 3) [N/mm²]
    conjugate to the jumps (t1, t2 slips; normal component tension-positive)."""
    s = np.asarray(tractions, dtype=float) * points.weights[:, None]
    return points.B.T @ s.ravel()


def interface_tangent(points: InterfacePoints, D) -> sp.csr_matrix:
    """Tangent Bᵀ diag(w_q D_q) B [N/mm] (3 n_nodes, 3 n_nodes) of local tangents D
    (n_points, 3, 3) [N/mm³] (∂s/∂δ; unsymmetric with non-associated friction)."""
    D = np.asarray(D, dtype=float) * points.weights[:, None, None]
    n = points.n_points
    blocks = sp.bsr_matrix((D, np.arange(n), np.arange(n + 1)), shape=(3 * n, 3 * n))
    return (points.B.T @ blocks.tocsr() @ points.B).tocsr()
