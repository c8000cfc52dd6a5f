"""Synthetic surfaces and the random-process (Nayak) predictions of summit statistics."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from mixed.surface import (
    analyse_surface,
    gaussian_acf,
    gaussian_acf_moments,
    gaussian_random_surface,
    nayak_continuous,
    nine_point_prediction,
    planted_asperities,
    spectral_moments,
    surface_statistics,
)

HERE = Path(__file__).parent


def test_gaussian_surface_has_requested_rq_and_moments():
    hm = gaussian_random_surface((256, 320), 0.2e-6, 30e-9, corr_length=2e-6, seed=4)
    assert np.sqrt(np.mean(hm.z**2)) == pytest.approx(30e-9, rel=1e-12)
    mom = spectral_moments(hm)
    ref = gaussian_acf_moments(30e-9, 2e-6)
    assert mom["m2"] == pytest.approx(ref["m2"], rel=0.08)
    assert mom["m4"] == pytest.approx(ref["m4"], rel=0.1)
    assert ref["alpha"] == pytest.approx(3.0)
    fractal = gaussian_random_surface(128, 0.1e-6, 20e-9, hurst=0.8, seed=1)
    assert fractal.meta["psd_slope"] == pytest.approx(-3.6)
    with pytest.raises(InputError, match="exactly one"):
        gaussian_random_surface(64, 1e-6, 1e-8)
    with pytest.raises(InputError, match="too long"):
        gaussian_random_surface(64, 1e-6, 1e-8, corr_length=50e-6)


def test_nayak_formulas_against_kac_rice_sampling():
    """Independent check of n and mean summit curvature: sample the Hessian of an isotropic field
    (cov zxx = zyy = m4, zxx zyy = zxy^2 = m4/3) and weight |det H| over negative-definite H."""
    m0, m2, m4 = 1.0, 2.0, 12.0
    rng = np.random.default_rng(0)
    C = np.array([[m4, m4 / 3, 0], [m4 / 3, m4, 0], [0, 0, m4 / 3]])
    a, b, c = (rng.standard_normal((400_000, 3)) @ np.linalg.cholesky(C).T).T
    w = np.abs(a * b - c * c) * ((a < 0) & (a * b - c * c > 0))
    pred = nayak_continuous(m0, m2, m4)
    assert w.mean() / (2 * math.pi * m2) == pytest.approx(pred["n"], rel=0.01)
    assert (w * -(a + b) / 2).sum() / w.sum() == pytest.approx(pred["kappa_mean"], rel=0.01)
    with pytest.raises(InputError, match="alpha"):
        nayak_continuous(1.0, 1.0, 1.0)


@pytest.mark.solver
def test_nine_point_rule_limits():
    ell, rq = 1e-6, 1e-8
    mom = gaussian_acf_moments(rq, ell)
    cont = nayak_continuous(mom["m0"], mom["m2"], mom["m4"])
    fine = nine_point_prediction(gaussian_acf(ell), rq, 0.2 * ell, n_samples=1_000_000, seed=1)
    assert fine["n"] == pytest.approx(cont["n"], rel=0.06)
    assert fine["kappa_mean"] == pytest.approx(cont["kappa_mean"], rel=0.07)
    coarse = nine_point_prediction(gaussian_acf(ell), rq, 5 * ell, n_samples=1_000_000, seed=1)
    assert coarse["p_summit"] == pytest.approx(1 / 9, rel=0.01)  # independent heights


def test_sampled_surface_matches_nine_point_prediction():
    ell, rq, h = 1e-6, 1e-8, 0.5e-6
    st = surface_statistics(gaussian_random_surface(384, h, rq, corr_length=ell, seed=8))
    pred = nine_point_prediction(gaussian_acf(ell), rq, h, n_samples=1_000_000, seed=2)
    assert st.n == pytest.approx(pred["n"], rel=0.05)
    assert st.kappa_mean == pytest.approx(pred["kappa_mean"], rel=0.05)
    assert st.sigma_s == pytest.approx(pred["sigma_s"], rel=0.05)
    assert st.dd == pytest.approx(pred["dd"], rel=0.05)


def test_planted_density_too_high_is_an_input_error():
    with pytest.raises(InputError, match="too high"):
        planted_asperities(64, 0.5e-6, 5e11, 30e-6, 0.1e-6, 0.01e-6, seed=0)


def test_regression_pinned_statistics():
    """Regression (not accuracy): statistics pinned from a stored run of this code
    (tests/surface/regression_surface.json, produced by tests/surface/make_regression_surface.py)."""
    ref = json.loads((HERE / "regression_surface.json").read_text())
    for case in ref["cases"]:
        p = case["params"]
        if case["kind"] == "gaussian":
            hm = gaussian_random_surface(p["n"], p["dx"], p["Rq"], corr_length=p["corr_length"], seed=p["seed"])
        else:
            hm, _ = planted_asperities(p["n"], p["dx"], p["density"], p["radius"], p["height_mean"],
                                       p["height_std"], seed=p["seed"])
        st = analyse_surface(hm).stats
        for k, v in case["stats"].items():
            assert getattr(st, k) == pytest.approx(v, rel=1e-9), (case["kind"], k)
