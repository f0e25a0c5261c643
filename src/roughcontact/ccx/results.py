"""What a CalculiX run of a rewritten deck printed, as the JSON of ``roughcontact fe run --json``
(:meth:`roughcontact.fe.deck_run.DeckResult.summary`; docs/ccx.md).

Read from the job's files: the ``.dat`` prints the rewritten deck asks for (:mod:`.deck_rewrite`:
``*NODE PRINT`` U of every node set, ``*EL PRINT`` SDV of every pair's user elements), the
``.sta`` summary (increments, attempts, iterations) and ccx's output ("number of equations").
CalculiX prints 7 significant digits (format e13.6): the JSON's values carry that precision.

Per interface point (an integration point of a user element, in element order): x, y, z (on the master
face), u_N_um, p_N, t_1, t_2, slip_1_um, slip_2_um and status as the engine's, from the law's
state the element stored (rc_ccx_element.f90: 1-9 friction's state, 13 the status); the frame
(e_1, e_2, n) from :func:`roughcontact.fe.interface_element.face_frame`, the engine's.
"""

from __future__ import annotations

import re

import numpy as np

from ..fe.deck_run import STATUS_NAMES
from ..fe.interface_element import face_frame
from ..fe.laws import LENGTH_UNITS
from ..interface import friction
from .deck_rewrite import USER_TYPES

__all__ = ["Print", "prints", "node_prints", "step_end_times", "sta_increments", "summary"]

_HEADER = re.compile(r"^\s*(.+?)\s+for set\s+(\S+)\s+and time\s+(\S+)\s*$")
#: the status code of rc_ccx_element.f90 past the heavy end of the table (roughcontact_law RC_BEYOND)
_BEYOND = -2


class Print(tuple):
    """One print of a .dat file: (kind, set name, total time, rows of numbers)."""

    kind = property(lambda self: self[0])
    set = property(lambda self: self[1])
    time = property(lambda self: self[2])
    rows = property(lambda self: self[3])


def prints(dat: str) -> list[Print]:
    """Every print block of a .dat text, in order (a header line ``… for set S and time T``, then
    its rows of numbers up to the next header)."""
    out, current = [], None
    for line in dat.splitlines():
        m = _HEADER.match(line)
        if m:
            current = Print((m.group(1).strip(), m.group(2).upper(), float(m.group(3)), []))
            out.append(current)
            continue
        parts = line.split()
        if current is not None and parts:
            try:
                current.rows.append([float(v) for v in parts])
            except ValueError:
                current = None
    return out


def node_prints(dat: str, node_set: str) -> list[tuple[float, dict[int, np.ndarray]]]:
    """Every displacement print of ``node_set`` in a .dat text: [(time, {node: (ux, uy, uz)})]."""
    return [(p.time, {int(r[0]): np.array(r[1:4]) for r in p.rows if len(r) == 4})
            for p in prints(dat) if p.kind.startswith("displacements") and p.set == node_set.upper()]


def step_end_times(deck) -> list[float]:
    """The total time at the end of each step (CalculiX's clock: the steps' periods added)."""
    return np.cumsum([s.period for s in deck.steps]).tolist()


def _at(printed, kind: str, name: str, t: float):
    hits = [p for p in printed if p.kind.startswith(kind) and p.set == name.upper()
            and abs(p.time - t) <= 1e-6 * max(1.0, abs(t))]
    return hits[-1] if hits else None


def sta_increments(sta: str) -> list[tuple[int, int, int, int, float]]:
    """Rows (step, increment, attempt, iterations, total time) of a .sta file."""
    rows = []
    for line in sta.splitlines():
        parts = line.split()
        if len(parts) == 7 and all(p.isdigit() for p in parts[:4]):
            rows.append((int(parts[0]), int(parts[1]), int(parts[2]), int(parts[3]), float(parts[4])))
    return rows


def _points(deck, pairs):
    """Positions (n, 3), frames (n, 3, 3) and areas w_q dA_q (n,) of every user element's Gauss
    points, in element order (rc_ccx_element.f90's geometry)."""
    xs, frames, areas = [], [], []
    for p in pairs:
        face = USER_TYPES[p.face].face
        xi, w = USER_TYPES[p.face].rule()
        nf = face.n_nodes
        A = deck.coords[deck.node_index(p.nodes[:, :nf].ravel())].reshape(-1, nf, 3)
        R, dA = face_frame(face, A, xi, p.constants.lay)
        xs.append(np.einsum("qa,cak->cqk", face.shape(xi), A).reshape(-1, 3))
        frames.append(R.reshape(-1, 3, 3))
        areas.append((dA * w[None, :]).ravel())
    return np.concatenate(xs), np.concatenate(frames), np.concatenate(areas)


def summary(deck, laws, pairs, dat: str, sta: str, log: str, seconds: float, *, extra: dict | None = None) -> dict:
    """The ``fe run --json`` contract of a ccx run (module docstring). RuntimeError naming the
    step when a print is missing (ccx stopped before the step's end)."""
    printed = prints(dat)
    x, frames, areas = _points(deck, pairs)
    counts = [p.ids.size * USER_TYPES[p.face].n_points for p in pairs]  # interface points per pair
    um = np.concatenate([np.full(n,
                                 10.0 ** (LENGTH_UNITS[laws.interactions[p.interaction].moments_unit] - LENGTH_UNITS["um"]))
                         for n, p in zip(counts, pairs)])
    increments = sta_increments(sta)
    steps = []
    for step, t_end in zip(deck.steps, step_end_times(deck)):
        incs = [r for r in increments if r[0] == step.index]
        t_start = t_end - step.period
        node_sets = {}
        for name in deck.nsets:
            p = _at(printed, "displacements", name, t_end)
            if p is None:
                raise RuntimeError(f"ccx did not finish step {step.index} (no print of {name} at time {t_end:g})")
            node_sets[name] = {"nodes": [int(r[0]) for r in p.rows], "u": [r[1:4] for r in p.rows]}
        states = []
        for pe in pairs:
            p = _at(printed, "internal state variables", pe.elset, t_end)
            if p is None:
                raise RuntimeError(f"ccx did not finish step {step.index} (no state print of {pe.elset} at time {t_end:g})")
            states += [r[2:] for r in p.rows]
        s = np.array(states)
        status = s[:, 12].round().astype(int)
        steps.append({
            "step": step.index, "time": t_end, "increments": len({r[1] for r in incs}),
            "fractions": [(r[4] - t_start) / step.period for r in incs],
            "newton_iterations": [r[3] for r in incs], "cutbacks": int(sum(r[2] - 1 for r in incs)),
            "node_sets": node_sets,
            "interface": {"x": x[:, 0].tolist(), "y": x[:, 1].tolist(), "z": x[:, 2].tolist(),
                          "u_N_um": (s[:, friction.U_N] * um).tolist(), "p_N": s[:, friction.T_N].tolist(),
                          "t_1": s[:, friction.T_X].tolist(), "t_2": s[:, friction.T_Y].tolist(),
                          "slip_1_um": (s[:, friction.UP_X] * um).tolist(),
                          "slip_2_um": (s[:, friction.UP_Y] * um).tolist(),
                          "D": s[:, friction.DISSIPATION].tolist(),
                          "status": ["beyond" if v == _BEYOND else STATUS_NAMES[v] for v in status]},
        })
    m = re.search(r"number of equations\s*\n\s*(\d+)", log)
    return {
        "dofs": int(m.group(1)) if m else None, "interface_points": int(x.shape[0]), "seconds": seconds,
        "newton_iterations": int(sum(r[3] for r in increments)), "cutbacks": int(sum(r[2] - 1 for r in increments)),
        "elements": "ccx: the deck's elements; interface: " + ", ".join(sorted({p.user_type for p in pairs})),
        "deck": deck.path, "interface_area": areas.tolist(),
        "interface_axes": {"interaction": [p.interaction for n, p in zip(counts, pairs) for _ in range(n)],
                           "e_1": frames[:, 0].tolist(), "e_2": frames[:, 1].tolist(), "n": frames[:, 2].tolist(),
                           "definition": "e_1: the law's lay_direction projected onto the master face; "
                                         "e_2 = n x e_1; n: the master face's normal, towards the slave"},
        "E_star": {p.interaction: p.E_star for p in pairs},
        "steps": steps,
        "units": {"x, y, z, u": f"{laws.length_unit} (the deck's length unit)",
                  "u_N_um": "um, closure from the law's reference state (seating pressure), positive closes",
                  "slip_1_um, slip_2_um": "um, plastic slips along e_1, e_2",
                  "p_N, t_1, t_2, E_star": "the deck's stress unit (that of its *ELASTIC moduli)",
                  "D": "dissipated energy per unit area (friction's state D): the deck's stress unit x the law's length unit",
                  "interface_area": "the deck's length unit squared: the area each interface point stands for",
                  "seconds": "s"},
        **(extra or {}),
    }
