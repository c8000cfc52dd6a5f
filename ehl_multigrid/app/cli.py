"""The ``ehl`` command line.

The core defines ``scenes``, ``show``, ``fits``, ``run`` and ``solve``; the layers above
(thermal, mixed) add their own subcommands through the ``ehl.commands`` entry-point group,
so this module never imports them. An entry point names a callable
``register(subparsers) -> None`` that adds one subparser whose ``func(args) -> dict``
returns the JSON payload (and prints human-readable text when ``args.json`` is false).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable, Sequence
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

from ..model.errors import ConvergenceError, InputError
from .console import add_common_options, jsonable, print_payload, print_table

__all__ = ["add_common_options", "build_parser", "jsonable", "main", "print_payload", "print_table"]

EXIT_INPUT = 2
EXIT_CONVERGENCE = 3


# -- core subcommands ------------------------------------------------------------------------
def _cmd_scenes(args: argparse.Namespace) -> dict:
    from ..model.scene import builtin_scene_names, load_scene

    rows = []
    for name in builtin_scene_names():
        sc = load_scene(name)
        rows.append({"name": name, "contact": sc.kind, "description": sc.description})
    if not args.json:
        w = max(len(r["name"]) for r in rows)
        for r in rows:
            print(f"{r['name']:<{w}}  {r['contact']:<8}  {r['description']}")
    return {"scenes": rows}


def _cmd_show(args: argparse.Namespace) -> dict:
    from ..model.scene import load_scene

    sc = load_scene(args.scene)
    summary = sc.summary()
    if not args.json:
        print(f"# scene {sc.name}: {sc.description}")
        if sc.source:
            print(f"# source: {sc.source}")
        print(sc.to_toml())
        print("# derived")
        print_table(summary)
    return summary


def _cmd_fits(args: argparse.Namespace) -> dict:
    from ..model import fits, groups

    if args.contact == "line":
        if args.ellipticity != 1.0:
            raise InputError("--ellipticity applies to point contacts only")
        Hc = fits.moes_line_central(args.M, args.L, args.gamma1)
        terms = fits.moes_line_terms(args.M, args.L)
        lam, abar = groups.venner_line(args.M, args.L)
        Hc_v = groups.venner_from_moes_line(Hc, args.M)
    else:
        Hc = fits.nijenbanning_central(args.M, args.L, args.ellipticity, args.gamma1)
        terms = fits.nijenbanning_terms(args.M, args.L, args.ellipticity)
        lam, abar = groups.venner_point(args.M, args.L)
        Hc_v = groups.venner_from_moes_point(Hc, args.M)
    out = {
        "contact": args.contact, "M": args.M, "L": args.L, "theta": args.ellipticity,
        "gamma1": args.gamma1, "Hc": Hc, "Hc_venner": Hc_v,
        "lambda_venner": lam, "alpha_bar": abar,
    }
    out.update({k: float(v) for k, v in terms.items()})
    if not args.json:
        print_table(out)
    return out


def _cmd_run(args: argparse.Namespace) -> dict:
    from ..model.scene import load_scene
    from .mainjob import MainJobOptions, run_main_job

    options = MainJobOptions(out_dir=Path(args.out), fidelity=args.fidelity, tolerance=args.tolerance,
                             plots=not args.no_plots, quiet=args.json)
    return run_main_job(load_scene(args.scene), options)


def _cmd_solve(args: argparse.Namespace) -> dict:
    from .solve import run_solve

    return run_solve(args)


def _cmd_sweep(args: argparse.Namespace) -> dict:
    from ..model.scene import load_scene
    from .sweep import SweepSpec, parse_values, run_sweep

    params: dict[str, list[float]] = {}
    for item in args.param:
        if "=" not in item:
            raise InputError(f"--param {item!r} must be NAME=VALUES (e.g. operating.us=0.01:10:20:log)")
        name, spec = item.split("=", 1)
        params[name.strip()] = parse_values(spec)
    if not params:
        raise InputError("a sweep needs at least one --param NAME=VALUES")
    options: dict[str, Any] = {}
    for item in args.option:
        if "=" not in item:
            raise InputError(f"--option {item!r} must be KEY=VALUE")
        k, v = item.split("=", 1)
        options[k.strip()] = json.loads(v) if v.strip()[:1] in "[{0123456789-tfn" else v
    spec = SweepSpec(load_scene(args.scene), args.task, params, options)
    out = Path(args.out)
    table = run_sweep(spec, out, workers=args.workers, scheduler=args.scheduler, progress=not args.json)
    payload = {"cases": len(table.rows), "counts": table.counts, "table": str(out / "table.csv")}
    if not args.json:
        print_table({"cases": len(table.rows), **table.counts, "table": str(out / "table.csv")})
    return payload


def _cmd_plan(args: argparse.Namespace) -> dict:
    from ..model.scene import load_scene
    from .plan import make_plan, print_plan

    plan = make_plan(load_scene(args.scene), fidelity=args.fidelity, tolerance=args.tolerance)
    if not args.json:
        print_plan(plan)
    return plan.to_dict()


def _positive_float(s: str) -> float:
    try:
        v = float(s)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{s!r} is not a number") from None
    return v


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="ehl",
        description="Film thickness, pressure, temperature and friction in lubricated concentrated contacts.",
    )
    parser.add_argument("--version", action="store_true", help="print the package version")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    p = sub.add_parser("scenes", help="list the built-in scenes")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_scenes)

    p = sub.add_parser("show", help="print a resolved scene with derived quantities (Hertz, Moes groups, fitted film)")
    p.add_argument("scene", help="built-in scene name or TOML file")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_show)

    p = sub.add_parser("fits", help="evaluate the Moes (line) or Nijenbanning (point) central-film fit")
    p.add_argument("--contact", choices=["line", "point", "elliptic"], required=True)
    p.add_argument("--M", type=_positive_float, required=True, help="Moes load parameter")
    p.add_argument("--L", type=_positive_float, required=True, help="Moes lubricant parameter")
    p.add_argument("--ellipticity", type=_positive_float, default=1.0, help="theta = Rx/Ry (point contacts)")
    p.add_argument("--gamma1", type=_positive_float, default=1.0, help="fluid load-sharing factor P/Ph (>= 1)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_fits)

    p = sub.add_parser("run", help="the main job on a scene (default: the built-in default scene)")
    p.add_argument("scene", nargs="?", default=None, help="built-in scene name or TOML file")
    p.add_argument("--fidelity", choices=["fast", "standard", "reference"], default=None)
    p.add_argument("--tolerance", type=float, default=None, help="target relative accuracy (overrides --fidelity)")
    add_common_options(p)
    p.set_defaults(func=_cmd_run)

    p = sub.add_parser("solve", help="multigrid EHL solve of a scene or of Moes (M, L)")
    from .solve import add_solve_arguments

    add_solve_arguments(p)
    add_common_options(p)
    p.set_defaults(func=_cmd_solve)

    p = sub.add_parser("plan", help="which physics a scene needs, and why (numbers behind each decision)")
    p.add_argument("scene", help="built-in scene name or TOML file")
    p.add_argument("--fidelity", choices=["fast", "standard", "reference"], default=None)
    p.add_argument("--tolerance", type=float, default=None, help="target relative accuracy (overrides --fidelity)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_plan)

    p = sub.add_parser("sweep", help="run a task over a grid of scene parameters, in parallel, resumable")
    p.add_argument("scene", help="built-in scene name or TOML file")
    p.add_argument("--task", default="fit", help="task name from the ehl.tasks group (default: %(default)s)")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUES",
                   help="dotted scene path or task option, values a,b,c or min:max:n[:log]; repeat for a grid")
    p.add_argument("--option", action="append", default=[], metavar="KEY=VALUE", help="fixed task option")
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: all cores)")
    p.add_argument("--scheduler", default=None, help="dask.distributed scheduler address (optional extra 'dask')")
    p.add_argument("--json", action="store_true")
    p.add_argument("--out", default="ehl_sweep", help="sweep folder (resumes if it holds finished cases)")
    p.set_defaults(func=_cmd_sweep)

    for ep in _plugin_entry_points():
        _register_plugin(sub, ep.name, ep.load)
    return parser


def _plugin_entry_points() -> list[Any]:
    try:
        return sorted(entry_points(group="ehl.commands"), key=lambda e: e.name)
    except TypeError:  # pragma: no cover - Python < 3.10 API
        return []


def _register_plugin(sub: Any, name: str, loader: Callable[[], Callable]) -> None:
    try:
        register = loader()
    except Exception as exc:  # the layer is not installed or broken: say so when called
        msg = f"subcommand {name!r} is unavailable: {type(exc).__name__}: {exc}"
        p = sub.add_parser(name, help=f"(unavailable: {exc})")
        p.add_argument("rest", nargs=argparse.REMAINDER)
        p.add_argument("--json", action="store_true")

        def _unavailable(args: argparse.Namespace, _msg: str = msg) -> dict:
            raise InputError(_msg)

        p.set_defaults(func=_unavailable)
        return
    register(sub)


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.version:
        from ..model.results import package_version

        print(package_version())
        return 0
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        payload = args.func(args)
    except InputError as exc:
        print(f"ehl {args.command}: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except ConvergenceError as exc:
        print(f"ehl {args.command}: did not converge: {exc}", file=sys.stderr)
        return EXIT_CONVERGENCE
    except KeyboardInterrupt:
        print(f"ehl {args.command}: interrupted; finished work was kept", file=sys.stderr)
        return 130
    if getattr(args, "json", False) and payload is not None:
        print_payload(payload)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
