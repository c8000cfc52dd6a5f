"""Error budget of TEHL solutions (grid along X and across the film, box, iteration) and the
accuracy-driven TEHL solve: the point estimate covers a finer solve, the refinement raises
the grid under a tight target and stops within its budget, and ``ehl solve --thermal`` on a
point contact is converged only when the estimate meets the target."""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.multigrid.controller import choose
from thermal.tehl import TEHLOptions, estimate_error, solve_tehl_line
from thermal.tehl.accuracy import (
    MAX_NZ,
    SolveCache,
    extrapolated_films,
    grid_sequence,
    solve_tehl_to_accuracy,
    step_candidates,
)

#: appendix D ball on flat (T9, 8 m/s, 60 degC) at 5 N: resolved from 65 points
POINT_LOAD = 5.0
#: the same at S = 0.5 on 257 points, nz = 20 (one grid finer along X and across the film
#: than the case below), a stored solve of this solver
POINT_FINE = {"Hc": 3.924134836115908, "Hm": 2.5763119913152797}


pytestmark = pytest.mark.solver


def next_step(est, accuracy, points, nz, box, tol_scale, max_points, max_nz=MAX_NZ, box_limit=4.0):
    """The refinement the controller takes among step_candidates: (what, points, nz, box, tol)."""
    c = choose(step_candidates(est, points, nz, box, tol_scale, max_points, max_nz, box_limit),
               accuracy, est.worst)
    return None if c is None else (c.what, c.at.points, c.at.nz, c.at.box, c.at.tol)


@pytest.fixture(scope="module")
def point_scene():
    return load_scene("appendix_d_point").with_operating(load=POINT_LOAD)


# the solve estimated here is test_tehl_point.py's cold start (one worker builds it once)
@pytest.mark.xdist_group("tehl_point_5n")
def test_point_estimate_is_finite_and_covers_the_finer_solve(tehl_ball_5n_129):
    r = tehl_ball_5n_129  # S = 0.5 on 129 points, nz = 10
    cache = SolveCache.of(r)
    e = estimate_error(r, cache=cache)
    for key in ("Hc", "Hm", "friction_coefficient"):
        assert all(math.isfinite(v) and v >= 0 for v in e[key].values()), key
    # 129 points have no quarter grid (33 < 65) to follow the temperature field over three
    # grids: T_max's grid part is unknown, said so, and the films do not depend on it
    assert math.isinf(e["T_max"]["grid_x"]) and any("T_max's grid error unknown" in n for n in e.notes)
    # the estimate reused the solves on every other node, on nz/2 and the box probe (a point
    # contact's probe on no fewer than 129 points per default box)
    assert {(65, 10, 1.0), (129, 5, 1.0), (257, 10, 2.0)} <= set(cache.results)
    for key, fine in POINT_FINE.items():
        true = abs(getattr(r, key) - fine) / fine
        assert true <= e[key]["total"], key
    assert e.Hc < 0.1 and e.Hm < 0.1


def test_line_estimate_has_a_box_part_from_a_wider_box():
    scene = load_scene("appendix_c_line_4240N")
    r = solve_tehl_line(scene, 0.5, points=257, nz=10)
    e = estimate_error(r)
    assert e.domain is not None and e.domain["points"] == 65
    assert 0 < e["Hc"]["domain"] < e["Hc"]["grid_x"]
    # without the box part the total is not known
    assert math.isnan(estimate_error(r, domain=False)["Hc"]["total"])


def test_refinement_raises_the_grid_under_a_tight_target_and_stops_within_budget():
    scene = load_scene("appendix_c_line_4240N")
    done = solve_tehl_to_accuracy(scene, 0.5, TEHLOptions(points=129, nz=8), 1e-4, max_points=257,
                                  max_nz=16, time_budget=120.0)
    steps = done.refinements
    assert not done.accurate and "not refined further" in done.message
    assert steps[0].points == 129 and steps[0].next == "points"
    assert max(s.points for s in steps) == 257 and max(s.nz for s in steps) <= 16
    assert done.result.options.points == 257
    # the returned solve is the most accurate one of the sequence
    assert done.estimate.worst == min(max(s.Hc_error, s.Hm_error) for s in steps)
    # a spent time budget stops the first solve at its first outer iteration
    from ehl_multigrid.multigrid.controller import TimeBudgetSpent

    with pytest.raises(TimeBudgetSpent, match="time budget of 0 s .* outer iteration 1"):
        solve_tehl_to_accuracy(scene, 0.5, TEHLOptions(points=129, nz=8), 1e-4, time_budget=0.0)


def test_next_step_refines_the_dominant_part():
    def est(gx, gz, dom, it):
        from thermal.tehl.accuracy import TEHLErrorEstimate

        b = {"grid_x": gx, "grid_z": gz, "domain": dom, "iteration": it}
        b["total"] = sum(b.values())
        return TEHLErrorEstimate({"Hc": b, "Hm": b}, (2.0, 2.0), {}, 0.0)

    assert next_step(est(0.02, 0.001, 0.001, 0.0), 0.01, 257, 20, 1.0, 1.0, 1025)[0] == "points"
    assert next_step(est(0.001, 0.02, 0.001, 0.0), 0.01, 257, 20, 1.0, 1.0, 1025)[0] == "nz"
    assert next_step(est(0.001, 0.001, 0.02, 0.0), 0.01, 257, 20, 1.0, 1.0, 1025)[:4] == ("box", 513, 20, 2.0)
    assert next_step(est(0.001, 0.001, 0.001, 0.02), 0.01, 257, 20, 1.0, 1.0, 1025)[0] == "tolerance"
    # nothing left within the limits
    assert next_step(est(0.02, 0.001, 0.001, 0.0), 0.01, 257, 20, 1.0, 1.0, 257) is None
    # an unknown grid part (the coarser solve failed) asks for more points
    assert next_step(est(math.nan, 0.001, 0.001, 0.0), 0.01, 257, 20, 1.0, 1.0, 1025)[0] == "points"


def test_ehl_solve_thermal_point_is_converged_when_the_estimate_meets_the_target(point_scene, tmp_path, capsys):
    from ehl_multigrid.app.cli import main

    f = tmp_path / "ball5N.toml"
    f.write_text(point_scene.to_toml())
    # S = 0.1 and nz = 8 (the fewest the estimate accepts): half the cost of S = 0.5, nz = 10,
    # whose estimate (Hc 0.050, Hm 0.066) is about the same (0.050, 0.061)
    base = ["solve", str(f), "--thermal", "--slip", "0.1", "--points", "129", "--nz", "8", "--json", "--no-plots",
            "--out", str(tmp_path / "o")]
    rc = main(base + ["--accuracy", "0.1"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["converged"] and out["contact"] == "point"
    assert max(out["Hc_error"], out["Hm_error"]) <= 0.1
    # the budget by part under the result contract's names, each with every stated quantity
    assert {"grid", "nz", "domain", "iteration"} <= set(out["error_budget"])
    assert set(out["error_budget"]["grid"]) == {"Hc", "Hm", "friction_coefficient", "T_max"}
    # the whole solve (the estimate's solves on half the grid and nz included) beside the returned one's
    assert out["wall_total_s"] > out["wall_s"] > 0


def _solve_stub(kind: str, Hc: float, Hm: float) -> SimpleNamespace:
    H = np.full((3, 5), 9.0)
    H[0, 2] = Hm  # the film's minimum on the symmetry row, as a point result's half domain holds it
    H[0, 1] = H[0, 3] = Hm + 0.5
    H[1, 2] = Hm + 0.5
    return SimpleNamespace(Hc=Hc, Hm=Hm, H=H, scene=SimpleNamespace(kind=kind),
                           problem=SimpleNamespace(moes_factor=1.0))


def test_films_of_a_second_order_sequence_are_extrapolated_by_a_third_of_the_last_difference():
    films = [2.0 - 1.0 / 4**k for k in range(4)]  # F* = 2, error h^2
    point = [_solve_stub("point", f, f / 2) for f in films]
    fixes = extrapolated_films(point)
    assert set(fixes) == {"Hc", "Hm"}
    d = films[-1] - films[-2]
    assert fixes["Hc"][0] == pytest.approx((films[-1] + d / 3) / films[-1] - 1.0)
    assert (films[-1] * (1 + fixes["Hc"][0])) == pytest.approx(2.0, rel=1e-12)
    # a line's Hm converges at about first order in the core: only Hc is extrapolated
    assert set(extrapolated_films([_solve_stub("line", f, f / 2) for f in films])) == {"Hc"}
    # an irregular sequence (ratios 2 and 8) is not
    assert extrapolated_films([_solve_stub("point", f, 1.0) for f in (1.0, 1.8, 1.9, 1.9125)]) == {}


# the reference's 1025-point solve is test_tehl_line.py's cold start (one worker builds it once)
@pytest.mark.xdist_group("tehl_line_lo_1025")
def test_accuracy_driven_line_reports_hc_extrapolated_within_its_stated_error(tehl_line_lo_1025):
    scene = load_scene("appendix_c_line_4240N")
    done = solve_tehl_to_accuracy(scene, 0.5, TEHLOptions(points=513, nz=10), 0.005, refine=False)
    r, est = done.result, done.estimate
    assert set(est.correction) == {"Hc"} and r.grid_films is not None
    assert r.Hc == pytest.approx(r.grid_films[0] * (1.0 + est.correction["Hc"]), rel=1e-12)
    assert r.Hc / r.Hc_isothermal == pytest.approx(r.grid_films[0] / done.result.Hc_isothermal * (1.0 + est.correction["Hc"]), rel=1e-12)
    assert "Hc extrapolated" in done.message and "Hm extrapolated" not in done.message and r.summary()["Hc_field"] == r.grid_films[0]
    # reference: the same extrapolation one grid finer (129 ... 1025 points)
    cache = SolveCache(scene, 0.5, TEHLOptions(points=1025, nz=10), False)
    cache.add(tehl_line_lo_1025)  # the solve cache(1025, 10, 1.0) makes first: from the isothermal start
    fine = cache(1025, 10, 1.0)
    ref = fine.Hc * (1.0 + extrapolated_films(grid_sequence(fine, cache))["Hc"][0])
    true = abs(r.Hc / ref - 1.0)
    assert true <= est["Hc"]["grid_x"]
    # the extrapolation is closer to the reference than the grid's own film
    assert true < abs(r.grid_films[0] / ref - 1.0) / 5.0


def test_a_max_nz_below_the_solves_own_nz_is_refused_naming_it():
    import ehl_multigrid as ehl

    with pytest.raises(InputError, match=r"max_nz = 2 .*\[20, 640\]"):
        ehl.solve("appendix_c_line_4240N", physics="thermal", accuracy=0.05, options={"max_nz": 2})
