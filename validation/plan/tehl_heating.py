"""The contact's heat and the thermal film: the planner's temperature-rise estimate against the
coupled TEHL film reduction under slip (`plan.CONTACT_HEATING_FILM` for line contacts,
`plan.CONTACT_HEATING_FILM_POINT` for point contacts).

    python validation/plan/tehl_heating.py [--contact line|point]

For each case: the planner's estimated temperature rise ``dT`` at the operating point
(`plan.temperature_rise_estimate`, one decoupled pass of the chapter-3 model on the Hertz
pressure), ``beta dT`` with the oil's ambient temperature-viscosity coefficient, Gupta's
reduction, and the coupled TEHL film (front door at 2 %) against its own isothermal solve:
the reductions of Hc and Hm and their ratio to ``beta dT``. The line constant must not lie below
the largest Hm ratio. Point contacts are solved on a fixed grid (513 or 1025 points, the coarsest
that holds a positive film; the ratio of the thermal and isothermal films of one grid), and the
point constant must not lie below any measured change of Hc or Hm over ``beta dT``, thinner or
thicker. Writes
``build/validation/plan/tehl_heating.json`` / ``tehl_heating_point.json`` (resumes).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tehl"))
from _paths import out_dir  # noqa: E402

# (scene, load [N] or None for the scene's own, sum speed [m/s] or None, slip or None)
CASES = [("appendix_c", 4240.0, 6.5, 0.5), ("appendix_c", 4240.0, 6.5, 1.0), ("appendix_c", 4240.0, 6.5, 2.0),
         ("appendix_c", 4240.0, 20.6, 0.5), ("appendix_c", 4240.0, 20.6, 1.0), ("appendix_c", 4240.0, 20.6, 2.0),
         ("appendix_c", 4240.0, 65.0, 0.5), ("appendix_c", 4240.0, 65.0, 1.0),
         ("appendix_c", 42400.0, 6.5, 0.5), ("appendix_c", 42400.0, 6.5, 1.0),
         ("appendix_c", 42400.0, 20.6, 0.5), ("appendix_c", 42400.0, 20.6, 1.0),
         ("page63_line_2000N", None, None, None), ("page63_line_8000N", None, None, None),
         ("page63_line_16000N", None, None, None)]
# point contacts: (scene, load [N] or None, sum speed [m/s], slip, points)
POINT_CASES = [("default", None, 0.05, 2.0, 1025), ("default", None, 0.5, 2.0, 513), ("default", None, 2.0, 2.0, 513),
               ("default", 175.0, 0.2, 2.0, 1025), ("ball_on_disc_tribometer", None, 0.25, 2.0, 1025),
               ("default", None, 0.05, 1.0, 1025), ("default", None, 0.2, 1.0, 1025), ("default", None, 0.5, 1.0, 513),
               ("default", None, 1.0, 1.0, 513), ("default", None, 2.0, 1.0, 513), ("default", 175.0, 0.5, 1.0, 1025),
               ("default", 175.0, 0.9, 1.0, 1025), ("ball_on_disc_tribometer", None, 0.5, 1.0, 513),
               ("series_C_disc3_1.93GPa", None, None, None, 1025)]


def case_scene(name: str, load: float | None, us: float | None, slip: float | None):
    from ehl_multigrid.model.scene import load_scene

    if name == "appendix_c":
        from slip_references import scene

        sc = scene()
    else:
        sc = load_scene(name)
    changes = {k: v for k, v in (("load", load), ("us", us), ("slip", slip)) if v is not None}
    return sc.with_operating(**changes) if changes else sc


def run(name: str, load: float | None, us: float | None, slip: float | None, points: int | None = None) -> dict:
    """One case: the front door at 2 % (``points`` None) or on a fixed grid without an estimate."""
    import ehl_multigrid as ehl
    from ehl_multigrid.app.plan import temperature_rise_estimate
    from ehl_multigrid.model import fits

    sc = case_scene(name, load, us, slip)
    dT = temperature_rise_estimate(sc, sc.us, sc.slip, float(sc.central_film_fit()[1]))["dT"]
    beta_dT = sc.lubricant.beta(sc.T_oil) * dT
    L = sc.thermal_properties()["thermal_loading"]
    gupta = 1.0 - float(fits.gupta_thermal_factor(L, sc.slip, sc.hertz.pmax / sc.E_reduced))
    t0 = time.perf_counter()
    if points is None:
        s = ehl.solve(sc, physics="thermal", accuracy=0.02, options={"slip": sc.slip})
    else:
        s = ehl.solve(sc, physics="thermal", accuracy=None, options={"slip": sc.slip, "points": points, "estimate": False})
    sm, d = s.summary(), s.details
    if d is None:
        return {"scene": name, "load": sc.load, "us": sc.us, "slip": sc.slip, "status": sm["status"],
                "message": s.message, "wall_s": round(time.perf_counter() - t0, 1)}
    hc, hm = 1.0 - sm["Hc"] / d.Hc_isothermal, 1.0 - sm["Hm"] / d.Hm_isothermal
    return {"scene": name, "load": sc.load, "us": sc.us, "slip": sc.slip, "pmax": sc.hertz.pmax, "dT": dT,
            "beta_dT": beta_dT, "gupta": gupta, "status": sm["status"],
            "points": sm["points"], "Hc_reduction": hc, "Hm_reduction": hm,
            "Hc_error": sm["Hc_error"], "Hm_error": sm["Hm_error"], "Hc_ratio": hc / beta_dT,
            "Hm_ratio": hm / beta_dT, "wall_s": round(time.perf_counter() - t0, 1)}


def main() -> None:
    from ehl_multigrid.app.plan import (
        CONTACT_HEATING_FILM,
        CONTACT_HEATING_FILM_POINT,
    )

    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--contact", choices=("line", "point"), default="line")
    contact = ap.parse_args().contact
    warnings.simplefilter("ignore")   # the study's speeds and slips lie outside the scenes' ranges
    path = Path(out_dir("plan")) / ("tehl_heating.json" if contact == "line" else "tehl_heating_point.json")
    data = json.loads(path.read_text()) if path.exists() else {}
    for case in CASES if contact == "line" else POINT_CASES:
        key = "_".join(str(v) for v in case)
        if key not in data:
            data[key] = run(*case)
            tmp = path.with_suffix(".tmp")
            tmp.write_text(json.dumps(data, indent=1))
            os.replace(tmp, path)
    done = [r for r in data.values() if "Hc_reduction" in r]
    for r in data.values():
        if r not in done:
            print(f"{r['scene']} us {r['us']:g} slip {r['slip']:g}: {r['status']} ({r['message'][:120]})")
    print("| case | pmax GPa | us m/s | S | dT K | beta dT | Gupta | Hc red. | Hm red. | Hc red./(beta dT) | Hm red./(beta dT) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in done:
        print(f"| {r['scene']} {r['load']:g} N | {r['pmax'] / 1e9:.2f} | {r['us']:g} | {r['slip']:g} | {r['dT']:.1f} | "
              f"{r['beta_dT']:.3f} | {r['gupta']:.3f} | {r['Hc_reduction']:.3f} | "
              f"{r['Hm_reduction']:.3f} | {r['Hc_ratio']:.3f} | {r['Hm_ratio']:.3f} |")
    if contact == "line":
        worst = max(r["Hm_ratio"] for r in done if r["status"] == "converged")
        print(f"\nlargest Hm reduction / (beta dT) {worst:.3f}; plan.CONTACT_HEATING_FILM = {CONTACT_HEATING_FILM:g}")
        return
    worst = max(max(abs(r["Hc_ratio"]), abs(r["Hm_ratio"])) for r in done)
    print(f"\nlargest |film change| / (beta dT) {worst:.3f}; plan.CONTACT_HEATING_FILM_POINT = "
          f"{CONTACT_HEATING_FILM_POINT:g}")


if __name__ == "__main__":
    main()
