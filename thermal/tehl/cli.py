"""``ehl tehl``: thermal EHL line solve (one slip) or TEHL traction curve (several slips),
and the thermal properties ``ehl show --json`` can list."""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

import numpy as np

from ehl_multigrid.app.console import print_table
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene

from .line import TEHLLineResult, TEHLOptions, solve_tehl_line, tehl_traction_curve


def thermal_properties(scene: Scene) -> dict[str, float]:
    """The oil's thermal properties at the scene's oil temperature and the thermal loading.

    ``beta`` = -d ln(eta)/dT at ambient pressure [1/K] (Roelands temperature term (2.6));
    ``k_oil`` [W/(m K)] (3.12) and ``cp_oil`` [J/(kg K)] (3.13) at ambient pressure;
    ``thermal_loading`` = beta eta0 um^2 / k_oil with um = us/2 (the parameter of the thermal
    film-reduction correlations of Murch & Wilson 1975, Wilson & Sheu 1983, Gupta et al. 1992).
    """
    lub, T = scene.lubricant, scene.T_oil
    dT = 0.01
    beta = -(math.log(lub.eta_at(T + dT)) - math.log(lub.eta_at(T - dT))) / (2.0 * dT)
    k = float(lub.conductivity(0.0))
    um = 0.5 * scene.us
    return {"beta": beta, "k_oil": k, "cp_oil": float(lub.specific_heat(T)),
            "thermal_loading": beta * float(lub.eta_at(T)) * um * um / k}


def solve_payload(r: TEHLLineResult) -> dict[str, Any]:
    """The ``--json`` keys of a thermal solve (``Hc``, ``Hm``, ``Hc_isothermal``, ``friction``,
    ``T_max``, ``heat_balance_error`` and the rest of :meth:`TEHLLineResult.summary`)."""
    out = r.summary()
    out["outer"] = [{k: v for k, v in o.items()} for o in r.outer]
    return out


def parse_slips(text: str) -> list[float]:
    from ..cli import parse_slips as _parse

    return _parse(text)


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
    p.add_argument("--json", action="store_true", help="print the result as JSON")


def run_tehl(args: argparse.Namespace) -> dict[str, Any]:
    scene = load_scene(args.scene)
    if scene.kind != "line":
        raise InputError(f"scene {scene.name!r} is a {scene.kind} contact; 'ehl tehl' solves line contacts")
    changes = {k: v for k, v in (("points", args.points), ("nz", args.nz)) if v is not None}
    opts = TEHLOptions(**changes)
    slips = parse_slips(args.slip) if args.slip is not None else [scene.slip]
    if len(slips) == 1:
        r = solve_tehl_line(scene, slips[0], opts)
        payload = {"scene": scene.name, **solve_payload(r), **{"properties": thermal_properties(scene)}}
        if args.json:
            print(json.dumps(payload, default=float))
        else:
            print_table({k: v for k, v in payload.items() if k not in ("outer", "properties")})
        return payload
    curve = tehl_traction_curve(scene, np.asarray(slips), opts)
    payload = {"scene": scene.name, "slip": [r.slip for r in curve],
               "friction_coefficient": [r.friction_coefficient for r in curve],
               "friction": [r.friction for r in curve], "Hc": [r.Hc for r in curve], "Hm": [r.Hm for r in curve],
               "Hc_isothermal": curve[0].Hc_isothermal, "T_max": [r.T_max for r in curve],
               "heat_balance_error": [r.heat_balance_error for r in curve],
               "wall_s": sum(r.wall_s for r in curve)}
    if args.json:
        print(json.dumps(payload, default=float))
    else:
        print(f"  {'slip':>8} {'mu':>9} {'Hc':>8} {'Hm':>8} {'T_max':>8}")
        for r in curve:
            print(f"  {r.slip:8.4g} {r.friction_coefficient:9.4g} {r.Hc:8.4g} {r.Hm:8.4g} {r.T_max:8.4g}")
    return payload


def solve_mode(args: argparse.Namespace, scene: Scene) -> dict[str, Any]:
    """``ehl solve SCENE --thermal``: one TEHL solve (line or point) at ``args.slip`` (default the
    scene's), ``args.points`` (default 513 line, 257 point) and ``args.nz`` (default 20); returns
    the payload of :func:`solve_payload` (printed as JSON by ``--json``)."""
    from .point import solve_tehl_point

    point = scene.kind != "line"
    points = getattr(args, "points", None) or (257 if point else 513)
    nz = getattr(args, "nz", None) or 20
    slip = getattr(args, "slip", None)
    opts = TEHLOptions(points=points, nz=nz)
    r = solve_tehl_point(scene, slip, opts) if point else solve_tehl_line(scene, slip, opts)
    payload = {"scene": scene.name, "contact": scene.kind, **r.summary(),
               "outer": [dict(o) for o in r.outer], "properties": thermal_properties(scene)}
    if not getattr(args, "json", False):
        print_table({k: v for k, v in payload.items() if k not in ("outer", "properties")})
    return payload
