"""The thermal Stribeck curve (thesis 5.4) solves all its film points as one batch of line
problems; each point's film force is the one thermal.film_friction gives at that point."""

import numpy as np
import pytest

from ehl_multigrid.model.scene import load_scene
from mixed.stribeck import stribeck_curve
from thermal import film_friction


@pytest.mark.parametrize("name, opts", [("page63_line_2000N", {"nx": 20, "nz": 5}),
                                        ("series_C_disc3_1.93GPa", {"nx": 20, "nz": 5, "slices": 3})])
def test_thermal_stribeck_points_equal_film_friction_at_each_speed(name, opts):
    sc = load_scene(name)
    us = np.geomspace(0.01, 10.0, 4)
    c = stribeck_curve(sc, us, thermal=True, thermal_options=opts, transitions=False)
    assert c.friction.thermal_used.all()
    for i, u in enumerate(us):
        ff = film_friction(sc, load=float(c.sharing.Ph[i]), h=float(c.sharing.hfr[i]), us=float(u),
                           slip=abs(sc.slip), thermal=True, pressure="hertz", **opts)
        assert c.friction.film_force[i] == min(abs(ff.force), c.friction.fc * c.sharing.Ph[i])
        assert c.friction.max_temperature_rise[i] == ff.max_temperature_rise
