"""``ehl surface``: JSON keys, scene writing, PNG and error exit codes."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.scene import load_scene
from mixed.surface import gaussian_random_surface, read_height_map

MAIN = ("Ra", "Rq", "n", "beta", "sigma_s", "dd", "psi")


@pytest.fixture
def csv_map(tmp_path):
    hm = gaussian_random_surface(96, 0.781e-6, 0.2e-6, corr_length=4e-6, seed=11)
    p = tmp_path / "disc.csv"
    np.savetxt(p, hm.z * 1e6, delimiter=",", fmt="%.6f")
    return p


def run_json(capsys, argv):
    code = main(argv)
    out = capsys.readouterr().out
    assert code == 0, out
    return json.loads(out.strip().splitlines()[-1])


def test_surface_json_has_the_main_keys(tmp_path, csv_map, capsys):
    d = run_json(capsys, ["surface", str(csv_map), "--dx", "0.781um", "--units", "um", "--json",
                          "--out", str(tmp_path / "o"), "--no-plots"])
    for k in MAIN:
        assert isinstance(d[k], float) and math.isfinite(d[k]), k
    assert d["units"]["n"] == "1/m^2" and d["units"]["beta"] == "m"
    assert 0.15e-6 < d["Rq"] < 0.25e-6
    assert d["nan_policy"] == "exclude" and d["processing"] == ["plane (tilt) removed"]
    assert (tmp_path / "o" / "surface_disc.h5").is_file()
    # the saved result is itself a readable height map with its summits
    hm = read_height_map(tmp_path / "o" / "surface_disc.h5", dataset="fields/z")
    assert hm.shape == (96, 96) and hm.dx == pytest.approx(0.781e-6)


@pytest.mark.solver
def test_surface_filter_and_scene_roundtrip(tmp_path, csv_map, capsys):
    out = tmp_path / "meas.toml"
    d = run_json(capsys, ["surface", str(csv_map), "--dx", "0.781um", "--units", "um", "--filter", "until-psi",
                          "--scene", "series_D_disc3_1.93GPa", "--write-scene", str(out), "--json",
                          "--out", str(tmp_path / "o")])
    assert d["filter_study"]["reached"] and d["psi"] <= 1.0
    assert d["unfiltered"]["psi"] > d["psi"]
    sc = load_scene(out)
    assert sc.roughness.n == pytest.approx(d["n"])
    assert sc.roughness.beta == pytest.approx(d["beta"])
    assert sc.roughness.sigma_s == pytest.approx(d["sigma_s"])
    assert sc.roughness.dd == pytest.approx(d["dd"])
    assert sc.roughness.Rq == pytest.approx(d["Rq"])
    assert sc.E_reduced == d["E_reduced"] == 2.3e11  # psi used the scene's E'
    assert sc.kind == "point" and sc.roughness.fc == load_scene("series_D_disc3_1.93GPa").roughness.fc
    assert (tmp_path / "o" / "surface_disc.png").stat().st_size > 10000


def test_surface_counter_surface_combines_sigma_s(tmp_path, csv_map, capsys):
    d = run_json(capsys, ["surface", str(csv_map), "--dx", "0.781um", "--units", "um", "--json",
                          "--counter-sigma-s", "2.25e-8", "--out", str(tmp_path), "--no-plots"])
    assert d["sigma_s"] == pytest.approx(math.hypot(d["surface1"]["sigma_s"], 2.25e-8))


def test_surface_errors_exit_2(tmp_path, csv_map, capsys):
    assert main(["surface", str(csv_map), "--json", "--out", str(tmp_path)]) == 2
    assert "dx" in capsys.readouterr().err
    assert main(["surface", str(csv_map), "--dx", "1um", "--filter", "gauss", "--out", str(tmp_path)]) == 2
    assert "cut-off" in capsys.readouterr().err
    assert main(["surface", str(tmp_path / "none.csv"), "--dx", "1um", "--out", str(tmp_path)]) == 2


@pytest.mark.solver
def test_measured_surface_to_stribeck_curve_in_two_commands(tmp_path, csv_map, capsys):
    """The issue's 'done when': file -> scene (ehl surface) -> Stribeck curve (ehl stribeck)."""
    pytest.importorskip("mixed.stribeck")
    scene = tmp_path / "measured.toml"
    run_json(capsys, ["surface", str(csv_map), "--dx", "0.781um", "--units", "um", "--filter", "until-psi",
                      "--scene", "series_D_disc3_1.93GPa", "--write-scene", str(scene), "--json",
                      "--out", str(tmp_path), "--no-plots"])
    d = run_json(capsys, ["stribeck", str(scene), "--json", "--no-plots", "--out", str(tmp_path)])
    f = np.asarray(d["friction_coefficient"], dtype=float)
    assert f.size > 1 and np.all(np.isfinite(f)) and np.all((f > 0) & (f < 0.2))
