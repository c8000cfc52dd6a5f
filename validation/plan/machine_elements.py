"""`ehl run` on the four machine-element scenes: wall time, the plan, and the film each stage used.

Usage: python validation/plan/machine_elements.py [--fidelity fast|standard|reference] [--scenes a,b]
Writes build/validation/plan/machine_elements_<fidelity>.json (finished scenes are kept and skipped).

For every scene: exit code and wall time of ``ehl run SCENE --fidelity F --no-plots --json``;
the film stage's central film (solved or fitted) and the fit; the film the traction stage ran on
(its input, and the film at the contact centre of its first line); the Stribeck stage's film
factor when the scene is rough. Then the thermal traction at slips 0, 0.1, 0.5, 1 on the film
stage's field (``ehl traction SCENE --input ehl --ehl-file``) and on Hertz + fit, at the
default thermal grid (nx 80, nz 20, 10 slices).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scene_run import run_scene

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("plan")
SCENES = ("bearing_6205_inner_race", "spur_gear_pitch_point", "roller_bearing_inner_race", "ball_on_disc_tribometer")


def films(h5: str) -> dict:
    from ehl_multigrid.model.results import load_results

    res = load_results(h5)
    row: dict = {}
    film = res["film"]
    row["film_kind"] = film.kind
    if film.kind.startswith("ehl"):
        row["film_hc_nm"] = float(film.scalars["hc"]) * 1e9
        row["film_hm_nm"] = float(film.scalars["hm"]) * 1e9
        row["film_points"] = int(film.scalars["points"])
    row["hc_fit_nm"] = float(film.scene.central_film_fit()[1]) * 1e9
    if "traction" in res:
        tr = res["traction"]
        row["traction_input"] = tr.scalars["input"]
        row["traction_film_source"] = tr.meta.get("film_source")
        X = tr["X"]
        h = tr["h"] if tr["h"].ndim == 1 else tr["h"][0]
        row["traction_h_centre_nm"] = float(h[int(np.argmin(np.abs(X)))]) * 1e9
        row["traction_thermal"] = bool(tr.scalars["thermal"])
        row["traction_max_temperature_rise_K"] = float(np.max(tr["max_temperature_rise"]))
        row["traction_converged"] = bool(tr.scalars["converged"])
    if "stribeck" in res:
        st = res["stribeck"]
        row["stribeck_film_factor"] = float(st.scalars["film_factor"])
        row["stribeck_film_source"] = st.meta.get("film_source")
    return row


SLIPS = "0,0.1,0.5,1"


def thermal_traction(name: str, h5: str, tmp: str) -> dict:
    from ehl_multigrid.model.results import load_results

    film = load_results(h5)["film"]
    out: dict = {}
    runs = [("hertz", [])]
    if film.kind.startswith("ehl"):
        path = str(Path(tmp) / "film.h5")
        film.save(path)
        runs.append(("ehl", ["--input", "ehl", "--ehl-file", path]))
    for label, extra in runs:
        t0 = time.perf_counter()
        p = subprocess.run([sys.executable, "-m", "ehl_multigrid", "traction", name, f"--slip={SLIPS}", "--json",
                            "--no-plots", "--out", str(Path(tmp) / label), *extra], capture_output=True, text=True)
        row = {"exit_code": p.returncode, "wall_s": time.perf_counter() - t0}
        try:
            d = json.loads(p.stdout)
            row.update({k: d[k] for k in ("slip", "friction_coefficient", "max_temperature_rise",
                                          "mean_temperature_rise", "converged")})
        except (json.JSONDecodeError, KeyError):
            row["stderr"] = p.stderr[-1000:]
        out[label] = row
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--fidelity", default="fast", choices=["fast", "standard", "reference"])
    ap.add_argument("--scenes", default=",".join(SCENES))
    a = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    path = OUT / f"machine_elements_{a.fidelity}.json"
    done = json.loads(path.read_text()) if path.exists() else {}
    for name in a.scenes.split(","):
        if name in done:
            continue
        with tempfile.TemporaryDirectory() as tmp:
            p, wall = run_scene(name, a.fidelity, tmp)
            row = {"exit_code": p.returncode, "wall_s": wall}
            try:
                d = json.loads(p.stdout)
                row["plan"] = d.get("plan")
                row.update(films(d["hdf5"]))
                row["thermal_traction"] = thermal_traction(name, d["hdf5"], tmp)
            except (json.JSONDecodeError, KeyError) as exc:
                row["error"] = f"{type(exc).__name__}: {exc}"
                row["stderr"] = p.stderr[-2000:]
        done[name] = row
        print(name, json.dumps(row))
        tmpf = path.with_suffix(".tmp")
        tmpf.write_text(json.dumps(done, indent=1))
        tmpf.replace(path)


if __name__ == "__main__":
    main()
