"""``ehl solve --contact line`` through the core CLI."""

import json

import pytest

from ehl_multigrid.app.cli import main


@pytest.mark.solver
def test_solve_line_json(capsys, tmp_path):
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--json", "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert rc == 0
    d = json.loads(out)
    for key in ("Hc", "Hm", "Hc_venner", "Hm_venner", "hc", "hm", "p_spike", "load_error",
                "levels", "points", "cycles", "wall_s", "converged"):
        assert key in d
    assert d["converged"] is True and d["hc"] is None
    assert 3.5 < d["Hc"] < 5.1  # Roelands + DH is below the Moes fit (5.10) at L = 10
    assert (tmp_path / "line_M20_L10.h5").is_file()
    assert (tmp_path / "line_M20_L10_zoom.png").stat().st_size > 1000


def test_solve_line_prints_the_oil_used_without_json(capsys, tmp_path):
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "513", "--accuracy", "none",
               "--out", str(tmp_path), "--no-plots"])
    assert rc == 0
    text = capsys.readouterr().out
    assert "alpha = 2.2e-08" in text and "eta0 = 0.04" in text and "p0 = 1.96e+08" in text


def test_solve_line_bad_levels_exits_2(capsys, tmp_path):
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "257", "--accuracy", "none",
               "--levels", "12", "--out", str(tmp_path)])
    assert rc == 2
    assert "levels" in capsys.readouterr().err


def test_default_solve_meets_the_default_accuracy_and_states_its_error(capsys, tmp_path):
    from ehl_multigrid.model.results import Result

    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--json", "--no-plots",
               "--out", str(tmp_path)])
    d = json.loads(capsys.readouterr().out)
    assert rc == 0 and d["status"] == "converged" and d["accuracy"] == 0.005
    assert d["Hc_error"] <= 0.005 and d["Hm_error"] <= 0.005
    assert set(d["error_budget"]) == {"grid", "domain", "iteration"}
    saved = Result.load(tmp_path / "line_M20_L10.h5")
    assert saved.scalars["Hc_error"] == d["Hc_error"]
    assert saved.meta["error_budget"] == d["error_budget"]


def test_explicit_coarse_grid_is_judged_against_the_accuracy_and_exits_3(capsys, tmp_path):
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "257",
               "--accuracy", "0.001", "--json", "--no-plots", "--out", str(tmp_path)])
    d = json.loads(capsys.readouterr().out)
    assert rc == 3 and d["status"] == "inaccurate" and d["converged"] is False
    assert d["Hc_error"] > 0.001


def test_accuracy_outside_its_range_is_a_usage_error(capsys, tmp_path):
    with pytest.raises(SystemExit) as exc:
        main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--accuracy", "2",
              "--out", str(tmp_path)])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "accuracy = 2 " in err and "[1e-05, 0.5]" in err
