"""Bad input to the layers' subcommands (traction, stribeck, surface) ends in exit 2 with one
line naming the field, before any long computation; huge sizes are refused, not run."""

import json
import time

import h5py
import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.errors import InputError
from mixed.surface.analysis import analyse_surface
from mixed.surface.heightmap import HeightMap


def _exit(argv):
    try:
        return main(argv)
    except SystemExit as exc:  # argparse usage errors
        return exc.code


def _check(capsys, argv, field, limit_s=30.0):
    t0 = time.perf_counter()
    assert _exit(argv) == 2
    assert time.perf_counter() - t0 < limit_s  # refused, not run
    err = capsys.readouterr().err
    assert field in err and "Traceback" not in err
    assert len([ln for ln in err.splitlines() if "error" in ln]) == 1


@pytest.mark.parametrize("flags, field", [
    (["--slip", "0.1", "--nx", "100000"], "nx = 100000"),
    (["--slip", "0.1", "--nz", "10000"], "nz = 10000"),
    (["--slip", "0:1:100000"], "n = 100000"),
    (["--slip", "5"], "--slip value 5"),
    (["--slip", "nan"], "--slip value nan"),
    (["--input", "ehl"], "--ehl-file"),
])
def test_traction_refuses_bad_flags(flags, field, tmp_path, capsys):
    _check(capsys, ["traction", "appendix_c_line_42400N", "--no-plots", "--out", str(tmp_path), *flags], field)


def test_traction_refuses_files_that_are_not_ehl_results(tmp_path, capsys):
    text = tmp_path / "notes.h5"
    text.write_text("this is not HDF5")
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as f:
        f.create_dataset("x", data=np.arange(3.0))
    base = ["traction", "appendix_c_line_42400N", "--no-plots", "--out", str(tmp_path / "o"), "--input", "ehl"]
    _check(capsys, base + ["--ehl-file", str(text)], "is not an HDF5 file")
    _check(capsys, base + ["--ehl-file", str(foreign)], "is not an ehl-multigrid result file")
    _check(capsys, base + ["--ehl-file", str(tmp_path / "missing.h5")], "does not exist")


@pytest.mark.parametrize("flags, field", [
    (["--n", "0"], "--n = 0"),
    (["--n", "100000000"], "--n = 100000000"),
    (["--thermal", "--n", "20000"], "20000 thermal solves"),
    (["--hoil=-1"], "--hoil value -1"),
])
def test_stribeck_refuses_bad_flags(flags, field, tmp_path, capsys):
    _check(capsys, ["stribeck", "page63_line_500N", "--no-plots", "--out", str(tmp_path), *flags], field)


@pytest.fixture
def rough_csv(tmp_path):
    path = tmp_path / "map.csv"
    np.savetxt(path, np.random.default_rng(3).normal(0.0, 1e-7, (32, 32)), delimiter=",")
    return path


@pytest.mark.parametrize("flags, field", [
    (["--dataset", "z"], "--dataset applies to HDF5"),
    (["--level", "form", "--form-order=-1"], "--form-order = -1"),
    (["--scene", "default", "--write-scene", "{dir}"], "--write-scene"),
    (["--out", "{dir}/map.csv"], "--out"),
])
def test_surface_refuses_bad_flags(flags, field, rough_csv, capsys):
    flags = [f.replace("{dir}", str(rough_csv.parent)) for f in flags]
    _check(capsys, ["surface", str(rough_csv), "--dx", "1um", "--no-plots",
                    *(["--out", str(rough_csv.parent / "o")] if "--out" not in flags else []), *flags], field)


def test_a_constant_height_map_is_refused_not_given_round_off_roughness(tmp_path, capsys):
    flat = tmp_path / "flat.csv"
    np.savetxt(flat, np.full((32, 32), 1.5e-6), delimiter=",")
    _check(capsys, ["surface", str(flat), "--dx", "1um", "--no-plots", "--out", str(tmp_path / "o")], "is flat")
    # a tilted plane is as flat once levelled
    x = np.arange(32) * 1e-6
    with pytest.raises(InputError, match=r"flat\b.*\bplane\b.*Rq = \S+ m"):
        analyse_surface(HeightMap(z=1e-3 * x[None, :] + 2e-3 * x[:, None], dx=1e-6, dy=1e-6))


def test_a_smooth_but_real_surface_is_still_analysed():
    # Rq 1 nm under 10 um of tilt: five orders above the flatness threshold
    rng = np.random.default_rng(0)
    x = np.arange(64) * 1e-6
    z = 1e-5 * x[None, :] / x[-1] + rng.normal(0.0, 1e-9, (64, 64))
    an = analyse_surface(HeightMap(z=z, dx=1e-6, dy=1e-6))
    assert an.stats.Rq == pytest.approx(1e-9, rel=0.1)


def test_traction_reads_the_film_stage_film_of_an_ehl_run_file(tmp_path, capsys):
    # the same friction as on that film saved alone (what 'ehl solve' writes)
    from ehl_multigrid.model.results import Result

    run = tmp_path / "run"
    assert _exit(["run", "page63_line_500N", "--no-plots", "--out", str(run)]) == 0
    h5 = run / "page63_line_500N.h5"
    alone = tmp_path / "film.h5"
    Result.load(h5, group="film").save(alone)
    frictions = []
    for path in (h5, alone):
        capsys.readouterr()
        assert _exit(["traction", "page63_line_500N", "--no-plots", "--json", "--out", str(tmp_path / "t"),
                      "--input", "ehl", "--ehl-file", str(path), "--slip", "0.05"]) == 0
        frictions.append(json.loads(capsys.readouterr().out)["friction_coefficient"])
    assert frictions[0] == frictions[1] and frictions[0][0] > 0.0


def test_traction_refuses_an_ehl_run_file_without_a_film_stage_result(tmp_path, capsys):
    from ehl_multigrid.model.results import Result, save_results

    path = tmp_path / "run.h5"
    save_results(path, {"traction": Result(kind="traction")})
    _check(capsys, ["traction", "appendix_c_line_42400N", "--no-plots", "--out", str(tmp_path / "o"), "--input", "ehl",
                    "--ehl-file", str(path)], "without a film stage result")
