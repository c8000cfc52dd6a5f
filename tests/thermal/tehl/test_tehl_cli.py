"""``ehl tehl`` subcommand (registered by thermal.tehl.cli) and the thermal properties of a scene."""

from __future__ import annotations

import argparse
import json

import pytest

from ehl_multigrid.model.constants import ETA_INF
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from thermal.tehl.cli import register, thermal_properties


def _parse(argv):
    ap = argparse.ArgumentParser()
    register(ap.add_subparsers())
    return ap.parse_args(argv)


def test_tehl_json_has_the_documented_keys(capsys):
    a = _parse(["tehl", "appendix_c_line_4240N", "--slip", "0.3", "--points", "129", "--nz", "10", "--json"])
    a.func(a)
    out = json.loads(capsys.readouterr().out)
    for key in ("Hc", "Hm", "Hc_isothermal", "friction", "T_max", "heat_balance_error"):
        assert key in out
    assert out["converged"] and out["friction"] > 0


def test_tehl_refuses_a_point_contact():
    a = _parse(["tehl", "appendix_d_point"])
    with pytest.raises(InputError, match="line contacts"):
        a.func(a)


def test_thermal_properties_of_T9_at_60C():
    p = thermal_properties(load_scene("appendix_c_line_4240N"))
    # Roelands temperature term (2.6): beta = ln(eta0/eta_inf) S0 (T0+135)^S0 / (T+135)^(S0+1)
    lub = load_scene("appendix_c_line_4240N").lubricant
    import math

    lnr = math.log(lub.eta0 / ETA_INF)
    beta = lnr * lub.S0 * (lub.T0 + 135) ** lub.S0 / (60 + 135) ** (lub.S0 + 1)
    assert p["beta"] == pytest.approx(beta, rel=1e-6)
    assert p["k_oil"] == pytest.approx(lub.k0)
    assert p["thermal_loading"] > 0


def test_solve_mode_for_ehl_solve_thermal():
    from thermal.tehl.cli import solve_mode

    args = argparse.Namespace(points=129, nz=10, slip=0.3, json=True)
    out = solve_mode(args, load_scene("appendix_c_line_4240N"))
    assert out["contact"] == "line" and out["converged"] and out["Hc_isothermal"] > 0
    assert 0 < out["heat_balance_error"] < 0.05
