"""Low-pass filters (thesis 5.3) and the ISO 16610-21 Gaussian low-pass."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from mixed.surface import (
    HeightMap,
    filter_until_psi,
    gaussian_lowpass,
    gaussian_random_surface,
    gaussian_sigma,
    gaussian_transmission,
    lowpass_3x3,
    lowpass_transmission,
    parse_filter,
)


def sinusoid(wavelength_pts: int, periods: int = 6, dx: float = 1e-6, ny: int = 8) -> HeightMap:
    n = wavelength_pts * periods
    x = np.arange(n) * dx
    return HeightMap(np.tile(np.sin(2 * math.pi * x / (wavelength_pts * dx)), (ny, 1)), dx, dx)


def amplitude(z: np.ndarray, wavelength_pts: int, cols: slice = slice(None)) -> float:
    """Least-squares amplitude of the sinusoid on the middle row."""
    row = z[z.shape[0] // 2, cols]
    j = np.arange(z.shape[1])[cols]
    A = np.column_stack([np.sin(2 * math.pi * j / wavelength_pts), np.cos(2 * math.pi * j / wavelength_pts)])
    c, *_ = np.linalg.lstsq(A, row, rcond=None)
    return float(np.hypot(*c))


def test_iso_gaussian_weighting_constants():
    assert gaussian_sigma(1.0) == pytest.approx(math.sqrt(math.log(2) / 2) / math.pi)
    assert gaussian_transmission(1.0, 1.0) == pytest.approx(0.5, rel=1e-12)


@pytest.mark.parametrize("ratio, expected", [(1.0, 0.5), (2.0, 0.5**0.25), (0.5, 0.5**4)])
def test_gaussian_transmission_of_a_sinusoid_periodic(ratio, expected):
    lam_pts = 32
    hm = sinusoid(lam_pts)
    out = gaussian_lowpass(hm, lam_pts * hm.dx / ratio, mode="wrap")
    assert amplitude(out.z, lam_pts) == pytest.approx(expected, rel=1e-9)


def test_gaussian_transmission_half_at_cutoff_with_mirrored_edges():
    lam_pts = 32
    hm = sinusoid(lam_pts, periods=10)
    out = gaussian_lowpass(hm, lam_pts * hm.dx)
    # away from the mirrored edges (2 cut-offs) the transmission is the ISO one
    assert amplitude(out.z, lam_pts, slice(2 * lam_pts, -2 * lam_pts)) == pytest.approx(0.5, rel=0.01)
    assert "Gaussian low-pass" in out.history[-1]


def test_lowpass_transmission_per_pass():
    lam_pts = 8
    hm = sinusoid(lam_pts)
    for passes in (1, 3):
        out = lowpass_3x3(hm, passes, mode="wrap")
        expect = lowpass_transmission(lam_pts * hm.dx, hm.dx, passes)
        assert expect == pytest.approx(math.cos(math.pi / lam_pts) ** (2 * passes))
        assert amplitude(out.z, lam_pts) == pytest.approx(expect, rel=1e-9)
    box = lowpass_3x3(hm, 1, weights="box", mode="wrap")
    assert amplitude(box.z, lam_pts) == pytest.approx(
        abs(lowpass_transmission(lam_pts * hm.dx, hm.dx, 1, "box")), rel=1e-9)


def test_lowpass_history_counts_passes():
    hm = sinusoid(8)
    out = lowpass_3x3(lowpass_3x3(hm, 2), 2)
    assert out.history == ("low-pass 3x3 binomial x 4",)


def test_filters_keep_missing_points_and_constants():
    z = np.full((20, 30), 3e-7)
    z[5:8, 10:14] = np.nan
    hm = HeightMap(z, 1e-6, 1e-6)
    for out in (lowpass_3x3(hm, 3), gaussian_lowpass(hm, 8e-6)):
        assert np.isnan(out.z[6, 12])
        np.testing.assert_allclose(out.z[~np.isnan(z)], 3e-7, rtol=1e-12)


def test_filter_until_psi_stops_at_first_step_below_target():
    hm = gaussian_random_surface(160, 0.78e-6, 0.2e-6, corr_length=4e-6, seed=5)
    for method in ("lowpass", "gaussian"):
        st = filter_until_psi(hm, target=1.0, method=method)
        psi = [s.stats.psi for s in st.steps]
        assert st.reached and psi[-1] <= 1.0 and all(p > 1.0 for p in psi[:-1])
        assert psi[0] > 1.5  # the unfiltered (or lightly filtered) surface is plastic
        assert st.result.stats.Rq < st.steps[0].stats.Rq
    unreachable = filter_until_psi(hm, target=1e-3, method="lowpass", max_passes=3)
    assert not unreachable.reached and len(unreachable.steps) == 4


def test_filter_arguments_checked():
    hm = sinusoid(8)
    with pytest.raises(InputError, match="passes"):
        lowpass_3x3(hm, -1)
    with pytest.raises(InputError, match="lambda_c"):
        gaussian_lowpass(hm, 0.0)
    with pytest.raises(InputError, match="filter"):
        parse_filter("median:3")
    assert parse_filter("gauss:20um").cutoff == pytest.approx(20e-6)
    assert parse_filter("lowpass:4").passes == 4
    assert parse_filter("until-psi:0.8").target == 0.8
