"""The fast paths of the thermal model give the answers of the plain ones: line problems on a
thread pool (slices, slips, Stribeck speeds), the relaxation of reverse-flow zones (same fixed
point of the march, thesis 3.2.2.2), the compiled surface weights ((3.6)-(3.7), moving strip)
and the compiled sinh/cosh, shear-stress and stress-slope solves of the Eyring law (3.3)."""

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.model.scene import load_scene
from thermal import film_friction, solve_traction, traction_curve
from thermal.film import FilmFriction, film_frictions
from thermal.kernels import _sinh_cosh, solve_stress_slope, solve_tau_mid
from thermal.line import solve_thermal_line
from thermal.surface import _GL_CELL, _GL_FAR, _GL_SING, moving_strip_kernel, wall_weights
from thermal.traction import prepare_traction


@pytest.fixture(scope="module")
def ehl_line():
    """Appendix C line contact (42400 N, 8 m/s) solved by the line solver on X in [-2.5, 1.5]:
    a thick inlet whose pressure-driven flux recirculates (reverse flow over ~25 stations)."""
    from ehl_multigrid.line import solve_line

    sc = load_scene("appendix_c_line_42400N")
    sol = solve_line(scene=sc, xmin=-2.5, xmax=1.5, points=513, estimate=False)
    assert sol.report.converged
    return sc, sol.to_result(sc)


def test_traction_curve_on_threads_equals_solving_each_slip_alone(point):
    slips = [0.05, 0.5, 1.0]
    curve = traction_curve(point, slips, slices=3, nx=30, nz=8, threads=2)
    for s, tp in zip(slips, curve, strict=True):
        alone = solve_traction(point, s, slices=3, nx=30, nz=8, threads=1)
        assert tp.force == alone.force
        assert tp.max_temperature_rise == alone.max_temperature_rise
        for a, b in zip(tp.solutions, alone.solutions, strict=True):
            assert np.array_equal(a.T, b.T)


def test_film_frictions_equal_film_friction_at_each_point(line_lo):
    loads, hs, us = [4240.0, 2000.0, 800.0], [2e-7, 1e-7, 5e-8], [8.0, 1.0, 0.1]
    many = list(film_frictions(line_lo, loads=loads, hs=hs, us=us, slip=0.3, nx=30, nz=8, threads=2))
    for P, h, u, ff in zip(loads, hs, us, many, strict=True):
        one = film_friction(line_lo, load=P, h=h, us=u, slip=0.3, nx=30, nz=8)
        assert isinstance(ff, FilmFriction)
        assert ff.force == one.force
        assert ff.mean_temperature_rise == one.mean_temperature_rise


def test_film_frictions_yield_a_failed_point_in_its_place(line_lo, monkeypatch):
    import thermal.parallel as par

    real = par.solve_thermal_line

    def failing(profile, env, options, kernel_length, start=None):
        if env.u1 + env.u2 < 0.5:
            raise ConvergenceError("test failure", None, "")
        return real(profile, env, options, kernel_length=kernel_length, start=start)

    monkeypatch.setattr(par, "solve_thermal_line", failing)
    out = list(film_frictions(line_lo, loads=[4240.0] * 3, hs=[2e-7] * 3, us=[8.0, 0.1, 4.0], slip=0.3,
                              nx=20, nz=5, threads=2))
    assert isinstance(out[0], FilmFriction) and isinstance(out[2], FilmFriction)
    assert isinstance(out[1], ConvergenceError)


def test_zone_relaxation_reaches_the_fixed_point_of_forward_sweeps_in_fewer_sweeps(ehl_line):
    sc, ehl = ehl_line
    st = prepare_traction(sc, 0.5, input="ehl", ehl=ehl, tol_T=1e-10, tol_tau=1e-10, max_sweeps=400)
    job = st.jobs[0]
    fwd = solve_thermal_line(job.profile, job.env, job.options, job.kernel_length, symmetric=False)
    sym = solve_thermal_line(job.profile, job.env, job.options, job.kernel_length, symmetric=True)
    assert fwd.report.converged and sym.report.converged
    assert fwd.report.extra["reverse_flow_nodes"] > 100  # a real recirculation zone
    assert sym.force_per_length == pytest.approx(fwd.force_per_length, rel=1e-9)
    assert np.max(np.abs(sym.T - fwd.T)) < 1e-6
    assert sym.report.iterations < fwd.report.iterations / 3
    assert sym.report.extra["zone_passes"] > 0 and fwd.report.extra["zone_passes"] == 0


@pytest.mark.parametrize("slip", [0.05, 0.5, 1.0])
def test_ehl_input_needs_no_more_sweeps_than_hertz_input(ehl_line, slip):
    # the recirculating EHL inlet is relaxed within each sweep: the march then settles as fast
    # as the Hertz input's, whose sweeps are set by the surface kernel's upstream reach
    # (appendix C at the default tolerance: 3, 3, 4 sweeps; 5, 5, 5 with one backward pass
    # per sweep instead)
    sc, ehl = ehl_line
    e = solve_traction(sc, slip, input="ehl", ehl=ehl)
    h = solve_traction(sc, slip)
    assert e.converged and h.converged
    assert e.report.extra["reverse_flow_nodes"] > 100
    assert e.report.iterations <= h.report.iterations


def test_surface_at_rest_is_not_taken_for_reverse_flow(line_hi):
    # S = 2: surface 2 at rest; the film velocity at its wall is zero only to the stress tolerance
    tp = solve_traction(line_hi, 2.0, nx=40, nz=10)
    assert tp.converged
    assert tp.report.extra["reverse_flow_nodes"] == 0


def _weights_by_cell_rules(n, dx, u, solid, length):
    """The half-hat weights evaluated cell by cell with the numpy kernel and the same Gauss
    rules (24 points for |m| <= 3, 8 further away, graded 48 points on the cells touching 0)."""
    m = np.arange(-(n - 1), n, dtype=float)
    WL, WR = np.empty_like(m), np.empty_like(m)
    for k, mm in enumerate(m):
        gx, gw = _GL_CELL if abs(mm) <= 3 else _GL_FAR
        s = 0.5 * (gx + 1.0)
        WR[k] = 0.5 * dx * np.sum(moving_strip_kernel((mm - 1.0 + s) * dx, u, solid, length) * s * gw)
        WL[k] = 0.5 * dx * np.sum(moving_strip_kernel((mm + s) * dx, u, solid, length) * (1.0 - s) * gw)
    sx, sw = _GL_SING
    g = 0.5 * (sx + 1.0)
    r, jac = g**2, g * sw
    i0 = n - 1
    WR[i0 + 1] = dx * np.sum(moving_strip_kernel(r * dx, u, solid, length) * r * jac)
    WR[i0] = dx * np.sum(moving_strip_kernel(-r * dx, u, solid, length) * (1.0 - r) * jac)
    WL[i0] = dx * np.sum(moving_strip_kernel(r * dx, u, solid, length) * (1.0 - r) * jac)
    WL[i0 - 1] = dx * np.sum(moving_strip_kernel(-r * dx, u, solid, length) * r * jac)
    return WL, WR


@pytest.mark.parametrize("u, length", [(0.0, 1e-3), (0.05, 1e-3), (4.0, 0.032), (40.0, math.inf)])
def test_compiled_surface_weights_equal_the_cell_by_cell_quadrature(line_hi, u, length):
    n, dx = 15, 3e-6
    WL, WR = wall_weights(n, dx, u, line_hi.body1, "moving-strip", length)
    rl, rr = _weights_by_cell_rules(n, dx, u, line_hi.body1, length)
    assert WL == pytest.approx(rl, rel=1e-12, abs=1e-14 * np.max(rl))
    assert WR == pytest.approx(rr, rel=1e-12, abs=1e-14 * np.max(rr))


def test_sinh_cosh_from_expm1_match_the_library_functions():
    s = np.concatenate([np.linspace(-700.0, 700.0, 4001), np.geomspace(1e-300, 30.0, 500),
                        -np.geomspace(1e-300, 30.0, 500), [0.0]])
    for v in s:
        sh, ch = _sinh_cosh(v)
        assert sh == pytest.approx(math.sinh(v), rel=1e-15, abs=1e-300)
        assert ch == pytest.approx(math.cosh(v), rel=1e-15)


def _stress_problem():
    nzp = 11
    w = np.full(nzp, 0.1)
    w[[0, -1]] = 0.05
    Zc = np.linspace(-0.5, 0.5, nzp)
    d = 2e6 * Zc
    inv_eta = 1.0 / np.geomspace(1e-2, 1e3, nzp)
    tau0 = 4e6
    target = 5e6  # 1/s

    def flow(t):
        return np.sum(w * tau0 * inv_eta * np.sinh((t + d) / tau0)) - target

    return d, w, inv_eta, tau0, np.zeros(nzp), target, flow


@pytest.mark.parametrize("case", ["inlet", "contact", "maxwell"])
@pytest.mark.parametrize("warm", [False, True])
def test_stress_slope_solve_meets_both_flow_conditions(case, warm):
    # the (tau_m, G) Newton sums the Maxwell terms once per solve and the Eyring terms per
    # evaluation; its root must satisfy the wall-speed condition and carry the given pressure
    # flow b, checked with the plain per-node sums and a bracketed root of each condition
    from scipy.optimize import brentq

    nzp = 21
    dZ = 1.0 / (nzp - 1)
    w = np.full(nzp, dZ)
    w[[0, -1]] = 0.5 * dZ
    Zc = np.linspace(-0.5, 0.5, nzp)
    tau0 = 5e6
    inv_eta = 1.0 / np.geomspace(0.05, 3.0, nzp)  # viscosity varying across a heated film
    mx_a, mx_r = 0.0, np.zeros(nzp)
    target, b = 2e6, 4e5  # 1/s: wall-speed shear rate and pressure-driven flow
    if case == "contact":
        inv_eta = 1.0 / np.geomspace(1e3, 3e3, nzp)
        target, b = 1e5, 1e-4
    elif case == "maxwell":
        mx_a, mx_r = 2e-2, np.linspace(-3e4, 5e4, nzp)

    def gdot(t):
        return tau0 * inv_eta * np.sinh(t / tau0) + mx_a * t + mx_r

    def tau_mid(G):
        return brentq(lambda t: np.sum(w * gdot(t + G * Zc)) - target, -60 * tau0, 60 * tau0, xtol=1e-15 * tau0)

    def pressure_flow(G):
        tm = tau_mid(G)
        return np.sum(w * Zc * (gdot(tm + G * Zc) - gdot(tm)))

    G_ref = brentq(lambda G: pressure_flow(G) - b, 0.0, 50 * tau0, xtol=1e-14 * tau0, rtol=1e-14)
    tm_ref = tau_mid(G_ref)
    d = np.empty(nzp)
    G0, tm0 = (G_ref * (1 + 1e-3), tm_ref + 1e-4 * tau0) if warm else (math.nan, 0.0)
    G, tm, ok = solve_stress_slope(G0, tm0, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target, b)
    assert ok
    assert abs(tm - tm_ref) <= 1e-10 * tau0
    assert abs(G - G_ref) <= 1e-9 * abs(G_ref) + 1e-10 * tau0
    assert np.array_equal(d, G * Zc)


@pytest.mark.parametrize("guess", [0.0, 1e4, -3e8, 2.0e7, "warm", "near"])
def test_mid_film_stress_solve_meets_its_tolerance_from_any_guess(guess):
    from scipy.optimize import brentq

    d, w, inv_eta, tau0, mx_r, target, flow = _stress_problem()
    root = brentq(flow, -10 * tau0, 10 * tau0, xtol=1e-16 * tau0, rtol=1e-15)
    if guess == "warm":
        # a previous iterate just inside the one-step acceptance (1e-6 tau0): the Newton step
        # is accepted unconfirmed and must still meet the tolerance
        guess = root + 9e-7 * tau0
    elif guess == "near":  # outside it: one unconfirmed step would leave ~1e-9 tau0
        guess = root + 5e-5 * tau0
    tm, ok = solve_tau_mid(guess, d, w, inv_eta, tau0, 0.0, mx_r, target)
    assert ok
    assert abs(tm - root) <= 1e-11 * tau0
