"""``ehl transient SCENE``: a surface feature from the scene's ``[feature]`` table passing
through the line contact of the scene (time-dependent isothermal EHL).

Registered through the ``ehl.commands`` entry point (``register``)."""

from __future__ import annotations

import argparse
from typing import Any

from ..app.console import add_common_options
from ..line.problem import LineProblem
from ..model.errors import InputError
from ..model.paths import output_file, safe_stem, writable_dir
from ..model.scene import load_scene
from .scene_feature import feature_from_scene_table
from .solve import SCHEMES, solve_transient_line

#: largest grid of the command line (a pass at 4097 points takes tens of minutes)
MAX_POINTS = 4097


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "transient",
        help="a surface feature (waviness, bump, dent) passing through a line contact",
        description="Time-dependent isothermal EHL of a line contact with the feature of the "
                    "scene's [feature] table on one surface (BDF2 steps, constant load).")
    p.add_argument("scene", help="built-in scene name or TOML file (line contact with [feature])")
    p.add_argument("--points", type=int, default=513, help="grid points (2^k + 1, default 513)")
    p.add_argument("--dt", type=float, default=None,
                   help="time step in T = t u_m/b (default: one mesh size at the faster speed)")
    p.add_argument("--steps", type=int, default=None, help="number of steps (default: until the feature has passed)")
    p.add_argument("--t-end", type=float, default=None, help="end time T instead of --steps")
    p.add_argument("--scheme", choices=list(SCHEMES), default="bdf2")
    p.add_argument("--snapshot-every", type=int, default=10, help="keep P and H every N steps")
    p.add_argument("--xmin", type=float, default=-4.5, help="inlet X = x/b (default -4.5)")
    p.add_argument("--threshold", type=float, default=None,
                   help="report the fraction of the Hertzian contact with h below this [m]")
    p.add_argument("--animate", action="store_true", help="also write a GIF of H and P")
    add_common_options(p)
    p.set_defaults(func=run_transient)


def run_transient(args: argparse.Namespace) -> dict[str, Any]:
    if not 65 <= args.points <= MAX_POINTS:
        raise InputError(f"--points = {args.points} is outside the allowed range [65, {MAX_POINTS}]")
    scene = load_scene(args.scene)
    if scene.kind != "line":
        raise InputError(f"contact.kind = {scene.kind!r}: 'ehl transient' solves line contacts")
    pb = LineProblem.from_scene(scene, xmin=args.xmin)
    feature, body = feature_from_scene_table(scene.feature, pb)
    res = solve_transient_line(pb, feature, body=body, slide_roll=scene.slip, dt=args.dt,
                               steps=args.steps, t_end=args.t_end, points=args.points,
                               scheme=args.scheme, snapshot_every=args.snapshot_every)
    out = writable_dir(args.out)
    stem = safe_stem(f"transient_{scene.name}")
    h5 = res.to_hdf5(output_file(out, stem, ".h5"))
    summary = res.summary()
    scale = pb.b**2 / pb.R
    payload: dict[str, Any] = {
        "scene": scene.name, "file": str(h5), "converged": True,
        "feature": feature.describe(), "body": body, "slide_roll": scene.slip,
        "points": summary["points"], "dt": summary["dt"], "steps": summary["steps"],
        "hc_steady": summary["Hc_steady"] * scale, "hc_min": summary["Hc_min"] * scale,
        "hc_max": summary["Hc_max"] * scale, "hm_min": summary["Hm_min"] * scale,
        "pressure_fluctuation": summary["dP_max"] * pb.pmax,
        "deformed_amplitude_ratio": summary["Ad_over_Ai"],
        "cycles_mean": summary["cycles_mean"], "stalled_steps": summary["stalled_steps"],
        "residual_max": summary["residual_max"], "wall_per_step_s": summary["wall_per_step_s"],
        "wall_s": summary["wall_s"],
    }
    if args.threshold is not None:
        payload["fraction_below_threshold"] = res.fraction_below(args.threshold / scale)
    if not args.no_plots:
        from .plots import animate, plot_series, plot_snapshots

        payload["plots"] = [str(plot_series(res, output_file(out, stem + "_series", ".png"))),
                            str(plot_snapshots(res, output_file(out, stem + "_snapshots", ".png")))]
        if args.animate:
            payload["plots"].append(str(animate(res, output_file(out, stem, ".gif"))))
    if not args.json:
        print(f"{scene.name}: {feature.kind} on body {body}, S = {scene.slip:g}, {summary['steps']} steps "
              f"of dT = {summary['dt']:.4g} on {summary['points']} points: hc {payload['hc_min']:.4g}"
              f"..{payload['hc_max']:.4g} m (smooth {payload['hc_steady']:.4g} m), hm min "
              f"{payload['hm_min']:.4g} m; written {h5}")
    return payload
