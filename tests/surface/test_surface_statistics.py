"""Statistics of analytic and planted surfaces (thesis 4.4.1-4.4.2, (2.48)-(2.49))."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from mixed.surface import (
    HeightMap,
    combine_statistics,
    counter_surface,
    find_summits,
    handle_missing,
    level,
    planted_asperities,
    plasticity_index,
    remove_form,
    remove_plane,
    sum_surface,
    surface_statistics,
)
from mixed.surface.statistics import amplitude_statistics


def egg_crate(n_periods: int = 8, pts: int = 16, dx: float = 1e-6, amp: float = 1e-7) -> HeightMap:
    """cos(kx) cos(ky) on (pts * n_periods + 2)^2 points: the tested interior holds whole periods."""
    n = pts * n_periods + 2
    k = 2 * math.pi / (pts * dx)
    x = np.arange(n) * dx
    return HeightMap(amp * np.outer(np.cos(k * x), np.cos(k * x)), dx, dx)


def test_sinusoid_ra_rq_skewness_kurtosis():
    n, per, dx, A = 2048, 256, 1e-6, 2e-7
    x = np.arange(n) * dx
    z = np.tile(A * np.sin(2 * math.pi * x / (per * dx)), (5, 1))
    st = amplitude_statistics(HeightMap(z, dx, dx))
    assert st["Rq"] == pytest.approx(A / math.sqrt(2), rel=1e-12)
    assert st["Ra"] == pytest.approx(2 * A / math.pi, rel=1e-4)
    assert abs(st["Rsk"]) < 1e-10
    assert st["Rku"] == pytest.approx(1.5, rel=1e-10)


def test_paraboloid_curvature_is_exact():
    dx, dy, Rx, Ry = 1e-6, 2e-6, 30e-6, 50e-6
    x = (np.arange(21) - 10) * dx
    y = (np.arange(21) - 10) * dy
    z = 1e-7 - y[:, None] ** 2 / (2 * Ry) - x[None, :] ** 2 / (2 * Rx)
    s = find_summits(HeightMap(z, dx, dy))
    assert s.count == 1
    assert (s.iy[0], s.ix[0]) == (10, 10)
    assert s.kappa[0] == pytest.approx(0.5 * (1 / Rx + 1 / Ry), rel=1e-9)


def test_egg_crate_summit_density_and_discrete_curvature():
    dx, pts = 1e-6, 16
    hm = egg_crate(pts=pts, dx=dx)
    st = surface_statistics(hm)
    lam = pts * dx
    k = 2 * math.pi / lam
    assert st.n == pytest.approx(2 / lam**2, rel=1e-12)  # maxima of cos*cos: 2 per period cell
    # 3-point second difference of cos: (2 - 2 cos(k dx))/dx^2 per axis, times amplitude
    assert st.kappa_mean == pytest.approx(1e-7 * (2 - 2 * math.cos(k * dx)) / dx**2, rel=1e-9)
    assert st.sigma_s == pytest.approx(0.0, abs=1e-20)  # every summit at the same height
    assert st.dd == pytest.approx(1e-7 - np.mean(hm.z), rel=1e-9)


def test_curvature_error_falls_second_order():
    """Accuracy: the 3-point curvature of a sphere's apex converges as dx^2 (observed order 2)."""
    R = 20e-6
    errs = []
    for dx in (2e-6, 1e-6, 0.5e-6):
        x = np.arange(-5, 6) * dx
        r2 = x[:, None] ** 2 + x[None, :] ** 2
        s = find_summits(HeightMap(np.sqrt(R**2 - r2), dx, dx))
        errs.append(abs(s.kappa[0] * R - 1))
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(np.abs(orders - 2) < 0.05), orders


def test_flat_plateau_has_no_summit():
    z = np.zeros((10, 10))
    z[4:6, 4:6] = 1e-7  # a 2 x 2 plateau: no point strictly higher than all 8 neighbours
    assert find_summits(HeightMap(z, 1e-6, 1e-6)).count == 0


def test_edges_are_not_tested():
    z = np.zeros((7, 7))
    z[0, 3] = 1.0
    z[3, 6] = 1.0
    s = find_summits(HeightMap(z, 1e-6, 1e-6))
    assert s.count == 0 and s.n_tested == 25


def test_planted_asperities_recovered_exactly():
    dx, R = 0.5e-6, 30e-6
    hm, truth = planted_asperities((200, 240), dx, 1e10, R, 0.06e-6, 0.012e-6, seed=3)
    s = find_summits(hm)
    # caps whose nearest grid point is interior give exactly one summit each
    jx, jy = np.rint(truth.x / dx).astype(int), np.rint(truth.y / dx).astype(int)
    inner = (jx >= 1) & (jx <= hm.nx - 2) & (jy >= 1) & (jy <= hm.ny - 2)
    assert s.count == int(inner.sum())
    r2 = (jx[inner] * dx - truth.x[inner]) ** 2 + (jy[inner] * dx - truth.y[inner]) ** 2
    expected = truth.apex[inner] - R + np.sqrt(R**2 - r2) - hm.z.mean()
    np.testing.assert_allclose(np.sort(s.height), np.sort(expected), rtol=1e-9)
    st = surface_statistics(hm)
    assert st.beta == pytest.approx(R, rel=2e-3)  # 3-point stencil off the apex: O(dx^2/R^2)
    assert st.sigma_s == pytest.approx(np.std(truth.apex[inner], ddof=1), rel=0.02)
    assert st.n == pytest.approx(truth.density, rel=0.1)


def test_plasticity_index_matches_thesis_table_4_3():
    # (sigma_s, beta, psi) of discs 1-4 (Table 4.3) and section 5.2-5.3; E' = 2.3e11, H' = 5 GPa
    rows = [(0.034e-6, 27e-6, 0.816), (0.029e-6, 46.2e-6, 0.58), (0.018e-6, 61.2e-6, 0.39),
            (0.27e-6, 5.441e-6, 5.12), (0.22e-6, 8.5e-6, 3.7), (0.13e-6, 58.8e-6, 1.083)]
    for ss, beta, psi in rows:
        assert plasticity_index(ss, beta, 2.3e11, 5e9) == pytest.approx(psi, abs=0.006)


def test_combined_surfaces_root_sum_square():
    hm, _ = planted_asperities(128, 0.5e-6, 1e10, 30e-6, 0.06e-6, 0.012e-6, seed=1)
    s1 = surface_statistics(hm)
    ball = counter_surface(0.0225e-6)
    c = combine_statistics(s1, ball)
    assert c.sigma_s == pytest.approx(math.hypot(s1.sigma_s, 0.0225e-6))
    assert c.Rq == pytest.approx(math.hypot(s1.Rq, 0.0225e-6 / 0.7))
    assert (c.n, c.beta) == (s1.n, s1.beta)
    assert c.psi == pytest.approx(plasticity_index(c.sigma_s, c.beta, s1.E_reduced, s1.hardness))
    h = combine_statistics(s1, s1, beta_rule="harmonic")
    assert h.beta == pytest.approx(s1.beta / 2)
    twice = surface_statistics(sum_surface(hm, hm))
    assert twice.Rq == pytest.approx(2 * s1.Rq)
    with pytest.raises(InputError):
        sum_surface(hm, HeightMap(hm.z[:-1], hm.dx, hm.dy))


def test_plane_and_form_removal_are_exact():
    ny, nx, dx = 30, 40, 1e-6
    y, x = np.mgrid[0:ny, 0:nx] * dx
    plane = 1e-7 + 3e-3 * x - 2e-3 * y
    hm = HeightMap(plane, dx, dx)
    assert np.abs(remove_plane(hm).z).max() < 1e-18
    quad = plane + 50.0 * x**2 - 20.0 * x * y
    assert np.abs(remove_form(HeightMap(quad, dx, dx), 2).z).max() < 1e-15
    holes = plane.copy()
    holes[5:9, 10:20] = np.nan
    lev = remove_plane(HeightMap(holes, dx, dx))
    assert np.isnan(lev.z[6, 12]) and np.nanmax(np.abs(lev.z)) < 1e-18
    assert lev.history == ("plane (tilt) removed",)


def test_missing_points_excluded_or_filled():
    rng = np.random.default_rng(0)
    z = rng.normal(0, 1e-7, (40, 50))
    zn = z.copy()
    zn[10:14, 20:26] = np.nan
    hm = HeightMap(zn, 1e-6, 1e-6)
    ex = handle_missing(hm, "exclude")
    st = surface_statistics(ex)
    valid = z[~np.isnan(zn)]
    assert st.Rq == pytest.approx(np.sqrt(np.mean((valid - valid.mean()) ** 2)))
    assert st.n_missing == 24
    assert st.n_tested == 38 * 48 - (6 * 8)  # the hole grown by one point on each side
    s = find_summits(ex)
    assert not np.any((s.iy >= 9) & (s.iy <= 14) & (s.ix >= 19) & (s.ix <= 26))
    assert "24 missing points excluded" in ex.history
    # a harmonic fill reproduces a plane exactly and makes no summit inside a hole
    y, x = np.mgrid[0:40, 0:50] * 1e-6
    plane = 2e-3 * x + 1e-3 * y
    pn = plane.copy()
    pn[10:14, 20:26] = np.nan
    filled = handle_missing(HeightMap(pn, 1e-6, 1e-6), "fill")
    np.testing.assert_allclose(filled.z, plane, atol=1e-18)
    fz = handle_missing(hm, "fill")
    assert not np.isnan(fz.z).any()
    sf = find_summits(fz)
    assert not np.any((sf.iy >= 11) & (sf.iy <= 12) & (sf.ix >= 21) & (sf.ix <= 24))
    with pytest.raises(InputError, match="nan policy"):
        handle_missing(hm, "drop")


def test_too_few_summits_give_nan_not_error():
    x = (np.arange(11) - 5) * 1e-6
    z = -(x[:, None] ** 2 + x[None, :] ** 2) / 60e-6
    st = surface_statistics(HeightMap(z, 1e-6, 1e-6))
    assert st.n_summits == 1 and math.isnan(st.beta) and math.isnan(st.psi)
    assert any("summit" in n for n in st.notes)
    with pytest.raises(InputError, match=r"roughness\.sigma_s\b.*\(nan\).*\b1 summits"):
        st.roughness_block()


def test_levelling_choice_checked():
    with pytest.raises(InputError, match="levelling"):
        level(HeightMap(np.zeros((3, 3)), 1.0, 1.0), "cubic")
