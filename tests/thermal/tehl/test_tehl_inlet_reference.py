"""The coupled TEHL against an independent thermal inlet solution of the same equations
(validation/tehl/inlet_reference.py: rigid Grubin inlet, surfaces at the oil temperature,
Newtonian incompressible oil, energy equation with convection and conduction), in pure rolling
on the appendix C line contact at 42400 N."""

import importlib.util
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[3] / "validation" / "tehl" / "inlet_reference.py"


@pytest.fixture(scope="module")
def inlet():
    spec = importlib.util.spec_from_file_location("inlet_reference_script", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod          # its dataclass looks its module up there
    spec.loader.exec_module(mod)
    return mod


def test_the_isothermal_inlet_is_grubins(inlet):
    c = inlet.inlet_from_scene(42400.0, 20.6, 0.0)
    hc = inlet.InletSolver(c, nx=160, nz=8).solve(thermal=False)["hc"]
    # Grubin's 1.95 is itself a fit of this integral to about a percent
    assert hc == pytest.approx(inlet.grubin_film(c), rel=0.01)


@pytest.mark.slow
@pytest.mark.timeout(1800)
def test_rolling_thermal_film_agrees_with_the_independent_inlet_solution(inlet):
    # thermal loading 1.6 (us 82.4 m/s), where the heating takes a fifth of the film; the
    # reference with the package's viscosity law (Roelands in pressure and temperature)
    c = inlet.inlet_from_scene(42400.0, 82.4, 0.0, roelands=True)
    ref = {}
    for nx, nz in ((160, 16), (320, 32)):
        iso = inlet.InletSolver(c, nx, nz).solve(thermal=False)["hc"]
        ref[nx] = inlet.InletSolver(c, nx, nz).solve()["hc"] / iso
    ref_error = abs(ref[320] - ref[160])          # first-order bound of the finer reference
    pkg = inlet.package_ratio(42400.0, 82.4, 0.0, inlet_assumptions=True)
    assert pkg["status"] == "converged"
    assert 1.0 - ref[320] > 0.15                  # a model without inlet heating fails below
    assert abs(pkg["ratio"] - ref[320]) <= pkg["Hc_error"] + ref_error
