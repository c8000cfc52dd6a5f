"""Line and point thermal Eyring model: limits, balances, symmetry, extremes (thesis ch. 3)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from thermal import solve_traction


def eyring_integral(scene, slip, x_in):
    """Isothermal Eyring friction, computed independently of the solver (Johnson-Tevaarwerk):
    ``B int tau0 asinh(eta(p(x), T_oil) (u1 - u2) / (h tau0)) dx`` over [x_in b, b], Hertz
    pressure, the fitted uniform film, tau constant across the film."""
    hz = scene.hertz
    h = scene.central_film_fit()[1]
    lub = scene.lubricant
    du = slip * scene.us / 2

    def tau(p):
        return lub.tau0 * math.asinh(lub.viscosity(p, scene.T_oil) * du / (h * lub.tau0))

    contact = quad(lambda th: tau(hz.pmax * math.cos(th)) * hz.b * math.cos(th), -math.pi / 2, math.pi / 2,
                   epsrel=1e-12, limit=200)[0]
    inlet = tau(0.0) * (-1.0 - x_in) * hz.b
    return scene.length * (contact + inlet)


@pytest.mark.parametrize("name", ["line_hi", "line_lo"])
def test_isothermal_switch_equals_independent_eyring_integral(name, request):
    sc = request.getfixturevalue(name)
    tp = solve_traction(sc, 0.05, thermal=False)
    ref = eyring_integral(sc, 0.05, tp.solutions[0].profile.X[0])
    assert tp.force == pytest.approx(ref, rel=1e-3)
    fine = solve_traction(sc, 0.05, thermal=False, nx=640)
    assert fine.force == pytest.approx(eyring_integral(sc, 0.05, fine.solutions[0].profile.X[0]), rel=1e-5)
    assert tp.max_temperature_rise == 0.0
    assert np.all(tp.solutions[0].T == sc.T_oil)


def test_thermal_friction_tends_to_isothermal_eyring_at_small_slip(line_hi):
    tp = solve_traction(line_hi, 1e-3)
    ref = eyring_integral(line_hi, 1e-3, tp.solutions[0].profile.X[0])
    assert tp.converged
    assert tp.force == pytest.approx(ref, rel=0.01)
    assert tp.max_temperature_rise < 0.5


def test_heat_generated_by_shear_leaves_by_conduction_and_convection(line_hi):
    tp = solve_traction(line_hi, 1.0)
    heat = tp.heat
    assert tp.converged
    assert abs(heat["balance"]) < 0.01
    assert heat["conduction1"] > 0 and heat["conduction2"] > 0 and heat["convection"] > 0
    # the sliding power is the shear heat: F (u1 - u2) ~ integral of tau gdot (up to the
    # rolling Poiseuille part, zero without the pressure-gradient term)
    assert heat["shear"] == pytest.approx(tp.force * (tp.u1 - tp.u2), rel=1e-3)


@pytest.mark.parametrize("name", ["line_hi", "point"])
def test_friction_is_odd_in_slip(name, request):
    sc = request.getfixturevalue(name)
    for s in (0.1, 0.7):
        a = solve_traction(sc, s, slices=4)
        b = solve_traction(sc, -s, slices=4)
        assert b.force == pytest.approx(-a.force, rel=1e-9)
        assert b.max_temperature_rise == pytest.approx(a.max_temperature_rise, rel=1e-9)
        # mirror image of the film: surface 1 of one case is surface 2 of the other
        assert b.solutions[0].T[:, ::-1] == pytest.approx(a.solutions[0].T, rel=1e-9)
    assert solve_traction(sc, 0.0, slices=4).force == pytest.approx(0.0, abs=1e-9 * a.force)


def test_momentum_term_keeps_odd_symmetry_and_makes_tau_linear_across_film(line_hi):
    a = solve_traction(line_hi, 0.4, momentum="on")
    b = solve_traction(line_hi, -0.4, momentum="on")
    assert b.force == pytest.approx(-a.force, rel=1e-9)
    tau = a.solutions[0].tau
    second = tau[:, 2:] - 2 * tau[:, 1:-1] + tau[:, :-2]
    assert np.max(np.abs(second)) < 1e-6 * np.max(np.abs(tau))
    assert np.max(np.abs(tau[:, -1] - tau[:, 0])) > 0


@pytest.mark.parametrize("slip", [2.0, -2.0])
def test_surface_at_rest_is_finite_converged_and_continuous(line_hi, slip):
    at_rest = solve_traction(line_hi, slip)
    near = solve_traction(line_hi, slip * 0.995)
    assert at_rest.converged
    assert min(at_rest.u1, at_rest.u2) == 0.0
    assert np.isfinite(at_rest.force) and np.isfinite(at_rest.max_temperature_rise)
    assert at_rest.force == pytest.approx(near.force, rel=0.03)
    assert at_rest.max_temperature_rise == pytest.approx(near.max_temperature_rise, rel=0.03)
    sol = at_rest.solutions[0]
    # the surface at rest sits under the whole heat source: it runs hotter than the moving one
    hot, cold = (sol.T_surface2, sol.T_surface1) if slip > 0 else (sol.T_surface1, sol.T_surface2)
    assert np.max(hot) > np.max(cold)


def test_carslaw_jaeger_kernel_refuses_surface_at_rest(line_hi):
    from ehl_multigrid.model.errors import InputError

    with pytest.raises(InputError, match="u > 0"):
        solve_traction(line_hi, 2.0, surface_kernel="carslaw-jaeger")


def test_thesis_kernel_and_exact_kernel_agree_at_high_peclet(line_hi):
    a = solve_traction(line_hi, 0.4)
    b = solve_traction(line_hi, 0.4, surface_kernel="carslaw-jaeger")
    assert b.force == pytest.approx(a.force, rel=0.01)
    assert b.max_temperature_rise == pytest.approx(a.max_temperature_rise, rel=0.05)


def test_thermal_softening_gives_friction_maximum_at_high_pressure(line_hi):
    S = [0.02, 0.1, 0.4, 1.0]
    thermal = [solve_traction(line_hi, s).force for s in S]
    iso = [solve_traction(line_hi, s, thermal=False).force for s in S]
    assert thermal[1] > thermal[2] > thermal[3]
    assert all(t < i for t, i in zip(thermal, iso, strict=True))
    assert np.all(np.diff(iso) > 0)


def test_maxwell_elasticity_lowers_low_slip_friction(line_hi):
    # (3.3): with a compliant fluid part of the slip is taken up elastically along the contact;
    # pure elastic shear over the transit would give tau ~ G S (2b/h)/2 ~ 1e7 * 5e-4 * 2.6e3
    viscous = solve_traction(line_hi, 5e-4)
    elastic = solve_traction(line_hi, 5e-4, G=1e7)
    stiff = solve_traction(line_hi, 5e-4, G=1e9)
    off = solve_traction(line_hi, 5e-4, G=1e30)
    assert elastic.converged
    assert elastic.force < 0.5 * viscous.force
    assert elastic.force < stiff.force < viscous.force
    assert stiff.force == pytest.approx(viscous.force, rel=1e-3)
    assert off.force == pytest.approx(viscous.force, rel=1e-12)


def test_point_contact_thesis_slices_carry_more_load_than_hertz(point):
    hertz = solve_traction(point, 0.3, slices=6)
    thesis = solve_traction(point, 0.3, slices=6, slice_pressure="thesis")
    # Hertz slices integrate to the load; the thesis slice (3.20) to (pi/2)^2 / (2 pi/3) of it
    assert hertz.extra["load_from_pressure"] == pytest.approx(point.load, rel=0.01)
    assert thesis.extra["load_from_pressure"] == pytest.approx(point.load * 3 * math.pi / 8, rel=0.01)
    assert thesis.force > hertz.force


def test_ehl_arrays_equal_to_hertz_reproduce_hertz_input(line_hi, point):
    tp = solve_traction(line_hi, 0.3)
    prof = tp.solutions[0].profile
    arr = solve_traction(line_hi, 0.3, input="ehl", ehl=(prof.x, prof.p, prof.h), momentum="off", x_in=prof.X[0])
    assert arr.force == pytest.approx(tp.force, rel=1e-9)
    # point field: Hertz pressure on an (x, y) grid, sliced back
    hz = point.hertz
    h = point.central_film_fit()[1]
    x = np.linspace(-2.5 * hz.a, 1.0 * hz.a, 401)
    y = np.linspace(0.0, 1.0 * hz.b, 201)
    P = hz.pmax * np.sqrt(np.clip(1 - (x[:, None] / hz.a) ** 2 - (y[None, :] / hz.b) ** 2, 0, None))
    H = np.full_like(P, h)
    a = solve_traction(point, 0.3, input="ehl", ehl=(x, y, P, H), slices=6, nx=161)
    b = solve_traction(point, 0.3, slices=6, nx=161)
    assert a.force == pytest.approx(b.force, rel=0.01)
