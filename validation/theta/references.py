"""theta > 1 (issue 44): the package's films against the references that could be reached.

    python validation/theta/references.py [--quick]

Writes ``build/validation/theta/references.json`` (each solve as it finishes; a rerun resumes)
and ``references.md``. Barus viscosity, incompressible oil (the fits' model), Moes units.

References reached (the search for published tables is reported in docs/fits.md):

* Chittenden, Dowson, Dunn & Taylor (1985), Proc. R. Soc. Lond. A 397, 245-269 and 271-294:
  the film formulas for entrainment along either principal axis, as quoted in
  ``CHITTENDEN_QUOTED`` (two quotations with different constants are kept, the one of the
  earlier study and the one of the tribonet calculator page). No tabulated solution of the
  papers could be reached.
* Nijenbanning, Venner & Moes (1994), Wear 176, 217-229 (thesis 2.23-2.29): the package's fit.
* Hamrock & Dowson (1977), J. Lubr. Technol. 99, 264-276: k >= 1 only, extrapolated.

Independent numbers: ``validation/theta/independent_point.py``, a second solver that shares no
code with the package (own Hertz solution, kernel, discretisation, iteration), solves the same
equations at theta = 1 and 4 where its plain iteration converges (M = 10-20, L = 0-2); it is
not a published reference, but it decides whether the package solves the theta > 1 problem it
states. Its films are grid-converged by comparing 65 and 129 nodes along X.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import independent_point  # noqa: E402
from _paths import out_dir  # noqa: E402

from ehl_multigrid.model.fits import nijenbanning_central  # noqa: E402

MODEL = {"viscosity": "barus", "density": "incompressible"}
US = 1e-11  # Us at which the power-law fits are evaluated (validation/theta/study.py)

# (k_c, c_c, k_m, c_m): H = k U^0.68 G^0.49 W^-0.073 (1 - exp(-c (Rs/Rx)^(2/3))), Rs/Rx = 1/theta,
# U on the mean speed, W = w/(E' Rx^2), H = h/Rx
CHITTENDEN_QUOTED = {
    "as quoted in validation/theta/study.py": (4.31, 1.23, 3.68, 0.67),
    "tribonet.org EHL film thickness calculator, elliptical contact (Hc only)": (4.30, 1.30, None, None),
}

INDEPENDENT_CASES = [(10.0, 0.0), (20.0, 0.0), (10.0, 2.0)]
PACKAGE_CASES = INDEPENDENT_CASES + [(20.0, 10.0), (50.0, 5.0)]
THETAS = (1.0, 2.0, 4.0)
NODES = (65, 129)
BOX_NODES = (65, 129, 257)


def _moes(k: float, M: float, L: float, us: float = US) -> float:
    a, b, c = 0.68, 0.49, -0.073
    return k * 2.0 ** (-a) * us ** (a - b / 4.0 + 3.0 * c / 4.0 - 0.5) * L**b * M**c


def chittenden(M: float, L: float, theta: float, k: float, c: float) -> float:
    return _moes(k, M, L) * (1.0 - math.exp(-c * (1.0 / theta) ** (2.0 / 3.0)))


def package(M: float, L: float, theta: float) -> dict:
    import ehl_multigrid as ehl

    t0 = time.perf_counter()
    pb = ehl.MoesProblem("point" if theta == 1.0 else "elliptic", M=M, L=L, theta=theta, **MODEL)
    s = ehl.solve(pb, accuracy=0.01)
    sm = s.summary()
    out = {k: sm.get(k) for k in ("status", "Hc", "Hm", "Hc_error", "Hm_error", "points", "points_y")}
    out["box"] = list(s.grid.box) if s.grid is not None else None
    out["wall_s"] = round(time.perf_counter() - t0, 1)
    return out


def package_box(M: float, L: float, theta: float, n: int) -> dict:
    """The package on a fixed grid with P = 0 on the box (``far_field=False``): the problem the
    independent solver states."""
    from ehl_multigrid.point import solve_point

    t0 = time.perf_counter()
    s = solve_point(M, L, theta=theta, points=n, far_field=False, **MODEL)
    return {"status": s.status_name, "Hc": s.scalars.get("Hc"), "Hm": s.scalars.get("Hm"),
            "nodes": list(s.P.shape), "wall_s": round(time.perf_counter() - t0, 1)}


def independent(M: float, L: float, theta: float, n: int, wedge: str = "central") -> dict:
    t0 = time.perf_counter()
    r = independent_point.solve(M, L, theta, n=n, mix=0.3, depth=10, max_iter=400, wedge=wedge)
    return {"Hc": r.Hc, "Hm": r.Hm, "converged": r.converged, "iterations": r.iterations,
            "change": r.change, "nodes": [r.nx, r.ny], "wall_s": round(time.perf_counter() - t0, 1)}


def _save(path: Path, data: dict) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1))
    os.replace(tmp, path)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="65 nodes only, (20, 0) only")
    a = ap.parse_args()
    out = out_dir("theta")
    path = out / ("references_quick.json" if a.quick else "references.json")
    data = json.loads(path.read_text()) if path.exists() else {}

    def once(key: str, fn) -> dict:
        if key not in data:
            data[key] = fn()
            _save(path, data)
            print(key, data[key], flush=True)
        return data[key]

    pcases = [(20.0, 0.0)] if a.quick else PACKAGE_CASES
    icases = [(20.0, 0.0)] if a.quick else INDEPENDENT_CASES
    nodes = NODES[:1] if a.quick else NODES
    for M, L in pcases:
        for th in THETAS:
            once(f"pkg_{M:g}_{L:g}_{th:g}", lambda M=M, L=L, th=th: package(M, L, th))
    for n in nodes:
        for M, L in icases:
            for th in (1.0, 4.0):
                once(f"ind_{M:g}_{L:g}_{th:g}_{n}", lambda M=M, L=L, th=th, n=n: independent(M, L, th, n))
    # identity check: with the package's second-order upwind wedge, on the package's grid (square
    # cells at theta = 1), both codes discretise the same equations alike
    for n in nodes:
        once(f"up2_10_0_1_{n}", lambda n=n: independent(10.0, 0.0, 1.0, n, wedge="upwind2"))
    for n in BOX_NODES[:2] if a.quick else BOX_NODES:
        for M, L in icases:
            for th in (1.0, 4.0):
                once(f"box_{M:g}_{L:g}_{th:g}_{n}", lambda M=M, L=L, th=th, n=n: package_box(M, L, th, n))
    report(data, out / ("references_quick.md" if a.quick else "references.md"), pcases, icases, nodes)


def report(data: dict, path: Path, pcases, icases, nodes) -> None:
    lines = ["# theta > 1 references (Barus, incompressible; Moes units)", "",
             "Package (front door, accuracy 1 %) against the independent solver, theta = 1 and 4:", "",
             "| M | L | theta | package Hc [err %] | package Hm | " + " | ".join(
                 f"independent Hc ({n})" for n in nodes) + " |", "|" + "---|" * (5 + len(nodes))]
    for M, L in icases:
        for th in (1.0, 4.0):
            p = data.get(f"pkg_{M:g}_{L:g}_{th:g}", {})
            cells = []
            for n in nodes:
                r = data.get(f"ind_{M:g}_{L:g}_{th:g}_{n}", {})
                cells.append(f"{r['Hc']:.4f}{'' if r.get('converged') else ' (not conv.)'}" if r else "-")
            lines.append(f"| {M:g} | {L:g} | {th:g} | {p.get('Hc', float('nan')):.4f} "
                         f"[{100 * (p.get('Hc_error') or float('nan')):.2f}] | {p.get('Hm', float('nan')):.4f} | "
                         + " | ".join(cells) + " |")
    lines += ["", "The same problem (P = 0 on the box, no far field): package fixed grids and the independent "
              "solver (central wedge); 'extr.' = Richardson (order 2) from the two finest grids:", "",
              "| M | L | theta | package 65 / 129 / 257 | package extr. | independent 65 / 129 | independent extr. "
              "| difference |", "|---|---|---|---|---|---|---|---|"]
    for M, L in icases:
        for th in (1.0, 4.0):
            b = [data.get(f"box_{M:g}_{L:g}_{th:g}_{n}", {}).get("Hc") for n in BOX_NODES]
            i = [data.get(f"ind_{M:g}_{L:g}_{th:g}_{n}", {}).get("Hc") for n in NODES]
            if None in b or None in i:
                continue
            be = b[-1] + (b[-1] - b[-2]) / 3.0
            ie = i[-1] + (i[-1] - i[-2]) / 3.0
            lines.append(f"| {M:g} | {L:g} | {th:g} | {' / '.join(f'{v:.4f}' for v in b)} | {be:.4f} | "
                         f"{' / '.join(f'{v:.4f}' for v in i)} | {ie:.4f} | {100 * (ie / be - 1):+.2f} % |")
    up = [data.get(f"up2_10_0_1_{n}", {}).get("Hc") for n in nodes]
    bx = [data.get(f"box_10_0_1_{n}", {}).get("Hc") for n in nodes]
    if None not in up and None not in bx:
        lines += ["", "Identity check, (10, 0, 1), both with the second-order upwind wedge on the same grid: "
                  + ", ".join(f"{n} nodes: independent {u:.6f}, package {b:.6f}" for n, u, b in zip(nodes, up, bx, strict=True))]
    lines += ["", "Hc(theta = 4) / Hc(theta = 1) at equal (M, L):", "",
              "| M | L | package | " + " | ".join(f"independent ({n})" for n in nodes)
              + " | Nijenbanning | " + " | ".join(CHITTENDEN_QUOTED) + " |",
              "|" + "---|" * (4 + len(nodes) + len(CHITTENDEN_QUOTED))]
    for M, L in pcases:
        p1, p4 = data.get(f"pkg_{M:g}_{L:g}_1", {}), data.get(f"pkg_{M:g}_{L:g}_4", {})
        pk = p4["Hc"] / p1["Hc"] if p1.get("Hc") and p4.get("Hc") else float("nan")
        ind = []
        for n in nodes:
            i1, i4 = data.get(f"ind_{M:g}_{L:g}_1_{n}"), data.get(f"ind_{M:g}_{L:g}_4_{n}")
            ok = i1 and i4 and i1.get("converged") and i4.get("converged")
            ind.append(f"{i4['Hc'] / i1['Hc']:.3f}" if ok else "-")
        nij = float(nijenbanning_central(M, L, 4.0) / nijenbanning_central(M, L, 1.0))
        ch = [f"{(1 - math.exp(-c * 0.25 ** (2 / 3))) / (1 - math.exp(-c)):.3f}" for _, c, _, _ in CHITTENDEN_QUOTED.values()]
        lines.append(f"| {M:g} | {L:g} | {pk:.3f} | " + " | ".join(ind) + f" | {nij:.3f} | " + " | ".join(ch) + " |")
    lines += ["", "Package Hc against the fits at theta = 2 and 4 (ratio package / fit):", "",
              "| M | L | theta | package Hc | Nijenbanning | Chittenden (quoted) |", "|---|---|---|---|---|---|"]
    k, c, _, _ = CHITTENDEN_QUOTED["as quoted in validation/theta/study.py"]
    for M, L in pcases:
        for th in (2.0, 4.0):
            p = data.get(f"pkg_{M:g}_{L:g}_{th:g}", {})
            if not p.get("Hc"):
                continue
            nij = float(nijenbanning_central(M, L, th))
            chs = f"{p['Hc'] / chittenden(M, L, th, k, c):.3f}" if L > 0 else "- (G = 0)"
            lines.append(f"| {M:g} | {L:g} | {th:g} | {p['Hc']:.4f} | {p['Hc'] / nij:.3f} | {chs} |")
    tmp = path.with_suffix(".tmp")
    tmp.write_text("\n".join(lines) + "\n")
    os.replace(tmp, path)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
