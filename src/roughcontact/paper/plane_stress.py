"""Example 9.1 solved again by a small, separate 2D plane-stress code: the engine-free anchor of
the beam's numbers in the verification gate.

The 3D engine (:mod:`roughcontact.fe`) reports the beam's interface deflections; the gate checks
them against the paper (20 % bands) and against other runs of the same engine (mesh, element
family), so an error common to all runs — a wrong unit, a lost factor — would pass. This module
solves the same problem with nothing of the engine: its own mesh, its own element (the 9-node
biquadratic Lagrange quadrilateral, plane stress, 3 × 3 Gauss), its own assembly and its own
Newton loop (numpy and scipy.sparse only; ``tests/paper/test_plane_stress.py`` checks that it
imports nothing from ``roughcontact.fe`` or ``roughcontact.examples``). What it shares with the
engine is the physics it is given: the library's normal law
(:class:`~roughcontact.interface.InterfaceLaw`), itself checked against direct integration and
mpmath, and the numbers of the run it solves again, read from the run's fields (duck-typed: a
:class:`~roughcontact.examples.beam.BeamRun` or anything with its fields, never its deck).

The problem (the engine's reading of example 9.1, :mod:`roughcontact.examples.beam`): a beam of length
L, height H and width b (E, ν) on a rigid base through the statistical interface with free
sliding (no tangential traction), a line load across the width at mid-length on the top face,
first the seating load, then the load; the interface law's reference state is the mean seating
pressure p0 = P_seat/(L b). Plane stress in the (x, z) plane of the beam (the width b = 10 mm is
thin against the height), half of the beam by symmetry (u_x = 0 at x = 0). The interface is
integrated at the bottom nodes (the weights of the quadratic edge, h/6, 4h/6, h/6). u_N is the
change of the closure from the seated state, negative = approach [µm], as in Table 4.

Checked against closed forms (tests): a uniform pressure gives the law's closure and the uniaxial
stress field; a linear interface k gives Hetényi's finite beam on a Winkler foundation
(:func:`roughcontact.fe.closed_forms.hetenyi_finite_beam`) plus Timoshenko's shear correction.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from threadpoolctl import threadpool_limits

__all__ = ["PlaneStressBeam", "PlaneStressResult", "solve_plane_stress_beam", "graded_edges", "plane_stress_beam",
           "beam_run_law", "reference_solution"]

#: 1-D quadratic Lagrange nodes and 3-point Gauss rule on [-1, 1]
_GAUSS = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


def _lagrange2(t):
    """Values and derivatives of the quadratic Lagrange polynomials on the nodes -1, 0, 1."""
    t = np.asarray(t, dtype=float)
    n = np.stack([0.5 * t * (t - 1.0), 1.0 - t * t, 0.5 * t * (t + 1.0)])
    d = np.stack([t - 0.5, -2.0 * t, t + 0.5])
    return n, d


def graded_edges(a: float, b: float, n: int, ratio: float = 1.0) -> np.ndarray:
    """n + 1 element edges from a to b whose sizes grow geometrically by ``ratio`` overall (the
    last element ``ratio`` times the first)."""
    if n < 1:
        raise ValueError(f"n must be a positive integer, got {n!r}")
    q = ratio ** (1.0 / max(n - 1, 1)) if n > 1 else 1.0
    sizes = q ** np.arange(n)
    return a + (b - a) * np.concatenate([[0.0], np.cumsum(sizes) / sizes.sum()])


@dataclass(frozen=True)
class PlaneStressBeam:
    """The beam [mm, N/mm², N; the paper's data come from the caller, e.g. the workflow] and its
    2D mesh: ``n_x`` elements along the half beam (uniform), ``n_z`` over the height graded by
    ``z_ratio`` from the contact face; loads on the full beam."""

    length: float
    height: float
    width: float
    E: float
    nu: float
    load: float
    initial_load: float
    increments: int = 16
    n_x: int = 100
    n_z: int = 24
    z_ratio: float = 4.0

    def __post_init__(self):
        for name in ("length", "height", "width", "E", "load", "initial_load", "z_ratio"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} must be positive, got {getattr(self, name)!r}")
        if not -1.0 < self.nu < 0.5 or not self.initial_load < self.load:
            raise ValueError("need -1 < nu < 0.5 and initial_load < load")
        for name in ("increments", "n_x", "n_z"):
            v = getattr(self, name)
            if not (isinstance(v, (int, np.integer)) and v >= 1):
                raise ValueError(f"{name} must be a positive integer, got {v!r}")

    @property
    def seating_pressure(self) -> float:
        """The mean interface pressure under the seating load [N/mm²]: the law's reference state."""
        return self.initial_load / (self.length * self.width)

    @property
    def levels(self) -> np.ndarray:
        return np.concatenate([[self.initial_load], np.linspace(self.initial_load, self.load, self.increments + 1)[1:]])


@dataclass(frozen=True, eq=False)
class PlaneStressResult:
    """x_mm: the bottom nodes from mid-length; u_N_um: their deflection from the seated state at
    the final load (negative = approach) [µm]; p_N [N/mm²]; equilibrium_error: |Σ w b p_N − P/2|
    / (P/2); newton_iterations per level; dofs; seconds."""

    beam: PlaneStressBeam
    x_mm: np.ndarray
    u_N_um: np.ndarray
    p_N: np.ndarray
    equilibrium_error: float
    newton_iterations: np.ndarray
    dofs: int
    seconds: float

    @property
    def u_N_centre_um(self) -> float:
        return float(self.u_N_um[0])

    @property
    def u_N_end_um(self) -> float:
        return float(self.u_N_um[-1])


def _mesh(beam: PlaneStressBeam):
    """Nodes of the doubled grid (every element edge and mid-point), the 9 nodes of each element
    (tensor order: ξ fastest), the element sizes."""
    xe = graded_edges(0.0, beam.length / 2.0, beam.n_x)
    ze = graded_edges(0.0, beam.height, beam.n_z, beam.z_ratio)

    def doubled(e):
        out = np.empty(2 * e.size - 1)
        out[0::2], out[1::2] = e, 0.5 * (e[:-1] + e[1:])
        return out

    X, Z = doubled(xe), doubled(ze)
    nx = X.size
    ex, ez = np.meshgrid(np.arange(beam.n_x), np.arange(beam.n_z), indexing="xy")
    ex, ez = ex.ravel(), ez.ravel()
    conn = np.stack([(2 * ez + b) * nx + 2 * ex + a for b in range(3) for a in range(3)], axis=1)
    sizes = np.stack([np.diff(xe)[ex], np.diff(ze)[ez]], axis=1)
    return X, Z, conn, sizes


def _stiffness(beam: PlaneStressBeam, X, Z, conn, sizes) -> sp.csr_matrix:
    """The plane-stress stiffness [N/mm] of the whole width b (2 dofs per node: u_x, u_z)."""
    g, w = _GAUSS
    n, d = _lagrange2(g)  # (3 nodes, 3 points)
    # per Gauss point (i along ξ, j along ζ) and node (a, b): dN/dξ, dN/dζ of the tensor product
    # point i*3 + j (ξ_i, ζ_j), node b*3 + a (ξ node a, ζ node b; the order of _mesh's conn)
    dxi = np.einsum("ai,bj->ijba", d, n).reshape(9, 9)
    dze = np.einsum("ai,bj->ijba", n, d).reshape(9, 9)
    wts = np.einsum("i,j->ij", w, w).reshape(9)
    E, nu = beam.E, beam.nu
    D = E / (1.0 - nu * nu) * np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1.0 - nu)]])
    hx, hz = sizes[:, 0], sizes[:, 1]
    ne = conn.shape[0]
    Ke = np.zeros((ne, 18, 18))
    for q in range(9):
        Nx = dxi[q][None, :] * (2.0 / hx)[:, None]  # (ne, 9) ∂N/∂x
        Nz = dze[q][None, :] * (2.0 / hz)[:, None]
        B = np.zeros((ne, 3, 18))
        B[:, 0, 0::2] = Nx
        B[:, 1, 1::2] = Nz
        B[:, 2, 0::2] = Nz
        B[:, 2, 1::2] = Nx
        det = 0.25 * hx * hz
        Ke += np.einsum("eki,kl,elj->eij", B, D, B) * (wts[q] * det * beam.width)[:, None, None]
    dof = np.empty((ne, 18), dtype=np.int64)
    dof[:, 0::2], dof[:, 1::2] = 2 * conn, 2 * conn + 1
    rows = np.repeat(dof, 18, axis=1).ravel()
    cols = np.tile(dof, (1, 18)).ravel()
    n_dofs = 2 * X.size * Z.size
    return sp.csr_matrix((Ke.ravel(), (rows, cols)), shape=(n_dofs, n_dofs))


def _edge_weights(X) -> np.ndarray:
    """Nodal (Lobatto / Simpson) weights [mm] of the bottom edge's nodes: h/6, 4h/6, h/6 per element."""
    w = np.zeros(X.size)
    for k in range(0, X.size - 1, 2):
        h = X[k + 2] - X[k]
        w[k:k + 3] += h * np.array([1.0, 4.0, 1.0]) / 6.0
    return w


def solve_plane_stress_beam(beam: PlaneStressBeam, law, *, length_per_mm: float = 1000.0, force_rtol: float = 1e-10,
                            max_iterations: int = 40) -> PlaneStressResult:
    """Solve the beam (module docstring) on the interface ``law``: any object with
    ``normal(u_N) -> (p_N, k_N)`` at closures u_N in its own length unit (``length_per_mm`` of
    them per mm; 1000 for the paper's µm moments), e.g. an
    :class:`~roughcontact.interface.InterfaceLaw` seated at ``beam.seating_pressure``.

    Newton with the consistent tangent at each load level; a step that leaves the law's table
    (ValueError) or fails to reduce the residual is halved. Converged when every residual force
    is below ``force_rtol`` of the larger of the applied load and the largest internal force. One BLAS thread: the dense systems are small, and
    threads only contend with the workflow's other jobs."""
    with threadpool_limits(limits=1, user_api="blas"):
        return _solve(beam, law, length_per_mm, force_rtol, max_iterations)


def _solve(beam, law, length_per_mm, force_rtol, max_iterations) -> PlaneStressResult:
    t0 = time.perf_counter()
    X, Z, conn, sizes = _mesh(beam)
    K = _stiffness(beam, X, Z, conn, sizes)
    n_dofs = K.shape[0]
    nx = X.size
    bottom_z = 2 * np.arange(nx) + 1  # u_z of the bottom row (k = 0)
    weights = _edge_weights(X) * beam.width  # mm²
    symmetry = 2 * (np.arange(Z.size) * nx)  # u_x at x = 0
    free = np.setdiff1d(np.arange(n_dofs), symmetry)
    top_centre_z = 2 * ((Z.size - 1) * nx) + 1
    Kf = K[free][:, free].tocsc()
    pos = np.full(n_dofs, -1)
    pos[free] = np.arange(free.size)
    bz = pos[bottom_z]
    load_dof = pos[top_centre_z]

    def interface(u):
        closure = -u[bz] * length_per_mm  # law units; moving down closes
        p, k = law.normal(closure)
        return np.asarray(p, dtype=float), np.asarray(k, dtype=float) * length_per_mm

    def residual(u, level):
        p, k = interface(u)
        r = Kf @ u
        r[bz] -= weights * p  # the interface pushes the beam up
        r[load_dof] += level / 2.0  # half the line load on the half beam, pressing down
        return r, p, k

    # The tangent is Kf + E diag(w k) Eᵀ, E selecting the bottom u_z: the bulk is factored once
    # with a reference spring k_ref on the bottom (it fixes the vertical translation) and each
    # Newton system is condensed onto the n_b bottom dofs: with G = Eᵀ A0⁻¹ E and
    # A0 = Kf + E diag(w k_ref) Eᵀ, (A0 + E Δ Eᵀ) x = b has Eᵀx = v from (I + G Δ) v = Eᵀ A0⁻¹ b,
    # then x = A0⁻¹ b − A0⁻¹ E Δ v (Δ = diag(w (k − k_ref))).
    k_ref = float(np.asarray(interface(np.zeros(free.size))[1]).max())
    A0 = (Kf + sp.csc_matrix((weights * k_ref, (bz, bz)), shape=Kf.shape)).tocsc()
    lu = spla.splu(A0, permc_spec="MMD_AT_PLUS_A")
    Ebz = np.zeros((free.size, bz.size))
    Ebz[bz, np.arange(bz.size)] = 1.0
    Y = lu.solve(Ebz)  # A0⁻¹ E
    G = Y[bz]

    def newton_step(r, k):
        delta = weights * (k - k_ref)
        y = lu.solve(-r)
        v = np.linalg.solve(np.eye(bz.size) + G * delta[None, :], y[bz])
        return y - Y @ (delta * v)

    u = np.zeros(free.size)
    iterations, seated = [], None
    for level in beam.levels:
        r, p, k = residual(u, level)
        for it in range(1, max_iterations + 1):
            # forces are judged against the applied load and the bulk's internal forces (the
            # round-off floor of the residual scales with the latter)
            tol = force_rtol * max(level / 2.0, float(np.max(np.abs(Kf @ u))))
            du = newton_step(r, k)
            norm0, step = np.max(np.abs(r)), 1.0
            while True:
                try:
                    r_new, p_new, k_new = residual(u + step * du, level)
                    norm = np.max(np.abs(r_new))
                except ValueError:  # beyond the law's table: a shorter step
                    norm = np.inf
                if norm < norm0 or norm <= tol:
                    break
                step *= 0.5
                if step < 1e-6:
                    raise RuntimeError(f"plane-stress Newton stalled at load {level:g} N (residual {norm0:.3g} N)")
            u, r, p, k = u + step * du, r_new, p_new, k_new
            if norm <= tol:
                break
        else:
            raise RuntimeError(f"plane-stress Newton did not converge at load {level:g} N")
        iterations.append(it)
        if seated is None:
            seated = u.copy()
    p, _ = interface(u)
    u_N = (u[bz] - seated[bz]) * 1000.0  # µm; negative = approach (moving down)
    eq = abs(float(np.sum(weights * p)) - beam.load / 2.0) / (beam.load / 2.0)
    return PlaneStressResult(beam=beam, x_mm=X.copy(), u_N_um=u_N, p_N=p, equilibrium_error=eq,
                             newton_iterations=np.array(iterations), dofs=int(free.size),
                             seconds=time.perf_counter() - t0)


def plane_stress_beam(run, n_x: int, n_z: int) -> PlaneStressBeam:
    """The 2D problem of a beam run (its ``spec``'s length, height, width [mm], E, nu [N/mm²],
    load and initial_load [N, full beam], increments and z_ratio; e.g. a
    :class:`~roughcontact.examples.beam.BeamRun`) on an ``n_x`` × ``n_z`` mesh of the half beam.
    The 3D mesh of the run (its n_x, n_z, elements, x_ratio) is not the 2D code's; a load patch
    is not modelled here and is refused."""
    spec = run.spec
    if getattr(spec, "load_patch", 0.0):
        raise ValueError("the 2D beam models the line load only, got a load patch of "
                         f"{spec.load_patch!r} mm")
    return PlaneStressBeam(length=spec.length, height=spec.height, width=spec.width, E=spec.E, nu=spec.nu,
                           load=spec.load, initial_load=spec.initial_load, increments=spec.increments,
                           z_ratio=spec.z_ratio, n_x=int(n_x), n_z=int(n_z))


def beam_run_law(run, seating_pressure: float):
    """The interface law of a beam run (its fields m00 [µm²], surface (the other moments, a
    mapping or (name, value) pairs), law, E_star [N/mm²], psi or Y; e.g. a
    :class:`~roughcontact.examples.beam.BeamRun`) as an
    :class:`~roughcontact.interface.InterfaceLaw` seated at ``seating_pressure``: the table over
    1e-12 … 100 N/mm² at the "plot" accuracy, as the engine's runs take it
    (:data:`roughcontact.examples.beam.PRESSURE_RANGE`), built here from the interface layer alone."""
    from ..contact import resolve_material
    from ..interface import InterfaceLaw, NormalLawTable
    from ..statistics import SpectralMoments

    surface = SpectralMoments(m00=run.m00, **dict(run.surface))
    if run.law == "elastic":
        law = {"E_star": run.E_star}
    else:
        by = {"Y": run.Y} if getattr(run, "Y", None) is not None else {"psi": run.psi}
        law = {"material": resolve_material(surface, E_star=run.E_star, **by)}
    table = NormalLawTable.build(surface, run.law, pressure_range=(1e-12, 100.0), accuracy="plot", **law)
    return InterfaceLaw.from_pressure(table, seating_pressure)


def reference_solution(run, mesh, coarse_mesh) -> dict:
    """The 2D solution of a beam run (:func:`plane_stress_beam`, :func:`beam_run_law`) on ``mesh``
    (n_x, n_z) and its change from ``coarse_mesh`` at the centre and the end (an estimate of its
    discretisation error): x_mm, u_N_um, p_N, u_N_centre_um, u_N_end_um, error_centre_um,
    error_end_um, dofs, seconds, newton_iterations, equilibrium_error."""
    fine, coarse = (plane_stress_beam(run, *m) for m in (mesh, coarse_mesh))
    law = beam_run_law(run, fine.seating_pressure)
    r, c = solve_plane_stress_beam(fine, law), solve_plane_stress_beam(coarse, law)
    return {"x_mm": r.x_mm, "u_N_um": r.u_N_um, "p_N": r.p_N, "u_N_centre_um": r.u_N_centre_um,
            "u_N_end_um": r.u_N_end_um, "error_centre_um": abs(r.u_N_centre_um - c.u_N_centre_um),
            "error_end_um": abs(r.u_N_end_um - c.u_N_end_um), "dofs": r.dofs, "seconds": r.seconds + c.seconds,
            "newton_iterations": int(r.newton_iterations.sum()), "equilibrium_error": r.equilibrium_error}
