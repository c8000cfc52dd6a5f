"""Shared helpers of the thermal validation scripts: output folder, compact JSON, Richardson
extrapolation, the EHL line solution used as 'EHL input'."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from _paths import out_dir  # noqa: E402

OUT = out_dir("thermal")
CACHE = Path("/tmp/ehl_thermal_validation_cache")


def quick_flag() -> bool:
    """``--quick``: fewer points / coarser grids (smoke run)."""
    return "--quick" in sys.argv


def rounded(obj: Any, sig: int = 7) -> Any:
    if isinstance(obj, dict):
        return {k: rounded(v, sig) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [rounded(v, sig) for v in obj]
    if isinstance(obj, np.ndarray):
        return rounded(obj.tolist(), sig)
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer, int)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        f = float(obj)
        if not math.isfinite(f):
            return None
        return float(f"{f:.{sig}g}")
    return obj


def write_json(name: str, data: dict) -> Path:
    path = OUT / name
    path.write_text(json.dumps(rounded(data), separators=(",", ":")))
    print(f"wrote {path}")
    return path


def richardson(h: list[float], f: list[float]) -> dict[str, float]:
    """Observed order and extrapolated value from the three finest of a sequence with constant
    refinement ratio (h = mesh size)."""
    h1, h2, h3 = h[-3:]
    f1, f2, f3 = f[-3:]
    r = h1 / h2
    d12, d23 = f1 - f2, f2 - f3
    if d23 == 0 or d12 == 0 or np.sign(d12) != np.sign(d23):
        return {"order": math.nan, "extrapolated": f3, "ratio": r, "monotone": False}
    p = math.log(d12 / d23) / math.log(r)
    ext = f3 + d23 / (r**p - 1.0)
    return {"order": p, "extrapolated": ext, "ratio": r, "monotone": True}


def richardson_resolved(h: list[float], f: list[float], noise: float = 1e-5) -> dict[str, Any]:
    """Richardson on the finest triple whose successive differences are monotone and above
    ``noise`` (relative): once the discretization error reaches the 1e-6 level the differences
    stop being meaningful. Also lists the order of every consecutive triple."""
    orders = [richardson(h[i:i + 3], f[i:i + 3])["order"] for i in range(len(f) - 2)]
    best = None
    for i in range(len(f) - 3, -1, -1):
        d1, d2 = f[i] - f[i + 1], f[i + 1] - f[i + 2]
        if abs(d2) > noise * abs(f[i + 2]) and abs(d1) > noise * abs(f[i + 2]) and np.sign(d1) == np.sign(d2):
            best = i
            break
    if best is None:
        out = {"order": math.nan, "extrapolated": f[-1], "monotone": False, "triple": None}
    else:
        out = richardson(h[best:best + 3], f[best:best + 3])
        out["triple"] = [best, best + 1, best + 2]
    out["triple_orders"] = orders
    out["finest"] = f[-1]
    return out


def ehl_line_result(scene, xmin: float = -2.5, xmax: float = 1.5):
    """EHL line solution of ``scene`` (ehl_multigrid.line), cached on disk; None if unavailable."""
    from ehl_multigrid.model.results import Result

    CACHE.mkdir(exist_ok=True)
    path = CACHE / f"ehl_{scene.name}_{scene.load:g}_{scene.us:g}_{scene.T_oil:g}_{scene.lubricant.name}_{xmin:g}_{xmax:g}.h5"
    if path.exists():
        return Result.load(path)
    try:
        from ehl_multigrid.line.solver import solve_line
    except ImportError:
        return None
    from ehl_multigrid.model.errors import ConvergenceError

    try:
        sol = solve_line(scene=scene, xmin=xmin, xmax=xmax)
    except ConvergenceError as exc:
        print(f"EHL line solve of {scene.name} (X in [{xmin}, {xmax}]) failed: {exc}")
        return None
    if not sol.report.converged:
        print(f"EHL line solve of {scene.name} did not converge: {sol.report.message}")
        return None
    res = sol.to_result()
    res.save(path)
    return res


def plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as p

    return p
