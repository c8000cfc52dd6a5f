"""Critical load (4.3.1): the EHL-ML transition speed is largest there."""

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from mixed.critical import critical_load
from mixed.sharing import load_sharing
from mixed.stribeck import transition_speed


def test_transition_speed_is_where_the_asperity_share_equals_the_fraction():
    sc = load_scene("page63_line_2000N")
    for frac in (0.9, 0.05, 1e-3):
        u = transition_speed(sc, frac)
        assert load_sharing(sc, u).asperity_fraction[0] == pytest.approx(frac, rel=1e-8)


def test_critical_load_maximises_the_ehl_ml_transition_speed():
    sc = load_scene("page63_line_2000N")
    c = critical_load(sc, fraction=0.07, n_scan=9)
    assert c.interior
    u0 = transition_speed(sc, 0.07, load=c.load)
    assert u0 == pytest.approx(c.us_transition, rel=1e-10)
    # below the critical load the transition moves to higher speed with load, above it to lower
    assert transition_speed(sc, 0.07, load=0.7 * c.load) < u0
    assert transition_speed(sc, 0.07, load=1.4 * c.load) < u0
    assert np.isfinite(c.hss_over_sigma_s) and c.asperity_log_stiffness > 0


def test_starved_transition_is_nan_when_the_supply_caps_the_film():
    sc = load_scene("chapter6_starved_1.93GPa")
    assert np.isnan(transition_speed(sc, 0.05, hoil=0.5 * sc.roughness.Rq))


def test_critical_load_rejects_bad_fraction():
    with pytest.raises(InputError, match="fraction"):
        critical_load(load_scene("page63_line_500N"), fraction=1.5)
