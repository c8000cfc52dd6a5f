"""``ehl solve`` for line contacts: ``run_solve(args, scene) -> dict`` (called by
:mod:`ehl_multigrid.app.solve`). Writes ``<out>/<name>.h5`` and PNG plots of P and H.

The output folder is locked while the command runs (a second command into it is refused);
the files are written into a staging folder and moved into place together, so a stop during
plotting keeps the result (not the figures of the interrupted plotting call) and nothing
partial reaches the folder.
Progress (each solve of the accuracy sequence, and the solver's cycles at most every few
seconds) goes to stderr. The film is solved by the front door :func:`ehl_multigrid.solve`."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from .. import front
from ..model.atomic import fault_point
from ..model.constants import MOES_ONLY_DEFAULTS
from ..model.errors import ConvergenceError, InputError, require_solution
from ..model.output_folder import StagedOutputs, output_lock
from ..model.paths import safe_stem
from ..solution import MoesProblem
from .console import Progress, report_leftovers
from .solved import package_result, require_computed

#: command-line flag (argparse name) -> line solver option
_ARG_OPTIONS = {"points": "points", "levels": "levels", "cycle": "cycle", "cycles": "cycles",
                "max_cycles": "max_cycles", "deformation": "deformation", "tol": "tol",
                "tol_load": "tol_load", "threads": "threads", "face": "face"}


def run_solve(args: argparse.Namespace, scene: Any) -> dict[str, Any]:
    """Solve the line contact of ``scene`` (or Moes ``--M``/``--L``), save and plot it.

    Options come from the solver's defaults, then the scene's ``[solver.ehl]`` table, then
    the command-line flags. The output folder ``args.out`` is locked meanwhile
    (:func:`~ehl_multigrid.model.output_folder.output_lock`).
    """
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with output_lock(out, "ehl solve") as removed:
        report_leftovers("ehl solve", removed)
        with Progress("ehl solve") as prog:
            return _run_solve(args, scene, out, prog)


def _run_solve(args: argparse.Namespace, scene: Any, out: Path, prog: Progress) -> dict[str, Any]:
    for opt in ("ymax", "ellipticity"):
        if getattr(args, opt, None) is not None:
            raise InputError(f"--{opt} applies to point contacts, not to a line contact")
    if getattr(args, "half", False) or getattr(args, "full_domain", False):
        raise InputError("--half and --full-domain apply to point contacts, not to a line contact")
    if getattr(args, "solver", None) == "newton":
        raise InputError("--solver newton is the point-contact cross-check path; line contacts use "
                         "the FAS solver (whose coarsest grid is already solved by Newton)")
    opts = {key: getattr(args, arg) for arg, key in _ARG_OPTIONS.items() if getattr(args, arg, None) is not None}
    accuracy = getattr(args, "accuracy", None)
    if getattr(args, "max_points", None) is not None:
        opts["max_points"] = args.max_points
    if getattr(args, "time_budget", None) is not None:
        opts["time_budget"] = args.time_budget
    if getattr(args, "rigid", False):
        opts["elastic"] = False
    model = {k: v for k in ("viscosity", "density", "xmin", "xmax") if (v := getattr(args, k, None)) is not None}
    # an unconverged or inaccurate result comes back (the front door never raises for it): it
    # is written and says so
    if scene is None:
        oil = {k: getattr(args, k, None) for k in ("alpha", "eta0", "p0")}
        laws = {k: model.pop(k) for k in ("viscosity", "density") if k in model}
        problem = MoesProblem("line", args.M, args.L, **laws, **oil)
        sol = front.solve(problem, physics="steady", accuracy=accuracy, options={**opts, **model},
                          callback=prog.solver_callback, progress=prog.say)
        raw = require_computed(sol)
        used = {k: (v if v is not None else MOES_ONLY_DEFAULTS[k]) for k, v in oil.items()}
        name = f"line_M{args.M:g}_L{args.L:g}"
        if not args.json:
            pb = raw.problem
            print(f"Moes-only line contact M = {args.M:g}, L = {args.L:g}; oil data used: "
                  f"p0 = {used['p0']:.4g} Pa, alpha = {used['alpha']:.4g} 1/Pa, "
                  f"eta0 = {used['eta0']:.4g} Pa s ({pb.viscosity}, {pb.density}); pmax = {pb.pmax:.4g} Pa"
                  f"{' (L = 0: isoviscous and incompressible)' if args.L == 0 else ''}")
    else:
        for k in ("alpha", "eta0", "p0"):
            if getattr(args, k, None) is not None:
                raise InputError(f"--{k} applies to Moes-only mode (--M/--L); with a scene the "
                                 f"oil comes from the scene's [lubricant] table")
        if math.isfinite(scene.supply.hoil):
            # a finite [supply] hoil: the mass-conserving (Elrod-Adams) solver finds the meniscus
            if "time_budget" in opts:
                raise InputError("--time-budget applies to flooded contacts: the starved line "
                                 "solver refines its grid only (use --max-points to bound it)")
            sol = front.solve(scene, physics="starved", accuracy=accuracy, options={**opts, **model})
            raw = require_computed(sol)
            if raw.X is None:  # nothing to write: e.g. a supply below the solver's reach
                raise ConvergenceError(f"starved line solver: {sol.message}")
        else:
            sol = front.solve(scene, physics="steady", accuracy=accuracy, options={**opts, **model},
                              callback=prog.solver_callback, progress=prog.say)
            raw = require_computed(sol)
        name = scene.name
    require_solution(raw, "line solver")
    stem = safe_stem(name)  # a scene name is a label: never a path out of --out
    res = package_result(sol)
    starved = "meniscus_x" in raw.scalars
    if starved:
        from ..starved.line import starved_payload

        payload = starved_payload(raw)  # adds Hc_flooded, meniscus_x, mass_balance_error ...
    else:
        payload = raw.payload()
    prog.status("writing the result", force=True)
    # the finished files are moved into --out together when the block ends (a stop while
    # plotting keeps the result and the CSV, not the figures of the interrupted call)
    with StagedOutputs(out, stem) as staged:
        payload["hdf5"] = str(staged.done(res.save(staged.path(f"{stem}.h5"))))
        if getattr(args, "csv", False):
            from .profiles import write_profiles_csv

            payload["csv"] = [str(staged.done(p)) for p in write_profiles_csv(res, staged.dir, stem)]
        if not args.no_plots:
            from .line_plots import plot_solution

            fault_point("solve.plots")
            payload["png"] = [str(staged.done(p)) for p in plot_solution(raw, staged.dir / stem, name)]
            if starved:
                from ..starved.plots import plot_starved

                payload["png"].append(str(staged.done(plot_starved(raw, staged.dir / stem, name))))
    if not args.json:
        from .console import print_table

        print_table({k: v for k, v in payload.items() if k != "actions"})
        for a in payload["actions"]:
            print(f"  action: {a}")
    return payload
