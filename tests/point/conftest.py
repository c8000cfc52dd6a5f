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
