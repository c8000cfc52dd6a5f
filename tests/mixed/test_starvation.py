"""Starvation (chapter 6): Chevalier's reduction, the hs_min guard, varsigma exact vs approximate."""

import math

import numpy as np
import pytest
from scipy import integrate, optimize

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from mixed.film import johnson_film
from mixed.sharing import load_sharing
from mixed.starvation import (
    chevalier_reduction,
    limiting_inlet_film,
    limiting_inlet_film_for_roughness,
    log_starved_film,
)
from mixed.stribeck import stribeck_curve

US = np.geomspace(1e-3, 30.0, 25)


def test_chevalier_reduction_limits():
    assert chevalier_reduction(np.inf) == 1.0
    assert chevalier_reduction(1e6, 3.5) == pytest.approx(1.0, abs=1e-15)
    assert chevalier_reduction(1e-4, 3.5) == pytest.approx(1e-4, rel=1e-12)
    assert chevalier_reduction(1.0, 2.0) == pytest.approx(2**-0.5)
    # film never exceeds the compressed inlet supply, nor the flooded film
    hc = np.geomspace(1e-9, 1e-5, 30)
    hcs = np.exp(log_starved_film(np.log(hc), 2e-7, 1.2, 3.5))
    assert np.all(hcs < 2e-7 / 1.2) and np.all(hcs < hc)
    with pytest.raises(InputError, match="delta"):
        chevalier_reduction(1.0, 0.1)


def test_large_inlet_film_reduces_to_flooded():
    sc = load_scene("chapter6_starved_1.93GPa")
    flooded = stribeck_curve(sc, US, transitions=False)
    starved = stribeck_curve(sc, US, hoil=1e4 * sc.roughness.Rq, transitions=False)
    assert np.allclose(starved.friction.coefficient, flooded.friction.coefficient, rtol=1e-6)
    assert np.allclose(starved.sharing.hfr, flooded.sharing.hfr, rtol=1e-6)


def test_starvation_caps_the_film_and_raises_mixed_friction():
    sc = load_scene("chapter6_starved_1.93GPa")
    flooded = stribeck_curve(sc, US, transitions=False)
    st = stribeck_curve(sc, US, hoil=2.0 * sc.roughness.Rq, transitions=False)
    assert np.all(st.sharing.hfr <= flooded.sharing.hfr * (1 + 1e-12))
    assert np.all(st.friction.asperity >= flooded.friction.asperity - 1e-15)
    rho_bar = 1 + 0.34615 * st.sharing.pmax / (0.59263e9 + st.sharing.pmax)
    assert st.sharing.hfr[-1] < 2.0 * sc.roughness.Rq / rho_bar


def test_inlet_film_below_the_limit_puts_all_load_on_the_asperities():
    sc = load_scene("chapter6_starved_1.93GPa")
    r = sc.roughness
    hz = sc.hertz
    lim = limiting_inlet_film_for_roughness(sc.load, hz.area, hz.pmax, sc.E_reduced, r.Rq, r.sigma_s, r.dd, r.n, r.beta)
    below = stribeck_curve(sc, US, hoil=0.98 * lim.varsigma_compressed * r.Rq, transitions=False)
    assert np.all(below.sharing.boundary)
    assert np.allclose(below.friction.coefficient, r.fc, rtol=1e-12)
    assert np.allclose(below.sharing.hs, below.sharing.hs_min)
    assert np.all(below.regime == 0)
    above = stribeck_curve(sc, US, hoil=1.1 * lim.varsigma_compressed * r.Rq, transitions=False)
    assert not above.sharing.boundary[-1] and above.sharing.Ph[-1] > 0


def test_hs_min_is_where_asperities_carry_the_whole_load():
    sc = load_scene("chapter6_starved_0.5GPa")
    ls = load_sharing(sc, [1e-12])
    assert ls.hs[0] == pytest.approx(ls.hs_min, abs=1e-3 * sc.roughness.Rq)


def f32_quadrature(lam):
    f = lambda s: (s - lam) ** 1.5 * math.exp(-0.5 * s * s) / math.sqrt(2 * math.pi)  # noqa: E731
    return integrate.quad(f, lam, lam + 40, epsabs=0, epsrel=1e-12, limit=200)[0]


@pytest.mark.parametrize("pmax, thesis", [(1.93e9, 0.10), (0.5e9, 0.46)])
def test_varsigma_thesis_approximation_reproduces_section_6_4_and_exact_differs(pmax, thesis):
    lim = limiting_inlet_film(pmax)
    assert lim.F32 == pytest.approx(2 * pmax / 1e9, rel=1e-12)  # (6.10)
    assert lim.varsigma_approx == pytest.approx(thesis, abs=0.005)
    # exact: an independent F_3/2 (quadrature) inverted by brentq, then (6.12)-(6.14)
    lam = optimize.brentq(lambda x: f32_quadrature(x) - lim.F32, -10, 5, xtol=1e-13)
    assert lim.lam_exact == pytest.approx(lam, abs=1e-9)
    assert lim.varsigma_exact == pytest.approx(johnson_film(0.82 + 0.7 * lam, 1.0), rel=1e-9)
    assert abs(lim.difference) > 0.01  # "the two differ noticeably"
