"""Vectorised assembly for 3D isotropic linear elasticity (scikit-fem style).

Every quantity is computed for all cells of a block at once (numpy einsum over the axes
cell c, quadrature point p, local node a, component i); there is no Python loop over elements.
A *block* is a pair ``(element, cells)``: an :class:`~roughcontact.fe.element.Element` and a
(n_cells, element.n_nodes) integer array of global node indices in the element's node order.

Conventions
-----------
* Units are consistent, the engine uses mm and N/mm²: coordinates and displacements in mm,
  E, stresses and tractions in N/mm², nodal forces in N, stiffness in N/mm.
* Degrees of freedom: global dof ``3 * node + component`` (component 0, 1, 2 = x, y, z).
* Voigt order of strains and stresses: xx, yy, zz, yz, xz, xy (:data:`VOIGT`), with
  engineering shear strains γ_yz = 2ε_yz etc., so that σ = D ε and the energy density is ½ εᵀDε.
* Default quadrature: Gauss–Legendre with degree + 1 points per direction of the element
  (3×3×3 for HEX20/HEX21, 4×4×3 for HEX28, 3×3 for QUAD8/QUAD9, 4×4 for QUAD16), which
  integrates the stiffness of an affine (parallelepiped) cell exactly.
"""

from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
from scipy import sparse
from threadpoolctl import threadpool_limits

from .element import Element
from . import quadrature
from .quadrature import Rule, tensor_rule

__all__ = [
    "VOIGT", "isotropic_elasticity", "default_rule", "block_geometry", "strain_matrix",
    "element_stiffness", "cell_dofs", "stiffness", "surface_traction", "face_area", "strain_stress",
]

#: Voigt order of strain and stress components (shear strains are engineering strains)
VOIGT = ("xx", "yy", "zz", "yz", "xz", "xy")

#: _STRAIN[s, i, k]: Voigt strain s = Σ_ik _STRAIN[s, i, k] ∂u_i/∂x_k
_STRAIN = np.zeros((6, 3, 3))
for _s, (_i, _k) in enumerate([(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]):
    _STRAIN[_s, _i, _k] = _STRAIN[_s, _k, _i] = 1.0

Block = tuple[Element, np.ndarray]
Traction = np.ndarray | Sequence[float] | Callable[[np.ndarray], np.ndarray]


def isotropic_elasticity(E: float, nu: float) -> np.ndarray:
    """6×6 Voigt elasticity matrix D (order :data:`VOIGT`) of an isotropic material with Young's
    modulus E > 0 [N/mm²] and Poisson's ratio −1 < ν < 0.5: σ = D ε, D in N/mm²."""
    if not (np.isfinite(E) and E > 0.0):
        raise ValueError(f"Young's modulus must be positive and finite, got E = {E}")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"Poisson's ratio must satisfy -1 < nu < 0.5, got nu = {nu}")
    lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    mu = E / (2.0 * (1.0 + nu))
    D = np.diag([2.0 * mu] * 3 + [mu] * 3)
    D[:3, :3] += lam
    return D


def default_rule(element: Element) -> Rule:
    """The element's rule (quadrature.element_rule): Gauss–Legendre with degree + 1 points per
    direction on the cube — exact for the stiffness (products of gradients) of affine cells and for
    N_a × (a traction linear in the face coordinates) on parallelogram faces — and the simplex
    rules of the same exactness on tetrahedra and triangles."""
    return quadrature.element_rule(element)


def _jacobian_checked(J: np.ndarray) -> np.ndarray:
    """det J (c, p) of Jacobians (c, p, d, d); ValueError naming the first cell with det J ≤ 0."""
    det = np.linalg.det(J)
    bad = np.flatnonzero(~np.all(det > 0.0, axis=1))  # `not > 0` also catches NaN
    if bad.size:
        c = int(bad[0])
        raise ValueError(f"cell {c}: det J = {np.nanmin(det[c]):.3g} <= 0 at a quadrature point "
                         f"(inverted or degenerate element; {bad.size} such cells)")
    return det


def _gradients(element: Element, x_cells: np.ndarray, xi: np.ndarray):
    """Physical shape-function gradients (c, p, n, 3) [1/mm] and det J (c, p) [mm³ per unit
    reference volume] at reference points xi (p, 3) of cells with node coordinates x_cells."""
    x_cells = np.asarray(x_cells, dtype=float)
    if element.dim != 3 or x_cells.ndim != 3 or x_cells.shape[1:] != (element.n_nodes, 3):
        raise ValueError(f"{element.name}: expected node coordinates (n_cells, {element.n_nodes}, 3), "
                         f"got {x_cells.shape}")
    dN = element.shape_gradients(xi)                      # (p, n, 3): ∂N_a/∂ξ_k
    J = np.einsum("pak,cai->cpik", dN, x_cells)           # J_ik = ∂x_i/∂ξ_k
    det = _jacobian_checked(J)
    G = np.einsum("pak,cpki->cpai", dN, np.linalg.inv(J))  # ∂N_a/∂x_i = ∂N_a/∂ξ_k ∂ξ_k/∂x_i
    return G, det


def block_geometry(element: Element, x_cells: np.ndarray, rule: Rule | None = None):
    """Geometry of a block at the points of ``rule`` (default :func:`default_rule`).

    x_cells  (n_cells, n_nodes, 3) node coordinates [mm].
    Returns (G, dV): G (n_cells, n_points, n_nodes, 3) the shape-function gradients ∂N_a/∂x_i
    [1/mm], dV (n_cells, n_points) det J × weight [mm³] (dV.sum(1) are the cell volumes).
    Raises ValueError naming the cell if det J ≤ 0 at any point (inverted or degenerate cell).
    """
    rule = default_rule(element) if rule is None else rule
    G, det = _gradients(element, x_cells, rule.points)
    return G, det * rule.weights


#: cells per chunk in element_stiffness (B of a hex20 chunk: 64 × 27 × 6 × 60 floats, 5 MB)
_CHUNK = 64
#: the non-zeros of _STRAIN as (Voigt s, component i, derivative k)
_STRAIN_NONZERO = tuple(zip(*np.nonzero(_STRAIN)))


def strain_matrix(G: np.ndarray) -> np.ndarray:
    """Strain-displacement matrices B (..., 6, 3n) [1/mm] from gradients G (..., n, 3): ε = B u_e
    with the cell's dofs ordered (node a, component i) → 3a + i (B_{s,3a+i} = Σ_k _STRAIN[s,i,k]
    ∂N_a/∂x_k, filled at the nine non-zeros of _STRAIN; the dense einsum did 9× the work)."""
    B = np.zeros(G.shape[:-2] + (6, G.shape[-2], 3))
    for s, i, k in _STRAIN_NONZERO:
        B[..., s, :, i] = G[..., k]
    return B.reshape(*B.shape[:-2], 3 * G.shape[-2])


def element_stiffness(element: Element, x_cells: np.ndarray, D: np.ndarray,
                      rule: Rule | None = None) -> np.ndarray:
    """Element stiffness matrices (n_cells, 3n, 3n) [N/mm]: K_e = Σ_points Bᵀ D B dV. Cells
    are taken in chunks of _CHUNK (the temporaries B, D B stay a few MB and are reused)."""
    D = _material(D)
    x_cells = np.asarray(x_cells, dtype=float)
    rule = default_rule(element) if rule is None else rule
    m = 3 * element.n_nodes
    K = np.empty((x_cells.shape[0] if x_cells.ndim == 3 else 0, m, m))
    # one BLAS thread: the products are small, and a second thread costs far more than it
    # gains (10x more CPU time measured on a loaded 2-core machine)
    with threadpool_limits(limits=1, user_api="blas"):
        for c0 in range(0, max(K.shape[0], 1), _CHUNK):
            K[c0:c0 + _CHUNK] = _stiffness_chunk(element, x_cells[c0:c0 + _CHUNK], D, rule)
    return K


def _stiffness_chunk(element, x_cells, D, rule):
    G, dV = block_geometry(element, x_cells, rule)
    B = strain_matrix(G)                                          # (c, p, 6, m)
    c, p, m = B.shape[0], B.shape[1], B.shape[-1]
    # D B for all cells and points as one matrix product (6 × 6)(6 × c p m), then × dV
    DB = (D @ B.transpose(2, 0, 1, 3).reshape(6, -1)).reshape(6, c, p, m).transpose(1, 2, 0, 3)
    DB = DB * dV[:, :, None, None]
    # Σ_p,s B_psa (D B dV)_psb as one batched matrix product (BLAS) per cell
    K = np.matmul(B.reshape(c, -1, m).transpose(0, 2, 1), DB.reshape(c, -1, m))
    # B^T D B is symmetric in exact arithmetic; symmetrise so round-off does not break it
    return 0.5 * (K + K.transpose(0, 2, 1))


def cell_dofs(cells: np.ndarray) -> np.ndarray:
    """Global dofs (n_cells, 3n) of cells (n_cells, n): 3 * node + component, node-major."""
    cells = np.asarray(cells)
    return (3 * cells[:, :, None] + np.arange(3)).reshape(cells.shape[0], -1)


def _material(D) -> np.ndarray:
    D = np.asarray(D, dtype=float)
    if D.shape != (6, 6):
        raise ValueError(f"the elasticity matrix D must be 6x6 (Voigt), got shape {D.shape}")
    return D


def _cells(element: Element, cells, n_points: int) -> np.ndarray:
    """Validated (n_cells, element.n_nodes) integer cell array."""
    cells = np.asarray(cells)
    if cells.ndim != 2 or cells.shape[1] != element.n_nodes or not np.issubdtype(cells.dtype, np.integer):
        raise ValueError(f"{element.name}: cells must be an integer array (n_cells, {element.n_nodes}), "
                         f"got {cells.dtype} {cells.shape}")
    if cells.size and (cells.min() < 0 or cells.max() >= n_points):
        raise ValueError(f"{element.name}: node indices must lie in [0, {n_points}), "
                         f"got [{cells.min()}, {cells.max()}]")
    return cells


def _points(points) -> np.ndarray:
    points = np.asarray(points, dtype=float)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"points must be (n_nodes, 3) coordinates, got shape {points.shape}")
    return points


def _per_block(value, n_blocks: int, single: Callable[[object], bool], name: str) -> list:
    """``value`` repeated for every block if ``single(value)``, else a sequence of n_blocks."""
    if single(value):
        return [value] * n_blocks
    value = list(value)
    if len(value) != n_blocks:
        raise ValueError(f"{name}: expected one per block ({n_blocks}), got {len(value)}")
    return value


def stiffness(points, blocks: Sequence[Block], D, rule: Rule | Sequence[Rule | None] | None = None
              ) -> sparse.csr_matrix:
    """Global stiffness matrix (3N, 3N) [N/mm], dof 3 * node + component.

    points  (N, 3) node coordinates [mm].
    blocks  sequence of (element, cells) pairs, cells (n_cells, element.n_nodes) global node indices.
    D       one 6×6 Voigt elasticity matrix [N/mm²] for all blocks, or one per block (materials).
    rule    None (each block's :func:`default_rule`), one Rule for every block, or one per block.

    The COO triplets of all blocks are concatenated and duplicates summed by the CSR conversion.
    Memory: ~24 (3n)² bytes of triplets per cell, plus a block's B matrices (n_points·18n floats
    per cell); split a very large block into several blocks (same element, same D) to bound the
    latter.
    """
    points = _points(points)
    blocks = list(blocks)
    Ds = _per_block(D, len(blocks), lambda v: np.ndim(v) == 2, "D")
    rules = _per_block(rule, len(blocks), lambda v: v is None or isinstance(v, Rule), "rule")
    rows, cols, vals = [], [], []
    for b, ((element, cells), Db, rb) in enumerate(zip(blocks, Ds, rules)):
        cells = _cells(element, cells, len(points))
        try:
            Ke = element_stiffness(element, points[cells], Db, rb)
        except ValueError as err:
            raise ValueError(f"block {b} ({element.name}): {err}") from None
        dofs = cell_dofs(cells)
        rows.append(np.broadcast_to(dofs[:, :, None], Ke.shape).ravel())
        cols.append(np.broadcast_to(dofs[:, None, :], Ke.shape).ravel())
        vals.append(Ke.ravel())
    n = 3 * len(points)
    cat = (lambda parts, dtype: np.concatenate(parts) if parts else np.empty(0, dtype))
    K = sparse.coo_matrix((cat(vals, float), (cat(rows, np.int64), cat(cols, np.int64))), shape=(n, n))
    return K.tocsr()


def _face_geometry(face_element: Element, x_faces: np.ndarray, xi: np.ndarray):
    """Physical points (c, p, 3) [mm] and area elements |∂x/∂ξ × ∂x/∂η| (c, p) [mm² per unit
    reference area] of faces (c, n, 3) at reference points xi (p, 2)."""
    if face_element.dim != 2 or x_faces.ndim != 3 or x_faces.shape[1:] != (face_element.n_nodes, 3):
        raise ValueError(f"{face_element.name}: expected face node coordinates "
                         f"(n_faces, {face_element.n_nodes}, 3), got {x_faces.shape}")
    x = np.einsum("pa,cai->cpi", face_element.shape(xi), x_faces)
    T = np.einsum("pad,cai->cpdi", face_element.shape_gradients(xi), x_faces)  # rows ∂x/∂ξ, ∂x/∂η
    dA = np.linalg.norm(np.cross(T[:, :, 0], T[:, :, 1]), axis=-1)
    bad = np.flatnonzero(~np.all(dA > 0.0, axis=1))
    if bad.size:
        raise ValueError(f"face {int(bad[0])}: zero area element at a quadrature point (degenerate face)")
    return x, dA


def surface_traction(points, face_element: Element, face_cells, traction: Traction,
                     rule: Rule | None = None) -> np.ndarray:
    """Consistent nodal forces f_a = ∫ N_a t dA [N] of a traction t [N/mm², force per area] on faces.

    face_cells  (n_faces, face_element.n_nodes) global node indices in ``face_element``'s order
                (e.g. the QUAD8 faces of hex20 cells).
    traction    a constant vector (3,), or a callable x (..., 3) → t (..., 3) evaluated at the
                physical quadrature points.
    rule        default :func:`default_rule` (face_element): exact for N_a × a constant or linear
                traction on flat faces with affine geometry.
    Returns the global force vector (3N,), dof 3 * node + component.
    """
    points = _points(points)
    face_cells = _cells(face_element, face_cells, len(points))
    rule = default_rule(face_element) if rule is None else rule
    x, dA = _face_geometry(face_element, points[face_cells], rule.points)
    t = traction(x) if callable(traction) else np.asarray(traction, dtype=float)
    t = np.broadcast_to(t, x.shape)
    f = np.einsum("pa,cpi,cp,p->cai", face_element.shape(rule.points), t, dA, rule.weights)
    return np.bincount(cell_dofs(face_cells).ravel(), weights=f.ravel(), minlength=3 * len(points))


def face_area(points, face_element: Element, face_cells, rule: Rule | None = None) -> np.ndarray:
    """Areas (n_faces,) [mm²] of the faces (node lists in ``face_element`` order)."""
    points = _points(points)
    face_cells = _cells(face_element, face_cells, len(points))
    rule = default_rule(face_element) if rule is None else rule
    _, dA = _face_geometry(face_element, points[face_cells], rule.points)
    return dA @ rule.weights


def strain_stress(points, element: Element, cells, u, D, xi):
    """Strains and stresses of a displacement field at reference points of every cell.

    u   displacements [mm], (3N,) (dof 3 * node + component) or (N, 3).
    xi  (n_points, 3) reference points (e.g. ``default_rule(element).points``).
    Returns (strain, stress), each (n_cells, n_points, 6) in Voigt order :data:`VOIGT`;
    strain dimensionless (engineering shear), stress [N/mm²].
    """
    points = _points(points)
    cells = _cells(element, cells, len(points))
    u = np.asarray(u, dtype=float).reshape(len(points), 3)
    G, _ = _gradients(element, points[cells], np.atleast_2d(np.asarray(xi, dtype=float)))
    strain = np.einsum("sik,cpak,cai->cps", _STRAIN, G, u[cells])
    return strain, strain @ _material(D).T
