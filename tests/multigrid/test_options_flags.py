"""The robustness switches are fields of the frozen solver options, not module flags: their
defaults keep the measured behaviour, bad values are refused naming the field, and a solve reads
them from its options (``confirm_early_stop`` on the driver's toy problem; the point retries in
tests/point, ``exact_rules`` in tests/starved)."""

from __future__ import annotations

import dataclasses

import numba
import pytest

import ehl_multigrid as ehl
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.multigrid.options import RETRIES, LineOptions, MultigridOptions, PointOptions
from ehl_multigrid.multigrid.threads import ThreadBudget, preserved_threads

from .toy import PoissonHierarchy, toy_solver


class _Films(PoissonHierarchy):
    """The toy with both films (its ``Hm`` is its ``Hc``), so that the film rule can stop it."""

    def measure(self, k):
        m = super().measure(k)
        m.Hm = m.Hc
        return m


def test_the_robustness_switches_default_to_on():
    p = PointOptions()
    assert all(getattr(p, name) is True for name in RETRIES)
    assert p.exact_rules == (None, 1)
    assert p.serial_below == 129 * 129
    for cls in (MultigridOptions, LineOptions, PointOptions):
        assert cls().confirm_early_stop is True


def test_the_switches_are_frozen_and_keep_the_options_hashable():
    p = PointOptions.build(exact_rules=[0, None], retry_square_cells=False)
    assert p.exact_rules == (0, None)  # a list (a mapping's value) becomes a tuple
    assert hash(p) == hash(PointOptions(exact_rules=(0, None), retry_square_cells=False))
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.retry_square_cells = True


@pytest.mark.parametrize("name", [*RETRIES, "confirm_early_stop"])
def test_a_switch_that_is_not_a_boolean_is_refused_naming_it(name):
    with pytest.raises(InputError, match=rf"{name} = 'no'.*\[True, False\]"):
        PointOptions(**{name: "no"})


@pytest.mark.parametrize("cls, name", [(PointOptions, "half"), (PointOptions, "elastic"), (PointOptions, "y_pre"),
                                       (PointOptions, "far_field"), (PointOptions, "alternating"),
                                       (LineOptions, "adapt"), (LineOptions, "fmg_match_film")])
def test_every_true_false_option_refuses_a_word(cls, name):
    # {"half": "no"} was taken as true: a non-empty string is truthy
    with pytest.raises(InputError, match=rf"{name} = 'no'.*True, False"):
        cls.build(**{name: "no"})


@pytest.mark.parametrize("rules", [(None, -1), (21,), ("1",), (True,), 1, "01"])
def test_bad_exact_rules_are_refused_with_the_allowed_values(rules):
    with pytest.raises(InputError, match=r"exact_rules = .*None.*\[0, 20\]"):
        PointOptions(exact_rules=rules)


@pytest.mark.parametrize("value", [0, -5, 2.5])
def test_a_bad_serial_below_is_refused_naming_it(value):
    with pytest.raises(InputError, match=f"serial_below = {value}"):
        PointOptions(serial_below=value)


def test_the_front_door_passes_the_switches_to_the_solver_options():
    # refused by PointOptions' own check before any solve: the key reached the options
    with pytest.raises(InputError, match="exact_rules = 'none'.*sequence"):
        ehl.solve(ehl.MoesProblem("point", 20, 10), accuracy=None, options={"exact_rules": "none"})


def test_no_module_flag_is_left_for_tests_to_monkeypatch():
    from ehl_multigrid.multigrid import driver
    from ehl_multigrid.point import fas
    from ehl_multigrid.point import solve as point_solve
    from ehl_multigrid.starved import point as starved_point

    flags = {driver: ["CONFIRM_EARLY_STOP"], fas: ["SERIAL_BELOW"], starved_point: ["EXACT_RULES"],
             point_solve: [n.upper() for n in RETRIES]}
    assert [f"{m.__name__}.{n}" for m, names in flags.items() for n in names if hasattr(m, n)] == []


def test_an_early_stop_is_confirmed_by_one_w_cycle_unless_the_options_say_not_to():
    kw = dict(cycle="V", cycles=1, max_cycles=200, tol=1e-10, tol_load=0.1, film_tol=1e-5)
    kinds = {}
    for confirm in (True, False):
        seen = []
        sol = toy_solver(hierarchy=_Films(129, 5), confirm_early_stop=confirm, **kw).solve(callback=seen.append)
        assert sol.success and sol.residual_history[-1] > 1e-10  # stopped on the films
        kinds[confirm] = [i["cycle_type"] for i in seen if i["level"] == 4]
    assert kinds[True][-1] == "W" and set(kinds[True][:-1]) == {"V"}
    assert set(kinds[False]) == {"V"}
    assert len(kinds[True]) == len(kinds[False]) + 1


def test_the_thread_budget_runs_grids_below_serial_below_on_one_thread():
    with preserved_threads():
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
        budget = ThreadBudget(numba.config.NUMBA_NUM_THREADS, serial_below=100)
        budget.for_size(99)
        assert numba.get_num_threads() == 1
        budget.for_size(100)
        assert numba.get_num_threads() == numba.config.NUMBA_NUM_THREADS


def test_the_point_hierarchy_takes_serial_below_from_its_options():
    from ehl_multigrid.point.fas import PointHierarchy
    from ehl_multigrid.point.problem import problem_from_moes

    with preserved_threads():
        hz = PointHierarchy(problem_from_moes(20.0, 10.0), PointOptions(points=65, serial_below=777))
    assert hz.threads.serial_below == 777
