"""Compressive heating in the film energy equation: the work of compression
``-(T/rho)(d rho/d T)_p u dp/dx`` (Bruyere et al. 2012; Habchi 2008) added to the thesis's
energy equation (3.5), with the density (2.7) with thermal expansion (3.10)."""

from __future__ import annotations

import numpy as np
import pytest

from ehl_multigrid.line import solve_line_problem
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.multigrid.options import LineOptions
from thermal.line import Surroundings, solve_thermal_line
from thermal.options import ThermalOptions
from thermal.profiles import profile_from_arrays
from thermal.tehl import TEHLOptions
from thermal.tehl.line import interior_heat_budget, line_problem
from thermal.traction import wall_speeds

POINTS = 257


@pytest.fixture(scope="module")
def film(line_hi):
    """The isothermal Newtonian EHL film of appendix C, 42400 N (pmax 1.6 GPa), on 257 points."""
    pb = line_problem(line_hi, TEHLOptions(points=POINTS))
    res = solve_line_problem(pb, LineOptions(points=POINTS))
    lub, T0 = line_hi.lubricant, line_hi.T_oil
    return profile_from_arrays(res.X * pb.b, res.P * pb.pmax, res.H * pb.b**2 / pb.R, b=pb.b, nx=POINTS,
                               width=line_hi.length, x_in=None, x_out=None, source="tehl",
                               viscosity=lambda p: np.asarray(lub.viscosity(p, T0), dtype=float))


def _solve(scene, prof, slip, nz=20, lubricant=None, **opts):
    u1, u2 = wall_speeds(scene.us, slip)
    env = Surroundings(lubricant or scene.lubricant, scene.body1, scene.body2, u1, u2, scene.T_oil,
                       scene.T_surface1, scene.T_surface2)
    o = ThermalOptions(nx=POINTS, nz=nz, tol_T=1e-7, tol_tau=1e-7, max_inner=500, max_sweeps=400,
                       momentum="flux", **opts)
    sol = solve_thermal_line(prof, env, o, kernel_length=scene.length)
    assert sol.report.converged, sol.report.message
    return sol


def test_compressive_heating_is_off_for_the_thesis_method_and_on_for_tehl():
    assert ThermalOptions().compressive_heating is False
    assert TEHLOptions().compressive_heating is True
    assert TEHLOptions().thermal_options().compressive_heating is True
    assert TEHLOptions(compressive_heating=False).thermal_options().compressive_heating is False


def test_compressive_heating_must_be_a_boolean():
    with pytest.raises(InputError, match="compressive_heating"):
        ThermalOptions(compressive_heating="yes")
    with pytest.raises(InputError, match="compressive_heating"):
        TEHLOptions(compressive_heating=1)


def test_an_oil_without_thermal_expansion_does_no_compression_work(line_hi, film):
    # alpha_T = 0: (d rho/d T)_p = 0, so the term vanishes and the field is bit for bit the
    # one without it (the option adds nothing else to the march)
    lub = line_hi.lubricant.with_changes(alpha_T=0.0)
    off = _solve(line_hi, film, 0.5, nz=10, lubricant=lub)
    on = _solve(line_hi, film, 0.5, nz=10, lubricant=lub, compressive_heating=True)
    for name in ("T", "tau", "u", "q1", "q2"):
        assert np.array_equal(getattr(on, name), getattr(off, name)), name
    assert on.heat["compression"] == 0.0


def test_compression_heats_the_inlet_and_expansion_cools_the_outlet(line_hi, film):
    off = _solve(line_hi, film, 0.0)
    on = _solve(line_hi, film, 0.0, compressive_heating=True)
    g = film.dpdx
    rise = on.T[:, 10] - off.T[:, 10]
    i_in, i_out = int(np.argmax(g)), int(np.argmin(g))
    assert film.X[i_in] < 0 < film.X[i_out]
    # pure rolling, 1.6 GPa, 8 m/s: +0.49 K mid-film where the pressure rises fastest,
    # -0.86 K where the outlet pressure falls (measured)
    assert rise[i_in] > 0.2
    assert rise[i_out] < -0.4
    # the work of compression in the inlet and of expansion at the outlet nearly cancel
    # (the pressure returns to ambient): the net is a few per cent of the gross
    assert abs(on.heat["compression"]) > 0.0
    assert off.heat["compression"] == 0.0


def test_heat_budget_closes_with_the_work_of_compression(line_hi, film):
    """Pure rolling (only Poiseuille shear heat, of the size of the compression work in the
    inlet): the interior budget with the compression term converges to zero at second order in
    nz (13.6 %, 3.9 %, 1.1 % at nz = 10, 20, 40); without it, it settles near -6 %."""
    bal, without = [], []
    for nz in (10, 20, 40):
        hb = interior_heat_budget(_solve(line_hi, film, 0.0, nz=nz, compressive_heating=True), line_hi.lubricant)
        bal.append(hb["balance"])
        without.append((hb["shear"] - hb["conduction1"] - hb["conduction2"] - hb["convection"]) / hb["shear"])
    assert abs(bal[0]) / abs(bal[1]) > 3.0 and abs(bal[1]) / abs(bal[2]) > 3.0
    assert abs(bal[2]) < 0.012
    assert without[2] < -0.04


def test_heat_budget_with_compression_within_one_percent_under_slip(line_hi, film):
    hb = _solve(line_hi, film, 0.5, compressive_heating=True)
    budget = interior_heat_budget(hb, line_hi.lubricant)
    assert budget["compression"] != 0.0
    assert abs(budget["balance"]) < 0.01
