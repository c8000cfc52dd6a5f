"""A point film whose grid sequence starts just above a grid without a positive film takes its
coarser grids from converged solves (multigrid/accuracy.py, ``_SteadyControl.filmless_below``):
the FMG films there carry the algebraic error of an interpolated non-film."""

import types

import pytest

import ehl_multigrid as ehl
from ehl_multigrid.multigrid.accuracy import ErrorEstimate, _SteadyControl


def _result(below_hc: float, levels: int = 5):
    fmg = [{"points": 65, "level": 0, "Hc": -0.03, "Hm": -0.03},
           {"points": 129, "level": 1, "Hc": below_hc, "Hm": 0.001},
           {"points": 257, "level": 2, "Hc": 0.0023, "Hm": 0.0010},
           {"points": 513, "level": 3, "Hc": 0.0036, "Hm": 0.0012},
           {"points": 1025, "level": 4, "Hc": 0.0040, "Hm": 0.0013}]
    return types.SimpleNamespace(levels=levels, fmg=fmg)


def _fires(res, extrapolated=("Hm",), dimensions=2, finals=None):
    ctl = types.SimpleNamespace(dimensions=dimensions, finals=finals or {})
    est = ErrorEstimate(0.04, 0.06, extrapolated=extrapolated)
    return _SteadyControl.filmless_below(ctl, res, est, 1025, "key")


def test_a_sequence_starting_above_a_filmless_grid_asks_for_converged_coarser_films():
    assert _fires(_result(-0.0056))  # 129 points: the grid below 257, 513 and 1025
    assert not _fires(_result(0.0008))  # a positive film there
    assert not _fires(_result(-0.0056), extrapolated=("Hc", "Hm"))  # both films extrapolated
    assert not _fires(_result(-0.0056), dimensions=1)  # line contacts have their own rules
    assert not _fires(_result(-0.0056), finals={"key": {513: (0.0, 0.0, 0.0)}})  # already solved


@pytest.mark.slow
def test_the_stated_errors_of_a_heavily_loaded_point_contact_cover_tight_finer_solves():
    # series C (M 6114): the Richardson limit of tight solves on 1025, 2049, 4097 points (half
    # domain, tol 1e-8: Hc 1.74028, 1.80874, 1.82612; Hm 0.34197, 0.39500, 0.40417); on the
    # FMG films alone the 1025-point answer stated Hc 4.6 % for a true 5.0 %
    hc_limit, hm_limit = 1.82612 + 0.01738 / 3.0, 0.40417 + 0.00917 / 3.0
    sol = ehl.solve("series_C_disc3_1.93GPa", physics="steady", accuracy=0.1, options={"half": True})
    assert sol.success
    assert abs(sol.Hc / hc_limit - 1.0) <= sol.error.Hc
    assert abs(sol.Hm / hm_limit - 1.0) <= sol.error.Hm
