"""Study 5: extremes. M from 1 to 5000, L from 0 to 25, theta from 0.1 to 10, Roelands + DH,
on max(129, min_points(M, b/a)) points (the solver's own minimum grid: 257 from M = 200, 513 from
M = 1000, more for theta > 2; quick: 65 points, fewer cases): every case converged, not converged (reported in the
result) or a clear error; counted and listed.

    python validation/point/extremes.py [--quick]
"""

import argparse
from collections import Counter

from common import Store, solve_case
from tqdm import tqdm

from ehl_multigrid.point.problem import hertz_shape, min_points


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    if a.quick:
        Ms, Ls, ths, n = [1, 100, 5000], [0, 25], [0.1, 1, 10], 65
    else:
        Ms, Ls, ths, n = [1, 10, 100, 1000, 5000], [0, 5, 15, 25], [0.1, 1, 10], None
    st = Store(f"extremes{'_quick' if a.quick else ''}.json")
    todo = [(M, L, th) for th in ths for M in Ms for L in Ls]
    for M, L, th in tqdm(todo, desc="extremes"):
        pts = n if n is not None else max(129, min_points(M, hertz_shape(th)[2]))
        key = f"{M}_{L}_{th}_{pts}"
        if key in st:
            continue
        st.put(key, solve_case(M, L, th, "roelands", "dowson-higginson", pts, max_cycles=40))
    c = Counter(r["status"] for r in st.data.values())
    bad = {k: (r["status"], (r.get("message") or "")[:160]) for k, r in st.data.items() if r["status"] != "converged"}
    Store(f"extremes_summary{'_quick' if a.quick else ''}.json").put("summary", {"counts": dict(c), "failures": bad})
    print(dict(c))
    for k, v in bad.items():
        print(k, v)


if __name__ == "__main__":
    main()
