"""A molecularly thin starved film cannot shear harder than the boundary layers: f <= fc."""

import numpy as np
import pytest

from ehl_multigrid.model.scene import Scene, load_scene
from mixed.friction import mixed_friction
from mixed.sharing import load_sharing


def very_smooth_starved_scene():
    d = load_scene("series_D_disc3_1.93GPa").to_dict()
    d["roughness"].update({"sigma_s": 1e-9, "Rq": 1e-9 / 0.7, "dd": 0.82e-9 / 0.7})
    d["operating"]["us"] = 100.0
    return Scene.from_dict(d)


def test_friction_never_exceeds_boundary_friction_for_a_molecular_film():
    sc = very_smooth_starved_scene()
    ls = load_sharing(sc, np.array([100.0]), hoil=0.01 * sc.roughness.Rq)
    assert ls.hfr[0] < 1e-10  # sub-angstrom film: the case the cap is for
    capped = mixed_friction(sc, ls)
    free = mixed_friction(sc, ls, limit_film_to_boundary=False)
    assert free.coefficient[0] > sc.roughness.fc  # without the cap Eyring exceeds fc here
    assert capped.coefficient[0] == pytest.approx(sc.roughness.fc, rel=1e-12)
    assert capped.film_limited[0]


def test_cap_does_not_touch_ordinary_films():
    sc = load_scene("page63_line_2000N")
    ls = load_sharing(sc, np.geomspace(1e-3, 100, 30))
    a = mixed_friction(sc, ls)
    b = mixed_friction(sc, ls, limit_film_to_boundary=False)
    assert not a.film_limited.any()
    np.testing.assert_array_equal(a.coefficient, b.coefficient)
