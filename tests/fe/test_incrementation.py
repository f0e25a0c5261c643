"""A deck's incrementation honoured by ``fe run`` (issue 31; roughcontact.fe.deck_increments):

* *STATIC 0.25, 1, 0.01, 0.5: the first increment 0.25, each converged one doubling the next up
  to the maximum 0.5, landing on the period: 0.25, 0.75, 1 (the schedule's closed form); the
  answer of a frictionless elastic interface (path-independent) equals the fixed-increment run's;
* *STEP, INC=: a step needing more increments is a clear error (fixed: before solving;
  growing: when reached), naming the step, its line and the value;
* *STATIC, DIRECT: exactly the fixed levels, its minimum and maximum increments one note each;
* the minimum increment: the smallest step a cut-back may reach (then an error naming it);
* --increments / --max-increments override the deck, each with a note;
* an unsupported value (SOLVER=, a fifth *STATIC value) gets one note.
"""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact.fe.deck import read_deck
from roughcontact.fe.deck_increments import IncrementsExceeded
from roughcontact.fe.deck_run import DeckConvergenceError, run_deck_file
from roughcontact.fe.solver import NewtonOptions

FIXED = "*STATIC\n0.25, 1.\n"


@pytest.fixture
def deck_with(block_deck, write_deck):
    """deck_with(static, step="*STEP", name) -> path of the one-element block deck (1 N/mm² on
    the top) with ``static`` in place of its *STATIC block and ``step`` of its *STEP line."""
    text = block_deck(n=1, steps=({"pressure": 1.0, "increments": 4},))
    assert text.count(FIXED) == 1 and text.count("*STEP\n") == 1

    def make(static, step="*STEP", name="model.inp"):
        return write_deck(text.replace(FIXED, static).replace("*STEP\n", step + "\n"), name)
    return make


def fractions(result):
    return [inc.fraction for inc in result.increments]


def line_of(path, needle):
    return next(i for i, line in enumerate(open(path).read().splitlines(), start=1) if needle in line)


def test_growing_increments_start_at_the_initial_and_stay_below_the_maximum(deck_with, law_file):
    law = law_file()
    said = []
    grown = run_deck_file(deck_with("*STATIC\n0.25, 1., 0.01, 0.5\n"), law,
                          progress=lambda step, n_steps, k, n, inc: said.append((step, n_steps, k, n)))
    assert fractions(grown) == [0.25, 0.75, 1.0]
    assert said == [(1, 1, 1, None), (1, 1, 2, None), (1, 1, 3, None)]  # growing: the count is not known ahead  # 0.25, then 2 x 0.25 = 0.5 (the cap), then the rest
    steps = np.diff([0.0, *fractions(grown)])
    assert steps[0] == 0.25 and steps.max() <= 0.5
    assert grown.summary()["steps"][0]["fractions"] == [0.25, 0.75, 1.0]
    assert [inc.time for inc in grown.increments] == [0.25, 0.75, 1.0]
    # a frictionless elastic interface is path-independent: the same answer as the fixed increments
    fixed = run_deck_file(deck_with(FIXED, name="fixed.inp"), law)
    assert fractions(fixed) == [0.25, 0.5, 0.75, 1.0]
    u, v = grown.increments[-1].u, fixed.increments[-1].u
    np.testing.assert_allclose(u, v, rtol=0, atol=1e-9 * np.abs(v).max())
    np.testing.assert_allclose(grown.increments[0].u, fixed.increments[0].u, rtol=0, atol=1e-9 * np.abs(v).max())


def test_a_maximum_larger_than_the_period_lets_one_step_double_to_the_end(deck_with, law_file):
    result = run_deck_file(deck_with("*STATIC\n0.125, 1., , 10.\n"), law_file())
    assert fractions(result) == [0.125, 0.375, 0.875, 1.0]  # steps 1/8, 1/4, 1/2, then the rest 1/8


def test_inc_below_the_fixed_increments_is_an_error_before_solving(deck_with, law_file, monkeypatch):
    import roughcontact.fe.deck_run as deck_run

    monkeypatch.setattr(deck_run, "solve", lambda *a, **k: pytest.fail("solved"))
    path = deck_with(FIXED, step="*STEP, INC=2")
    with pytest.raises(IncrementsExceeded) as err:
        run_deck_file(path, law_file())
    assert str(err.value).startswith(f"step 1 ({path}:{line_of(path, 'INC=2')}): its 4 fixed increments (period 1 / "
                                      "initial increment 0.25) exceed the maximum number of increments 2")


def test_inc_reached_by_growing_increments_is_an_error_naming_it(deck_with, law_file):
    path = deck_with("*STATIC\n0.25, 1., 0.01, 0.5\n", step="*STEP, INC=2")
    with pytest.raises(IncrementsExceeded) as err:
        run_deck_file(path, law_file())
    said = str(err.value)
    assert said.startswith(f"step 1 ({path}:{line_of(path, 'INC=2')}): *STEP, INC=2 (the maximum number of increments")
    assert "reached at step fraction 0.75" in said and "the maximum increment 0.5" in said
    ok = run_deck_file(deck_with("*STATIC\n0.25, 1., 0.01, 0.5\n", step="*STEP, INC=3", name="three.inp"), law_file())
    assert fractions(ok) == [0.25, 0.75, 1.0]


def test_direct_runs_exactly_the_fixed_levels_and_notes_what_it_ignores(deck_with, law_file):
    path = deck_with("*STATIC, DIRECT\n0.25, 1., 0.01, 0.5\n")
    result = run_deck_file(path, law_file())
    assert fractions(result) == [0.25, 0.5, 0.75, 1.0]
    where = f"{path}:{line_of(path, '0.25, 1., 0.01')}"
    notes = [n for n in result.summary()["notes"] if "*STATIC" in n]
    assert notes == [f"{where}: *STATIC the minimum increment 0.01 ignored: DIRECT runs 4 fixed increments "
                     "(period / initial increment), each halved when Newton fails (up to six times)",
                     f"{where}: *STATIC the maximum increment 0.5 ignored: DIRECT runs 4 fixed increments "
                     "(period / initial increment), each halved when Newton fails (up to six times)"]


def test_honoured_values_get_no_note_and_unsupported_ones_one_each(deck_with):
    d = read_deck(deck_with("*STATIC\n0.25, 1., 0.01, 0.5\n", step="*STEP, INC=7"))
    assert not [n for n in d.notes if "STATIC" in n or "INC" in n]
    assert (d.steps[0].minimum, d.steps[0].maximum, d.steps[0].max_increments, d.steps[0].direct) == (0.01, 0.5, 7, False)
    path = deck_with("*STATIC, SOLVER=PARDISO\n0.25, 1., 0.01, 0.5, 3.\n", name="odd.inp")
    notes = [n for n in read_deck(path).notes if "STATIC" in n]
    assert notes == [f"{path}:{line_of(path, 'SOLVER=')}: *STATIC, SOLVER=PARDISO ignored: the engine chooses its own "
                     "linear solver",
                     f"{path}:{line_of(path, '0.5, 3.')}: *STATIC field 5 3 ignored: the step runs 4 fixed increments "
                     "(period / initial increment), each halved when Newton fails (up to six times)"]


@pytest.mark.parametrize("values, rule", [("0.25, 1., 0.5", "at most the initial increment 0.25"),
                                          ("0.25, 1., 0.01, 0.1", "at least the initial increment 0.25"),
                                          ("0.25, 1., -1.", "at most the initial increment 0.25")])
def test_inconsistent_minimum_or_maximum_is_refused(deck_with, values, rule):
    from roughcontact.fe.deck_syntax import DeckError

    path = deck_with(f"*STATIC\n{values}\n")
    with pytest.raises(DeckError, match=rf"^{path}:{line_of(path, values)}: \*STATIC the m\w+ increment .*: it must "
                                        rf"be positive and {rule}"):
        read_deck(path)


def test_the_minimum_increment_is_the_floor_of_the_cutbacks(deck_with, law_file):
    """One Newton iteration never meets the convergence test: every increment fails and is
    halved, 0.25 → 0.125 (≥ 0.1) → 0.0625 (< 0.1): refused after two cut-backs, naming the
    minimum; without a minimum, after the six halvings of max_cutbacks."""
    fail = NewtonOptions(max_iterations=1)
    for static, name, where in [("0.25, 1., 0.1, 0.5", "grow.inp", "increment 1 (step fraction 0.125)"),
                                ("0.25, 1., 0.1", "fixed.inp", "increment 1 of 4 (step fraction 0.25)")]:
        path = deck_with(f"*STATIC\n{static}\n", name=name)
        with pytest.raises(DeckConvergenceError) as err:
            run_deck_file(path, law_file(), options=fail)
        said = str(err.value)
        assert f"no convergence at {where}: 1 iterations without convergence; residual" in said
        assert said.endswith(f"after the allowed cut-backs: a further cut-back would fall below the minimum increment "
                             f"0.1 of *STATIC at {path}:{line_of(path, static)}")
        assert err.value.level == 0.125  # the last trial: one halving (the next, 0.0625, is below 0.1)
    with pytest.raises(DeckConvergenceError) as err:
        run_deck_file(deck_with(FIXED, name="plain.inp"), law_file(), options=fail)
    assert err.value.level == 0.25 / 2 ** 6 and "minimum increment" not in str(err.value)  # max_cutbacks = 6 halvings


def test_the_command_line_overrides_the_deck_with_a_note(deck_with, law_file):
    path = deck_with("*STATIC\n0.25, 1., 0.01, 0.5\n", step="*STEP, INC=9")
    result = run_deck_file(path, law_file(), increments=3, max_increments=5)
    assert fractions(result) == pytest.approx([1 / 3, 2 / 3, 1.0], rel=1e-15)
    notes = result.summary()["notes"]
    assert f"{path}:{line_of(path, '0.25, 1., 0.01')}: --increments 3 overrides *STATIC's initial increment 0.25, " \
           "maximum increment 0.5: the step runs 3 fixed increments of 0.333333" in notes
    assert f"{path}:{line_of(path, 'INC=9')}: --max-increments 5 overrides *STEP, INC=9" in notes
    with pytest.raises(IncrementsExceeded, match="its 3 fixed increments .* exceed the maximum number of increments 2"):
        run_deck_file(path, law_file(), increments=3, max_increments=2)
    with pytest.raises(IncrementsExceeded, match=r"INC=2 .* reached at step fraction 0.75"):
        run_deck_file(path, law_file(), max_increments=2)
