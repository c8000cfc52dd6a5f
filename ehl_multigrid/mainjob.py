"""``ehl run``: the main job on a scene.

The core stage resolves the scene, computes Hertz and the fitted film, and stores the Hertz
pressure with the fitted film as fields. Layers above add stages through the ``ehl.stages``
entry-point group (a callable ``stage(scene, outdir, args) -> dict``), run in name order,
so the core never imports them.
"""

from __future__ import annotations

import argparse
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

import numpy as np

from .hertz import hertz_pressure_line, hertz_pressure_point
from .results import Result
from .scene import Scene, load_scene


def hertz_result(scene: Scene, n: int = 201) -> Result:
    """Hertz pressure and fitted uniform film on the scene's contact, as a :class:`Result`."""
    hz = scene.hertz
    Hc, hc = scene.central_film_fit()
    res = Result("hertz_fit", scene=scene)
    x = np.linspace(-1.5 * hz.a, 1.5 * hz.a, n)
    res.add_coord("x", x, "m", "rolling direction")
    if scene.kind == "line":
        res.add_field("p", hertz_pressure_line(x, hz.b, hz.pmax), "Pa", ("x",), "Hertz pressure")
    else:
        y = np.linspace(-1.5 * hz.b, 1.5 * hz.b, n)
        res.add_coord("y", y, "m", "transverse direction")
        X, Y = np.meshgrid(x, y, indexing="ij")
        res.add_field("p", hertz_pressure_point(X, Y, hz.a, hz.b, hz.pmax), "Pa", ("x", "y"), "Hertz pressure")
    for k, v in scene.summary().items():
        if isinstance(v, (int, float)):
            res.set_scalar(k, v, _UNITS.get(k, "-"))
    res.meta["stage"] = "hertz + fitted film"
    return res


_UNITS = {
    "load": "N", "us": "m/s", "T_oil": "degC", "E_reduced": "Pa", "Rx": "m", "Ry": "m",
    "eta0": "Pa s", "alpha": "1/Pa", "pmax": "Pa", "mean_pressure": "Pa", "area": "m^2",
    "hc_fit": "m", "a": "m", "b": "m", "length": "m",
}


def plot_hertz(res: Result, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sc = res.scene
    fig, ax = plt.subplots(figsize=(6, 3.5))
    x = res["x"]
    p = res["p"] if res["p"].ndim == 1 else res["p"][:, res["p"].shape[1] // 2]
    ax.plot(x * 1e3, p / 1e9, label="Hertz pressure")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("p [GPa]")
    ax2 = ax.twinx()
    inside = p > 0
    ax2.plot(x[inside] * 1e3, np.full(inside.sum(), res.scalars["hc_fit"] * 1e9), "C1--", label="fitted central film")
    ax2.set_ylabel("h [nm]")
    ax2.set_ylim(0, 2 * res.scalars["hc_fit"] * 1e9)
    ax.set_title(f"{sc.name}: pmax = {res.scalars['pmax'] / 1e9:.3g} GPa, hc(fit) = {res.scalars['hc_fit'] * 1e9:.3g} nm")
    fig.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def run_main_job(args: argparse.Namespace) -> dict[str, Any]:
    scene = load_scene(args.scene)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    res = hertz_result(scene)
    h5 = res.save(out / f"{scene.name}.h5")
    payload: dict[str, Any] = dict(scene.summary())
    payload["hdf5"] = str(h5)
    if not args.no_plots:
        payload["png"] = str(plot_hertz(res, out / f"{scene.name}_hertz.png"))
    for ep in sorted(entry_points(group="ehl.stages"), key=lambda e: e.name):
        stage = ep.load()
        payload[ep.name] = stage(scene, out, args)
    if not args.json:
        from .cli import print_table

        print(f"scene {scene.name}: {scene.description}")
        print_table({k: v for k, v in payload.items() if not isinstance(v, dict)})
    return payload
