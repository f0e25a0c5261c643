"""Solving a deck step by step, and its results (the ``roughcontact fe run`` JSON).

Each ``*STEP`` is one call of :func:`.solver.solve` from the state the previous step ended in:
with u_s the displacements at the step's start, the step's unknown is v = u − u_s − λd, where d
holds the prescribed displacement increments (target − u_s on every supported dof; zero on the
interface, :mod:`.deck_model`) and λ runs through the step's increments to 1. Its equations are
the solver's with the dead load F_s − K u_s and the load pattern (F_e − F_s) − K d (F_s, F_e the
load vectors at the step's start and end: loads move linearly within a step), and the interface
laws continue from the committed states. The step's increments follow its *STATIC and INC=
(:mod:`.deck_increments`): fixed, or growing up to the maximum increment; the solver cuts an
increment back when Newton fails and reports it; a step that still fails raises
:class:`DeckConvergenceError` naming the step, its line and the increment.

Outputs per interface point (:meth:`DeckResult.interface_fields`): position x, y, z (master
side, deck length unit); u_N_um, the closure from the law's reference state (the seating
pressure) in µm, positive closes; p_N, and the tangential tractions t_1, t_2 along e_1 (the
law's lay direction projected onto the master face) and e_2 = n × e_1 (n from master to slave),
in the deck's stress unit; slip_1_um, slip_2_um, the plastic slips along e_1, e_2 in µm; status
stick/slip/open. The model-validity of the law is judged on the solved state: the largest
pressure of every interaction (:func:`DeckResult.validity_warnings`).

A law file read for a deck is checked against it first (:func:`check_law_file`): its E* against
the deck's *ELASTIC (eq. (42)), its length unit against the deck's stresses, its lay directions
against the contact faces; a law for an interaction the deck lacks is a note.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..interface import friction
from .deck_model import DeckProblem, surface_material
from .laws import LENGTH_UNITS, UNIT_RTOL, LawError
from .deck_increments import IncrementsExceeded, check_fixed_counts, grows, level_stepping
from .solver import BELOW_SMALLEST, ContactModel, ConvergenceError, IncrementLimitError, NewtonOptions, Stepping, solve

__all__ = ["DeckIncrement", "DeckResult", "DeckConvergenceError", "run_deck", "run_deck_file", "STATUS_NAMES",
           "check_law_file", "law_notes", "SOLID_E_STAR_PA"]

#: friction.STICK, SLIP, OPEN by name
STATUS_NAMES = ("stick", "slip", "open")
#: E* [Pa] of two solids in contact, from the softest elastomers (E ≈ 1 MPa) to diamond on
#: diamond (E = 1.05 TPa, ν = 0.1: E* = 0.53 TPa; on a rigid body 1.06 TPa). A deck's E*
#: outside it, read in N/length_unit² (the law file's units, forces in N), means a wrong
#: length_unit: one of the factors 10⁶ that separate N/m², N/mm², N/µm², N/nm².
SOLID_E_STAR_PA = (1e6, 2e12)


class DeckConvergenceError(ConvergenceError):
    """Newton failed in a step even after the cut-backs: the step, its line and the increment."""

    def __init__(self, step, exc: ConvergenceError, increment: int, fraction: float):
        hint = (" (a body free to move as a rigid body? a frictionless interface holds nothing tangentially: "
                "support the bodies in every direction)" if "singular" in exc.reason else "")
        of = "" if grows(step) else f" of {len(step.fractions)}"
        reason, below, _ = exc.reason.partition(BELOW_SMALLEST)  # the solver's step is in load-level units
        floor = (f": a further cut-back would fall below the minimum increment {step.minimum:g} of *STATIC at "
                 f"{step.static_where}" if below else "")
        RuntimeError.__init__(self, f"step {step.index} ({step.where}): no convergence at increment {increment}"
                                    f"{of} (step fraction {fraction:.6g}): {reason}{hint}; "
                                    f"residual {exc.residual:.3e} after the allowed cut-backs{floor}")
        self.increment, self.level, self.residual, self.reason = exc.increment, exc.level, exc.residual, exc.reason
        self.step = step.index


@dataclass(frozen=True, eq=False)
class DeckIncrement:
    """A converged increment: step (1-based), the fraction of the step and the deck time, the
    total displacements u (3N,) [deck length], the interface states, tractions (t_1, t_2, σ_N)
    and status, Newton iterations, cut-backs and wall time."""

    step: int
    fraction: float
    time: float
    u: np.ndarray
    state: np.ndarray
    tractions: np.ndarray
    status: np.ndarray
    iterations: int
    cutbacks: int
    seconds: float


@dataclass(frozen=True, eq=False)
class DeckResult:
    """Every converged increment of a deck run, the problem, the element family and the time."""

    problem: DeckProblem
    increments: tuple[DeckIncrement, ...]
    family: str
    seconds: float

    @property
    def n_dofs(self) -> int:
        """Unknowns of the bulk and the interface (free dofs of the last step)."""
        return int(3 * self.problem.mesh.n_nodes - len(self.problem.supports[-1]))

    def step_end(self, step: int) -> DeckIncrement:
        """The last increment of step ``step`` (1-based)."""
        return [inc for inc in self.increments if inc.step == step][-1]

    def _um_per_law_unit(self) -> np.ndarray:
        """Per point: µm per unit of its law's length (its moments' unit)."""
        out = np.empty(self.problem.points.n_points)
        for material, a, b in self.problem.materials.parts:
            name = self.problem.interaction_of_point[a]
            out[a:b] = 10.0 ** (LENGTH_UNITS[self.problem.laws.interactions[name].moments_unit] - LENGTH_UNITS["um"])
        return out

    def interface_fields(self, inc: DeckIncrement) -> dict[str, np.ndarray]:
        """Per interface point (module docstring): x, y, z, u_N_um, p_N, t_1, t_2, slip_1_um,
        slip_2_um, status (0 stick, 1 slip, 2 open)."""
        x, s, um = self.problem.points.x, inc.state, self._um_per_law_unit()
        return {"x": x[:, 0], "y": x[:, 1], "z": x[:, 2], "u_N_um": s[:, friction.U_N] * um,
                "p_N": s[:, friction.T_N], "t_1": s[:, friction.T_X], "t_2": s[:, friction.T_Y],
                "slip_1_um": s[:, friction.UP_X] * um, "slip_2_um": s[:, friction.UP_Y] * um,
                "status": inc.status.astype(np.int32)}

    def node_sets(self, inc: DeckIncrement) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """{deck *NSET name: (deck node ids, u (n, 3))}: the nodes of the set in the model (a
        mid-edge node replaced by the cubic elements interpolated along its edge)."""
        dm, U = self.problem.dm, inc.u.reshape(-1, 3)
        out = {}
        for name, ids in dm.deck.nsets.items():
            idx = dm.engine_index(ids)
            keep = (idx >= 0) | np.isin(ids, list(dm.replaced))
            u = np.zeros((int(keep.sum()), 3))
            for j, (nid, i) in enumerate(zip(ids[keep].tolist(), idx[keep].tolist())):
                if i >= 0:
                    u[j] = U[i]
                else:
                    nodes, w = dm.replaced[nid]
                    u[j] = w @ U[nodes]
            out[name] = (ids[keep], u)
        return out

    def validity_warnings(self) -> list[str]:
        """The law's model-validity warnings at the largest pressure each interaction reached
        (contact.at_pressure on that pressure, contact.validity's criteria); none for a BEM law
        (the law file's ``normal: {table: ...}``), which holds in its table's range."""
        import warnings

        from ..contact.at_pressure import contact_at_pressure
        from ..interface.normal_law import LEVELS

        out = []
        p = np.max(np.stack([inc.state[:, friction.T_N] for inc in self.increments]), axis=0)
        for material, a, b in self.problem.materials.parts:
            name = self.problem.interaction_of_point[a]
            law = material.normal
            p_max = float(p[a:b].max())
            if not p_max > 0.0 or law.table.level not in LEVELS:  # a BEM law: the solver judges its range
                continue
            kw = ({"E_star": law.table.E_star} if law.table.material is None else {"material": law.table.material})
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # returned in r.warnings, said once below
                r = contact_at_pressure(law.table.surface, [p_max], accuracy="plot", validity="warn", **kw)
            out += [f"interaction {name}: at the largest solved pressure {p_max:.4g}: {w.split(': ', 1)[-1]}"
                    for w in r.warnings]
        return list(dict.fromkeys(out))

    def summary(self, *, node_sets: bool = True) -> dict:
        """The JSON of ``roughcontact fe run`` (module docstring; docs/own-model.md)."""
        pts = self.problem.points
        steps = []
        for step in self.problem.dm.deck.steps:
            incs = [inc for inc in self.increments if inc.step == step.index]
            end = incs[-1]
            f = self.interface_fields(end)
            entry = {"step": step.index, "time": end.time, "increments": len(incs),
                     "fractions": [float(i.fraction) for i in incs],
                     "newton_iterations": [int(i.iterations) for i in incs],
                     "cutbacks": int(sum(i.cutbacks for i in incs))}
            if node_sets:
                entry["node_sets"] = {name: {"nodes": ids.tolist(), "u": u.tolist()}
                                      for name, (ids, u) in self.node_sets(end).items()}
            entry["interface"] = {**{k: v.tolist() for k, v in f.items() if k != "status"},
                                  "status": [STATUS_NAMES[int(v)] for v in f["status"]]}
            steps.append(entry)
        return {
            "dofs": self.n_dofs, "interface_points": int(pts.n_points), "seconds": self.seconds,
            "newton_iterations": int(sum(i.iterations for i in self.increments)),
            "cutbacks": int(sum(i.cutbacks for i in self.increments)),
            "elements": self.family, "deck": self.problem.dm.deck.path,
            "interface_axes": {"interaction": self.problem.interaction_of_point.tolist(),
                               "e_1": pts.frames[:, 0].tolist(), "e_2": pts.frames[:, 1].tolist(),
                               "n": pts.frames[:, 2].tolist(),
                               "definition": "e_1: the law's lay_direction projected onto the master face; "
                                             "e_2 = n x e_1; n: the master face's normal, towards the slave"},
            "E_star": dict(self.problem.E_star),
            "steps": steps,
            "notes": [*self.problem.dm.deck.notes, *law_notes(self.problem.dm.deck, self.problem.laws)],
            "units": {"x, y, z, u": f"{self.problem.laws.length_unit} (the deck's length unit)",
                      "u_N_um": "um, closure from the law's reference state (seating pressure), positive closes",
                      "slip_1_um, slip_2_um": "um, plastic slips along e_1, e_2",
                      "p_N, t_1, t_2, E_star": "the deck's stress unit (that of its *ELASTIC moduli)",
                      "seconds": "s"},
        }


def _parallel(z, P) -> float | None:
    """c with z = c P (to 1e-12 relative), or None."""
    pp = float(P @ P)
    if pp == 0.0:
        return None
    c = float(z @ P) / pp
    return c if np.linalg.norm(z - c * P) <= 1e-12 * max(np.linalg.norm(z), abs(c) * np.sqrt(pp)) else None


def _plan(problem: DeckProblem, s: int, u: np.ndarray, F_start: np.ndarray):
    """One solve from step s: the steps it covers, its supports, the dead load part, the load
    pattern (forces, prescribed displacements) and the levels [(step, fraction, λ, λ at the
    step's start, dλ per unit fraction)] (a growing step, :mod:`.deck_increments`: one level).

    Steps whose load increments (forces and prescribed displacements together) are multiples
    c_k of one pattern, on the same supports, are one solve along λ (the solver's secant
    predictor and factorisation carry over); a first step of one increment whose increment is
    not such a multiple becomes the solve's dead load, reached at λ = 0 (e.g. a seating load
    before a load that goes up and down). Otherwise a step is a solve of its own."""
    steps, n = problem.dm.deck.steps, len(u)
    sup = problem.supports[s]
    fixed = np.array(sorted(sup), dtype=np.int64)
    d_first = np.zeros(n)
    d_first[fixed] = [sup[j] - u[j] for j in fixed.tolist()]

    def z(k):
        if k == s:
            return np.concatenate([problem.loads[k] - F_start, d_first])
        d = np.zeros(n)
        d[fixed] = [problem.supports[k][j] - problem.supports[k - 1][j] for j in fixed.tolist()]
        return np.concatenate([problem.loads[k] - problem.loads[k - 1], d])

    same = [k for k in range(s + 1, len(steps)) if set(problem.supports[k]) == set(sup)]
    following = []
    for k in range(s + 1, len(steps)):
        if k not in same:
            break
        following.append(k)
    pattern = z(following[0]) if following else z(s)
    c_first = _parallel(z(s), pattern) if following else 1.0
    dead_first = c_first is None
    if dead_first and len(steps[s].fractions) != 1:
        following, pattern, c_first, dead_first = [], z(s), 1.0, False
    covered, levels, lam = [s], [], 0.0
    if dead_first:
        levels.append((s, 1.0, 0.0, 0.0, 0.0))
    else:
        levels += [(s, f, c_first * f, 0.0, c_first) for f in _fractions(steps[s])]
        lam = c_first
    for k in following:
        c = _parallel(z(k), pattern)
        if c is None:
            break
        levels += [(k, f, lam + c * f, lam, c) for f in _fractions(steps[k])]
        lam += c
        covered.append(k)
    dead_z = z(s) if dead_first else np.zeros(2 * n)
    return covered, fixed, dead_z, pattern, levels


def _fractions(step) -> tuple[float, ...]:
    """The fractions the solver is given as levels: every fixed increment, or a growing step's end."""
    return (1.0,) if grows(step) else step.fractions


def run_deck(problem: DeckProblem, options: NewtonOptions | None = None, progress=None) -> DeckResult:
    """Solve every step of the deck (module docstring; :func:`_plan` groups steps that share one
    load path). ``progress(step, n_steps, k, n, increment)`` after every converged increment."""
    t0 = time.perf_counter()
    deck, K = problem.dm.deck, problem.stiffness
    check_fixed_counts(deck)
    n = K.shape[0]
    u, F_start, materials = np.zeros(n), np.zeros(n), problem.materials
    start_time = np.concatenate([[0.0], np.cumsum([st.period for st in deck.steps])])
    out, s = [], 0
    while s < len(deck.steps):
        covered, fixed, dead_z, pattern, levels = _plan(problem, s, u, F_start)
        dead_u = dead_z[n:]
        # the node coordinates give the linear solvers their nested-dissection ordering
        model = ContactModel(K, problem.points, materials, fixed, pattern[:n] - K @ pattern[n:],
                             F_start + dead_z[:n] - K @ (u + dead_u), coordinates=problem.mesh.points)
        counts = {k: None if grows(deck.steps[k]) else sum(1 for lv in levels if lv[0] == k) for k in covered}
        done = {k: 0 for k in covered}  # converged increments of each step so far

        def report(j, m, inc, levels=levels, counts=counts, done=done):
            k = levels[j - 1][0]
            done[k] += 1
            if progress is not None:
                progress(k + 1, len(deck.steps), done[k], counts[k], inc)

        try:
            specs = [level_stepping(deck.steps[lv[0]], lv[4]) for lv in levels]
            plain = all(spec == Stepping() for spec in specs)  # every level in one step, cut back on failure
            sol = solve(model, [lv[2] for lv in levels], options, report, **({} if plain else {"stepping": specs}))
        except ConvergenceError as exc:
            k, f, lam, lam0, c = levels[exc.increment - 1]
            step = deck.steps[k]
            f = (exc.level - lam0) / c if grows(step) and c != 0.0 else f
            if isinstance(exc, IncrementLimitError):
                raise IncrementsExceeded(step, f"*STEP, INC={step.max_increments} (the maximum number of increments, "
                                               f"or --max-increments) reached at step fraction {f:.6g}: the step needs "
                                               f"more increments; raise it, or the maximum increment {step.maximum:g} "
                                               f"(*STATIC at {step.static_where})", exc.level, exc.residual) from None
            raise DeckConvergenceError(step, exc, done[k] + 1, f) from None
        j = 0
        for inc in sol.increments:
            k, f, lam, lam0, c = levels[j]
            if inc.level == lam:  # the level's own increment (the solver lands on it exactly)
                j += 1
            else:  # a growing step's sub-step
                f = (inc.level - lam0) / c
            out.append(DeckIncrement(k + 1, f, start_time[k] + f * deck.steps[k].period,
                                     u + dead_u + inc.u + inc.level * pattern[n:], inc.state, inc.tractions,
                                     inc.status, inc.iterations, inc.cutbacks, inc.seconds))
        u = out[-1].u
        materials = problem.materials.resumed(sol.final.state)
        F_start = problem.loads[covered[-1]]
        s = covered[-1] + 1
    return DeckResult(problem, tuple(out), problem.dm.family, time.perf_counter() - t0)


def check_law_file(deck, laws) -> None:
    """A law file checked against the deck it is read for (issue 29); LawError naming the law
    file, the key and both numbers otherwise:

    * a stated ``E_star`` within 1 % (:data:`~.laws.UNIT_RTOL`) of the deck's own E*, eq. (42)
      of the *ELASTIC of the pair's two bodies (where each surface lies on one material);
    * the length unit: the law file's stresses are N/length_unit² (forces in N), so the
      deck's E* in Pa must be that of solids (:data:`SOLID_E_STAR_PA`) — unless the file
      states its ``stress_unit``, which laws.law_file_from_dict has checked against the length
      unit already (the escape for a genuinely softer or stiffer pair).

    A law file of mm with a deck of m (or the reverse) otherwise runs with a length scale wrong
    by 10³ and gives closures of the wrong size and even sign (issue 29: −6.0 µm for +1.35 µm)."""
    from ..asperity import effective_modulus

    for pair in deck.contact_pairs:
        law = laws.interactions.get(pair.interaction)
        a, b = surface_material(deck, pair.slave), surface_material(deck, pair.master)
        if law is None or a is None or b is None:
            continue  # a missing law, or bodies of several materials: deck_model names them
        E_deck = effective_modulus(a.E, a.nu, b.E, b.nu)  # eq. (42)
        key = f"{laws.where}: interactions.{pair.interaction}"
        if law.E_star is not None and abs(law.E_star / E_deck - 1.0) > UNIT_RTOL:
            raise LawError(f"{key}.E_star: {law.E_star:.6g} differs by {100 * abs(law.E_star / E_deck - 1):.3g} % from "
                           f"the deck's E* = {E_deck:.6g} (eq. (42) of *ELASTIC {a.name} at {a.where} and {b.name} at "
                           f"{b.where}, the deck's stress unit): omit E_star to use the deck's, or correct the unit")
        if laws.stress_unit is None:
            lo, hi = SOLID_E_STAR_PA
            pa = E_deck * laws.pascal_per_stress_unit
            if not lo <= pa <= hi:
                guess = [u for u, k in LENGTH_UNITS.items() if u != "µm" and lo <= E_deck * 10.0 ** (-2 * k) <= hi]
                hint = f"; with length_unit {guess[0]} it is {E_deck * 10.0 ** (-2 * LENGTH_UNITS[guess[0]]):.3g} Pa" if guess else ""
                raise LawError(f"{laws.where}: length_unit {laws.length_unit}: the deck's stresses are then "
                               f"N/{laws.length_unit}^2 (forces in N), and its E* = {E_deck:.6g} (eq. (42), *ELASTIC at "
                               f"{a.where}, {b.where}) is {pa:.3g} Pa, outside {lo:g} ... {hi:g} Pa of solids{hint}: "
                               "give the deck's length unit (or stress_unit, for bodies this soft or stiff)")


def law_notes(deck, laws) -> list[str]:
    """Notes on a law file read for a deck: a law for an interaction the deck does not define is
    not used (a note, not an error: one law file may serve several decks)."""
    return [f"{laws.where}: interactions.{name}: the deck has no *SURFACE INTERACTION, NAME={name}; its law "
            "is not used" for name in laws.interactions if name not in deck.interactions]


def run_deck_file(deck, laws, family: str = "quadratic", options: NewtonOptions | None = None,
                  progress=None, *, increments: int | None = None, max_increments: int | None = None) -> DeckResult:
    """Read, mesh, assemble and solve: ``deck`` a path or a :class:`~.deck.Deck`, ``laws`` a
    path or a :class:`~.laws.LawFile`. A law file read from a path is checked against the deck
    (:func:`check_law_file`; a LawFile built by the library's examples, whose E* may be chosen
    apart from the bodies', e.g. ``fe punch --E-star``, is not); every law's lay direction is, where
    deck_model builds the interface points. ``increments``, ``max_increments``: the command
    line's overrides of every step's incrementation (:func:`.deck_increments.with_incrementation`)."""
    from .deck import Deck, read_deck
    from .deck_mesh import deck_mesh
    from .deck_increments import with_incrementation
    from .deck_model import deck_problem
    from .laws import LawFile, read_law_file

    t0 = time.perf_counter()
    deck = with_incrementation(deck if isinstance(deck, Deck) else read_deck(deck), increments, max_increments)
    if not isinstance(laws, LawFile):
        laws = read_law_file(laws)
        check_law_file(deck, laws)
    result = run_deck(deck_problem(deck_mesh(deck, family), laws), options, progress)
    return DeckResult(result.problem, result.increments, result.family, time.perf_counter() - t0)
