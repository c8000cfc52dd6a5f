"""A stop (Ctrl-C, SIGTERM) during an accuracy sequence keeps its most accurate finished
solve when the caller asked for it (multigrid/controller.py, ``keep_on_stop``), on a toy
physics whose error halves with every grid."""

from dataclasses import dataclass, field

import pytest

from ehl_multigrid.model.errors import Terminated
from ehl_multigrid.multigrid.controller import Candidate, Resolution, control, keep_on_stop


@dataclass
class Stopping:
    """Error 0.04 at 257 points, halving per grid; ``stop_at`` raises ``stop`` when solving it
    (``in_estimate``: when estimating it)."""

    stop_at: int = 1025
    stop: BaseException = field(default_factory=KeyboardInterrupt)
    in_estimate: bool = False
    dimensions: int = 1

    def solve(self, at):
        if at.points == self.stop_at and not self.in_estimate:
            raise self.stop
        return {"at": at, "err": 0.04 * 257 / at.points}

    def converged(self, r):
        return True

    def failure(self, r):
        return ""

    def estimate(self, r, at, record):
        if at.points == self.stop_at:
            raise self.stop
        return r["err"], r["err"] / 2

    def candidates(self, r, at):
        return [Candidate("points", at.finer(), 1, r["err"] / 2)]

    def remedy(self, r, at, first):
        return None

    def why_short(self, r, at):
        return ""


def test_a_stop_during_a_refinement_returns_the_most_accurate_finished_solve():
    lines = []
    with keep_on_stop() as scope:
        out = control(Stopping(), Resolution(257), 1e-4, progress=lines.append)
    assert isinstance(scope.stop, KeyboardInterrupt)
    assert out.result["at"].points == 513 and out.converged and not out.met
    assert out.worst == pytest.approx(0.04 * 257 / 513)
    assert out.why == "interrupted (Ctrl-C) during the solve on 1025 points (box x1)"
    assert [s.points for s in out.steps] == [257, 513]
    assert "keeping the most accurate finished solve" in lines[-1]


def test_a_stop_during_an_estimate_names_it_and_keeps_the_solve_before():
    with keep_on_stop() as scope:
        out = control(Stopping(in_estimate=True), Resolution(257), 1e-4)
    assert out.result["at"].points == 513
    assert "during the error estimate of the solve on 1025 points" in out.why
    assert scope.stop is not None


@pytest.mark.parametrize("stop", [Terminated(), SystemError("numba callback")], ids=["sigterm", "wrapped"])
def test_sigterm_and_a_stop_wrapped_by_compiled_code_are_kept_too(stop):
    if isinstance(stop, SystemError):
        stop.__cause__ = KeyboardInterrupt()
    with keep_on_stop() as scope:
        out = control(Stopping(stop=stop), Resolution(257), 1e-4)
    assert out.result["at"].points == 513
    assert scope.stop is (stop if isinstance(stop, Terminated) else stop.__cause__)
    assert out.why.startswith("terminated (SIGTERM)" if isinstance(stop, Terminated) else "interrupted")


def test_without_a_scope_or_a_finished_solve_the_stop_propagates():
    with pytest.raises(KeyboardInterrupt):
        control(Stopping(), Resolution(257), 1e-4)  # nobody asked to keep an answer
    with keep_on_stop() as scope, pytest.raises(KeyboardInterrupt):
        control(Stopping(stop_at=257), Resolution(257), 1e-4)  # nothing finished yet
    assert scope.stop is None


def test_only_the_outermost_sequence_keeps_its_answer():
    class Outer(Stopping):
        def solve(self, at):
            if at.points == 1025:  # an inner sequence (a probe's) stops: the outer one keeps
                control(Stopping(stop_at=513), Resolution(257), 1e-4)
            return super().solve(at)

    with keep_on_stop() as scope:
        with keep_on_stop() as inner:
            assert inner is None  # a nested block leaves the stop to the outermost caller
        out = control(Outer(stop_at=0), Resolution(257), 1e-4)
    assert out.result["at"].points == 513 and "during the solve on 1025 points" in out.why
    assert isinstance(scope.stop, KeyboardInterrupt)


def test_a_resolution_names_its_tolerance_scale():
    assert Resolution(513, tol=0.1).describe() == "513 points, tolerances x0.1 (box x1)"
