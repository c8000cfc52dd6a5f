"""The local film refresh between the X and Y halves of an alternating sweep
(``point.fas.LOCAL_UPDATE_FROM``): it adds exactly the near cell-kernel weights of a pressure
change, and the solve converges to the same discrete solution as with the full deformation."""

import numpy as np
import pytest

from ehl_multigrid.point import fas, solve_point
from ehl_multigrid.point import numerics as nm
from ehl_multigrid.point.deformation import cell_kernel, make_deformation


def test_the_local_update_adds_the_near_kernel_weights_of_the_full_deformation():
    nx, ny, h = 33, 17, 0.1
    K = cell_kernel(2, 2, h, h)
    P_old = np.zeros((ny, nx))
    P = P_old.copy()
    P[5, 10] = 0.3  # one changed point
    H = np.zeros_like(P)
    nm.local_film_update(H, P, P_old, K, False)
    W = make_deformation("fft", nx, ny, h, h, False, 1)(P)
    # the 3 x 3 neighbourhood carries the full deformation's values there, nothing beyond
    assert np.allclose(H[4:7, 9:12], W[4:7, 9:12], rtol=1e-12, atol=1e-14)
    H[4:7, 9:12] = 0.0
    assert not H.any()


def test_the_local_update_mirrors_rows_at_the_symmetry_line():
    nx, ny, h = 17, 9, 0.1
    K = cell_kernel(2, 2, h, h)
    P_old = np.zeros((ny, nx))
    P = P_old.copy()
    P[1, 8] = 1.0  # its mirror image at row -1 acts on row 0 as well
    H = np.zeros_like(P)
    nm.local_film_update(H, P, P_old, K, True)
    row = np.concatenate([K[:, :0:-1], K], axis=1)  # weights at X offsets -1, 0, 1
    expect = np.zeros_like(H)
    expect[0, 7:10] = 2.0 * row[1]  # the point and its mirror image, one row away each
    expect[1, 7:10] = row[0]
    expect[2, 7:10] = row[1]
    assert np.allclose(H, expect, rtol=1e-12, atol=1e-15)


def _count_local_updates(monkeypatch):
    """Count the calls of the local refresh (``numerics.local_film_update``)."""
    calls = []
    real = nm.local_film_update

    def counted(*args):
        calls.append(1)
        return real(*args)

    monkeypatch.setattr(nm, "local_film_update", counted)
    return calls


#: 257 points alternating on every grid: the finest grid (LOCAL_UPDATE_FROM) refreshes locally,
#: as 513 points do with the default alternation on the fine grids, at a third of the cost; to
#: the residual tolerance itself (grid_stop=None), without the error estimate's probes
CHEAP = dict(points=257, half=True, alternating=True, estimate=False, threads=1, tol=1e-7,
             tol_load=1e-7, max_cycles=40, grid_stop=None)


@pytest.fixture(scope="module")
def local():
    """(20, 10) solved with the local refresh, and the number of local refreshes it made: the
    solve both comparisons below start from."""
    mp = pytest.MonkeyPatch()
    try:
        calls = _count_local_updates(mp)
        return solve_point(20.0, 10.0, **CHEAP), len(calls)
    finally:
        mp.undo()


@pytest.mark.solver
@pytest.mark.xdist_group("point_local_film_update_local")
def test_a_solve_with_the_local_refresh_reaches_the_same_films(monkeypatch, local):
    local, refreshes = local
    assert refreshes  # the path under test was taken
    calls = _count_local_updates(monkeypatch)
    monkeypatch.setattr(fas.PointHierarchy, "local_update", False)
    full = solve_point(20.0, 10.0, **CHEAP)
    assert not calls
    assert local.success and full.success
    assert abs(local.Hc / full.Hc - 1.0) < 1e-6 and abs(local.Hm / full.Hm - 1.0) < 1e-6


@pytest.mark.solver
@pytest.mark.xdist_group("point_local_film_update_local")
def test_whole_refresh_option_gives_the_same_discrete_film(monkeypatch, local):
    """``local_film_update=False`` refreshes the film between the X and Y halves by a whole
    deformation evaluation: another iteration of the same discrete problem."""

    local, refreshes = local
    assert refreshes
    calls = _count_local_updates(monkeypatch)
    whole = solve_point(20.0, 10.0, local_film_update=False, **CHEAP)
    assert not calls  # whole deformations between the halves
    assert local.success and whole.success
    for f in ("Hc_venner", "Hm_venner"):
        assert whole.scalars[f] == pytest.approx(local.scalars[f], rel=2e-5)


@pytest.mark.slow
def test_a_barus_ellipse_that_diverges_on_x_lines_converges_with_alternating_lines():
    """Circular Barus (500, 20, theta 0.25) at 1025 points with the 1 % target (the fit map's
    case) diverges in its FMG on X lines (load errors of 1e173-1e286); the retry with X and Y
    lines alternating on every grid converges (about 17 s), with the local film refresh. It
    once needed the last retry (whole deformations between the halves); no case known now
    reaches it (the retry chain's order: test_point_retry_chain.py)."""

    r = solve_point(500.0, 20.0, theta=0.25, viscosity="barus", density="incompressible",
                    points=1025, accuracy=0.01, raise_on_failure=False)
    assert r.status_name in ("converged", "inaccurate")  # the iteration converged
    assert any("diverged" in a and "alternating on every grid" in a for a in r.actions)
