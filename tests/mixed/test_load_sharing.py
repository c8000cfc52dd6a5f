"""Load sharing (4.21)-(4.29): Table 4.1, the equations at the solution, and the extremes."""

import math

import numpy as np
import pytest

from ehl_multigrid.model import fits
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene
from mixed.film import johnson_film
from mixed.gw import asperity_pressure
from mixed.roots import bracketed_root
from mixed.sharing import _Problem, load_sharing

# Thesis Table 4.1 (page 66): us, load -> Pa, Ph, gamma2, gamma1, h (hf,r), hss
TABLE_4_1 = [
    (0.056, 500, 453, 47, 1.1, 10.6, 6.78e-8, 0.28e-8),
    (0.056, 2000, 1784, 216, 1.12, 9.3, 4.87e-8, -2.27e-8),
    (0.56, 500, 27, 473, 18.5, 1.06, 13.4e-8, 7.55e-8),
    (0.56, 2000, 139, 1861, 14.44, 1.07, 11.4e-8, 5.45e-8),
]


@pytest.mark.parametrize("row", TABLE_4_1, ids=lambda r: f"{r[0]}m/s-{r[1]}N")
def test_table_4_1_is_reproduced_within_2_percent(row):
    us, P, Pa, Ph, g2, g1, h, hss = row
    ls = load_sharing(load_scene(f"page63_line_{P}N"), us)
    got = dict(Pa=ls.Pa[0], Ph=ls.Ph[0], gamma2=ls.gamma2[0], gamma1=ls.gamma1[0], h=ls.hfr[0], hss=ls.hss[0])
    want = dict(Pa=Pa, Ph=Ph, gamma2=g2, gamma1=g1, h=h, hss=hss)
    for k in want:
        assert got[k] == pytest.approx(want[k], rel=0.02), k


@pytest.mark.parametrize("name", ["page63_line_8000N", "series_A_disc1_0.78GPa", "series_D_disc4_1.93GPa"])
def test_every_equation_holds_at_the_solution(name):
    sc = load_scene(name)
    us = np.geomspace(1e-3, 10, 9)
    ls = load_sharing(sc, us)
    r = sc.roughness
    # (4.21)-(4.22)
    assert np.allclose(1 / ls.gamma1 + 1 / ls.gamma2, 1.0, rtol=1e-12)
    assert np.allclose(ls.Pa + ls.Ph, sc.load, rtol=1e-12)
    # (4.23)/(4.25): film is the mixed fit at gamma1
    theta = 1.0 if sc.kind == "line" else sc.theta
    for i, u in enumerate(us):
        M, L = sc.moes(u)
        Hc = fits.central_film_fit(sc.kind, M, L, theta, ls.gamma1[i])
        assert ls.hfr[i] == pytest.approx(Hc * sc.film_scale(u), rel=1e-12)
    # (4.27)-(4.28)
    assert np.allclose(johnson_film(ls.hs, r.Rq), ls.hfr, rtol=1e-11)
    assert np.allclose(ls.hss, ls.hs - r.dd, rtol=0, atol=1e-22)
    # (4.29): asperity load from GW at hss
    Pa_gw = sc.hertz.area * asperity_pressure(ls.hss, r.n, r.beta, r.sigma_s, sc.E_reduced)
    assert np.allclose(Pa_gw, ls.Pa, rtol=1e-9)


def test_gamma1_tends_to_one_at_high_speed_and_gamma2_at_low_speed():
    sc = load_scene("page63_line_2000N")
    ls = load_sharing(sc, [1e-9, 1e-6, 1e2, 1e3])
    assert ls.gamma2[0] - 1 < 1e-7 and ls.gamma2[1] - 1 < 1e-3  # boundary: asperities carry it all
    assert ls.gamma1[2] - 1 < 1e-12 and ls.gamma1[3] == 1.0  # full film
    assert ls.Pa[3] < 1e-100 * sc.load and ls.Pa[3] >= 0.0


def test_high_load_gives_negative_separation_with_a_positive_film():
    sc = load_scene("page63_line_16000N")
    ls = load_sharing(sc, np.geomspace(1e-3, 0.03, 5))
    assert np.all(ls.hs < 0) and np.all(ls.hss < -ls.roughness.dd)
    assert np.all(ls.hfr > 0)
    assert np.all(ls.Pa < sc.load) and np.all(ls.hs > ls.hs_min)


def test_asperity_share_falls_monotonically_with_speed_for_line_and_point():
    for name in ("page63_line_500N", "series_C_disc3_1.93GPa"):
        ls = load_sharing(load_scene(name), np.geomspace(1e-4, 1e2, 40))
        f = ls.asperity_fraction
        assert np.all(np.diff(f[f > 1e-300]) < 0)  # beyond, the share underflows to exactly 0
        assert np.all(np.diff(f) <= 0)
        assert np.all(np.diff(ls.hfr) > 0)


def test_residual_is_monotonic_in_log_gamma1_minus_1():
    sc = load_scene("series_B_disc2_1GPa")
    us = np.geomspace(1e-3, 1e1, 5)
    prob = _Problem(sc, us, sc.load, sc.roughness, math.inf, 3.5)
    xs = np.linspace(-40, 40, 161)
    for i in range(us.size):
        r = prob.residual(xs, np.full(xs.size, i))
        assert np.all(np.diff(r) < 0)


def test_tolerance_refinement_converges():
    # accuracy of the root finder: tightening xtol changes ln(gamma1 - 1) by less than the loose tolerance
    sc = load_scene("page63_line_2000N")
    us = np.geomspace(1e-3, 1.0, 7)
    loose = load_sharing(sc, us, xtol=1e-6)
    tight = load_sharing(sc, us, xtol=1e-13)
    assert np.allclose(np.log(loose.gamma1 - 1), np.log(tight.gamma1 - 1), atol=2e-6)
    assert tight.report.converged and tight.report.iterations < 60


def test_elliptic_scene_with_equal_radii_matches_the_point_contact():
    sc = load_scene("series_A_disc2_1GPa")
    d = sc.to_dict()
    d["contact"]["kind"] = "elliptic"
    d["geometry"]["Ry"] = d["geometry"]["Rx"] * (1 + 1e-12)
    ell = Scene.from_dict(d)
    a = load_sharing(sc, [0.01, 0.3])
    b = load_sharing(ell, [0.01, 0.3])
    assert np.allclose(a.gamma1, b.gamma1, rtol=1e-8)


def test_vectorised_root_finder_solves_independent_monotone_equations():
    t = np.array([1e-3, 0.1, 1.0, 50.0])
    f = lambda x, i: np.log(t[i]) - (x**3 + x)  # noqa: E731
    lo, hi = np.full(4, -20.0), np.full(4, 20.0)
    idx = np.arange(4)
    res = bracketed_root(f, lo, hi, f(lo, idx), f(hi, idx), xtol=1e-13)
    assert np.all(res.converged)
    assert np.allclose(res.x**3 + res.x, np.log(t), atol=1e-11)


def test_missing_roughness_and_bad_speeds_raise_input_error():
    with pytest.raises(InputError, match="roughness"):
        load_sharing(load_scene("appendix_c_line_4240N"))
    sc = load_scene("page63_line_500N")
    with pytest.raises(InputError, match="us"):
        load_sharing(sc, [0.1, -1.0])
    d = sc.to_dict()
    d["roughness"].pop("n")
    with pytest.raises(InputError, match="roughness.n"):
        load_sharing(Scene.from_dict(d))


def test_film_factor_calibrates_the_fitted_film_at_every_speed():
    from mixed.sharing import fitted_film
    from mixed.stribeck import transition_speed

    sc = load_scene("page63_line_2000N")
    us = np.geomspace(0.01, 100.0, 25)
    k = 0.8
    ref = load_sharing(sc, us)
    cal = load_sharing(sc, us, film_factor=k)
    assert cal.film_factor == k and ref.film_factor == 1.0
    # at a given load share the film is the fit times k, exactly
    for u, g1 in ((0.05, 1.0), (0.5, 3.0), (20.0, 1.2)):
        assert fitted_film(sc, u, g1, film_factor=k) == pytest.approx(k * fitted_film(sc, u, g1), rel=1e-14)
    # full film (fast end): the film follows the factor; everywhere the thinner film puts more
    # load on the asperities and the transitions to full film move to higher speed
    assert cal.hfr[-1] == pytest.approx(k * ref.hfr[-1], rel=1e-9)
    assert np.all(cal.Pa >= ref.Pa * (1 - 1e-12)) and cal.Pa[10] > 1.01 * ref.Pa[10]
    assert transition_speed(sc, 0.05, film_factor=k) > transition_speed(sc, 0.05)
    with pytest.raises(InputError, match="film_factor"):
        load_sharing(sc, us, film_factor=0.0)
