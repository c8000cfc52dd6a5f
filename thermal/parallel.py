"""Many independent line problems at once (the slices of a point contact, the slips of a
traction curve, the speeds of a Stribeck curve).

Each line of the thermal model (thesis 3.2.2.2: one line contact, or one slice of a point
contact) is solved on its own, so a batch of lines runs on a pool of threads: the compiled
march (:func:`thermal.kernels.sweep_line`) and the surface weights release the GIL, and each
line owns its arrays. The answer of every line is the one of the serial call.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.multigrid.threads import resolve_threads

from .line import Surroundings, ThermalLineSolution, solve_thermal_line
from .options import ThermalOptions
from .profiles import LineProfile


@dataclass(frozen=True)
class LineJob:
    """One line problem: the arguments of :func:`~thermal.line.solve_thermal_line`."""

    profile: LineProfile
    env: Surroundings
    options: ThermalOptions
    kernel_length: float = math.inf
    #: a solution of a nearby profile on the same stations to start from (warm start)
    start: ThermalLineSolution | None = None


def _solve(job: LineJob, keep_errors: bool) -> ThermalLineSolution | ConvergenceError:
    try:
        return solve_thermal_line(job.profile, job.env, job.options, kernel_length=job.kernel_length,
                                  start=job.start)
    except ConvergenceError as exc:
        if keep_errors:
            return exc
        raise


def solve_thermal_lines(
    jobs: Sequence[LineJob], *, threads: int | None = None, keep_errors: bool = False,
) -> Iterator[ThermalLineSolution | ConvergenceError]:
    """Solve ``jobs`` and yield their solutions in order, as they become available.

    Parameters
    ----------
    jobs : the line problems.
    threads : pool size (default: numba's current thread count, the package's thread setting);
        1 solves them one after the other in the calling thread.
    keep_errors : yield a line's :class:`ConvergenceError` in its place instead of raising it.
        Other errors are always raised.

    An error raised while iterating cancels the lines not yet started.
    """
    n = len(jobs)
    workers = min(resolve_threads(threads), n)
    if workers <= 1:
        for job in jobs:
            yield _solve(job, keep_errors)
        return
    pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="thermal-line")
    try:
        futures = [pool.submit(_solve, job, keep_errors) for job in jobs]
        for fut in futures:
            yield fut.result()
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
