"""Accuracy against cost: for each model, the error against a reference
resolution versus wall time, across its resolution knobs; Pareto front per model and the
recommended settings per fidelity level (cheapest setting whose error is within the fidelity's
tolerance: fast 10 %, standard 2 %, reference 0.2 %).

Each setting is run on a small set of operating points and its error is the LARGEST relative
error over them (one operating point alone lets errors of opposite sign cancel by luck: 3 slices
on a 20 x 5 grid matched the reference traction to 0.08 % at one slip with a 0.9 % slice error).
Wall times are per operating point.

Models and knobs
  line_ehl   Moes (M, L) = (20, 10), (100, 10), (500, 10), Roelands + Dowson-Higginson; points,
             V/W, MLMI/FFT; film fit
  point_ehl  (M, L) = (20, 10), (100, 10); points, V/W, MLMI/FFT; film fit
  traction   appendix C 42400 N and appendix D at slips 0.02, 0.3, 1: nx, nz (slices); input
             Hertz + fit or EHL film; isothermal model
  stribeck   page-63 line contact 2000 N at us = 0.1, 0.3, 1 m/s (mixed regime) and series D
             disc 3 at 0.3, 1, 3 m/s: isothermal vs thermal film friction, thermal nx x nz

Usage: python validation/pareto/pareto.py [--quick] [--models line_ehl,point_ehl,traction,stribeck]
Writes build/validation/pareto/pareto[_quick].json, build/validation/pareto/pareto_<model>.png and build/validation/pareto/recommended[_quick].json;
finished settings are kept (resume). Each setting is timed after one warm-up solve, so numba
compilation is excluded.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("pareto")
FIDELITY_TOL = {"fast": 0.1, "standard": 0.02, "reference": 0.002}


def timed(fn: Callable[[], list[float]], repeats: int = 1) -> tuple[list[float], float]:
    """Values and the best wall time per operating point over ``repeats`` runs."""
    best = math.inf
    val: list[float] = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        val = fn()
        best = min(best, (time.perf_counter() - t0) / max(len(val), 1))
    return val, best


def max_rel_error(val: list[float], ref: list[float]) -> float:
    return max(abs(v - r) / abs(r) for v, r in zip(val, ref, strict=True))


# -- line EHL ----------------------------------------------------------------------------------
def line_settings(quick: bool) -> tuple[dict, list[dict]]:
    pts = [257, 513, 1025, 2049, 4097] if quick else [257, 513, 1025, 2049, 4097, 8193]
    ref = {"points": 8193 if quick else 16385, "cycle": "V", "deformation": "fft"}
    sets = [{"points": n, "cycle": c, "deformation": d} for n in pts for c in ("V", "W") for d in ("mlmi", "fft")]
    return ref, sets + [{"film": "fit"}]


LINE_CASES = ((20.0, 10.0), (100.0, 10.0), (500.0, 10.0))
POINT_CASES = ((20.0, 10.0), (100.0, 10.0))


def line_run(s: dict) -> list[float]:
    if s.get("film") == "fit":
        from ehl_multigrid.model.fits import moes_line_central

        return [float(moes_line_central(M, L)) for M, L in LINE_CASES]
    from ehl_multigrid.line import solve_line

    out = []
    for M, L in LINE_CASES:
        sol = solve_line(M, L, **s)
        if not sol.converged:
            raise RuntimeError(f"line solve not converged for {s} at (M, L) = ({M:g}, {L:g})")
        out.append(float(sol.Hc))
    return out


# -- point EHL ---------------------------------------------------------------------------------
def point_settings(quick: bool) -> tuple[dict, list[dict]]:
    pts = [65, 129, 257] if quick else [65, 129, 257, 513]
    ref = {"points": 513 if quick else 1025, "cycle": "V", "deformation": "fft"}
    sets = [{"points": n, "cycle": c, "deformation": d} for n in pts for c in ("V", "W") for d in ("mlmi", "fft")]
    return ref, sets + [{"film": "fit"}]


def point_run(s: dict) -> list[float]:
    if s.get("film") == "fit":
        from ehl_multigrid.model.fits import nijenbanning_central

        return [float(nijenbanning_central(M, L)) for M, L in POINT_CASES]
    from ehl_multigrid.point import solve_point

    out = []
    for M, L in POINT_CASES:
        sol = solve_point(M, L, **s)
        if not sol.converged:
            raise RuntimeError(f"point solve not converged for {s} at (M, L) = ({M:g}, {L:g})")
        out.append(float(sol.Hc))
    return out


# -- thermal traction --------------------------------------------------------------------------
def traction_settings(quick: bool) -> tuple[dict, list[dict]]:
    grid = [(20, 5), (40, 10), (80, 20), (160, 40)] if not quick else [(20, 5), (40, 10), (80, 20)]
    sets = []
    for scene in ("appendix_c_line_42400N", "appendix_d_point"):
        for nx, nz in grid:
            for sl in ((3, 5, 10) if scene == "appendix_d_point" else (0,)):
                sets.append({"scene": scene, "nx": nx, "nz": nz, "slices": sl})
        sets.append({"scene": scene, "nx": 80, "nz": 20, "slices": 10, "thermal": False})
        sets.append({"scene": scene, "nx": 80, "nz": 20, "slices": 10, "input": "ehl"})
    ref = {"nx": 320 if not quick else 160, "nz": 80 if not quick else 40, "slices": 20}
    return ref, sets


_EHL_CACHE: dict[str, Any] = {}


TRACTION_SLIPS = (0.02, 0.3, 1.0)


def traction_run(s: dict) -> list[float]:
    from ehl_multigrid.model.scene import load_scene
    from thermal.traction import solve_traction

    s = dict(s)
    scene = load_scene(s.pop("scene"))
    slices = s.pop("slices")
    if scene.kind != "line":
        s["slices"] = slices
    if s.pop("input", "hertz") == "ehl":
        key = scene.name
        if key not in _EHL_CACHE:
            if scene.kind == "line":
                from ehl_multigrid.line import solve_line

                _EHL_CACHE[key] = solve_line(scene=scene, points=4097).to_result(scene)
            else:
                from ehl_multigrid.point import solve_point

                _EHL_CACHE[key] = solve_point(scene=scene, points=257).to_result(scene)
        return [float(solve_traction(scene, sl, input="ehl", ehl=_EHL_CACHE[key], **s).coefficient)
                for sl in TRACTION_SLIPS]
    return [float(solve_traction(scene, sl, **s).coefficient) for sl in TRACTION_SLIPS]


# -- Stribeck point ----------------------------------------------------------------------------
def stribeck_settings(quick: bool) -> tuple[dict, list[dict]]:
    sets = []
    for scene, us in (("page63_line_2000N", (0.1, 0.3, 1.0)), ("series_D_disc3_1.93GPa", (0.3, 1.0, 3.0))):
        sets.append({"scene": scene, "us": us, "thermal": False})
        for nx, nz in ((20, 5), (40, 10), (80, 20)):
            sets.append({"scene": scene, "us": us, "thermal": True, "nx": nx, "nz": nz})
    ref = {"thermal": True, "nx": 160, "nz": 40}
    return ref, sets


def stribeck_run(s: dict) -> list[float]:
    import numpy as np

    from ehl_multigrid.model.scene import load_scene
    from mixed.stribeck import stribeck_curve

    scene = load_scene(s["scene"])
    topts = {k: s[k] for k in ("nx", "nz") if k in s}
    c = stribeck_curve(scene, np.array(s["us"], dtype=float), thermal=s["thermal"], thermal_options=topts or None,
                       transitions=False)
    return [float(f) for f in c.friction.coefficient]


MODELS = {
    "line_ehl": (line_settings, line_run, None),
    "point_ehl": (point_settings, point_run, None),
    "traction": (traction_settings, traction_run, ("scene",)),
    "stribeck": (stribeck_settings, stribeck_run, ("scene", "us")),
}


def key(d: dict) -> str:
    return json.dumps(d, sort_keys=True)


def run_model(name: str, quick: bool, store: dict) -> None:
    settings_fn, run, group_keys = MODELS[name]
    ref_over, settings = settings_fn(quick)
    rec = store.setdefault(name, {"rows": {}, "refs": {}})
    from tqdm import tqdm

    for s in tqdm(settings, desc=name, unit="setting"):
        k = key(s)
        if k in rec["rows"]:
            continue
        group = {g: s[g] for g in group_keys} if group_keys else {}
        gk = key(group)
        if gk not in rec["refs"]:
            ref_setting = {**group, **ref_over}
            run(ref_setting)  # warm-up (compilation)
            val, wall = timed(lambda rs=ref_setting: run(rs))
            rec["refs"][gk] = {"setting": ref_setting, "value": val, "wall_s": wall}
        try:
            run(s)  # warm-up
            val, wall = timed(lambda s=s: run(s))
            ref = rec["refs"][gk]["value"]
            rec["rows"][k] = {"setting": s, "group": group, "value": val, "wall_s": wall,
                              "error": max_rel_error(val, ref), "load_avg": os.getloadavg()[0]}
        except Exception as exc:  # recorded, not hidden
            rec["rows"][k] = {"setting": s, "group": group, "error_message": f"{type(exc).__name__}: {exc}"}
        save(store, quick)


def pareto_front(rows: list[dict]) -> list[dict]:
    ok = sorted((r for r in rows if "error" in r), key=lambda r: (r["wall_s"], r["error"]))
    front, best = [], math.inf
    for r in ok:
        if r["error"] < best:
            front.append(r)
            best = r["error"]
    return front


def recommend(store: dict) -> dict:
    out: dict[str, Any] = {}
    for name, rec in store.items():
        groups: dict[str, list[dict]] = {}
        for r in rec["rows"].values():
            groups.setdefault(key(r.get("group", {})), []).append(r)
        out[name] = {}
        for gk, rows in groups.items():
            sel = {}
            for fid, tol in FIDELITY_TOL.items():
                ok = [r for r in rows if "error" in r and r["error"] <= tol]
                best = min(ok, key=lambda r: r["wall_s"]) if ok else None
                sel[fid] = None if best is None else {"setting": best["setting"], "error": best["error"], "wall_s": best["wall_s"]}
            out[name][gk] = sel
    return out


def save(store: dict, quick: bool) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    sfx = "_quick" if quick else ""
    tmp = OUT / f".pareto{sfx}.tmp"
    tmp.write_text(json.dumps(store, indent=1))
    tmp.replace(OUT / f"pareto{sfx}.json")
    (OUT / f"recommended{sfx}.json").write_text(json.dumps(recommend(store), indent=1))


def plot(store: dict, quick: bool) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    for name, rec in store.items():
        rows = [r for r in rec["rows"].values() if "error" in r]
        if not rows:
            continue
        fig, ax = plt.subplots(figsize=(6.5, 4.2))
        groups: dict[str, list[dict]] = {}
        for r in rows:
            groups.setdefault(key(r.get("group", {})), []).append(r)
        for i, (gk, rs) in enumerate(groups.items()):
            lab = ", ".join(str(v) for v in json.loads(gk).values()) or name
            ax.loglog([r["wall_s"] for r in rs], [max(r["error"], 1e-7) for r in rs], "o", color=f"C{i}", alpha=0.5, label=lab)
            fr = pareto_front(rs)
            ax.loglog([r["wall_s"] for r in fr], [max(r["error"], 1e-7) for r in fr], "-", color=f"C{i}")
        for fid, tol in FIDELITY_TOL.items():
            ax.axhline(tol, color="0.6", lw=0.8, ls=":")
            ax.text(ax.get_xlim()[0], tol, f" {fid}", va="bottom", fontsize=7, color="0.4")
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("relative error vs reference")
        ax.set_title(f"{name}: error against cost (line = Pareto front)")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(OUT / f"pareto_{name}{'_quick' if quick else ''}.png", dpi=100)
        plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--models", default=",".join(MODELS))
    args = ap.parse_args()
    path = OUT / f"pareto{'_quick' if args.quick else ''}.json"
    store = json.loads(path.read_text()) if path.exists() else {}
    for m in args.models.split(","):
        run_model(m, args.quick, store)
    save(store, args.quick)
    plot(store, args.quick)
    print(json.dumps(recommend(store), indent=1))


if __name__ == "__main__":
    main()
