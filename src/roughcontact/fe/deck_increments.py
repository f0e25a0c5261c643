"""A deck step's incrementation on the engine's incremental loading (docs/own-model.md,
"Incrementation").

A ``*STEP`` with ``*STATIC`` (initial increment Δt₀, period T, minimum Δt_min, maximum Δt_max,
``INC=`` N, ``DIRECT``) runs, in fractions of the step (Δt/T) and with the solver's load
levels λ = λ₀ + c·fraction (:mod:`.deck_run`, ``_plan``):

* **fixed** (``DIRECT``, or no Δt_max above Δt₀): the levels Δt₀/T, 2Δt₀/T, …, 1; a level
  whose Newton fails is halved (sub-steps, counted as cut-backs, not increments) down to
  Δt_min (``DIRECT``: six halvings, as without Δt_min). ``INC=`` below the number of levels is
  an error before anything is solved.
* **growing** (Δt_max > Δt₀, not ``DIRECT``): one solver level per step,
  :class:`~.solver.Stepping` with the first sub-step Δt₀, each converged sub-step doubling the
  next (the engine's step growth) up to Δt_max, each failure halving it down to Δt_min, every
  converged sub-step an increment of the result, at most N of them
  (:class:`~.solver.IncrementLimitError` beyond). ccx grows its increments from the number of
  Newton iterations instead (by 1.5); the bounds are the deck's either way.

The command line overrides the deck (:func:`with_incrementation`): ``--increments N`` runs
every step in N fixed increments (Δt₀ = T/N, no growth), ``--max-increments N`` sets every
step's ``INC=``; each override is a note naming the deck value it replaces.
"""

from __future__ import annotations

import dataclasses
import math

from .deck import MAX_INCREMENTS, Deck, Step
from .solver import IncrementLimitError, Stepping

__all__ = ["with_incrementation", "grows", "level_stepping", "check_fixed_counts", "IncrementsExceeded"]


class IncrementsExceeded(IncrementLimitError):
    """A step needs more increments than its ``INC=`` (or ``--max-increments``) allows."""

    def __init__(self, step: Step, message: str, level: float = math.nan, residual: float = math.nan):
        RuntimeError.__init__(self, f"step {step.index} ({step.where}): {message}")
        self.increment, self.level, self.residual, self.reason, self.step = 1, level, residual, message, step.index


def grows(step: Step) -> bool:
    """Whether the step's increments may grow: a maximum increment above the initial one, not DIRECT."""
    initial = step.fractions[0] * step.period
    return (not step.direct and step.maximum is not None and step.maximum > initial * (1.0 + 1e-12)
            and len(step.fractions) > 1)


def level_stepping(step: Step, c: float) -> Stepping:
    """The solver's :class:`~.solver.Stepping` of one level of ``step`` whose load level moves
    by c per unit step fraction (the whole step for a growing one, module docstring)."""
    if c == 0.0:
        return Stepping()
    scale = abs(c) / step.period
    smallest = None if step.direct or step.minimum is None else step.minimum * scale
    if not grows(step):
        return Stepping(smallest=smallest)
    return Stepping(first=abs(c) * step.fractions[0], largest=step.maximum * scale, smallest=smallest, record=True,
                    max_increments=step.max_increments)


def check_fixed_counts(deck: Deck) -> None:
    """IncrementsExceeded for the first fixed step with more increments than its INC= allows."""
    for step in deck.steps:
        n = len(step.fractions)
        if step.max_increments is not None and not grows(step) and n > step.max_increments:
            initial = step.fractions[0] * step.period
            raise IncrementsExceeded(step, f"its {n} fixed increments (period {step.period:g} / initial increment "
                                           f"{initial:g}) exceed the maximum number of increments "
                                           f"{step.max_increments} (*STEP, INC= or --max-increments): raise it, "
                                           "raise the initial increment, or give a larger maximum increment "
                                           "(*STATIC, 4th value) to let the increments grow")


def with_incrementation(deck: Deck, increments: int | None = None, max_increments: int | None = None) -> Deck:
    """The deck with the command line's ``--increments N`` (every step in N fixed increments)
    and ``--max-increments N`` (every step's INC=) in place of its own, a note per value
    replaced; the deck itself when both are None."""
    if increments is None and max_increments is None:
        return deck
    for name, value in (("--increments", increments), ("--max-increments", max_increments)):
        if value is not None and not 1 <= value <= MAX_INCREMENTS:
            raise ValueError(f"{name} {value}: must lie in 1 ... {MAX_INCREMENTS}")
    steps, notes = [], list(deck.notes)
    for step in deck.steps:
        change = {}
        if increments is not None:
            initial = step.fractions[0] * step.period
            was = f"initial increment {initial:g}" + (f", maximum increment {step.maximum:g}" if grows(step) else "")
            notes.append(f"{step.static_where}: --increments {increments} overrides *STATIC's {was}: the step runs "
                         f"{increments} fixed increments of {step.period / increments:g}")
            change.update(fractions=tuple((k + 1) / increments for k in range(increments - 1)) + (1.0,),
                          maximum=None)
        if max_increments is not None:
            if step.max_increments is not None and step.max_increments != max_increments:
                notes.append(f"{step.where}: --max-increments {max_increments} overrides *STEP, "
                             f"INC={step.max_increments}")
            change["max_increments"] = max_increments
        steps.append(dataclasses.replace(step, **change))
    return dataclasses.replace(deck, steps=tuple(steps), notes=tuple(notes))
