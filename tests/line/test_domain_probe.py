"""The line domain probe (``line_domain_change``): its two solves start on their finest grid from
the solution (``from_guess``) at a film tolerance tight enough that the measured box change is
the change between the two discrete solutions, not a remnant of their common start."""

import dataclasses

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.solver import line_domain_change, solve_line_problem


@pytest.fixture(scope="module")
def sol():
    return solve_line(20.0, 10.0, points=2049, estimate=False)


def test_a_solve_from_the_solution_starts_on_the_finest_grid_and_keeps_the_discrete_film(sol):
    o = dataclasses.replace(sol.options, points=1025, levels=None, tol=1e-9, tol_load=1e-10,
                            max_cycles=200)
    fmg = solve_line_problem(sol.problem, o)
    start = solve_line_problem(sol.problem, o, guess=(sol.X, sol.P, sol.H0), from_guess=True)
    assert fmg.success and start.success
    assert any("no FMG" in a for a in start.actions)
    assert start.cycles < fmg.cycles
    assert start.Hc == pytest.approx(fmg.Hc, rel=1e-7)
    assert start.Hm == pytest.approx(fmg.Hm, rel=1e-7)


def test_domain_probe_from_the_solution_measures_the_deep_box_change(sol):
    change = line_domain_change(sol.problem, sol.options, sol)
    assert change is not None
    # the same two discrete problems solved deep by FMG (the probe's pair: a quarter of the
    # points on the default box, half on the box twice as long)
    wide = dataclasses.replace(sol.problem, xmin=sol.problem.xmin - (sol.problem.xmax - sol.problem.xmin))
    o = dataclasses.replace(sol.options, levels=None, tol=1e-9, tol_load=1e-10, max_cycles=200)
    a = solve_line_problem(sol.problem, o, points=513)
    b = solve_line_problem(wide, o, points=1025)
    deep = (b.Hc / a.Hc - 1.0, b.Hm / a.Hm - 1.0)
    assert abs(deep[0]) > 1e-5  # a change the probe must resolve
    for got, want in zip(change, deep, strict=True):
        assert got == pytest.approx(want, rel=0.05)


def _fmg_probe_grids(monkeypatch, sol, below_start):
    """The grids (points of the default box) of ``line_domain_change``'s solves for ``sol``."""
    import ehl_multigrid.line.solver as ls

    seen, real = [], ls.solve_line_problem

    def spy(problem, options, *a, **kw):
        if problem.xmin == sol.problem.xmin:
            seen.append(options.points)
        return real(problem, options, *a, **kw)

    monkeypatch.setattr(ls, "solve_line_problem", spy)
    return line_domain_change(sol.problem, sol.options, sol, below_start=below_start), seen


def _probe_grids(monkeypatch, sol, below_start):
    """The same for ``sol`` as if it had started on its finest grid (no FMG grids below it)."""
    started_on_finest = dataclasses.replace(sol)
    started_on_finest.fmg = [{"level": sol.levels - 1}]
    return _fmg_probe_grids(monkeypatch, started_on_finest, below_start)


def test_a_solve_started_on_its_finest_grid_measures_its_box_on_a_coarse_grid_where_far_below(
        monkeypatch, sol):
    """The continuation in M starts on the finest grid, so the probes had only that grid
    ((5000, 0) on 16385 and 32769 points: 7.4 s for a change of 2e-6). Two grids below, the box
    change is accepted where ``below_start`` says it lies far below the target; the same change
    as on the finest grid within the factor 1.2 that ``solve_line``'s rule allows for (the
    inlet is resolved on coarse meshes)."""
    coarse, seen = _probe_grids(monkeypatch, sol, lambda change: True)
    assert seen == [513]
    fine, seen = _probe_grids(monkeypatch, sol, lambda change: False)  # ends on the finest grid
    assert seen[-1] == 2049
    for c, f in zip(coarse, fine, strict=True):
        assert 1.0 / 1.2 < c / f < 1.2  # measured: Hc 1.01, Hm 1.12


def test_a_coarse_box_change_not_far_below_the_target_is_measured_again_on_a_finer_grid(
        monkeypatch, sol):
    change, seen = _probe_grids(monkeypatch, sol, lambda change: False)
    assert seen == [513, 1025, 2049]  # neither coarse grid's change counts: the finest measures it
    assert change is not None


def test_without_below_start_the_probe_stays_on_the_grids_the_fmg_reached(monkeypatch, sol):
    _, seen = _probe_grids(monkeypatch, sol, None)
    assert seen == [2049]



def test_an_fmg_solve_first_looks_at_its_box_on_a_coarse_fmg_grid(monkeypatch):
    """An accuracy-driven solve's probe first runs on the coarsest FMG grid of at least
    ``COARSE_PROBE_POINTS`` (513 of 8193 here, a sixteenth of the points of the probe two grids
    below the finest) and keeps that change where ``below_start`` accepts it; otherwise it goes
    on two grids below the finest, as before. Coarse and fine meshes measure the same change
    (the inlet is resolved on 513 points)."""
    sol = solve_line(20.0, 10.0, points=8193, estimate=False)
    assert min(d["points"] for d in sol.fmg) < 513
    coarse, seen = _fmg_probe_grids(monkeypatch, sol, lambda change: True)
    assert seen == [513]
    fine, seen = _fmg_probe_grids(monkeypatch, sol, lambda change: False)
    assert seen == [513, 2049]
    for c, f in zip(coarse, fine, strict=True):
        assert 1.0 / 1.2 < c / f < 1.2
    _, seen = _fmg_probe_grids(monkeypatch, sol, None)  # no rule: two grids below the finest
    assert seen == [2049]


def test_an_isoviscous_solve_probes_two_grids_below_the_finest_without_the_coarse_look(monkeypatch):
    """Isoviscous contacts at high M hardly carry a film on coarse grids, and the coarse look cost
    more than it saved there ((1000, 0) at 0.5 %: 1.6 -> 2.5 s): L = 0 keeps the probe two grids
    below the finest."""
    sol = solve_line(20.0, 0.0, points=8193, estimate=False)
    assert min(d["points"] for d in sol.fmg) < 513
    _, seen = _fmg_probe_grids(monkeypatch, sol, lambda change: True)
    assert seen == [2049]
