"""``ehl traction``: thermal (or isothermal) Eyring friction against slip for a scene."""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from ehl_multigrid.app.console import (
    accuracy_argument,
    add_common_options,
    locked_command,
    print_table,
)
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.paths import output_file, safe_stem, writable_dir
from ehl_multigrid.model.results import Result, result_names
from ehl_multigrid.model.scene import load_scene

from .options import SLICE_PRESSURES, SLICE_RULES, SURFACE_KERNELS, ThermalOptions
from .slips import parse_slips

#: Grid limits of the command line: far beyond the thesis grid (80 x 20, 10 slices) and the
#: reference fidelity (160 x 40), short of grids that run for many minutes (the surface
#: temperature kernel costs nx^2 per sweep: nx = 1e5 takes several minutes per slip).
GRID_LIMITS = {"nx": 10000, "nz": 1000, "slices": 200}


def check_grid(options: ThermalOptions) -> None:
    """Refuse grids of the command line (or the scene's ``[solver.thermal]``) that would run
    for many minutes; the limits are :data:`GRID_LIMITS`."""
    for key, hi in GRID_LIMITS.items():
        v = getattr(options, key)
        if v > hi:
            raise InputError(f"{key} = {v} (--{key} or [solver.thermal] {key}) is above {hi}, the largest grid "
                             f"`ehl traction` runs (the thesis grid is nx = 80, nz = 20, 10 slices)")


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "traction",
        help="thermal non-linear Roelands-Eyring friction against slip (thesis chapter 3)",
        description="Friction force and coefficient against slip S = 2(u1-u2)/(u1+u2) (thesis 100 %% = 1).",
    )
    p.add_argument("scene", help="built-in scene name or TOML file")
    p.add_argument("--isothermal", action="store_true", help="hold the temperature at the oil inlet value")
    p.add_argument("--coupled", action="store_true",
                   help="traction curve from thermal EHL solves (pressure, film and temperature "
                        "together, Eyring flow; line contacts) instead of the thermal model on a "
                        "given film")
    p.add_argument("--points", type=int, default=None,
                   help="EHL grid points of --coupled solves (2^k + 1, default 513)")
    p.add_argument("--no-estimate", dest="estimate", action="store_false",
                   help="--coupled: skip the curve's error estimate (at its first and last slip and "
                        "its largest friction)")
    p.add_argument("--accuracy", type=accuracy_argument, default=argparse.SUPPRESS,
                   help="--coupled: relative accuracy the curve's largest estimated film error is judged "
                        "against (default 0.005; 'none': not judged)")
    p.add_argument("--slip", default=None,
                   help="slip values S: comma list or min:max:n; write --slip=-1,0,1 when the list starts negative "
                   "(default: scene ranges.slip)")
    p.add_argument("--nx", type=int, default=None, help="stations along x (default: scene or 80)")
    p.add_argument("--nz", type=int, default=None, help="intervals across the film (default: scene or 20)")
    p.add_argument("--slices", type=int, default=None, help="slices over half a point contact (default: scene ny or 10)")
    p.add_argument("--input", choices=["hertz", "ehl"], default="hertz",
                   help="Hertz pressure + fitted uniform film, or an EHL solution (--ehl-file)")
    p.add_argument("--ehl-file", default=None,
                   help="HDF5 result of kind ehl_line/ehl_point for --input ehl ('ehl solve'; of an 'ehl run' "
                        "file its film stage's film); the scene stored beside the film must be the same "
                        "contact (load, radii, moduli, oil, speed, supply)")
    p.add_argument("--unchecked-ehl-file", action="store_true",
                   help="accept an --ehl-file that stores no scene (its contact cannot be checked against "
                        "the scene's; the film is then taken as the scene's)")
    p.add_argument("--x-in", type=float, default=None, help="inlet boundary X (default -2.5)")
    p.add_argument("--surface-kernel", choices=list(SURFACE_KERNELS), default=None)
    p.add_argument("--slice-pressure", choices=list(SLICE_PRESSURES), default=None)
    p.add_argument("--slice-rule", choices=list(SLICE_RULES), default=None)
    p.add_argument("--tol", type=float, default=None, help="tol_T and tol_tau (default 1e-5)")
    add_common_options(p)
    p.set_defaults(func=locked_command(run_traction, "ehl traction"))


def run_traction(args: argparse.Namespace) -> dict[str, Any]:
    from .traction import default_slips, save_partial, traction_curve, traction_result

    scene = load_scene(args.scene)
    if args.coupled:
        from .tehl.cli import run_tehl

        if args.slip is None:
            args.slip = ",".join(f"{s:g}" for s in default_slips(scene))
        if not hasattr(args, "accuracy"):  # (absent unless given, so that it is refused without --coupled)
            args.accuracy = 0.005
        return run_tehl(args)
    if args.points is not None:
        raise InputError("--points applies to --coupled traction curves only")
    if hasattr(args, "accuracy"):
        raise InputError("--accuracy applies to --coupled traction curves only (the thermal model's "
                         "friction states its own error)")
    options = ThermalOptions.from_scene(
        scene, nx=args.nx, nz=args.nz, slices=args.slices, x_in=args.x_in, surface_kernel=args.surface_kernel,
        slice_pressure=args.slice_pressure, slice_rule=args.slice_rule, tol_T=args.tol, tol_tau=args.tol,
        thermal=False if args.isothermal else None,
    )
    check_grid(options)
    slips = parse_slips(args.slip) if args.slip is not None else [float(s) for s in default_slips(scene)]
    ehl = None
    if args.input == "ehl":
        if args.ehl_file is None:
            raise InputError("--input ehl needs --ehl-file PATH (an HDF5 result of kind ehl_line/ehl_point, e.g. from 'ehl solve')")
        names = result_names(args.ehl_file)
        if names is not None and "film" not in names:
            raise InputError(f"--ehl-file {args.ehl_file!r} is an 'ehl run' file without a film stage result "
                             f"(it holds {names})")
        # an 'ehl run' file: the film stage's isothermal film (the one a traction curve reads)
        ehl = Result.load(args.ehl_file, group=None if names is None else "film")
        want = "ehl_line" if scene.kind == "line" else "ehl_point"
        if ehl.kind != want:
            raise InputError(f"--ehl-file {args.ehl_file!r} holds a result of kind {ehl.kind!r}; the {scene.kind} "
                             f"contact of scene {scene.name!r} needs one of kind {want!r} (from 'ehl solve')")
        if ehl.scene is not None:
            from .traction import check_ehl_contact

            check_ehl_contact(ehl.scene, scene, f"--ehl-file {args.ehl_file!r}")
        elif not args.unchecked_ehl_file:
            raise InputError(f"--ehl-file {args.ehl_file!r} stores no scene, so its contact (load, radii, "
                             f"materials, oil, speed) cannot be checked against scene {scene.name!r}; give "
                             f"--unchecked-ehl-file to use it as this scene's film anyway")
    elif args.ehl_file is not None:
        raise InputError("--ehl-file applies to --input ehl only")
    elif args.unchecked_ehl_file:
        raise InputError("--unchecked-ehl-file applies to --input ehl only")
    out = writable_dir(args.out)
    stem = safe_stem(f"traction_{scene.name}{'_iso' if not options.thermal else ''}")
    h5 = output_file(out, stem, ".h5")
    points = traction_curve(
        scene, slips, progress=not args.json, on_point=save_partial(h5, scene, options),
        options=options, input=args.input, ehl=ehl,
    )
    res = traction_result(scene, points, options)
    res.save(h5)
    payload: dict[str, Any] = {
        "scene": scene.name,
        "input": args.input,
        "thermal": options.thermal,
        "load": points[0].load,
        "us": points[0].us,
        "pmax": points[0].hertz.pmax,
        "h_uniform": points[0].h if math.isfinite(points[0].h) else None,
        "slip": [p.slip for p in points],
        "friction_coefficient": [p.coefficient for p in points],
        "friction_force": [p.force for p in points],
        "max_temperature_rise": [p.max_temperature_rise for p in points],
        "mean_temperature_rise": [p.mean_temperature_rise for p in points],
        "converged_per_point": [p.converged for p in points],
        "converged": all(p.converged for p in points),
        "wall_s": sum(p.report.wall_s for p in points),
        "hdf5": str(h5),
    }
    # the friction at the operating slip with its error, as the main job's traction stage states it
    # (the curve's other slips share its grid); with the Hertz input the film is the fit's, whose
    # own error is not in it (the default scene's friction differs by 3-5 % on the solved
    # 513-point film)
    from .stage import ModelChoice, operating_friction

    op = operating_friction(scene, options, ModelChoice(options.thermal, float(scene.slip), "the command's model"),
                            input=args.input, ehl=ehl)
    hc_fit = scene.supplied_film_fit()[1]
    payload["film_source"] = ("Hertz pressure and the fitted film (Moes/Nijenbanning), not a solved one: "
                              f"hc = {hc_fit * 1e9:.4g} nm" if args.input == "hertz" else
                              f"the EHL pressure and film of {args.ehl_file}")
    payload["operating_point"] = op.payload()
    payload["friction_coefficient_at_operating_slip"] = op.coefficient
    payload["friction_coefficient_at_operating_slip_error"] = op.error
    payload["converged"] = payload["converged"] and op.converged
    payload["friction_error"] = (f"at the operating slip {op.slip:g}: +- {op.error:.2g} (parts "
                                 f"{', '.join(k for k, v in op.parts.items() if v)}; computed on {op.grid}); "
                                 f"not counted: the film's own error ({payload['film_source']})")
    print(f"ehl traction: note: f = {op.coefficient:.4g} +- {op.error:.2g} at the operating slip {op.slip:g}; "
          f"the film's own error is not counted (the film is {payload['film_source']})", file=sys.stderr)
    if not args.no_plots:
        from .plots import plot_all

        payload["plots"] = plot_all(res, out, stem)
    if not args.json:
        print(f"traction {scene.name}: {'thermal' if options.thermal else 'isothermal'}, input {args.input}, "
              f"load {points[0].load:.6g} N, pmax {points[0].hertz.pmax / 1e9:.4g} GPa, us {points[0].us:.4g} m/s")
        print(f"  {'slip':>8} {'force [N]':>12} {'coeff':>9} {'max dT [K]':>11} {'conv':>5}")
        for p in points:
            print(f"  {p.slip:8.4g} {p.force:12.5g} {p.coefficient:9.4g} {p.max_temperature_rise:11.4g} {str(p.converged):>5}")
        print_table({"converged": payload["converged"], "wall_s": payload["wall_s"], "hdf5": payload["hdf5"]})
    return payload
