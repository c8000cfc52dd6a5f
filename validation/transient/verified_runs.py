"""Verified transient films: `ehl transient SCENE --json --no-plots` at its default accuracy on
real contacts with a dent, each in a fresh process, and (``--check``) the largest difference of
its film series from a run on twice the points at half the step (docs/transient.md, "What a
run's films are worth").

    python validation/transient/verified_runs.py                       # every case
    python validation/transient/verified_runs.py --cases p63_500 --check

writes build/validation/transient/verified_runs.json (one record per case: exit code, wall,
status, grid, step, the stated parts and, with --check, the difference from the finer run). A
case is a built-in scene with a ``[feature]`` table added; its scene file is written beside the
output.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = Path(out_dir("transient"))

#: name -> (built-in scene, [feature] table, operating changes)
CASES: dict[str, tuple[str, dict[str, Any], dict[str, Any]]] = {
    "p63_500": ("page63_line_500N", {"kind": "dent", "amplitude": 3e-9, "width": 1e-4, "x0": -1.5}, {}),
    "p63_2000": ("page63_line_2000N", {"kind": "dent", "amplitude": 1e-8, "width": 1e-4, "x0": -1.5}, {}),
    "gear": ("spur_gear_pitch_point", {"kind": "dent", "amplitude": 1e-6, "width": 5e-5, "x0": -2.5}, {}),
    "tribometer": ("ball_on_disc_tribometer",
                   {"kind": "dent", "amplitude": 5e-7, "width": 5e-5, "x0": -2.5, "y0": 0.0}, {}),
}


def scene_file(name: str) -> Path:
    from ehl_multigrid import Scene, load_scene

    base, feature, operating = CASES[name]
    d = load_scene(base).to_dict()
    d["feature"] = dict(feature)
    d["operating"].update(operating)
    path = OUT / f"{name}.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    return path


def run_case(name: str, check: bool, timeout: float) -> dict[str, Any]:
    path = scene_file(name)
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "ehl_multigrid", "transient", str(path), "--json", "--no-plots",
                        "--out", str(OUT / name)], capture_output=True, text=True, timeout=timeout)
    rec: dict[str, Any] = {"case": name, "exit": p.returncode, "wall_s": time.perf_counter() - t0,
                           "load": os.getloadavg()[0]}
    try:
        d = json.loads(p.stdout)
    except json.JSONDecodeError:
        rec["stderr"] = p.stderr[-2000:]
        return rec
    rec.update({k: d.get(k) for k in ("status", "message", "points", "points_y", "dt", "steps", "films_error",
                                      "hm_min", "hc_min")})
    if check and d.get("status") in ("converged", "inaccurate"):
        rec["check"] = finer_difference(path, d)
    return rec


def finer_difference(path: Path, d: dict[str, Any]) -> dict[str, Any]:
    """The largest relative difference of Hc(T), Hm(T) of the run in ``d`` from the same run on
    twice the points at half the step, on the answer's box (relative to the smooth film)."""
    import numpy as np

    import ehl_multigrid as ehl
    from ehl_multigrid.transient import load_series

    ans = load_series(d["hdf5"])
    n, dt = 2 * (d["points"] - 1) + 1, d["dt"] / 2
    t0 = time.perf_counter()
    ref = ehl.solve(str(path), physics="transient", accuracy=None,
                    options={"points": n, "dt": dt, "steps": 2 * d["planned_steps"],
                             "xmin": float(ans["X"][0])})
    out: dict[str, Any] = {"points": n, "dt": dt, "status": ref.status.label, "wall_s": time.perf_counter() - t0}
    if ref.success:
        for name in ("Hc", "Hm"):
            a = np.asarray(ans["series"][name], dtype=float)
            r = np.asarray(getattr(ref.raw, name), dtype=float)[::2]
            if r.size != a.size:
                raise RuntimeError(f"the reference has {r.size} time levels at the answer's, not {a.size}")
            out[name] = float(np.max(np.abs(a - r)) / ref.raw.steady_film(name))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", nargs="*", default=list(CASES), choices=list(CASES))
    ap.add_argument("--check", action="store_true", help="also run each on twice the points at half the step")
    ap.add_argument("--timeout", type=float, default=1800.0, help="seconds per case")
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    records = []
    for name in args.cases:
        rec = run_case(name, args.check, args.timeout)
        records.append(rec)
        fe = rec.get("films_error") or {}
        print(f"{name}: exit {rec['exit']}, {rec['wall_s']:.1f} s, {rec.get('status')}, {rec.get('points')} points, "
              f"dT {rec.get('dt')}, stated Hc {fe.get('Hc', math.nan):.3g} Hm {fe.get('Hm', math.nan):.3g}"
              + (f", check {rec['check']}" if "check" in rec else ""), file=sys.stderr, flush=True)
        tmp = OUT / "verified_runs.json.tmp"
        tmp.write_text(json.dumps(records, indent=1))
        tmp.replace(OUT / "verified_runs.json")


if __name__ == "__main__":
    main()
