"""CSV export of EHL profiles (``ehl solve --csv``): the pressure and film along the centre
lines, dimensionless and, when the result has a physical scale (a scene), in SI units.

* line contact: ``<stem>_profile.csv`` with ``X, P, H`` (``X = x/b``, ``P = p/pmax``, ``H``
  in Venner's scaling ``h R/b^2``) and ``x_m, p_Pa, h_m``;
* point contact: ``<stem>_profile_x.csv`` along the rolling direction through the centre
  (``Y = 0``) and ``<stem>_profile_y.csv`` across it (``X = 0``), ``X = x/a``, ``Y = y/a``,
  ``H = h Rx/a^2``.

One header row of column names; numbers with 10 significant digits.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np

from ..model.atomic import write_text_atomic
from ..model.paths import output_file
from ..model.results import Result


def _csv(columns: dict[str, np.ndarray]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(list(columns))
    for row in zip(*columns.values(), strict=True):
        w.writerow([f"{float(v):.10g}" for v in row])
    return buf.getvalue()


def profile_columns(res: Result) -> dict[str, dict[str, np.ndarray]]:
    """The profiles of ``res`` (kind ``ehl_line`` or ``ehl_point``) as ``{suffix: columns}``."""
    physical = "p" in res.fields and "h" in res.fields
    if res.kind == "ehl_line":
        cols = {"X": res["X"], "P": res["P"], "H": res["H"]}
        if physical:
            cols.update(x_m=res["x"], p_Pa=res["p"], h_m=res["h"])
        return {"_profile": cols}
    if res.kind != "ehl_point":
        raise ValueError(f"no profiles for a result of kind {res.kind!r}")
    X, Y = res["X"], res["Y"]
    j0 = int(np.argmin(np.abs(Y)))  # centre line Y = 0 (on the half domain: its symmetry edge)
    i0 = int(np.argmin(np.abs(X)))
    along = {"X": X, "P": res["P"][:, j0], "H": res["H"][:, j0]}
    across = {"Y": Y, "P": res["P"][i0, :], "H": res["H"][i0, :]}
    if physical:
        along.update(x_m=res["x"], p_Pa=res["p"][:, j0], h_m=res["h"][:, j0])
        across.update(y_m=res["y"], p_Pa=res["p"][i0, :], h_m=res["h"][i0, :])
    return {"_profile_x": along, "_profile_y": across}


def write_profiles_csv(res: Result, outdir: str | Path, stem: str) -> list[Path]:
    """Write the profiles of ``res`` as CSV files in ``outdir``; return their paths."""
    return [write_text_atomic(output_file(outdir, f"{stem}{suffix}", ".csv"), _csv(cols))
            for suffix, cols in profile_columns(res).items()]
