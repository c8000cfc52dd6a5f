"""Behaviour fingerprint of the EHL solvers: every scalar a refactor must reproduce.

Runs a fixed set of line and point solves and writes their films, work and cycle counts to
JSON, so two versions of the code can be compared number by number::

    python validation/core/fingerprint.py build/validation/core/before.json
    python validation/core/fingerprint.py build/validation/core/after.json
    python validation/core/fingerprint.py --compare build/validation/core/before.json build/validation/core/after.json
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

LINE_CASES = [
    ("line_20_10_1025", dict(M=20.0, L=10.0, points=1025)),
    ("line_20_10_1025_W", dict(M=20.0, L=10.0, points=1025, cycle="W")),
    ("line_20_10_513_fft", dict(M=20.0, L=10.0, points=513, deformation="fft")),
    ("line_100_10_1025", dict(M=100.0, L=10.0, points=1025)),
    ("line_5_2_513", dict(M=5.0, L=2.0, points=513)),
    ("line_1000_10_2049", dict(M=1000.0, L=10.0, points=2049)),
    ("line_barus_20_10_513", dict(M=20.0, L=10.0, points=513, viscosity="barus", density="incompressible")),
    ("line_rigid_10_0_513", dict(M=10.0, L=0.0, points=513, elastic=False)),
]
POINT_CASES = [
    ("point_20_10_129", dict(M=20.0, L=10.0, points=129)),
    ("point_20_10_257", dict(M=20.0, L=10.0, points=257)),
    ("point_20_10_513", dict(M=20.0, L=10.0, points=513)),
    ("point_20_10_257_half", dict(M=20.0, L=10.0, points=257, half=True)),
    ("point_20_10_129_V_mlmi", dict(M=20.0, L=10.0, points=129, cycle="V", deformation="mlmi")),
    ("point_100_10_257", dict(M=100.0, L=10.0, points=257)),
    ("point_200_20_257", dict(M=200.0, L=20.0, points=257)),
    ("point_5_0_129", dict(M=5.0, L=0.0, points=129)),
    ("point_ellipse_0.5_129", dict(M=20.0, L=10.0, theta=0.5, points=129)),
    ("point_ellipse_4_257", dict(M=20.0, L=10.0, theta=4.0, points=257)),
    ("point_barus_20_10_129", dict(M=20.0, L=10.0, points=129, viscosity="barus", density="incompressible")),
    ("point_rigid_10_0_129", dict(M=10.0, L=0.0, points=129, rigid=True)),
    ("point_newton_20_10_65", dict(M=20.0, L=10.0, points=65, solver="newton")),
]


def _scalars(sol) -> dict:
    rep = sol.report
    out = {k: sol.scalars.get(k) for k in ("Hc", "Hm", "Hc_venner", "Hm_venner", "p_spike", "load_error")}
    out.update(converged=bool(rep.converged), work_units=float(rep.work_units),
               iterations=int(rep.iterations), n_residuals=int(len(rep.residual_history)),
               final_residual=float(rep.residual_history[-1]) if len(rep.residual_history) else None,
               actions=list(rep.extra.get("actions", [])), wall_s=float(rep.wall_s))
    return {k: (float(v) if isinstance(v, (np.floating, float)) else v) for k, v in out.items()}


def run(only: str | None = None) -> dict:
    import inspect

    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    if "estimate" not in inspect.signature(solve_line).parameters:  # the code before the change
        def strip(f):
            return lambda estimate=None, **kw: f(**kw)
        solve_line, solve_point = strip(solve_line), strip(solve_point)
    out = {}
    for name, kw in LINE_CASES + POINT_CASES:
        if only and only not in name:
            continue
        fn = solve_line if name.startswith("line") else solve_point
        kw = dict(kw)
        if fn is solve_line:
            kw.setdefault("raise_on_failure", False)
        if kw.get("solver") != "newton":
            kw["estimate"] = False  # the same single solve as before the error estimates existed
        t0 = time.perf_counter()
        sol = fn(**kw)
        out[name] = _scalars(sol)
        out[name]["process_wall_s"] = time.perf_counter() - t0
        print(f"{name:28s} Hc {out[name]['Hc']:.10g} conv {out[name]['converged']} "
              f"WU {out[name]['work_units']:.2f} t {out[name]['process_wall_s']:.2f}s", flush=True)
    return out


def compare(a: dict, b: dict) -> int:
    worst = 0.0
    for name in a:
        if name not in b:
            print(f"{name}: missing in the second file")
            continue
        for k in ("Hc", "Hm", "p_spike", "load_error", "work_units", "n_residuals", "converged"):
            va, vb = a[name].get(k), b[name].get(k)
            if isinstance(va, float) and isinstance(vb, float):
                if np.isnan(va) and np.isnan(vb):
                    continue
                rel = abs(va - vb) / max(abs(va), 1e-300)
                if k in ("Hc", "Hm"):
                    worst = max(worst, rel)
                if rel > 1e-12:
                    print(f"{name:28s} {k:12s} {va!r:>24} -> {vb!r:<24} rel {rel:.2e}")
            elif va != vb:
                print(f"{name:28s} {k:12s} {va!r:>24} -> {vb!r:<24}")
    print(f"largest relative change in Hc or Hm: {worst:.3e}")
    return 0


if __name__ == "__main__":
    if sys.argv[1] == "--compare":
        sys.exit(compare(json.loads(Path(sys.argv[2]).read_text()), json.loads(Path(sys.argv[3]).read_text())))
    res = run(sys.argv[2] if len(sys.argv) > 2 else None)
    Path(sys.argv[1]).parent.mkdir(parents=True, exist_ok=True)
    Path(sys.argv[1]).write_text(json.dumps(res, indent=1))
