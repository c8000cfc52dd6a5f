"""A transient run's grid (space) part and its refinement in the grid and the time step
(transient/accuracy.py ``grid_error``, transient/control.py): on runs whose films carry a known
error in the mesh size and in the time step, the stated parts cover the true ones, the
controller refines the part that dominates, and no run is made twice; on real runs, the grid
part covers the film's difference from a run on a grid four times finer."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pytest

import ehl_multigrid as ehl
from ehl_multigrid import Scene, load_scene
from ehl_multigrid.multigrid.accuracy import GRID_SAFETY
from ehl_multigrid.multigrid.controller import Resolution, control
from ehl_multigrid.solution import Status
from ehl_multigrid.transient.accuracy import grid_error
from ehl_multigrid.transient.control import TransientControl

BOX = (-4.5, 1.5)
T_END = 1.0
#: the runs of a refinement in the grid from 129 points: each answer, its time pair, and the
#: answers before it as its grid pairs (65 points for the first)
CALLS_GRID = [(129, 0.01), (129, 0.02), (65, 0.01), (257, 0.01), (257, 0.02), (513, 0.01), (513, 0.02),
              (1025, 0.01), (1025, 0.02)]


@dataclass
class Run:
    """A run whose films are ``1 + cg h^pg sin(3T) + ct dT^2 cos(5T)`` (h the mesh size; Hm
    with half the errors)."""

    points: int
    dt: float
    cg: float
    ct: float
    pg: float = 1.5
    speed: float = 1.0
    scheme: str = "bdf2"
    complete: bool = True
    stop_reason: str = ""
    X: np.ndarray = field(init=False)
    planned_steps: int = field(init=False)

    def __post_init__(self) -> None:
        self.X = np.linspace(*BOX, self.points)
        self.planned_steps = round(T_END / self.dt)
        T = self.dt * np.arange(self.planned_steps + 1)
        h = (BOX[1] - BOX[0]) / (self.points - 1)
        self.Hc = 1.0 + self.cg * h**self.pg * np.sin(3 * T) + self.ct * self.dt**2 * np.cos(5 * T)
        self.Hm = 1.0 + 0.5 * (self.Hc - 1.0)

    def steady_film(self, name: str) -> float:
        return 1.0


def true_error(run: Run) -> float:
    """The largest relative film error of ``run`` against the exact films (h, dT -> 0)."""
    return float(np.max(np.abs(run.Hc - 1.0)))


def no_box(run: Run, line: bool) -> tuple[dict[str, float], str]:
    """The box part of a synthetic run: none (its films carry no box error)."""
    return {"Hc": 0.0, "Hm": 0.0}, "synthetic run: no box truncation"


def controlled(points: int, dt: float, cg: float, ct: float, max_points: int):
    """A TransientControl over synthetic runs, and the list of ``(points, dt)`` it ran."""
    calls: list[tuple[int, float]] = []

    def run(callback=None, **step):
        n, d = step.get("points", points), step.get("dt", dt)
        calls.append((n, d))
        return Run(n, d, cg, ct)

    return TransientControl(run, dimensions=1, points=points, max_points=max_points, box_measure=no_box), calls


def test_the_grid_part_of_an_asymptotic_sequence_is_its_richardson_term_and_covers_the_truth():
    fine, half, quarter = (Run(n, 0.01, cg=5.0, ct=0.0) for n in (257, 129, 65))
    g = grid_error(fine, [half, quarter])
    assert g["order_Hc"] == pytest.approx(1.5, abs=1e-6)
    d2 = np.max(np.abs(fine.Hc - half.Hc))
    assert g["Hc"] == pytest.approx(GRID_SAFETY * d2 / (2**1.5 - 1.0))
    assert true_error(fine) <= g["Hc"] <= 2.0 * true_error(fine)
    # from two grids, first order
    assert grid_error(fine, [half])["Hc"] == pytest.approx(GRID_SAFETY * d2)
    assert math.isnan(grid_error(fine, [half])["order_Hc"])


def test_an_irregular_grid_sequence_takes_half_the_earlier_difference():
    # first order on the two coarser grids, then a much smaller step: not asymptotic
    fine, half, quarter = Run(257, 0.01, 5.0, 0.0), Run(129, 0.01, 5.0, 0.0), Run(65, 0.01, 5.0, 0.0, pg=0.3)
    g = grid_error(fine, [half, quarter])
    d1 = np.max(np.abs(half.Hc - quarter.Hc))
    assert math.isnan(g["order_Hc"]) and g["Hc"] >= GRID_SAFETY * 0.5 * d1


def test_grid_error_refuses_runs_of_another_time_step():
    with pytest.raises(ValueError, match="same box and time step"):
        grid_error(Run(257, 0.01, 1.0, 0.0), [Run(129, 0.02, 1.0, 0.0)])


def test_a_grid_error_above_the_target_refines_the_grid_at_the_same_step_and_reuses_its_runs():
    ctl, calls = controlled(129, 0.01, cg=5.0, ct=0.0, max_points=2049)
    out = control(ctl, Resolution(129), 0.005)
    assert out.met and out.result.at.points > 129 and out.result.at.dt == 1.0
    stated = max(ctl.grid_parts[out.result.at][k] for k in ("Hc", "Hm"))
    assert true_error(out.result.result) <= stated <= 0.005
    # each finer answer takes the answer before it (and the one before that) as its grid
    # pairs, and a time pair of its own
    assert calls == CALLS_GRID


def test_a_time_error_above_the_target_halves_the_step_on_the_same_grid():
    ctl, calls = controlled(257, 0.02, cg=0.0, ct=2.0, max_points=257)
    out = control(ctl, Resolution(257), 1e-4)
    assert out.met and out.result.at.points == 257 and out.result.at.dt < 1.0
    t = ctl.parts[out.result.at]
    assert true_error(out.result.result) <= max(t["Hc"], t["Hm"]) <= 1e-4
    assert len(set(calls)) == len(calls)
    assert {n for n, _ in calls} == {257, 129, 65}  # the answers' grid pairs at every step


def test_a_fixed_grid_whose_grid_part_misses_the_target_is_not_refined_in_time():
    ctl, calls = controlled(129, 0.01, cg=5.0, ct=2.0, max_points=129)
    out = control(ctl, Resolution(129), 1e-4)
    assert not out.met and out.result.at == Resolution(129)
    assert "more than the 129 allowed" in out.why
    # the first run, its time pair and its two grid pairs, and nothing else
    assert sorted(calls) == sorted([(129, 0.01), (129, 0.02), (65, 0.01)])


# -- real runs ----------------------------------------------------------------------------------
def dent_scene(name: str, amplitude: float) -> Scene:
    d = load_scene(name).to_dict()
    d["feature"] = {"kind": "dent", "amplitude": amplitude, "width": 1e-4, "x0": -1.5}
    return Scene.from_dict(d)


@pytest.mark.solver
def test_the_grid_part_of_a_real_run_covers_its_difference_from_a_grid_four_times_finer():
    scene = dent_scene("page63_line_500N", 3e-9)
    opts = {"dt": 0.01171875, "t_end": 1.0}
    sol = ehl.solve(scene, physics="transient", accuracy=0.5, options={**opts, "points": 257})
    ref = ehl.solve(scene, physics="transient", accuracy=None, options={**opts, "points": 1025}).raw
    res, g = sol.raw, sol.error.parts["grid"]
    true = {k: np.max(np.abs(getattr(res, k) - getattr(ref, k))) / res.steady_film(k) for k in ("Hc", "Hm")}
    assert sol.status == Status.CONVERGED and math.isfinite(sol.error.Hc)
    assert true["Hc"] <= g.Hc and true["Hm"] <= g.Hm
    assert sol.error.Hc == pytest.approx(g.Hc + sol.error.parts["time"].Hc + sol.error.parts["domain"].Hc)


@pytest.mark.solver
def test_a_grid_pair_that_cannot_be_solved_leaves_the_error_unknown_and_the_run_inaccurate():
    # page 63 at 2000 N (M 87): the 65-point steady start is not positive
    scene = dent_scene("page63_line_2000N", 1e-8)
    sol = ehl.solve(scene, physics="transient", accuracy=0.5,
                    options={"points": 129, "dt": 0.01171875, "t_end": 0.2})
    assert sol.status == Status.INACCURATE and math.isnan(sol.error.Hc)
    assert math.isnan(sol.error.parts["grid"].Hc) and math.isfinite(sol.error.parts["time"].Hc)
    assert "grid error not measured: the run on 65 points failed" in " ".join(sol.details.notes)
    assert "grid part not measured" in sol.message
