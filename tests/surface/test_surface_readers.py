"""Every reader on a small file written by the test, and the error paths."""

from __future__ import annotations

import h5py
import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from mixed.surface import make_height_map, parse_length, read_height_map

Z_UM = np.array([[0.1, 0.2, 0.3, 0.2], [0.0, -0.1, 0.4, 0.1], [0.3, 0.2, -0.2, 0.0]])


def check(hm, dx=0.5e-6, dy=0.5e-6, atol=0.0):
    np.testing.assert_allclose(hm.z, Z_UM * 1e-6, rtol=1e-12, atol=atol, equal_nan=True)
    assert hm.dx == pytest.approx(dx) and hm.dy == pytest.approx(dy)


def test_csv_matrix_with_header_spacing_and_units(tmp_path):
    p = tmp_path / "m.csv"
    p.write_text("# units = um\n# dx: 0.5 um\n" + "\n".join(",".join(f"{v:g}" for v in r) for r in Z_UM))
    check(read_height_map(p))


def test_whitespace_matrix_with_user_spacing(tmp_path):
    p = tmp_path / "m.txt"
    np.savetxt(p, Z_UM)
    check(read_height_map(p, dx="0.5um", units="um"))
    check(read_height_map(p, dx=0.5, dy=1.0, units="um", xy_units="um"), dy=1e-6)
    check(read_height_map(p, dx=5e-7, units="um"))


def test_csv_with_missing_values(tmp_path):
    p = tmp_path / "m.csv"
    p.write_text("0.1,0.2,0.3,0.2\n0.0,,0.4,0.1\n0.3,nan,-0.2,0.0\n")
    hm = read_height_map(p, dx="0.5um", units="um")
    assert hm.n_missing == 2 and np.isnan(hm.z[1, 1]) and np.isnan(hm.z[2, 1])


def test_xyz_columns_any_order_with_a_missing_point(tmp_path):
    rows = [(j * 0.5, i * 0.5, Z_UM[i, j]) for i in range(3) for j in range(4) if (i, j) != (1, 2)]
    rows = [rows[k] for k in np.random.default_rng(1).permutation(len(rows))]
    p = tmp_path / "s.xyz"
    np.savetxt(p, rows)
    hm = read_height_map(p, units="um")
    assert hm.n_missing == 1 and np.isnan(hm.z[1, 2])
    expected = Z_UM.copy()
    expected[1, 2] = np.nan
    np.testing.assert_allclose(hm.z, expected * 1e-6, equal_nan=True)
    assert hm.dx == pytest.approx(0.5e-6) and hm.dy == pytest.approx(0.5e-6)


def test_npy_and_npz(tmp_path):
    p = tmp_path / "m.npy"
    np.save(p, Z_UM)
    check(read_height_map(p, dx="0.5um", units="um"))
    q = tmp_path / "m.npz"
    np.savez(q, z=Z_UM, dx=0.5, units="um", xy_units="um")
    check(read_height_map(q))


def test_hdf5_attributes_and_coordinates(tmp_path):
    p = tmp_path / "m.h5"
    with h5py.File(p, "w") as f:
        ds = f.create_dataset("topography", data=Z_UM)
        ds.attrs["dx"] = 0.5e-6
        ds.attrs["dy"] = 0.5e-6
        ds.attrs["units"] = "um"
    check(read_height_map(p))
    q = tmp_path / "c.h5"
    with h5py.File(q, "w") as f:
        f.create_dataset("height", data=Z_UM * 1e-6)
        f.create_dataset("x", data=np.arange(4) * 0.5e-6)
        f.create_dataset("y", data=np.arange(3) * 0.5e-6)
    check(read_height_map(q))
    with pytest.raises(InputError, match="not found"):
        read_height_map(q, dataset="nothing")


def test_user_spacing_overrides_file_and_says_so(tmp_path):
    q = tmp_path / "m.npz"
    np.savez(q, z=Z_UM, dx=0.5e-6)
    hm = read_height_map(q, dx="1um", units="um")
    assert hm.dx == pytest.approx(1e-6)
    assert any("overrides" in n for n in hm.meta["notes"])


def test_non_uniform_grid_is_rejected(tmp_path):
    xs = [0.0, 1.0, 2.5, 3.5]
    rows = [(x, y, 0.1) for y in (0.0, 1.0, 2.0) for x in xs]
    p = tmp_path / "bad.xyz"
    np.savetxt(p, rows)
    # the file, the axis and the two steps found
    with pytest.raises(InputError, match=r"bad\.xyz\b.*\bx steps\b.*\b1 to 1\.5\b"):
        read_height_map(p)
    with h5py.File(tmp_path / "bad.h5", "w") as f:
        f.create_dataset("z", data=np.zeros((3, 4)))
        f.create_dataset("x", data=np.array(xs))
    with pytest.raises(InputError, match=r"bad\.h5\b.*\bx steps\b.*\b1 to 1\.5\b"):
        read_height_map(tmp_path / "bad.h5", dy=1.0)


def test_wrong_shapes_are_rejected(tmp_path):
    np.save(tmp_path / "v.npy", np.arange(10.0))
    with pytest.raises(InputError, match="2-D"):
        read_height_map(tmp_path / "v.npy", dx=1e-6)
    np.save(tmp_path / "small.npy", np.zeros((2, 5)))
    with pytest.raises(InputError, match="3 x 3"):
        read_height_map(tmp_path / "small.npy", dx=1e-6)
    (tmp_path / "ragged.csv").write_text("1,2,3\n4,5\n6,7,8\n")
    with pytest.raises(InputError, match="rectangular"):
        read_height_map(tmp_path / "ragged.csv", dx=1e-6)
    with pytest.raises(InputError, match="2-D"):
        make_height_map(np.zeros((3, 3, 3)), dx=1e-6)


def test_missing_spacing_is_an_error(tmp_path):
    np.save(tmp_path / "m.npy", Z_UM)
    with pytest.raises(InputError, match=r"m\.npy\b.*\bdx\b.*--dx"):
        read_height_map(tmp_path / "m.npy")
    with pytest.raises(InputError, match="dx"):
        make_height_map(Z_UM, dx=None)


def test_other_input_errors(tmp_path):
    with pytest.raises(InputError, match=r"none\.csv\b.*\bexist"):
        read_height_map(tmp_path / "none.csv", dx=1e-6)
    (tmp_path / "m.xls").write_text("x")
    with pytest.raises(InputError, match="suffix"):
        read_height_map(tmp_path / "m.xls", dx=1e-6)
    np.save(tmp_path / "m.npy", Z_UM)
    with pytest.raises(InputError, match="units"):
        read_height_map(tmp_path / "m.npy", dx=1e-6, units="furlong")
    with pytest.raises(InputError, match="dx"):
        read_height_map(tmp_path / "m.npy", dx=-1.0)
    rows = [(j * 0.5, i * 0.5, Z_UM[i, j]) for i in range(3) for j in range(4)]
    np.savetxt(tmp_path / "s.xyz", rows)
    with pytest.raises(InputError, match="disagrees"):
        read_height_map(tmp_path / "s.xyz", dx="0.7um", units="um")
    assert parse_length("781nm", "dx") == pytest.approx(7.81e-7)


def test_instrument_format_through_surfalize(tmp_path):
    surfalize = pytest.importorskip("surfalize")
    surf = surfalize.Surface(Z_UM.copy(), 0.5, 0.5)  # surfalize works in micrometres
    for suffix in (".sur", ".x3p"):
        p = tmp_path / f"m{suffix}"
        surf.save(p)
        check(read_height_map(p), atol=1e-12)  # .sur stores integer counts: 1 pm quantisation


def test_instrument_format_without_reader_says_how_to_install(tmp_path, monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_surfalize(name, *a, **k):
        if name.startswith("surfalize"):
            raise ImportError(name)
        return real_import(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", no_surfalize)
    (tmp_path / "m.opd").write_bytes(b"\x00" * 16)
    with pytest.raises(InputError, match=r"\.opd\b.*\bsurfalize\b"):
        read_height_map(tmp_path / "m.opd")
