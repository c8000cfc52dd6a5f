"""Deep references of point contacts solved with the far-field boundary (``point.farfield``,
``point.farfield_angular``: the package's default), checked against the
references of ``references.py``, which hold ``P = 0`` on boxes up to 8x the default and
extrapolate the box change: two boundary treatments of the same unbounded problem.

Per case: Richardson over three tight solves on the default box (the finest 1025 points, 2049
at M >= 1000 and theta > 2) and the box series 1x, 2x, 4x at 129 and 257 points per default box
(257 and 513 at theta > 2; far field on), extrapolated beyond 4x; the reference is the grid limit times (1 + the box change), its
uncertainty the Richardson uncertainty (order +- 0.5, twice the algebraic noise) plus the box
remainder and the change of the box effect between the two meshes.

    python validation/accuracy/far_references.py            # solve (cached) and compare
    python validation/accuracy/far_references.py --table    # the stored comparison

writes build/validation/accuracy/far_references/point_M.._L.._t1.json (what
``validation/bench/honesty_table.py --refs far`` reads) and compare.md.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from common import (
    POINT_CASES,
    POINT_TIGHT,
    box_extrapolation,
    cached_solve,
    code_version,
    out_dir,
    richardson_reference,
    usable,
)
from tqdm import tqdm

OUT = Path(out_dir("accuracy/far_references"))
P0_REFS = Path(out_dir("accuracy/references"))
OPTS = {**POINT_TIGHT, "half": True, "far_field": True}
#: box-series meshes (points per default box)
BOX_MESHES = (129, 257)


def ref_path(M: float, L: float, theta: float = 1.0, root: Path = OUT) -> Path:
    return root / f"point_M{M:g}_L{L:g}_t{theta:g}.json"


def _films(rec: dict[str, Any]) -> tuple[float, float]:
    return float(rec["Hc_venner"]), float(rec["Hm_venner"])


def _noise(recs: list[dict[str, Any]]) -> float:
    return max((float(r.get("spread") or 0.0) + 0.5 * abs(float(r.get("load_error") or 0.0)) for r in recs),
               default=0.0)


def grids(M: float, theta: float = 1.0) -> tuple[int, int, int]:
    return (513, 1025, 2049) if M >= 1000 or theta > 2.0 else (257, 513, 1025)


def box_meshes(theta: float) -> tuple[int, int]:
    """Box-series meshes, points per default box along X (narrow contacts need more)."""
    return (257, 513) if theta > 2.0 else BOX_MESHES


def far_reference(M: float, L: float, theta: float = 1.0, bar: Any = None) -> dict[str, Any]:
    path = ref_path(M, L, theta)
    if path.exists():
        old = json.loads(path.read_text())
        if old.get("code") == code_version():
            return old

    def solve(n: int, box: float) -> dict[str, Any]:
        if bar is not None:
            bar.set_postfix_str(f"({M:g}, {L:g}, {theta:g}) {n} pts box {box:g}")
        return cached_solve("point", M, L, theta, n, box, **OPTS)

    out: dict[str, Any] = {"M": M, "L": L, "theta": theta, "options": OPTS, "code": code_version()}
    seq = [solve(n, 1.0) for n in grids(M, theta)]
    out["grid_solves"] = [{k: r.get(k) for k in ("points", "status", "Hc_venner", "Hm_venner", "spread")} for r in seq]
    if not all(usable(r) for r in seq):
        out.update(ok=False, reason="a default-box grid solve did not converge")
        path.write_text(json.dumps(out, indent=1))
        return out
    noise = _noise(seq)
    R1 = {k: richardson_reference([_films(r)[i] for r in seq], noise) for i, k in enumerate(("Hc", "Hm"))}
    boxes = {}
    for m in box_meshes(theta):
        recs = [solve((m - 1) * f + 1, float(f)) for f in (1, 2, 4)]
        if not all(usable(r, 1e-4) for r in recs):
            continue
        g = [_films(r) for r in recs]
        bn = _noise(recs)
        boxes[m] = {k: box_extrapolation(g[0][i], g[1][i], g[2][i]) for i, k in enumerate(("Hc", "Hm"))}
        for k in ("Hc", "Hm"):
            boxes[m][k]["uncertainty"] += 2.0 * bn
    if not boxes:
        out.update(ok=False, reason="no box series converged")
        path.write_text(json.dumps(out, indent=1))
        return out
    fine = max(boxes)
    mesh = {k: abs(boxes[fine][k]["total"] - boxes[min(boxes)][k]["total"]) if len(boxes) > 1 else
            abs(boxes[fine][k]["total"]) for k in ("Hc", "Hm")}
    ref, unc = {}, {}
    for k in ("Hc", "Hm"):
        ref[k] = R1[k]["value"] * (1.0 + boxes[fine][k]["total"])
        unc[k] = R1[k]["uncertainty"] + abs(ref[k]) * (boxes[fine][k]["uncertainty"] + mesh[k])
    out.update(ok=True, R1=R1, box=boxes[fine], box_by_mesh={str(m): b for m, b in boxes.items()},
               box_mesh_dependence=mesh, Hc_ref=ref["Hc"], Hm_ref=ref["Hm"],
               Hc_unc=unc["Hc"] / abs(ref["Hc"]), Hm_unc=unc["Hm"] / abs(ref["Hm"]),
               method=f"far field: Richardson on the default box ({', '.join(map(str, grids(M, theta)))}) x "
                      f"(1 + box change 1x-4x at {fine} points per default box, extrapolated)")
    path.write_text(json.dumps(out, indent=1))
    return out


def compare() -> str:
    lines = ["| (M, L, theta) | film | far field ref (Venner) | +- | P = 0 ref | +- | difference | within joint +- | "
             "far box change 1x->2x, 2x->4x |", "|" + " --- |" * 9]
    for M, L, theta in POINT_CASES:
        if not ref_path(M, L, theta).exists():
            continue
        far = json.loads(ref_path(M, L, theta).read_text())
        p0p = ref_path(M, L, theta, root=P0_REFS)
        p0 = json.loads(p0p.read_text()) if p0p.exists() else {}
        for k in ("Hc", "Hm"):
            if not far.get("ok"):
                lines.append(f"| ({M:g}, {L:g}, {theta:g}) | {k} | {far.get('reason')} | | | | | | |")
                continue
            b = far["box"][k]
            row = f"| ({M:g}, {L:g}, {theta:g}) | {k} | {far[k + '_ref']:.7g} | {100 * far[k + '_unc']:.3f} % | "
            if p0.get("ok"):
                d = far[k + "_ref"] / p0[k + "_ref"] - 1.0
                joint = far[k + "_unc"] + p0[k + "_unc"]
                row += (f"{p0[k + '_ref']:.7g} | {100 * p0[k + '_unc']:.3f} % | {100 * d:+.3f} % | "
                        f"{'yes' if abs(d) <= joint else 'NO'} | ")
            else:
                row += "| | | | "
            row += f"{100 * b['d2']:+.4f} %, {100 * (b['d4'] - b['d2']):+.4f} % |"
            lines.append(row)
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--table", action="store_true", help="only print the stored comparison")
    ap.add_argument("--cases", nargs="*", help="M,L,theta triples (default: every point case)")
    args = ap.parse_args()
    if not args.table:
        todo = list(POINT_CASES)
        if args.cases:
            want = {tuple(float(x) for x in c.split(",")) for c in args.cases}
            todo = [c for c in todo if c in want]
        todo.sort(key=lambda c: (c[0] >= 1000, c[2] != 1.0, c[0]))
        bar = tqdm(todo, desc="far-field references")
        for M, L, theta in bar:
            r = far_reference(M, L, theta, bar)
            msg = (f"Hc {r['Hc_ref']:.7g} +- {100 * r['Hc_unc']:.3g} %, Hm {r['Hm_ref']:.7g} +- "
                   f"{100 * r['Hm_unc']:.3g} %" if r.get("ok") else r.get("reason"))
            tqdm.write(f"({M:g}, {L:g}, {theta:g}): {msg}")
    text = compare()
    (OUT / "compare.md").write_text(text + "\n")
    print(text)


if __name__ == "__main__":
    main()
