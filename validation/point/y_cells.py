"""Cells across the narrow semi-axis of contacts long in the rolling direction (theta > 1).

The point grid uses near-square cells (``y_ratio``: (ny - 1)/(nx - 1) the power of 2 closest
to the box's aspect, b/a), so a theta = 4 contact (b/a = 0.40) has 0.4x the cells across b that
it has across a; its minimum film sits in the side lobes near |Y| = b. This study solves
each case with the default ratio and with cells stretched with the ellipse (ratio twice the
default: hy ~ hx b/a) on the same X grids, one process per solve (timeout), and records
Hc, Hm, status, work units and wall time.

    python validation/point/y_cells.py [--points 513 1025 2049] [--tag T]

Writes ``build/validation/point/y_cells[_T].json`` (resumable by case, grid and ratio; a record computed by other
code is not reused).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[0] / "extremes"))
sys.path.insert(0, str(HERE.parent))
from _paths import out_dir  # noqa: E402
from accuracy_map import code_version  # noqa: E402

CASES = [  # (M, L, theta, viscosity, density)
    (20.0, 10.0, 4.0, "barus", "incompressible"),
    (100.0, 10.0, 4.0, "barus", "incompressible"),
    (500.0, 10.0, 4.0, "barus", "incompressible"),
    (500.0, 0.0, 4.0, "barus", "incompressible"),
    (100.0, 10.0, 4.0, "roelands", "dowson-higginson"),
    (1000.0, 10.0, 10.0, "roelands", "dowson-higginson"),
]


def one(case: list, points: int, ratio: float | None) -> dict:
    from ehl_multigrid.point import solve_point

    M, L, theta, visc, dens = case
    kw = {} if ratio is None else {"y_ratio": ratio}
    t = time.perf_counter()
    r = solve_point(M, L, theta=theta, viscosity=visc, density=dens, points=points, estimate=False,
                    raise_on_failure=False, **kw)
    return {"status": r.status_name, "Hc": r.scalars.get("Hc"), "Hm": r.scalars.get("Hm"),
            "ny": int(r.P.shape[0]), "wu": r.work_units, "wall_s": time.perf_counter() - t,
            }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, nargs="+", default=[513, 1025, 2049])
    ap.add_argument("--tag", default="")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--one", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.one:
        case, n, ratio = json.loads(a.one)
        print(json.dumps(one(case, n, ratio)))
        return
    from tqdm import tqdm

    out = out_dir("point") / f"y_cells{'_' + a.tag if a.tag else ''}.json"
    code = code_version()
    done = json.loads(out.read_text()) if out.is_file() else {}
    done = {k: v for k, v in done.items() if v.get("code") == code and not code.endswith("dirty")}
    todo = [(c, n, r) for c in CASES for n in a.points for r in ("default", "stretched")]
    for case, n, which in tqdm(todo):
        key = json.dumps([case, n, which])
        if key in done:
            continue
        ratio = None
        if which == "stretched":
            dflt = done.get(json.dumps([case, n, "default"]), {}).get("ratio_used")
            if dflt is None:
                continue
            ratio = 2.0 * dflt
        try:
            p = subprocess.run([sys.executable, __file__, "--one", json.dumps([list(case), n, ratio])],
                               capture_output=True, text=True, timeout=a.timeout)
            rec = json.loads(p.stdout.strip().splitlines()[-1]) if p.returncode == 0 else {
                "status": "crash", "message": p.stderr.strip().splitlines()[-1:]}
        except subprocess.TimeoutExpired:
            rec = {"status": "timeout"}
        rec.update(case=list(case), points=n, which=which, code=code)
        if "ny" in rec:
            rec["ratio_used"] = (2 * (rec["ny"] - 1)) / (n - 1)  # half domain: ny = (nyf - 1)/2 + 1
        done[key] = rec
        tmp = out.with_suffix(".tmp")
        tmp.write_text(json.dumps(done, indent=1))
        tmp.replace(out)
    for rec in done.values():
        print(rec["case"][:3], rec["points"], rec["which"], rec["status"], rec.get("Hc"), rec.get("Hm"),
              rec.get("ny"), round(rec.get("wall_s", 0), 1))


if __name__ == "__main__":
    main()
