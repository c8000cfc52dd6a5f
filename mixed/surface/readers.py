"""Reading height maps: plain text / CSV (matrix or x y z columns), ``.npy``/``.npz``, HDF5,
and instrument formats through the optional ``surfalize`` reader library.

Spacings and units come from the caller or the file; the caller wins and a disagreement is
recorded in ``HeightMap.meta["notes"]`` (for ``x y z`` files, whose coordinates define the
grid, a disagreement is an error). Missing points stay NaN here; filling or excluding them is
:func:`mixed.surface.levelling.handle_missing`'s job.

Text files may carry ``# key = value`` (or ``# key: value``) header lines for ``dx``, ``dy``,
``units`` and ``xy_units``; values may carry a unit (``# dx = 0.781 um``).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import InputError, require_choice

from .heightmap import HeightMap, parse_length, unit_factor

TEXT_SUFFIXES = (".txt", ".csv", ".tsv", ".asc", ".dat", ".xyz")
NPY_SUFFIXES = (".npy", ".npz")
HDF5_SUFFIXES = (".h5", ".hdf5", ".hdf", ".he5")
#: Instrument formats the optional reader (surfalize) is known to read; others it lists are
#: accepted too when it is installed.
INSTRUMENT_SUFFIXES = (
    ".opd", ".sur", ".x3p", ".plu", ".plux", ".vk4", ".vk6", ".vk7", ".sdf", ".al3d", ".gwy",
    ".nms", ".os3d", ".zmg", ".zon", ".lext", ".tmd", ".sflz", ".hdat",
)
LAYOUTS = ("auto", "matrix", "xyz")
#: Largest distance of a coordinate from the regular lattice, in steps, before a grid is called
#: non-uniform (exports round coordinates to a few digits).
UNIFORM_TOL = 0.01
_HEADER_RE = re.compile(r"^\s*[#%]\s*([A-Za-z_]+)\s*[:=]\s*(.+?)\s*$")
_HEADER_KEYS = {"dx", "dy", "units", "xy_units"}
_HDF5_Z_NAMES = ("z", "height", "heights", "topography", "data", "fields/z")


def read_height_map(
    path: str | Path,
    dx: Any = None,
    dy: Any = None,
    units: str | None = None,
    xy_units: str | None = None,
    layout: str = "auto",
    dataset: str | None = None,
) -> HeightMap:
    """Read a height map from ``path``.

    Parameters
    ----------
    path : file (text/CSV, .npy/.npz, HDF5, or an instrument format with ``surfalize`` installed).
    dx, dy : spacings, a number in ``xy_units`` (default metres) or a string with a unit
        (``"0.781um"``). ``dy`` defaults to ``dx``. Required unless the file carries them.
    units : height units of the file (``m``, ``mm``, ``um``, ``nm``); default from the file or ``m``.
    xy_units : units of ``x y`` columns and of plain-number spacings; default ``units`` for
        ``x y z`` columns, metres otherwise.
    layout : ``"matrix"`` (rows are y, columns x), ``"xyz"`` (three columns x, y, z), or
        ``"auto"`` (xyz when there are three columns whose first two form a grid with at most
        half of its points missing).
    dataset : HDF5 dataset path (default: ``z``, ``height``, ``topography``, ``data``, or the
        only 2-D dataset).
    """
    p = Path(path)
    if not p.is_file():
        raise InputError(f"height map file {str(p)!r} does not exist")
    require_choice("layout", layout, LAYOUTS)
    suffix = p.suffix.lower()
    if suffix in NPY_SUFFIXES:
        return _read_numpy(p, dx, dy, units, xy_units)
    if suffix in HDF5_SUFFIXES:
        return _read_hdf5(p, dx, dy, units, xy_units, dataset)
    if suffix in INSTRUMENT_SUFFIXES or (suffix not in TEXT_SUFFIXES and _surfalize_reads(suffix)):
        return read_instrument(p, dx, dy, units)
    if suffix in TEXT_SUFFIXES or suffix == "":
        return _read_text(p, dx, dy, units, xy_units, layout)
    raise InputError(
        f"height map file {p.name!r}: suffix {suffix!r} is not known; text {list(TEXT_SUFFIXES)}, "
        f"numpy {list(NPY_SUFFIXES)}, HDF5 {list(HDF5_SUFFIXES)}, instrument formats "
        f"{list(INSTRUMENT_SUFFIXES)} with the optional reader (pip install surfalize)"
    )


# -- helpers ------------------------------------------------------------------------------------
def _finish(
    z: np.ndarray,
    dx_user: Any,
    dy_user: Any,
    dx_file: float | None,
    dy_file: float | None,
    units: str | None,
    xy_units: str | None,
    source: str,
    meta: dict[str, Any],
) -> HeightMap:
    """Resolve spacings (user over file), scale heights to metres, and build the map."""
    notes: list[str] = list(meta.pop("notes", []))
    if z.ndim != 2:
        raise InputError(f"{source}: height data must be 2-D (ny, nx), got shape {z.shape}")
    dxm = parse_length(dx_user, "dx", xy_units) if dx_user is not None else None
    dym = parse_length(dy_user, "dy", xy_units) if dy_user is not None else None
    for name, user, filev in (("dx", dxm, dx_file), ("dy", dym, dy_file)):
        if user is not None and filev is not None and not np.isclose(user, filev, rtol=1e-3):
            notes.append(f"{name} = {user:.6g} m given by the user overrides {filev:.6g} m from the file")
    if dxm is None:
        dxm = dx_file
    if dym is None:
        dym = dy_file if dy_file is not None else dxm
    if dxm is None:
        raise InputError(
            f"{source}: the grid spacing dx is missing; give --dx (e.g. --dx 0.781um) or store it in the file"
        )
    zf = unit_factor(units, "units")
    meta.update({"units": units or "m", "notes": notes})
    return HeightMap(np.asarray(z, dtype=float) * zf, dxm, dym, source=source, meta=meta)


def uniform_step(coords: np.ndarray, name: str) -> float:
    """The step of a regular grid's coordinates; raises InputError if the grid is not uniform.

    Every distinct coordinate must lie within ``UNIFORM_TOL`` steps of the lattice
    ``c0 + k * step`` (whole multiples allow missing rows or columns).
    """
    u = np.unique(coords)
    if u.size < 2:
        raise InputError(f"{name} coordinates have fewer than 2 distinct values: not a 2-D grid")
    d = np.diff(u)
    step0 = float(np.min(d))
    span = float(u[-1] - u[0])
    step = span / max(1.0, float(np.rint(span / step0)))
    k = (u - u[0]) / step
    dev = float(np.max(np.abs(k - np.rint(k))))
    if dev > UNIFORM_TOL or d.max() / step0 > 10.0:
        raise InputError(
            f"non-uniform grid: {name} steps range from {d.min():.6g} to {d.max():.6g}; a regular grid "
            f"is required (one step, or whole multiples of it for missing rows, within {UNIFORM_TOL:g} step)"
        )
    return step


# -- text -----------------------------------------------------------------------------------
def _text_header(p: Path) -> tuple[dict[str, str], int]:
    meta: dict[str, str] = {}
    n_header = 0
    with p.open("r", errors="replace") as fh:
        for line in fh:
            s = line.strip()
            if not s:
                n_header += 1
                continue
            if s[0] in "#%":
                m = _HEADER_RE.match(s)
                if m and m.group(1).lower() in _HEADER_KEYS:
                    meta[m.group(1).lower()] = m.group(2)
                n_header += 1
                continue
            break
    return meta, n_header


def _sniff_delimiter(p: Path) -> str | None:
    with p.open("r", errors="replace") as fh:
        for line in fh:
            s = line.strip()
            if s and s[0] not in "#%":
                if "," in s:
                    return ","
                if ";" in s:
                    return ";"
                if "\t" in s:
                    return "\t"
                return None
    return None


def _load_table(p: Path, delimiter: str | None) -> np.ndarray:
    try:
        arr = np.loadtxt(p, delimiter=delimiter, comments=("#", "%"), ndmin=2)
    except ValueError:
        try:
            arr = np.genfromtxt(p, delimiter=delimiter, comments="#", missing_values=("", "nan", "NaN", "NA"),
                                filling_values=np.nan, invalid_raise=True)
        except ValueError as exc:
            raise InputError(f"{p.name}: not a rectangular table of numbers ({exc})") from None
        arr = np.atleast_2d(arr)
    return arr


def _read_text(p: Path, dx: Any, dy: Any, units: str | None, xy_units: str | None, layout: str) -> HeightMap:
    head, _ = _text_header(p)
    units = units if units is not None else head.get("units")
    xy_units = xy_units if xy_units is not None else head.get("xy_units")
    arr = _load_table(p, _sniff_delimiter(p))
    if arr.size == 0:
        raise InputError(f"{p.name}: no numbers found")
    if layout == "auto":
        layout = "xyz" if _looks_like_xyz(arr) else "matrix"
    meta: dict[str, Any] = {"format": f"text ({layout})"}
    if layout == "xyz":
        z, dxf, dyf = xyz_to_grid(arr, p.name)
        xyf = unit_factor(xy_units if xy_units is not None else units, "xy_units")
        dx_file, dy_file = dxf * xyf, dyf * xyf
        _check_user_spacing(dx, dy, dx_file, dy_file, xy_units if xy_units is not None else units, p.name)
        return _finish(z, None, None, dx_file, dy_file, units, None, str(p), meta)
    dx_file = parse_length(head["dx"], "dx (file header)", xy_units) if "dx" in head else None
    dy_file = parse_length(head["dy"], "dy (file header)", xy_units) if "dy" in head else None
    return _finish(arr, dx, dy, dx_file, dy_file, units, xy_units, str(p), meta)


def _looks_like_xyz(arr: np.ndarray) -> bool:
    if arr.shape[1] != 3 or arr.shape[0] < 9:
        return False
    nu0 = np.unique(arr[:, 0]).size
    nu1 = np.unique(arr[:, 1]).size
    return nu0 >= 3 and nu1 >= 3 and nu0 * nu1 <= 2 * arr.shape[0]


def xyz_to_grid(arr: np.ndarray, name: str = "xyz") -> tuple[np.ndarray, float, float]:
    """Grid ``x y z`` rows (any order, points may be missing) into a ``(ny, nx)`` array.

    Returns ``(z, dx, dy)`` in the file's units; missing grid points are NaN.
    """
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise InputError(f"{name}: x y z data must have exactly 3 columns, got shape {arr.shape}")
    x, y, z = arr[:, 0], arr[:, 1], arr[:, 2]
    if not (np.isfinite(x).all() and np.isfinite(y).all()):
        raise InputError(f"{name}: x and y columns must be finite numbers")
    dx = uniform_step(x, f"{name}: x")
    dy = uniform_step(y, f"{name}: y")
    ix = np.rint((x - x.min()) / dx).astype(np.int64)
    iy = np.rint((y - y.min()) / dy).astype(np.int64)
    nx, ny = int(ix.max()) + 1, int(iy.max()) + 1
    if nx * ny > 4 * arr.shape[0]:
        raise InputError(f"{name}: the x y points fill only {arr.shape[0]} of a {ny} x {nx} grid")
    flat = iy * nx + ix
    if np.unique(flat).size != flat.size:
        raise InputError(f"{name}: duplicate (x, y) points")
    grid = np.full(ny * nx, np.nan)
    grid[flat] = z
    return grid.reshape(ny, nx), dx, dy


def _check_user_spacing(dx: Any, dy: Any, dx_file: float, dy_file: float, units: str | None, name: str) -> None:
    for label, user, filev in (("dx", dx, dx_file), ("dy", dy, dy_file)):
        if user is None:
            continue
        um = parse_length(user, label, units)
        if not np.isclose(um, filev, rtol=1e-3):
            raise InputError(
                f"{name}: {label} = {um:.6g} m disagrees with the x y columns ({filev:.6g} m); "
                f"omit --{label} for x y z files"
            )


# -- numpy ----------------------------------------------------------------------------------
def _read_numpy(p: Path, dx: Any, dy: Any, units: str | None, xy_units: str | None) -> HeightMap:
    try:
        obj = np.load(p, allow_pickle=False)
    except (ValueError, OSError) as exc:
        raise InputError(f"{p.name}: cannot read as numpy data ({exc})") from None
    meta: dict[str, Any] = {"format": p.suffix.lower()[1:]}
    dx_file = dy_file = None
    if isinstance(obj, np.lib.npyio.NpzFile):
        with obj:
            keys = list(obj.keys())
            zkey = "z" if "z" in keys else None
            if zkey is None:
                cands = [k for k in keys if obj[k].ndim == 2]
                if len(cands) != 1:
                    raise InputError(f"{p.name}: store the heights as 'z' (2-D arrays found: {cands})")
                zkey = cands[0]
            z = obj[zkey]
            file_units = str(obj["units"]) if "units" in keys else None
            file_xy = str(obj["xy_units"]) if "xy_units" in keys else None
            xy_units = xy_units if xy_units is not None else file_xy
            if "dx" in keys:
                dx_file = parse_length(float(obj["dx"]), "dx (file)", xy_units)
            if "dy" in keys:
                dy_file = parse_length(float(obj["dy"]), "dy (file)", xy_units)
            units = units if units is not None else file_units
    else:
        z = obj
    if z.dtype.kind not in "fiu":
        raise InputError(f"{p.name}: heights must be numbers, got dtype {z.dtype}")
    return _finish(np.asarray(z, dtype=float), dx, dy, dx_file, dy_file, units, xy_units, str(p), meta)


# -- HDF5 -----------------------------------------------------------------------------------
def _read_hdf5(
    p: Path, dx: Any, dy: Any, units: str | None, xy_units: str | None, dataset: str | None
) -> HeightMap:
    import h5py

    try:
        f = h5py.File(p, "r")
    except OSError as exc:
        raise InputError(f"{p.name}: cannot open as HDF5 ({exc})") from None
    with f:
        if dataset is None:
            dataset = next((n for n in _HDF5_Z_NAMES if n in f and isinstance(f[n], h5py.Dataset)), None)
        if dataset is None:
            found: list[str] = []
            f.visititems(lambda n, o: found.append(n) if isinstance(o, h5py.Dataset) and o.ndim == 2 else None)
            if len(found) != 1:
                raise InputError(f"{p.name}: name the height dataset with --dataset (2-D datasets: {found})")
            dataset = found[0]
        if dataset not in f or not isinstance(f[dataset], h5py.Dataset):
            raise InputError(f"{p.name}: dataset {dataset!r} not found")
        ds = f[dataset]
        z = np.asarray(ds[()], dtype=float)
        attrs = {**{k: v for k, v in f.attrs.items()}, **{k: v for k, v in ds.attrs.items()}}

        def attr_str(key: str) -> str | None:
            v = attrs.get(key)
            return v.decode() if isinstance(v, bytes) else (None if v is None else str(v))

        units = units if units is not None else attr_str("units")
        xy_units = xy_units if xy_units is not None else attr_str("xy_units")
        dx_file = parse_length(float(attrs["dx"]), "dx (file)", xy_units) if "dx" in attrs else None
        dy_file = parse_length(float(attrs["dy"]), "dy (file)", xy_units) if "dy" in attrs else None
        # coordinate datasets (ehl-multigrid Result files: /coords/x, /coords/y with units)
        for axis, names in (("x", ("x", "coords/x")), ("y", ("y", "coords/y"))):
            name = next((n for n in names if n in f and isinstance(f[n], h5py.Dataset) and f[n].ndim == 1), None)
            if name is None:
                continue
            c = np.asarray(f[name][()], dtype=float)
            cu = f[name].attrs.get("units", xy_units)
            cu = cu.decode() if isinstance(cu, bytes) else cu
            step = uniform_step(c, f"{p.name}: {name}") * unit_factor(cu if cu not in (None, "-") else xy_units, f"{name} units")
            if axis == "x":
                dx_file = step
            else:
                dy_file = step
    meta: dict[str, Any] = {"format": "hdf5", "dataset": dataset}
    return _finish(z, dx, dy, dx_file, dy_file, units, xy_units, str(p), meta)


# -- instrument formats (optional extra) ---------------------------------------------------------
def _surfalize_reads(suffix: str) -> bool:
    try:
        from surfalize.file import supported_formats_read
    except Exception:
        return False
    return suffix in {s.lower() for s in supported_formats_read}


def read_instrument(p: str | Path, dx: Any = None, dy: Any = None, units: str | None = None) -> HeightMap:
    """Read an instrument export (Wyko/Vision ``.opd``, Digital Surf ``.sur``, ``.x3p``, ...)
    with the optional ``surfalize`` library (``pip install surfalize``).

    surfalize returns heights and pixel sizes in micrometres; they are converted to metres.
    ``units`` is ignored (the format defines it); ``dx``/``dy`` override the file's pixel size.
    """
    p = Path(p)
    try:
        from surfalize import Surface
    except ImportError:
        raise InputError(
            f"{p.name}: instrument format {p.suffix!r} needs the optional reader library; "
            "install it with `pip install surfalize` (or export the map as text, .npy or HDF5)"
        ) from None
    try:
        surf = Surface.load(p)
    except Exception as exc:  # the library's own errors vary by format
        raise InputError(f"{p.name}: the instrument reader (surfalize) failed: {type(exc).__name__}: {exc}") from None
    meta: dict[str, Any] = {"format": f"instrument {p.suffix.lower()} (surfalize)"}
    if units is not None:
        meta["notes"] = [f"units = {units!r} ignored: surfalize returns micrometres"]
    z = np.array(surf.data, dtype=float)
    return _finish(z, dx, dy, float(surf.step_x) * 1e-6, float(surf.step_y) * 1e-6, "um", None, str(p), meta)
