"""The Stribeck stage calibrates the fitted film on the film stage's solved film; when that
solve was starved, on its flooded companion, because the curves apply each supply's
starvation themselves (6.4) -- otherwise the starvation would count twice."""

from types import SimpleNamespace

import numpy as np
import pytest

from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.model.solved_film import SolvedFilm
from mixed.stage import film_calibration


def _ctx(hc, Hc_ratio=None):
    scene = load_scene("chapter6_starved_0.5GPa")
    x, y = np.linspace(-1e-4, 1e-4, 3), np.linspace(0.0, 1e-4, 2)
    film = SolvedFilm("point", scene, hc, Hc_ratio, x, y, np.zeros((3, 2)), np.full((3, 2), hc), "converged")
    return SimpleNamespace(scene=scene, plan=None, film=lambda: film), scene


def test_a_flooded_solve_calibrates_on_its_own_film():
    ctx, scene = _ctx(2.0e-8)
    k, text = film_calibration(ctx)
    assert k == pytest.approx(2.0e-8 / scene.central_film_fit()[1])
    assert "flooded" not in text


def test_a_starved_solve_calibrates_on_its_flooded_companion_not_on_the_starved_film():
    ctx, scene = _ctx(1.2e-8, Hc_ratio=0.6)
    k, text = film_calibration(ctx)
    assert k == pytest.approx(2.0e-8 / scene.central_film_fit()[1])
    assert "flooded" in text and "6.4" in text
