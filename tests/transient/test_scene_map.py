"""A measured or synthetic surface in a scene's ``[feature]`` table (``kind = "map"``: a height
file in metres), for line and point contacts, and its named errors."""

import numpy as np
import pytest

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.point.problem import problem_from_scene
from ehl_multigrid.transient.scene_feature import (
    feature_from_scene_table,
    point_feature_from_scene_table,
)


@pytest.mark.solver
def test_a_text_profile_becomes_a_line_feature_in_venner_units(tmp_path, scene_with_feature):
    z = 20e-9 * np.sin(np.linspace(0.0, 6.0, 50))
    f = tmp_path / "profile.csv"
    np.savetxt(f, z[None, :], delimiter=",")
    sc = scene_with_feature("page63_line_2000N", {"kind": "map", "file": str(f), "dx": "2 um", "level": "none"})
    pb = LineProblem.from_scene(sc)
    feat, body = feature_from_scene_table(sc.feature, pb)
    assert body == 1 and feat.kind == "profile"
    assert np.allclose(feat.z, z * pb.R / pb.b**2)
    assert feat.x[1] - feat.x[0] == pytest.approx(2e-6 / pb.b)
    assert feat.x[0] == pytest.approx(pb.xmin)  # entering from the inlet


def test_an_npy_map_becomes_a_centred_point_height_map(tmp_path, scene_with_feature):
    z = np.random.default_rng(0).normal(0.0, 10e-9, (16, 24))
    f = tmp_path / "map.npy"
    np.save(f, z)
    sc = scene_with_feature("default", {"kind": "map", "file": str(f), "dx": "3 um", "dy": "2 um", "body": 2,
                                  "level": "none"})
    pb = problem_from_scene(sc)
    feat, body = point_feature_from_scene_table(sc.feature, pb)
    assert body == 2 and feat.z.shape == (16, 24)
    assert np.allclose(feat.z, z * pb.Rx / pb.a**2)
    x0, x1, y0, y1 = feat.extent
    assert x1 == pytest.approx(-1.5) and y0 == pytest.approx(-y1)


@pytest.mark.parametrize("content, match", [
    (None, "not a readable file"),
    ("1e-9, nan, 2e-9, 3e-9, 1e-9", "NaN"),
    ("1e-8 2e-8\n3e-8 4e-8", "one row"),
])
def test_bad_height_files_are_named(tmp_path, content, match, scene_with_feature):
    f = tmp_path / "h.txt"
    if content is not None:
        f.write_text(content)
    sc = scene_with_feature("page63_line_2000N", {"kind": "map", "file": str(f), "dx": "2 um"})
    with pytest.raises(InputError, match=match):
        feature_from_scene_table(sc.feature, LineProblem.from_scene(sc))


def test_a_map_without_its_spacing_is_refused(tmp_path, scene_with_feature):
    f = tmp_path / "p.csv"
    np.savetxt(f, np.zeros((1, 10)))
    sc = scene_with_feature("page63_line_2000N", {"kind": "map", "file": str(f)})
    with pytest.raises(InputError, match="feature.dx"):
        feature_from_scene_table(sc.feature, LineProblem.from_scene(sc))
