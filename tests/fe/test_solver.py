"""Newton solver of the FE contact engine (roughcontact.fe.solver): the consistent tangent,
quadratic convergence, cut-backs, error reporting, input validation, equilibrium.

The model is a 10 × 10 × 12 mm block (quarter: symmetry planes x = 0, y = 0) on a rigid base
through the paper's statistical interface (section 9.1 surface, E* = 1.127e5 N/mm², seated at
p0 = 0.05 N/mm²) under a uniform pressure on its top. The references are finite differences of
the residual, the law's inverse (the closure where p_N equals the applied pressure) and global
equilibrium; nothing is copied from the solver.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from roughcontact import SpectralMoments
from roughcontact.fe import assembly
from roughcontact.fe import solver as solver_module
from roughcontact.examples.beam import BeamRun, BeamSpec, run_beam
from roughcontact.fe.contact import InterfaceMaterial, statistical_interface
from roughcontact.fe.interface_points import interface_forces, interface_tangent
from roughcontact.fe.mesh import box, rigid_base_interface
from roughcontact.fe.solver import ContactModel, ConvergenceError, NewtonOptions, solve
from roughcontact.interface import friction as fr

SURFACE = SpectralMoments(m00=0.625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)  # µm units
E_STAR, P0 = 1.127e5, 0.05  # N/mm², N/mm²
E, NU = 1.057e5, 0.25  # bulk, section 9.1
TANGENTIAL = {"free": {}, "stick": {}, "coulomb": {"mu": 0.3}}


@pytest.fixture(scope="module")
def materials():
    return {t: statistical_interface(SURFACE, P0, E_star=E_STAR, tangential=t, **kw) for t, kw in TANGENTIAL.items()}


def dofs(nodes, components):
    return (3 * np.asarray(nodes)[:, None] + np.asarray(components)[None, :]).ravel()


def block_model(material, *, symmetry=True, n=(2, 2, 2)) -> ContactModel:
    """The block; without ``symmetry`` only the base is fixed (the interface holds the body)."""
    mesh = rigid_base_interface(box(np.linspace(0, 10, n[0] + 1), np.linspace(0, 10, n[1] + 1),
                                    np.linspace(0, 12, n[2] + 1), contact_face="bottom"))
    fixed = [dofs(mesh.node_sets["base"], (0, 1, 2))]
    if symmetry:
        fixed += [dofs(mesh.node_sets["xmin"], (0,)), dofs(mesh.node_sets["ymin"], (1,))]
    top = mesh.face_sets["zmax"]
    load = assembly.surface_traction(mesh.points, top.face_element, top.face_nodes, (0.0, 0.0, -1.0))
    return ContactModel.assemble(mesh, assembly.isotropic_elasticity(E, NU), material, np.concatenate(fixed), load)


def residual(model, level, u, u_n, state_n):
    """r(u) = λF − K u − Bᵀ(w ⊙ s(δ(u))) on the free dofs, written out from the module docstring,
    and the law's response."""
    pts = model.points
    resp = model.material.respond(state_n, pts.jumps(u) - pts.jumps(u_n))
    r = level * model.load - model.stiffness @ u - interface_forces(pts, resp.tractions)
    return r[model.free], resp


def closure_reference_um(material, p):
    """The law's inverse: the closure [µm] at which the interface carries p [N/mm²]."""
    law = material.normal
    return law.h_ref - law.table.separation_at(p)


# -------------------------------------------------------------------------------------------
# consistent tangent
# -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("tangential", list(TANGENTIAL))
def test_residual_jacobian_is_the_consistent_tangent(tangential, materials):
    """K_t = K + Bᵀ diag(w D) B against central differences of r(u) along random directions,
    at a state 0.5 µm of tangential slip beyond a converged one (Coulomb: points slipping)."""
    mat = materials[tangential]
    model = block_model(mat, symmetry=False)
    free = model.free
    # committed state: converged at 1 N/mm² with the "stick" interface (the models below have
    # no symmetry supports, so a frictionless body could slide freely and its K_t is singular;
    # harmless for a finite-difference check, not for a solve); "free"/"coulomb" then take
    # that state through a zero increment (t_T = 0, or t_T returned to the Coulomb cone)
    committed = solve(block_model(materials["stick"], symmetry=False), [P0, 1.0]).final
    state_n = mat.respond(committed.state, np.zeros((model.points.n_points, 3))).state
    rng = np.random.default_rng(3)
    u_trial = committed.u.copy()
    u_trial[0::3] += 5e-4  # the body slides 0.5 µm along x over the base ...
    u_trial[model.fixed] = 0.0  # ... which stays put
    u_trial[free] += rng.normal(scale=2e-6, size=free.size)
    _, resp = residual(model, 1.0, u_trial, committed.u, state_n)
    if tangential == "coulomb":
        assert np.mean(resp.status == fr.SLIP) > 0.5  # the check covers the sliding tangent
    K = model.stiffness.tocsr()[free][:, free]
    K_int = interface_tangent(model.points, resp.tangent).tocsr()[free][:, free]
    # directions on the interface dofs only: there the interface part of K_t v is not drowned by
    # the bulk's (which is exactly linear and checked with it)
    on_interface = np.isin(free, model.points.dofs)
    h = 1e-8  # mm = 1e-5 µm: truncation (1e-5/0.1)² ~ 1e-8, round-off ε·|K u|/(h·|K_int v|) ~ 1e-9
    worst = 0.0
    for _ in range(3):
        v = np.where(on_interface, rng.normal(size=free.size), 0.0)
        up, um = u_trial.copy(), u_trial.copy()
        up[free] += h * v
        um[free] -= h * v
        rp, resp_p = residual(model, 1.0, up, committed.u, state_n)
        rm, resp_m = residual(model, 1.0, um, committed.u, state_n)
        assert np.array_equal(resp_p.status, resp.status) and np.array_equal(resp_m.status, resp.status)
        fd = (rp - rm) / (2 * h)
        worst = max(worst, np.max(np.abs(fd + K @ v + K_int @ v)) / np.max(np.abs(K_int @ v)))
    # 1e-6 of the interface part: the FD errors above are ≤ 1e-8 (measured worst 3e-9); a wrong
    # or missing tangent term is far larger (dropping the sliding rows of D: 0.3)
    assert worst <= 1e-6


def slipped_state(materials, tangential):
    """(model, u, r, response): the block converged at level 1, then every free dof moved by
    2e-4 mm (tangential slips of 0.2 µm: Coulomb points slip, an unsymmetric tangent), with the
    residual r and the law's response there."""
    model = block_model(materials[tangential])
    free = model.free
    sol = solve(model, [P0, 1.0])
    rng = np.random.default_rng(1)
    u = sol.final.u.copy()
    u[free] += rng.normal(scale=2e-4, size=free.size)
    r, resp = residual(model, 1.0, u, sol.final.u, sol.final.state)
    if tangential == "coulomb":
        assert np.any(resp.status == fr.SLIP) and not np.allclose(resp.tangent, np.swapaxes(resp.tangent, 1, 2))
    return model, u, r, resp


@pytest.mark.parametrize("kind", ["sparse", "condensed", "auto"])
@pytest.mark.parametrize("tangential", ["free", "coulomb"])
def test_linear_solvers_solve_the_tangent_system(kind, tangential, materials):
    """Both linear strategies return du with K_t du = r (the Cholesky path for the symmetric
    frictionless tangent, LU for the unsymmetric sliding one)."""
    model, u, r, resp = slipped_state(materials, tangential)
    free = model.free
    # the residual at (u, level 1): the condensed solver reads the bulk part of r off (u, level)
    du = solver_module._linear_solver(model, kind)(model.points, resp.tangent, r, u[free], 1.0)
    Kt = (model.stiffness + interface_tangent(model.points, resp.tangent)).tocsr()[free][:, free]
    ref = spla.spsolve(Kt.tocsc(), r)
    # backward-stable solves of a system with cond(K_t) ≈ 1e3 (measured): ~1e-13; measured 3e-15
    np.testing.assert_allclose(du, ref, rtol=0, atol=1e-10 * np.max(np.abs(ref)))


# -------------------------------------------------------------------------------------------
# Newton: convergence rate, cut-backs, errors
# -------------------------------------------------------------------------------------------
def test_newton_converges_quadratically(materials):
    """Residual histories of the increments 0.5 → 1 → 2 N/mm²: in the asymptotic range (below
    the first residual, above the round-off floor) r_{k+1} ≤ C r_k² with one constant C, and the
    linear rate r_{k+1}/r_k falls towards zero. Measured: r_{k+1}/r_k² = 7e-3 … 1.8e-2 N⁻¹
    (spread ≤ 2.4×), the linear rate falling by 3e-4 over the asymptotic iterations."""
    model = block_model(materials["free"])
    sol = solve(model, [P0, 0.5, 1.0, 2.0])
    for inc in sol.increments[2:]:
        r = np.array(inc.residuals)
        floor = 1e-10 * r[0]  # the force tolerance's order: below it round-off governs
        k = np.flatnonzero((r[1:] > floor) & (r[:-1] < r[0]))  # asymptotic pairs (k, k + 1)
        assert k.size >= 2
        q = r[k + 1] / r[k] ** 2
        # C bounded (a linearly converging Newton has r_{k+1}/r_k² → ∞ as r_k → 0): within a
        # factor 10 over the asymptotic iterations (measured 2.4 at most), and < 0.1 N⁻¹
        assert q.max() / q.min() < 10.0 and q.max() < 0.1
        linear = r[k + 1] / r[k]
        assert linear[-1] < 1e-2 * linear[0]  # measured 3e-4: superlinear


def test_cut_back_recovers_and_converges_to_the_right_state(materials):
    """0.05 → 0.5 N/mm² in one step needs ~11 Newton iterations (the soft tangent at p0
    overshoots on the stiffening law); with at most 5 per attempt the solver halves the step
    until the attempts converge, and lands on the law's closure for 0.5 N/mm²."""
    mat = materials["free"]
    model = block_model(mat)
    unlimited = solve(model, [P0, 0.5])
    assert unlimited.final.iterations > 5 and unlimited.final.cutbacks == 0
    sol = solve(model, [P0, 0.5], NewtonOptions(max_iterations=5))
    inc = sol.final
    assert inc.cutbacks > 0 and inc.level == 0.5
    ref = closure_reference_um(mat, 0.5)
    # 1e-9: Newton converged to the force tolerance 1e-9 relative (module docstring); measured
    # 3e-14 for the closure, 1e-14 between the two displacement fields
    np.testing.assert_allclose(inc.state[:, fr.U_N], ref, rtol=1e-9)
    np.testing.assert_allclose(inc.u, unlimited.final.u, rtol=0, atol=1e-9 * np.max(np.abs(inc.u)))


def test_convergence_error_names_increment_level_and_residual(materials):
    model = block_model(materials["free"])
    with pytest.raises(ConvergenceError) as info:
        solve(model, [P0, 0.5], NewtonOptions(max_iterations=5, max_cutbacks=0))
    err = info.value
    assert err.increment == 2 and err.level == 0.5 and err.residual > 0.0
    assert "5 iterations" in err.reason
    msg = str(err)
    assert "increment 2" in msg and "load level 0.5" in msg
    number = float(re.search(r"residual ([0-9.e+-]+) N", msg).group(1))
    assert number == pytest.approx(err.residual, rel=1e-3)  # printed with 4 significant digits


def test_bad_inputs_raise_clear_errors(materials):
    model = block_model(materials["free"])
    K, pts, mat, n = model.stiffness, model.points, model.material, model.stiffness.shape[0]
    with pytest.raises(ValueError, match="load pattern"):
        ContactModel(K, pts, mat, model.fixed, np.zeros(n - 3))
    bad = model.load.copy()
    bad[5] = np.nan
    with pytest.raises(ValueError, match="load pattern"):
        ContactModel(K, pts, mat, model.fixed, bad)
    for fixed in ([n], [-1], [0, 3 * n]):
        with pytest.raises(ValueError, match="out of range"):
            ContactModel(K, pts, mat, fixed, model.load)
    other = block_model(materials["free"], n=(1, 1, 1)).points
    with pytest.raises(ValueError, match="another mesh"):
        ContactModel(K, other, mat, model.fixed, model.load)
    for options, match in [(dict(linear_solver="dense"), "linear_solver"), (dict(max_iterations=0), "max_iterations"),
                           (dict(max_cutbacks=-1), "max_cutbacks"), (dict(force_rtol=0.0), "force_rtol"),
                           (dict(displacement_atol=-1.0), "displacement_atol")]:
        with pytest.raises(ValueError, match=match):
            NewtonOptions(**options)
    for levels in ([], [P0, np.nan], [np.inf]):
        with pytest.raises(ValueError, match="levels"):
            solve(model, levels)


# -------------------------------------------------------------------------------------------
# equilibrium of the paper's beam (example 9.1), coarse
# -------------------------------------------------------------------------------------------
def test_beam_example_is_in_equilibrium():
    """Σ w p_N equals the applied load (a quarter of it on the quarter model) at every level:
    the residual's interface forces are the pressure's nodal forces, so the force tolerance
    1e-9·|F| bounds the error; measured ≤ 3e-12. 1e-10 leaves a margin."""
    spec = BeamSpec(n_x=8, n_z=3, elements="quadratic")
    res = run_beam(BeamRun(spec=spec, m00=SURFACE.m00, E_star=E_STAR))
    weights = res.deck.problem.points.weights
    for level, inc in zip(spec.levels, res.deck.increments):
        # the quarter carries a quarter of the full-beam load
        assert np.sum(weights * -inc.tractions[:, 2]) == pytest.approx(level / 4, rel=1e-10)
    assert res.equilibrium_error <= 1e-10
    assert res.cutbacks.sum() == 0 and np.all(res.newton_iterations <= 15)
    assert res.u_N_centre_um < 0.0  # the beam approaches the base under the load (paper's sign)


@pytest.mark.parametrize("kind", [
    "sparse",
    "condensed",
])
def test_first_touch_constant_stiffness(kind):
    """A constant-k_N interface starting at first touch (closure0 = 0) is open in the law
    (p_N = k_N·max(u_N, 0)), so the first tangent has no interface stiffness and the body
    floats: K_t is singular. Acceptable outcomes: the right answer (closure p/k_N) or a
    ConvergenceError. The sparse path currently gets there by luck: SuperLU factors the
    singular matrix and takes a ~1e16 step (residual 2.5e15 N) before Newton recovers."""
    mesh = rigid_base_interface(box([0.0, 10.0], [0.0, 10.0], [0.0, 10.0], contact_face="bottom"))
    fixed = dofs(mesh.node_sets["base"], (0, 1, 2))
    top = mesh.face_sets["zmax"]
    load = assembly.surface_traction(mesh.points, top.face_element, top.face_nodes, (0.0, 0.0, -1.0))
    k = 1e3  # N/mm³
    mat = InterfaceMaterial(k, fr.NoSlip(), k_T=(k, k), length_per_mm=1.0)
    model = ContactModel.assemble(mesh, assembly.isotropic_elasticity(2e5, 0.3), mat, fixed, load)
    try:
        sol = solve(model, [1.0], NewtonOptions(linear_solver=kind))
    except ConvergenceError:
        return
    # mean closure 1/k (equilibrium of the resultant; the bonded Poisson effect makes it
    # non-uniform by 1e-4): 1e-9 relative
    closure = sol.final.state[:, fr.U_N]
    assert np.sum(closure * model.points.weights) / 100.0 == pytest.approx(1.0 / k, rel=1e-9)


def test_fixed_dofs_must_be_integer_indices(materials):
    model = block_model(materials["free"])
    mask = np.zeros(model.stiffness.shape[0], dtype=bool)
    mask[model.fixed] = True
    for fixed in (mask, model.fixed + 0.5):
        try:
            other = ContactModel(model.stiffness, model.points, model.material, fixed, model.load)
        except (TypeError, ValueError):
            continue  # a clear error is fine
        assert np.array_equal(other.fixed, model.fixed)  # or the mask's dofs


def test_auto_strategy_by_interface_size(materials, monkeypatch):
    """"auto" condenses (kept dense factor, GMRES) while the interface has at most
    AUTO_CONDENSED_MAX dofs, else reuses the sparse factor (GMRES); the two give the same
    solution (to the force tolerance)."""
    model = block_model(materials["free"])
    n_I = solver_module.interface_dofs(model)
    assert 0 < n_I <= 3 * model.points.n_points  # the rigid base: one side free (less the symmetry planes)
    assert solver_module.linear_strategy(model) == "condensed-krylov"
    assert solver_module.linear_strategy(model, "sparse") == "sparse"
    condensed = solve(model, [P0, 1.0])
    monkeypatch.setattr(solver_module, "AUTO_CONDENSED_MAX", n_I - 1)
    assert solver_module.linear_strategy(model) == "sparse-krylov"
    sparse = solve(model.with_material(model.material), [P0, 1.0])
    np.testing.assert_allclose(sparse.final.u, condensed.final.u, rtol=0, atol=1e-9 * np.max(np.abs(condensed.final.u)))


def test_coordinates_are_checked_and_optional(materials):
    """Node coordinates only order the sparse factorisations: without them (reverse
    Cuthill–McKee) the answer is the same; a wrong shape is a clear error."""
    model = block_model(materials["free"])
    assert model.coordinates is not None and model.with_material(model.material).coordinates is model.coordinates
    bare = ContactModel(model.stiffness, model.points, model.material, model.fixed, model.load)
    for kind in ("condensed", "sparse"):
        a = solve(model, [P0, 1.0], NewtonOptions(linear_solver=kind)).final.u
        b = solve(bare, [P0, 1.0], NewtonOptions(linear_solver=kind)).final.u
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * np.max(np.abs(a)))
    with pytest.raises(ValueError, match="coordinates"):
        ContactModel(model.stiffness, model.points, model.material, model.fixed, model.load,
                     coordinates=model.coordinates[:-1])
