"""The box (domain) probes of an accuracy-driven point solve: a refinement sequence never
solves the same probe twice (the wide solve of one box is the narrow solve of the next)."""

import pytest

import ehl_multigrid.point.solve as point_solve
from ehl_multigrid.point.solve import solve_point


@pytest.mark.solver
def test_a_refinement_sequence_solves_each_probe_once(monkeypatch):
    seen = []
    original = point_solve.solve_fas

    def recording(problem, options, **kw):
        seen.append(options)
        return original(problem, options, **kw)

    monkeypatch.setattr(point_solve, "solve_fas", recording)
    res = solve_point(20, 10, accuracy=0.02, max_points=257)
    boxes = {o.xmin for o in seen}
    assert len(res.extra["refinements"]) >= 2 and len(boxes) >= 3  # two boxes probed
    assert len(seen) == len(set(seen))


def test_a_probe_that_needed_the_coarser_start_passes_it_on_to_the_wider_boxes():
    """A probe whose first attempt diverged and converged from half the rule's coarse intervals
    (retry_coarser_start) makes the later probes start from that share of the rule at once;
    without such a probe the rule stands."""
    from types import SimpleNamespace

    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import coarse_intervals, problem_from_moes
    from ehl_multigrid.point.solve import learned_coarse

    pb = problem_from_moes(3000.0, 10.0, 1.0, "roelands", "dowson-higginson", None, None, None)
    wide = PointOptions(points=1025, xmin=-9.0, xmax=3.0, ymax=6.0)
    rule = coarse_intervals(pb.M, 12.0, 1025)
    assert rule == 128
    plain = SimpleNamespace(success=True, actions=[], levels=4)
    assert learned_coarse(pb, {wide: plain}, 2049, 24.0) is None
    retried = SimpleNamespace(success=True, levels=5,  # 1024 / 2^4 = 64 coarse intervals
                              actions=["ended diverged (...); solved again with 64 coarse intervals "
                                       "instead of 128 (retry_coarser_start): converged"])
    assert learned_coarse(pb, {wide: retried}, 2049, 24.0) == coarse_intervals(pb.M, 24.0, 2049) // 2 == 128
    failed = SimpleNamespace(success=False, levels=5, actions=retried.actions)
    assert learned_coarse(pb, {wide: failed}, 2049, 24.0) is None


def test_a_tighter_probe_starts_from_the_looser_probe_of_its_grid_and_box():
    """The box series needs its probes tighter than the domain probes on the same grids and
    boxes: each continues from the looser probe instead of a new FMG, in fewer work units, to
    the change a probe solved afresh at the tight tolerance gives."""
    from dataclasses import replace

    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import problem_from_moes
    from ehl_multigrid.point.solve import looser_probe, point_domain_change, solve_fas

    pb = problem_from_moes(20.0, 10.0, 1.0, "roelands", "dowson-higginson", None, None, None)
    sol = solve_fas(pb, PointOptions(points=257, half=True, film_tol=5e-4))
    cache: dict = {}
    point_domain_change(pb, sol.options, sol, cache)
    loose = dict(cache)
    warm = point_domain_change(pb, sol.options, sol, cache, tight=1e-5)
    tight = {o: r for o, r in cache.items() if o not in loose}
    assert len(loose) == len(tight) == 2
    for o, r in tight.items():
        start = looser_probe(loose, o)
        assert start is not None and start.options.film_tol > o.film_tol
        assert r.success and r.scalars["work_units"] < 0.7 * start.scalars["work_units"]
        assert looser_probe(tight, replace(o, film_tol=1e-6)) is r  # the tightest so far
        assert looser_probe(loose, replace(o, xmin=2.0 * o.xmin)) is None  # another box
    fresh = point_domain_change(pb, sol.options, sol, {}, tight=1e-5)
    assert warm[0] == pytest.approx(fresh[0], abs=1e-4) and warm[1] == pytest.approx(fresh[1], abs=1e-4)


def test_a_tolerance_step_of_the_solve_reuses_its_domain_probes(monkeypatch):
    from dataclasses import replace

    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import problem_from_moes

    pb = problem_from_moes(20.0, 10.0, 1.0)
    opts = PointOptions(points=129, half=True, film_tol=1e-4, raise_on_failure=False, far_field=False)
    sol = point_solve.solve_fas(pb, opts)
    cache = {}
    first = point_solve.point_domain_change(pb, opts, sol, cache)
    seen = []
    original = point_solve.solve_fas
    monkeypatch.setattr(point_solve, "solve_fas",
                        lambda problem, options, **kw: seen.append(options) or original(problem, options, **kw))
    # the solve's tolerances ten times tighter: the probes stop on their own film tolerance
    # (PROBE_FILM_TOL), so they are the same and none is solved again
    tighter = replace(opts, tol=0.1 * opts.tol, tol_load=0.1 * opts.tol_load, film_tol=1e-5)
    again = point_solve.point_domain_change(pb, tighter, sol, cache)
    assert first is not None and again == first and seen == []


def _record_solves(monkeypatch) -> list:
    """The options of every point solve from here on (``point.solve.solve_fas``), in order."""
    seen = []
    original = point_solve.solve_fas
    monkeypatch.setattr(point_solve, "solve_fas",
                        lambda problem, options, **kw: seen.append(options) or original(problem, options, **kw))
    return seen


@pytest.mark.solver
def test_a_box_series_that_cannot_meet_the_target_solves_no_wider_probe(monkeypatch):
    from ehl_multigrid.multigrid.accuracy import DECAY_SAFETY, MESH_SAFETY
    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import default_domain, problem_from_moes

    pb = problem_from_moes(20.0, 10.0, 1.0)
    opts = PointOptions(points=513, half=True, film_tol=1e-4, raise_on_failure=False)
    sol = point_solve.solve_fas(pb, opts)
    seen = _record_solves(monkeypatch)
    cache = {}
    # no room left by the grid and iteration parts: the two cheap pairs decide, nothing wider
    assert point_solve.point_box_series(pb, opts, sol, cache, left=(1e-6, 1e-6)) is None
    x0 = default_domain(pb)[0]
    assert seen and max(o.xmin / x0 for o in seen) == pytest.approx(2.0)
    assert "mesh dependence" in sol.extra["box_series_skipped"]
    # the bound it used is the part of the correction's error those pairs measure
    fine = point_solve.point_domain_change(pb, opts, sol, cache, tight=point_solve.SERIES_FILM_TOL)
    rough = point_solve.point_domain_change(pb, opts, sol, cache, coarser=1, tight=point_solve.SERIES_FILM_TOL)
    least = max(DECAY_SAFETY * MESH_SAFETY * abs(f - r) for f, r in zip(fine, rough, strict=True))
    assert least > 1e-6
    # room enough: the series goes on to four times the box, reusing the pairs already solved
    n = len(seen)
    series = point_solve.point_box_series(pb, opts, sol, cache, left=(1.0, 1.0))
    assert series is not None and series.d4 is not None
    assert max(o.xmin / x0 for o in seen[n:]) == pytest.approx(4.0)
    assert len(seen) == len(set(seen))


def test_plain_probes_of_a_narrow_contact_run_on_the_circular_minimum_mesh(monkeypatch):
    from types import SimpleNamespace

    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import min_points, problem_from_moes

    pb = problem_from_moes(50.0, 10.0, 3.0)  # b/a 0.48: min_points 257, a circular contact's 129
    assert (min_points(pb.M, pb.b_over_a), min_points(pb.M)) == (257, 129)
    opts = PointOptions(points=513, half=True, raise_on_failure=False)
    planned = point_solve.planned_solve(pb, opts)
    seen = []

    def failing(problem, options, **kw):
        seen.append(int(options.points))
        return SimpleNamespace(success=False, status_name="diverged", actions=[], levels=1)

    monkeypatch.setattr(point_solve, "solve_fas", failing)
    assert point_solve.point_domain_change(pb, opts, planned, {}) is None
    assert seen[0] == 129  # a quarter of the solve's points: the circular floor allows it
    seen.clear()
    point_solve.point_domain_change(pb, opts, planned, {}, tight=point_solve.SERIES_FILM_TOL)
    assert seen[0] == 257  # the box series keeps the contact's own floor


@pytest.mark.solver
def test_a_large_solve_takes_the_second_box_change_from_the_coarse_mesh_when_the_meshes_agree(monkeypatch):
    """The change beyond twice the box is measured on the coarse mesh and scaled by the first
    change's ratio of the two meshes (COARSE_D4_FROM, lowered here to this 513-point solve);
    where the first changes of the two meshes differ by more than COARSE_D4_AGREEMENT, on the
    probe mesh as before."""
    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import problem_from_moes

    pb = problem_from_moes(100.0, 10.0, 1.0)
    opts = PointOptions(points=513, half=True, film_tol=2.5e-4, raise_on_failure=False, far_field=False)
    sol = point_solve.solve_fas(pb, opts)
    seen = _record_solves(monkeypatch)
    monkeypatch.setattr(point_solve, "COARSE_D4_FROM", 513)
    cache = {}
    coarse = point_solve.point_box_series(pb, opts, sol, cache)
    assert max(o.points for o in seen) == 257  # the 4x box on 65 points per default box, not 129
    kind = sol.extra["box_series_hm"] == "sub-grid"
    d2, d2c = (point_solve.point_domain_change(pb, opts, sol, cache, tight=point_solve.SERIES_FILM_TOL,
                                               coarser=c, hm_sub=kind) for c in (0, 1))
    low = point_solve.point_domain_change(pb, opts, sol, cache, boxes=(1.0, 2.0, 4.0), coarser=1,
                                          tight=point_solve.SERIES_FILM_TOL, hm_sub=kind)
    assert all(abs(c - d) <= point_solve.COARSE_D4_AGREEMENT * abs(d) for c, d in zip(d2c, d2, strict=True))
    assert coarse.d2 == d2 and coarse.d4 == pytest.approx([low[1][i] * d2[i] / d2c[i] for i in (0, 1)])
    monkeypatch.setattr(point_solve, "COARSE_D4_AGREEMENT", 0.0)
    seen.clear()
    fine = point_solve.point_box_series(pb, opts, sol, cache)
    assert max(o.points for o in seen) == 513 and fine.d2 == d2 and fine.d4 != coarse.d4


def test_a_probe_that_ran_out_of_cycles_is_not_solved_again_at_a_tighter_tolerance():
    """A probe that failed from its FMG start fails again at a tighter film and load tolerance
    (the same cycles from the same start): the cache answers it; another grid, box or coarse
    start, or a looser tolerance, is solved."""
    from dataclasses import replace
    from types import SimpleNamespace

    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.solve import failed_looser

    o = PointOptions(points=1025, xmin=-36.0, xmax=12.0, ymax=24.0, film_tol=1e-4, tol_load=1e-4)
    failed = SimpleNamespace(success=False)
    cache = {o: failed}
    tighter = replace(o, film_tol=1e-5, tol_load=1e-5)
    assert failed_looser(cache, tighter) is failed
    assert failed_looser(cache, o) is failed
    assert failed_looser(cache, replace(o, film_tol=1e-3, tol_load=1e-3)) is None  # looser
    assert failed_looser(cache, replace(tighter, points=2049)) is None
    assert failed_looser(cache, replace(tighter, xmin=-18.0)) is None
    assert failed_looser(cache, replace(tighter, n_coarse=64)) is None
    assert failed_looser({o: SimpleNamespace(success=True)}, tighter) is None  # converged: looser_probe


def test_a_probe_out_of_cycles_on_the_rules_coarse_grid_is_solved_again_from_half_of_it(monkeypatch):
    """circular (5, 0), 1025 points on eight times the box: 128 coarse intervals ran out of
    cycles (1136 work units), 64 converge in 146; the answer is the converged attempt, charged
    for both. A probe with its own coarse grid, or fewer than 64 intervals, is left as it is."""
    from types import SimpleNamespace

    from ehl_multigrid.multigrid.options import PointOptions

    calls = []

    def fake_solve(problem, options):
        calls.append(options.n_coarse)
        return SimpleNamespace(success=True, status_name="converged", work_units=146.0, wall_s=7.0,
                               actions=[])

    monkeypatch.setattr(point_solve, "solve_fas", fake_solve)
    o = PointOptions(points=1025, xmin=-36.0, xmax=12.0, ymax=24.0)
    failed = SimpleNamespace(success=False, status_name="max_cycles", levels=4, work_units=1136.0,
                             wall_s=55.0, actions=[])
    r = point_solve.coarser_probe(None, o, failed)
    assert calls == [64] and r.success and r.work_units == 1136.0 + 146.0
    assert "128 coarse intervals" in r.actions[-1]
    assert point_solve.coarser_probe(None, o, SimpleNamespace(**{**vars(failed), "levels": 5})) \
        .status_name == "max_cycles"  # 64 intervals: not halved again
    own = PointOptions(points=1025, xmin=-36.0, xmax=12.0, ymax=24.0, n_coarse=128)
    assert point_solve.coarser_probe(None, own, failed) is failed
    assert calls == [64]


def test_a_probe_that_fails_from_half_its_coarse_grid_too_keeps_its_first_answer_charged_for_both(monkeypatch):
    from types import SimpleNamespace

    from ehl_multigrid.multigrid.options import PointOptions

    monkeypatch.setattr(point_solve, "solve_fas", lambda problem, options: SimpleNamespace(
        success=False, status_name="diverged", work_units=40.0, wall_s=2.0, actions=[]))
    failed = SimpleNamespace(success=False, status_name="max_cycles", levels=4, work_units=1136.0,
                             wall_s=55.0, actions=[])
    r = point_solve.coarser_probe(None, PointOptions(points=1025), failed)
    assert r is failed and r.work_units == 1176.0 and "diverged" in r.actions[-1]


@pytest.mark.solver
def test_a_fine_probe_first_looks_on_the_mesh_twice_as_coarse_and_bounds_the_probe_mesh_change():
    """A probe mesh of 257 points per box (a 1025-point solve) first looks on 129: where twice
    that change leaves a domain part under a quarter of the target, it is the answer and the
    257-point pair is not solved; the margined look bounds the probe mesh's own change."""
    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import problem_from_moes
    from ehl_multigrid.point.solve import LOOK_MARGIN, planned_solve, point_domain_change

    pb = problem_from_moes(100.0, 10.0, 1.0, "roelands", "dowson-higginson", None, None, None)
    opts = PointOptions(points=1025, half=True, raise_on_failure=False, film_tol=2.5e-4)
    cache, used = {}, []
    plan = planned_solve(pb, opts)
    looked = point_domain_change(pb, opts, plan, cache, used=used, look=0.005)
    assert sorted(int(r.options.points) for r in used) == [129, 257]  # the look's pair alone
    assert "halved" in plan.extra["domain_note"]
    coarse = point_domain_change(pb, opts, planned_solve(pb, opts), cache, coarser=1)
    assert looked == pytest.approx(tuple(LOOK_MARGIN * c for c in coarse), rel=0, abs=0)
    fine = point_domain_change(pb, opts, planned_solve(pb, opts), cache)
    assert all(abs(f) <= abs(m) for f, m in zip(fine, looked, strict=True)), (fine, looked)
    # a target the look cannot show met: the probe mesh's own change
    assert point_domain_change(pb, opts, planned_solve(pb, opts), cache, look=1e-5) == fine


def test_a_look_is_taken_only_on_a_mesh_that_holds_the_solves_film():
    """The chapter-6 0.5 GPa ball's 1025-point solve holds Hc 7.9 % off on 129 points, where its
    look's wide probe stopped at a residual floor; the 6205's 257 points are 2.5 % off."""
    from types import SimpleNamespace

    from ehl_multigrid.point.solve import PlannedSolve, resolved_on

    def solve(films, top):
        return SimpleNamespace(fmg=[{"points": n, "Hc": hc} for n, hc in films.items()],
                               scalars={"Hc_venner": top})

    assert not resolved_on(solve({129: 0.05308, 257: 0.05652}, 0.05761), 129)
    assert resolved_on(solve({257: 0.05662, 513: 0.05778}, 0.05807), 257)
    assert resolved_on(solve({513: 0.05778}, 0.05807), 257)  # no film there: not known
    assert resolved_on(PlannedSolve(levels=3, X=[0.0, 1.0]), 129)  # not solved yet
