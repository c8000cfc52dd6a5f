"""Study 1: grid convergence of Hc, Hm, spike at (M, L) = (20,10), (100,10), (10,5), (10,0),
Roelands + Dowson-Higginson and Barus + incompressible, 65^2 .. 1025^2 (quick: .. 257^2).

    python validation/point/grid_convergence.py [--quick]
"""

import argparse

from common import Store, plt, richardson, solve_case
from tqdm import tqdm

CASES = [(20, 10), (100, 10), (10, 5), (10, 0)]
MODELS = [("roelands", "dowson-higginson"), ("barus", "incompressible")]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    grids = [65, 129, 257] if a.quick else [65, 129, 257, 513, 1025]
    st = Store("grid_convergence_quick.json" if a.quick else "grid_convergence.json")
    todo = [(c, m, n) for c in CASES for m in MODELS for n in grids]
    for (M, L), (v, d), n in tqdm(todo, desc="grid convergence"):
        key = f"{M}_{L}_{v}_{n}"
        if key in st:
            continue
        st.put(key, solve_case(M, L, 1.0, v, d, n, max_cycles=60))
    summary = {}
    fig, ax = plt().subplots(1, 2, figsize=(10, 4))
    for (M, L) in CASES:
        for v, _d in MODELS:
            rows = [st.data[f"{M}_{L}_{v}_{n}"] for n in grids]
            hc = [r.get("Hc") for r in rows]
            hm = [r.get("Hm") for r in rows]
            p, ext = richardson(hc)
            pm, extm = richardson(hm)
            summary[f"{M}_{L}_{v}"] = {
                "grids": grids, "Hc": hc, "Hm": hm, "p_spike": [r.get("p_spike") for r in rows],
                "converged": [r.get("converged") for r in rows], "order_Hc": p, "Hc_extrapolated": ext,
                "order_Hm": pm, "Hm_extrapolated": extm,
                "err_Hc_pct": [None if (h is None or ext != ext) else 100 * (h / ext - 1) for h in hc],
            }
            if ext == ext and all(h is not None for h in hc):
                hs = [6.0 / (n - 1) for n in grids]
                ax[0 if v == "roelands" else 1].loglog(hs, [abs(h - ext) / ext for h in hc], "o-",
                                                        label=f"M={M}, L={L}")
    for k, t in enumerate(("Roelands + DH", "Barus + incompressible")):
        ax[k].set_xlabel("hx")
        ax[k].set_ylabel("|Hc - Hc_extrapolated| / Hc_extrapolated")
        ax[k].set_title(t)
        ax[k].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(st.path.with_suffix(".png"), dpi=90)
    Store("grid_convergence_summary" + ("_quick" if a.quick else "") + ".json").put("summary", summary)
    for k, s in summary.items():
        print(k, "order", round(s["order_Hc"], 2) if s["order_Hc"] == s["order_Hc"] else None,
              "ext", s["Hc_extrapolated"], "Hc", s["Hc"])


if __name__ == "__main__":
    main()
