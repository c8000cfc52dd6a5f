"""``ehl surface``: roughness parameters of a measured height map, optionally written into a
scene's ``[roughness]`` block so ``ehl stribeck`` can use the measured surface directly::

    ehl surface disc.csv --dx 0.781um --units um --filter until-psi --scene series_D_disc3_1.93GPa \\
        --write-scene disc_measured.toml --json
    ehl stribeck disc_measured.toml
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ehl_multigrid.app.console import add_common_options, locked_command, print_table
from ehl_multigrid.model.atomic import write_text_atomic
from ehl_multigrid.model.errors import InputError, require_positive, require_range
from ehl_multigrid.model.paths import output_file, safe_stem, writable_dir

from .readers import HDF5_SUFFIXES, LAYOUTS

if TYPE_CHECKING:
    from .analysis import Analysis

MAIN_KEYS = ("Ra", "Rq", "n", "beta", "sigma_s", "dd", "psi")


def _float(s: str) -> float:
    try:
        return float(s)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{s!r} is not a number") from None


def register(subparsers: Any) -> None:
    """Add the ``surface`` subcommand (entry point ``ehl.commands: surface``)."""
    p = subparsers.add_parser(
        "surface",
        help="roughness parameters (Ra, Rq, n, beta, sigma_s, dd, psi) of a height map; write them into a scene",
        description=(
            "Read a height map (text/CSV matrix or x y z columns, .npy/.npz, HDF5, or an instrument file with the "
            "optional surfalize reader), remove missing points, tilt or form, optionally low-pass filter it, and "
            "compute the Greenwood-Williamson roughness parameters (thesis 4.4.1-4.4.2, 5.3). Lengths accept units, "
            "e.g. --dx 0.781um."
        ),
    )
    p.add_argument("file", help="height map file")
    g = p.add_argument_group("reading")
    g.add_argument("--dx", help="grid spacing along x (columns): metres or with a unit, e.g. 0.781um")
    g.add_argument("--dy", help="grid spacing along y (rows); default dx")
    g.add_argument("--units", help="height units of the file: m, mm, um, nm (default: from the file, else m)")
    g.add_argument("--xy-units", help="units of x y columns and of plain-number --dx/--dy (default: --units for x y z files, m otherwise)")
    g.add_argument("--layout", choices=LAYOUTS, default="auto", help="text layout (default: %(default)s)")
    g.add_argument("--dataset", help="HDF5 dataset holding the heights")
    g = p.add_argument_group("processing")
    g.add_argument("--nan", choices=("exclude", "fill"), default="exclude",
                   help="missing points: excluded from every statistic, or filled by harmonic interpolation (default: %(default)s)")
    g.add_argument("--level", choices=("plane", "form", "mean", "none"), default="plane",
                   help="levelling: tilt (thesis), polynomial form, mean only, none (default: %(default)s)")
    g.add_argument("--form-order", type=int, default=2, help="polynomial order for --level form (default: %(default)s)")
    g.add_argument("--filter", default="none",
                   help="none | lowpass:K (K passes of the 3x3 weighted mean) | gauss:LAMBDA (ISO 16610-21 cut-off) "
                        "| until-psi[:TARGET] (filter until psi <= TARGET, thesis 5.3) (default: %(default)s)")
    g.add_argument("--filter-method", choices=("lowpass", "gaussian"), default="lowpass",
                   help="filter used by until-psi (default: %(default)s)")
    g.add_argument("--target-psi", type=_float, default=1.0, help="target of until-psi (default: %(default)s)")
    g.add_argument("--weights", choices=("binomial", "box"), default="binomial",
                   help="3x3 low-pass weights (default: %(default)s)")
    g = p.add_argument_group("material (plasticity index)")
    g.add_argument("--E-reduced", dest="E_reduced", type=_float,
                   help="E' [Pa] (E'_GW = E'/2 is used in psi); default: the scene's, else steel on steel 2.308e11")
    g.add_argument("--hardness", type=_float, help="H' [Pa]; default: the scene's roughness.hardness, else 5e9")
    g = p.add_argument_group("second surface (Greenwood-Tripp equivalent surface)")
    g.add_argument("--counter", help="height map of the counter surface (read with the same options)")
    g.add_argument("--counter-sigma-s", type=_float, help="summit height std of the counter surface [m] (e.g. 2.25e-8, thesis ball)")
    g.add_argument("--counter-Rq", dest="counter_Rq", type=_float, help="Rq of the counter surface [m] (default sigma_s/0.7)")
    g = p.add_argument_group("scene")
    g.add_argument("--scene", help="base scene (built-in name or TOML) whose roughness block is replaced")
    g.add_argument("--write-scene", help="write the base scene with the measured roughness to this TOML file")
    g.add_argument("--fc", type=_float, help="boundary friction coefficient for the written roughness block (default: the scene's)")
    add_common_options(p)
    p.set_defaults(func=locked_command(run_surface, "ehl surface"))


def _analyse_file(path: str, args: argparse.Namespace, E: float | None, H: float | None) -> Analysis:
    from .analysis import analyse_surface, parse_filter
    from .readers import read_height_map

    hm = read_height_map(path, dx=args.dx, dy=args.dy, units=args.units, xy_units=args.xy_units,
                         layout=args.layout, dataset=args.dataset)
    spec = parse_filter(args.filter, method=args.filter_method, target=args.target_psi, weights=args.weights)
    return analyse_surface(hm, levelling=args.level, form_order=args.form_order, nan=args.nan, filter=spec,
                           E_reduced=E, hardness=H)


def run_surface(args: argparse.Namespace) -> dict[str, Any]:
    from ehl_multigrid.model.scene import load_scene

    from .statistics import combine_statistics, counter_surface

    scene = None
    if args.scene or args.write_scene:
        scene = load_scene(args.scene)  # None -> the default scene
    E = args.E_reduced
    H = args.hardness
    if E is None and scene is not None:
        E = scene.E_reduced
    if H is None and scene is not None:
        H = scene.roughness.hardness if scene.roughness is not None else scene.body1.hardness
    if E is not None:
        require_range("--E-reduced", E, 1e6, 4e12, "Pa")
    if H is not None:
        require_positive("--hardness", H, "Pa")
    if not isinstance(args.form_order, int) or not 0 <= args.form_order <= 6:
        raise InputError(f"--form-order = {args.form_order} must be an integer in [0, 6]")
    for flag, path in (("file", args.file), ("--counter", args.counter)):
        if args.dataset is not None and path and Path(path).suffix.lower() not in HDF5_SUFFIXES:
            raise InputError(f"--dataset applies to HDF5 height maps; {flag} {path!r} is not one "
                             f"(suffixes {list(HDF5_SUFFIXES)})")
    if args.write_scene:
        target = Path(args.write_scene)
        if target.is_dir():
            raise InputError(f"--write-scene {args.write_scene!r} is a folder; give the TOML file to write")
        writable_dir(target.parent if str(target.parent) else ".", "--write-scene folder")
    if args.fc is not None:
        require_range("--fc", args.fc, 0.0, 1.0, "-")
    out = writable_dir(args.out)

    an = _analyse_file(args.file, args, E, H)
    payload = an.payload()
    stats = an.stats
    if args.counter or args.counter_sigma_s is not None:
        if args.counter and args.counter_sigma_s is not None:
            raise InputError("give either --counter FILE or --counter-sigma-s, not both")
        if args.counter:
            other = _analyse_file(args.counter, args, E, H).stats
        else:
            other = counter_surface(args.counter_sigma_s, args.counter_Rq)
        combined = combine_statistics(stats, other)
        payload["surface1"] = {k: getattr(stats, k) for k in MAIN_KEYS}
        payload["surface2"] = {k: getattr(other, k) for k in MAIN_KEYS}
        payload["combined"] = "Greenwood-Tripp: sigma_s, Rq, dd root-sum-square; n, beta of the rougher surface"
        payload.update({k: getattr(combined, k) for k in MAIN_KEYS})
        payload["Ra"] = stats.Ra  # Ra of the measured surface (not defined for the combination)
        stats = combined

    stem = safe_stem(f"surface_{Path(args.file).stem}")
    payload["files"] = {}
    res_path = _save_result(an, payload, scene, output_file(out, stem, ".h5"))
    payload["files"]["result"] = str(res_path)
    if not args.no_plots:
        from .plots import plot_analysis

        payload["files"]["png"] = str(plot_analysis(an, output_file(out, stem, ".png")))
    if args.write_scene:
        payload["files"]["scene"] = str(write_scene(scene, stats, args.write_scene, args.file, an, args.fc))
        payload["scene_base"] = scene.name

    for note in list(an.stats.notes) + list(an.raw.meta.get("notes", [])):
        print(f"ehl surface: note: {note}", file=sys.stderr)
    if not args.json:
        print(f"# {args.file}: {an.surface.describe()}")
        print(f"# processing: {'; '.join(an.surface.history) or 'none'}")
        print_table({k: payload[k] for k in MAIN_KEYS} | {"n_summits": stats.n_summits, "Rsk": an.stats.Rsk,
                                                         "Rku": an.stats.Rku, "E_reduced": stats.E_reduced,
                                                         "hardness": stats.hardness})
        if an.study is not None:
            print("# filter study (psi per step):")
            for s in an.study.steps:
                print(f"  {s.method} {s.setting:.4g}: psi = {s.stats.psi:.4g}, n = {s.stats.n:.4g}, "
                      f"beta = {s.stats.beta:.4g}, sigma_s = {s.stats.sigma_s:.4g}")
        for k, v in payload["files"].items():
            print(f"# {k}: {v}")
        if args.write_scene:
            print(f"# next: ehl stribeck {args.write_scene}")
    return payload


def write_scene(scene: Any, stats: Any, path: str | Path, source: str, an: Analysis, fc: float | None) -> Path:
    """Write ``scene`` with its ``[roughness]`` block replaced by ``stats`` (validated by loading)."""
    from ehl_multigrid.model.scene import Scene

    if fc is None:
        fc = scene.roughness.fc if scene.roughness is not None else None
    else:
        require_range("--fc", fc, 0.0, 1.0, "-")
    d = scene.to_dict()
    d["roughness"] = stats.roughness_block(fc)
    path = Path(path)
    d["name"] = path.stem
    d["description"] = (f"{scene.description} | roughness measured from {Path(source).name} "
                        f"(levelling and filter: {'; '.join(an.surface.history) or 'none'})")
    d["source"] = f"ehl surface {source} on scene {scene.name}"
    new = Scene.from_dict(d, origin=str(path))
    path.parent.mkdir(parents=True, exist_ok=True)
    write_text_atomic(path, new.to_toml())
    return path


def _save_result(an: Analysis, payload: dict[str, Any], scene: Any, path: Path) -> Path:
    from ehl_multigrid.model.results import Result

    hm = an.surface
    r = Result("surface", scene=scene)
    r.add_coord("x", hm.x, "m", "x")
    r.add_coord("y", hm.y, "m", "y")
    r.add_field("z", hm.z, "m", ("y", "x"), "levelled (and filtered) heights about their mean plane")
    s = an.summits
    r.add_coord("summit", np.arange(s.count), "-", "summit index")
    r.add_field("summit_x", s.ix * hm.dx, "m", ("summit",), "summit x")
    r.add_field("summit_y", s.iy * hm.dy, "m", ("summit",), "summit y")
    r.add_field("summit_height", s.height, "m", ("summit",), "summit height above the mean plane")
    r.add_field("summit_kappa", s.kappa, "1/m", ("summit",), "-(z_xx + z_yy)/2 at the summit")
    units = an.stats.UNITS
    for k, v in payload.items():
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            r.set_scalar(k, float(v) if math.isfinite(float(v)) else math.nan, units.get(k, "-"))
    r.meta["processing"] = list(hm.history)
    r.meta["method"] = an.stats.method
    r.meta["filter"] = an.filter.describe()
    r.meta["nan_policy"] = an.nan_policy
    r.meta["source"] = an.raw.source
    if an.study is not None:
        r.meta["filter_study"] = an.study.to_dict()
    return r.save(path)
