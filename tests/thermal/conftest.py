import pytest

from ehl_multigrid.model.scene import load_scene


@pytest.fixture(scope="session")
def line_hi():
    """Appendix C line contact, P = 42400 N (pmax 1.6 GPa), us = 8 m/s, T9."""
    return load_scene("appendix_c_line_42400N")


@pytest.fixture(scope="session")
def line_lo():
    """Appendix C line contact, P = 4240 N (pmax 0.5 GPa)."""
    return load_scene("appendix_c_line_4240N")


@pytest.fixture(scope="session")
def point():
    """Appendix D ball on flat, 42.8 N (pmax 1 GPa), T9 with tau0 = 8 MPa."""
    return load_scene("appendix_d_point")


@pytest.fixture(scope="session")
def tehl_ball_5n_129():
    """The TEHL solve of the appendix D ball on flat at 5 N (resolved from 65 points) at S =
    0.5 on 129 points, nz = 10, from the isothermal start (no coarser grid's factors): read by
    test_tehl_point.py and test_tehl_accuracy.py, whose tests that take it share the xdist
    group ``tehl_point_5n``."""
    from thermal.tehl.point import solve_tehl_point

    return solve_tehl_point(load_scene("appendix_d_point").with_operating(load=5.0), 0.5, points=129, nz=10)


@pytest.fixture(scope="session")
def tehl_line_lo_1025(line_lo):
    """The TEHL solve of :func:`line_lo` at S = 0.5 on 1025 points, nz = 10, from the
    isothermal start: read by test_tehl_line.py and test_tehl_accuracy.py, whose tests that
    take it share the xdist group ``tehl_line_lo_1025``."""
    from thermal.tehl import solve_tehl_line

    return solve_tehl_line(line_lo, 0.5, points=1025, nz=10)
