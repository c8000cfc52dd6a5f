"""The FFT deformation (pruned full domain, DCT-I half domain, work arrays reused) and the
half-domain direct sum give the direct O(N^2) sum of the film equation's elastic integral to
round-off."""

import numpy as np
import pytest

from ehl_multigrid.point.deformation import (
    DIRECT_MAX_POINTS,
    DirectDeformation,
    FFTDeformation,
    make_deformation,
    mirror_full,
)


def _pressure(nx, ny, half, seed=0):
    rng = np.random.default_rng(seed)
    P = rng.random((ny, nx))
    P[:, 0] = P[:, -1] = 0.0
    P[-1] = 0.0
    if not half:
        P[0] = 0.0
    return P


def _rel(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


@pytest.mark.parametrize("nx,ny,half", [(17, 17, False), (33, 33, False), (65, 33, False),
                                        (33, 65, False), (257, 129, False), (17, 9, True), (33, 17, True),
                                        (65, 33, True), (33, 9, True)])
def test_fft_equals_direct_sum_to_round_off(nx, ny, half):
    hx, hy = 6.0 / (nx - 1), 0.23
    P = _pressure(nx, ny, half)
    ref = DirectDeformation(nx, ny, hx, hy, half)(P)
    assert _rel(FFTDeformation(nx, ny, hx, hy, half)(P), ref) < 1e-12


@pytest.mark.parametrize("nx,ny", [(17, 9), (33, 17)])
def test_half_direct_sum_equals_mirrored_full_sum(nx, ny):
    hx, hy = 6.0 / (nx - 1), 0.3
    P = _pressure(nx, ny, True)
    full = DirectDeformation(nx, 2 * ny - 1, hx, hy).full(mirror_full(P))[ny - 1:]
    assert _rel(DirectDeformation(nx, ny, hx, hy, True)(P), full) < 1e-13


@pytest.mark.parametrize("half", [False, True])
def test_fft_writes_into_out_and_repeated_calls_agree(half):
    nx, ny = 65, 33
    op = FFTDeformation(nx, ny, 0.1, 0.1, half)
    P1, P2 = _pressure(nx, ny, half, 1), _pressure(nx, ny, half, 2)
    out = np.empty((ny, nx))
    first = op(P1).copy()
    assert op(P2, out) is out
    # the reused work arrays carry nothing from one call to the next
    assert np.array_equal(op(P1), first)
    assert _rel(out, DirectDeformation(nx, ny, 0.1, 0.1, half)(P2)) < 1e-12


def test_fft_kind_sums_directly_on_small_grids_only():
    assert isinstance(make_deformation("fft", 17, 9, 0.1, 0.1, True), DirectDeformation)
    assert 17 * 9 <= DIRECT_MAX_POINTS < 17 * 17
    assert isinstance(make_deformation("fft", 17, 17, 0.1, 0.1), FFTDeformation)


def test_fft_rejects_a_pressure_of_another_grid():
    with pytest.raises(ValueError, match="shape"):
        FFTDeformation(33, 33, 0.1, 0.1)(np.zeros((17, 17)))


@pytest.mark.parametrize("half", [False, True])
def test_fft_with_two_workers_equals_one_worker(half):
    # workers are used from 256^2 points on
    nx, ny = 257, 257
    P = _pressure(nx, ny, half)
    one = FFTDeformation(nx, ny, 0.05, 0.05, half, workers=1)(P)
    two = FFTDeformation(nx, ny, 0.05, 0.05, half, workers=2)
    assert two._workers(P.size) == 2
    assert _rel(two(P), one) < 1e-14


@pytest.mark.parametrize("parts", [1, 2, 3])
@pytest.mark.parametrize("n", [1, 5, 64, 513])
def test_thread_ranges_cover_every_index_once(parts, n):
    from ehl_multigrid.point.deformation import _split

    hits = np.zeros(n, dtype=int)

    def mark(lo, hi):
        hits[lo:hi] += 1

    _split(mark, n, parts)
    assert (hits == 1).all()


def test_an_error_in_a_thread_range_reaches_the_caller():
    from ehl_multigrid.point.deformation import _split

    def fail_first(lo, hi):
        if lo == 0:
            raise RuntimeError("range 0 failed")

    with pytest.raises(RuntimeError, match="range 0 failed"):
        _split(fail_first, 100, 2)


def test_a_forked_process_builds_its_own_thread_pool():
    import multiprocessing as mp

    from ehl_multigrid.point.deformation import _split

    _split(lambda lo, hi: None, 100, 2)  # the parent's pool exists now
    ctx = mp.get_context("fork")
    with ctx.Pool(1) as pool:
        res = pool.apply_async(_forked_split_total)
        assert res.get(timeout=60) == 4950


def _forked_split_total() -> int:
    from ehl_multigrid.point.deformation import _split

    total = np.zeros(1, dtype=np.int64)
    parts = []

    def add(lo, hi):
        parts.append(int(np.arange(lo, hi).sum()))

    _split(add, 100, 2)
    total[0] = sum(parts)
    return int(total[0])
