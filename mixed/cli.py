"""``ehl stribeck``: Stribeck curves of a scene (isothermal, thermal, starved).

Registered through the ``ehl.commands`` entry point (``stribeck = "mixed.cli:register"``).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from ehl_multigrid.app.console import add_common_options, locked_command, print_table
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.paths import output_file, safe_stem, writable_dir

#: Most sum velocities of one curve (isothermal: GW load sharing per point, milliseconds).
MAX_POINTS = 100000
#: Most thermal film-friction solves of one ``ehl stribeck --thermal`` (curves x speeds; about
#: 40 per second: 2000 take under a minute).
MAX_THERMAL_SOLVES = 2000


def _float_list(text: str) -> list[float]:
    try:
        vals = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a list of numbers (e.g. 0.5,1,2)") from None
    if not vals:
        raise argparse.ArgumentTypeError("empty list")
    return vals


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "stribeck",
        help="Stribeck curve (friction, load sharing, film, regime against sum velocity) of a rough contact",
        description="Mixed-lubrication Stribeck curve (Liu 2002, chapters 4-6): Greenwood-Williamson "
        "asperities + Moes/Nijenbanning fitted film, isothermal or thermal film friction, starved inlets.",
    )
    p.add_argument("scene", help="built-in scene name or TOML file (needs a [roughness] table)")
    p.add_argument("--thermal", action="store_true", help="film friction from the thermal Roelands-Eyring solver (ch. 5.4)")
    p.add_argument("--hoil", type=_float_list, default=None, metavar="LIST",
                   help="inlet oil films hoil/Rq for starved curves, e.g. 0.5,1,2 (default: the scene's supply.hoil_over_sigma)")
    p.add_argument("--delta", default=None, metavar="DELTA",
                   help="Chevalier's exponent of the starved film (6.1): a number in [0.5, 20], or 'inlet' for the "
                        "exponent from the flooded inlet at each speed (default: the scene's supply.delta, 3.5)")
    p.add_argument("--n", type=int, default=None, help="number of sum velocities (default: scene range or 60)")
    p.add_argument("--us-min", type=float, default=None, help="smallest sum velocity [m/s]")
    p.add_argument("--us-max", type=float, default=None, help="largest sum velocity [m/s]")
    p.add_argument("--load", type=float, default=None, help="normal load [N] (default: the scene's)")
    p.add_argument("--slip", type=float, default=None, help="slip S = 2(u1-u2)/(u1+u2) (default: the scene's)")
    p.add_argument("--bl-fraction", type=float, default=None, help="asperity load share at or above which the regime is BL (default 0.95)")
    p.add_argument("--ehl-fraction", type=float, default=None, help="asperity load share at or below which the regime is EHL (default 0.05)")
    add_common_options(p)
    p.set_defaults(func=locked_command(run_stribeck, "ehl stribeck"))


def run_stribeck(args: argparse.Namespace) -> dict:
    from ehl_multigrid.model.scene import load_scene

    from .stribeck import default_us, stribeck_cases, stribeck_options, stribeck_result

    t0 = time.perf_counter()
    if args.n is not None and not 1 <= args.n <= MAX_POINTS:
        raise InputError(f"--n = {args.n} must be an integer in [1, {MAX_POINTS}] (number of sum velocities)")
    out = writable_dir(args.out)
    scene = load_scene(args.scene)
    if scene.roughness is None:
        raise InputError(f"scene {scene.name!r} has no [roughness] table; `ehl stribeck` needs Rq, n, beta (and sigma_s, dd)")
    if args.load is not None or args.slip is not None:
        changes = {k: v for k, v in (("load", args.load), ("slip", args.slip)) if v is not None}
        scene = scene.with_operating(**changes)
    if args.delta is not None:
        try:
            delta: float | str = float(args.delta)
        except ValueError:
            delta = args.delta
        scene = scene.with_supply(delta=delta)
    opts = stribeck_options(scene, bl_fraction=args.bl_fraction, ehl_fraction=args.ehl_fraction)
    us = default_us(scene, args.n, args.us_min, args.us_max)
    hoil = list(scene.supply.hoil_over_sigma) if args.hoil is None else args.hoil
    for v in hoil:
        if not v > 0:
            raise InputError(f"--hoil value {v:g} must be > 0 (inlet oil film hoil/Rq)")
    if args.thermal and us.size * (1 + len(hoil)) > MAX_THERMAL_SOLVES:
        raise InputError(f"--thermal with {us.size} sum velocities and {1 + len(hoil)} curve(s) needs "
                         f"{us.size * (1 + len(hoil))} thermal solves; at most {MAX_THERMAL_SOLVES} "
                         "(lower --n or the scene's ranges.us n)")
    stem = safe_stem(f"stribeck_{scene.name}" + ("_thermal" if args.thermal else ""))
    h5 = output_file(out, stem, ".h5")

    bar = None
    progress = None
    if not args.json:
        from tqdm import tqdm

        total = (1 + len(hoil)) * (us.size if args.thermal else 1)
        bar = tqdm(total=total, desc=f"stribeck {scene.name}", unit="pt" if args.thermal else "curve", file=sys.stderr)
        progress = bar.update
    try:
        curves = stribeck_cases(scene, us, hoil_over_sigma=hoil, thermal=args.thermal, options=opts,
                                save_path=h5, progress=progress)
    except BaseException:
        mark_incomplete(h5)  # the finished curves stay, saying that the rest is missing
        raise
    finally:
        if bar is not None:
            bar.close()
    wall = time.perf_counter() - t0
    result = stribeck_result(scene, curves, thermal=args.thermal, wall_s=wall)
    result.save(h5)
    files = [str(h5)]
    if not args.no_plots:
        from .plots import stribeck_figures

        files += [str(f) for f in stribeck_figures(curves, out, stem)]

    payload = _payload(scene, curves, args.thermal, wall, files)
    # the thesis's Stribeck model takes the fitted film at every speed (chapter 5): no film is
    # solved and its error is not stated; the fit's bias at the operating point says how far off
    # it may be (series B disc 1 at 1 GPa: 17-38 % above solved films over 0.37-12 m/s)
    fit_note = scene.summary()["hc_fit_note"]
    payload["film_source"] = ("Moes/Nijenbanning fitted film at each speed (chapter 5), not a solved film; "
                              f"its error is not stated (at the operating point: {fit_note})")
    print(f"ehl stribeck: note: the films are the fit's, not solved ones: {fit_note}", file=sys.stderr)
    if not args.json:
        c = curves[0]
        print(f"# {scene.name}: {scene.kind} contact, P = {c.sharing.load:.6g} N, pmax = {c.sharing.pmax / 1e9:.4g} GPa, "
              f"slip = {c.friction.slip:g}, {'thermal' if args.thermal else 'isothermal'}")
        print(f"{'us [m/s]':>10} {'f':>8} {'f_asp':>8} {'f_film':>8} {'Pa/P':>9} {'gamma1':>10} {'hfr [m]':>10} {'hss [m]':>11} regime")
        step = max(1, c.us.size // 20)
        for i in range(0, c.us.size, step):
            print(f"{c.us[i]:10.4g} {c.friction.coefficient[i]:8.4f} {c.friction.asperity[i]:8.4f} {c.friction.film[i]:8.4f} "
                  f"{c.sharing.asperity_fraction[i]:9.3g} {c.sharing.gamma1[i]:10.4g} {c.sharing.hfr[i]:10.3e} "
                  f"{c.sharing.hss[i]:11.3e} {c.regime_names()[i]}")
        print_table({k: v for k, v in payload.items() if not isinstance(v, (list, dict))})
        for cs, case in zip(curves[1:], payload.get("cases", []), strict=True):
            # each starved curve in one line (its table is in the JSON and the HDF5 file)
            f = cs.friction.coefficient
            k = int(np.argmin(f))
            print(f"  starved hoil/Rq = {case['hoil_over_sigma']:g} (hoil {case['hoil'] * 1e9:.4g} nm): f = "
                  f"{f[0]:.4g} at the slowest speed, minimum {f[k]:.4g} at {cs.us[k]:.4g} m/s, {f[-1]:.4g} at the "
                  f"fastest; regimes {' -> '.join(dict.fromkeys(cs.regime_names()))}")
        for f in files:
            print(f"  wrote {f}")
    return payload


def mark_incomplete(path: Path) -> None:
    """Set ``complete = False`` on the partial result at ``path`` (if one was written)."""
    import h5py

    try:
        with h5py.File(path, "r+") as f:
            f.attrs["complete"] = np.bool_(False)
    except OSError:
        pass  # nothing written yet


def _curve_dict(c, thermal: bool) -> dict[str, Any]:
    d: dict[str, Any] = {
        "hoil": c.hoil,
        "hoil_over_sigma": c.hoil / c.sharing.roughness.Rq,
        "delta_used": c.sharing.delta_used,
        "friction_coefficient": c.friction.coefficient,
        "friction_asperity": c.friction.asperity,
        "friction_film": c.friction.film,
        "Pa": c.sharing.Pa,
        "Ph": c.sharing.Ph,
        "gamma1": c.sharing.gamma1,
        "gamma2": c.sharing.gamma2,
        "hfr": c.sharing.hfr,
        "hs": c.sharing.hs,
        "hss": c.sharing.hss,
        "Lambda": c.sharing.Lambda,
        "asperity_fraction": c.sharing.asperity_fraction,
        "regime": c.regime_names(),
        "boundary_guard": c.sharing.boundary,
        "us_bl_ml": c.transitions.get("us_bl_ml", math.nan),
        "us_ml_ehl": c.transitions.get("us_ml_ehl", math.nan),
    }
    if thermal:
        d["mean_temperature_rise"] = c.friction.mean_temperature_rise
        d["max_temperature_rise"] = c.friction.max_temperature_rise
        d["thermal_converged"] = c.friction.thermal_converged
    return d


def _payload(scene, curves, thermal: bool, wall: float, files: list[str]) -> dict[str, Any]:
    c0 = curves[0]
    out: dict[str, Any] = {
        "scene": scene.name,
        "contact": scene.kind,
        "load": c0.sharing.load,
        "pmax": c0.sharing.pmax,
        "slip": c0.friction.slip,
        "fc": c0.friction.fc,
        "Rq": c0.sharing.roughness.Rq,
        "hs_min": c0.sharing.hs_min,
        "thermal": thermal,
        "bl_fraction": c0.options["bl_fraction"],
        "ehl_fraction": c0.options["ehl_fraction"],
        "delta": c0.sharing.delta,
        "converged": all(c.converged for c in curves),
        "wall_s": wall,
        "us": c0.us,
    }
    out.update(_curve_dict(c0, thermal))
    if len(curves) > 1:
        out["cases"] = [_curve_dict(c, thermal) for c in curves[1:]]
    out["files"] = files
    return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in out.items()}
