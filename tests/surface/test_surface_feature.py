"""Measured surfaces as transient features: the mixed layer's height-map reader, found by the
transient solver through the ``ehl.height_maps`` entry point (formats, units, levelling,
filters, the rolling axis), and a short transient run of a synthetic surface from a scene."""

import json

import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.point.problem import problem_from_scene
from ehl_multigrid.transient.scene_feature import (
    feature_from_scene_table,
    height_map_reader,
    point_feature_from_scene_table,
)
from mixed.surface.feature import feature_heights
from mixed.surface.synthetic import gaussian_random_surface


def test_the_transient_solver_finds_the_mixed_layer_reader():
    assert height_map_reader() is feature_heights


def test_an_xyz_file_in_nanometres_with_a_tilt_is_levelled_and_scaled(tmp_path):
    nx, ny, d = 12, 8, 0.5  # um
    x, y = np.meshgrid(np.arange(nx) * d, np.arange(ny) * d)
    rough = 20.0 * np.sin(2 * np.pi * x / 3.0) * np.cos(2 * np.pi * y / 2.0)  # nm
    tilt = 400.0 * x  # nm: 2 um over the map, far above the film
    f = tmp_path / "scan.xyz"
    np.savetxt(f, np.column_stack([x.ravel(), y.ravel(), (rough + tilt).ravel()]),
               header="units = nm\nxy_units = um")
    z, dx, dy = feature_heights({"file": str(f), "units": "nm", "xy_units": "um"}, 2)
    assert dx == pytest.approx(0.5e-6) and dy == pytest.approx(0.5e-6)
    # the plane fit removes the tilt; what is left is the roughness (its own mean plane aside)
    expect = rough * 1e-9
    X = np.column_stack([np.ones(x.size), x.ravel(), y.ravel()])
    expect = expect - (X @ np.linalg.lstsq(X, expect.ravel(), rcond=None)[0]).reshape(expect.shape)
    assert np.allclose(z, expect, atol=1e-14)


def test_a_map_rolled_along_y_is_transposed_and_a_line_contact_takes_one_row(tmp_path):
    z = np.random.default_rng(1).normal(0.0, 5e-9, (6, 9))
    f = tmp_path / "m.npy"
    np.save(f, z)
    zt, dx, dy = feature_heights({"file": str(f), "dx": 1e-6, "dy": 2e-6, "level": "none",
                                  "rolling": "y"}, 2)
    assert zt.shape == (9, 6) and np.array_equal(zt, z.T) and (dx, dy) == (2e-6, 1e-6)
    row, dx1, dy1 = feature_heights({"file": str(f), "dx": 1e-6, "level": "none", "row": 4}, 1)
    assert np.array_equal(row, z[4]) and dx1 == 1e-6 and dy1 is None


def test_a_gaussian_filter_removes_the_short_waves_of_a_map(tmp_path):
    nx = 64
    x = np.arange(nx) * 1e-6
    long_wave = 10e-9 * np.sin(2 * np.pi * x / 32e-6)
    short_wave = 10e-9 * np.sin(2 * np.pi * x / 2e-6 + 0.3)
    f = tmp_path / "w.npy"
    np.save(f, np.tile(long_wave + short_wave, (8, 1)))
    z, _, _ = feature_heights({"file": str(f), "dx": 1e-6, "level": "none", "filter": "gauss:8um"}, 2)
    mid = slice(16, 48)  # away from the filter's edge treatment
    resid = z[4, mid] - long_wave[mid]
    assert np.sqrt(np.mean(resid**2)) < 0.15 * np.sqrt(np.mean(short_wave[mid] ** 2))


@pytest.mark.parametrize("table, match", [
    ({"file": "x.npy", "dx": 1e-6, "levle": "none"}, "levle"),
    ({"file": "MISSING", "dx": 1e-6}, "not a readable file"),
    ({"file": "p.txt", "dx": 1e-6, "level": "tilted"}, "feature.level"),
    ({"file": "p.txt", "dx": 1e-6, "filter": "gauss:8um"}, "needs a 2-D map"),
    ({"file": "p.txt"}, "feature.dx"),
])
def test_bad_map_keys_are_named(tmp_path, monkeypatch, table, match):
    monkeypatch.chdir(tmp_path)
    np.save(tmp_path / "x.npy", np.zeros((4, 4)))
    np.savetxt(tmp_path / "p.txt", np.linspace(0.0, 1e-8, 20)[None, :])
    with pytest.raises(InputError, match=match):
        feature_heights(table, 1, {"kind"})


def test_the_scene_keys_of_the_solver_stay_its_own(tmp_path, scene_with_feature):
    """x0, y0 and body are the solver's; the reader accepts them and the solver places the map."""
    surf = gaussian_random_surface((16, 16), 2e-6, 10e-9, corr_length=8e-6, seed=3)
    f = tmp_path / "s.npy"
    np.save(f, surf.z)
    sc = scene_with_feature("default", {"kind": "map", "file": str(f), "dx": 2e-6, "dy": 2e-6, "x0": -2.0,
                            "body": 2})
    pb = problem_from_scene(sc)
    feat, body = point_feature_from_scene_table(sc.feature, pb)
    assert body == 2 and feat.extent[0] == pytest.approx(-2.0)
    # a line scene reads the middle row of the same map
    sl = scene_with_feature("page63_line_2000N", {"kind": "map", "file": str(f), "dx": 2e-6})
    lf, _ = feature_from_scene_table(sl.feature, LineProblem.from_scene(sl))
    assert lf.z.size == 16


@pytest.mark.solver
def test_a_synthetic_surface_passes_through_a_line_contact_from_a_scene_file(tmp_path, monkeypatch, capsys):
    """``ehl transient`` on a scene whose [feature] is a synthetic height map written as text with
    a unit header (nanometres, 1.5 nm Rq under a 6 nm film): it runs, and the central film
    moves with the surface."""
    surf = gaussian_random_surface((32, 256), 1e-6, 1.5e-9, corr_length=6e-6, seed=7)
    f = tmp_path / "rough.txt"
    np.savetxt(f, surf.z * 1e9, header="dx = 1 um\nunits = nm")
    d = load_scene("page63_line_2000N").to_dict()
    d["feature"] = {"kind": "map", "file": str(f), "units": "nm", "row": 3, "x0": -1.0}
    path = tmp_path / "rough.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    monkeypatch.chdir(tmp_path)
    rc = main(["transient", str(path), "--accuracy", "none", "--points", "129", "--steps", "60", "--json", "--out", str(tmp_path / "o"),
               "--no-plots"])
    out = capsys.readouterr()
    assert rc == 0, out.err
    payload = json.loads(out.out[out.out.index("{"):])
    assert payload["converged"] and payload["hc_max"] > 1.005 * payload["hc_min"]
