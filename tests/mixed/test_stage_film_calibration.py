"""The Stribeck stage calibrates the fitted film on the film stage's solved film; when that
solve was starved, on its flooded companion, because the curves apply each supply's
starvation themselves (6.4) -- otherwise the starvation would count twice."""

from types import SimpleNamespace

import pytest

from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import load_scene
from mixed.stage import film_calibration


def _ctx(scalars):
    scene = load_scene("chapter6_starved_0.5GPa")
    res = Result("ehl_point")
    for k, v in scalars.items():
        res.set_scalar(k, v)
    return SimpleNamespace(scene=scene, plan=None, result=lambda name: res if name == "film" else None), scene


def test_a_flooded_solve_calibrates_on_its_own_film():
    ctx, scene = _ctx({"hc": 2.0e-8})
    k, text = film_calibration(ctx)
    assert k == pytest.approx(2.0e-8 / scene.central_film_fit()[1])
    assert "flooded" not in text


def test_a_starved_solve_calibrates_on_its_flooded_companion_not_on_the_starved_film():
    ctx, scene = _ctx({"hc": 1.2e-8, "Hc_ratio": 0.6})
    k, text = film_calibration(ctx)
    assert k == pytest.approx(2.0e-8 / scene.central_film_fit()[1])
    assert "flooded" in text and "6.4" in text
