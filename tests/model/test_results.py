"""HDF5 results: round trip, scene stored beside the fields, atomic writes."""

import re

import h5py
import numpy as np
import pytest

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import load_scene


def make_result() -> Result:
    r = Result("demo", scene=load_scene("appendix_d_point"))
    r.add_coord("x", np.linspace(-1, 1, 7), "m", "rolling direction")
    r.add_coord("y", np.linspace(-2, 2, 5), "m")
    r.add_field("p", np.arange(35.0).reshape(7, 5), "Pa", ("x", "y"), "pressure")
    r.set_scalar("Hc", 0.25, "-")
    r.set_scalar("converged", True)
    r.set_scalar("levels", 6)
    r.set_scalar("label", "abc")
    r.add_report(ConvergenceReport(True, "ok", 3, np.array([1.0, 0.1, 0.01]), np.array([0.1, 0.01, 1e-4]), wall_s=0.5))
    r.meta["options"] = {"cycle": "V", "levels": [1, 2]}
    return r


def test_result_round_trips_through_hdf5(tmp_path):
    r = make_result()
    path = r.save(tmp_path / "r.h5")
    back = Result.load(path)
    assert back.kind == "demo"
    np.testing.assert_array_equal(back["p"], r["p"])
    assert back.fields["p"].units == "Pa" and back.fields["p"].dims == ("x", "y")
    assert back.scalars["Hc"] == 0.25 and back.scalars["converged"] is True
    assert back.scalars["levels"] == 6 and back.scalars["label"] == "abc"
    np.testing.assert_array_equal(back.history["residual"], [1.0, 0.1, 0.01])
    assert back.meta["options"] == {"cycle": "V", "levels": [1, 2]}
    assert back.scene == r.scene


def test_hdf5_layout_has_units_and_dimension_scales(tmp_path):
    path = make_result().save(tmp_path / "r.h5")
    with h5py.File(path) as f:
        assert f["fields/p"].attrs["units"] == "Pa"
        assert f["fields/p"].dims[0][0].name == "/coords/x"
        assert "toml" in f["scene"].attrs
        assert f["scalars"].attrs["units.Hc"] == "-"


def test_failed_write_leaves_no_partial_file(tmp_path):
    r = make_result()
    r.scalars["bad"] = object()  # cannot be stored
    target = tmp_path / "r.h5"
    with pytest.raises(InputError, match="bad"):
        r.save(target)
    assert list(tmp_path.iterdir()) == []


def test_failed_write_keeps_the_previous_file(tmp_path):
    target = make_result().save(tmp_path / "r.h5")
    r = make_result()
    r.scalars["bad"] = object()
    with pytest.raises(InputError):
        r.save(target)
    assert Result.load(target).scalars["Hc"] == 0.25


def test_field_dims_are_checked_against_coordinates():
    r = Result("demo")
    r.add_coord("x", np.zeros(4))
    with pytest.raises(InputError, match=r"'p'.* 3 points.*'x' has 4"):
        r.add_field("p", np.zeros(3), "Pa", ("x",))
    with pytest.raises(InputError, match=r"'p'.*coordinate 'z'"):
        r.add_field("p", np.zeros(4), "Pa", ("z",))


def test_loading_a_foreign_file_is_refused(tmp_path):
    f = tmp_path / "other.h5"
    with h5py.File(f, "w") as h:
        h.attrs["x"] = 1
    with pytest.raises(InputError, match=re.escape(str(f)) + ".*ehl-multigrid"):
        Result.load(f)


def test_several_results_round_trip_in_one_file(tmp_path):
    from ehl_multigrid.model.results import load_results, save_results

    a, b = make_result(), make_result()
    b.kind = "other"
    b.scalars["Hc"] = 0.5
    path = save_results(tmp_path / "run.h5", {"film": a, "traction": b}, meta={"plan": {"film": "fit"}})
    back = load_results(path)
    assert set(back) == {"film", "traction"}
    assert back["traction"].kind == "other" and back["traction"].scalars["Hc"] == 0.5
    np.testing.assert_array_equal(back["film"]["p"], a["p"])
    assert Result.load(path, group="film").scene == a.scene
    with pytest.raises(InputError, match=r"'stribeck'.*\['film', 'traction'\]"):
        Result.load(path, group="stribeck")


def test_a_partial_run_file_is_written_uncompressed_and_the_final_one_compressed(tmp_path):
    from ehl_multigrid.model.results import load_results, save_results

    r = make_result()
    r.add_coord("x", np.linspace(-1, 1, 101), "m")
    r.add_coord("y", np.linspace(-1, 1, 81), "m")
    r.fields.pop("p")
    r.add_field("p", np.outer(np.linspace(0, 1, 101), np.linspace(1, 2, 81)), "Pa", ("x", "y"))
    for compress, filters in ((False, (None, False)), (True, ("gzip", True))):
        path = save_results(tmp_path / f"run_{compress}.h5", {"film": r}, compress=compress)
        with h5py.File(path) as f:
            ds = f["film/fields/p"]
            assert (ds.compression, ds.shuffle) == filters
        np.testing.assert_array_equal(load_results(path)["film"]["p"], r["p"])


def test_loading_a_transient_run_file_names_its_reader(tmp_path):
    path = tmp_path / "run.h5"
    with h5py.File(path, "w") as f:  # the layout `ehl transient` writes
        f.create_group("series")
        f.create_group("steady")
    with pytest.raises(InputError, match="ehl transient.*load_series"):
        Result.load(path)
