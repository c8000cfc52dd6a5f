"""Behaviour fingerprint of every physics through the front door: what a refactor must reproduce.

Solves a fixed set of small steady (accuracy-driven), starved, thermal and transient cases with
``ehl_multigrid.solve`` and writes their films, stated errors, work, statuses and a digest of
every field to JSON, so two versions of the code can be compared number by number::

    python validation/core/fingerprint_physics.py build/validation/core/physics_before.json
    python validation/core/fingerprint_physics.py build/validation/core/physics_after.json
    python validation/core/fingerprint_physics.py --compare build/validation/core/physics_before.json \
        build/validation/core/physics_after.json

``--only NAME`` runs the cases whose name contains NAME. The steady fixed-grid solves are in
``fingerprint.py``.
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import math
import sys
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np


def _scene(name: str, **tables: Any) -> Any:
    from ehl_multigrid import Scene, load_scene

    d = load_scene(name).to_dict()
    for key, table in tables.items():
        if key == "load_factor":
            d["operating"]["load"] *= table
        else:
            d[key] = table
    return Scene.from_dict(d)


def _cases() -> list[tuple[str, Any, dict[str, Any]]]:
    from ehl_multigrid import MoesProblem

    dent = {"kind": "dent", "amplitude": 5e-9, "width": 2e-5, "x0": -2.5}
    bump = {"kind": "bump", "amplitude": 1e-8, "width": 1e-5, "x0": -3.0}
    return [
        ("steady_line_20_10_acc", MoesProblem("line", M=20, L=10), dict(accuracy=0.01)),
        ("steady_line_1000_10_acc", MoesProblem("line", M=1000, L=10), dict(accuracy=0.005)),
        ("steady_point_20_10_acc", MoesProblem("point", M=20, L=10), dict(accuracy=0.02)),
        ("steady_elliptic_20_10_4_acc", MoesProblem("elliptic", M=20, L=10, theta=4.0), dict(accuracy=0.05)),
        ("starved_line_257", _scene("page63_line_500N", supply={"hoil": 1.5e-8}),
         dict(options={"points": 257})),
        ("starved_line_acc", _scene("page63_line_500N", supply={"hoil": 1.5e-8}), dict(accuracy=0.01)),
        ("starved_point_65", _scene("default", supply={"hoil": 5e-8}), dict(options={"points": 65})),
        ("starved_point_acc", _scene("default", supply={"hoil": 5e-8}), dict(accuracy=0.02)),
        ("thermal_line_129", "appendix_c_line_4240N",
         dict(physics="thermal", options={"points": 129, "nz": 8, "slip": 0.5})),
        ("thermal_line_starved_129", _scene("appendix_c_line_4240N", supply={"hoil": 2e-7}),
         dict(physics="thermal", options={"points": 129, "nz": 8, "slip": 0.5})),
        ("thermal_point_129", "default", dict(physics="thermal", options={"points": 129, "nz": 8})),
        ("transient_line_bump", _scene("page63_line_2000N", feature=bump),
         dict(physics="transient", accuracy=None, options={"points": 129, "steps": 5})),
        ("transient_line_bump_mc", _scene("page63_line_2000N", feature=bump),
         dict(physics="transient", accuracy=None,
              options={"points": 129, "steps": 5, "cavitation": "mass-conserving"})),
        ("transient_line_time_error", _scene("page63_line_2000N", feature=bump),
         dict(physics="transient", accuracy=None, options={"points": 129, "steps": 4, "dt": 0.0014,
                                                            "time_error": True})),
        ("transient_point_dent", _scene("default", feature=dent),
         dict(physics="transient", accuracy=None, options={"points": 65, "steps": 2})),
        ("transient_point_dent_mc", _scene("default", feature=dent),
         dict(physics="transient", accuracy=None, options={"points": 65, "steps": 2,
                                                            "cavitation": "mass-conserving"})),
    ]


def _digest(a: np.ndarray) -> dict[str, Any]:
    a = np.ascontiguousarray(np.asarray(a, dtype=float))
    finite = a[np.isfinite(a)]
    return {"sha1": hashlib.sha1(a.tobytes()).hexdigest()[:16], "shape": list(a.shape),
            "sum": float(finite.sum()) if finite.size else math.nan,
            "max": float(finite.max()) if finite.size else math.nan}


def _plain(v: Any) -> Any:
    if isinstance(v, (np.floating, float)):
        return float(v)
    if isinstance(v, (np.integer, int)) and not isinstance(v, bool):
        return int(v)
    if isinstance(v, np.ndarray):
        return _digest(v)
    if isinstance(v, (tuple, list)):
        return [_plain(x) for x in v]
    if isinstance(v, Mapping):
        return {str(k): _plain(x) for k, x in v.items()}
    if dataclasses.is_dataclass(v) and not isinstance(v, type):
        return {f.name: _plain(getattr(v, f.name)) for f in dataclasses.fields(v)}
    return v if isinstance(v, (bool, str, type(None))) else repr(v)


def _record(sol: Any) -> dict[str, Any]:
    out: dict[str, Any] = {
        "status": sol.status.label, "success": bool(sol.success), "Hc": float(sol.Hc), "Hm": float(sol.Hm),
        "error_Hc": float(sol.error.Hc), "error_Hm": float(sol.error.Hm),
        "parts": {k: [float(p.Hc), float(p.Hm)] for k, p in sol.error.parts.items()},
        "work_units": float(sol.outcome.work_units), "iterations": int(sol.outcome.iterations),
        "actions": list(sol.outcome.actions),
        "grid": _plain(sol.grid),
        "fields": {k: _digest(v) for k, v in sorted(sol.fields.items())},
    }
    if sol.details is not None:
        out["details"] = _plain(sol.details)
    return out


def run(only: str | None = None) -> dict[str, Any]:
    import ehl_multigrid as ehl

    out: dict[str, Any] = {}
    for name, problem, kw in _cases():
        if only and only not in name:
            continue
        t0 = time.perf_counter()
        sol = ehl.solve(problem, **kw)
        out[name] = _record(sol)
        out[name]["wall_s"] = time.perf_counter() - t0
        print(f"{name:30s} {out[name]['status']:12s} Hc {out[name]['Hc']:.10g} Hm {out[name]['Hm']:.10g} "
              f"t {out[name]['wall_s']:.2f}s", file=sys.stderr, flush=True)
    return out


def _differences(a: Any, b: Any, path: str) -> list[str]:
    if isinstance(a, dict) and isinstance(b, dict):
        diffs = []
        for k in sorted(set(a) | set(b)):
            if k == "wall_s" or k.endswith("_s"):
                continue
            if k not in a or k not in b:
                diffs.append(f"{path}.{k}: only in {'second' if k in b else 'first'}")
                continue
            diffs += _differences(a[k], b[k], f"{path}.{k}")
        return diffs
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for i, (x, y) in enumerate(zip(a, b, strict=True)) for d in _differences(x, y, f"{path}[{i}]")]
    if isinstance(a, float) and isinstance(b, float):
        if (math.isnan(a) and math.isnan(b)) or a == b:
            return []
        return [f"{path}: {a!r} -> {b!r} (rel {abs(a - b) / max(abs(a), 1e-300):.2e})"]
    return [] if a == b else [f"{path}: {a!r} -> {b!r}"]


def compare(a: dict[str, Any], b: dict[str, Any]) -> int:
    """Print every difference between two fingerprints (wall times ignored); exit 1 if any."""
    diffs = _differences(a, b, "")
    for d in diffs:
        print(d)
    print(f"{len(diffs)} differences over {len(a)} cases")
    return 1 if diffs else 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?")
    ap.add_argument("--only")
    ap.add_argument("--compare", nargs=2, metavar=("BEFORE", "AFTER"))
    args = ap.parse_args(argv)
    if args.compare:
        a, b = (json.loads(Path(p).read_text()) for p in args.compare)
        return compare(a, b)
    if not args.out:
        ap.error("give the output JSON path or --compare BEFORE AFTER")
    res = run(args.only)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(args.out).with_suffix(".tmp")
    tmp.write_text(json.dumps(res, indent=1))
    tmp.replace(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
