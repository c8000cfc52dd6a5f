"""Thread use of one solve, without touching the caller's settings.

numba's thread count is process state: a solve that changes it (one thread on coarse grids,
where a barrier costs more than the work) restores the caller's value when it ends, and
the FFT worker count is passed to each deformation operator rather than set globally.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import numba


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
