"""Independent reference values of Hc and Hm (Venner units) for the accuracy studies.

Line (M, L) with tested grids up to N -- reference solves at tolerances 1e-8 / 1e-9; where the
multigrid stalls (L = 0 and long inlets on fine grids), the dense direct solver of
dense_line.py up to common.DENSE_MAX points:

* the default box at the tested grids and 2N, 4N, 8N (points ``k (N - 1) + 1``): Richardson
  from the three finest consecutive converged grids (``R1``);
* the box 2x and 4x longer upstream (``xmin = xmax - 4 (xmax - xmin_default)``, nodes aligned)
  at the mesh of N, and the 4x box at the meshes of 2N, 4N and 8N (4x the points, up to
  LINE_R4_MAX): where it converges up to the default box's finest mesh, Richardson on the 4x
  box (``R4``) continued beyond 4x with the measured decay of the change per doubling
  (``reference = R4 (1 + beyond/(1 + d4))``);
* elsewhere ``reference = R1 (1 + d_box)`` with ``d_box`` the box change measured at the mesh
  of N and extrapolated (an additive split of grid and box errors: where both are available
  the box change agrees to 1e-6 relative between the meshes of N and 8N).

Point (M, L, theta): half-domain solves at ten times the default tolerances (the W cycles end
in a limit cycle near a load error of 1e-5; a solve that stops at max_cycles counts when its
films moved by < 3e-5 over the last cycles, and that spread enters the uncertainty). The
default box at 257, 513, 1025 (and the tested grids): Richardson from the three finest
consecutive converged grids (``R1``); boxes 1x, 2x, 4x (8x where the change decays by less
than 3 per doubling, up to POINT_BOX_MAX points) at the mesh of the smallest tested grid
(X and Y scaled, twice the points per doubling), extrapolated with the measured decay
(``d_box``); ``reference = R1 (1 + d_box)``. For two cases the box series is repeated at a
mesh twice as fine to measure how much the box change depends on the mesh.

Uncertainty of a reference: the Richardson uncertainty (extrapolation with the order moved by
+-0.5, plus twice the algebraic noise of the reference solves) plus the box remainder beyond
the largest box (the extrapolated remainder itself) plus, where measured, the change of the
box effect between meshes.

    python validation/accuracy/references.py [--contact line|point|both] [--table]
"""

from __future__ import annotations

import argparse
import math
from typing import Any

from common import (
    LINE_CASES,
    POINT_CASES,
    POINT_TIGHT,
    REFS,
    box_extrapolation,
    cached_solve,
    consecutive_chain,
    fmt,
    line_reference_solve,
    nan,
    read_json,
    richardson_reference,
    usable,
    write_json,
)
from tqdm import tqdm

#: largest 4x-box line grid attempted (131073 points at M = 1000 ran > 8 minutes under load
#: without converging; where the box change is 1e-5, as there, the additive split is exact enough)
LINE_R4_MAX = 65537
#: settling (relative spread of the films over the last cycles) accepted for a box solve
BOX_SPREAD = 1e-3
#: extra options of the reference solves of a point case
POINT_REF_OPTIONS: dict[tuple[float, float, float], dict[str, Any]] = {}
#: settling accepted for the default-box point solves of a case (default: common.usable's 3e-5);
#: at (1000, 10) the W cycles end with Hm moving by 4e-4 (added to the uncertainty)
POINT_SPREAD = {(1000.0, 10.0, 1.0): 1e-3}
#: largest point grid of a box series (half domain)
POINT_BOX_MAX = 1025
#: point cases whose box series is repeated at twice the mesh density (mesh dependence: Hm's box
#: change is irregular on coarse meshes, circular (100, 10) 0.19 % on 129 points, 0.34 % on 257)
POINT_BOX_MESH_CHECK = {(20.0, 10.0, 1.0), (5.0, 0.0, 1.0), (20.0, 0.0, 1.0), (100.0, 10.0, 1.0),
                        (100.0, 20.0, 1.0), (20.0, 10.0, 0.25), (20.0, 10.0, 4.0)}


def refine(n: int, k: int) -> int:
    return k * (n - 1) + 1


def ref_path(contact: str, M: float, L: float, theta: float = 1.0):
    return REFS / f"{contact}_M{fmt(M)}_L{fmt(L)}_t{fmt(theta)}.json"


def _films(rec: dict[str, Any]) -> tuple[float, float]:
    return nan(rec.get("Hc_venner")), nan(rec.get("Hm_venner"))


#: algebraic error of a converged tight line solve: the dense direct solver agrees with it to
#: <= 2e-7 in Hc and Hm (build/validation/accuracy/dense_check.json, ``dense_line.py``)
LINE_TIGHT_ALGEBRAIC = 1e-6


def _noise(recs: list[dict[str, Any]]) -> float:
    """Relative algebraic uncertainty of reference solves: 0 for the dense direct solver (exact
    to round-off), LINE_TIGHT_ALGEBRAIC for converged tight line solves, else the spread of
    the films over the last finest-grid cycles plus half the load error."""
    s = []
    for r in recs:
        if r.get("solver") == "dense":
            s.append(0.0)
        elif r.get("contact") == "line" and r.get("success"):
            s.append(LINE_TIGHT_ALGEBRAIC)
        else:
            s.append(nan(r.get("spread")))
    s = [x for x in s if math.isfinite(x)]
    return max(s) if s else 0.0


def line_reference(M: float, L: float, tested: tuple[int, ...], bar: Any = None) -> dict[str, Any]:
    path = ref_path("line", M, L)
    old = read_json(path)
    if old is not None:
        return old
    N = max(tested)
    fine = [refine(N, k) for k in (2, 4, 8)]

    def solve(n: int, box: float, dense: bool = True) -> dict[str, Any]:
        if bar is not None:
            bar.set_postfix_str(f"line ({M:g}, {L:g}) {n} pts box {box:g}")
        return line_reference_solve(M, L, n, box, dense)

    one: dict[int, dict[str, Any]] = {}
    for n in sorted(set(tested) | set(fine)):
        one[n] = solve(n, 1.0)
        if not usable(one[n]) and n > max(tested):
            break  # beyond the dense solver's reach: finer grids would stall as well
    b2, b4 = solve(refine(N, 2), 2.0), solve(refine(N, 4), 4.0)
    four: dict[int, dict[str, Any]] = {refine(N, 4): b4}
    if usable(b4):
        for n in (m for m in fine if refine(m, 4) <= LINE_R4_MAX):
            # no dense fallback here: the 4x box's grid sequence only counts when it reaches
            # the finest default-box grid, beyond the dense solver's size
            four[refine(n, 4)] = solve(refine(n, 4), 4.0, dense=False)
            if not usable(four[refine(n, 4)]):
                break
    out: dict[str, Any] = {"contact": "line", "M": M, "L": L, "theta": 1.0, "tested": list(tested),
                           "solves": {**{f"{n}_box1": r for n, r in one.items()},
                                      f"{refine(N, 2)}_box2": b2,
                                      **{f"{n}_box4": r for n, r in four.items()}}}
    chain1 = consecutive_chain(one)
    if len(chain1) < 2 or chain1[-1] <= N:
        out.update(ok=False, reason="no converged default-box solve finer than the tested grids")
        write_json(path, out)
        return out
    noise = _noise([one[n] for n in chain1[-3:]])
    R1 = {k: richardson_reference([_films(one[n])[i] for n in chain1[-3:]], noise)
          for i, k in enumerate(("Hc", "Hm"))}
    R1["grids"] = chain1[-3:]
    b1 = one[N]
    if not (usable(b1) and usable(b2)):
        out.update(ok=False, reason="the box solves at the mesh of N did not converge")
        write_json(path, out)
        return out
    box = {k: box_extrapolation(_films(b1)[i], _films(b2)[i], _films(b4)[i] if usable(b4) else None)
           for i, k in enumerate(("Hc", "Hm"))}
    chain4 = consecutive_chain(four)
    ref, unc = {}, {}
    # the 4x box's own grid sequence is used when it reaches the default box's finest mesh
    if len(chain4) >= 3 and chain4[-1] >= refine(chain1[-1], 4):
        noise4 = _noise([four[n] for n in chain4[-3:]])
        R4 = {k: richardson_reference([_films(four[n])[i] for n in chain4[-3:]], noise4)
              for i, k in enumerate(("Hc", "Hm"))}
        R4["grids"] = chain4[-3:]
        out["R4"] = R4
        out["box_change_by_mesh"] = {
            str((n - 1) // 4 + 1): {k: _films(four[n])[i] / _films(one[(n - 1) // 4 + 1])[i] - 1.0
                                    for i, k in enumerate(("Hc", "Hm"))}
            for n in chain4 if usable(one.get((n - 1) // 4 + 1))}
        for k in ("Hc", "Hm"):
            bx = box[k]
            beyond = bx["beyond"] / (1.0 + bx["d4"])
            ref[k] = R4[k]["value"] * (1.0 + beyond)
            unc[k] = R4[k]["uncertainty"] + abs(ref[k]) * bx["uncertainty"]
        method = (f"Richardson on the 4x box ({', '.join(str(n) for n in chain4[-3:])} points) "
                  f"+ box remainder beyond 4x")
    else:
        for k in ("Hc", "Hm"):
            bx = box[k]
            ref[k] = R1[k]["value"] * (1.0 + bx["total"])
            unc[k] = R1[k]["uncertainty"] + abs(ref[k]) * bx["uncertainty"]
        method = (f"Richardson on the default box ({', '.join(str(n) for n in chain1[-3:])}) x "
                  f"(1 + box change at the mesh of {N}, boxes up to {'4x' if usable(b4) else '2x'})")
    dense = sorted(key for key, r in out["solves"].items() if r.get("solver") == "dense" and usable(r))
    if dense:
        method += f"; dense direct solves: {', '.join(dense)}"
    out.update(ok=True, R1=R1, box=box, method=method, Hc_ref=ref["Hc"], Hm_ref=ref["Hm"],
               Hc_unc=unc["Hc"] / abs(ref["Hc"]), Hm_unc=unc["Hm"] / abs(ref["Hm"]),
               grid_ref={k: R1[k]["value"] for k in ("Hc", "Hm")})
    write_json(path, out)
    return out


def point_grids(theta: float, tested: tuple[int, ...]) -> list[int]:
    top = 2049 if theta > 2.0 else 1025
    return sorted(set(tested) | {(top - 1) // 4 + 1, (top - 1) // 2 + 1, top})


def point_reference(M: float, L: float, theta: float, tested: tuple[int, ...], bar: Any = None) -> dict[str, Any]:
    path = ref_path("point", M, L, theta)
    old = read_json(path)
    if old is not None:
        return old
    opts = {**POINT_TIGHT, "half": True, **POINT_REF_OPTIONS.get((M, L, theta), {})}
    grids = point_grids(theta, tested)
    n0 = min(tested)
    plan = [(n0, 1.0), (refine(n0, 2), 2.0)] + ([(refine(n0, 4), 4.0)] if refine(n0, 4) <= POINT_BOX_MAX else [])
    if (M, L, theta) in POINT_BOX_MESH_CHECK:
        n1 = refine(n0, 2)
        plan += [(n1, 1.0), (refine(n1, 2), 2.0), (refine(n1, 4), 4.0)]
    plan += [(n, 1.0) for n in grids]
    recs: dict[tuple[int, float], dict[str, Any]] = {}
    for n, box in plan:
        if (n, box) in recs:
            continue
        if bar is not None:
            bar.set_postfix_str(f"point ({M:g}, {L:g}, {theta:g}) {n} pts box {box:g}")
        recs[(n, box)] = cached_solve("point", M, L, theta, n, box, **opts)
    out: dict[str, Any] = {"contact": "point", "M": M, "L": L, "theta": theta, "tested": list(tested),
                           "solves": {f"{n}_box{fmt(b)}": r for (n, b), r in recs.items()}}
    spread = POINT_SPREAD.get((M, L, theta), 3e-5)
    chain = consecutive_chain({n: recs[(n, 1.0)] for n in grids}, spread)
    if len(chain) < 2 or chain[-1] <= max(tested):
        out.update(ok=False, reason="no converged default-box solve finer than the tested grids")
        write_json(path, out)
        return out
    seq = [recs[(n, 1.0)] for n in chain[-3:]]
    noise = _noise(seq)
    R1 = {k: richardson_reference([_films(r)[i] for r in seq], noise, two_grid_regular=k == "Hc")
          for i, k in enumerate(("Hc", "Hm"))}
    R1["grids"] = chain[-3:]

    def box_series(n: int) -> dict[str, Any] | None:
        bs = [recs.get((refine(n, f), float(f))) for f in (1, 2, 4, 8)]
        # the box changes are percents: films settled to 1e-3 measure them well enough (the
        # spread is added to the uncertainty)
        ok = [usable(b, BOX_SPREAD) for b in bs]
        if not (ok[0] and ok[1]):
            return None
        g = [_films(b) if good else None for b, good in zip(bs, ok, strict=True)]
        if not ok[2]:
            g[3] = None
        noise = _noise([b for b, good in zip(bs, ok, strict=True) if good])
        out = {}
        for i, k in enumerate(("Hc", "Hm")):
            bx = box_extrapolation(g[0][i], g[1][i], g[2][i] if g[2] else None, g[3][i] if g[3] else None)
            bx["uncertainty"] += 2.0 * noise
            out[k] = bx
        return out

    box = box_series(n0)
    # where the box change decays slowly (< 3x per doubling) one more doubling, if affordable
    slow = box is not None and any(not (box[k]["decay"] >= 3.0) for k in ("Hc", "Hm"))
    if slow and refine(n0, 8) <= POINT_BOX_MAX:
        if bar is not None:
            bar.set_postfix_str(f"point ({M:g}, {L:g}, {theta:g}) {refine(n0, 8)} pts box 8")
        recs[(refine(n0, 8), 8.0)] = cached_solve("point", M, L, theta, refine(n0, 8), 8.0, **opts)
        out["solves"][f"{refine(n0, 8)}_box8"] = recs[(refine(n0, 8), 8.0)]
        box = box_series(n0)
    if box is None:
        out.update(ok=False, reason="the box solves did not converge")
        write_json(path, out)
        return out
    mesh_dep = {"Hc": 0.0, "Hm": 0.0}
    if (M, L, theta) in POINT_BOX_MESH_CHECK:
        fine_box = box_series(refine(n0, 2))
        out["box_fine_mesh"] = fine_box
        if fine_box is not None:
            mesh_dep = {k: abs(fine_box[k]["total"] - box[k]["total"]) for k in ("Hc", "Hm")}
            # the finer mesh's box change is the value; the change between meshes its uncertainty
            box, n0 = fine_box, refine(n0, 2)
    ref, unc = {}, {}
    for k in ("Hc", "Hm"):
        ref[k] = R1[k]["value"] * (1.0 + box[k]["total"])
        unc[k] = R1[k]["uncertainty"] + abs(ref[k]) * (box[k]["uncertainty"] + mesh_dep[k])
    out.update(ok=True, R1=R1, box=box, box_mesh_dependence=mesh_dep,
               method=f"Richardson on the default box ({', '.join(str(n) for n in chain[-3:])}) x "
                      f"(1 + box change at the mesh of {n0}, boxes 1x-"
                      f"{'8' if math.isfinite(box['Hc']['d8']) else ('4' if math.isfinite(box['Hc']['d4']) else '2')}x, "
                      f"extrapolated)",
               Hc_ref=ref["Hc"], Hm_ref=ref["Hm"], Hc_unc=unc["Hc"] / abs(ref["Hc"]),
               Hm_unc=unc["Hm"] / abs(ref["Hm"]), grid_ref={k: R1[k]["value"] for k in ("Hc", "Hm")})
    write_json(path, out)
    return out


def reference(contact: str, M: float, L: float, theta: float = 1.0, bar: Any = None) -> dict[str, Any]:
    if contact == "line":
        return line_reference(M, L, LINE_CASES[(M, L)], bar)
    return point_reference(M, L, theta, POINT_CASES[(M, L, theta)], bar)


def table() -> str:
    """Markdown table of the stored references."""
    lines = ["| contact | (M, L, theta) | Hc ref (Venner) | +- | order Hc | Hm ref | +- | order Hm | "
             "box change (Hc) 2x, 4x, limit | decay per doubling (Hc, Hm) | method |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for contact, M, L, theta in [("line", M, L, 1.0) for M, L in LINE_CASES] + \
            [("point", *k) for k in POINT_CASES]:
        r = read_json(ref_path(contact, M, L, theta))
        case = f"({M:g}, {L:g}" + (f", {theta:g})" if contact == "point" else ")")
        if r is None or not r.get("ok"):
            lines.append(f"| {contact} | {case} | - | | | - | | | | | {r.get('reason') if r else 'not run'} |")
            continue
        bx = r["box"]
        lines.append(
            f"| {contact} | {case} | {r['Hc_ref']:.6g} | {100 * r['Hc_unc']:.2g} % | "
            f"{nan(r['R1']['Hc']['order']):.2f} | {r['Hm_ref']:.6g} | {100 * r['Hm_unc']:.2g} % | "
            f"{nan(r['R1']['Hm']['order']):.2f} | {100 * bx['Hc']['d2']:.3g}, {100 * nan(bx['Hc']['d4']):.3g}, "
            f"{100 * bx['Hc']['total']:.3g} % | {nan(bx['Hc']['decay']):.2g}, {nan(bx['Hm']['decay']):.2g} | "
            f"{r['method']} |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--contact", choices=("line", "point", "both"), default="both")
    ap.add_argument("--table", action="store_true", help="only print the stored references")
    args = ap.parse_args()
    if args.table:
        print(table())
        return
    todo = []
    if args.contact in ("line", "both"):
        todo += [("line", M, L, 1.0) for M, L in LINE_CASES]
    if args.contact in ("point", "both"):
        # cheapest first, so an interrupted run leaves the most cases done
        todo += sorted((("point", *k) for k in POINT_CASES), key=lambda c: (c[3] != 1.0, c[1]))
    bar = tqdm(todo, desc=f"references ({args.contact})")
    for contact, M, L, theta in bar:
        r = reference(contact, M, L, theta, bar)
        if r.get("ok"):
            tqdm.write(f"{contact} ({M:g}, {L:g}, {theta:g}): Hc {r['Hc_ref']:.7g} +- {100 * r['Hc_unc']:.3g} %, "
                       f"Hm {r['Hm_ref']:.7g} +- {100 * r['Hm_unc']:.3g} %  [{r['method']}]")
        else:
            tqdm.write(f"{contact} ({M:g}, {L:g}, {theta:g}): no reference ({r.get('reason')})")


if __name__ == "__main__":
    main()
