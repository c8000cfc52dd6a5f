"""The accuracy sequence reports the seconds its estimator took (``estimate_s``: the box probes
before the first solve, the probes and repair solves of each estimate), a call inside another
timed call counted once, beside the sequence's total (``wall_total_s``)."""

import time

from ehl_multigrid.line import solve_line
from ehl_multigrid.multigrid.accuracy import EstimateClock


def test_nested_timed_calls_are_counted_once():
    clock = EstimateClock()

    def inner():
        time.sleep(0.02)

    outer = clock.timed(lambda: (time.sleep(0.02), clock.timed(inner)()))
    t0 = time.perf_counter()
    outer()
    clock.timed(inner)()
    t2 = time.perf_counter()
    # the two outermost calls, whatever the machine's load; counting the nested call again
    # would add its 0.02 s
    assert t2 - t0 - 0.005 <= clock.seconds <= t2 - t0
    assert clock.timed(None) is None


def test_an_accuracy_sequence_reports_its_estimator_seconds_within_its_total():
    r = solve_line(20, 10, accuracy=0.02)
    est, total = r.extra["estimate_s"], r.extra["wall_total_s"]
    assert r.scalars["estimate_s"] == est
    assert 0.0 < est < total
    assert r.payload()["estimate_s"] == est  # what `ehl solve --json` writes
