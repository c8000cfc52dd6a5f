"""Arguments of ``ehl solve`` and the dispatch to the line or point multigrid solver.

:func:`~ehl_multigrid.app.contact_solve.run_contact_solve` solves any contact (``scene`` is
``None`` in Moes-only mode, ``--M``/``--L``).
A mode of a layer above the core (``--thermal``) declares the options it reads; any other one
given with it is refused (:func:`refuse_unread_options`), as ``--slip`` and ``--nz`` are
without ``--thermal``.
"""

from __future__ import annotations

import argparse

from ..model.constants import MOES_ONLY_DEFAULTS
from ..model.errors import InputError
from .console import accuracy_argument

__all__ = ["MOES_ONLY_DEFAULTS", "add_solve_arguments", "refuse_unread_options", "resolve_contact", "run_solve",
           "seconds_argument"]


def seconds_argument(text: str) -> float:
    """``--time-budget``: seconds, a number >= 0."""
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"time-budget = {text!r} is not a number of seconds") from None
    if not v >= 0.0:
        raise argparse.ArgumentTypeError(f"time-budget = {v:g} s is outside the allowed range [0, inf) s")
    return v


def grid_points_argument(text: str) -> int:
    """``--max-points``: a grid size ``2^k + 1`` of at least 65 points."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"max-points = {text!r} is not a whole number of points") from None
    if n < 65 or (n - 1) & (n - 2):
        raise argparse.ArgumentTypeError(f"max-points = {n} is not a grid size: 2^k + 1 points, at least 65 "
                                         f"(65, 129, 257, 513, 1025, ...)")
    return n


def add_solve_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", nargs="?", default=None, help="built-in scene name or TOML file (or use --M/--L)")
    p.add_argument("--contact", choices=["line", "point", "elliptic"], help="contact type in Moes-only mode")
    p.add_argument("--M", type=float, help="Moes load parameter (Moes-only mode)")
    p.add_argument("--L", type=float, help="Moes lubricant parameter (Moes-only mode)")
    p.add_argument("--ellipticity", type=float, default=None, help="theta = Rx/Ry (elliptic, Moes-only mode)")
    p.add_argument("--viscosity", choices=["roelands", "barus"], default=None,
                   help="viscosity law (default: the scene's [solver.ehl] table, else roelands)")
    p.add_argument("--density", choices=["dowson-higginson", "incompressible"], default=None,
                   help="density law (default: the scene's [solver.ehl] table, else dowson-higginson)")
    p.add_argument("--alpha", type=float, default=None, help=f"pressure-viscosity coefficient [1/Pa] (Moes-only; default {MOES_ONLY_DEFAULTS['alpha']:g})")
    p.add_argument("--eta0", type=float, default=None, help=f"ambient viscosity [Pa s] (Moes-only; default {MOES_ONLY_DEFAULTS['eta0']:g})")
    p.add_argument("--p0", type=float, default=None, help=f"Roelands reference pressure [Pa] (Moes-only; default {MOES_ONLY_DEFAULTS['p0']:g})")
    p.add_argument("--accuracy", type=accuracy_argument, default=0.005,
                   help="relative accuracy wanted for Hc and Hm (default 0.005); without --points the "
                        "solver picks and refines grid and box until its error estimate meets it; "
                        "'none' only reports the estimate (the result is then judged on its "
                        "iteration alone)")
    p.add_argument("--max-points", type=grid_points_argument, default=None,
                   help="largest grid (points along X) the accuracy target may refine to (default: "
                        "4097 for point, 262145 for line contacts; --thermal: 1025 point, 16385 line)")
    p.add_argument("--time-budget", type=seconds_argument, default=None,
                   help="seconds the accuracy target may spend (flooded contacts): no refinement "
                        "predicted to overrun it is started, and the most accurate answer so far "
                        "comes back, marked inaccurate when it misses the target (default: none; "
                        "--thermal: 600)")
    p.add_argument("--levels", type=int, default=None, help="number of multigrid levels")
    p.add_argument("--points", type=int, default=None, help="finest-grid points per direction (2^k + 1)")
    p.add_argument("--cycle", choices=["V", "W", "F"], default=None, help="multigrid cycle type")
    p.add_argument("--cycles", type=int, default=None, help="cycles per FMG level")
    p.add_argument("--max-cycles", type=int, default=None, help="extra finest-level cycles allowed to converge")
    p.add_argument("--deformation", choices=["mlmi", "fft", "direct"], default=None, help="elastic deformation path")
    p.add_argument("--face", choices=["arithmetic", "logarithmic", "auto"], default=None,
                   help="line contacts: Poiseuille face coefficient, the arithmetic (default) or "
                        "logarithmic mean of the neighbours' eps; 'auto' takes the logarithmic one "
                        "for piezoviscous oils (more accurate minimum film on fewer points)")
    p.add_argument("--xmin", type=float, default=None, help="inlet boundary X")
    p.add_argument("--xmax", type=float, default=None, help="outlet boundary X")
    p.add_argument("--ymax", type=float, default=None, help="half-width of the domain in Y (point contacts)")
    p.add_argument("--half", action="store_true",
                   help="solve half the domain using symmetry in Y (point contacts; the default of the FAS solver)")
    p.add_argument("--full-domain", action="store_true",
                   help="solve the whole domain instead of the symmetric half (point contacts)")
    p.add_argument("--threads", type=int, default=None, help="numba threads (default: all cores)")
    p.add_argument("--tol", type=float, default=None, help="residual tolerance")
    p.add_argument("--tol-load", type=float, default=None, help="relative load-error tolerance")
    p.add_argument("--solver", choices=["fas", "newton"], default=None,
                   help="point contacts: FAS/FMG multigrid (default) or the Newton semi-system path with pyamg")
    p.add_argument("--rigid", action="store_true", help="rigid surfaces: elastic deformation off (FAS)")
    p.add_argument("--thermal", action="store_true",
                   help="thermal EHL: pressure, film and temperature solved together with Eyring "
                        "shear thinning (a scene, line or point; provided by the thermal layer)")
    p.add_argument("--slip", type=float, default=None,
                   help="slide-to-roll ratio S for --thermal (default: the scene's)")
    p.add_argument("--nz", type=int, default=None,
                   help="intervals across the film for --thermal (default 20)")
    p.add_argument("--no-compression", dest="compressive_heating", action="store_false",
                   help="--thermal: leave the compressive heating out of the film energy equation "
                        "(the thesis's (3.5))")
    p.add_argument("--csv", action="store_true",
                   help="also write the centre-line profiles (P, H and, with a scene, p [Pa], h [m]) as CSV")


def resolve_contact(args: argparse.Namespace):
    """Return ``(contact, scene)``; ``scene`` is ``None`` in Moes-only mode."""
    from ..model.scene import load_scene

    moes_only = args.M is not None or args.L is not None
    if moes_only:
        if args.scene is not None:
            raise InputError("give either a scene or --M/--L, not both")
        if args.M is None or args.L is None:
            raise InputError("Moes-only mode needs both --M and --L")
        if args.contact is None:
            raise InputError("Moes-only mode needs --contact line|point|elliptic")
        return args.contact, None
    scene = load_scene(args.scene)
    if args.contact is not None and args.contact != scene.kind:
        raise InputError(f"--contact {args.contact} contradicts the scene's contact.kind = {scene.kind!r}")
    return scene.kind, scene


def run_solve(args: argparse.Namespace) -> dict:
    """Solve the contact of ``args`` (a scene or Moes ``--M``/``--L``) with the line or the
    point solver; return the payload that ``ehl solve --json`` prints."""
    contact, scene = resolve_contact(args)
    if getattr(args, "thermal", False):
        return run_solve_mode("thermal", args, scene)
    for flag in ("slip", "nz"):
        if getattr(args, flag, None) is not None:
            raise InputError(f"--{flag} applies to --thermal solves only")
    if not getattr(args, "compressive_heating", True):
        raise InputError("--no-compression applies to --thermal solves only")
    if contact != "line" and getattr(args, "face", None) is not None:
        raise InputError("--face applies to line contacts only (the point solver keeps the "
                         "arithmetic mean)")
    from .contact_solve import run_contact_solve

    return run_contact_solve(args, scene, contact)


def run_solve_mode(name: str, args: argparse.Namespace, scene) -> dict:
    """An ``ehl solve`` mode a layer above the core provides through the ``ehl.solve_modes``
    entry-point group (``--thermal``: the thermal layer's coupled TEHL solve), so the core never
    imports it."""
    from importlib.metadata import entry_points

    if scene is None:
        raise InputError(f"--{name} needs a scene (the lubricant's thermal properties and the "
                         f"surfaces' speeds come from it), not --M/--L")
    found = [e for e in entry_points(group="ehl.solve_modes") if e.name == name]
    if not found:
        raise InputError(f"--{name} is provided by a layer that is not installed "
                         f"(no entry point ehl.solve_modes:{name})")
    mode = found[0].load()
    refuse_unread_options(args, name, getattr(mode, "honoured_options", frozenset()))
    return mode(args, scene)


#: options every ``ehl solve`` path reads (the scene, the --contact check) or that belong to
#: the command rather than the solve (--json, --out, --no-plots are not solve arguments)
ALWAYS_READ = frozenset({"scene", "contact"})


def refuse_unread_options(args: argparse.Namespace, name: str, honoured: frozenset[str] | set[str]) -> None:
    """Raise :class:`InputError` for the first ``ehl solve`` option given (a value other than
    its default) that the ``--name`` mode does not read.

    A mode lists the argparse names of the options it reads in its ``honoured_options``
    attribute; a mode without one reads none beyond :data:`ALWAYS_READ`. An option a path
    does not honour must not be accepted silently (``--rigid`` with ``--thermal`` gave the
    elastic solution)."""
    probe = argparse.ArgumentParser(add_help=False)
    add_solve_arguments(probe)
    allowed = set(honoured) | ALWAYS_READ | {name}
    for action in probe._actions:
        dest = action.dest
        if dest in allowed or not action.option_strings:
            continue
        value = getattr(args, dest, action.default)
        if value is action.default or value == action.default:
            continue  # not given
        flag = max(action.option_strings, key=len)
        raise InputError(f"{flag} does not apply to --{name} solves: the {name} solve does not read it "
                         f"(options it reads: {', '.join(sorted(_flags(probe, allowed)))})")


def _flags(parser: argparse.ArgumentParser, dests: set[str]) -> list[str]:
    return [max(a.option_strings, key=len) for a in parser._actions
            if a.dest in dests and a.option_strings]
