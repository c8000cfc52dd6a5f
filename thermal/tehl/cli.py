"""``ehl tehl``: thermal EHL line solve (one slip) or TEHL traction curve (several slips),
and the thermal properties ``ehl show --json`` can list."""

from __future__ import annotations

import argparse
import dataclasses
import math
from typing import Any

import numpy as np

from ehl_multigrid.app.console import accuracy_argument, print_table
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.scene import Scene, load_scene

from ..slips import parse_slips


def thermal_properties(scene: Scene) -> dict[str, float]:
    """The oil's thermal properties and the thermal loading (:meth:`Scene.thermal_properties`)."""
    return scene.thermal_properties()


def solve_payload(r: Any) -> dict[str, Any]:
    """The ``--json`` keys of a thermal solve (``Hc``, ``Hm``, ``Hc_isothermal``, ``friction``,
    ``T_max``, ``heat_balance_error`` and the rest of :meth:`TEHLLineResult.summary`)."""
    out = r.summary()
    out["outer"] = [{k: v for k, v in o.items()} for o in r.outer]
    return out


def require_computed(sol: Any) -> Any:
    """The solver's own result of the front door's ``sol``; a :class:`ConvergenceError` with its
    message (exit 3, naming why) when the solve raised and nothing was computed (the
    application's :func:`ehl_multigrid.app.solved.require_computed`, which this layer may not import)."""
    if sol.raw is None:
        raise ConvergenceError(sol.message)
    return sol.raw


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "tehl",
        help="thermal EHL line contact: pressure, film and temperature solved together (Eyring flow)",
        description="Thermal EHL (generalised Reynolds, Yang & Wen 1990, with the thermal layer's "
                    "Eyring and energy equations): one slip gives the solution, several a traction curve.",
    )
    add_arguments(p)
    p.set_defaults(func=run_tehl)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", help="built-in scene name or TOML file (line contact)")
    p.add_argument("--slip", default=None, help="slip S (comma list or min:max:n gives a curve; default: the scene's)")
    p.add_argument("--points", type=int, default=None, help="EHL grid points (2^k + 1, default 513)")
    p.add_argument("--nz", type=int, default=None, help="thermal intervals across the film (default 20)")
    p.add_argument("--no-compression", dest="compressive_heating", action="store_false",
                   help="leave the compressive heating out of the energy equation (the thesis's (3.5))")
    p.add_argument("--accuracy", type=accuracy_argument, default=0.005,
                   help="relative accuracy wanted for Hc and Hm (default 0.005): one slip without --points "
                        "and --nz is refined until its estimate meets it (as 'ehl solve --thermal'); a given "
                        "grid and a curve are judged against it; 'none' judges on the iteration alone")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--no-estimate", dest="estimate", action="store_false",
                   help="skip the error estimate (a curve estimates it at its first and last slip "
                        "and at its largest friction: about three more solves each); the film is then "
                        "judged on its outer iteration alone (--accuracy does not apply)")


def curve_slips_to_estimate(curve: list[Any]) -> list[int]:
    """Indices of a traction curve whose error is estimated: the first and last slip and the
    largest |friction coefficient| (the traction peak, where the heating is largest)."""
    mu = [abs(r.friction_coefficient) for r in curve]
    return sorted({0, len(curve) - 1, int(np.argmax(mu))})


def curve_error(curve: list[Any]) -> dict[str, Any]:
    """Error estimate of a TEHL traction curve (:func:`thermal.tehl.accuracy.estimate_error`
    at :func:`curve_slips_to_estimate`): per estimated slip, and the largest of each quantity
    over them (NaN when one of them could not be measured) as the curve's ``*_error`` keys; the
    friction's relative error leaves out slips whose friction is below 1 % of the curve's largest."""
    from .accuracy import QUANTITIES, estimate_error

    mu_max = max(abs(r.friction_coefficient) for r in curve)
    per = []
    for i in curve_slips_to_estimate(curve):
        try:
            est = estimate_error(curve[i]).payload()
        except ConvergenceError as exc:
            # a solve of the estimate failed: that slip's error is unknown, the curve is kept
            # (appendix C at slips 0-2: the S = 2 estimate's outer iteration ran out after 175 s)
            keys = [f"{k}_error" for k in QUANTITIES if k != "T_max"] + ["T_max_error_K"]
            per.append({"slip": curve[i].slip, **dict.fromkeys(keys, math.nan),
                        "estimate_failed": str(exc).splitlines()[0]})
            continue
        row = {"slip": curve[i].slip, **{k: v for k, v in est.items() if k.endswith(("_error", "_K"))}}
        if abs(curve[i].friction_coefficient) < 0.01 * mu_max:
            # near zero slip the friction is ~0 and its relative error says nothing
            row["friction_coefficient_error"] = None
        per.append(row)
    keys = [k for k in per[0] if k not in ("slip", "estimate_failed")]
    worst = {}
    for k in keys:
        vals = [p[k] for p in per if p[k] is not None]
        worst[k] = math.nan if not vals or any(not math.isfinite(v) for v in vals) else max(vals)
    return {**worst, "error_at_slips": per}


def traction_curve_films(scene: Scene, slips: list[float], options: Any) -> list[Any]:
    """The TEHL films of a traction curve through the front door, on the grid of ``options``
    (a :class:`~thermal.tehl.options.TEHLOptions`): each slip solved without its estimate
    (``estimate=False``, judged on its outer iteration) and continuing from the previous
    slip's solution (``start``: its isothermal start and film, or a starved inlet's meniscus),
    as :func:`thermal.tehl.line.tehl_traction_curve` solves them. A slip that fails ends the
    curve: :class:`ConvergenceError` with its message (exit 3)."""
    from ehl_multigrid import front

    grid = {"points": options.points, "nz": options.nz, "box": options.box,
            "compressive_heating": options.compressive_heating}
    sols: list[Any] = []
    for s in slips:
        sol = front.solve(scene, physics="thermal", accuracy=None,
                          options={**grid, "slip": float(s), "estimate": False, "start": sols[-1] if sols else None})
        require_computed(sol)
        sols.append(sol)
    return [sol.raw.result for sol in sols]


def run_tehl(args: argparse.Namespace) -> dict[str, Any]:
    """``ehl tehl``: every film through the front door :func:`ehl_multigrid.solve` (the
    thermal physics). One slip: refined towards ``--accuracy`` unless ``--points`` or ``--nz``
    fix the grid (then judged); ``--no-estimate``: the film alone, judged on its outer
    iteration. Several slips: a traction curve on one grid (the one the accuracy loop refines
    the largest slip to, unless given), each slip solved without its estimate and continuing
    from the previous slip's film (option ``start``); the curve is then judged at its first
    and last slip and its friction peak (:func:`curve_error`)."""
    from ehl_multigrid import front

    from .options import TEHLOptions

    scene = load_scene(args.scene)
    if scene.kind != "line":
        raise InputError(f"scene {scene.name!r} is a {scene.kind} contact; 'ehl tehl' solves line contacts "
                         f"(a {scene.kind} contact's thermal EHL film at one slip: "
                         f"ehl solve {scene.name} --thermal [--slip S])")
    changes = {k: v for k, v in (("points", args.points), ("nz", args.nz)) if v is not None}
    accuracy = getattr(args, "accuracy", None)
    estimate = getattr(args, "estimate", True)
    opts = TEHLOptions(**changes, compressive_heating=getattr(args, "compressive_heating", True))
    slips = parse_slips(args.slip) if args.slip is not None else [scene.slip]
    if len(slips) == 1:
        options = {**changes, "compressive_heating": opts.compressive_heating, "slip": slips[0]}
        if estimate:
            # refined towards --accuracy unless --points or --nz fixes the grid (then judged)
            sol = front.solve(scene, physics="thermal", accuracy=accuracy, options=options)
        else:
            # the film alone: its error unknown, so judged on its outer iteration
            sol = front.solve(scene, physics="thermal", accuracy=None, options={**options, "estimate": False})
        done = require_computed(sol)
        r = done.result
        payload = {"scene": scene.name, **solve_payload(r), **{"properties": thermal_properties(scene)}}
        if done.estimate is not None:
            payload.update(done.estimate.payload(), points=r.options.points, nz=r.options.nz,
                           wall_total_s=sol.outcome.wall_s)
        payload.update(message=sol.message, status=sol.status.label)
        if not args.json:  # with --json the ehl command prints the returned payload
            print_table({k: v for k, v in payload.items() if k not in ("outer", "properties")})
        return payload
    calibrated = None
    if accuracy is not None and not changes and estimate:
        # the curve's grid: the one the accuracy loop refines the largest slip's solve to (the
        # most heating), through the front door; the curve is then judged at its three slips
        at = max(slips, key=abs)
        sol = front.solve(scene, physics="thermal", accuracy=accuracy,
                          options={"compressive_heating": opts.compressive_heating, "slip": at})
        ro = require_computed(sol).result.options
        opts = dataclasses.replace(opts, points=ro.points, nz=ro.nz, box=ro.box)
        calibrated = {"slip": at, "points": ro.points, "nz": ro.nz, "box": ro.box, "status": sol.status.label}
    curve = traction_curve_films(scene, slips, opts)
    payload = {"scene": scene.name, "slip": [r.slip for r in curve],
               "friction_coefficient": [r.friction_coefficient for r in curve],
               "friction": [r.friction for r in curve], "Hc": [r.Hc for r in curve], "Hm": [r.Hm for r in curve],
               "Hc_isothermal": curve[0].Hc_isothermal, "T_max": [r.T_max for r in curve],
               "heat_balance_error": [r.heat_balance_error for r in curve],
               "converged": all(bool(r.report.converged) for r in curve),
               "wall_s": sum(r.wall_s for r in curve)}
    if calibrated is not None:
        payload["grid_from"] = calibrated
    if curve[0].starved is not None:
        # a finite [supply] hoil: each slip's film is starved at its own meniscus
        payload.update({k: [r.starved[k] for r in curve] for k in ("meniscus_x", "Hc_ratio", "mass_balance_error")})
        payload["hoil"] = curve[0].starved["hoil"]
    if estimate:
        payload.update(curve_error(curve))
        worst = max(payload["Hc_error"], payload["Hm_error"])
        if accuracy is not None and payload["converged"] and not worst <= accuracy:
            # a curve is solved on one given grid: judged, not refined
            payload["status"] = "inaccurate"
            failed = [f"slip {p['slip']:g}: {p['estimate_failed']}" for p in payload["error_at_slips"]
                      if "estimate_failed" in p]
            payload["message"] = (
                f"the curve's error is not known: its estimate failed at {'; '.join(failed)}" if failed else
                f"the curve's largest estimated film error ({worst:.2g}) exceeds the accuracy "
                f"{accuracy:g} on {opts.points} points: give a finer --points")
    if not args.json:
        print(f"  {'slip':>8} {'mu':>9} {'Hc':>8} {'Hm':>8} {'T_max':>8}")
        for r in curve:
            print(f"  {r.slip:8.4g} {r.friction_coefficient:9.4g} {r.Hc:8.4g} {r.Hm:8.4g} {r.T_max:8.4g}")
        if "Hc_error" in payload:
            print(f"  estimated errors (largest at slips {[p['slip'] for p in payload['error_at_slips']]}): "
                  f"mu {payload['friction_coefficient_error']:.2g}, Hc {payload['Hc_error']:.2g}, "
                  f"Hm {payload['Hm_error']:.2g}, T_max {payload['T_max_error_K']:.2g} K")
    return payload


def solve_mode(args: argparse.Namespace, scene: Scene) -> dict[str, Any]:
    """``ehl solve SCENE --thermal``: a TEHL solve (line or point) at ``args.slip`` (default the
    scene's) with its error budget (:func:`thermal.tehl.accuracy.estimate_error`: grid along X
    and across the film, box, iteration), and ``args.compressive_heating`` (default True; the
    ``--no-compression`` flag).

    With an accuracy target (``args.accuracy``, relative error of Hc and Hm; ``ehl solve``'s
    default 0.005) and neither ``--points`` nor ``--nz`` given, the grid (from 513 points line,
    257 point, nz 20), nz and box are refined until the estimate meets the target or the budget
    runs out (``args.max_points``, default 16385 line and 1025 point; nz 80; a box 4 times the
    default; ``args.time_budget``, default 600 s); explicit ``--points``/``--nz`` are only judged. ``converged`` is true only
    when the outer iteration converged and the estimate meets the target (status
    ``inaccurate`` otherwise). Returns the payload of :func:`solve_payload` with the error keys
    (printed as JSON by ``--json``).

    A line scene with a finite ``[supply] hoil`` is solved starved (the meniscus search of
    :func:`thermal.tehl.line.solve_tehl_line_starved`; ``meniscus_x``, ``Hc_ratio``,
    ``mass_balance_error`` ... in the payload); a point scene with one is refused. A slip
    outside [-2, 2] is refused before any solve; ``args.threads`` sets numba's threads for
    the solve."""
    point = scene.kind != "line"
    slip = getattr(args, "slip", None)
    if slip is not None and not -2.0 <= slip <= 2.0:  # also catches nan
        raise InputError(f"--slip {slip:g} is outside the allowed range [-2, 2] (S = 2(u1-u2)/(u1+u2); "
                         f"2 = pure sliding)")
    if not point and (getattr(args, "half", False) or getattr(args, "full_domain", False)):
        raise InputError("--half and --full-domain apply to point contacts, not to a line contact")
    if point:
        from .point import require_flooded_point

        require_flooded_point(scene)
    return _solve_mode(args, scene, point, slip)


#: the ``ehl solve`` options (argparse names) the ``--thermal`` mode reads; ``ehl solve``
#: refuses any other one given with ``--thermal`` (besides the scene, --contact as a check,
#: --json, --out and --no-plots)
solve_mode.honoured_options = frozenset({
    "scene", "contact", "accuracy", "max_points", "time_budget", "points", "nz", "slip",
    "compressive_heating", "threads", "half", "thermal"})


def _solve_mode(args: argparse.Namespace, scene: Scene, point: bool, slip: float | None) -> dict[str, Any]:
    from ehl_multigrid import front

    # the front door's thermal physics (thermal.front.solve_thermal): from 513 points (line) or
    # 257 (point) and nz 20, refined towards the accuracy unless --points or --nz is given
    options: dict[str, Any] = {k: v for k in ("points", "nz") if (v := getattr(args, k, None)) is not None}
    options["compressive_heating"] = getattr(args, "compressive_heating", True)
    for key in ("max_points", "time_budget", "threads"):
        if getattr(args, key, None) is not None:
            options[key] = getattr(args, key)
    if slip is not None:
        options["slip"] = slip
    accuracy = getattr(args, "accuracy", None)
    from ehl_multigrid.app.console import Progress

    keeper = front.StopKeeper()  # a stop writes the sequence's most accurate finished film
    with Progress("ehl solve") as prog:  # each solve of the accuracy sequence, on stderr
        sol = keeper.solve(scene, physics="thermal", accuracy=accuracy, options=options, progress=prog.say)
    done = require_computed(sol)
    r = done.result
    payload = {"scene": scene.name, "contact": scene.kind, **r.summary(),
               "outer": [dict(o) for o in r.outer], "properties": thermal_properties(scene),
               "points": r.options.points, "nz": r.options.nz, "box": r.options.box,
               **done.estimate.payload(), "refinements": [vars(s) for s in done.refinements],
               # the whole accuracy sequence (wall_s is the returned solve's), as a steady solve says
               "wall_total_s": sol.outcome.wall_s}
    if accuracy is not None:
        payload["accuracy"] = accuracy
    if payload["converged"] and not done.accurate:
        # as for 'ehl solve': converged means the iteration converged and the estimate meets
        # the target
        payload["converged"] = False
        payload["status"] = "inaccurate"
        payload["message"] = "iteration converged but " + done.message
    else:
        payload["message"] = done.message
    # the status word every solve's --json carries (ehl solve: "converged", "inaccurate", ...)
    payload.setdefault("status", sol.status.label)
    out = getattr(args, "out", None)
    if out is not None:
        from pathlib import Path

        from ehl_multigrid.model.paths import output_file, safe_stem

        folder = Path(out)
        folder.mkdir(parents=True, exist_ok=True)
        res = sol.to_result()
        payload["hdf5"] = str(res.save(output_file(folder, safe_stem(f"{scene.name}_tehl"), ".h5")))
        if not getattr(args, "no_plots", False):
            from .plots import plot_tehl

            payload["plots"] = [str(plot_tehl(res, output_file(folder, safe_stem(f"{scene.name}_tehl"), ".png")))]
    keeper.raise_stop(payload.get("hdf5", ""))
    if not getattr(args, "json", False):
        print_table({k: v for k, v in payload.items() if k not in ("outer", "properties", "error_budget", "refinements")})
    return payload
