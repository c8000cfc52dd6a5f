"""One result type and one HDF5 layout for every layer.

A :class:`Result` carries coordinates, fields (each with units and the names of the
coordinates it is defined on), scalars with units, convergence histories, the scene it was
computed for and the package version.

HDF5 layout (written by :meth:`Result.save`, read by :meth:`Result.load`)::

    /                    attrs: kind, package, package_version, created, format_version
    /scene               attrs: toml (resolved scene, TOML text), name; absent if no scene
    /coords/<name>       dataset, attrs: units, long_name; HDF5 dimension scale
    /fields/<name>       dataset, attrs: units, long_name, dims (coordinate names);
                         dimension scales of /coords attached
    /scalars             attrs: one per scalar (numbers, strings, bools); attrs
                         ``units.<name>`` give units
    /history/<name>      1-D datasets (residual per cycle, load error, ...)
    /meta                attrs: free text (solver options used, notes); JSON-encoded values

A result of :meth:`ehl_multigrid.solution.Solution.to_result` holds the solution's outcome and
error estimate the same way for every physics (scalars ``status``, ``message``, ``success``,
``Hc_error``, ``Hm_error``; meta ``error_budget`` by part name, ``error_notes``, ``accuracy``).
Older files named the ``iteration`` part of ``error_budget`` ``algebraic``: it is read under
the current name.

Files are written to a temporary file beside the target and renamed, so a crash never
leaves a half-written result.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from .atomic import atomic_path, fault_point
from .errors import InputError

FORMAT_VERSION = 1
#: part names of the error budget (meta ``error_budget``) that older files wrote -> the names
#: written now, those of :class:`~ehl_multigrid.solution.ErrorEstimate` ``parts``
RENAMED_PARTS = {"algebraic": "iteration"}
#: HDF5 filters of the larger fields: the byte shuffle before gzip level 1 (standard filters
#: every HDF5 reader has). On the four 1025^2 float64 fields of a point film: 24.5 MB in 0.67 s,
#: against 29.4 MB in 1.05 s with gzip level 4 alone and 34.8 MB uncompressed
COMPRESSION = {"compression": "gzip", "compression_opts": 1, "shuffle": True}


def package_version() -> str:
    try:
        from importlib.metadata import version

        return version("ehl-multigrid")
    except Exception:  # not installed (running from a source tree)
        return "0+unknown"


@dataclass
class Variable:
    data: np.ndarray
    units: str = "-"
    dims: tuple[str, ...] = ()
    long_name: str = ""


class ScalarAccess:
    """Solver answers (line, point): the entries of ``self.scalars`` read as attributes
    (``sol.Hc``) and ``converged`` taken from ``self.report``."""

    def __getattr__(self, name: str) -> Any:
        scal = self.__dict__.get("scalars", {})
        if name in scal:
            return scal[name]
        raise AttributeError(name)

    @property
    def converged(self) -> bool:
        return bool(self.report.converged)


@dataclass
class Result:
    """Container for any solver output.

    Examples
    --------
    >>> import numpy as np
    >>> r = Result("demo")
    >>> r.add_coord("X", np.linspace(-1, 1, 5), "-", "x / b")
    >>> r.add_field("P", np.zeros(5), "-", ("X",), "p / pmax")
    >>> r.scalars["Hc"] = 0.5
    >>> r["P"].shape
    (5,)
    """

    kind: str
    scene: Any = None  # ehl_multigrid.model.scene.Scene | None (kept loose: results may be scene-free)
    coords: dict[str, Variable] = field(default_factory=dict)
    fields: dict[str, Variable] = field(default_factory=dict)
    scalars: dict[str, Any] = field(default_factory=dict)
    scalar_units: dict[str, str] = field(default_factory=dict)
    history: dict[str, np.ndarray] = field(default_factory=dict)
    meta: dict[str, Any] = field(default_factory=dict)
    package_version: str = field(default_factory=package_version)
    #: False for a result saved part-way (an interrupted curve's finished points); also set by
    #: ``meta["partial"] = True``. Stored as the root attribute ``complete``.
    complete: bool = True

    # -- building -----------------------------------------------------------------------------
    def add_coord(self, name: str, data: np.ndarray, units: str = "-", long_name: str = "") -> None:
        arr = np.asarray(data)
        if arr.ndim != 1:
            raise InputError(f"coordinate {name!r} must be 1-D, got shape {arr.shape}")
        self.coords[name] = Variable(arr, units, (name,), long_name)

    def add_field(self, name: str, data: np.ndarray, units: str = "-", dims: tuple[str, ...] = (), long_name: str = "") -> None:
        arr = np.asarray(data)
        if dims:
            if len(dims) != arr.ndim:
                raise InputError(f"field {name!r}: dims {dims} do not match shape {arr.shape}")
            for ax, d in enumerate(dims):
                if d not in self.coords:
                    raise InputError(f"field {name!r}: unknown coordinate {d!r}")
                if self.coords[d].data.shape[0] != arr.shape[ax]:
                    raise InputError(
                        f"field {name!r}: axis {ax} has {arr.shape[ax]} points, coordinate {d!r} has "
                        f"{self.coords[d].data.shape[0]}"
                    )
        self.fields[name] = Variable(arr, units, tuple(dims), long_name)

    def set_scalar(self, name: str, value: Any, units: str = "-") -> None:
        self.scalars[name] = value
        self.scalar_units[name] = units

    def add_report(self, report: Any) -> None:
        """Store a :class:`~ehl_multigrid.model.convergence.ConvergenceReport`."""
        for k, v in report.scalars().items():
            self.scalars[k] = v
        self.scalar_units.setdefault("wall_s", "s")
        for k, v in report.histories().items():
            self.history[k] = np.asarray(v)

    def __getitem__(self, name: str) -> np.ndarray:
        if name in self.fields:
            return self.fields[name].data
        if name in self.coords:
            return self.coords[name].data
        if name in self.history:
            return self.history[name]
        raise KeyError(name)

    # -- I/O --------------------------------------------------------------------------------
    def save(self, path: str | os.PathLike) -> Path:
        """Write atomically to ``path`` (HDF5). Returns the path."""
        return _write_atomic(path, self._write)

    def _write(self, f: h5py.Group, compress: bool = True) -> None:
        f.attrs["kind"] = self.kind
        f.attrs["package"] = "ehl-multigrid"
        f.attrs["package_version"] = self.package_version
        f.attrs["format_version"] = FORMAT_VERSION
        f.attrs["created"] = _dt.datetime.now(_dt.timezone.utc).isoformat()
        f.attrs["complete"] = np.bool_(self.complete and not self.meta.get("partial", False))
        if self.scene is not None:
            g = f.create_group("scene")
            g.attrs["toml"] = self.scene.to_toml()
            g.attrs["name"] = self.scene.name
        gc = f.create_group("coords")
        for name, v in self.coords.items():
            ds = gc.create_dataset(name, data=v.data)
            ds.attrs["units"] = v.units
            ds.attrs["long_name"] = v.long_name
            ds.make_scale(name)
        gf = f.create_group("fields")
        for name, v in self.fields.items():
            big = compress and v.data.size > 4096
            ds = gf.create_dataset(name, data=v.data, **(COMPRESSION if big else {}))
            ds.attrs["units"] = v.units
            ds.attrs["long_name"] = v.long_name
            ds.attrs["dims"] = json.dumps(list(v.dims))
            for ax, d in enumerate(v.dims):
                ds.dims[ax].attach_scale(gc[d])
        gs = f.create_group("scalars")
        for name, val in self.scalars.items():
            gs.attrs[name] = _attr_value(name, val)
            if name in self.scalar_units:
                gs.attrs[f"units.{name}"] = self.scalar_units[name]
        gh = f.create_group("history")
        for name, arr in self.history.items():
            gh.create_dataset(name, data=np.asarray(arr))
        gm = f.create_group("meta")
        for name, val in self.meta.items():
            gm.attrs[name] = json.dumps(val, default=_json_default)

    @classmethod
    def load(cls, path: str | os.PathLike, group: str | None = None) -> Result:
        """Read a file written by :meth:`save` (or one result of :func:`save_results`)."""
        with _open_result_file(path) as f:
            if group is not None:
                if group not in f:
                    raise InputError(f"{path} has no result {group!r}; it holds {sorted(f.keys())}")
                return cls._read(f[group], path)
            return cls._read(f, path)

    @classmethod
    def _read(cls, f: h5py.Group, path: Path) -> Result:
        if f.attrs.get("package") != "ehl-multigrid":
            if "series" in f and "steady" in f:
                # the run file `ehl transient` writes (raw.to_hdf5): another layout
                raise InputError(f"{path} is an `ehl transient` run file, not a Result: read it with "
                                 f"ehl_multigrid.transient.result.load_series")
            raise InputError(f"{path} is not an ehl-multigrid result file")
        if _str(f.attrs.get("kind", "")) == "collection":
            raise InputError(f"{path} holds several results {sorted(f.keys())} (ehl run); "
                             "read it with load_results, or name one of them")
        missing = [g for g in ("coords", "fields", "scalars", "history", "meta") if g not in f]
        if missing:
            raise InputError(f"{path} is not a complete ehl-multigrid result (no {missing} group)")
        scene = None
        if "scene" in f:
            from .scene import Scene, tomllib

            scene = Scene.from_dict(tomllib.loads(_str(f["scene"].attrs["toml"])), origin=str(path))
        res = cls(kind=_str(f.attrs["kind"]), scene=scene, package_version=_str(f.attrs["package_version"]),
                  complete=bool(f.attrs.get("complete", True)))
        for name, ds in f["coords"].items():
            res.coords[name] = Variable(ds[()], _str(ds.attrs["units"]), (name,), _str(ds.attrs["long_name"]))
        for name, ds in f["fields"].items():
            dims = tuple(json.loads(_str(ds.attrs["dims"])))
            res.fields[name] = Variable(ds[()], _str(ds.attrs["units"]), dims, _str(ds.attrs["long_name"]))
        for key, val in f["scalars"].attrs.items():
            if key.startswith("units."):
                res.scalar_units[key[6:]] = _str(val)
            else:
                res.scalars[key] = _from_attr(val)
        for name, ds in f["history"].items():
            res.history[name] = ds[()]
        for key, val in f["meta"].attrs.items():
            res.meta[key] = json.loads(_str(val))
        if isinstance(res.meta.get("error_budget"), dict):
            res.meta["error_budget"] = current_part_names(res.meta["error_budget"])
        return res


def current_part_names(budget: dict[str, Any]) -> dict[str, Any]:
    """An error budget (part name -> errors) with the part names of older files
    (:data:`RENAMED_PARTS`) read as the current ones."""
    return {RENAMED_PARTS.get(k, k): v for k, v in budget.items()}


def save_results(path: str | os.PathLike, results: dict[str, Result], meta: dict[str, Any] | None = None,
                 complete: bool = True, planned: list[str] | None = None, compress: bool = True) -> Path:
    """Several results in one HDF5 file, each under ``/<name>`` with the layout above;
    written atomically like :meth:`Result.save`.

    The root attributes ``complete`` (bool) and ``planned`` (JSON list of the result names the
    writer meant to store) say whether the file holds everything: a run interrupted after some of
    its stages stores ``complete = False``, and :func:`load_results` readers can tell.
    ``compress=False`` writes the fields uncompressed (a file the next save replaces: gzip
    costs 0.65 s on the four 1025^2 film fields, against 0.1 s uncompressed).
    """

    def write(f: h5py.File) -> None:
        f.attrs["package"] = "ehl-multigrid"
        f.attrs["kind"] = "collection"
        f.attrs["package_version"] = package_version()
        f.attrs["format_version"] = FORMAT_VERSION
        f.attrs["complete"] = np.bool_(complete)
        f.attrs["planned"] = json.dumps(list(planned) if planned is not None else list(results))
        for k, v in (meta or {}).items():
            f.attrs[k] = json.dumps(v, default=_json_default)
        for name, res in results.items():
            res._write(f.create_group(name), compress)

    return _write_atomic(path, write)


def _write_atomic(path: str | os.PathLike, write: Any) -> Path:
    """Run ``write(h5file)`` on a temporary file beside ``path`` (hidden, named with this
    process's PID so that a later run can tell it is left over from a dead writer), then
    rename it into place with the user's usual file mode."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            write(f)
        fault_point("h5")
    return path


def load_results(path: str | os.PathLike) -> dict[str, Result]:
    """Every result stored by :func:`save_results`."""
    with _open_result_file(path) as f:
        if f.attrs.get("kind") != "collection":
            raise InputError(f"{path} is a single result; use Result.load")
        return {name: Result._read(f[name], path) for name in f.keys()}


def result_names(path: str | os.PathLike) -> list[str] | None:
    """The names of the results a collection (``ehl run``) stores, None for a single result."""
    with _open_result_file(path) as f:
        return sorted(f.keys()) if _str(f.attrs.get("kind", "")) == "collection" else None


def is_complete(path: str | os.PathLike) -> bool:
    """Whether the result or collection at ``path`` holds everything its writer meant to store
    (files written before the ``complete`` attribute existed count as complete)."""
    with _open_result_file(path) as f:
        return bool(f.attrs.get("complete", True))


def _open_result_file(path: str | os.PathLike) -> h5py.File:
    """Open ``path`` for reading; a missing file, a folder or a file that is not HDF5 raises
    :class:`InputError` naming it."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"result file {str(path)!r} does not exist")
    try:
        return h5py.File(path, "r")
    except OSError as exc:
        raise InputError(f"result file {str(path)!r} is not an HDF5 file ({exc})") from None


def _json_default(o: Any) -> Any:
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, np.generic):
        return o.item()
    return str(o)


def _attr_value(name: str, val: Any) -> Any:
    if val is None:
        return "None"
    if isinstance(val, (bool, np.bool_)):
        return np.bool_(val)
    if isinstance(val, (int, float, str, np.integer, np.floating)):
        return val
    arr = np.asarray(val)
    if arr.dtype.kind in "fiub":
        return arr
    raise InputError(f"scalar {name!r} has unsupported type {type(val).__name__}")


def _str(v: Any) -> str:
    return v.decode() if isinstance(v, bytes) else str(v)


def _from_attr(v: Any) -> Any:
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.bool_):
        return bool(v)
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.floating):
        return float(v)
    if isinstance(v, str):
        return None if v == "None" else v
    return v
