"""``ehl transient SCENE``: a surface feature from the scene's ``[feature]`` table passing
through the line, point or elliptic contact of the scene (time-dependent isothermal EHL).

Registered through the ``ehl.commands`` entry point (``register``)."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import Any

from ..app.console import add_common_options
from ..model.errors import InputError
from ..model.paths import output_file, safe_stem, writable_dir
from ..model.scene import load_scene
from .stepping import SCHEMES

#: largest grid of the command line (a pass at 4097 points takes tens of minutes)
MAX_POINTS = 4097
#: largest point-contact grid (points along X) of the command line: a pass at 513^2 takes
#: about an hour
MAX_POINT_POINTS = 513
#: default grids: line, point
DEFAULT_POINTS = {"line": 513, "point": 129}


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "transient",
        help="a surface feature (waviness, bump, dent) passing through a line or point contact",
        description="Time-dependent isothermal EHL of a line, point or elliptic contact with the "
                    "feature of the scene's [feature] table on one surface (BDF2 steps, constant load).")
    p.add_argument("scene", help="built-in scene name or TOML file (a contact with [feature])")
    p.add_argument("--points", type=int, default=None,
                   help="grid points along X (2^k + 1; default 513 line, 129 point)")
    p.add_argument("--dt", type=float, default=None,
                   help="time step in T = t u_m/b (point: t u_m/a) (default: one mesh size at the "
                        "faster speed)")
    p.add_argument("--steps", type=int, default=None, help="number of steps (default: until the feature has passed)")
    p.add_argument("--t-end", type=float, default=None, help="end time T instead of --steps")
    p.add_argument("--scheme", choices=list(SCHEMES), default="bdf2")
    p.add_argument("--snapshot-every", type=int, default=10, help="keep P and H every N steps")
    p.add_argument("--xmin", type=float, default=-4.5, help="inlet X = x/b (point: x/a) (default -4.5)")
    p.add_argument("--threshold", type=float, default=None,
                   help="report the fraction of the Hertzian contact with h below this [m] "
                        "(point contacts also: the fraction of the load carried there)")
    p.add_argument("--animate", action="store_true", help="also write a GIF of H and P")
    add_common_options(p)
    p.set_defaults(func=run_transient)


def run_transient(args: argparse.Namespace) -> dict[str, Any]:
    if args.points is not None:
        _require_points(args.points, MAX_POINTS)
    scene = load_scene(args.scene)
    if scene.kind != "line":
        return run_transient_point(args, scene)
    from ..line.problem import LineProblem
    from .scene_feature import feature_from_scene_table
    from .solve import solve_transient_line

    args.points = DEFAULT_POINTS["line"] if args.points is None else args.points
    pb = LineProblem.from_scene(scene, xmin=args.xmin)
    feature, body = feature_from_scene_table(scene.feature, pb)
    res = solve_transient_line(pb, feature, body=body, slide_roll=scene.slip, dt=args.dt,
                               steps=args.steps, t_end=args.t_end, points=args.points,
                               scheme=args.scheme, snapshot_every=args.snapshot_every)

    def figures() -> tuple[Callable, Callable, Callable]:
        from .plots import animate, plot_series, plot_snapshots

        return plot_series, plot_snapshots, animate

    return _report(args, scene, res, feature, body, pb.b**2 / pb.R, pb.pmax, None, figures)


def run_transient_point(args: argparse.Namespace, scene: Any) -> dict[str, Any]:
    """The point or elliptic contact of ``ehl transient``."""
    from ..point.problem import problem_from_scene
    from .point_solve import solve_transient_point
    from .scene_feature import point_feature_from_scene_table

    points = DEFAULT_POINTS["point"] if args.points is None else args.points
    _require_points(points, MAX_POINT_POINTS, f" for a {scene.kind} contact")
    pb = problem_from_scene(scene)
    feature, body = point_feature_from_scene_table(scene.feature, pb)
    res = solve_transient_point(pb, feature, body=body, slide_roll=scene.slip, dt=args.dt,
                                steps=args.steps, t_end=args.t_end, points=points, xmin=args.xmin,
                                scheme=args.scheme, snapshot_every=args.snapshot_every)

    def figures() -> tuple[Callable, Callable, Callable]:
        from .point_plots import animate_point, plot_point_series, plot_point_snapshots

        return plot_point_series, plot_point_snapshots, animate_point

    return _report(args, scene, res, feature, body, pb.a**2 / pb.Rx, pb.pmax, scene.kind, figures)


def _require_points(points: int, most: int, where: str = "") -> None:
    if not 65 <= points <= most:
        raise InputError(f"--points = {points} is outside the allowed range [65, {most}]{where}")


def _report(args: argparse.Namespace, scene: Any, res: Any, feature: Any, body: int, scale: float,
            pmax: float, contact: str | None, figures: Callable[[], tuple[Callable, Callable, Callable]],
            ) -> dict[str, Any]:
    """Write the run (HDF5, figures) and return the payload of ``ehl transient`` (printing a
    line without ``--json``). ``scale``: metres per film unit; ``pmax``: Pa per pressure unit;
    ``contact``: the point or elliptic contact's kind (None for a line contact)."""
    point = contact is not None
    out = writable_dir(args.out)
    stem = safe_stem(f"transient_{scene.name}")
    h5 = res.to_hdf5(output_file(out, stem, ".h5"))
    summary = res.summary()
    payload: dict[str, Any] = {"scene": scene.name, **({"contact": contact} if point else {}),
                               "file": str(h5), "converged": True, "feature": feature.describe(),
                               "body": body, "slide_roll": scene.slip, "points": summary["points"]}
    if point:
        payload["points_y"] = summary["points_y"]
    payload.update({
        "dt": summary["dt"], "steps": summary["steps"],
        "hc_steady": summary["Hc_steady"] * scale, "hc_min": summary["Hc_min"] * scale,
        "hc_max": summary["Hc_max"] * scale, "hm_min": summary["Hm_min"] * scale,
        "pressure_fluctuation": summary["dP_max"] * pmax,
        "deformed_amplitude_ratio": summary["Ad_over_Ai"],
        "cycles_mean": summary["cycles_mean"], "stalled_steps": summary["stalled_steps"],
        "residual_max": summary["residual_max"],
    })
    if point:
        payload["mass_balance_max"] = summary["mass_balance_max"]
    payload.update({"wall_per_step_s": summary["wall_per_step_s"], "wall_s": summary["wall_s"]})
    if args.threshold is not None:
        payload["fraction_below_threshold"] = res.fraction_below(args.threshold / scale)
        if point:
            payload["load_fraction_below_threshold"] = res.load_fraction_below(args.threshold / scale)
    if not args.no_plots:
        plot_series, plot_snapshots, animate = figures()
        payload["plots"] = [str(plot_series(res, output_file(out, stem + "_series", ".png"))),
                            str(plot_snapshots(res, output_file(out, stem + "_snapshots", ".png")))]
        if args.animate:
            payload["plots"].append(str(animate(res, output_file(out, stem, ".gif"))))
    if not args.json:
        grid = f"{summary['points']}x{summary['points_y']}" if point else f"{summary['points']}"
        print(f"{scene.name}: {feature.kind} on body {body}, S = {scene.slip:g}, {summary['steps']} steps "
              f"of dT = {summary['dt']:.4g} on {grid} points: hc {payload['hc_min']:.4g}"
              f"..{payload['hc_max']:.4g} m (smooth {payload['hc_steady']:.4g} m), hm min "
              f"{payload['hm_min']:.4g} m; written {h5}")
    return payload
