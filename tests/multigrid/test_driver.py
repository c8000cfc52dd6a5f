"""The shared multilevel driver on a toy FAS problem with a known solution (tests/multigrid/toy.py)."""

import math
import re

import numpy as np
import pytest

from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.multigrid import STATUS, PolicyParameters

from .toy import PoissonHierarchy, toy_solver


@pytest.mark.parametrize("cycle", ["V", "W", "F"])
def test_cycles_converge_at_the_textbook_rate(cycle):
    solver = toy_solver(cycle=cycle, cycles=1, max_cycles=20, tol=1e-11, tol_load=1e-3)
    sol = solver.solve()
    assert sol.success and sol.status_name == "converged"
    r = sol.residual_history
    # weighted Jacobi (smoothing factor 1/3) with nu1 + nu2 = 3: about 1/27 per two-grid cycle;
    # a cycle that is not FAS-consistent, or a wrong transfer, converges at 0.5-0.9
    factor = (r[-1] / r[0]) ** (1.0 / (len(r) - 1))
    assert factor < 0.12, (cycle, factor)


def test_fmg_alone_reaches_the_discretisation_error_at_second_order():
    errors = []
    for n in (65, 129, 257):
        levels = int(math.log2((n - 1) // 4)) + 1
        solver = toy_solver(points=n, levels=levels, cycles=1, max_cycles=0, tol=1e-14, tol_load=0.1)
        sol = solver.solve()
        assert sol.status_name == "max_cycles"  # tol 1e-14 is not reached without extra cycles
        errors.append(solver.hierarchy.error())
    # the truncation error of -u'' by central differences is pi^4 h^2/12 sin(pi x)
    for n, e in zip((65, 129, 257), errors, strict=True):
        assert e < 1.5 * math.pi**2 / 12.0 / (n - 1) ** 2
    order = math.log2(errors[1] / errors[2])
    assert 1.9 < order < 2.1


def test_w_cycle_visits_coarse_grids_more_than_v():
    wv = toy_solver(cycle="V", cycles=1, max_cycles=3, tol=1e-14, tol_load=0.1).solve().work_units
    ww = toy_solver(cycle="W", cycles=1, max_cycles=3, tol=1e-14, tol_load=0.1).solve().work_units
    wf = toy_solver(cycle="F", cycles=1, max_cycles=3, tol=1e-14, tol_load=0.1).solve().work_units
    assert wv < wf < ww


def test_rejected_cycle_is_undone_and_repeated_with_halved_relaxation():
    hz = PoissonHierarchy(129, 5, unstable_above=0.6)
    params = PolicyParameters(recover=1.0)
    solver = toy_solver(hierarchy=hz, params=params, omega=1.0, max_cycles=20, tol=1e-10, tol_load=0.1)
    sol = solver.solve()
    assert sol.success
    rejected = [a for a in sol.actions if "rejected" in a]
    assert rejected and "omega = 0.5" in rejected[0]
    assert solver.settings.omega == 0.5
    # every accepted cycle lowered the residual: the diverging attempts left no trace
    assert np.all(np.diff(sol.residual_history) < 0)


def test_every_rejection_exhausts_the_retries_and_reports_divergence():
    hz = PoissonHierarchy(129, 5, unstable_above=0.0)  # unstable at any omega
    sol = toy_solver(hierarchy=hz, omega=1.0, max_cycles=5, tol=1e-10, tol_load=0.1).solve()
    assert not sol.success and sol.status_name == "diverged" and sol.status == 3
    assert "attempts" in sol.message
    assert len([a for a in sol.actions if "rejected" in a]) == PolicyParameters().max_retries


def test_retries_stop_once_the_remedies_can_change_nothing():
    # the under-relaxation at its floor: the next attempt would repeat the last one exactly
    hz = PoissonHierarchy(129, 5, unstable_above=0.0)
    params = PolicyParameters(floors=(0.25, 0.075, 0.0))
    sol = toy_solver(hierarchy=hz, params=params, omega=1.0, max_cycles=5, tol=1e-10, tol_load=0.1).solve()
    # stopped after three rejections of one cycle (fewer than the retries allowed), with its residual
    assert sol.status_name == "diverged" and re.search(r"\brejected 3 times\b.*\bresidual \d", sol.message)
    omegas = [a.split("omega = ")[1].split(",")[0] for a in sol.actions if "rejected" in a]
    assert omegas == ["0.5", "0.25", "0.25"]  # 1.0 -> 0.5 -> 0.25, then one identical attempt


def test_retries_without_adaptation_stop_at_the_first_rejection():
    hz = PoissonHierarchy(129, 5, unstable_above=0.0)
    sol = toy_solver(hierarchy=hz, omega=1.0, max_cycles=5, tol=1e-10, tol_load=0.1, adapt=False).solve()
    assert sol.status_name == "diverged"
    assert len([a for a in sol.actions if "rejected" in a]) == 1


def test_stall_switches_to_w_then_raises_the_switch_then_gives_up():
    hz = PoissonHierarchy(129, 5, no_correction=True)  # smoothing only: the residual stalls
    sol = toy_solver(hierarchy=hz, cycle="V", cycles=1, max_cycles=200, tol=1e-10, tol_load=0.1).solve()
    assert sol.status_name == "stalled"
    stalls = [a for a in sol.actions if "stalled" in a]
    assert len(stalls) == 2 and "V -> W" in stalls[0] and "switch raised" in stalls[1]
    assert sol.settings.cycle == "W"
    assert sol.cycles < 40  # gave up after three stall windows, not at max_cycles


def test_a_stall_below_the_quiet_level_ends_at_the_residual_floor_without_stall_steps():
    hz = PoissonHierarchy(129, 5, no_correction=True)  # smoothing only: the residual stalls
    params = PolicyParameters(quiet_below=1.0)  # every residual of this solve counts as the floor
    sol = toy_solver(hierarchy=hz, params=params, cycle="V", cycles=1, max_cycles=200, tol=1e-10,
                     tol_load=0.1).solve()
    assert sol.status_name == "residual_floor" and sol.status == 8 and not sol.success
    assert not [a for a in sol.actions if "stalled" in a]  # no W switch, no raised switch
    # the residual it stopped at, the tolerance asked and the films' last changes
    assert re.search(r"\bresidual\b.*\d.*\(tol 1e-10\)", sol.message), sol.message
    assert re.search(r"\bHc\b\D*\d.*\bHm\b", sol.message), sol.message
    assert sol.settings.cycle == "V"


def test_a_film_stopped_solve_keeps_the_stall_ladder_below_the_quiet_level():
    hz = PoissonHierarchy(129, 5, no_correction=True)
    params = PolicyParameters(quiet_below=1.0)
    sol = toy_solver(hierarchy=hz, params=params, cycle="V", cycles=1, max_cycles=200, tol=1e-10,
                     tol_load=0.1, film_tol=1e-12).solve()
    assert sol.status_name != "residual_floor"
    assert [a for a in sol.actions if "stalled" in a]


class _FloorHierarchy(PoissonHierarchy):
    """The toy with a relaxation floor: the residual never falls below 1e-6 and, with
    ``jitter``, the films jump by that relative amount from cycle to cycle around their
    converged values (as the point solver's films do at M = 5000)."""

    def __init__(self, jitter: float) -> None:
        super().__init__(129, 5)
        self.jitter, self.calls = jitter, 0

    def measure(self, k):
        m = super().measure(k)
        self.calls += 1
        m.residual = max(m.residual, 1e-6 * (1.0 + 0.3 * (self.calls % 3)))
        m.Hc = m.Hc * (1.0 + self.jitter * (-1) ** self.calls)
        m.Hm = m.Hc
        return m


def test_a_film_stopped_solve_with_jittering_films_ends_at_the_floor_not_at_max_cycles():
    params = PolicyParameters(quiet_below=1e-5)
    sol = toy_solver(hierarchy=_FloorHierarchy(1e-4), params=params, cycle="V", cycles=1,
                     max_cycles=200, tol=1e-10, tol_load=0.1, film_tol=1e-5).solve()
    assert sol.status_name == "residual_floor" and not sol.success
    assert "film_tol = 1e-05" in sol.message
    assert re.search(r"\bHc \d\S*, Hm \d", sol.message), sol.message
    assert sol.cycles < 30
    # films that settle meet the film rule at the same residual floor
    calm = toy_solver(hierarchy=_FloorHierarchy(0.0), params=params, cycle="V", cycles=1,
                      max_cycles=200, tol=1e-10, tol_load=0.1, film_tol=1e-5).solve()
    assert calm.success
    # without a quiet level (line contacts) the floor rule is off: the cycles run out
    off = toy_solver(hierarchy=_FloorHierarchy(1e-4), params=PolicyParameters(), cycle="V", cycles=1,
                     max_cycles=40, tol=1e-10, tol_load=0.1, film_tol=1e-5).solve()
    assert off.status_name != "residual_floor" and not off.success


def test_stall_raises_with_a_hint_when_asked_to():
    hz = PoissonHierarchy(129, 5, no_correction=True)
    with pytest.raises(ConvergenceError, match="stalled"):
        toy_solver(hierarchy=hz, max_cycles=200, tol=1e-10, tol_load=0.1, raise_on_failure=True).solve()


def test_callback_sees_every_cycle_and_stop_iteration_stops_the_solve():
    seen = []

    def cb(info):
        seen.append(info)
        if len(seen) == 6:
            raise StopIteration

    sol = toy_solver(cycles=2, max_cycles=20, tol=1e-14, tol_load=0.1).solve(callback=cb)
    assert sol.status_name == "stopped" and sol.status == 4 and not sol.success
    assert len(seen) == 6 == sol.cycles
    assert {"level", "points", "cycle", "residual", "load_error", "Hc_venner", "work_units"} <= set(seen[0])
    assert [i["points"] for i in seen[:2]] == [17, 17]


def test_repr_lists_levels_points_and_mesh_sizes():
    text = repr(toy_solver())
    assert "PoissonHierarchy" in text and "cycle V" in text and "5 levels" in text
    assert "level 4: 129 points, h = 0.0078" in text


def test_status_table_is_complete():
    assert set(STATUS) == set(range(11))
    assert len(set(STATUS.values())) == len(STATUS) and STATUS[9] == "mass_not_conserved"


def test_a_converged_iterate_with_a_non_positive_film_is_not_a_success():
    class TouchingFilm(PoissonHierarchy):
        # the toy's "film": u - 0.5, negative near the ends of the interval
        def measure(self, k):
            m = super().measure(k)
            m.Hm = float(self.levels[k].u.min() - 0.5)
            return m

    sol = toy_solver(hierarchy=TouchingFilm(129, 5), max_cycles=20, tol=1e-8, tol_load=1e-3).solve()
    assert not sol.success and sol.status_name == "film_not_positive" and sol.status == 7
    assert "not positive" in sol.message and "more points" in sol.message
