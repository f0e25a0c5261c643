"""Assembly of 3D linear elasticity: material matrix, stiffness (symmetry, rigid body modes,
energy), patch tests on distorted and mixed (transition-element) meshes, consistent surface
loads, uniaxial tension against the closed form.

The small meshes are generated here: a logical lattice of n_x × n_y × n_z unit cells, each
cell's reference nodes placed by the trilinear map of its 8 lattice corners, coincident nodes
merged; the logical coordinates are then mapped to physical space (a perturbed lattice, an
affine map, or additional random node perturbations). Layer k of the lattice uses the element
type layers[k]; the transition elements' contact faces (local ζ = −1) lie on the bottom z = 0.

Why the patch tests can be asserted exactly (ξ-degrees counted per variable, as a tensor Gauss
rule with n points integrates ξ^a η^b ζ^c exactly for a, b, c ≤ 2n − 1):
* linear field, any isoparametric mesh: u = a + Bx lies in the discrete space (Σ N_a x_a = x),
  and the discrete equilibrium of an unknown node, Σ_e Q_e[∫ ∇N_a dV]·σ = boundary load, holds
  if the quadrature Q_e integrates ∇N_a det J = cof(J)ᵀ ∇_ξ N_a exactly (and the face rule
  N_a dA). HEX20/HEX21 with 3×3×3 points: the map has degree ≤ 2 per variable, the cofactors
  ≤ (4, 3, 3) (ξ row; the others permuted), ∇_ξ N ≤ (1, 2, 2): total ≤ 5, exact on curved cells.
  HEX28 with 4×4×3 points: on a trilinear map (straight edges, distorted corners) ≤ (4, 4, 3),
  exact; on a curved map up to (8, 8, 5) for the contact-face nodes, not exact — but the other
  nodes' functions lie in S2·L1 ⊕ Q1·B (degree ≤ 2 in ξ, η), giving ≤ 7: exact. So curved HEX28
  passes when its contact face is prescribed (Dirichlet test) and fails at quadrature-error
  level when the contact-face nodes are unknowns (test_hex28_curved_..., which also shows that
  5 points in ξ, η restore exactness).
* quadratic field: contained in every space on affine cells only, where the default rule
  integrates the stiffness exactly; so it is tested on (non-uniform, sheared) parallelepipeds.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy import sparse
from scipy.sparse.linalg import spsolve

from roughcontact.fe.assembly import (
    VOIGT, block_geometry, default_rule, element_stiffness, face_area, isotropic_elasticity,
    stiffness, strain_stress, surface_traction,
)
from roughcontact.fe.element import HEX20, HEX21, HEX28, QUAD8, QUAD9, QUAD16
from roughcontact.fe.quadrature import tensor_rule

E, NU = 2.1e5, 0.3  # N/mm², steel-like: the tolerances below are relative, so the scale is free
D = isotropic_elasticity(E, NU)


@pytest.fixture
def rng():
    """A fresh seeded generator per test: results do not depend on which tests run."""
    return np.random.default_rng(2009)

# Patch tests: K_ff of these meshes has condition numbers ~1e2–1e3 (measured), so the solve is
# accurate to ~1e-13 and strains, differences of nodal values over O(1) cells, lose at most
# another digit: the measured worst relative error is 6e-14. 1e-10 leaves a wide margin, while
# the one inexact case (curved HEX28, quadrature error) sits at 1e-4, six orders above.
PATCH = 1e-10


# ------------------------------------------------------------------------------------------
# small structured meshes
# ------------------------------------------------------------------------------------------
def _trilinear(xi: np.ndarray):
    """Trilinear weights (p, 8) of the corners at reference points xi (p, 3), and the corners
    (8, 3) in VTK order."""
    c = np.array(list(itertools.product((-1, 1), repeat=3)))[:, ::-1]  # x fastest
    c = c[[0, 1, 3, 2, 4, 5, 7, 6]]                                     # → counter-clockwise
    return np.prod(1 + xi[:, None, :] * c[None, :, :], axis=2) / 8, c


def logical_mesh(layers, nx: int = 2, ny: int = 2):
    """Mesh of nx × ny × len(layers) unit cells in logical coordinates s ∈ [0, n]³.

    Returns (s, blocks): node coordinates (N, 3) and [(element, cells)] grouped by type."""
    all_nodes, owner = [], []
    for k, element in enumerate(layers):
        W, corners = _trilinear(element.nodes)
        for j, i in itertools.product(range(ny), range(nx)):
            lattice = np.array([i, j, k]) + (corners + 1) / 2           # (8, 3) cell corners
            all_nodes.append(W @ lattice)
            owner.append(element)
    # merge coincident nodes (logical coordinates are O(1) and exact to ~1e-16; 1e-9 rounding
    # finds them) and keep the unrounded coordinates: rounding 1/√5 to 9 digits would distort
    # the cells at the 1e-10 level and spoil the exactness checked below
    stacked = np.vstack(all_nodes)
    _, first, inverse = np.unique(np.round(stacked, 9), axis=0, return_index=True, return_inverse=True)
    s = stacked[first]
    gaps = np.linalg.norm(s[:, None] - s[None], axis=2) + np.eye(len(s))
    assert gaps.min() > 0.05  # distinct nodes are far apart: the merge was unambiguous
    cells = np.split(inverse.reshape(-1), np.cumsum([len(n) for n in all_nodes])[:-1])
    blocks = {}
    for element, c in zip(owner, cells):
        blocks.setdefault(element.name, (element, []))[1].append(c)
    return s, [(el, np.array(c, dtype=np.int64)) for el, c in blocks.values()]


def lattice_map(shape, rng, amplitude: float = 0.2, sizes=(1.0, 1.0, 1.0), keep_planar=False):
    """A piecewise trilinear map of the logical lattice with randomly moved corners; with
    ``keep_planar`` boundary corners move only within their boundary plane(s)."""
    n = np.array(shape)
    grid = np.stack(np.meshgrid(*[np.arange(m + 1.0) for m in n], indexing="ij"), axis=-1)
    move = rng.uniform(-amplitude, amplitude, size=grid.shape)
    if keep_planar:
        on_boundary = (grid == 0) | (grid == n)
        move[on_boundary] = 0.0
    X = (grid + move) * np.asarray(sizes)

    def phys(s):
        cell = np.minimum(np.floor(s).astype(int), n - 1)
        xi = 2 * (s - cell) - 1
        out = np.zeros_like(s)
        for corner in itertools.product((0, 1), repeat=3):
            w = np.prod([(1 + (2 * c - 1) * xi[:, a]) / 2 for a, c in enumerate(corner)], axis=0)
            out += w[:, None] * X[tuple((cell + corner).T)]
        return out

    return phys


def affine_box(shape, spacing, shear):
    """Non-uniform box cells (per-axis spacing) under a global linear map: parallelepipeds."""
    edges = [np.concatenate([[0.0], np.cumsum(h)]) for h in spacing]

    def phys(s):
        x = np.column_stack([np.interp(s[:, a], np.arange(len(e)), e) for a, e in enumerate(edges)])
        return x @ np.asarray(shear).T

    return phys


def boundary(s, shape):
    """Nodes on the outer surface of the logical block."""
    return np.flatnonzero(np.any((np.abs(s) < 1e-9) | (np.abs(s - shape) < 1e-9), axis=1))


def open_bottom(s, shape):
    """Boundary nodes except those inside the bottom face s_z = 0 (its rim stays fixed: a rim
    node's function is non-zero on a lateral face too, which carries no applied traction)."""
    lateral = np.any((np.abs(s[:, :2]) < 1e-9) | (np.abs(s[:, :2] - shape[:2]) < 1e-9), axis=1)
    inside = (np.abs(s[:, 2]) < 1e-9) & ~lateral
    return np.setdiff1d(boundary(s, shape), np.flatnonzero(inside))


def face_cells(blocks, s, zeta: float, height: float):
    """Faces at local ζ = zeta of the cells whose face lies on the logical plane s_z = height,
    as (face element, (n_faces, n_face_nodes) node lists in the face element's order)."""
    out = []
    for element, cells in blocks:
        face = element.face_element if zeta == -1 else QUAD8
        idx = [int(np.flatnonzero(np.all(np.abs(element.nodes - (*p, zeta)) < 1e-12, axis=1))[0])
               for p in face.nodes]
        faces = cells[:, idx]
        faces = faces[np.all(np.abs(s[faces, 2] - height) < 1e-9, axis=1)]
        if len(faces):
            out.append((face, faces))
    assert len(out) == 1  # one face type on a boundary plane in these meshes
    return out[0]


def rigid_modes(x):
    """(3N, 6) rigid-body displacement fields: three translations, three rotations."""
    modes = []
    for k in range(3):
        t = np.zeros_like(x)
        t[:, k] = 1.0
        modes.append(t.ravel())
    for axis in np.eye(3):
        modes.append(np.cross(axis, x - x.mean(axis=0)).ravel())
    return np.column_stack(modes)


def solve(K, f, fixed, u_fixed):
    """K u = f with u[fixed] = u_fixed (dofs); returns u (3N,)."""
    n = K.shape[0]
    free = np.setdiff1d(np.arange(n), fixed)
    u = np.zeros(n)
    u[fixed] = u_fixed
    K = sparse.csr_matrix(K)
    u[free] = spsolve(K[free][:, free].tocsc(), f[free] - K[free][:, fixed] @ u_fixed)
    return u


def node_dofs(nodes, components=(0, 1, 2)):
    return (3 * np.asarray(nodes)[:, None] + np.asarray(components)).ravel()


def voigt_strain(grad_u):
    """Voigt strains (..., 6) from displacement gradients (..., 3, 3), written out here."""
    g = grad_u
    return np.stack([g[..., 0, 0], g[..., 1, 1], g[..., 2, 2], g[..., 1, 2] + g[..., 2, 1],
                     g[..., 0, 2] + g[..., 2, 0], g[..., 0, 1] + g[..., 1, 0]], axis=-1)


def physical_points(x, element, cells, xi):
    return np.einsum("pa,cak->cpk", element.shape(xi), x[cells])


LAYERS = {
    "hex20": (HEX20, HEX20, HEX20),
    "hex21+hex20": (HEX21, HEX20, HEX20),
    "hex28+hex20": (HEX28, HEX20, HEX20),
}


# ------------------------------------------------------------------------------------------
# material
# ------------------------------------------------------------------------------------------
def test_isotropic_elasticity_against_lame_form(rng):
    assert VOIGT == ("xx", "yy", "zz", "yz", "xz", "xy")
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    for _ in range(5):
        g = rng.normal(size=(3, 3))
        eps_t = (g + g.T) / 2
        sig_t = lam * np.trace(eps_t) * np.eye(3) + 2 * mu * eps_t  # tensor form
        sig = D @ voigt_strain(g)
        expected = [sig_t[0, 0], sig_t[1, 1], sig_t[2, 2], sig_t[1, 2], sig_t[0, 2], sig_t[0, 1]]
        assert np.max(np.abs(sig - expected)) < 1e-12 * E * np.abs(g).max()
    # uniaxial stress: the compliance gives 1/E and −ν/E
    C = np.linalg.inv(D)
    assert abs(C[0, 0] * E - 1) < 1e-13 and abs(C[0, 1] * E + NU) < 1e-13
    assert np.array_equal(D, D.T)


@pytest.mark.parametrize("E_, nu", [(0.0, 0.3), (-1.0, 0.3), (np.inf, 0.3), (1.0, 0.5), (1.0, -1.0), (1.0, 0.7)])
def test_isotropic_elasticity_rejects(E_, nu):
    with pytest.raises(ValueError):
        isotropic_elasticity(E_, nu)


# ------------------------------------------------------------------------------------------
# single elements
# ------------------------------------------------------------------------------------------
def _affine_cell(element, rng):
    M = np.eye(3) * [2.0, 1.0, 0.5] + rng.uniform(-0.2, 0.2, (3, 3))  # a parallelepiped
    c = rng.uniform(-1, 1, 3)
    return element.nodes @ M.T + c, 8 * abs(np.linalg.det(M))


@pytest.mark.parametrize("element", [HEX20, HEX21, HEX28], ids=lambda e: e.name)
def test_default_rule(element):
    counts = {"hex20": (3, 3, 3), "hex21": (3, 3, 3), "hex28": (4, 4, 3)}[element.name]
    rule = default_rule(element)
    assert len(rule.weights) == math.prod(counts)
    assert np.array_equal(rule.points, tensor_rule("gauss", counts).points)


@pytest.mark.parametrize("element", [HEX20, HEX21, HEX28], ids=lambda e: e.name)
def test_single_element_rigid_modes_and_energy(element, rng):
    x, volume = _affine_cell(element, rng)
    cells = np.arange(element.n_nodes)[None]
    K = stiffness(x, [(element, cells)], D).toarray()
    assert np.array_equal(K, element_stiffness(element, x[None], D)[0])  # one cell: no sums
    # symmetry: exact (the element matrices are symmetrised), so 0 up to the summation order
    assert np.max(np.abs(K - K.T)) <= 1e-14 * np.abs(K).max()
    # exactly 6 zero eigenvalues (rigid body modes) and the rest clearly positive: round-off of
    # the eigen-solver is ~n·1e-16·λmax, the smallest elastic mode ~1e-3·λmax
    lam = np.linalg.eigvalsh(K) / np.abs(K).max()
    assert np.all(np.abs(lam[:6]) < 1e-12) and lam[6] > 1e-4
    R = rigid_modes(x)
    assert np.max(np.abs(K @ R)) < 1e-12 * np.abs(K).max() * np.abs(R).max()
    # the volume and the energy of a linear field u = a + B x: V · ½ εᵀ D ε
    G, dV = block_geometry(element, x[None])
    assert abs(dV.sum() - volume) < 1e-13 * volume
    B = rng.normal(size=(3, 3)) * 1e-3
    u = (rng.normal(size=3) * 1e-3 + x @ B.T).ravel()  # translation of the size of Bx: no cancellation
    eps = voigt_strain(B)
    assert abs(0.5 * u @ K @ u / (volume * 0.5 * eps @ D @ eps) - 1) < 1e-12


def test_reduced_integration_is_rank_deficient():
    # the rule override is used: 2×2×2 Gauss points leave hex20 with spurious zero-energy
    # modes (more than the 6 rigid ones), the default 3×3×3 does not
    x = HEX20.nodes.copy()
    K = stiffness(x, [(HEX20, np.arange(20)[None])], D, rule=tensor_rule("gauss", (2, 2, 2))).toarray()
    lam = np.linalg.eigvalsh(K) / np.abs(K).max()
    assert np.sum(np.abs(lam) < 1e-12) > 6


def test_inverted_cell_is_named():
    s, blocks = logical_mesh((HEX20, HEX20))
    element, cells = blocks[0]
    bad = cells.copy()
    bad[3] = bad[3][[4, 5, 6, 7, 0, 1, 2, 3, 16, 17, 18, 19, 12, 13, 14, 15, 8, 9, 10, 11]]  # upside down
    with pytest.raises(ValueError, match="cell 3"):
        stiffness(s, [(element, bad)], D)
    with pytest.raises(ValueError, match="cell 3"):
        block_geometry(element, s[bad])


def test_per_block_material_and_rules():
    s, blocks = logical_mesh((HEX28, HEX20))
    K1 = stiffness(s, blocks, D)
    K2 = stiffness(s, blocks, [D, D], rule=[None, default_rule(HEX20)])
    assert abs(K1 - K2).max() == 0.0
    K3 = stiffness(s, blocks, [D, 2 * D])  # the hex20 block twice as stiff
    K4 = stiffness(s, blocks[:1], D) + 2 * stiffness(s, blocks[1:], D)
    assert abs(K3 - K4).max() < 1e-12 * abs(K3).max()
    with pytest.raises(ValueError):
        stiffness(s, blocks, [D])


def test_input_validation():
    s, blocks = logical_mesh((HEX20,))
    element, cells = blocks[0]
    with pytest.raises(ValueError, match="node indices"):
        stiffness(s, [(element, cells + len(s))], D)
    with pytest.raises(ValueError, match="cells must be"):
        stiffness(s, [(element, cells[:, :8])], D)
    with pytest.raises(ValueError, match="points"):
        stiffness(s[:, :2], blocks, D)
    with pytest.raises(ValueError, match="6x6"):
        stiffness(s, blocks, np.eye(3))
    good = cells[:1, [0, 1, 2, 3, 8, 9, 10, 11]]  # the bottom face of cell 0, QUAD8 order
    flat = cells[:1, [0, 1, 1, 0, 8, 1, 8, 0]]     # all nodes on one edge: zero area everywhere
    with pytest.raises(ValueError, match="face 1"):
        surface_traction(s, QUAD8, np.vstack([good, flat]), (0, 0, 1.0))
    # strain_stress takes u as (3N,) or (N, 3)
    u = np.arange(s.size, dtype=float)
    a = strain_stress(s, element, cells, u, D, default_rule(element).points)
    b = strain_stress(s, element, cells, u.reshape(-1, 3), D, default_rule(element).points)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


# ------------------------------------------------------------------------------------------
# meshes: rigid modes
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("layers", list(LAYERS), ids=list(LAYERS))
def test_mesh_rigid_modes(layers, rng):
    s, blocks = logical_mesh(LAYERS[layers][:2])
    x = lattice_map((2, 2, 2), rng)(s)
    K = stiffness(x, blocks, D)
    assert abs(K - K.T).max() <= 1e-14 * abs(K).max()
    lam = np.linalg.eigvalsh(K.toarray()) / abs(K).max()
    assert np.all(np.abs(lam[:6]) < 1e-12) and lam[6] > 1e-5
    R = rigid_modes(x)
    assert np.max(np.abs(K @ R)) < 1e-12 * abs(K).max() * np.abs(R).max()


# ------------------------------------------------------------------------------------------
# patch tests
# ------------------------------------------------------------------------------------------
def _linear_field(rng):
    a, B = rng.normal(size=3) * 1e-3, rng.normal(size=(3, 3)) * 1e-3
    return (lambda x: a + x @ B.T), voigt_strain(B)


def _check_patch(x, blocks, u, u_exact, strain_exact):
    """Worst relative errors of the nodal displacements and of the strains and stresses at the
    Gauss points (each relative to the largest exact value)."""
    ue = u_exact(x)
    err_u = np.max(np.abs(u.reshape(-1, 3) - ue)) / np.max(np.abs(ue))
    err_s = 0.0
    for element, cells in blocks:
        xi = default_rule(element).points
        eps, sig = strain_stress(x, element, cells, u, D, xi)
        eps_ex = strain_exact(physical_points(x, element, cells, xi))
        sig_ex = eps_ex @ D.T
        err_s = max(err_s, np.max(np.abs(sig - sig_ex)) / np.max(np.abs(sig_ex)),
                    np.max(np.abs(eps - eps_ex)) / np.max(np.abs(eps_ex)))
    return err_u, err_s


def _distorted(s, shape, rng, curved: bool, flat_bottom: bool = False):
    """Node coordinates: the perturbed-lattice (trilinear) map of the logical mesh; if ``curved``,
    every non-corner node moved by up to 0.08 (curved edges and faces); with ``flat_bottom``
    the bottom nodes stay in z = 0 (they move in-plane only)."""
    x = lattice_map(shape, rng)(s)
    bottom = np.abs(s[:, 2]) < 1e-9
    if flat_bottom:
        # z of the trilinear map on the bottom face is bilinear in the face coordinates, and so is
        # its interpolant: zeroing it keeps the map trilinear-type (degree 1 per variable)
        x[bottom, 2] = 0.0
    if curved:
        mid = np.any(np.abs(s - np.round(s)) > 1e-9, axis=1)
        x[mid] += rng.uniform(-0.08, 0.08, size=(mid.sum(), 3)) * np.where(flat_bottom & bottom[mid, None], [1, 1, 0], 1)
    return x


def _constant(eps):
    return lambda p: np.broadcast_to(eps, p.shape[:-1] + (6,))


@pytest.mark.parametrize("layers", list(LAYERS), ids=list(LAYERS))
@pytest.mark.parametrize("geometry", ["trilinear", "curved"])
def test_linear_patch_dirichlet(layers, geometry, rng):
    # u = a + Bx on every boundary node; interior nodes solved. Curved HEX28 passes too: its only
    # unknown nodes are off the contact face, whose functions lie in S2·L1 ⊕ Q1·B (degree ≤ 2
    # in ξ, η), which brings the integrand within the 4×4×3 rule (module docstring).
    shape = (3, 3, 3)
    s, blocks = logical_mesh(LAYERS[layers], *shape[:2])
    x = _distorted(s, shape, rng, geometry == "curved")
    u_exact, eps = _linear_field(rng)
    fixed = node_dofs(boundary(s, shape))
    assert len(fixed) < x.size  # there are interior unknowns
    u = solve(stiffness(x, blocks, D), np.zeros(x.size), fixed, u_exact(x).ravel()[fixed])
    err_u, err_s = _check_patch(x, blocks, u, u_exact, _constant(eps))
    assert err_u < PATCH and err_s < PATCH


def _free_contact_face_patch(layers, curved, rng, volume_rule=None, face_rule=None):
    """Linear patch test with Dirichlet data on the sides and the top and the consistent traction
    σ·n on the bottom z = 0 (n = −e_z), whose inner nodes (the transition elements' face centres,
    1/√5 and interior face nodes) are unknowns. Returns the relative errors (nodes, stresses)."""
    shape = (3, 3, 3)
    s, blocks = logical_mesh(LAYERS[layers], *shape[:2])
    x = _distorted(s, shape, rng, curved, flat_bottom=True)
    u_exact, eps = _linear_field(rng)
    sig = D @ eps
    t = -np.array([sig[4], sig[3], sig[2]])  # σ·(−e_z) = −(σ_xz, σ_yz, σ_zz)
    face, faces = face_cells(blocks, s, -1.0, 0.0)
    f = surface_traction(x, face, faces, t, rule=face_rule)
    fixed = node_dofs(open_bottom(s, shape))
    rules = [volume_rule if element is HEX28 else None for element, _ in blocks]
    u = solve(stiffness(x, blocks, D, rule=rules), f, fixed, u_exact(x).ravel()[fixed])
    return _check_patch(x, blocks, u, u_exact, _constant(eps))


@pytest.mark.parametrize("layers, curved", [("hex20", True), ("hex21+hex20", False), ("hex21+hex20", True),
                                            ("hex28+hex20", False)])
def test_linear_patch_free_contact_face(layers, curved, rng):
    # exact: HEX20/HEX21 for any geometry (3×3×3 volume rule, see the module docstring; on the
    # flat face the QUAD8/QUAD9 area element has degree ≤ 3 per variable, N_a dA ≤ 5, within 3
    # Gauss points), HEX28 on trilinear geometry (face map bilinear: N_a dA ≤ 4 ≤ 7)
    err_u, err_s = _free_contact_face_patch(layers, curved, rng)
    assert err_u < PATCH and err_s < PATCH


def test_hex28_curved_free_contact_face_needs_more_points():
    # the limit stated in the module docstring: with curved HEX28 cells and contact-face nodes
    # among the unknowns, neither the 4×4×3 volume rule nor the 4×4 face rule is exact (degree
    # 8 in ξ, η), so the patch test holds to quadrature accuracy only (well above round-off,
    # well below the solution); 5 points in ξ, η (exact to degree 9) restore exactness, which
    # shows the error is the quadrature's and not the element's or the assembly's
    err_u, err_s = _free_contact_face_patch("hex28+hex20", True, np.random.default_rng(7))
    assert 1e-8 < err_u < 1e-2 and 1e-8 < err_s < 1e-1
    err_u, err_s = _free_contact_face_patch("hex28+hex20", True, np.random.default_rng(7),  # same mesh
                                            tensor_rule("gauss", (5, 5, 3)), tensor_rule("gauss", (5, 5)))
    assert err_u < PATCH and err_s < PATCH


def _bending_field(kappa):
    """u with σ_zz = E κ x the only stress (a beam along z bent about y): divergence-free, so no
    body force; u_z = κxz, u_x = −κ(z² + ν(x² − y²))/2, u_y = −νκxy."""
    def u(x):
        X, Y, Z = x[..., 0], x[..., 1], x[..., 2]
        return np.stack([-kappa * (Z ** 2 + NU * (X ** 2 - Y ** 2)) / 2, -NU * kappa * X * Y,
                         kappa * X * Z], axis=-1)

    def strain(x):
        X = x[..., 0]
        z = np.zeros_like(X)
        return np.stack([-NU * kappa * X, -NU * kappa * X, kappa * X, z, z, z], axis=-1)

    return u, strain


@pytest.mark.parametrize("layers", list(LAYERS), ids=list(LAYERS))
def test_quadratic_patch_affine(layers):
    # a quadratic displacement (linear stress) on parallelepipeds of different sizes: every space
    # contains the complete quadratics there, the stiffness is integrated exactly, and the bottom
    # traction σ·(−e_z) = −E κ x e_z is linear (integrated exactly by the face rule). Dirichlet on
    # the sides and the top; the bottom (transition faces) is free and loaded.
    shape = (3, 3, 3)
    s, blocks = logical_mesh(LAYERS[layers], *shape[:2])
    shear = np.array([[1.0, 0.2, 0.1], [0.0, 1.0, -0.15], [0.0, 0.0, 1.0]])  # keeps z = 0 at s_z = 0
    x = affine_box(shape, [(0.5, 1.0, 0.7), (1.2, 0.4, 0.8), (0.3, 0.6, 1.0)], shear)(s)
    kappa = 1e-3
    u_exact, strain = _bending_field(kappa)
    bottom = face_cells(blocks, s, -1.0, 0.0)
    f = surface_traction(x, bottom[0], bottom[1], lambda p: -E * kappa * p[..., [0]] * [0.0, 0.0, 1.0])
    fixed = node_dofs(open_bottom(s, shape))
    u = solve(stiffness(x, blocks, D), f, fixed, u_exact(x).ravel()[fixed])
    err_u, err_s = _check_patch(x, blocks, u, u_exact, strain)
    assert err_u < PATCH and err_s < PATCH


# ------------------------------------------------------------------------------------------
# surface loads
# ------------------------------------------------------------------------------------------
def _flat_face(face, a=2.0, b=3.0):
    """A flat a × b rectangle in the plane z = 1, rotated: the face element's own nodes."""
    c, s_ = math.cos(0.4), math.sin(0.4)
    R = np.array([[c, -s_, 0], [s_, c, 0], [0, 0, 1.0]])
    x = np.column_stack([face.nodes[:, 0] * a / 2, face.nodes[:, 1] * b / 2, np.ones(face.n_nodes)])
    return x @ R.T, a * b


def test_quad8_consistent_loads():
    x, area = _flat_face(QUAD8)
    t = np.array([0.5, -1.0, 2.0])
    f = surface_traction(x, QUAD8, np.arange(8)[None], t).reshape(-1, 3)
    share = np.array([-1 / 12] * 4 + [1 / 3] * 4)  # the classical serendipity loads
    assert np.max(np.abs(f - share[:, None] * t * area)) < 1e-14 * area * np.abs(t).max()


def test_quad9_and_quad16_consistent_loads():
    for face, share in [(QUAD9, np.array([1] * 4 + [4] * 4 + [16]) / 36),
                        # bicubic on the Lobatto nodes: products of the 4-point Lobatto weights
                        # (1/6, 5/6) / 2, exact since the rule integrates the cubic ℓ_i exactly
                        (QUAD16, np.array([1] * 4 + [5] * 8 + [25] * 4) / 144)]:
        x, area = _flat_face(face)
        f = surface_traction(x, face, np.arange(face.n_nodes)[None], (0.0, 0.0, -1.0))
        assert np.max(np.abs(f.reshape(-1, 3)[:, 2] + share * area)) < 1e-14 * area


@pytest.mark.parametrize("layers", ["hex20", "hex21+hex20", "hex28+hex20"])
def test_traction_sums_to_force_on_distorted_faces(layers, rng):
    # bottom faces of a distorted mesh flattened onto z = 0: each face is a planar quadrilateral
    # with straight edges, whose area is given independently by the shoelace formula
    s, blocks = logical_mesh(LAYERS[layers][:2])
    x = lattice_map((2, 2, 2), rng)(s)
    x[np.abs(s[:, 2]) < 1e-9, 2] = 0.0
    face, faces = face_cells(blocks, s, -1.0, 0.0)
    q = x[faces[:, :4], :2]  # the 4 corners, counter-clockwise
    shoelace = 0.5 * np.abs(np.sum(q[:, :, 0] * np.roll(q[:, :, 1], -1, 1) - np.roll(q[:, :, 0], -1, 1) * q[:, :, 1], 1))
    # 1e-13: a sum of 9–16 weighted O(1) terms, measured 1e-15
    assert np.max(np.abs(face_area(x, face, faces) - shoelace)) < 1e-13 * shoelace.max()
    t = np.array([0.3, -0.2, 1.5])
    f = surface_traction(x, face, faces, t).reshape(-1, 3)
    assert np.max(np.abs(f.sum(axis=0) - t * shoelace.sum())) < 1e-13 * shoelace.sum() * np.abs(t).max()


# ------------------------------------------------------------------------------------------
# uniaxial tension against the closed form
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("layers", list(LAYERS), ids=list(LAYERS))
def test_uniaxial_tension(layers, rng):
    # symmetry supports u_x = 0 on x = 0, u_y = 0 on y = 0, u_z = 0 on z = 0; a uniform σ on the
    # top face. Closed form: u_z = σz/E, u_x = −νσx/E, u_y = −νσy/E. Distortion keeps the outer
    # faces planar (corners move within them), so the solution is linear and exact.
    shape = (2, 2, 3)
    s, blocks = logical_mesh(LAYERS[layers], *shape[:2])
    x = lattice_map(shape, rng, sizes=(4.0, 3.0, 2.0), keep_planar=True)(s)
    sigma = 10.0  # N/mm²
    top = face_cells(blocks, s, 1.0, s[:, 2].max())
    f = surface_traction(x, top[0], top[1], (0.0, 0.0, sigma))
    fixed = np.concatenate([node_dofs(np.flatnonzero(np.abs(s[:, a]) < 1e-9), [a]) for a in range(3)])
    u = solve(stiffness(x, blocks, D), f, fixed, np.zeros(len(fixed))).reshape(-1, 3)
    exact = np.column_stack([-NU * sigma * x[:, 0] / E, -NU * sigma * x[:, 1] / E, sigma * x[:, 2] / E])
    assert np.max(np.abs(u - exact)) < PATCH * np.abs(exact).max()


def test_bimaterial_column(rng):
    # per-block materials: HEX28 layer (E1, ν1) under a HEX20 layer (E2, ν2) with ν1/E1 = ν2/E2,
    # so the lateral contraction is continuous and the piecewise-linear closed form is exact
    E1, nu1, E2, nu2 = 1.0e5, 0.2, 1.5e5, 0.3
    shape = (2, 2, 2)
    s, blocks = logical_mesh((HEX28, HEX20))
    x = lattice_map(shape, rng, sizes=(2.0, 2.0, 1.0), keep_planar=True)(s)
    x[:, 2] = s[:, 2]  # horizontal layers z ∈ [0, 1], [1, 2] (the interface must be a plane)
    sigma = 5.0
    top = face_cells(blocks, s, 1.0, s[:, 2].max())
    f = surface_traction(x, top[0], top[1], (0.0, 0.0, sigma))
    fixed = np.concatenate([node_dofs(np.flatnonzero(np.abs(s[:, a]) < 1e-9), [a]) for a in range(3)])
    K = stiffness(x, blocks, [isotropic_elasticity(E1, nu1), isotropic_elasticity(E2, nu2)])
    u = solve(K, f, fixed, np.zeros(len(fixed))).reshape(-1, 3)
    z = x[:, 2]
    uz = np.where(z <= 1, sigma * z / E1, sigma / E1 + sigma * (z - 1) / E2)
    exact = np.column_stack([-nu1 * sigma * x[:, 0] / E1, -nu1 * sigma * x[:, 1] / E1, uz])
    assert np.max(np.abs(u - exact)) < PATCH * np.abs(exact).max()


def test_strain_matrix_and_chunked_stiffness_against_their_dense_forms(rng, monkeypatch):
    """strain_matrix fills the non-zeros of the Voigt operator: equal to the dense einsum
    Σ_ik _STRAIN[s, i, k] ∂N_a/∂x_k; element_stiffness in chunks of cells equals one chunk
    (to round-off of the summation order)."""
    from roughcontact.fe import assembly
    from roughcontact.fe.mesh import box

    G = rng.normal(size=(4, 5, 20, 3))
    dense = np.einsum("sik,...ak->...sai", assembly._STRAIN, G).reshape(4, 5, 6, 60)
    assert np.array_equal(assembly.strain_matrix(G), dense)
    mesh = box(np.linspace(0, 2, 4), np.linspace(0, 1, 3), np.linspace(0, 1, 3))
    cells, el = mesh.blocks[0].cells, mesh.blocks[0].element
    x = mesh.points[cells] + rng.normal(scale=0.02, size=mesh.points[cells].shape)
    D = assembly.isotropic_elasticity(2e5, 0.3)
    whole = assembly.element_stiffness(el, x, D)
    monkeypatch.setattr(assembly, "_CHUNK", 5)
    np.testing.assert_allclose(assembly.element_stiffness(el, x, D), whole, rtol=0, atol=1e-12 * np.abs(whole).max())
