import numpy as np
import pytest
from scipy.integrate import simpson

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


def _even(n: int) -> int:
    return n + n % 2


def _load_around_box(pressure, xmin: float, xmax: float, ymax: float, big: float = 20.0,
                     h: float = 0.01) -> float:
    """Simpson sums (an even number of intervals of about ``h``) of ``pressure(X, Y)`` (2-D
    arrays) over the eight rectangles around the box ``[xmin, xmax] x [-ymax, ymax]`` out to the
    square of half-side ``big``: the far-field load tests add the analytic load beyond that
    square. Where the pressure is smooth (the elliptic far fields) Simpson on 0.04 is within
    2e-7 of the load, trapezoids on 0.01 (16 times the evaluations) within 4e-6; the circular
    one with its gap terms converges at first order either way (2e-5 on 0.01)."""
    num = 0.0
    for xa, xb in ((-big, xmin), (xmin, xmax), (xmax, big)):
        for ya, yb in ((-big, -ymax), (-ymax, ymax), (ymax, big)):
            if (xa, ya) == (xmin, -ymax):
                continue
            x = np.linspace(xa, xb, _even(int(round((xb - xa) / h))) + 1)
            y = np.linspace(ya, yb, _even(int(round((yb - ya) / h))) + 1)
            num += simpson(simpson(pressure(x[None, :], y[:, None]), x=x, axis=1), x=y)
    return float(num)


@pytest.fixture
def load_around_box():
    """:func:`_load_around_box`, for the far-field load tests."""
    return _load_around_box
