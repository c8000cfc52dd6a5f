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
