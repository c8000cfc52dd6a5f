"""One exit-code convention for every ``ehl`` subcommand (0 ok, 2 bad input, 3 not converged or
short of its accuracy, 1 internal error), bad flags refused with one line naming them, the
fit's extrapolation warned about, and ``ehl solve --csv``."""

import csv
import json
import math
import re
from pathlib import Path

import pytest

from ehl_multigrid.app.cli import main, not_converged
from ehl_multigrid.model import fits


def _err(capsys):
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return err


@pytest.mark.parametrize("payload, verdict", [
    ({"converged": True, "status": "converged"}, None),
    ({"converged": False, "message": "max cycles"}, "max cycles"),
    ({"status": "inaccurate", "message": "error 0.09 > 0.005"}, "status inaccurate: error 0.09 > 0.005"),
    ({"film": {"converged": True}, "traction": {"converged": False}}, "stage traction: converged = false"),
    ({"cases": 3, "counts": {"ok": 3}}, None),
])
def test_payloads_that_did_not_converge_are_recognised(payload, verdict):
    assert not_converged(payload) == verdict


def test_solve_exits_3_when_the_result_is_not_a_success_and_still_writes_it(tmp_path, capsys):
    # an explicit coarse grid judged against the default accuracy target: status 'inaccurate'
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "129", "--no-plots",
               "--out", str(tmp_path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["status"] != "converged"
    assert (tmp_path / "line_M20_L10.h5").exists()


def test_solve_with_a_failed_start_exits_3_without_a_traceback_or_a_file(tmp_path, capsys):
    # line (5000, 0) on 129 points: no positive film on the start grid, nor at M = 2500, 1250
    # and 625 (the continuation in M); the fields are the initial guess, so nothing is written
    # or plotted (plotting them divided by Hc = 0 before). On its default grid (5000, 0) now
    # converges by continuation (tests/line/test_line_continuation.py).
    rc = main(["solve", "--contact", "line", "--M", "5000", "--L", "0", "--points", "129",
               "--out", str(tmp_path)])
    err = _err(capsys)
    # the message names the film, the grid it failed on and the contact
    assert rc == 3 and all(s in err for s in ("film", "positive", "129-point", "M = 5000"))
    assert not list(tmp_path.iterdir())


def test_json_failures_still_print_one_object_on_stdout(tmp_path, capsys):
    # a script reading --json output gets an object with the exit code and the reason, for
    # bad input (2) and a computation that raised (3) alike
    rc = main(["solve", "--contact", "point", "--M", "-5", "--L", "10", "--json", "--no-plots",
               "--out", str(tmp_path)])
    out = json.loads(capsys.readouterr().out)
    assert rc == 2 and out["exit_code"] == 2 and out["error"] == "input" and "M = -5" in out["message"]
    rc = main(["solve", "--contact", "line", "--M", "5000", "--L", "0", "--points", "129", "--json",
               "--out", str(tmp_path)])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["exit_code"] == 3 and not out["converged"] and "positive" in out["message"]


def test_a_diverged_point_solve_writes_no_film_and_exits_3(tmp_path, capsys):
    # the default ball at 0.0428 N (a load given in kN as N): diverged on the second grid; its
    # iterate (H = 0) was written as a film with Hc = 0 in --json
    path = tmp_path / "light.toml"
    text = (Path(__file__).parents[2] / "ehl_multigrid" / "scenes" / "default.toml").read_text()
    path.write_text(re.sub(r"(?m)^load = .*$", "load = 0.0428", text))
    out_dir = tmp_path / "out"
    rc = main(["solve", str(path), "--json", "--no-plots", "--out", str(out_dir)])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["error"] == "convergence" and "diverged" in out["message"]
    assert "Hc" not in out and not (out_dir.exists() and list(out_dir.iterdir()))


def test_a_solve_stopped_by_its_time_budget_before_any_film_writes_nothing(tmp_path, capsys):
    # (5000, 0) continues in M: 0.3 s run out in its first start's Newton solve, whose iterate
    # (the start guess, Hc = Hm = 0) the front door gave as films of 0
    import ehl_multigrid as ehl
    from ehl_multigrid.solution import MoesProblem

    sol = ehl.solve(MoesProblem("line", 5000, 0), accuracy=0.005, options={"time_budget": 0.3})
    assert sol.status.label == "time_budget" and not sol.fields and math.isnan(sol.Hc)
    rc = main(["solve", "--contact", "line", "--M", "5000", "--L", "0", "--time-budget", "0.3", "--json",
               "--no-plots", "--out", str(tmp_path / "o")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and "time budget" in out["message"] and not (tmp_path / "o").exists()


@pytest.mark.parametrize("flags, field", [
    (["--threads", "0"], "--threads"),
    (["--threads", "1000"], "--threads"),
    (["--points", "100"], "points"),
    (["--levels", "0"], "levels"),
    (["--max-points", "5"], "max-points = 5 is not a grid size"),  # (refused by the argument parser)
])
def test_solve_refuses_bad_flags_with_exit_2(flags, field, tmp_path, capsys):
    try:
        rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--no-plots", "--out", str(tmp_path),
                   *flags])
    except SystemExit as stop:
        rc = stop.code
    assert rc == 2
    assert field in _err(capsys)


def test_max_points_caps_the_refinement_and_the_message_names_the_grid_needed(tmp_path, capsys):
    # (20, 10) line at 0.1 %: 1025 points are predicted to fall short; capped at 513 the result
    # is the most accurate solve within the cap and says how many points would meet the target
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--accuracy", "0.001",
               "--max-points", "513", "--no-plots", "--out", str(tmp_path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["status"] == "inaccurate"
    # names the cap and the number of points predicted to meet the target (more than the cap)
    assert "max_points = 513" in out["message"]
    needed = [int(n) for n in re.findall(r"\b(\d+) points\b", out["message"])]
    assert max(needed, default=0) > 513, out["message"]


def test_a_time_budget_stops_the_refinement_and_the_message_says_so(tmp_path, capsys):
    # the same (20, 10) line at 0.1 %, with no time to refine: the first solve comes back,
    # marked inaccurate, and says which refinement the budget left out
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--accuracy", "0.001",
               "--time-budget", "0", "--no-plots", "--out", str(tmp_path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["status"] == "inaccurate"
    assert re.search(r"time budget\b.* 0 s\b", out["message"]), out["message"]


def test_a_negative_time_budget_is_refused_by_the_parser(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--time-budget", "-1",
              "--out", str(tmp_path)])
    assert exit_.value.code == 2
    err = _err(capsys)
    assert "time-budget = -1 s" in err and "[0, inf)" in err


def test_solve_into_a_file_is_refused_before_solving(tmp_path, capsys):
    (tmp_path / "afile").write_text("x")
    assert main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--out", str(tmp_path / "afile")]) == 2
    assert "--out" in _err(capsys)


def test_solve_csv_writes_the_centre_line_profiles(tmp_path, capsys):
    rc = main(["solve", "appendix_d_point", "--points", "65", "--accuracy", "none", "--csv", "--no-plots",
               "--out", str(tmp_path), "--json"])
    payload = json.loads(capsys.readouterr().out)
    assert rc in (0, 3) and len(payload["csv"]) == 2
    with open(tmp_path / "appendix_d_point_profile_x.csv") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == ["X", "P", "H", "x_m", "p_Pa", "h_m"] and len(rows) == 65
    # the SI columns are the dimensionless ones times one scale each (pmax, a, a^2/Rx)
    loaded = [r for r in rows if float(r["P"]) > 1e-3 and abs(float(r["X"])) > 1e-3]
    for num, den in (("p_Pa", "P"), ("x_m", "X"), ("h_m", "H")):
        ratios = [float(r[num]) / float(r[den]) for r in loaded]
        assert max(ratios) == pytest.approx(min(ratios), rel=1e-8)


def test_fits_warns_when_extrapolating_and_not_inside_the_checked_range(capsys):
    assert main(["fits", "--contact", "point", "--M", "1e9", "--L", "10", "--json"]) == 0
    captured = capsys.readouterr()
    assert "extrapolated" in captured.err and "M = 1e+09 outside [5, 1000]" in captured.err
    assert json.loads(captured.out)["extrapolated"] is True
    assert main(["fits", "--contact", "point", "--M", "20", "--L", "10", "--json"]) == 0
    captured = capsys.readouterr()
    assert "warning" not in captured.err and json.loads(captured.out)["extrapolated"] is False


def test_fits_warns_that_the_fit_under_predicts_contacts_long_in_the_rolling_direction(capsys):
    assert main(["fits", "--contact", "point", "--M", "20", "--L", "10", "--ellipticity", "4", "--json"]) == 0
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert out["extrapolated"] is False and "theta = 4 > 1" in out["warning"]
    # the warning gives the measured bias of the solver's film against the fit, in per cent
    assert re.search(r"\d+%-\d+%.*Nijenbanning", captured.err), captured.err
    assert fits.deviation_note("point", 0.25) is None and fits.deviation_note("line", 4.0) is None


def test_checked_range_is_the_fit_check_tables():
    line = fits.checked_range("line")
    assert line["M"] == (2.0, 2000.0) and line["L"] == (0.0, 20.0)
    assert fits.extrapolation_note("line", 20.0, 10.0) is None
    assert "L = 1e+04" in fits.extrapolation_note("line", 20.0, 1e4)
    assert "theta = 0.01" in fits.extrapolation_note("point", 20.0, 10.0, 0.01)


@pytest.mark.parametrize("argv, field", [
    (["fits", "--contact", "elliptic", "--M", "20", "--L", "10", "--ellipticity", "0"], "--ellipticity"),
    (["fits", "--contact", "point", "--M", "nan", "--L", "10"], "--M"),
    (["fits", "--contact", "point", "--M", "inf", "--L", "10"], "--M"),
    (["fits", "--contact", "point", "--M", "20", "--L", "10", "--gamma1", "0.5"], "--gamma1"),
    (["plan", "default", "--tolerance", "nan"], "tolerance"),
    (["plan", "default", "--tolerance", "tight"], "--tolerance"),
])
def test_bad_numbers_exit_2_naming_the_flag(argv, field, capsys):
    try:
        rc = main(argv)
    except SystemExit as exc:  # argparse's own usage errors
        rc = exc.code
    assert rc == 2
    assert field in _err(capsys)


@pytest.mark.solver
def test_run_takes_a_time_budget_for_its_film_solve_and_reports_why_it_stopped(tmp_path, capsys):
    # the Appendix C line contact at 0.1 %: the first solve misses the target, and with no time
    # to refine the film stage says so in its summary and the report
    rc = main(["run", "appendix_c_line_4240N", "--tolerance", "0.001", "--time-budget", "0", "--no-plots",
               "--out", str(tmp_path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["film"]["converged"] is False
    assert re.search(r"time budget\b.* 0 s\b", out["film"]["not_refined_because"])
    report = (tmp_path / "appendix_c_line_4240N_report.md").read_text()
    assert re.search(r"time budget\b.* 0 s\b", report)
