"""Thermal point films anchored on the core's isothermal films: the film is the thermal/isothermal
ratio of its grid times the converged isothermal film, its error the ratio's grid and box
changes plus the reference's own error (`thermal.tehl.accuracy.anchored_estimate`)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from ehl_multigrid.multigrid.accuracy import DOMAIN_SAFETY
from thermal.tehl.accuracy import (
    GRID_SAFETY,
    RATIO_ORDERS,
    IsothermalReference,
    TEHLErrorEstimate,
    anchored_estimate,
)


def _solve(points: int, box: float, Hc: float, Hm: float, Hc_iso: float, Hm_iso: float) -> SimpleNamespace:
    return SimpleNamespace(Hc=Hc, Hm=Hm, Hc_isothermal=Hc_iso, Hm_isothermal=Hm_iso,
                           options=SimpleNamespace(points=points, nz=20, box=box))


def _estimate(domain: dict | None) -> TEHLErrorEstimate:
    parts = {"grid_x": 0.05, "grid_z": 0.001, "domain": 0.002, "iteration": 0.0003}
    budget = {k: {**parts, "total": sum(parts.values())} for k in ("Hc", "Hm", "friction_coefficient", "T_max")}
    return TEHLErrorEstimate(budget, (1.5, 2.0), domain, 0.0, ["Hc extrapolated over the grids along X"])


def test_anchored_films_are_the_grid_ratio_times_the_converged_isothermal_film():
    # the isothermal films still move 4 % per grid, their thermal ratios 0.3 %
    fine = _solve(1025, 1.0, Hc=1.8446, Hm=0.5672, Hc_iso=1.9557, Hm_iso=0.5674)
    coarse = _solve(513, 1.0, Hc=1.7628, Hm=0.5186, Hc_iso=1.8749, Hm_iso=0.5158)
    cache = SimpleNamespace(results={(513, 20, 1.0): coarse})
    ref = IsothermalReference(Hc=1.98326, Hm=0.58219, error_Hc=1e-4, error_Hm=0.0037, points=4097, wall_s=30.0)
    # the box probe's changes of the films and of their ratios (domain_change)
    box = {"points": 257, "Hc": 0.001, "Hm": 0.003, "ratio_Hc": 0.0002, "ratio_Hm": 0.0004}
    est = anchored_estimate(_estimate(box), fine, cache, ref)
    assert est.anchor is ref
    for key, iso in (("Hc", 1.98326), ("Hm", 0.58219)):
        iso_h = getattr(fine, f"{key}_isothermal")
        # the reported film: the grid's ratio times the reference (corrected_result scales both films)
        assert est.correction[key] == pytest.approx(iso / iso_h - 1.0)
        r, rc = getattr(fine, key) / iso_h, getattr(coarse, key) / getattr(coarse, f"{key}_isothermal")
        b = est[key]
        assert b["grid_x"] == pytest.approx(GRID_SAFETY * abs(r - rc) / r / (2.0 ** RATIO_ORDERS[key] - 1.0))
        assert b["domain"] == pytest.approx(DOMAIN_SAFETY * box[f"ratio_{key}"])
        assert b["isothermal"] == getattr(ref, f"error_{key}")
        assert b["grid_z"] == 0.001 and b["iteration"] == 0.0003
        assert b["total"] == pytest.approx(sum(v for p, v in b.items() if p != "total"))
    # far below the films' own grid part (0.05): the ratio's changes are 0.2-1 %
    assert est.Hc < 0.01 and est.Hm < 0.02
    assert not any("extrapolated" in n for n in est.notes) and any("anchored" in n for n in est.notes)


def test_a_box_probe_without_the_ratios_counts_the_films_box_change():
    fine = _solve(1025, 1.0, 1.8, 0.56, 1.9, 0.57)
    coarse = _solve(513, 1.0, 1.75, 0.52, 1.86, 0.53)
    ref = IsothermalReference(2.0, 0.58, 1e-4, 1e-3, 4097, 1.0)
    est = anchored_estimate(_estimate({"points": 257, "Hc": 0.001, "Hm": 0.003}), fine,
                            SimpleNamespace(results={(513, 20, 1.0): coarse}), ref)
    assert est["Hc"]["domain"] == pytest.approx(DOMAIN_SAFETY * 0.001)
    assert est["Hm"]["domain"] == pytest.approx(DOMAIN_SAFETY * 0.003)


def test_without_the_solve_on_every_other_node_there_is_no_anchored_estimate():
    fine = _solve(1025, 1.0, 1.8, 0.56, 1.9, 0.57)
    ref = IsothermalReference(2.0, 0.58, 1e-4, 1e-3, 4097, 1.0)
    assert anchored_estimate(_estimate(None), fine, SimpleNamespace(results={}), ref) is None


def test_an_unmeasured_box_leaves_the_anchored_error_unknown():
    fine = _solve(1025, 1.0, 1.8, 0.56, 1.9, 0.57)
    coarse = _solve(513, 1.0, 1.75, 0.52, 1.86, 0.53)
    ref = IsothermalReference(2.0, 0.58, 1e-4, 1e-3, 4097, 1.0)
    est = anchored_estimate(_estimate(None), fine, SimpleNamespace(results={(513, 20, 1.0): coarse}), ref)
    assert math.isnan(est.Hc) and math.isinf(est.worst) and "domain" in est.unknown_parts()


#: appendix D point (T9, 8 m/s, 42.8 N, slip 0.05) through the front door at 0.5 % without
#: anchoring: 1025 points, films extrapolated over the grids, stated errors 0.38 % / 0.20 % (86 s)
DIRECT_0P5 = {"Hc": (3.4459015229387884, 0.0037624209889926983), "Hm": (1.6048454204208733, 0.001953394580024379)}


@pytest.mark.slow
def test_anchored_point_films_agree_with_the_direct_fine_grid_films_within_both_estimates():
    import warnings

    import ehl_multigrid as ehl
    from ehl_multigrid.model.scene import load_scene

    sc = load_scene("appendix_d_point")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = ehl.solve(sc, physics="thermal", accuracy=0.005, options={"slip": sc.slip})
    assert s.success and "anchored" in s.message
    # 257 points against 1025: about 10 s against 86 s
    assert s.grid.points < 1025
    for key, (direct, stated) in DIRECT_0P5.items():
        mine = getattr(s, key)
        assert abs(mine - direct) / direct <= getattr(s.error, key) + stated, key
