"""A nested TEHL solve whose start from the coarser grid's factors fails is solved again from
its own isothermal start (thermal.tehl.accuracy.SolveCache); a failure of the outer iteration
itself is not repeated."""

from types import SimpleNamespace

import pytest

import thermal.tehl.line as tl
from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.model.scene import load_scene
from thermal.tehl.accuracy import SolveCache
from thermal.tehl.options import TEHLOptions
from thermal.tehl.outer import CoarseStartError


def _cache(monkeypatch, error: type[ConvergenceError]):
    calls = []

    def fake(scene, slip, opts, meniscus=None, coarse=None):
        calls.append(coarse)
        if coarse is not None or error is ConvergenceError:
            raise error("TEHL outer iteration 0: the multilevel solve failed: diverged")
        report = SimpleNamespace(extra={"actions": []}, converged=True)
        return SimpleNamespace(options=opts, report=report, starved=None)

    monkeypatch.setattr(tl, "solve_tehl_line", fake)
    cache = SolveCache(load_scene("spur_gear_pitch_point"), 0.5, TEHLOptions(points=257, nz=10), point=False)
    cache.results[(129, 10, 1.0)] = SimpleNamespace(options=TEHLOptions(points=129, nz=10))
    return cache, calls


def test_a_failed_start_from_the_coarser_factors_is_solved_again_from_the_isothermal_start(monkeypatch):
    cache, calls = _cache(monkeypatch, CoarseStartError)
    res = cache(257, 10, 1.0)
    assert res is not None and len(calls) == 2 and calls[0] is not None and calls[1] is None
    assert (257, 10, 1.0) not in cache.errors
    assert any("129-point solve failed" in a for a in res.report.extra["actions"])


def test_a_failed_outer_iteration_is_not_solved_again(monkeypatch):
    cache, calls = _cache(monkeypatch, ConvergenceError)
    assert cache(257, 10, 1.0) is None
    assert len(calls) == 1 and "diverged" in cache.errors[(257, 10, 1.0)]


def test_a_failed_first_multilevel_solve_with_the_coarse_factors_is_a_coarse_start_error():
    import numpy as np

    from thermal.tehl.outer import Iterate, coupled_solve

    failed = SimpleNamespace(success=False, status=2, residual_history=[1.0], history=[],
                             message="diverged on grid 3", report=None)
    hz = SimpleNamespace(set_factors=lambda a, c: None, set_iterate=lambda P, H0: None, levels=[0, 1])
    contact = SimpleNamespace(hierarchy=hz, options=SimpleNamespace(tol=1e-5), label="TEHL", hint="",
                              notes=[], multilevel=lambda: (failed, None, None, None),
                              finer_factor=lambda f: np.ones(5), factors=lambda th: (np.ones(5), np.ones(5)))
    one = np.ones(5)
    state = Iterate(one, one, 0.0, 1.0, 1.0)
    coarse = SimpleNamespace(a=np.ones(3), c=np.ones(3), X=np.zeros(3))
    with pytest.raises(CoarseStartError, match="diverged on grid 3"):
        coupled_solve(contact, state, None, one, one, one, TEHLOptions(), coarse)
