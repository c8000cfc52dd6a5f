"""The ``ehl`` command line.

The core defines ``scenes``, ``show``, ``fits``, ``run`` and ``solve``; the layers above
(thermal, mixed) add their own subcommands through the ``ehl.commands`` entry-point group,
so this module never imports them. An entry point names a callable
``register(subparsers) -> None`` that adds one subparser whose ``func(args) -> dict``
returns the JSON payload (and prints human-readable text when ``args.json`` is false).

Exit codes, the same for every subcommand (the layers' included):

* 0 -- success;
* 2 -- bad input: an :class:`~ehl_multigrid.model.errors.InputError` or a usage error, with a
  one-line message naming the field, the value and what is allowed;
* 3 -- the computation did not converge or did not meet its accuracy: a
  :class:`~ehl_multigrid.model.errors.ConvergenceError`, or a payload whose ``converged`` (or
  a stage's ``converged``) is false; a result may still have been written, and it says so;
* 1 -- an unexpected internal error (a bug: the traceback is printed to report it);
* 130 / 143 -- interrupted by Ctrl-C / terminated by SIGTERM; finished work is kept;
* 141 -- the reader of the output went away (``ehl show default | head -2``): output stops
  quietly, as for a process ended by SIGPIPE.

With ``--json`` a failure that leaves no payload (exit 2, 3, 130, 143) still prints one JSON
object on stdout: ``command``, ``exit_code``, ``error`` (``input``, ``convergence``,
``interrupted``, ``terminated``), ``message`` and ``converged: false``.

Implausible inputs and results (a ball radius of 10 m, a 343 degC oil: usually a unit mistake)
are warned about once each on stderr, one line naming field, value, plausible range and the
probable mistake (:class:`~ehl_multigrid.model.errors.PlausibilityWarning`); ``ehl --strict``
or ``EHL_STRICT=1`` refuses them instead (exit 2).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import signal
import sys
import warnings
from collections.abc import Callable, Sequence
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

from ..model.errors import (
    ConvergenceError,
    InputError,
    ModelRangeWarning,
    PlausibilityWarning,
    Terminated,
    require_range,
    require_slip,
    signal_cause,
    strict_from_environment,
)
from .console import add_common_options, jsonable, locked_command, print_payload, print_table

__all__ = ["Terminated", "add_common_options", "build_parser", "jsonable", "main", "print_payload", "print_table",
           "run"]

EXIT_OK = 0
EXIT_INTERNAL = 1
EXIT_INPUT = 2
EXIT_CONVERGENCE = 3
EXIT_INTERRUPTED = 130
EXIT_TERMINATED = 143
EXIT_BROKEN_PIPE = 141


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
    if not summary["hc_fit_in_range"] or math.isnan(summary["hc_fit_deviation"]):
        # the fitted film where the fit was not checked (or is known to be off): as 'ehl fits'
        print(f"ehl show: warning: hc_fit: {summary['hc_fit_note']}", file=sys.stderr)
    if not args.json:
        print(f"# scene {sc.name}: {sc.description}")
        if sc.source:
            print(f"# source: {sc.source}")
        print(sc.to_toml())
        # commented, so that `ehl show NAME > my.toml` is a scene file to edit
        print("# derived")
        print_table({k: v for k, v in summary.items()
                     if not (k.startswith("hc_fit_deviation") and math.isnan(v))}, prefix="#")
    return summary


def _cmd_fits(args: argparse.Namespace) -> dict:
    from ..model import fits, groups
    from ..model.constants import THETA_MAX, THETA_MIN

    require_range("--M", args.M, 0.0, math.inf, "-", lo_open=True, hi_open=True)
    require_range("--L", args.L, 0.0, math.inf, "-", hi_open=True)
    require_range("--gamma1", args.gamma1, 1.0, math.inf, "-", hi_open=True)
    if args.contact != "line":
        require_range("--ellipticity", args.ellipticity, THETA_MIN, THETA_MAX, "-")
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
    validity = fits.fit_validity(args.contact, args.M, args.L, args.ellipticity)
    out["extrapolated"] = not validity["in_range"]
    out.update({k: validity[k] for k in ("range", "deviation", "deviation_min", "deviation_max")})
    out["fit_note"] = validity["note"]
    notes = [n for n in (validity["extrapolation"], validity["theta_note"]) if n is not None]
    if notes:
        out["warning"] = "; ".join(notes)
        for n in notes:
            print(f"ehl fits: warning: {n}", file=sys.stderr)
    if not args.json:
        print_table(out)
    return out


def _cmd_run(args: argparse.Namespace) -> dict:
    from ..model.scene import load_scene
    from .mainjob import MainJobOptions, run_main_job

    scene = load_scene(args.scene)
    options = MainJobOptions(out_dir=Path(args.out), fidelity=args.fidelity, tolerance=args.tolerance,
                             plots=not args.no_plots, quiet=args.json, time_budget=args.time_budget,
                             max_points=args.max_points)
    return run_main_job(scene, options)


def _cmd_solve(args: argparse.Namespace) -> dict:
    from ..model.paths import writable_dir
    from .solve import run_solve

    if args.threads is not None:
        require_range("--threads", args.threads, 1, max_threads(), "threads (numba's NUMBA_NUM_THREADS)")
    if getattr(args, "slip", None) is not None:
        # refused here, before a solve that would report it as a failure to converge
        require_slip("--slip", args.slip)
    writable_dir(args.out)
    return run_solve(args)


def max_threads() -> int:
    """The most threads a solve may ask for: numba's thread pool size (the cores by default)."""
    try:
        import numba

        return int(numba.config.NUMBA_NUM_THREADS)
    except Exception:  # numba missing or misconfigured: the solver will say so itself
        return os.cpu_count() or 1


def task_options(items: list[str]) -> dict[str, Any]:
    """``--option KEY=VALUE`` items as task options: a JSON value (number, ``true``, ``null``,
    list, table) or, for a word that is not JSON, the string itself (``physics=thermal``)."""
    options: dict[str, Any] = {}
    for item in items:
        if "=" not in item:
            raise InputError(f"--option {item!r} must be KEY=VALUE")
        k, v = item.split("=", 1)
        try:
            options[k.strip()] = json.loads(v)
        except json.JSONDecodeError as exc:
            if v.strip()[:1] in "[{0123456789-.":  # meant as a number, list or table
                raise InputError(f"--option {k.strip()}: {v!r} is not a valid JSON value ({exc.msg})") from None
            options[k.strip()] = v
    return options


def _cmd_sweep(args: argparse.Namespace) -> dict:
    from ..model.paths import writable_dir
    from ..model.scene import load_scene
    from .sweep import MAX_CASES, MAX_WORKERS, SweepSpec, check_spec, parse_values, run_sweep
    from .tasks import get_task

    params: dict[str, list[float]] = {}
    for item in args.param:
        if "=" not in item:
            raise InputError(f"--param {item!r} must be NAME=VALUES (e.g. operating.us=0.01:10:20:log)")
        name, spec = item.split("=", 1)
        params[name.strip()] = parse_values(spec, field=f"--param {name.strip()}")
    if not params:
        raise InputError("a sweep needs at least one --param NAME=VALUES")
    n_cases = math.prod(len(v) for v in params.values())
    if n_cases > MAX_CASES:
        raise InputError(f"--param values give {n_cases} cases; a sweep runs at most {MAX_CASES} cases "
                         "(split it into several sweeps)")
    if args.workers is not None:
        require_range("--workers", args.workers, 1, MAX_WORKERS, "worker processes")
    options = task_options(args.option)
    get_task(args.task)  # an unknown task fails here, not in every case
    spec = SweepSpec(load_scene(args.scene), args.task, params, options)
    check_spec(spec)
    out = writable_dir(args.out)
    table = run_sweep(spec, out, workers=args.workers, scheduler=args.scheduler, progress=True)
    counts = table.counts
    payload = {"cases": len(table.rows), "counts": counts, "table": str(out / "table.csv")}
    if not args.json:
        print_table({"cases": len(table.rows), **counts, "table": str(out / "table.csv")})
    failed = [r for r in table.rows if r["status"] != "ok"]
    if failed and len(failed) == len(table.rows) and all(str(r.get("error", "")).startswith("InputError")
                                                           for r in failed):
        # every case refused the same way: the sweep's input is bad, not one case of it
        raise InputError(f"every case of the sweep failed; case {failed[0]['index']}: "
                         f"{str(failed[0]['error']).removeprefix('InputError: ')}")
    if counts.get("error"):
        payload["converged"] = False
        payload["failure"] = (f"{counts['error']} of {len(table.rows)} cases raised an unexpected error "
                              f"(a bug; tracebacks in {out / 'cases'})")
        payload["internal_error"] = True
    elif failed:
        payload["converged"] = False
        payload["failure"] = (f"{len(failed)} of {len(table.rows)} cases failed (status 'failed' in "
                              f"{out / 'table.csv'}); the others were written")
    else:
        # a task that returns its own verdict (a film solve short of its accuracy is a row, not
        # an error): the sweep did not converge where one of its cases did not
        short = [r for r in table.rows if r.get("converged") is False]
        if short:
            payload["converged"] = False
            payload["failure"] = (f"{len(short)} of {len(table.rows)} cases did not converge or missed their "
                                  f"accuracy (converged false in {out / 'table.csv'})")
    return payload


def _cmd_plan(args: argparse.Namespace) -> dict:
    from ..model.scene import load_scene
    from .plan import make_plan, print_plan

    plan = make_plan(load_scene(args.scene), fidelity=args.fidelity, tolerance=args.tolerance)
    if not args.json:
        print_plan(plan)
    return plan.to_dict()


def _number(s: str) -> float:
    try:
        return float(s)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{s!r} is not a number") from None


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="ehl",
        description="Film thickness, pressure, temperature and friction in lubricated concentrated contacts.",
    )
    parser.add_argument("--version", action="store_true", help="print the package version")
    parser.add_argument("--strict", action="store_true",
                        help="refuse implausible inputs (likely unit mistakes) instead of warning "
                             "(exit 2); also EHL_STRICT=1")
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
    p.add_argument("--M", type=_number, required=True, help="Moes load parameter")
    p.add_argument("--L", type=_number, required=True, help="Moes lubricant parameter")
    p.add_argument("--ellipticity", type=_number, default=1.0, help="theta = Rx/Ry (point contacts)")
    p.add_argument("--gamma1", type=_number, default=1.0, help="fluid load-sharing factor P/Ph (>= 1)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_fits)

    from .solve import grid_points_argument, seconds_argument

    p = sub.add_parser("run", help="the main job on a scene (default: the built-in default scene)")
    p.add_argument("scene", nargs="?", default=None, help="built-in scene name or TOML file")
    p.add_argument("--fidelity", choices=["fast", "standard", "reference"], default=None)
    p.add_argument("--tolerance", type=_number, default=None, help="target relative accuracy (overrides --fidelity)")
    p.add_argument("--time-budget", type=seconds_argument, default=None,
                   help="seconds for the film solve's accuracy sequence: no refinement predicted to "
                        "overrun it is started; the most accurate film so far is used, its error stated")
    p.add_argument("--max-points", type=grid_points_argument, default=None,
                   help="largest grid (points along X) the film solves may refine to (default: each "
                        "solver's own: 4097 point, 262145 line, 513 starved point; the coupled thermal "
                        "film 1025 point, 16385 line)")
    add_common_options(p)
    p.set_defaults(func=_cmd_run)

    p = sub.add_parser("solve", help="multigrid EHL solve of a scene or of Moes (M, L)")
    from .solve import add_solve_arguments

    add_solve_arguments(p)
    add_common_options(p)
    # a solve writes its result when the solve ends, or on a stop the most accurate finished
    # solve of its accuracy sequence (the stop then says so); a stop before one keeps nothing
    p.set_defaults(func=locked_command(_cmd_solve, "ehl solve"),
                   on_stop="a result was written only if a solve had finished before the stop")

    p = sub.add_parser("plan", help="which physics a scene needs, and why (numbers behind each decision)")
    p.add_argument("scene", help="built-in scene name or TOML file")
    p.add_argument("--fidelity", choices=["fast", "standard", "reference"], default=None)
    p.add_argument("--tolerance", type=_number, default=None, help="target relative accuracy (overrides --fidelity)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_plan)

    p = sub.add_parser("sweep", help="run a task over a grid of scene parameters, in parallel, resumable")
    p.add_argument("scene", help="built-in scene name or TOML file")
    p.add_argument("--task", default="fit", help="task name from the ehl.tasks group (default: %(default)s)")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUES",
                   help="dotted scene path or task option, values a,b,c or min:max:n[:log]; repeat for a grid")
    p.add_argument("--option", action="append", default=[], metavar="KEY=VALUE", help="fixed task option")
    p.add_argument("--workers", type=int, default=None, help="local worker processes, 1 to 256 (default: all cores)")
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


def _raise_terminated(signum: int, frame: Any) -> None:
    raise Terminated()


def not_converged(payload: Any) -> str | None:
    """Why ``payload`` reports a computation that did not converge (exit 3), or ``None``.

    A payload (or one of its stage summaries, for ``ehl run``) says so by ``converged = False``
    or a ``status`` other than ``"converged"``; ``failure`` or ``message`` give the reason.
    """
    if not isinstance(payload, dict):
        return None

    def verdict(d: dict) -> str | None:
        status = d.get("status")
        if d.get("converged") is False or (isinstance(status, str) and status != "converged"):
            why = str(d.get("failure") or d.get("message") or "converged = false").splitlines()[0]
            return f"status {status}: {why}" if isinstance(status, str) else why
        return None

    why = verdict(payload)
    if why is not None:
        return why
    for name, sub in payload.items():
        if isinstance(sub, dict) and (why := verdict(sub)) is not None:
            return f"stage {name}: {why}"
    return None


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``ehl`` with ``argv``; returns the exit code (see the module docstring).

    Output into a pipe whose reader has gone (``ehl scenes --json | head -c 600``) stops
    quietly: stdout is pointed at the null device, so that nothing is written (nor complained
    about) at exit, and the exit code is 141, as for a process ended by SIGPIPE.
    """
    from ..multigrid.threads import passive_openmp_wait

    # before any solver loads the OpenMP runtime (which reads the policy once): idle threads
    # sleep instead of taking the time slice of the one doing the work
    passive_openmp_wait()
    try:
        code = _main(argv)
        sys.stdout.flush()
        return code
    except BrokenPipeError:
        _stdout_to_devnull()
        return EXIT_BROKEN_PIPE


def run() -> None:
    """The ``ehl`` console script: :func:`main`, then the process ends without the
    interpreter's teardown.

    Once the command has returned, its files are closed and its output written; what the
    interpreter would still do is wait for the threads (:func:`threading._shutdown`: the
    idle FFT and thermal pools), run the ``atexit`` handlers (logging, h5py, multiprocessing)
    and then free every module and object one by one, which takes 0.3-0.4 s after a solve
    (numba's and OpenMP's runtimes; docs/performance.md). The first two are done here, the
    last is skipped by :func:`os._exit`. Without ``threading._shutdown`` (another Python) the
    exit is the ordinary one."""
    code = main()
    import atexit
    import threading

    shutdown = getattr(threading, "_shutdown", None)
    if shutdown is None:
        sys.exit(code)
    shutdown()
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a reader gone or a closed stream: nothing left to say
            pass
    os._exit(code)


def _stdout_to_devnull() -> None:
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):  # a stdout without a file descriptor (captured)
        pass


def _plausibility_printer(command: str, fallback: Callable[..., None]) -> Callable[..., None]:
    """A ``warnings.showwarning`` printing each distinct plausibility or model-range warning
    once, as one line of stderr; other warnings go to ``fallback``."""
    seen: set[str] = set()

    def show(message: Warning | str, category: type[Warning], filename: str, lineno: int,
             file: Any = None, line: str | None = None) -> None:
        if not issubclass(category, (PlausibilityWarning, ModelRangeWarning)):
            fallback(message, category, filename, lineno, file, line)
            return
        text = _one_line(message)
        if text not in seen:
            seen.add(text)
            print(f"ehl {command}: warning: {text}", file=sys.stderr)

    return show


def _main(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.version:
        from ..model.results import package_version

        print(package_version())
        return EXIT_OK
    if not getattr(args, "func", None):
        parser.print_help()
        return EXIT_OK
    with warnings.catch_warnings():
        # strict: warn_implausible turns the warning into an InputError (exit 2)
        warnings.simplefilter("error" if args.strict or strict_from_environment() else "always",
                              PlausibilityWarning)
        warnings.simplefilter("always", ModelRangeWarning)  # not a unit mistake: never refused
        warnings.showwarning = _plausibility_printer(args.command, warnings.showwarning)
        return _run_command(args)


def _failed(args: argparse.Namespace, code: int, error: str, message: str, written: Any = None) -> int:
    """``code``; with ``--json`` also one line of JSON on stdout saying why nothing else came
    (``{"command", "exit_code", "error", "message", "converged": false}``, and ``hdf5``, the
    file a stop kept, when ``written``), so that a script reading stdout always gets an object."""
    if getattr(args, "json", False):
        try:
            print_payload({"command": args.command, "exit_code": code, "error": error, "message": message,
                           "converged": False, **({"hdf5": str(written)} if written else {})})
        except (BrokenPipeError, ValueError):  # the reader went away, or stdout is closed
            pass
    return code


def _run_command(args: argparse.Namespace) -> int:
    kept = getattr(args, "on_stop", "finished work was kept")  # what a stop leaves
    previous = None
    try:
        previous = signal.signal(signal.SIGTERM, _raise_terminated)
    except ValueError:  # not the main thread (main() called from a thread): keep the default
        pass
    try:
        payload = args.func(args)
    except InputError as exc:
        print(f"ehl {args.command}: error: {_one_line(exc)}", file=sys.stderr)
        return _failed(args, EXIT_INPUT, "input", _one_line(exc))
    except ConvergenceError as exc:
        print(f"ehl {args.command}: did not converge: {exc}", file=sys.stderr)
        return _failed(args, EXIT_CONVERGENCE, "convergence", str(exc).splitlines()[0])
    except KeyboardInterrupt as exc:
        kept = getattr(exc, "kept", kept)  # what the command wrote before the stop reached here
        print(f"ehl {args.command}: interrupted; {kept}", file=sys.stderr)
        return _failed(args, EXIT_INTERRUPTED, "interrupted", f"interrupted; {kept}", getattr(exc, "written", None))
    except Terminated as exc:
        kept = getattr(exc, "kept", kept)
        print(f"ehl {args.command}: terminated; {kept}", file=sys.stderr)
        return _failed(args, EXIT_TERMINATED, "terminated", f"terminated; {kept}", getattr(exc, "written", None))
    except SystemError as exc:
        # a signal that arrived while compiled code ran reaches us wrapped in a SystemError
        cause = signal_cause(exc)
        if cause is None:
            raise
        kept = getattr(cause, "kept", kept)
        interrupted = isinstance(cause, KeyboardInterrupt)
        what = "interrupted" if interrupted else "terminated"
        print(f"ehl {args.command}: {what}; {kept}", file=sys.stderr)
        return _failed(args, EXIT_INTERRUPTED if interrupted else EXIT_TERMINATED, what, f"{what}; {kept}",
                       getattr(cause, "written", None))
    except OSError as exc:
        if exc.filename is None:
            raise
        # the disk filled up, a file vanished or permissions changed while writing
        message = f"cannot access {exc.filename!s}: {exc.strerror or exc}"
        print(f"ehl {args.command}: error: {message}", file=sys.stderr)
        return _failed(args, EXIT_INPUT, "input", message)
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
    record_payload_outputs(getattr(args, "out", None), payload)
    if getattr(args, "json", False) and payload is not None:
        print_payload(payload)
    if isinstance(payload, dict) and payload.get("internal_error"):
        print(f"ehl {args.command}: internal error: {payload.get('failure')}", file=sys.stderr)
        return EXIT_INTERNAL
    why = not_converged(payload)
    if why is not None:
        print(f"ehl {args.command}: not converged or short of its accuracy ({why}); what was computed "
              "is written and says so", file=sys.stderr)
        return EXIT_CONVERGENCE
    return EXIT_OK


def payload_files(payload: Any, depth: int = 0) -> list[Path]:
    """Every existing file a command's payload names (``file``, ``hdf5``, ``plots``, ``png``,
    ``csv`` ... at any depth up to 4)."""
    found: list[Path] = []
    if depth > 4:
        return found
    if isinstance(payload, str):
        if len(payload) < 4096 and "\n" not in payload:
            try:
                p = Path(payload)
                if p.suffix and p.is_file():
                    found.append(p)
            except (OSError, ValueError):
                pass
    elif isinstance(payload, dict):
        for v in payload.values():
            found += payload_files(v, depth + 1)
    elif isinstance(payload, (list, tuple)):
        for v in payload:
            found += payload_files(v, depth + 1)
    return found


def record_payload_outputs(out: Any, payload: Any) -> None:
    """After a command wrote into ``--out``: for every result ``<stem>.h5`` it names, record
    the files of that stem it wrote (``<stem>.*``, ``<stem>_*``) and delete what the previous
    run of the stem recorded and this one did not rewrite
    (:func:`~ehl_multigrid.model.paths.record_outputs`)."""
    if out is None or not isinstance(payload, dict):
        return
    from ..model.paths import record_outputs

    folder = Path(out).resolve()
    files = [p for p in payload_files(payload) if p.resolve().parent == folder]
    for h5 in (p for p in files if p.suffix == ".h5"):
        stem = h5.stem
        mine = [p for p in files if p.stem == stem or p.name.startswith(stem + "_")]
        record_outputs(folder, stem, mine)


def _one_line(exc: BaseException) -> str:
    """The message of ``exc`` on one line (an error is one line of stderr)."""
    return " ".join(str(exc).split())


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
