"""How far does the collapse ``delta(Hc_ff)`` of study_collapse.py reach, and does it hold for
elliptical contacts?

study_collapse.py measured Chevalier's exponent ``delta`` of the reduction (6.1) on nine circular
contacts with flooded central films ``Hc_ff`` = 0.063-0.447 (Venner units ``h R/a^2``) and fitted
``delta = 2.37 - 0.95 log10(Hc_ff)``. The mixed layer's speed-dependent ``delta`` (thesis
section 6.2.1; ``mixed.starvation.inlet_delta``) uses that line over whole Stribeck curves,
where ``Hc_ff`` runs over decades. This study adds, with the same solver, grid and supplies:

* thicker and thinner circular films (``Hc_ff`` about 1.3, 5 and 0.03-0.05), to see where the
  line holds and where ``delta`` leaves it;
* elliptical contacts ``theta = Rx/Ry`` = 0.5 and 2 (wide and long in the rolling direction) at
  (M, L) = (20, 10) and (100, 10): Damiens et al. (2004) collapse elliptical contacts with a
  parameter that includes the ellipticity; here the question is only whether ``Hc_ff`` of the
  solver's scaling (``a`` the Hertzian semi-axis in the rolling direction) is enough.

    python validation/starved/study_collapse_range.py [--quick]

Writes ``build/validation/starved/starved_collapse_range.json`` (resumable: cases of the same plan are kept) and
``build/validation/starved/starved_collapse_range.png``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from study_point import RATIOS, fit_delta, resumable, run_case  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("starved")
#: (M, L, theta, points): circular films outside the first study's range, then ellipses. The
#: stiff (300, 5) reaches max_cycles at every supply on 129^2 (measured), so it runs on 257^2.
#: Thicker films than (5, 10) are not meaningful in the default box: at (2, 5) (Hc_ff 5.2) a
#: supply of 4 Hc_ff already gave Hc/Hc_ff = 0.79, the layer being thicker than the gap at the
#: box's inlet edge (the box starves the contact, not the supply).
CASES = [(5.0, 10.0, 1.0, 129), (300.0, 5.0, 1.0, 257),
         (20.0, 10.0, 0.5, 129), (20.0, 10.0, 2.0, 129), (100.0, 10.0, 0.5, 129), (100.0, 10.0, 2.0, 129)]
#: the line of study_collapse.py (nine circular contacts, 129^2)
LINE = (2.37, -0.95)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="first case only")
    a = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    tag = "_quick" if a.quick else ""
    path = OUT / f"starved_collapse_range{tag}.json"
    cases = CASES[:1] if a.quick else CASES
    plan = {"cases": cases, "ratios": RATIOS}
    data, save = resumable(path, plan)
    done = {(c["M"], c["L"], c["theta"]) for c in data["cases"]}
    t0 = time.perf_counter()

    for M, L, theta, points in cases:
        if (M, L, theta) in done:
            continue
        try:
            c = run_case(M, L, points, RATIOS, theta)
        except Exception as exc:  # a case that cannot run is recorded, not hidden
            data["cases"].append({"M": M, "L": L, "theta": theta, "error": repr(exc)})
            save()
            continue
        c["converged"] = sum(r["status"] == "converged" for r in c["runs"])
        if c["converged"] < 4:
            c["error"] = f"{c['converged']} of {len(c['runs'])} supplies converged: no delta fitted"
            data["cases"].append(c)
            save()
            continue
        c["fit"] = fit_delta(c["runs"])
        c["delta_line"] = LINE[0] + LINE[1] * float(np.log10(c["Hc_ff"]))
        data["cases"].append(c)
        save()
    rows = [{"M": c["M"], "L": c["L"], "theta": c["theta"], "points": c["points"], "Hc_ff": c["Hc_ff"], "delta": c["fit"]["delta"],
             "delta_line": c["delta_line"], "off_line": c["fit"]["delta"] - c["delta_line"],
             "max_rel_dev": c["fit"]["max_rel_dev"], "converged": c["converged"], "of": len(c["runs"])}
            for c in data["cases"] if "fit" in c]
    data["summary"] = {"rows": rows, "failed": [{k: c[k] for k in ("M", "L", "theta", "error")} for c in data["cases"] if "error" in c],
                       "wall_s": data.get("wall_s", 0.0) + time.perf_counter() - t0}
    data["wall_s"] = data["summary"]["wall_s"]
    save()
    plot(data, OUT / f"starved_collapse_range{tag}.png")
    for r in rows:
        print(f"({r['M']:g}, {r['L']:g}, theta {r['theta']:g}) Hc_ff {r['Hc_ff']:.4f} delta {r['delta']:.3f} "
              f"line {r['delta_line']:.3f} off {r['off_line']:+.3f} ({r['converged']}/{r['of']})")


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    base = json.loads((OUT / "starved_collapse.json").read_text()) if (OUT / "starved_collapse.json").exists() else None
    if base:
        ax.semilogx([c["Hc_ff"] for c in base["cases"]], [c["fit"]["delta"] for c in base["cases"]], "ko",
                    label="study_collapse (circular)")
    for c in data["cases"]:
        if "fit" not in c:
            continue
        mk = "s" if c["theta"] == 1.0 else ("^" if c["theta"] > 1 else "v")
        ax.semilogx(c["Hc_ff"], c["fit"]["delta"], mk, label=f"({c['M']:g}, {c['L']:g}, theta {c['theta']:g})")
    hh = np.geomspace(0.01, 10.0, 50)
    ax.semilogx(hh, LINE[0] + LINE[1] * np.log10(hh), "k--", lw=0.8, label="2.37 - 0.95 log10 Hc_ff")
    ax.set_xlabel("flooded Hc (Venner, h R/a^2)")
    ax.set_ylabel("least-squares delta of (6.1)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
