"""Shared helpers of the point-contact validation scripts: one solve -> flat dict, a JSON
store that keeps finished cases (interrupt-safe, resumable), machine-load records."""

from __future__ import annotations

import json
import math
import os
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
sys.path.insert(0, str(HERE.parent))
from _paths import out_dir  # noqa: E402

OUT = out_dir("point")

from ehl_multigrid.model.errors import ConvergenceError, InputError  # noqa: E402
from ehl_multigrid.point import build_result, problem_from_moes, solve_fas  # noqa: E402


def load_avg() -> float:
    return os.getloadavg()[0]


def solve_case(M: float, L: float, theta: float = 1.0, viscosity: str = "roelands",
               density: str = "dowson-higginson", points: int = 129, **opts) -> dict:
    """Solve one case; never raises for numerical failure (the failure is recorded)."""
    row = {"M": M, "L": L, "theta": theta, "viscosity": viscosity, "density": density,
           "points": points, **{k: v for k, v in opts.items() if isinstance(v, (int, float, str, bool))},
           "load_before": load_avg()}
    t0 = time.perf_counter()
    try:
        pb = problem_from_moes(M, L, theta, viscosity, density)
        sol = solve_fas(pb, points=points, **opts)
        res = build_result(sol)
        s = res.scalars
        row.update({k: s.get(k) for k in ("Hc", "Hm", "Hc_venner", "Hm_venner", "Hc_dpdx0", "p_spike",
                                          "X_Hm", "Y_Hm", "load_error", "final_residual", "work_units",
                                          "cycles", "converged", "message", "levels")})
        row["actions"] = res.meta.get("actions", [])
        row["status"] = "converged" if s["converged"] else "not_converged"
    except ConvergenceError as exc:
        row.update(status="error", converged=False, message=str(exc))
    except InputError as exc:
        row.update(status="input_error", converged=False, message=str(exc))
    row["wall_s"] = time.perf_counter() - t0
    row["load_after"] = load_avg()
    return row


class Store:
    """``{key: row}`` JSON file, rewritten atomically after every case."""

    def __init__(self, name: str) -> None:
        self.path = OUT / name
        self.data = json.loads(self.path.read_text()) if self.path.exists() else {}

    def __contains__(self, key: str) -> bool:
        return key in self.data

    def put(self, key: str, row: dict) -> None:
        self.data[key] = _clean(row)
        tmp = self.path.with_suffix(".tmp")
        tmp.write_text(json.dumps(self.data, separators=(",", ":")))
        os.replace(tmp, self.path)


def _clean(o):
    if isinstance(o, dict):
        return {k: _clean(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_clean(v) for v in o]
    if isinstance(o, float) and not math.isfinite(o):
        return None
    if hasattr(o, "item"):
        return _clean(o.item())
    return o


def richardson(h: list[float]) -> tuple[float, float]:
    """Observed order and extrapolated value from the last three values of a sequence on
    grids refined by 2 (NaN when the differences do not shrink monotonically)."""
    if len(h) < 3 or any(v is None for v in h[-3:]):
        return math.nan, math.nan
    a, b, c = h[-3:]
    d1, d2 = b - a, c - b
    if d2 == 0 or d1 == 0 or d1 * d2 < 0 or abs(d2) >= abs(d1):
        return math.nan, c + d2 / 3.0 if d2 else c
    p = math.log2(abs(d1 / d2))
    return p, c + d2 / (2**p - 1)


def plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as _plt

    return _plt
