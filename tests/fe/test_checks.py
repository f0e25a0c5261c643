"""The FE contact engine against closed forms (section 9 of Buczkowski & Kleiber 2009).

1. A block on a rigid base under uniform pressure: the interface closure is the statistical
   law's inverse, the bulk is in uniaxial stress (displacements known in closed form), both
   linear solvers agree.
2. Gauss vs Lobatto (nodal) integration of a stiff interface: a linear traction is exact with
   both; at a bonded edge Gauss tractions oscillate, nodal ones do not.
3. A slender beam on a linear (Winkler) interface against Hetényi's finite free–free beam
   (roughcontact.fe.closed_forms, itself checked against solve_bvp here).

References: the law's table inverted by root finding (NormalLawTable.separation_at), elasticity
closed forms, Hetényi's formula and an independent BVP solve. No expected value comes from the
engine.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from roughcontact import SpectralMoments
from roughcontact.fe import assembly
from roughcontact.fe.closed_forms import hetenyi_finite_beam, hetenyi_infinite_beam, winkler_lambda
from roughcontact.fe.contact import InterfaceMaterial, statistical_interface
from roughcontact.fe.mesh import box, rigid_base_interface
from roughcontact.fe.solver import ContactModel, ConvergenceError, NewtonOptions, solve
from roughcontact.interface import friction as fr

SURFACE = SpectralMoments(m00=0.625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)  # µm units
E_STAR, P0 = 1.127e5, 0.05  # N/mm²: section 9.1's E* and a seating pressure
FAMILIES = ("quadratic", "cubic")
RULES = ("lobatto", "gauss")


def dofs(nodes, components):
    return (3 * np.asarray(nodes)[:, None] + np.asarray(components)[None, :]).ravel()


@pytest.fixture(scope="module")
def frictionless_law():
    return statistical_interface(SURFACE, P0, E_star=E_STAR, tangential="free")


# ===========================================================================================
# 1. block under uniform pressure
# ===========================================================================================
BLOCK = (10.0, 10.0, 12.0)  # mm: quarter of a 20 × 20 × 12 block (symmetry planes x = 0, y = 0)
E_BULK, NU_BULK = 1.057e5, 0.25  # N/mm², section 9.1
LEVELS = (P0, 0.5, 1.0, 2.0)  # N/mm² on the top face


def block_on_base(material, family, rule, n=(2, 2, 3)):
    X, Y, H = BLOCK
    mesh = rigid_base_interface(box(np.linspace(0, X, n[0] + 1), np.linspace(0, Y, n[1] + 1),
                                    np.linspace(0, H, n[2] + 1), contact_face="bottom", family=family))
    fixed = np.concatenate([dofs(mesh.node_sets["base"], (0, 1, 2)), dofs(mesh.node_sets["xmin"], (0,)),
                            dofs(mesh.node_sets["ymin"], (1,))])
    top = mesh.face_sets["zmax"]
    load = assembly.surface_traction(mesh.points, top.face_element, top.face_nodes, (0.0, 0.0, -1.0))
    model = ContactModel.assemble(mesh, assembly.isotropic_elasticity(E_BULK, NU_BULK), material, fixed, load,
                                  rule=rule)
    return mesh, model


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("rule", RULES)
def test_block_closure_is_the_laws_inverse(family, rule, frictionless_law):
    """Frictionless interface, free lateral faces: the bulk is in uniaxial stress σ_zz = −p
    (in the discrete space: the displacement field is linear), so with z from the base

        u_x = ν p x / E,   u_y = ν p y / E,   u_z = −c(p) − p z / E,

    c(p) = h_ref − h(p) the law's closure [µm → mm] (c(p0) = 0, the reference state); the
    solve starts from an unstressed bulk on a seated interface, so at p0 the bulk alone has
    shortened. Sign: closure and shortening both move the top down (−z); Poisson's expansion
    moves the lateral faces outwards (+x at x = X)."""
    mat = frictionless_law
    mesh, model = block_on_base(mat, family, rule)
    sols = {kind: solve(model, LEVELS, NewtonOptions(linear_solver=kind)) for kind in ("sparse", "condensed")}
    sol = sols["sparse"]
    body = np.setdiff1d(np.arange(mesh.n_nodes), mesh.node_sets["base"])
    x = mesh.points[body]
    c_max = (mat.normal.h_ref - mat.normal.table.separation_at(LEVELS[-1])) / 1000.0  # mm
    for k, p in enumerate(LEVELS):
        inc = sol.increments[k]
        c = (mat.normal.h_ref - mat.normal.table.separation_at(p)) / 1000.0  # mm
        closure = inc.state[:, fr.U_N] / 1000.0
        # 1e-9 relative (to c at 2 N/mm², c(p0) being 0): Newton stops at a force residual of
        # 1e-9 of the load (measured worst 8e-14)
        np.testing.assert_allclose(closure, c, rtol=0, atol=1e-9 * c_max)
        np.testing.assert_allclose(-inc.tractions[:, 2], p, rtol=1e-9)
        exact = np.column_stack([NU_BULK * p * x[:, 0] / E_BULK, NU_BULK * p * x[:, 1] / E_BULK,
                                 -c - p * x[:, 2] / E_BULK])
        u = inc.u.reshape(-1, 3)
        # the same 1e-9 of the largest displacement (measured worst 4e-13)
        np.testing.assert_allclose(u[body], exact, rtol=0, atol=1e-9 * np.max(np.abs(exact)))
        assert not np.any(u[mesh.node_sets["base"]])
        # equilibrium: round-off of sums of O(100) terms (measured ≤ 3e-13)
        assert sol.equilibrium_error(k) <= 1e-10
        # the two linear solvers: both converge far below 1e-10 (measured 9e-14)
        other = sols["condensed"].increments[k].u
        np.testing.assert_allclose(other, inc.u, rtol=0, atol=1e-10 * np.max(np.abs(inc.u)))
    # the top moved by the closure change plus the uniaxial shortening p H / E
    top = mesh.node_sets["zmax"]
    drop = -sol.final.u.reshape(-1, 3)[top, 2]
    np.testing.assert_allclose(drop, c_max + LEVELS[-1] * BLOCK[2] / E_BULK, rtol=1e-9)


# ===========================================================================================
# 2. Gauss vs Lobatto integration of a stiff interface
# ===========================================================================================
# Schellekens & de Borst (1993, "On the numerical integration of interface elements", IJNME
# 36:43–66) showed by an eigenvalue analysis of the interface stiffness that Gauss integration
# couples the node pairs of an interface element, so that with a high (dummy) stiffness the
# traction profile oscillates where it has a steep gradient, while Newton–Cotes / Lobatto
# (nodal) integration decouples them (a diagonal interface matrix) and gives smooth profiles;
# they recommend nodal integration for stiff interfaces. In the stiff limit the Gauss tractions
# are the consistent-mass projection M⁻¹f of the nodal interface forces f (M_ab = ∫N_a N_b dA),
# the Lobatto ones f_a/w_a (the lumped projection): M⁻¹ has entries of both signs and spreads
# a local force with alternating sign, the lumped projection keeps it local. The 28-node element of the paper puts its contact-face nodes at ±1/√5, the 4-point
# Lobatto abscissae, for exactly this reason (notes, section 9).
STIFF = 1e8  # N/mm³ (length_per_mm = 1): k·(element size 2.5 mm)/E ≈ 1e3, a penalty-like interface
SOFT = 1e4  # N/mm³: k·2.5/E ≈ 0.1, the interface more compliant than the bulk


def strip(family, rule, k, model, top_pressure, *, L=10.0, H=8.0, n=(4, 4), nu=0.25, x_support="symmetry"):
    """A block x ∈ [0, L], y ∈ [0, 1], z ∈ [0, H] in plane strain (u_y = 0 on both y faces) on a
    rigid base through a linear interface k_N = k_T = k, pre-compressed by 1 N/mm² (closure0 =
    1/k: closed from the start), under a top pressure q(x). x_support "symmetry": u_x = 0 on
    x = 0 (half of a block of length 2L); "point": u_x = 0 at the body's node (0, 0, 0) only.
    Returns the normal pressures along the row of points nearest to y = 0 (on it for the nodal
    rule, at the first Gauss abscissa otherwise; plane strain makes every row alike) sorted by x
    (positions, p_N)."""
    mesh = rigid_base_interface(box(np.linspace(0, L, n[0] + 1), [0.0, 1.0], np.linspace(0, H, n[1] + 1),
                                    contact_face="bottom", family=family))
    fixed = [dofs(mesh.node_sets["base"], (0, 1, 2)), dofs(mesh.node_sets["ymin"], (1,)),
             dofs(mesh.node_sets["ymax"], (1,))]
    if x_support == "symmetry":
        fixed.append(dofs(mesh.node_sets["xmin"], (0,)))
    else:
        corner = np.flatnonzero(np.all(mesh.points == 0.0, axis=1))
        corner = np.setdiff1d(corner, mesh.node_sets["base"])
        fixed.append(dofs(corner, (0,)))
    top = mesh.face_sets["zmax"]

    def traction(x):
        return np.stack([np.zeros_like(x[..., 0]), np.zeros_like(x[..., 0]), -top_pressure(x[..., 0])], axis=-1)

    load = assembly.surface_traction(mesh.points, top.face_element, top.face_nodes, traction)
    mat = InterfaceMaterial(k, model, k_T=(k, k), length_per_mm=1.0, closure0=1.0 / k)
    cm = ContactModel.assemble(mesh, assembly.isotropic_elasticity(2e5, nu), mat, np.concatenate(fixed), load,
                               rule=rule)
    sol = solve(cm, [1.0])
    assert np.all(sol.final.status != fr.OPEN)  # linear throughout: the comparison is clean
    pts = cm.points
    line = np.flatnonzero(np.isclose(pts.x[:, 1], pts.x[:, 1].min()))
    line = line[np.argsort(pts.x[line, 0])]
    return pts.x[line, 0], -sol.final.tractions[line, 2]


def spurious_variation(p):
    """Total variation of a profile in excess of a monotone one: the sum of its increases when
    walking from the edge (last point) to the centre (first), where the continuum profile only
    decreases. 0 for a monotone profile."""
    return float(np.sum(np.clip(np.diff(p[::-1]), 0.0, None)))


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("rule", RULES)
def test_linear_traction_is_exact_with_both_rules(family, rule):
    """A frictionless stiff interface under a linearly varying pressure: the bulk is in a
    linear uniaxial stress state (plane strain; the displacement is quadratic, in the discrete
    space), so the interface pressure is the applied one at every point, with both rules."""
    q = lambda x: 0.5 + 0.1 * x  # N/mm², from 0.5 to 1.5
    x, p = strip(family, rule, STIFF, fr.Frictionless(), q, x_support="point")
    # 1e-8: the stiff interface's jumps are 1e-8 mm, the bulk's displacements 1e-4 mm; the
    # round-off of K u relative to the load is ~1e-10 (measured 2e-12)
    np.testing.assert_allclose(p, q(x), rtol=1e-8)


@pytest.mark.parametrize("family", FAMILIES)
def test_gauss_oscillates_at_a_bonded_edge_lobatto_does_not(family):
    """A bonded (NoSlip) block under uniform pressure: the pressure rises monotonically from the
    centre to the edge (the bonded-edge singularity). With a stiff interface, Gauss points
    zig-zag around that profile, the nodal points follow it; with a soft interface neither rule
    oscillates (the effect is the stiff-interface one of Schellekens & de Borst).

    Measured spurious variation / p (this configuration; neighbours H = 8–12 mm, ν = 0.25–0.35
    with 4 elements along x give the same picture): Gauss 0.18 (quadratic), 0.37 (cubic);
    Lobatto 0 and 2e-4; soft interface 0 with both rules. Thresholds: Gauss > 0.1 (10 % of the
    mean pressure), Lobatto < 0.01 (1 %), soft < 0.01. Finer meshes (6 elements) raise Gauss to
    0.3–0.8 but also let the nodal cubic profile wiggle next to the singular edge (up to 0.1)."""
    uniform = lambda x: np.ones_like(x)
    tv, reversals = {}, {}
    for rule in RULES:
        x, p = strip(family, rule, STIFF, fr.NoSlip(), uniform)
        assert p[-1] > 1.5 and p[0] < 1.0  # the edge carries the peak, the centre less than the mean
        tv[rule] = spurious_variation(p)
        # zig-zags: increases by more than 1 % of the mean pressure walking from edge to centre
        reversals[rule] = np.count_nonzero(np.diff(p[::-1]) > 0.01)
        _, p_soft = strip(family, rule, SOFT, fr.NoSlip(), uniform)
        assert spurious_variation(p_soft) < 0.01
    assert tv["gauss"] > 0.1 and reversals["gauss"] >= 2  # measured 3 zig-zags for both families
    assert tv["lobatto"] < 0.01 and reversals["lobatto"] == 0


# ===========================================================================================
# 3. beam on a Winkler foundation: Hetényi
# ===========================================================================================
def bvp_deflection(P, L, EI, k_b, x):
    """Independent reference: EI w'''' + k_b w = P δ on the half beam [0, L/2] from the load,
    w'(0) = 0, w'''(0⁺) = P/(2EI) (the shear jump, split by symmetry), w'' = w''' = 0 at the
    free end; scipy's collocation BVP solver at tolerance 1e-10."""
    def f(s, y):
        return np.vstack([y[1], y[2], y[3], -k_b * y[0] / EI])

    def bc(ya, yb):
        return np.array([ya[1], ya[3] - P / (2 * EI), yb[2], yb[3]])

    s = np.linspace(0.0, L / 2, 201)
    sol = solve_bvp(f, bc, s, np.zeros((4, s.size)), tol=1e-10, max_nodes=100000)
    assert sol.status == 0
    return sol.sol(np.abs(x))[0]


@pytest.mark.parametrize("lam_L", [0.5, 2.0, 4.0, 7.0])
def test_hetenyi_formula_solves_the_beam_equation(lam_L):
    L, EI, P = 1000.0, 1.3e9, 100.0
    k_b = 4 * EI * (lam_L / L) ** 4
    x = np.linspace(-L / 2, L / 2, 41)
    w = hetenyi_finite_beam(P, L, EI, k_b, x)
    # the collocation error at tol 1e-10 is ~1e-10 of max w (measured ≤ 4e-10 at λL = 7)
    np.testing.assert_allclose(w, bvp_deflection(P, L, EI, k_b, x), rtol=0, atol=1e-8 * np.max(np.abs(w)))
    # equilibrium: the foundation carries P, ∫ k_b w dx = P (Simpson on a fine grid: 1e-10)
    xs = np.linspace(-L / 2, L / 2, 4001)
    ws = hetenyi_finite_beam(P, L, EI, k_b, xs)
    integral = (xs[1] - xs[0]) / 3 * (ws[0] + ws[-1] + 4 * ws[1:-1:2].sum() + 2 * ws[2:-1:2].sum())
    assert k_b * integral == pytest.approx(P, rel=1e-9)


def test_hetenyi_limits():
    L, EI, P = 1000.0, 1.3e9, 100.0
    k_rigid = 4 * EI * (1e-3 / L) ** 4  # λL = 1e-3: a rigid beam sinks uniformly, P/(k_b L)
    w = hetenyi_finite_beam(P, L, EI, k_rigid, np.array([0.0, 250.0, 500.0]))
    np.testing.assert_allclose(w, P / (k_rigid * L), rtol=1e-9)  # correction O((λL)⁴) = 1e-12
    k_long = 4 * EI * (30.0 / L) ** 4  # λL = 30: the ends do not matter near the load
    x = np.linspace(0.0, 100.0, 11)  # λx ≤ 3
    # end effects ~ e^{-λL/2} = 3e-7 of w(0)
    np.testing.assert_allclose(hetenyi_finite_beam(P, L, EI, k_long, x), hetenyi_infinite_beam(P, EI, k_long, x),
                               rtol=0, atol=1e-6 * hetenyi_infinite_beam(P, EI, k_long, 0.0))
    assert winkler_lambda(EI, k_long) == pytest.approx(30.0 / L, rel=1e-14)
    with pytest.raises(ValueError):
        hetenyi_finite_beam(P, L, EI, k_long, 501.0)


def beam_on_winkler(family, *, lam_L=4.0, height=20.0, nu=0.0, n=(16, 2), L=1000.0, b=10.0, E=2e5, P=100.0,
                    options=NewtonOptions(force_atol=1e-6)):
    """Quarter of a free–free beam L × b × h (x ∈ [0, L/2], y ∈ [0, b/2], symmetry planes x = 0,
    y = 0) on a rigid base through a frictionless linear interface k_N [N/mm³] = k_b / b, a line
    load P (full beam) across the top at mid-length. The interface is pre-compressed to twice the
    largest |k_b w| (closure0; no point opens) and the matching uniform pressure is on the top, so
    that the pre-stress alone is in equilibrium with zero jumps: the deflection is the closure
    minus closure0. Returns (x, deflection FE, deflection Hetényi, uniform-pressure-only jumps)."""
    EI = E * b * height ** 3 / 12
    k_b = 4 * EI * (lam_L / L) ** 4
    k_N = k_b / b
    w_max = np.max(np.abs(hetenyi_finite_beam(P, L, EI, k_b, np.linspace(0, L / 2, 501))))
    p_pre = 2.0 * k_N * w_max
    mesh = rigid_base_interface(box(np.linspace(0, L / 2, n[0] + 1), [0.0, b / 2], np.linspace(0, height, n[1] + 1),
                                    contact_face="bottom", family=family))
    fixed = np.concatenate([dofs(mesh.node_sets["base"], (0, 1, 2)), dofs(mesh.node_sets["xmin"], (0,)),
                            dofs(mesh.node_sets["ymin"], (1,))])
    top = mesh.face_sets["zmax"]
    pre = assembly.surface_traction(mesh.points, top.face_element, top.face_nodes, (0.0, 0.0, -p_pre))
    line = np.flatnonzero(np.isclose(mesh.points[:, 0], 0.0) & np.isclose(mesh.points[:, 2], height))
    line = line[np.argsort(mesh.points[line, 1])]
    assert line.size == 3  # one quadratic top edge across the half width
    point = np.zeros_like(pre)
    # P/2 on the half beam x ≥ 0, spread over the whole width b: P/4 on the quarter's edge,
    # consistent weights 1/6, 2/3, 1/6 of the quadratic edge
    point[3 * line + 2] = -(P / 4) * np.array([1.0, 4.0, 1.0]) / 6.0
    mat = InterfaceMaterial(k_N, fr.Frictionless(), k_T=(k_N, k_N), length_per_mm=1.0, closure0=p_pre / k_N)
    D = assembly.isotropic_elasticity(E, nu)
    # options: force_atol 1e-6 N, because the soft foundation lets the beam move by mm under
    # loads of N, so the round-off of K u (ε·|K|·|u| ~ 1e-7 N) can exceed the default
    # 1e-9·|F| + 1e-9 N tolerance (test_soft_foundation_converges_with_default_tolerances);
    # the problem is linear, one Newton step solves it
    opts = options
    only_pre = solve(ContactModel.assemble(mesh, D, mat, fixed, pre), [1.0], opts)
    sol = solve(ContactModel.assemble(mesh, D, mat, fixed, pre + point), [1.0], opts)
    pts = only_pre.model.points
    assert np.all(sol.final.status != fr.OPEN)
    centre = np.flatnonzero(np.isclose(pts.x[:, 1], 0.0))
    centre = centre[np.argsort(pts.x[centre, 0])]
    x = pts.x[centre, 0]
    w_fe = sol.final.state[centre, fr.U_N] - p_pre / k_N
    return x, w_fe, hetenyi_finite_beam(P, L, EI, k_b, x), pts.jumps(only_pre.final.u)


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("nu", [0.0, 0.3])
def test_beam_on_linear_interface_matches_hetenyi(family, nu):
    """λL = 4 (the deflection changes sign along the beam), L/h = 50. Measured: 0.114–0.117 % of
    w(0), largest at the centre (0.144 % in the converged limit, below). Tolerance 0.5 %: the Euler–Bernoulli beam
    neglects shear, whose relative effect is EI λ²/(κGA) = 1.3e-3 here (κ = 5/6, ν = 0), and
    the 3D spreading of the line load over ~h near the centre."""
    x, w_fe, w_h, jumps_pre = beam_on_winkler(family, nu=nu)
    # the pre-stress is self-equilibrated: zero normal jumps (uniaxial stress; frictionless, so
    # the Poisson expansion just slides); round-off of mm-sized closures: 1e-9
    assert np.max(np.abs(jumps_pre[:, 2])) <= 1e-9 * np.max(np.abs(w_h))
    assert w_h[-1] < 0.0 < w_h[0]  # the ends lift: a strongly varying deflection
    np.testing.assert_allclose(w_fe, w_h, rtol=0, atol=5e-3 * w_h[0])


def test_beam_discrepancy_is_the_shear_correction():
    """The converged difference from Hetényi scales as (λh)², the order of the shear and
    through-thickness corrections to Euler–Bernoulli: halving h at fixed λL divides it by ~4
    (measured 4.8, differences 1.44e-3 and 3.0e-4 of w(0)); a discretisation or loading error
    would not scale so. Meshes 32 × 2 quadratic: discretisation error < 3e-5."""
    diffs = []
    for h in (20.0, 10.0):
        x, w_fe, w_h, _ = beam_on_winkler("quadratic", height=h, n=(32, 2))
        diffs.append((w_fe[0] - w_h[0]) / w_h[0])
    assert diffs[0] > 0 and diffs[1] > 0  # the FE beam is softer (it also shears)
    assert 3.0 < diffs[0] / diffs[1] < 6.0
    assert diffs[0] < 2e-3


def test_soft_foundation_converges_with_default_tolerances():
    x, w_fe, w_h, _ = beam_on_winkler("quadratic", height=10.0, lam_L=3.0, options=NewtonOptions())
    np.testing.assert_allclose(w_fe, w_h, rtol=0, atol=5e-3 * w_h[0])  # as the test above
