"""Thread use of one solve, without touching the caller's settings.

numba's thread count is process state: a solve that changes it (one thread on coarse grids,
where a barrier costs more than the work) restores the caller's value when it ends, and
the FFT worker count is passed to each deformation operator rather than set globally.

Importing the package changes no environment variable. OpenMP threads (numba's usual
threading layer) spin at the end of a parallel region unless ``OMP_WAIT_POLICY`` says
otherwise, and a spinning thread takes the time slice of the thread doing the work when the
other core is busy (on a loaded 2-core machine, circular (20, 10) at 513^2: 8.3 s with two
spinning threads, 2.0 s with two passive ones, 4.0 s with one thread). The ``ehl`` command
calls :func:`passive_openmp_wait` at its start and :func:`ehl_multigrid.solve` at each call;
code that runs the kernels without them sets ``OMP_WAIT_POLICY=PASSIVE`` before the first
parallel kernel runs (the OpenMP runtime reads it once, when numba loads it).

numba is imported on first use, so that the command line can call
:func:`passive_openmp_wait` without loading it.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

#: the OpenMP wait policy the ``ehl`` command defaults to (:func:`passive_openmp_wait`)
OMP_WAIT_POLICY = "PASSIVE"


def passive_openmp_wait() -> bool:
    """Default ``OMP_WAIT_POLICY`` to ``PASSIVE`` in this process's environment (a value already
    set wins): waiting OpenMP threads then sleep instead of spinning.

    For programs (the ``ehl`` entry point), not for import: call it before the first parallel
    numba kernel, after which the OpenMP runtime no longer reads the variable. Child processes
    inherit it.

    Returns
    -------
    bool
        True when this call set the variable, False when the environment already had it.
    """
    if "OMP_WAIT_POLICY" in os.environ:
        return False
    os.environ["OMP_WAIT_POLICY"] = OMP_WAIT_POLICY
    return True


def resolve_threads(threads: int | None) -> int:
    """Threads for a solve: the option, else the caller's current numba setting."""
    import numba

    current = numba.get_num_threads()
    if threads is None:
        return current
    return max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS))


class ThreadBudget:
    """Switches numba between one thread (small grids) and the solve's thread count.

    Parameters
    ----------
    threads : the solve's thread count (:func:`resolve_threads`).
    serial_below : grids with fewer points run on one thread
        (``PointOptions.serial_below``).

    The caller restores its own thread count afterwards (:func:`preserved_threads`).
    """

    def __init__(self, threads: int, serial_below: int) -> None:
        self.threads = threads
        self.serial_below = serial_below
        import numba

        self._current = numba.get_num_threads()

    def for_size(self, npts: int) -> None:
        """Set numba's thread count for the kernels of a grid of ``npts`` points."""
        want = 1 if npts < self.serial_below else self.threads
        if want != self._current:
            import numba

            numba.set_num_threads(want)
            self._current = want


@contextmanager
def preserved_threads() -> Iterator[None]:
    """Restore numba's thread count on exit, whatever the body set."""
    import numba

    saved = numba.get_num_threads()
    try:
        yield
    finally:
        numba.set_num_threads(saved)


_blas_controller = None


@contextmanager
def serial_blas() -> Iterator[None]:
    """One BLAS/LAPACK thread inside, the caller's setting restored on exit (threadpoolctl).

    For the dense LU factorisations of the line solver's Newton start: on a 2-core machine at
    load 5, one ``scipy.linalg.solve`` takes 0.36 s at n = 512 and 0.44 s at 1024 with
    OpenBLAS's two threads against 0.014 s and 0.062 s with one (the threads wait for a
    core). One thread also makes the factorisation's rounding, and so the Newton path, the
    same whatever the load."""
    global _blas_controller
    from threadpoolctl import ThreadpoolController

    if _blas_controller is None:
        _blas_controller = ThreadpoolController()
    with _blas_controller.limit(limits=1, user_api="blas"):
        yield
