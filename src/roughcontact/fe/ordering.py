"""Fill-reducing orderings of the FE stiffness for scipy's SuperLU (:mod:`.solver`).

SuperLU's own orderings (minimum degree of Aᵀ + A, COLAMD) leave a lot of fill on 3D solid
meshes: on the 65k-dof block-on-base deck of ``make bench-fe`` the factor of the bulk had 140 M
non-zeros with MMD_AT_PLUS_A (51 s, 6.7 GB). A nested dissection by the mesh's geometry
(George 1973; recursive coordinate bisection with vertex separators) leaves 95 M (20 s,
2.7 GB) — docs/performance.md, "FE linear solvers". The orderings work on nodes (the three
dofs of a node stay together) and are handed to SuperLU with ``permc_spec="NATURAL"``.

* :func:`nested_dissection` — the nodes in dissection order: recursively, split at a plane
  normal to the widest extent of the current set near its median; the separator is the nodes
  on the upper side with a neighbour below (a vertex separator of the node graph); the plane is
  chosen among the five node layers around the median for the smallest separator (on a mesh of
  quadratic elements a plane through an element face leaves one node layer, a plane through
  mid-side nodes two). Order: lower part, upper part, separator.
* :func:`reverse_cuthill_mckee` — without coordinates: scipy's bandwidth-reducing ordering.
* :func:`dof_order` — a permutation of some dofs of a matrix (e.g. the bulk dofs R ahead of the
  interface dofs, which go last) from either of them.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse import csgraph

__all__ = ["node_graph", "nested_dissection", "reverse_cuthill_mckee", "dof_order"]

#: sets of at most this many nodes are not dissected further
LEAF = 32
#: node layers tried on each side of the median
_CANDIDATES = 2


def node_graph(A: sp.spmatrix, dof_node: np.ndarray) -> sp.csr_matrix:
    """Adjacency (n_nodes × n_nodes, no diagonal) of the nodes ``dof_node[i]`` of the dofs i of
    the square matrix A (two nodes are adjacent when a dof of one couples to a dof of the other)."""
    C = A.tocoo()
    dof_node = np.asarray(dof_node)
    n = int(dof_node.max()) + 1 if dof_node.size else 0
    a, b = dof_node[C.row], dof_node[C.col]
    off = a != b
    G = sp.csr_matrix((np.ones(np.count_nonzero(off), dtype=np.int8), (a[off], b[off])), shape=(n, n))
    G.data[:] = 1  # duplicates were summed
    return G


def nested_dissection(G: sp.csr_matrix, x: np.ndarray, leaf: int = LEAF) -> np.ndarray:
    """The nodes of the graph G (symmetric adjacency) with coordinates x (n, d) in nested
    dissection order (module docstring)."""
    G = sp.csr_matrix(G)
    x = np.asarray(x, dtype=float)
    below = np.zeros(G.shape[0], dtype=bool)
    out: list[np.ndarray] = []
    stack: list[tuple[np.ndarray, bool]] = [(np.arange(G.shape[0]), False)]
    # an explicit stack (no recursion limit): (set, done) pops parts before their separator
    while stack:
        nodes, done = stack.pop()
        if done or nodes.size <= leaf:
            out.append(nodes)
            continue
        parts = _bisect(G, x, nodes, below)
        if parts is None:
            out.append(nodes)
            continue
        low, high, separator = parts
        stack += [(separator, True), (high, False), (low, False)]
    order = np.concatenate(out) if out else np.empty(0, dtype=np.int64)
    return order


def _bisect(G, x, nodes, below):
    """(lower part, upper part, separator) of ``nodes``, or None when they cannot be split."""
    xs = x[nodes]
    axis = int(np.argmax(np.ptp(xs, axis=0)))
    levels = np.unique(xs[:, axis])
    if levels.size < 3:
        return None
    k = int(np.searchsorted(levels, np.median(xs[:, axis])))
    best = None
    for j in range(max(1, k - _CANDIDATES), min(levels.size - 1, k + _CANDIDATES + 1)):
        is_low = xs[:, axis] < levels[j]
        low, high = nodes[is_low], nodes[~is_low]
        below[low] = True
        rows = G[high]
        touches = np.zeros(high.size, dtype=bool)
        has = np.diff(rows.indptr) > 0
        if rows.nnz:
            counts = np.add.reduceat(below[rows.indices].astype(np.int32), rows.indptr[:-1][has])
            touches[has] = counts > 0
        below[low] = False
        if best is None or np.count_nonzero(touches) < best[0]:
            best = (np.count_nonzero(touches), low, high[~touches], high[touches])
    _, low, high, separator = best
    if low.size == 0 or high.size == 0:
        return None
    return low, high, separator


def reverse_cuthill_mckee(G: sp.csr_matrix) -> np.ndarray:
    """The nodes of G in reverse Cuthill–McKee order (scipy.sparse.csgraph)."""
    return np.asarray(csgraph.reverse_cuthill_mckee(sp.csr_matrix(G), symmetric_mode=True), dtype=np.int64)


def dof_order(A: sp.spmatrix, dofs: np.ndarray, dof_node: np.ndarray, coordinates: np.ndarray | None) -> np.ndarray:
    """A fill-reducing permutation of ``dofs`` (indices of A's rows/columns): their nodes
    (``dof_node[dofs]``, indices into ``coordinates``) in nested dissection order with the
    coordinates, else in reverse Cuthill–McKee order, each node's dofs together."""
    dofs = np.asarray(dofs, dtype=np.int64)
    if dofs.size == 0:
        return dofs
    nodes, local = np.unique(np.asarray(dof_node)[dofs], return_inverse=True)
    G = node_graph(A[dofs][:, dofs], local)
    order = (nested_dissection(G, np.asarray(coordinates)[nodes]) if coordinates is not None
             else reverse_cuthill_mckee(G))
    rank = np.empty(nodes.size, dtype=np.int64)
    rank[order] = np.arange(nodes.size)
    return dofs[np.argsort(rank[local], kind="stable")]
