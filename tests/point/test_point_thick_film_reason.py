"""A thick-film (low M) point contact that misses its target says why in physical terms: the
inlet length its film still depends on, and, where the box probes did not converge, that the box
error matters there but could not be measured."""

import math
import re
from types import SimpleNamespace

from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import thick_film_reason


def _result(domain: float):
    budget = {"grid": {"Hc": 0.001, "Hm": 0.05}, "domain": {"Hc": domain, "Hm": domain},
              "algebraic": {"Hc": 1e-4, "Hm": 1e-4}}
    return SimpleNamespace(error=SimpleNamespace(budget=budget), extra={"domain": (-9.0, 3.0, 6.0)})


def test_thick_film_reason_names_the_inlet_needed_when_the_box_error_dominates():
    pb = problem_from_moes(5.0, 20.0, 4.0, viscosity="barus", density="incompressible")
    why = thick_film_reason(pb, _result(0.05), 0.01)
    # half of the 1 % target left to the box: 9 a x 5 % / 0.5 % = 90 a
    assert re.search(r"\b90 a\b.*\bbox: 9 a\b", why), why  # the inlet needed, the box's


def test_thick_film_reason_is_silent_when_the_box_error_is_small():
    pb = problem_from_moes(5.0, 20.0, 4.0, viscosity="barus", density="incompressible")
    assert thick_film_reason(pb, _result(0.001), 0.01) == ""


def test_thick_film_reason_says_the_box_error_was_not_measured_when_its_probes_failed():
    pb = problem_from_moes(5.0, 20.0, 4.0, viscosity="barus", density="incompressible")
    why = thick_film_reason(pb, _result(math.nan), 0.01)
    assert "M = 5" in why and "thick" in why
    assert "did not converge" in why and "needs an inlet" not in why
