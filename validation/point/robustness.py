"""Robustness at the points where the classic code diverges: (M, L) = (200, 20)
and (100, 2) with Roelands + DH, and (20, 10) Barus + incompressible on fine grids; also the
classic settings (V cycles, GS/JD switch 0.3, 16^2 coarsest grid) to show what the
adaptation is needed for. Records what the solver did (report.extra['actions']).

    python validation/point/robustness.py [--quick]
"""

import argparse

from common import Store, solve_case
from tqdm import tqdm

CLASSIC = {"cycle": "V", "switch": 0.3, "omega": 0.4, "omega_jd": 0.2, "n_coarse": 16, "adapt": False}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    n = 129 if a.quick else 257
    cases = [(200, 20, "roelands", "dowson-higginson"), (100, 2, "roelands", "dowson-higginson"),
             (20, 10, "barus", "incompressible")]
    st = Store(f"robustness{'_quick' if a.quick else ''}.json")
    for M, L, v, d in tqdm(cases, desc="robustness"):
        for tag, kw in (("default", {}), ("classic", CLASSIC)):
            key = f"{M}_{L}_{v}_{n}_{tag}"
            if key not in st:
                st.put(key, solve_case(M, L, 1.0, v, d, n, max_cycles=40, **kw))
            r = st.data[key]
            print(key, r["status"], r.get("Hc"), r.get("final_residual"), r.get("actions"))


if __name__ == "__main__":
    main()
