"""The contact's heat thins the film where Gupta's inlet heating is nil: the thesis's page-63
line contact in pure sliding (S = 2, one surface at rest) at 0.056 m/s, thermal loading 5e-6,
and a ball sliding slowly. The planner stages the coupled film there (`plan.CONTACT_HEATING_FILM`,
`plan.CONTACT_HEATING_FILM_POINT`); this checks that the film it would otherwise report
isothermal is off by more than the 2 % tolerance."""

import warnings

import pytest

import ehl_multigrid as ehl
from ehl_multigrid.model.fits import gupta_thermal_factor
from ehl_multigrid.model.scene import load_scene


def test_pure_sliding_at_low_speed_thins_the_film_beyond_the_tolerance_gupta_misses():
    sc = load_scene("page63_line_2000N")
    L_T = sc.thermal_properties()["thermal_loading"]
    assert 1.0 - float(gupta_thermal_factor(L_T, sc.slip, sc.hertz.pmax / sc.E_reduced)) < 1e-3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = ehl.solve(sc, physics="thermal", accuracy=None, options={"slip": sc.slip, "points": 513})
    assert s.success
    sm = s.summary()
    # the thermal and isothermal films of one grid: 0.961 / 0.959 on 513 points, 0.962 / 0.959 on
    # 1025 (the front door at 2 %, stated errors 0.2 / 1.5 %): the ratio barely depends on the grid
    assert sm["Hc"] / s.details.Hc_isothermal < 0.98
    assert sm["Hm"] / s.details.Hm_isothermal < 0.98


@pytest.mark.slow
def test_a_point_contact_sliding_slowly_has_a_film_thinner_than_isothermal_beyond_the_tolerance():
    # the default ball (1 GPa) at 0.5 m/s, slip 1: Gupta's reduction 0.002; the surface moving at
    # 0.125 m/s (upstream Peclet number 0.42) conducts the contact's heat into the inlet: Hc 0.940
    # of isothermal on 513 points (0.948 on 1025 at 0.2 m/s); about 20 s
    sc = load_scene("default").with_operating(us=0.5, slip=1.0)
    L_T = sc.thermal_properties()["thermal_loading"]
    assert 1.0 - float(gupta_thermal_factor(L_T, sc.slip, sc.hertz.pmax / sc.E_reduced)) < 0.005
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = ehl.solve(sc, physics="thermal", accuracy=None, options={"slip": sc.slip, "points": 513, "estimate": False})
    assert s.success
    assert s.summary()["Hc"] / s.details.Hc_isothermal < 0.98
