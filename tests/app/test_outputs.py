"""Outputs that are never stale, partial without saying so, lost, or written outside --out:
the main job's output set, completeness marks, safe names, writable folders, file modes."""

import json
import os
import stat

import h5py
import pytest

import ehl_multigrid.app.mainjob as mainjob
from ehl_multigrid.app.cli import main
from ehl_multigrid.app.mainjob import MainJobOptions, run_main_job
from ehl_multigrid.app.stages import StageOutput
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.paths import output_file, safe_stem, writable_dir
from ehl_multigrid.model.results import Result, is_complete, load_results
from ehl_multigrid.model.scene import Scene, load_scene


def _fake_stage(name, figure=None):
    def stage(ctx):
        figures = []
        if figure is not None:
            p = ctx.outdir / f"{figure}_{ctx.scene.name}.png"
            p.write_bytes(b"png")
            figures.append(p)
        res = Result(name)
        res.set_scalar("x", 1.0)
        return StageOutput(name, res, {"converged": True}, figures, f"stage {name}")

    return stage


@pytest.fixture
def only_film(monkeypatch):
    """The main job with the core film stage and the test's own stages (no thermal/mixed)."""
    stages = []
    monkeypatch.setattr(mainjob, "registered_stages", lambda: list(stages))
    return stages


def test_finished_run_is_marked_complete_and_files_have_the_users_mode(tmp_path, only_film):
    only_film.append(("extra", _fake_stage("extra")))
    old = os.umask(0o022)
    try:
        out = run_main_job(load_scene("appendix_c_line_4240N"), MainJobOptions(out_dir=tmp_path, tolerance=0.5,
                                                                                plots=False, quiet=True))
    finally:
        os.umask(old)
    assert is_complete(out["hdf5"])
    with h5py.File(out["hdf5"]) as f:
        assert json.loads(f.attrs["planned"]) == ["film", "extra"]
    for name in (out["hdf5"], out["report"]):
        assert stat.S_IMODE(os.stat(name).st_mode) == 0o644  # not mkstemp's 0600


def test_interrupted_run_keeps_finished_stages_marked_incomplete(tmp_path, only_film):
    def interrupted(ctx):
        raise KeyboardInterrupt

    only_film += [("extra", _fake_stage("extra")), ("later", interrupted), ("never", _fake_stage("never"))]
    with pytest.raises(KeyboardInterrupt):
        run_main_job(load_scene("appendix_c_line_4240N"), MainJobOptions(out_dir=tmp_path, tolerance=0.5,
                                                                          plots=False, quiet=True))
    h5 = tmp_path / "appendix_c_line_4240N.h5"
    assert set(load_results(h5)) == {"film", "extra"}
    assert not is_complete(h5)
    report = (tmp_path / "appendix_c_line_4240N_report.md").read_text()
    assert "Incomplete run" in report and "later, never" in report
    assert not [p for p in tmp_path.iterdir() if p.is_dir()]  # no staging folder left behind


def test_rerun_removes_the_previous_runs_files_it_does_not_replace(tmp_path, only_film):
    scene = load_scene("appendix_c_line_4240N")
    only_film.append(("extra", _fake_stage("extra", figure="old_figure")))
    run_main_job(scene, MainJobOptions(out_dir=tmp_path, tolerance=0.5, plots=False, quiet=True))
    assert (tmp_path / "old_figure_appendix_c_line_4240N.png").exists()
    only_film[:] = [("extra", _fake_stage("extra"))]  # the new run draws no such figure
    run_main_job(scene, MainJobOptions(out_dir=tmp_path, tolerance=0.5, plots=False, quiet=True))
    assert not (tmp_path / "old_figure_appendix_c_line_4240N.png").exists()
    assert (tmp_path / "appendix_c_line_4240N.h5").exists()


def test_legacy_single_report_of_the_same_scene_is_removed(tmp_path, only_film):
    (tmp_path / "report.md").write_text("# appendix_c_line_4240N\nold report\n")
    run_main_job(load_scene("appendix_c_line_4240N"), MainJobOptions(out_dir=tmp_path, tolerance=0.5, plots=False,
                                                                      quiet=True))
    assert not (tmp_path / "report.md").exists()


def test_two_scenes_in_one_folder_keep_their_own_reports(tmp_path, only_film):
    only_film.append(("extra", _fake_stage("extra", figure="fig")))
    for name in ("appendix_c_line_4240N", "appendix_c_line_42400N"):
        run_main_job(load_scene(name), MainJobOptions(out_dir=tmp_path, tolerance=0.5, plots=False, quiet=True))
    names = {p.name for p in tmp_path.iterdir()}
    for name in ("appendix_c_line_4240N", "appendix_c_line_42400N"):
        assert {f"{name}.h5", f"{name}_report.md", f"fig_{name}.png"} <= names
        assert (tmp_path / f"{name}_report.md").read_text().startswith(f"# {name}\n")


@pytest.mark.parametrize("name", ["/abs/escaped", "../../escaped", "a/b/../../../c", "..", "", "x" * 400,
                                  "nul\x00byte", "two\nlines"])
def test_scene_names_never_write_outside_the_output_folder(tmp_path, only_film, name):
    only_film.append(("extra", _fake_stage("extra", figure="fig")))
    d = load_scene("appendix_c_line_4240N").to_dict()
    d["name"] = name
    scene = Scene.from_dict(d)
    out = tmp_path / "deep" / "out"
    payload = run_main_job(scene, MainJobOptions(out_dir=out, tolerance=0.5, plots=False, quiet=True))
    written = [p for p in tmp_path.rglob("*") if p.is_file()]
    assert written and all(out in p.parents and p.parent == out for p in written)
    assert all(len(p.name) < 200 for p in written)
    assert os.path.dirname(payload["hdf5"]) == str(out)


def test_safe_stem_keeps_ordinary_names_and_tames_the_rest():
    assert safe_stem("series_A_disc1_0.78GPa") == "series_A_disc1_0.78GPa"
    assert safe_stem("../../etc/passwd") == "etc_passwd"
    assert safe_stem("/abs/path") == "abs_path"
    assert safe_stem("..") == "scene" and safe_stem("") == "scene"
    long_a, long_b = safe_stem("x" * 300 + "a"), safe_stem("x" * 300 + "b")
    assert len(long_a) <= 120 and long_a != long_b
    assert output_file("/tmp/o", "../x", ".h5").parent.name == "o"


def test_output_folder_that_is_a_file_is_refused_before_any_work(tmp_path, only_film, monkeypatch, capsys):
    def no_solve(ctx):
        raise AssertionError("the film was computed before the output folder was checked")

    monkeypatch.setattr(mainjob, "film_stage", no_solve)
    (tmp_path / "afile").write_text("x")
    for out in (tmp_path / "afile", tmp_path / "afile" / "sub"):
        assert main(["run", "appendix_c_line_4240N", "--tolerance", "0.5", "--out", str(out)]) == 2
        err = capsys.readouterr().err
        assert "--out" in err and str(out) in err and "Traceback" not in err


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs a read-only /proc")
def test_output_folder_on_a_read_only_file_system_is_a_clear_error():
    with pytest.raises(InputError, match="--out '/proc/ehl_test_out'.*writable"):
        writable_dir("/proc/ehl_test_out")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_output_folder_is_a_clear_error(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        with pytest.raises(InputError, match=f"--out.*{ro.name}.*writable"):
            writable_dir(ro)
    finally:
        ro.chmod(0o755)


def test_single_results_carry_the_completeness_attribute(tmp_path):
    r = Result("demo")
    r.set_scalar("x", 1.0)
    assert is_complete(r.save(tmp_path / "done.h5")) and Result.load(tmp_path / "done.h5").complete
    r.meta["partial"] = True  # how a curve's part-way saves mark themselves
    assert not is_complete(r.save(tmp_path / "part.h5"))
    assert Result.load(tmp_path / "part.h5").complete is False


def test_interrupted_stribeck_curve_keeps_its_finished_curves_marked_incomplete(tmp_path, monkeypatch, capsys):
    import mixed.stribeck as stribeck

    real = stribeck.stribeck_curve
    calls = []

    def interrupt_second(*args, **kwargs):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(stribeck, "stribeck_curve", interrupt_second)
    rc = main(["stribeck", "chapter6_starved_0.5GPa", "--n", "5", "--hoil", "1,2", "--no-plots", "--out", str(tmp_path)])
    assert rc == 130
    h5 = next(tmp_path.glob("*.h5"))
    assert not is_complete(h5)


@pytest.mark.solver
@pytest.mark.parametrize("command", [
    ["solve", "{scene}", "--points", "65", "--accuracy", "none", "--csv"],
    ["traction", "{scene}", "--slip", "0.1", "--nx", "16", "--nz", "4"],
    ["stribeck", "{scene}", "--n", "4"],
])
def test_every_writing_command_keeps_a_hostile_scene_name_inside_out(command, tmp_path, capsys):
    d = load_scene("page63_line_500N").to_dict()
    d["name"] = "../../escaped"
    scene_file = tmp_path / "hostile.toml"
    scene_file.write_text(Scene.from_dict(d).to_toml())
    out = tmp_path / "a" / "b" / "out"
    argv = [a.replace("{scene}", str(scene_file)) for a in command] + ["--out", str(out), "--json"]
    assert main(argv) in (0, 3)
    capsys.readouterr()
    written = [p for p in tmp_path.rglob("*") if p.is_file() and p != scene_file]
    assert written and all(p.parent == out for p in written), written


@pytest.mark.solver
def test_a_new_result_leaves_no_figure_of_the_previous_run_beside_it(tmp_path, capsys):
    """``ehl solve --out o`` with plots, then again with ``--no-plots``: the earlier figures
    of that result are gone (two runs, as a user runs them; what the first run wrote is known
    to the second only through the folder); files the runs did not write stay, even when their
    names start with the result's."""
    out = tmp_path / "o"
    out.mkdir()
    other = out / "point_M20_L10_th1_tehl.h5"
    other.write_bytes(b"")
    keep = [out / "point_M20_L10_th1_tehl_maps.png", out / "notes.png"]
    for p in keep:
        p.write_bytes(b"png")
    argv = ["solve", "--contact", "point", "--M", "20", "--L", "10", "--points", "65", "--accuracy", "none",
            "--out", str(out)]
    assert main(argv) == 0, capsys.readouterr().err
    figures = sorted(p.name for p in out.glob("point_M20_L10_th1_*.png") if "tehl" not in p.name)
    assert figures  # the first run wrote its figures
    assert main([*argv, "--no-plots"]) == 0, capsys.readouterr().err
    assert not [p.name for p in out.glob("point_M20_L10_th1_*.png") if "tehl" not in p.name]
    assert all(p.exists() for p in keep) and (out / "point_M20_L10_th1.h5").exists()


def test_only_files_a_run_recorded_are_ever_deleted(tmp_path):
    """A user's own file named like a result's figure stays; the previous run's figure that
    this run did not rewrite goes; the manifest holds this run's set."""
    from ehl_multigrid.model.paths import record_outputs

    for name in ("r.h5", "r_maps.png", "r_profiles.png", "r_my_annotated.png"):
        (tmp_path / name).write_bytes(b"x")
    record_outputs(tmp_path, "r", [tmp_path / "r.h5", tmp_path / "r_maps.png", tmp_path / "r_profiles.png"])
    removed = record_outputs(tmp_path, "r", [tmp_path / "r.h5", tmp_path / "r_profiles.png"])
    assert [p.name for p in removed] == ["r_maps.png"]
    assert sorted(p.name for p in tmp_path.iterdir() if not p.name.startswith(".")) == [
        "r.h5", "r_my_annotated.png", "r_profiles.png"]
    manifest = json.loads((tmp_path / ".ehl-files-r.json").read_text())
    assert manifest["files"] == ["r.h5", "r_profiles.png"]


@pytest.mark.parametrize("contact", ["line", "point"])
def test_ehl_solve_names_its_result_hdf5_and_its_figures_plots_for_every_contact(contact, tmp_path, capsys):
    main(["solve", "--contact", contact, "--M", "20", "--L", "10", "--points", "129" if contact == "line" else "33",
          "--accuracy", "none", "--json", "--out", str(tmp_path)])
    payload = json.loads(capsys.readouterr().out)
    assert is_complete(payload["hdf5"]) and os.path.dirname(payload["hdf5"]) == str(tmp_path)
    assert payload["plots"] and all(os.path.isfile(p) for p in payload["plots"])
    assert not {"file", "png"} & set(payload)


def test_a_refused_command_leaves_no_output_folder_it_created(tmp_path):
    new, kept = tmp_path / "new", tmp_path / "kept"
    kept.mkdir()
    for out in (new, kept):
        assert main(["traction", "appendix_c_line_4240N", "--accuracy", "0.005", "--out", str(out)]) == 2
    assert not new.exists()
    assert kept.is_dir() and not any(kept.iterdir())
