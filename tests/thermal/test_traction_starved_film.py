"""Traction from Hertz input on a starved scene uses the starved film, not the flooded fit."""

from __future__ import annotations

import pytest

from ehl_multigrid.model.scene import load_scene
from thermal.traction import solve_traction


def test_hertz_input_of_a_starved_scene_uses_the_supplied_film() -> None:
    flooded = load_scene("appendix_c_line_4240N")
    starved = flooded.with_supply(hoil=0.3 * flooded.central_film_fit()[1])
    opts = {"nx": 20, "nz": 5}
    f = solve_traction(flooded, 0.1, **opts)
    s = solve_traction(starved, 0.1, **opts)
    assert f.h == pytest.approx(flooded.central_film_fit()[1])
    assert s.h == pytest.approx(starved.supplied_film_fit()[1])
    assert s.h < 0.35 * f.h
