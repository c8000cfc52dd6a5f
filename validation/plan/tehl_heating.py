"""The contact's heat and the thermal film: the planner's temperature-rise estimate against the
coupled TEHL film reduction of line contacts under slip (`plan.CONTACT_HEATING_FILM`).

    python validation/plan/tehl_heating.py

For each case: the planner's estimated temperature rise ``dT`` at the operating point
(`plan.temperature_rise_estimate`, one decoupled pass of the chapter-3 model on the Hertz
pressure), ``beta dT`` with the oil's ambient temperature-viscosity coefficient, Gupta's
reduction, and the coupled TEHL film (front door at 2 %) against its own isothermal solve:
the reductions of Hc and Hm and their ratio to ``beta dT``. The constant must not lie below the
largest Hm ratio. Writes ``build/validation/plan/tehl_heating.json`` (resumes).
"""

from __future__ import annotations

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


def case_scene(name: str, load: float | None, us: float | None, slip: float | None):
    from ehl_multigrid.model.scene import load_scene

    if name == "appendix_c":
        from slip_references import scene

        sc = scene()
    else:
        sc = load_scene(name)
    changes = {k: v for k, v in (("load", load), ("us", us), ("slip", slip)) if v is not None}
    return sc.with_operating(**changes) if changes else sc


def run(name: str, load: float | None, us: float | None, slip: float | None) -> dict:
    import ehl_multigrid as ehl
    from ehl_multigrid.app.plan import temperature_rise_estimate
    from ehl_multigrid.model import fits

    sc = case_scene(name, load, us, slip)
    dT = temperature_rise_estimate(sc, sc.us, sc.slip, float(sc.central_film_fit()[1]))["dT"]
    beta_dT = sc.lubricant.beta(sc.T_oil) * dT
    L = sc.thermal_properties()["thermal_loading"]
    gupta = 1.0 - float(fits.gupta_thermal_factor(L, sc.slip, sc.hertz.pmax / sc.E_reduced))
    t0 = time.perf_counter()
    s = ehl.solve(sc, physics="thermal", accuracy=0.02, options={"slip": sc.slip})
    sm, d = s.summary(), s.details
    hc, hm = 1.0 - sm["Hc"] / d.Hc_isothermal, 1.0 - sm["Hm"] / d.Hm_isothermal
    return {"scene": name, "load": sc.load, "us": sc.us, "slip": sc.slip, "pmax": sc.hertz.pmax, "dT": dT,
            "beta_dT": beta_dT, "gupta": gupta, "status": sm["status"], "Hc_reduction": hc, "Hm_reduction": hm,
            "Hc_error": sm["Hc_error"], "Hm_error": sm["Hm_error"], "Hc_ratio": hc / beta_dT,
            "Hm_ratio": hm / beta_dT, "wall_s": round(time.perf_counter() - t0, 1)}


def main() -> None:
    from ehl_multigrid.app.plan import CONTACT_HEATING_FILM

    warnings.simplefilter("ignore")   # the study's speeds and slips lie outside the scenes' ranges
    path = Path(out_dir("plan")) / "tehl_heating.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    for case in CASES:
        key = "_".join(str(v) for v in case)
        if key not in data:
            data[key] = run(*case)
            tmp = path.with_suffix(".tmp")
            tmp.write_text(json.dumps(data, indent=1))
            os.replace(tmp, path)
    print("| case | pmax GPa | us m/s | S | dT K | beta dT | Gupta | Hc red. | Hm red. | Hm red./(beta dT) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in data.values():
        print(f"| {r['scene']} {r['load']:g} N | {r['pmax'] / 1e9:.2f} | {r['us']:g} | {r['slip']:g} | {r['dT']:.1f} | "
              f"{r['beta_dT']:.3f} | {r['gupta']:.3f} | {r['Hc_reduction']:.3f} | {r['Hm_reduction']:.3f} | "
              f"{r['Hm_ratio']:.3f} |")
    worst = max(r["Hm_ratio"] for r in data.values() if r["status"] == "converged")
    print(f"\nlargest Hm reduction / (beta dT) {worst:.3f}; plan.CONTACT_HEATING_FILM = {CONTACT_HEATING_FILM:g}")


if __name__ == "__main__":
    main()
