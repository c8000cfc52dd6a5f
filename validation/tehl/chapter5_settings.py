"""Why the point TEHL solve fails at the thesis's chapter 5 condition (series D, disc 3,
1.93 GPa, 12 m/s, 80 degC, M = 1595): one :func:`thermal.tehl.solve_tehl_point` with the
given settings, printing every inner multilevel solve's last finest-grid residuals, Hc and Hm
(Venner units) and, at the end, the outer iteration's history.

Usage: ``python validation/tehl/chapter5_settings.py POINTS SLIP ['{"tol_H": 1e-3, ...}']``
(the JSON holds TEHLOptions changes). The runs of the report were kept with
``... > build/validation/tehl/chapter5_settings.log``.
"""

from __future__ import annotations

import json
import sys
import time

from ehl_multigrid.model.scene import load_scene
from thermal.tehl import point as tp

Base = tp.MultilevelSolver


class Logged(Base):
    """The core driver, printing the end of each solve's finest-grid history."""

    def solve(self):
        res = Base.solve(self)
        top = max(h.level for h in res.history)
        fin = [h for h in res.history if h.level == top]
        print("  inner: success", res.success, "cycles", res.cycles, "res",
              [f"{r:.2e}" for r in res.residual_history[-8:]], flush=True)
        print("  finest Hc", [f"{h.Hc:.6f}" for h in fin[-8:]], flush=True)
        print("  finest Hm", [f"{h.Hm:.6f}" for h in fin[-8:]], flush=True)
        return res


def main() -> None:
    tp.MultilevelSolver = Logged
    sc = load_scene("series_D_disc3_1.93GPa")
    pts, S = int(sys.argv[1]), float(sys.argv[2])
    kw = json.loads(sys.argv[3]) if len(sys.argv) > 3 else {}
    print("run", pts, S, kw, flush=True)
    t = time.perf_counter()
    try:
        r = tp.solve_tehl_point(sc, S, points=pts, threads=1, **kw)
        print("OK", r.summary(), time.perf_counter() - t)
        for o in r.outer:
            print(o)
        print(r.report.extra.get("actions"))
    except Exception as e:  # recorded, not hidden
        print("FAIL", str(e)[:800], time.perf_counter() - t)
        rep = getattr(e, "report", None)
        if rep is not None and hasattr(rep, "extra"):
            for k, v in rep.extra.items():
                if k in ("outer", "actions"):
                    print(k, v)


if __name__ == "__main__":
    main()
