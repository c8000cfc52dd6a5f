"""Study 2: solver Hc against the Nijenbanning fit (2.23-2.29), theta = 1, 0.25, 4, over
M in {5,10,20,50,100,200,500,1000} x L in {0,2.5,5,10,15,20}; Barus + incompressible (the
fit's own assumptions) and Barus + Dowson-Higginson (compressible: the cost of the fit's
incompressibility); optionally theta = 1 Roelands + DH (--roelands) and the grid error
(--grid-error: theta = 1 Barus map re-solved at twice the resolution). Without it, the grid
error at 129^2 is the one measured by grid_convergence.py.

    python validation/point/fit_check.py [--quick] [--points 129] [--roelands]

Each case runs on max(points, min_points(M, b/a)) points (257 from M = 200, 513 from M = 1000,
more for theta > 2).
"""

import argparse

import numpy as np
from common import Store, plt, solve_case
from tqdm import tqdm

from ehl_multigrid.model.fits import nijenbanning_central
from ehl_multigrid.point.problem import hertz_shape, min_points

MS = [5, 10, 20, 50, 100, 200, 500, 1000]
LS = [0, 2.5, 5, 10, 15, 20]
THETAS = [1.0, 0.25, 4.0]
MODELS = [("barus", "incompressible"), ("barus", "dowson-higginson")]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--points", type=int, default=129)
    ap.add_argument("--roelands", action="store_true", help="also Roelands + DH at theta = 1")
    ap.add_argument("--grid-error", action="store_true", help="theta = 1 map again at 2x resolution")
    a = ap.parse_args()
    ms = [10, 100, 1000] if a.quick else MS
    ls = [0, 10, 20] if a.quick else LS
    thetas = [1.0] if a.quick else THETAS
    st = Store(f"fit_check{'_quick' if a.quick else ''}.json")
    def pts(M: float, th: float = 1.0) -> int:
        return max(a.points, min_points(M, hertz_shape(th)[2]))

    todo = [(th, m, M, L, pts(M, th)) for th in thetas for m in MODELS for M in ms for L in ls]
    if a.roelands:
        todo += [(1.0, ("roelands", "dowson-higginson"), M, L, pts(M)) for M in ms for L in ls]
    if a.grid_error:  # grid error: theta = 1, Barus + incompressible at twice the resolution
        todo += [(1.0, MODELS[0], M, L, 2 * pts(M) - 1) for M in ms for L in (0, 10, 20)]
    for th, (v, d), M, L, n in tqdm(todo, desc="fit check"):
        key = f"{th}_{v}_{d}_{M}_{L}_{n}"
        if key in st:
            continue
        row = solve_case(M, L, th, v, d, n, max_cycles=25)
        row["Hc_fit"] = float(nijenbanning_central(M, L, th))
        st.put(key, row)
    # maps of relative deviation
    out = {}
    combos = [(th, m) for th in thetas for m in MODELS]
    if a.roelands:
        combos.append((1.0, ("roelands", "dowson-higginson")))
    fig, axes = plt().subplots(1, len(combos), figsize=(3.2 * len(combos), 3.2))
    for ax, (th, (v, d)) in zip(np.atleast_1d(axes), combos, strict=True):
        dev = np.full((len(ls), len(ms)), np.nan)
        for i, L in enumerate(ls):
            for j, M in enumerate(ms):
                r = st.data[f"{th}_{v}_{d}_{M}_{L}_{pts(M, th)}"]
                if r.get("Hc") is not None and r.get("converged"):
                    dev[i, j] = 100.0 * (r["Hc"] / r["Hc_fit"] - 1.0)
        out[f"{th}_{v}_{d}"] = {"M": ms, "L": ls, "dev_pct": dev.tolist()}
        im = ax.imshow(dev, origin="lower", cmap="RdBu_r", vmin=-40, vmax=40, aspect="auto")
        for i in range(len(ls)):
            for j in range(len(ms)):
                if np.isfinite(dev[i, j]):
                    ax.text(j, i, f"{dev[i, j]:.0f}", ha="center", va="center", fontsize=6)
        ax.set_xticks(range(len(ms)), [str(m) for m in ms], fontsize=6)
        ax.set_yticks(range(len(ls)), [str(x) for x in ls], fontsize=6)
        ax.set_xlabel("M")
        ax.set_ylabel("L")
        ax.set_title(f"theta={th:g} {v[:5]}+{'DH' if d.startswith('dow') else 'inc'}", fontsize=8)
    fig.colorbar(im, ax=axes, label="(Hc_solver / Hc_fit - 1) [%]", shrink=0.8)
    fig.savefig(st.path.with_suffix(".png"), dpi=90)
    if a.grid_error:
        g = np.full((len(ls), len(ms)), np.nan)
        for i, L in enumerate(ls):
            for j, M in enumerate(ms):
                r1 = st.data[f"1.0_barus_incompressible_{M}_{L}_{pts(M)}"]
                r2 = st.data.get(f"1.0_barus_incompressible_{M}_{L}_{2 * pts(M) - 1}", {})
                if r1.get("Hc") and r2.get("Hc") and r1.get("converged") and r2.get("converged"):
                    g[i, j] = 100.0 * (r1["Hc"] / r2["Hc"] - 1.0)
        out["grid_error_pct_theta1_barus_inc"] = {"M": ms, "L": ls, "points": [a.points, 2 * a.points - 1],
                                                  "dev_pct": g.tolist()}
    counts = {s: sum(1 for r in st.data.values() if r.get("status") == s)
              for s in ("converged", "not_converged", "error", "input_error")}
    out["counts"] = counts
    Store(f"fit_check_summary{'_quick' if a.quick else ''}.json").put("summary", out)
    print(counts)
    for k, v in out.items():
        if "dev_pct" in v:
            arr = np.array(v["dev_pct"], dtype=float)
            if np.isfinite(arr).any():
                print(k, f"dev range {np.nanmin(arr):.1f} .. {np.nanmax(arr):.1f} %")


if __name__ == "__main__":
    main()
