"""Measured and synthetic surfaces as moving features of ``ehl transient``.

A scene's ``[feature]`` table with ``kind = "map"`` names a height file; the transient solver
(``ehl_multigrid.transient.scene_feature``) finds this reader through the entry-point group
``ehl.height_maps`` and then places the heights in the contact (``x0``, ``y0``, ``body``). What
this reader adds to a plain array of heights in metres is what a measured surface needs before
it can pass through a film a few tens of nanometres thick:

* every format :func:`mixed.surface.readers.read_height_map` reads (text with ``# dx = ...``
  headers, ``x y z`` columns, ``.npy``/``.npz``, HDF5, instrument formats through the optional
  reader), with height ``units`` and spacing ``xy_units``;
* missing points filled (harmonic interpolation: the solver needs every height);
* levelling (``level = "plane"`` by default, as the thesis levels its measurements before the
  statistics; ``"form"`` with ``form_order``, ``"mean"``, ``"none"``), so that an instrument
  tilt of micrometres over the map does not enter the gap;
* a filter (``filter = "none" | "lowpass:K" | "gauss:LAMBDA"``), the same filters the
  surface statistics use;
* ``rolling = "x"`` (default) or ``"y"``: the map axis along the rolling direction;
* for a line contact, one profile: a single-row file, or row ``row`` of a map (default the
  middle row).

Keys (besides ``kind``, ``x0``, ``y0`` and ``body``, which the transient solver reads):
``file``, ``dx``, ``dy``, ``units``, ``xy_units``, ``layout``, ``dataset``, ``level``,
``form_order``, ``filter``, ``rolling``, ``row``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import (
    InputError,
    reject_unknown_keys,
    require_choice,
    require_range,
)

from .analysis import parse_filter
from .filters import gaussian_lowpass, lowpass_3x3
from .heightmap import parse_length, unit_factor
from .levelling import handle_missing, level
from .readers import HDF5_SUFFIXES, INSTRUMENT_SUFFIXES, read_height_map

#: keys this reader understands in a ``[feature]`` table
KEYS = frozenset({"file", "dx", "dy", "units", "xy_units", "layout", "dataset", "level",
                  "form_order", "filter", "rolling", "row"})
LEVELS = ("plane", "form", "mean", "none")


def feature_heights(table: dict[str, Any], ndim: int,
                    solver_keys: Any = frozenset()) -> tuple[np.ndarray, float, float | None]:
    """Heights [m] and spacings [m] of a ``[feature] kind = "map"`` table (module docstring).

    Parameters
    ----------
    table : the scene's ``[feature]`` table (lengths already in metres where the scene gave units).
    ndim : 1 for a line contact (a profile along the rolling direction), 2 for a point contact
        (a map, rows along Y).
    solver_keys : the keys the transient solver reads itself (accepted, not used here).

    Returns
    -------
    z, dx, dy : heights [m] (1-D, or 2-D with rows along Y and columns along the rolling
        direction) and the spacings along the rolling direction and across it (None for a line).

    Examples
    --------
    >>> import numpy as np, tempfile, os
    >>> d = tempfile.mkdtemp(); f = os.path.join(d, "m.txt")
    >>> np.savetxt(f, 1e-3 * np.arange(20.0).reshape(4, 5), header="dx = 2 um\\nunits = um")
    >>> z, dx, dy = feature_heights({"kind": "map", "file": f}, 2, {"kind"})
    >>> float(abs(z).max()) < 1e-12, dx, dy   # the tilt is levelled away
    (True, 2e-06, 2e-06)
    """
    reject_unknown_keys("feature", table, set(KEYS) | set(solver_keys))
    path = table.get("file")
    if not isinstance(path, str) or not Path(path).is_file():
        raise InputError(f"feature.file = {path!r} is not a readable file")
    how = require_choice("feature.level", table.get("level", "plane"), LEVELS)
    order = int(require_range("feature.form_order", table.get("form_order", 2), 1, 8, "-"))
    rolling = require_choice("feature.rolling", table.get("rolling", "x"), ("x", "y"))
    units = table.get("units")
    raw = _raw_array(Path(path))
    if ndim == 1 and raw is not None and np.squeeze(raw).ndim == 1:
        return _profile(np.squeeze(raw) * unit_factor(units, "feature.units"), table, how, order), \
            _spacing(table, "dx"), None
    hm = read_height_map(path, table.get("dx"), table.get("dy"), units, table.get("xy_units"),
                         table.get("layout", "auto"), table.get("dataset"))
    hm = handle_missing(hm, "fill")
    hm = level(hm, how, order)
    spec = parse_filter(table.get("filter"))
    if spec.kind == "lowpass":
        hm = lowpass_3x3(hm, spec.passes, spec.weights)
    elif spec.kind == "gaussian":
        hm = gaussian_lowpass(hm, spec.cutoff)
    elif spec.kind != "none":
        raise InputError(f"feature.filter = {table.get('filter')!r}: a feature takes none, "
                         f"lowpass:K or gauss:LAMBDA (until-psi belongs to the statistics)")
    z, dx, dy = (hm.z, hm.dx, hm.dy) if rolling == "x" else (hm.z.T, hm.dy, hm.dx)
    if ndim == 2:
        return np.array(z), dx, dy
    row = int(require_range("feature.row", table.get("row", z.shape[0] // 2), 0, z.shape[0] - 1, "-"))
    return np.array(z[row]), dx, None


def _raw_array(p: Path) -> np.ndarray | None:
    """The plain numbers of a ``.npy`` or text file when they form a single row (a line-contact
    profile, which a map reader refuses); None for maps and other formats."""
    from ehl_multigrid.transient.scene_feature import load_height_array

    suffix = p.suffix.lower()
    if suffix in INSTRUMENT_SUFFIXES or suffix in HDF5_SUFFIXES or suffix == ".npz":
        return None
    try:
        arr = load_height_array(str(p))
    except InputError:
        return None  # a header or x y z columns: the map reader's business
    if np.squeeze(arr).ndim == 2 and min(arr.shape) < 3:
        raise InputError(f"feature.file = {str(p)!r} holds an array of shape {arr.shape}: a line "
                         f"contact needs one row (a profile) and a map at least 3 x 3 points")
    return arr if np.squeeze(arr).ndim == 1 else None


def _spacing(table: dict[str, Any], key: str) -> float:
    v = table.get(key)
    if v is None:
        raise InputError(f"feature.{key} is missing: a profile file carries no spacing "
                         f"(give it, e.g. {key} = \"2 um\")")
    return parse_length(v, f"feature.{key}", table.get("xy_units"))


def _profile(z: np.ndarray, table: dict[str, Any], how: str, order: int) -> np.ndarray:
    """A single profile levelled as a map would be (``plane``: a straight line; ``form``: a
    polynomial of ``order``); filters need a map."""
    if table.get("filter") not in (None, "none"):
        raise InputError("feature.filter needs a 2-D map; filter a profile before writing it")
    if not np.all(np.isfinite(z)):
        raise InputError(f"feature.file = {table.get('file')!r} has missing (NaN) heights: a "
                         f"profile is not filled; give a map or fill it first")
    x = np.linspace(-1.0, 1.0, z.size)
    if how == "plane":
        return z - np.polyval(np.polyfit(x, z, 1), x)
    if how == "form":
        return z - np.polyval(np.polyfit(x, z, order), x)
    if how == "mean":
        return z - z.mean()
    return z


__all__ = ["KEYS", "feature_heights"]
