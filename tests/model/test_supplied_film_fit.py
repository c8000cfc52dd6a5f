"""The fitted film of a starved scene: Chevalier's (6.1)-(6.4) applied to the flooded fit."""

from __future__ import annotations

import math

import pytest

from ehl_multigrid.model.lubricant import density_ratio_dh
from ehl_multigrid.model.scene import load_scene


def _starved(hoil: float, kind: str = "point", delta: float | str = 3.5):
    sc = load_scene("appendix_d_point" if kind == "point" else "appendix_c_line_4240N")
    return sc.with_supply(hoil=hoil, delta=delta)


def test_flooded_scene_gives_the_flooded_fit() -> None:
    sc = load_scene("appendix_d_point")
    assert sc.supplied_film_fit() == sc.central_film_fit()


@pytest.mark.parametrize("kind", ["point", "line"])
def test_starved_fit_never_carries_more_oil_than_supplied(kind: str) -> None:
    flooded = _starved(math.inf, kind).central_film_fit()[1]
    for factor in (0.01, 0.3, 1.0, 3.0):
        sc = _starved(factor * flooded, kind)
        hcs = sc.supplied_film_fit()[1]
        rho = float(density_ratio_dh(sc.hertz.pmax))
        assert hcs < flooded
        assert rho * hcs <= sc.supply.hoil * (1 + 1e-12)


def test_thin_supply_film_tends_to_the_compressed_layer() -> None:
    flooded = _starved(math.inf).central_film_fit()[1]
    sc = _starved(1e-4 * flooded)
    rho = float(density_ratio_dh(sc.hertz.pmax))
    assert sc.supplied_film_fit()[1] == pytest.approx(sc.supply.hoil / rho, rel=1e-6)


def test_inlet_exponent_is_used_for_delta_inlet() -> None:
    flooded = _starved(math.inf).central_film_fit()[1]
    a = _starved(flooded, delta="inlet").supplied_film_fit()[1]
    b = _starved(flooded, delta=20.0).supplied_film_fit()[1]
    assert a != b and a < flooded


def test_show_summary_of_a_starved_scene_gives_the_starved_fit_beside_the_flooded_one() -> None:
    flooded = load_scene("appendix_d_point")
    sc = _starved(0.3 * flooded.central_film_fit()[1])
    s = sc.summary()
    assert s["hc_fit_starved"] == pytest.approx(sc.supplied_film_fit()[1])
    assert s["hc_fit_starved"] < 0.35 * s["hc_fit"]
    assert "hc_fit_starved" not in flooded.summary()
