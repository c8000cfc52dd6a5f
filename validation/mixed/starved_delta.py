"""What Chevalier's exponent from the flooded inlet changes in starved Stribeck curves.

The thesis (chapter 6) and the mixed layer's default use one exponent, ``delta = 3.5``, in the
starved film (6.1)-(6.4). The package's mass-conserving starved solvers say otherwise
(validation/starved/REPORT.md): line contacts follow ``min(r, 1)`` (no side flow, ``delta -> 20``)
and circular contacts a ``delta`` that falls with the flooded inlet film,
``delta = 2.37 - 0.95 log10(Hc_ff)`` (Venner units). ``supply.delta = "inlet"`` applies both
(``mixed.starvation.inlet_delta``). This study runs the chapter-6 curves and two user contacts
with both rules and reports what moves: the film (Lambda), the friction coefficient, the speed
of lowest friction and the mixed-to-EHL transition, and where the exponent had to be held at
the end of its measured films.

    python validation/mixed/starved_delta.py [--quick]

Writes build/validation/mixed/starved_delta.json and build/validation/mixed/starved_delta.png (isothermal, as chapter 6).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import out_dir, write_json  # noqa: E402

from ehl_multigrid.model.scene import Scene, load_scene  # noqa: E402
from mixed.sharing import contact_at_load  # noqa: E402
from mixed.starvation import INLET_HC_RANGE  # noqa: E402
from mixed.stribeck import stribeck_curve  # noqa: E402


def tribometer_with_roughness() -> Scene:
    """The built-in ball-on-disc tribometer with the series-C disc's measured roughness, at 5 %
    slip (the scene itself rolls without sliding, so its film carries no friction)."""
    d = load_scene("ball_on_disc_tribometer").with_operating(slip=0.05).to_dict()
    d["roughness"] = load_scene("series_C_disc3_1.93GPa").to_dict()["roughness"]
    return Scene.from_dict(d, origin="ball_on_disc_tribometer + series C roughness")


#: scene, supplies hoil/Rq (the flooded curve is the reference of every case)
CASES = [
    ("chapter6_starved_1.93GPa", (0.5, 1.0, 2.0, 3.0)),
    ("chapter6_starved_0.5GPa", (1.0, 1.5, 2.0, 3.0, 6.0)),
    ("ball_on_disc_tribometer+roughness", (1.0, 2.0, 4.0)),
    ("page63_line_2000N", (1.0, 2.0, 4.0)),
]


def scene_of(name: str) -> Scene:
    return tribometer_with_roughness() if name == "ball_on_disc_tribometer+roughness" else load_scene(name)


def compare(sc: Scene, us: np.ndarray, hoil_sigma: float) -> dict:
    hoil = hoil_sigma * sc.roughness.Rq
    a = stribeck_curve(sc.with_supply(delta=3.5), us, hoil=hoil)
    b = stribeck_curve(sc.with_supply(delta="inlet"), us, hoil=hoil)
    film = ~(a.sharing.boundary | b.sharing.boundary)
    dl = b.sharing.Lambda[film] / a.sharing.Lambda[film] - 1.0
    fa, fb = a.friction.coefficient, b.friction.coefficient
    df = fb / fa - 1.0
    ka, kb = int(np.argmin(fa)), int(np.argmin(fb))
    hc_v = b.sharing.hc_fit * sc.Rx / contact_at_load(sc, b.sharing.load).a ** 2  # Venner units
    lo, hi = INLET_HC_RANGE
    held = film & ((hc_v < lo) | (hc_v > hi)) if sc.kind != "line" else np.zeros_like(film)
    i = int(np.argmax(np.abs(dl))) if dl.size else 0
    j = int(np.argmax(np.abs(df)))
    return {
        "hoil_over_sigma": hoil_sigma,
        "film_points": int(film.sum()),
        "Lambda_change_max": float(dl[i]) if dl.size else 0.0,
        "Lambda_change_at_us": float(us[film][i]) if dl.size else None,
        "friction_change_max": float(df[j]), "friction_change_at_us": float(us[j]),
        "f_min_3p5": float(fa[ka]), "us_f_min_3p5": float(us[ka]),
        "f_min_inlet": float(fb[kb]), "us_f_min_inlet": float(us[kb]),
        "us_ml_ehl_3p5": a.transitions["us_ml_ehl"], "us_ml_ehl_inlet": b.transitions["us_ml_ehl"],
        "us_bl_ml_3p5": a.transitions["us_bl_ml"], "us_bl_ml_inlet": b.transitions["us_bl_ml"],
        "delta_used_range": [float(np.nanmin(b.sharing.delta_used)), float(np.nanmax(b.sharing.delta_used))]
        if film.any() else None,
        "Hc_ff_venner_range": [float(np.nanmin(hc_v[film])), float(np.nanmax(hc_v[film]))] if film.any() else None,
        "points_held_at_range_end": int(held.sum()),
        "curves": {"us": us, "f_3p5": fa, "f_inlet": fb, "Lambda_3p5": a.sharing.Lambda,
                   "Lambda_inlet": b.sharing.Lambda},
    }


def main(quick: bool = False) -> dict:
    t0 = time.perf_counter()
    out_path = out_dir(quick)
    us = np.geomspace(0.01, 100.0, 25 if quick else 80)
    cases = CASES[:2] if quick else CASES
    data: dict = {"us_range": [us[0], us[-1], us.size], "inlet_hc_range": INLET_HC_RANGE, "scenes": {}}
    for name, hoils in cases:
        sc = scene_of(name)
        rows = [compare(sc, us, h) for h in hoils]
        data["scenes"][name] = {"kind": sc.kind, "pmax": sc.hertz.pmax, "Rq": sc.roughness.Rq, "rows": rows}
        for r in rows:
            print(f"{name} hoil {r['hoil_over_sigma']:g} sigma: Lambda {r['Lambda_change_max']:+.3%} at "
                  f"{r['Lambda_change_at_us']} m/s, f {r['friction_change_max']:+.3%}; f_min {r['f_min_3p5']:.4g} at "
                  f"{r['us_f_min_3p5']:.3g} -> {r['f_min_inlet']:.4g} at {r['us_f_min_inlet']:.3g} m/s; delta "
                  f"{r['delta_used_range']}; held {r['points_held_at_range_end']}/{r['film_points']}", flush=True)
    data["wall_s"] = time.perf_counter() - t0
    plot(data, out_path / "starved_delta.png")
    write_json(out_path / "starved_delta.json", data)
    return data


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(data["scenes"])
    fig, axes = plt.subplots(2, len(names), figsize=(4 * len(names), 6.5), squeeze=False)
    for k, name in enumerate(names):
        for j, r in enumerate(data["scenes"][name]["rows"]):
            c = r["curves"]
            col = f"C{j}"
            axes[0, k].loglog(c["us"], c["Lambda_3p5"], "--", color=col, lw=0.8)
            axes[0, k].loglog(c["us"], c["Lambda_inlet"], "-", color=col, lw=1.0, label=f"hoil {r['hoil_over_sigma']:g} Rq")
            axes[1, k].semilogx(c["us"], c["f_3p5"], "--", color=col, lw=0.8)
            axes[1, k].semilogx(c["us"], c["f_inlet"], "-", color=col, lw=1.0)
        axes[0, k].set_title(name, fontsize=8)
        axes[0, k].set_ylabel("Lambda = hf,r/Rq")
        axes[1, k].set_ylabel("friction coefficient")
        axes[1, k].set_xlabel("us [m/s]")
        axes[0, k].legend(fontsize=6)
    fig.suptitle("starved Stribeck curves: delta = 3.5 (dashed) against delta from the flooded inlet (solid)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    main(ap.parse_args().quick)
