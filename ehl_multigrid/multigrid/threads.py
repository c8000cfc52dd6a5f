"""Thread use of one solve, without touching the caller's settings.

numba's thread count is process state: a solve that changes it (one thread on coarse grids,
where a barrier costs more than the work) restores the caller's value when it ends, and
the FFT worker count is passed to each deformation operator rather than set globally.

OpenMP threads (numba's usual threading layer) wait passively at the end of a parallel region
unless the environment already sets ``OMP_WAIT_POLICY``: this module sets the default before
the first parallel kernel loads the OpenMP runtime. Spinning threads take the time slice of the
thread doing the work when the other core is busy. Measured on a 2-core machine under load
(load average about 7; circular (20, 10), half domain, 513^2, median of 2): 8.3 s with two
spinning threads, 2.0 s with two passive threads, 4.0 s with one thread.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

# before numba loads libgomp (it does at the first parallel kernel, not at import); an
# explicit setting of the user's wins
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numba  # noqa: E402


def resolve_threads(threads: int | None) -> int:
    """Threads for a solve: the option, else the caller's current numba setting."""
    current = numba.get_num_threads()
    if threads is None:
        return current
    return max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS))


class ThreadBudget:
    """Switches numba between one thread (small grids) and the solve's thread count."""

    def __init__(self, threads: int, serial_below: int) -> None:
        self.threads = threads
        self.serial_below = serial_below
        self._current = numba.get_num_threads()

    def for_size(self, npts: int) -> None:
        want = 1 if npts < self.serial_below else self.threads
        if want != self._current:
            numba.set_num_threads(want)
            self._current = want


@contextmanager
def preserved_threads() -> Iterator[None]:
    """Restore numba's thread count on exit, whatever the body set."""
    saved = numba.get_num_threads()
    try:
        yield
    finally:
        numba.set_num_threads(saved)


_blas_controller = None


@contextmanager
def serial_blas() -> Iterator[None]:
    """One BLAS/LAPACK thread inside, the caller's setting restored on exit (threadpoolctl).

    For the dense LU factorisations of the line solver's Newton start: measured on this 2-core
    machine at load 5, one ``scipy.linalg.solve`` took 0.36 s at n = 512 and 0.44 s at 1024
    with OpenBLAS's two threads against 0.014 s and 0.062 s with one (the threads wait for a
    core). One thread also makes the factorisation's rounding, and so the Newton path, the
    same whatever the load."""
    global _blas_controller
    from threadpoolctl import ThreadpoolController

    if _blas_controller is None:
        _blas_controller = ThreadpoolController()
    with _blas_controller.limit(limits=1, user_api="blas"):
        yield
