"""``ehl solve --contact point|elliptic`` through ehl_multigrid.app.cli.main."""

import json

import h5py
import pytest

import ehl_multigrid.point.solve as point_solve
from ehl_multigrid.app.cli import main
from ehl_multigrid.model.results import Result

KEYS = {"Hc", "Hm", "Hc_venner", "Hm_venner", "hc", "hm", "p_spike", "load_error", "levels",
        "points", "cycles", "wall_s", "converged"}


@pytest.fixture
def no_domain_probe(monkeypatch):
    """The solve's domain probes skipped: under ``--accuracy none`` they only add to the reported
    estimate, which the tests that take this do not read (the films, the iteration's verdict and
    the files are the same; 0.5 of a 65-point elliptic command's 0.8-1.2 s)."""
    monkeypatch.setattr(point_solve, "point_domain_change", lambda *a, **k: None)


def test_cli_json_moes_only(tmp_path, capsys):
    rc = main(["solve", "--contact", "point", "--M", "20", "--L", "10", "--points", "65", "--accuracy", "none",
               "--json", "--out", str(tmp_path), "--no-plots"])
    out = capsys.readouterr().out
    assert rc == 0
    payload = json.loads(out.strip().splitlines()[-1])
    assert KEYS <= set(payload)
    assert payload["converged"] is True
    assert payload["hc"] is None and payload["hm"] is None
    res = Result.load(payload["hdf5"])
    assert res.kind == "ehl_point"
    assert res["P"].shape == (65, 65) and res.fields["P"].dims == ("X", "Y")
    with h5py.File(payload["hdf5"]) as f:
        assert "residual" in f["history"]


@pytest.mark.solver
def test_cli_prints_the_oil_used_in_moes_only_mode(tmp_path, capsys, no_domain_probe):
    # 65 points: the printed oil and the figures do not depend on the grid (half the cost of 129)
    rc = main(["solve", "--contact", "elliptic", "--ellipticity", "4", "--M", "20", "--L", "5",
               "--points", "65", "--accuracy", "none", "--out", str(tmp_path), "--alpha", "1.5e-8"])
    out = capsys.readouterr().out
    assert rc == 0
    assert "alpha = 1.5e-08" in out and "eta0 = 0.04" in out and "p0 = 1.96e+08" in out
    assert list(tmp_path.glob("*_maps.png")) and list(tmp_path.glob("*_interference.png"))


@pytest.mark.solver
def test_cli_scene_gives_physical_films(tmp_path, capsys, no_domain_probe):
    # 65 points: a scene's films in metres and its fields' units do not depend on the grid
    rc = main(["solve", "appendix_d_point", "--points", "65", "--accuracy", "none", "--json", "--no-plots",
               "--out", str(tmp_path)])
    payload = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert rc == 0
    assert payload["hc"] > 0 and payload["hm"] > 0
    res = Result.load(payload["hdf5"])
    assert res.fields["h"].units == "m" and res.fields["p"].units == "Pa"


def test_cli_error_paths(tmp_path, capsys):
    assert main(["solve", "--contact", "elliptic", "--M", "20", "--L", "10", "--out", str(tmp_path)]) == 2
    assert "ellipticity" in capsys.readouterr().err
    assert main(["solve", "--contact", "point", "--M", "20", "--L", "10", "--points", "100",
                 "--out", str(tmp_path)]) == 2
    assert "points" in capsys.readouterr().err
    assert main(["solve", "appendix_d_point", "--alpha", "2e-8", "--out", str(tmp_path)]) == 2
