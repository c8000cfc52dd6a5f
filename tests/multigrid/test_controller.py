"""The one accuracy controller (multigrid/controller.py) on a toy physics whose error halves
with every grid: the choice among candidates, failures, budgets and the record of solves."""

import math
from dataclasses import dataclass, field

import pytest

from ehl_multigrid.multigrid.controller import Candidate, Resolution, choose, control


def test_choose_takes_the_cheapest_candidate_that_meets_the_target():
    a = Candidate("points", Resolution(513), 1, 0.004)
    b = Candidate("tolerance", Resolution(257, tol=0.1), 0, 0.003)
    c = Candidate("box", Resolution(257, box=2.0), 0, 0.02)
    assert choose([a, b, c], 0.005, 0.03) is b
    assert choose([a, c], 0.005, 0.03) is a


def test_choose_takes_a_cheaper_candidate_within_the_sharpness_of_the_best_prediction():
    fine = Candidate("points", Resolution(513), 1, 0.0100)
    cheap = Candidate("box", Resolution(257, box=2.0), 0, 0.0105)
    assert choose([fine, cheap], 0.005, 0.03) is cheap
    # a prediction that does not lower the error by 10 % is no refinement
    assert choose([fine], 0.005, 0.0105) is None


def test_a_cheaper_candidate_that_gains_too_little_does_not_hide_one_that_gains_enough():
    # circular (5, 0) at 1 % on 513 points and four times the box, error 1.18 %: a tolerance
    # step predicted 1.11 %, within the sharpness of the finer grid's 1.02 %, but short of a
    # 10 % gain; the finer grid gains enough
    fine = Candidate("points", Resolution(1025, box=4.0, tol=0.1), 1, 0.0102)
    tol = Candidate("tolerance", Resolution(513, box=4.0, tol=0.01), 0, 0.0111)
    assert choose([fine, tol], 0.01, 0.0118) is fine
    assert choose([tol], 0.01, 0.0118) is None


def test_choose_takes_a_candidate_with_an_unknown_prediction_first():
    measured = Candidate("points", Resolution(513), 1, 0.001)
    needed = Candidate("nz", Resolution(257, nz=16), 0, math.nan)
    assert choose([measured, needed], 0.005, math.nan) is needed


def test_choose_tries_a_cheaper_finer_grid_predicted_near_the_target_before_the_meeting_one():
    one = Candidate("points", Resolution(513), 1, 0.007)
    two = Candidate("2 points+box", Resolution(1025, box=2.0), 2, 0.003)
    tol = Candidate("tolerance", Resolution(257, tol=0.1), 0, 0.006)
    assert choose([one, two, tol], 0.005, 0.03) is two  # no hope: the one predicted to meet
    assert choose([one, two, tol], 0.005, 0.03, hope=1.5) is one
    # a tolerance step adds no FMG grid: nothing the prediction leaves out, no hope
    assert choose([two, tol], 0.005, 0.03, hope=1.5) is two
    far = Candidate("points", Resolution(513), 1, 0.008)  # beyond 1.5 x the target
    assert choose([far, two], 0.005, 0.03, hope=1.5) is two
    # what the finer solve may add (a box correction) is hoped for only by the hopeful choice,
    # also where no candidate is predicted to meet and the lowest prediction would be taken
    corrected = Candidate("points+box", Resolution(513, box=2.0), 1, 0.015, 0.007)
    lowest = Candidate("2 points+box", Resolution(1025, box=2.0), 2, 0.012)
    assert choose([corrected, lowest], 0.005, 0.03) is lowest
    assert choose([corrected, lowest], 0.005, 0.03, hope=1.5) is corrected


@dataclass
class Toy:
    """Error 0.04 at 257 points, halving per grid; ``fail`` lists resolutions that diverge."""

    fail: set = field(default_factory=set)
    remedy_to: Resolution | None = None
    dimensions: int = 1
    solved: list = field(default_factory=list)

    def solve(self, at):
        self.solved.append(at)
        err = 0.04 * 257 / at.points
        return {"at": at, "ok": at not in self.fail, "err": err}

    def converged(self, r):
        return r["ok"]

    def failure(self, r):
        return "diverged: load error 1e10"

    def estimate(self, r, at, record):
        return r["err"], r["err"] / 2

    def candidates(self, r, at):
        return [Candidate("points", at.finer(), 1, r["err"] / 2)] if at.points < 4097 else []

    def remedy(self, r, at, first):
        return self.remedy_to

    def why_short(self, r, at):
        return f"max points at {at.points}"


def test_control_refines_until_the_target_and_records_every_solve():
    toy = Toy()
    out = control(toy, Resolution(257), 0.006)
    assert out.met and out.converged and out.result["at"].points == 2049
    assert [s.points for s in out.steps] == [257, 513, 1025, 2049]
    assert [s.next for s in out.steps] == ["points", "points", "points", ""]
    assert out.steps[0].Hc_error == pytest.approx(0.04)


def test_control_stops_at_the_limit_and_says_why():
    out = control(Toy(), Resolution(257), 1e-4)
    assert not out.met and out.converged and out.result["at"].points == 4097
    assert "max points at 4097" in out.why


def test_a_failed_refinement_returns_the_most_accurate_converged_solve():
    toy = Toy(fail={Resolution(1025)})
    out = control(toy, Resolution(257), 0.006, max_points=4097)
    assert out.result["at"].points == 513 and not out.met
    assert "1025" in out.why and "did not converge" in out.why and "diverged" in out.why
    assert out.last["at"].points == 1025


def test_a_first_failure_with_a_remedy_is_refined_and_without_one_is_returned():
    toy = Toy(fail={Resolution(257)}, remedy_to=Resolution(513))
    out = control(toy, Resolution(257), 0.021)
    assert out.met and out.result["at"].points == 513
    out = control(Toy(fail={Resolution(257)}), Resolution(257), 0.02)
    assert not out.converged and out.result["at"].points == 257 and "diverged" in out.why


def test_a_refinement_predicted_to_overrun_the_time_budget_is_not_started(monkeypatch):
    import types

    import ehl_multigrid.multigrid.controller as ctl

    clock = [0.0]
    monkeypatch.setattr(ctl, "time", types.SimpleNamespace(perf_counter=lambda: clock[0]))

    class Slow(Toy):
        def solve(self, at):
            clock[0] += 10.0 * ((at.points - 1) / 256) ** self.dimensions
            return super().solve(at)

    out = control(Slow(dimensions=2), Resolution(257), 0.006, time_budget=30.0)
    assert [s.points for s in out.steps] == [257] and not out.met
    assert "40 s" in out.why and "30 s" in out.why


def test_the_cost_prediction_scales_only_the_work_a_refinement_repeats(monkeypatch):
    import types

    import ehl_multigrid.multigrid.controller as ctl

    clock = [0.0]
    monkeypatch.setattr(ctl, "time", types.SimpleNamespace(perf_counter=lambda: clock[0]))

    class CoarseEstimate(Toy):
        # each round: its own solve (10 s per 256^2 intervals) and a slow coarse-grid solve of
        # the estimate (60 s) that the next round reuses
        def solve(self, at):
            clock[0] += 10.0 * ((at.points - 1) / 256) ** 2
            return super().solve(at)

        def estimate(self, r, at, record):
            clock[0] += 60.0 if at.points == 257 else 0.0
            return super().estimate(r, at, record)

    # the whole round (70 s) times 4 overruns 200 s: not refined
    out = control(CoarseEstimate(dimensions=2), Resolution(257), 0.021, time_budget=200.0)
    assert [s.points for s in out.steps] == [257] and "280 s" in out.why

    class Reported(CoarseEstimate):
        def recurring_seconds(self, at):
            return 10.0 * ((at.points - 1) / 256) ** 2

    out = control(Reported(dimensions=2), Resolution(257), 0.021, time_budget=200.0)
    assert out.met and [s.points for s in out.steps] == [257, 513]
    # a physics that knows nothing of the round says None: the whole round, as before
    out = control(type("Unknown", (CoarseEstimate,), {"recurring_seconds": lambda self, at: None})(
        dimensions=2), Resolution(257), 0.021, time_budget=200.0)
    assert [s.points for s in out.steps] == [257]


@dataclass
class Stopping(Toy):
    """A solve of ``iterations[points]`` iterations of 10 s each on a fake clock, checking the
    budget between them as a thermal EHL outer iteration does; one that stops fails."""

    iterations: dict = field(default_factory=lambda: {257: 3, 513: 10})
    clock: list = field(default_factory=lambda: [0.0])

    def solve(self, at):
        from ehl_multigrid.multigrid.controller import TimeBudgetSpent, check_deadline

        self.solved.append(at)
        try:
            for it in range(1, self.iterations[at.points] + 1):
                check_deadline(f"iteration {it}")
                self.clock[0] += 10.0
        except TimeBudgetSpent as exc:
            return {"at": at, "ok": False, "err": math.nan, "why": str(exc).splitlines()[0]}
        return {"at": at, "ok": True, "err": 0.04 * 257 / at.points}

    def failure(self, r):
        return r["why"]


def fake_clock(monkeypatch, clock):
    import types

    import ehl_multigrid.multigrid.controller as ctl

    monkeypatch.setattr(ctl, "time", types.SimpleNamespace(perf_counter=lambda: clock[0]))


def test_a_running_solve_that_checks_the_budget_stops_when_it_runs_out(monkeypatch):
    # 257 points: 3 iterations (30 s); 513 points: 10 (100 s), predicted 60 s (twice the
    # first), started within a budget of 100 s and stopped when it runs out
    toy = Stopping()
    fake_clock(monkeypatch, toy.clock)
    toy.candidates = lambda r, at: [Candidate("points", at.finer(), 1, 0.001)]
    out = control(toy, Resolution(257), 0.021, time_budget=1000.0)
    assert out.met and not out.budget_spent  # 30 + 100 s
    toy.clock[0] = 0.0
    out = control(toy, Resolution(257), 0.021, time_budget=100.0)
    # the 257-point solve is returned, with why the finer one did not finish
    assert out.converged and not out.met and out.budget_spent
    assert out.result["at"].points == 257 and out.last["at"].points == 513
    assert toy.clock[0] == pytest.approx(100.0)
    assert "100 s" in out.why and "513" in out.why
    assert [s.points for s in out.steps] == [257, 513]


def test_a_first_solve_stopped_by_the_budget_fails_without_its_remedy(monkeypatch):
    toy = Stopping(remedy_to=Resolution(513))
    fake_clock(monkeypatch, toy.clock)
    out = control(toy, Resolution(257), 0.006, time_budget=15.0)
    assert not out.converged and out.budget_spent and toy.solved == [Resolution(257)]
    assert "15 s" in out.why and out.why.endswith("at iteration 3")  # the step it stopped at
    # outside a controlled sequence no deadline applies
    from ehl_multigrid.multigrid.controller import check_deadline

    toy.clock[0] = 1e9
    check_deadline("anywhere")


def test_without_a_target_or_refinement_the_first_solve_is_only_judged():
    toy = Toy()
    assert control(toy, Resolution(257), None).met
    out = control(toy, Resolution(257), 0.001, refine=False)
    assert not out.met and len(out.steps) == 1 and out.why == ""


def test_a_hopeful_step_that_misses_is_not_repeated():
    """One finer grid is always predicted within 1.5x of the target and two grids meet it; the
    real error meets it only from 2049 points: in two dimensions one hopeful step, then the
    meeting one."""

    class Hopeful(Toy):
        def solve(self, at):
            self.solved.append(at)
            return {"at": at, "ok": True, "err": 0.004 if at.points >= 2049 else 0.01}

        def candidates(self, r, at):
            return [Candidate("points", at.finer(), 1, 0.007),
                    Candidate("2 points", at.finer().finer(), 2, 0.003)]

    out = control(Hopeful(dimensions=2), Resolution(257), 0.005)
    assert out.met and [s.points for s in out.steps] == [257, 513, 2049]
    # in one dimension a rank is 2x the work, not 4x: no hopeful step
    out = control(Hopeful(dimensions=1), Resolution(257), 0.005)
    assert out.met and [s.points for s in out.steps] == [257, 1025, 4097]


def test_when_the_last_solve_is_no_better_than_an_earlier_one_the_reason_says_so():
    # a starved 6205 outer race at 2 %: 513 points solved, its estimate no better than 257's,
    # and the message said only that the next grid exceeds max_points
    class Worse(Toy):
        def estimate(self, r, at, record):
            return (0.04, 0.02) if at.points == 257 else (0.05, 0.02)

        def candidates(self, r, at):
            return [Candidate("points", at.finer(), 1, 0.03)] if at.points < 513 else []

    out = control(Worse(), Resolution(257), 0.02)
    assert out.result["at"].points == 257 and out.last["at"].points == 513
    assert out.why.startswith("the solve on 513 points (box x1) estimated 0.05, no better than the 0.04 of "
                              "the solve returned; from it, max points at 513")


def test_a_failed_refinement_falls_back_to_a_finer_grid_only_where_that_is_predicted_to_gain():
    # a time-step refinement fails; the finer grid at the same step is predicted to leave the
    # time part (0.04 -> 0.039): no fallback solve, the sequence ends with why
    @dataclass
    class TimeBound(Toy):
        def candidates(self, r, at):
            return [Candidate("dt", Resolution(at.points, dt=0.5), 0, 0.001),
                    Candidate("points", at.finer(), 1, 0.039)]

    toy = TimeBound(fail={Resolution(257, dt=0.5)})
    out = control(toy, Resolution(257), 0.005, max_points=4097)
    assert toy.solved == [Resolution(257), Resolution(257, dt=0.5)]
    assert out.result["at"] == Resolution(257) and "did not converge" in out.why

    # a two-grid jump fails; one grid finer is predicted to halve the error: it is tried
    @dataclass
    class Jumping(Toy):
        def candidates(self, r, at):
            return [Candidate("2 points", at.finer().finer(), 1, r["err"] / 4),
                    Candidate("points", at.finer(), 1, r["err"] / 2)]

    toy = Jumping(fail={Resolution(1025)})
    out = control(toy, Resolution(257), 0.005, max_points=4097)
    assert toy.solved[:3] == [Resolution(257), Resolution(1025), Resolution(513)]
