"""Supply profile across the track: side ridges left by the previous over-rolling.

Run: ``python validation/starved/study_ridges.py [--quick]``. Writes build/validation/starved/starved_ridges.json and
build/validation/starved/starved_ridges.png. Circular contact (M, L) = (20, 10), half domain, Roelands +
Dowson-Higginson, the point core's default box (Y in [0, 3]).

The over-rolled track (``|Y| < 1``, the Hertzian width) carries a layer ``h_in``; ridges beside
it carry ``k h_in``. Compared, on the same grid:

* the ridge profile;
* a uniform supply ``h_in`` (the track alone);
* a uniform supply with the ridge profile's mean over the box width (the rows of the mass
  balance), i.e. the same oil spread evenly.

Checks independent of the profile path: the uniform profile given as an array reproduces the
scalar supply bit for bit; every solve reports its mass imbalance.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.starved.point import StarvedPointHierarchy, solve_starved_point

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("starved")
M, L = 20.0, 10.0
#: track layer as a fraction of the flooded central film; ridge height over the track layer
CASES = [(0.25, 3.0, 1.0, 3.0), (0.25, 3.0, 0.8, 1.4), (0.6, 3.0, 1.0, 3.0)]


def grid_rows(points: int) -> np.ndarray:
    pb = problem_from_moes(M, L)
    opt = PointOptions.build(None, points=points, half=True, wedge_order=1)
    return StarvedPointHierarchy(pb, opt, 1.0).levels[-1].Y


def record(s) -> dict:
    e = s.extra
    return {"status": s.status_name, "hoil_mean": e["hoil"], "hoil_centre": e["hoil_centre"],
            "Hc": s.scalars["Hc_venner"], "Hm": s.scalars["Hm_venner"], "meniscus_x": e["meniscus_x"],
            "mass_balance_error": e["mass_balance_error"],
            "side_over_in": e["fluxes"]["side"] / e["fluxes"]["in"], "cycles": len(s.residual_history)}


def run(points: int) -> dict:
    pb = problem_from_moes(M, L)
    kw = dict(points=points, half=True, raise_on_failure=False)
    ff = solve_starved_point(pb, float("inf"), **kw)
    Hff = ff.scalars["Hc_venner"]
    Y = grid_rows(points)
    out = {"points": points, "Hc_ff": Hff, "Hm_ff": ff.scalars["Hm_venner"], "cases": []}
    for frac, k, y0, y1 in CASES:
        h_in = frac * Hff
        prof = np.where((np.abs(Y) >= y0) & (np.abs(Y) <= y1), k * h_in, h_in)
        scalar = solve_starved_point(pb, h_in, **kw)
        as_array = solve_starved_point(pb, np.full(Y.size, h_in), **kw)
        ridge = solve_starved_point(pb, prof, **kw)
        same_mean = solve_starved_point(pb, ridge.extra["hoil"], **kw)
        c = {"h_in_over_Hc_ff": frac, "ridge_factor": k, "ridge_Y": [y0, y1],
             "uniform_array_equals_scalar": bool(np.array_equal(scalar.P, as_array.P)),
             "track_only": record(scalar), "ridges": record(ridge), "uniform_same_mean": record(same_mean)}
        for key in ("track_only", "ridges", "uniform_same_mean"):
            c[key]["Hc_over_Hc_ff"] = c[key]["Hc"] / Hff
            c[key]["Hm_over_Hm_ff"] = c[key]["Hm"] / out["Hm_ff"]
        c["theta_ridges"] = np.round(ridge.extra["theta"], 4).tolist() if points <= 129 else None
        out["cases"].append(c)
        print(f"n {points} h_in {frac:g} Hc_ff, ridges {k:g}x at {y0:g}-{y1:g}: Hc/Hc_ff track "
              f"{c['track_only']['Hc_over_Hc_ff']:.4f}, ridges {c['ridges']['Hc_over_Hc_ff']:.4f}, "
              f"same mean {c['uniform_same_mean']['Hc_over_Hc_ff']:.4f}", flush=True)
    out["X"] = ff.X.tolist()
    out["Y"] = Y.tolist()
    return out


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    run0 = data["runs"][0]
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.2))
    labels = [f"{c['h_in_over_Hc_ff']:g} Hc_ff, {c['ridge_factor']:g}x at |Y| {c['ridge_Y'][0]:g}-{c['ridge_Y'][1]:g}"
              for c in run0["cases"]]
    x = np.arange(len(labels))
    for i, (key, name) in enumerate((("track_only", "track layer only"), ("ridges", "track + ridges"),
                                      ("uniform_same_mean", "uniform, same mean"))):
        ax[0].bar(x + (i - 1) * 0.27, [c[key]["Hc_over_Hc_ff"] for c in run0["cases"]], 0.27, label=name)
    ax[0].set_xticks(x, labels, fontsize=7)
    ax[0].set_ylabel("Hc / Hc_ff")
    ax[0].legend(fontsize=8)
    ax[0].set_title(f"(M, L) = ({M:g}, {L:g}), {run0['points']}^2 half domain")
    c = run0["cases"][0]
    if c["theta_ridges"] is not None:
        X, Y = np.array(run0["X"]), np.array(run0["Y"])
        th = np.array(c["theta_ridges"])
        Yf = np.concatenate([-Y[:0:-1], Y])
        thf = np.vstack([th[:0:-1], th])
        cs = ax[1].contourf(X, Yf, thf, levels=np.linspace(0, 1, 11))
        fig.colorbar(cs, ax=ax[1])
        ax[1].set_aspect("equal")
        ax[1].set_title(f"theta with ridges ({labels[0]})")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    t0 = time.perf_counter()
    grids = [129] if args.quick else [129, 257]
    data = {"M": M, "L": L, "runs": [run(n) for n in grids]}
    data["wall_s"] = time.perf_counter() - t0
    tag = "_quick" if args.quick else ""
    (OUT / f"starved_ridges{tag}.json").write_text(json.dumps(data, indent=1, default=float))
    plot(data, OUT / f"starved_ridges{tag}.png")
    print(f"wall {data['wall_s']:.0f} s")


if __name__ == "__main__":
    main()
