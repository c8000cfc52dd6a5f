"""``ehl solve`` for line contacts: ``run_solve(args, scene) -> dict`` (called by
:mod:`ehl_multigrid.app.solve`). Writes ``<out>/<name>.h5`` and PNG plots of P and H."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from ..line.problem import LineProblem
from ..line.solver import LineSolverOptions, MultilevelLineSolver
from ..model.constants import MOES_ONLY_DEFAULTS
from ..model.errors import InputError, reject_unknown_keys

#: keys of a scene's [solver.ehl] table the line solver accepts
SCENE_KEYS = {"points", "levels", "cycle", "cycles", "max_cycles", "deformation", "tol",
              "tol_load", "xmin", "xmax", "viscosity", "density", "threshold", "omega_gs",
              "omega_jac", "h0_factor", "nu1", "nu2"}

_ARG_OPTIONS = {"points": "points", "levels": "levels", "cycle": "cycle", "cycles": "cycles",
                "max_cycles": "max_cycles", "deformation": "deformation", "tol": "tol",
                "tol_load": "tol_load"}


def _options(args: argparse.Namespace, scene: Any) -> tuple[dict[str, Any], dict[str, Any]]:
    table = dict(scene.solver.get("ehl", {})) if scene is not None else {}
    reject_unknown_keys("solver.ehl", table, SCENE_KEYS)
    model = {k: table.pop(k) for k in ("xmin", "xmax", "viscosity", "density") if k in table}
    opts = dict(table)
    for arg, key in _ARG_OPTIONS.items():
        v = getattr(args, arg, None)
        if v is not None:
            opts[key] = v
    for k in ("xmin", "xmax"):
        if getattr(args, k, None) is not None:
            model[k] = getattr(args, k)
    # argparse defaults are the package defaults; a scene table may override them
    for k in ("viscosity", "density"):
        v = getattr(args, k, None)
        if v is not None and (k not in model or v != "roelands" and v != "dowson-higginson"):
            model[k] = v
    return opts, model


def run_solve(args: argparse.Namespace, scene: Any) -> dict[str, Any]:
    """Solve the line contact of ``scene`` (or Moes ``--M``/``--L``), save and plot it."""
    if getattr(args, "threads", None):
        import numba

        numba.set_num_threads(int(args.threads))
    for opt in ("ymax", "ellipticity"):
        if getattr(args, opt, None) is not None:
            raise InputError(f"--{opt} applies to point contacts, not to a line contact")
    if getattr(args, "half", False):
        raise InputError("--half applies to point contacts, not to a line contact")
    if getattr(args, "solver", None) == "newton":
        raise InputError("--solver newton is the point-contact cross-check path; line contacts use "
                         "the FAS solver (whose coarsest grid is already solved by Newton)")
    opts, model = _options(args, scene)
    if getattr(args, "rigid", False):
        model["elastic"] = False
    if scene is None:
        oil = {k: getattr(args, k, None) for k in ("alpha", "eta0", "p0")}
        pb = LineProblem.from_moes(args.M, args.L, **oil, **model)
        used = {k: (v if v is not None else MOES_ONLY_DEFAULTS[k]) for k, v in oil.items()}
        name = f"line_M{args.M:g}_L{args.L:g}"
        if not args.json:
            print(f"Moes-only line contact M = {args.M:g}, L = {args.L:g}; oil data used: "
                  f"p0 = {used['p0']:.4g} Pa, alpha = {used['alpha']:.4g} 1/Pa, "
                  f"eta0 = {used['eta0']:.4g} Pa s ({model.get('viscosity', 'roelands')}, "
                  f"{model.get('density', 'dowson-higginson')}); pmax = {pb.pmax:.4g} Pa")
    else:
        for k in ("alpha", "eta0", "p0"):
            if getattr(args, k, None) is not None:
                raise InputError(f"--{k} applies to Moes-only mode (--M/--L); with a scene the "
                                 f"oil comes from the scene's [lubricant] table")
        pb = LineProblem.from_scene(scene, **model)
        name = scene.name
    solver = MultilevelLineSolver(pb, LineSolverOptions(**opts))
    sol = solver.solve()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    h5 = sol.to_result(scene).save(out / f"{name}.h5")
    payload = sol.payload()
    payload["hdf5"] = str(h5)
    if not args.no_plots:
        from .line_plots import plot_solution

        payload["png"] = [str(p) for p in plot_solution(sol, out / name, name)]
    if not args.json:
        from .console import print_table

        print_table({k: v for k, v in payload.items() if k != "actions"})
        for a in payload["actions"]:
            print(f"  action: {a}")
    return payload
