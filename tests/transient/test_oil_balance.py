"""The oil-balance criterion of mass-conserving time steps (``transient.oil_balance``): more
cycles while the step's mass error is above ``mass_tol`` and still falling, none at its floor,
a fresh count for every solve."""

from __future__ import annotations

import math

import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.transient.oil_balance import (
    MASS_FLOOR_CYCLES,
    MASS_TOL,
    OilBalanceCycles,
    require_mass_tol,
)


class _Step(OilBalanceCycles):
    def __init__(self, errors):
        self.errors = iter(errors)

    def step_mass_error(self):
        return next(self.errors)


def _asks(step, solver, n):
    return [step.wants_cycles(solver) for _ in range(n)]


def test_cycles_are_asked_while_the_balance_is_above_the_tolerance_and_falling():
    step = _Step([3e-4, -1e-4, 3e-5, -1e-5, 3e-6, 9e-7])
    assert _asks(step, object(), 6) == [True] * 5 + [False]


def test_no_cycle_is_asked_at_the_floor_of_the_cycles():
    # the balance stops falling: asked for MASS_FLOOR_CYCLES more cycles, then no more
    step = _Step([2e-5] * 20)
    asks = _asks(step, object(), MASS_FLOOR_CYCLES + 1)
    assert asks == [True] * MASS_FLOOR_CYCLES + [False]


def test_a_balance_that_rises_for_a_cycle_and_falls_on_keeps_its_cycles():
    # measured on a point supply step: 1.43e-6, 3.18e-6, 2.44e-6, 1.42e-6, then below 1e-6
    step = _Step([1.43e-6, 3.18e-6, 2.44e-6, 1.42e-6, 9.9e-7])
    assert _asks(step, object(), 5) == [True] * 4 + [False]


def test_every_solve_counts_its_own_cycles():
    step = _Step([2e-5] * 20)
    first = object()
    _asks(step, first, MASS_FLOOR_CYCLES + 1)
    assert step.wants_cycles(object())  # a new step's solve starts afresh


def test_no_criterion_asks_nothing_and_nan_asks_nothing():
    step = _Step([1.0])
    step.mass_tol = None
    assert not step.wants_cycles(object())
    assert not _Step([math.nan]).wants_cycles(object())


@pytest.mark.parametrize("bad", [0.0, -1e-6, 2.0, math.inf])
def test_a_tolerance_outside_its_range_is_refused_naming_it(bad):
    with pytest.raises(InputError, match=r"mass_tol = .* range \[1e-12, 1\]"):
        require_mass_tol(bad)


def test_a_tolerance_for_the_projection_is_refused_rather_than_ignored():
    with pytest.raises(InputError, match=r"mass_tol = 1e-08 .*mass-conserving"):
        require_mass_tol(1e-8, "projection")
    assert require_mass_tol(None, "projection") is None
    assert require_mass_tol(MASS_TOL, "projection") == MASS_TOL  # the default, not asked for
