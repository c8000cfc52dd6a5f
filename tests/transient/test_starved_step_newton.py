"""The mass-conserving time step of a starved line contact: a residual continuous in the film
content (the second-order share of a face, ``starved.discrete.second_order_share``), the dense
semismooth Newton of the starved solver with the step's squeeze term and moving geometry
(Woloszynski et al. 2015) as the last resort of a stalled step, and a dent that passes the
outlet of a starved contact with it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import scipy.linalg

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.starved.discrete import elrod_adams_residual
from ehl_multigrid.starved.newton import _jacobian, _residual
from ehl_multigrid.transient import Bump, solve_transient_line
from ehl_multigrid.transient.cavitated import CavitatedStepLevel

PB = dataclasses.replace(LineProblem.from_moes(20, 10), xmin=-4.5, xmax=1.5)


def _starved_state(n: int = 40):
    X = np.linspace(-2.0, 1.5, n)
    P = np.maximum(0.0, 1.0 - X**2) ** 0.5
    H = 0.05 + 0.5 * np.maximum(X - 0.8, 0.0) ** 2 + 0.01 * np.sin(3.0 * X) ** 2
    theta = np.ones(n)
    theta[:5] = 0.3  # a starved inlet: the supplied layer fills part of the gap
    rho = np.ones(n)
    eps = 1e-3 * H**3
    return P, H, rho, theta, eps, X[1] - X[0]


def test_the_starved_residual_is_continuous_in_the_film_content_of_a_full_point():
    P, H, rho, theta, eps, h = _starved_state()
    f = np.zeros_like(P)
    r1, scale = elrod_adams_residual(P, H, rho, theta, eps, h, f, 2, True)
    i = 20
    th = theta.copy()
    th[i] = 1.0 - 1e-9
    r2, _ = elrod_adams_residual(P, H, rho, th, eps, h, f, 2, True)
    # the faces next to the point switch from second to first order gradually: a content 1e-9
    # below full moves the rows by about that much of a film flux (by 0.5 |q_i - q_(i-1)|/h
    # with a switch at theta = 1)
    q = rho * H
    assert np.max(np.abs(r2 - r1)) < 1e-7 * np.max(q) / h


def _step_level(ct: float) -> CavitatedStepLevel:
    lv = CavitatedStepLevel(65, PB.xmin, PB.xmax, PB.rheology(), PB.lam, True, "direct", 2)
    lv.hoil, lv.starved_inlet = 0.05, True
    X = lv.X
    lv.P = np.where(np.abs(X) < 1.0, np.sqrt(np.maximum(1.0 - X**2, 0.0)), 0.0)
    lv.H0 = -0.4
    lv.R = -0.02 * np.exp(-((X - 0.3) / 0.25) ** 2)  # a dent in the contact
    lv.ct = ct
    lv.hist = 0.3 * np.ones(lv.n)
    lv.theta = np.where(X > 1.05, 0.6, 1.0)  # ruptured behind the contact
    return lv


@pytest.mark.parametrize("ct", [0.0, 64.0])
def test_the_dense_newton_jacobian_of_a_time_step_is_its_residuals_derivative(ct):
    lv = _step_level(ct)
    Kmat = scipy.linalg.toeplitz(lv.kernel)
    P, theta, H0 = lv.P.copy(), lv.theta.copy(), float(lv.H0)
    r, dL, dT, th = _jacobian(lv, P, theta, H0, Kmat)
    theta[0] = th[0]
    inner = np.arange(1, lv.n - 1)
    for j in (10, 30, 40, 50):  # pressures in and around the contact
        e = 1e-7
        Pp = P.copy()
        Pp[j] += e
        fd = -(_residual(lv, Pp, theta, H0) - r) / e
        assert np.allclose(fd[inner], dL[inner, j], rtol=1e-4, atol=1e-6 * np.abs(dL[inner, j]).max())
    for j in (56, 60):  # film contents behind the rupture
        e = 1e-7
        tp = theta.copy()
        tp[j] -= e
        fd = (_residual(lv, P, tp, H0) - r) / e
        assert np.allclose(fd[inner], dT[inner, j], rtol=1e-4, atol=1e-6 * np.abs(dT[inner, j]).max())
    e = 1e-8
    fd = -(_residual(lv, P, theta, H0 + e) - r) / e
    assert np.allclose(fd[inner], dL[inner, lv.n], rtol=1e-4, atol=1e-6 * np.abs(dL[inner, lv.n]).max())


@pytest.mark.solver
def test_a_dent_through_a_starved_line_contact_passes_the_outlet_conserving_oil():
    # a dent 2.4 starved central films deep under rolling, fed half the flooded flux: its
    # steps stalled with the dent near the outlet (the free boundary in the dent flipping
    # between regimes) until the stalled step was finished by the dense Newton
    res = solve_transient_line(PB, Bump(-0.1, 0.5, x0=-1.6), points=257, t_end=2.7,
                               cavitation="mass-conserving", hoil=0.05, snapshot_every=10**5)
    assert res.complete and not np.any(res.stalled)
    assert res.T[-1] >= 2.7 - 1e-9
    err = np.asarray(res.series["mass_error"][1:])
    assert np.max(np.abs(err)) < 1e-6
    # the dent thins the film as it passes, and the film stays positive
    assert 0.0 < np.min(res.Hm) < 0.9 * res.Hm[0]
