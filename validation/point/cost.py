"""Study 3: cost at (M, L) = (20, 10), Roelands + DH. Wall time and work units against grid
size (65^2 .. 1025^2, full mode also 2049^2), fitted growth exponent, time to Hc within 1 % and
0.1 % of the extrapolated value, V against W cycles, MLMI against FFT, 1 against 2 cores, FAS
against the Newton/pyamg path (which is also tried at (100, 10) and (200, 20)).

    python validation/point/cost.py [--quick]
"""

import argparse
import json
import math
import time

import numpy as np
from common import HERE, OUT, Store, load_avg, plt, richardson, solve_case
from tqdm import tqdm

from ehl_multigrid.point import build_result, problem_from_moes


def newton_case(M, L, n):
    from ehl_multigrid.model.errors import ConvergenceError
    from ehl_multigrid.point.newton import solve_newton_amg

    row = {"M": M, "L": L, "points": n, "solver": "newton-pyamg", "load_before": load_avg()}
    t0 = time.perf_counter()
    try:
        nw = solve_newton_amg(problem_from_moes(M, L), points=n, max_iter=60)
        s = build_result(nw).scalars
        row.update(Hc=s["Hc"], Hm=s["Hm"], converged=s["converged"], message=s["message"],
                   newton_steps=int(nw.report.iterations),
                   gmres_iterations=int(np.sum(nw.report.extra["gmres_iterations"])),
                   status="converged" if s["converged"] else "not_converged")
    except (ConvergenceError, ValueError, FloatingPointError) as exc:
        row.update(status="error", converged=False, message=f"{type(exc).__name__}: {str(exc)[:200]}")
    row["wall_s"] = time.perf_counter() - t0
    return row


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    grids = [65, 129, 257] if a.quick else [65, 129, 257, 513, 1025, 2049]
    st = Store(f"cost{'_quick' if a.quick else ''}.json")
    jobs = [("grid", n, {}) for n in grids]
    mid = [257] if a.quick else [257, 513]
    jobs += [("V", n, {"cycle": "V"}) for n in mid]
    jobs += [("mlmi", n, {"deformation": "mlmi"}) for n in mid]
    jobs += [("1core", n, {"threads": 1}) for n in mid]
    jobs += [("2core", n, {"threads": 2}) for n in mid]
    for tag, n, kw in tqdm(jobs, desc="cost FAS"):
        key = f"{tag}_{n}"
        if key in st:
            continue
        row = solve_case(20, 10, 1.0, "roelands", "dowson-higginson", n, max_cycles=60, **kw)
        row["tag"] = tag
        st.put(key, row)
    nws = [(20, 10, n) for n in ([65, 129] if a.quick else [65, 129, 257])]
    nws += [(100, 10, 129), (200, 20, 129)]
    for M, L, n in tqdm(nws, desc="cost Newton"):
        key = f"newton_{M}_{L}_{n}"
        if key not in st:
            st.put(key, newton_case(M, L, n))
        fkey = f"fas_{M}_{L}_{n}"
        if fkey not in st:
            st.put(fkey, solve_case(M, L, 1.0, "roelands", "dowson-higginson", n, max_cycles=60))
    # extrapolated Hc: tests/point/reference.json (257/513/1025 Richardson) if present
    ref_path = HERE.parents[1] / "tests" / "point" / "reference.json"
    rows = [st.data[f"grid_{n}"] for n in grids]
    hc = [r["Hc"] for r in rows]
    if ref_path.exists():
        ext = json.loads(ref_path.read_text())["Hc_extrapolated"]
    else:
        ext = richardson(hc)[1]
    walls = [r["wall_s"] for r in rows]
    solver_walls = [r.get("wall_s") for r in rows]
    wu = [r.get("work_units") for r in rows]
    N = np.array([n * n for n in grids], float)
    sel = N >= 257**2
    expo = float(np.polyfit(np.log(N[sel]), np.log(np.array(walls)[sel]), 1)[0]) if sel.sum() >= 2 else math.nan
    err = [abs(h / ext - 1) for h in hc]
    t1 = min((w for w, e in zip(walls, err, strict=True) if e < 0.01), default=None)
    t01 = min((w for w, e in zip(walls, err, strict=True) if e < 0.001), default=None)
    summary = {
        "grids": grids, "wall_s": walls, "solver_wall_s": solver_walls, "work_units": wu, "Hc": hc,
        "Hc_extrapolated": ext, "err_pct": [100 * e for e in err], "growth_exponent_wall_vs_N": expo,
        "time_to_1pct_s": t1, "time_to_0p1pct_s": t01,
        "converged": [r.get("converged") for r in rows],
        "V_vs_W": {n: {"V": st.data[f"V_{n}"].get("wall_s"), "W": st.data[f"grid_{n}"]["wall_s"],
                       "V_wu": st.data[f"V_{n}"].get("work_units"), "W_wu": st.data[f"grid_{n}"].get("work_units"),
                       "V_converged": st.data[f"V_{n}"].get("converged"),
                       "V_Hc": st.data[f"V_{n}"].get("Hc")} for n in mid},
        "mlmi_vs_fft": {n: {"mlmi": st.data[f"mlmi_{n}"].get("wall_s"), "fft": st.data[f"grid_{n}"]["wall_s"],
                            "Hc_mlmi": st.data[f"mlmi_{n}"].get("Hc"), "Hc_fft": st.data[f"grid_{n}"]["Hc"]}
                        for n in mid},
        "cores": {n: {"1": st.data[f"1core_{n}"]["wall_s"], "2": st.data[f"2core_{n}"]["wall_s"],
                      "load_1": st.data[f"1core_{n}"]["load_before"], "load_2": st.data[f"2core_{n}"]["load_before"]}
                  for n in mid},
        "newton_vs_fas": {f"{M}_{L}_{n}": {"newton": st.data[f"newton_{M}_{L}_{n}"],
                                           "fas": {k: st.data[f"fas_{M}_{L}_{n}"].get(k)
                                                   for k in ("Hc", "Hm", "wall_s", "converged")}}
                          for M, L, n in nws},
    }
    Store(f"cost_summary{'_quick' if a.quick else ''}.json").put("summary", summary)
    fig, ax = plt().subplots(1, 2, figsize=(10, 4))
    ax[0].loglog(N, walls, "o-", label="FAS W, FFT (wall)")
    ax[0].loglog(N, walls[-1] * (N / N[-1]) * np.log(N) / np.log(N[-1]), "k:", label="N log N")
    ax[0].set_xlabel("points N")
    ax[0].set_ylabel("wall [s]")
    ax[0].legend(fontsize=7)
    ax[1].semilogx(N, wu, "o-")
    ax[1].set_xlabel("points N")
    ax[1].set_ylabel("work units (finest-grid sweeps)")
    fig.tight_layout()
    fig.savefig(OUT / f"cost{'_quick' if a.quick else ''}.png", dpi=90)
    print(json.dumps(summary, default=str)[:3000])


if __name__ == "__main__":
    main()
