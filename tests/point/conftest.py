import numpy as np
import pytest

import ehl_multigrid.point.solve as solve_mod


@pytest.fixture
def probing(monkeypatch):
    """A one-element list whose value is True while a domain probe
    (``point.solve.point_domain_change``) runs: tests that make one solve of a sequence fail
    tell the sequence's solves from the probes' on the same grid and box."""
    flag = [False]
    real = solve_mod.point_domain_change

    def probe(*args, **kw):
        flag[0] = True
        try:
            return real(*args, **kw)
        finally:
            flag[0] = False

    monkeypatch.setattr(solve_mod, "point_domain_change", probe)
    return flag


def _load_around_box(pressure, xmin: float, xmax: float, ymax: float, big: float = 20.0,
                     h: float = 0.01) -> float:
    """Trapezoid sums of ``pressure(X, Y)`` (2-D arrays) over the eight rectangles around the
    box ``[xmin, xmax] x [-ymax, ymax]`` out to the square of half-side ``big``: the far-field
    load tests add the analytic load beyond that square."""
    num = 0.0
    for xa, xb in ((-big, xmin), (xmin, xmax), (xmax, big)):
        for ya, yb in ((-big, -ymax), (-ymax, ymax), (ymax, big)):
            if (xa, ya) == (xmin, -ymax):
                continue
            x = np.linspace(xa, xb, int(round((xb - xa) / h)) + 1)
            y = np.linspace(ya, yb, int(round((yb - ya) / h)) + 1)
            num += np.trapezoid(np.trapezoid(pressure(x[None, :], y[:, None]), x, axis=1), y)
    return float(num)


@pytest.fixture
def load_around_box():
    """:func:`_load_around_box`, for the far-field load tests."""
    return _load_around_box
