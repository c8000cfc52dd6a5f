"""Friction (4.30)-(4.39): the boundary and full-film limits, the isothermal film term, thermal path."""

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from mixed.friction import film_area, mixed_friction
from mixed.sharing import load_sharing
from mixed.stribeck import classify_regime, stribeck_curve, stribeck_options


def thermal_available():
    try:
        import thermal

        return callable(getattr(thermal, "film_friction", None))
    except ImportError:
        return False


@pytest.mark.parametrize("name", ["page63_line_16000N", "series_C_disc3_1.93GPa"])
def test_friction_tends_to_fc_at_vanishing_speed(name):
    sc = load_scene(name)
    ls = load_sharing(sc, [1e-9])
    fr = mixed_friction(sc, ls)
    assert fr.coefficient[0] == pytest.approx(sc.roughness.fc, rel=2e-3)
    assert fr.film[0] < 1e-3 * fr.asperity[0]


@pytest.mark.parametrize("name", ["page63_line_500N", "series_B_disc2_1GPa"])
def test_friction_tends_to_the_film_friction_at_high_speed(name):
    sc = load_scene(name)
    us = 200.0
    ls = load_sharing(sc, [us])
    fr = mixed_friction(sc, ls)
    assert fr.asperity[0] < 1e-12
    # independent full-film Eyring friction: Hertz area and mean pressure, film hf,r
    hz = sc.hertz
    eta = sc.lubricant.viscosity(hz.mean_pressure, sc.T_oil)
    gdot = abs(sc.slip) * us / 2 / ls.hfr[0]
    tau = sc.lubricant.tau0 * math.asinh(eta * gdot / sc.lubricant.tau0)
    assert fr.coefficient[0] == pytest.approx(tau * hz.area / sc.load, rel=1e-9)


def test_isothermal_film_term_uses_the_film_area_and_pressure_of_4_35_to_4_37():
    sc = load_scene("page63_line_2000N")
    ls = load_sharing(sc, [0.056])
    fr = mixed_friction(sc, ls)
    AH = sc.hertz.area * (ls.Ph[0] / sc.load) ** 0.5  # (4.36)
    assert fr.AH[0] == pytest.approx(AH, rel=1e-12)
    assert fr.pavehl[0] == pytest.approx(ls.Ph[0] / AH, rel=1e-12)
    # Hertz at load Ph has exactly this area and mean pressure (line and point)
    from ehl_multigrid.model.hertz import hertz_circular, hertz_line

    h = hertz_line(ls.Ph[0], sc.length, sc.Rx, sc.E_reduced)
    assert (h.area, h.mean_pressure) == (pytest.approx(AH, rel=1e-12), pytest.approx(fr.pavehl[0], rel=1e-12))
    pc = load_scene("series_A_disc1_1GPa")
    frac = 0.3
    assert film_area("point", pc.hertz.area, frac) == pytest.approx(hertz_circular(frac * pc.load, pc.Rx, pc.E_reduced).area, rel=1e-12)
    assert fr.coefficient[0] == pytest.approx(sc.roughness.fc * ls.Pa[0] / sc.load + fr.tau_film[0] * AH / sc.load, rel=1e-12)


def test_friction_scales_with_fc_and_vanishes_without_slip():
    sc = load_scene("page63_line_500N")
    ls = load_sharing(sc, [0.01, 0.1])
    a = mixed_friction(sc, ls, fc=0.1)
    b = mixed_friction(sc, ls, fc=0.2)
    assert np.allclose(b.asperity, 2 * a.asperity)
    rolling = mixed_friction(sc, ls, slip=0.0)
    assert np.all(rolling.film == 0.0)
    with pytest.raises(InputError, match="fc"):
        mixed_friction(sc, ls, fc=1.5)


def test_regimes_follow_the_asperity_share_thresholds():
    f = np.array([1.0, 0.96, 0.5, 0.05, 0.0])
    assert classify_regime(f, 0.95, 0.05).tolist() == [0, 0, 1, 2, 2]
    with pytest.raises(InputError, match="ehl_fraction"):
        stribeck_options(bl_fraction=0.5, ehl_fraction=0.6)


@pytest.mark.skipif(not thermal_available(), reason="thermal.film_friction not available")
def test_thermal_friction_runs_and_softens_the_film_at_high_speed():
    sc = load_scene("series_C_disc3_1.93GPa")
    us = np.array([1e-3, 0.05, 2.0])
    iso = stribeck_curve(sc, us, transitions=False)
    th = stribeck_curve(sc, us, thermal=True, transitions=False)
    assert th.converged and np.all(th.friction.thermal_converged)
    # the load sharing and the asperity part do not change with the thermal film (ch. 5.4)
    assert np.allclose(th.friction.asperity, iso.friction.asperity)
    assert np.all(th.friction.mean_temperature_rise >= 0)
    assert th.friction.mean_temperature_rise[-1] > 10.0
    assert th.friction.film[-1] < 0.9 * iso.friction.film[-1]
    assert th.friction.coefficient[0] == pytest.approx(iso.friction.coefficient[0], rel=0.01)


def test_scene_solver_table_sets_the_regime_thresholds_and_rejects_unknown_keys():
    from ehl_multigrid.model.scene import Scene

    d = load_scene("page63_line_500N").to_dict()
    d["solver"] = {"mixed": {"bl_fraction": 0.9, "ehl_fraction": 0.01}}
    opts = stribeck_options(Scene.from_dict(d))
    assert (opts["bl_fraction"], opts["ehl_fraction"]) == (0.9, 0.01)
    assert stribeck_options(Scene.from_dict(d), ehl_fraction=0.02)["ehl_fraction"] == 0.02
    d["solver"] = {"mixed": {"bl_fractoin": 0.9}}
    with pytest.raises(InputError, match="bl_fractoin"):
        stribeck_options(Scene.from_dict(d))
