"""Hostile inputs for the ``ehl`` command line: bad scene values of every section and type, bad
flags of every subcommand, binary/empty/truncated files, path tricks and huge sizes.

Each input runs in its own subprocess (``python -m ehl_multigrid.app.cli ...``) with a time limit
and is classified as

* ``clear error``: exit 2, no traceback, and the message names the field (the case's ``names``);
* ``unclear error``: exit 2 without a traceback, but the message does not name the field;
* ``traceback``: a Python traceback, or exit 1 (an unexpected internal error);
* ``silent``: exit 0 on nonsense, a missing warning, a file written outside ``--out``, or a hang
  (time limit reached);
* ``ok``: a valid input accepted (exit 0, or the documented exit 3 for "did not converge" where
  that is the expected answer), warnings present where the case expects them.

Usage::

    python validation/inputs/hostile.py [--only SUBSTRING] [--jobs 2] [--label before|after]

Writes ``build/validation/inputs/hostile.json`` (every case with its exit code, the last line of
stderr and the class) and the summary table of ``validation/inputs/REPORT.md`` (between the
markers ``<!-- counts:LABEL -->``).
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import copy
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import tomli_w

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

HERE = Path(__file__).resolve().parent
OUT = out_dir("inputs")
REPORT = HERE / "REPORT.md"

CLASSES = ("clear error", "unclear error", "traceback", "silent", "exit-0 failure", "warned", "ok")


@dataclass
class Case:
    """One hostile input.

    ``expect``: ``"error"`` (exit 2 naming ``names``), ``"ok"`` (exit 0), ``"warn"`` (exit 0
    with ``names`` in the output), ``"noconv"`` (exit 3, or 0 with ``names`` in the output), or
    ``"refuse_or_ok"`` (either a clear error naming ``names`` or exit 0; for path tricks, where
    the ``check`` decides).
    """

    group: str
    name: str
    argv: list[str]
    expect: str = "error"
    names: list[str] = field(default_factory=list)
    timeout: float = 90.0
    check: str = ""  # name of a post-run check in CHECKS
    files: dict[str, Any] = field(default_factory=dict, repr=False)  # relative path -> bytes/str/dict


# -- scenes ---------------------------------------------------------------------------------------
POINT = {
    "name": "hostile_point",
    "contact": {"kind": "point"},
    "geometry": {"Rx": 0.01032, "Ry": 0.01032},
    "solids": {"E_reduced": 2.3e11},
    "lubricant": {"preset": "T9-point"},
    "operating": {"load": 42.8, "us": 8.0, "slip": 0.05, "T_oil": 60.0},
    "roughness": {"Rq": 2.8e-8, "n": 5.816e10, "beta": 6.12e-5, "sigma_s": 1.8e-8, "fc": 0.125},
}
LINE = {
    "name": "hostile_line",
    "contact": {"kind": "line", "length": 0.01},
    "geometry": {"Rx": 0.02},
    "solids": {"E_reduced": 2.31e11},
    "lubricant": {"preset": "T9", "eta0": 0.0202, "alpha": 2e-8, "tau0": 2.5e6},
    "operating": {"load": 4240.0, "us": 1.0, "slip": 0.05, "T_oil": 40.0},
}


def scene(base: dict, path: str, value: Any = None, delete: bool = False, **top: Any) -> dict:
    """A copy of ``base`` with the dotted ``path`` set to ``value`` (or deleted)."""
    d = copy.deepcopy(base)
    d.update(top)
    if path:
        keys = path.split(".")
        node = d
        for k in keys[:-1]:
            node = node.setdefault(k, {})
        if delete:
            node.pop(keys[-1], None)
        else:
            node[keys[-1]] = value
    return d


def toml_text(d: dict) -> str:
    return tomli_w.dumps(d)


# -- the cases ------------------------------------------------------------------------------------
def cases() -> list[Case]:
    C: list[Case] = []

    def bad_scene(name: str, d: dict | str | bytes, names: list[str], cmd: str = "show", extra: list[str] | None = None,
                  expect: str = "error", timeout: float = 90.0) -> None:
        fname = f"{name}.toml"
        C.append(Case("scene", name, [cmd, "{dir}/" + fname] + (extra or []), expect, names, timeout,
                      files={fname: d}))

    P, L = POINT, LINE
    # top level
    bad_scene("top_unknown_key", scene(P, "colour", "red"), ["colour"])
    bad_scene("top_name_table", scene(P, "name", {"a": 1}), ["name"])
    bad_scene("top_contact_not_table", scene(P, "contact", "point"), ["[contact]"])
    bad_scene("top_missing_contact", scene(P, "contact", delete=True), ["[contact]"])
    # contact
    bad_scene("contact_kind_unknown", scene(P, "contact.kind", "ring"), ["contact.kind"])
    bad_scene("contact_kind_number", scene(P, "contact.kind", 5), ["contact.kind"])
    bad_scene("contact_line_no_length", scene(L, "contact.length", delete=True), ["contact.length"])
    bad_scene("contact_length_negative", scene(L, "contact.length", -0.01), ["contact.length"])
    bad_scene("contact_length_text", scene(L, "contact.length", "long"), ["contact.length"])
    bad_scene("contact_length_wrong_unit", scene(L, "contact.length", "5 kg"), ["contact.length"])
    bad_scene("contact_length_for_point", scene(P, "contact.length", 0.01), ["contact.length"])
    # geometry
    bad_scene("geometry_Rx_zero", scene(P, "geometry.Rx", 0.0), ["geometry.Rx"])
    bad_scene("geometry_Rx_negative", scene(P, "geometry.Rx", -0.01), ["geometry.Rx"])
    bad_scene("geometry_Rx_nan", scene(P, "geometry.Rx", math.nan), ["geometry.Rx"])
    bad_scene("geometry_Rx_huge", scene(P, "geometry.Rx", 1e9, **{}), ["geometry.Rx"])
    bad_scene("geometry_Rx_bool", scene(P, "geometry.Rx", True), ["geometry.Rx"])
    bad_scene("geometry_Rx_list", scene(P, "geometry.Rx", [1, 2]), ["geometry.Rx"])
    bad_scene("geometry_point_not_round", scene(P, "geometry.Ry", 0.02), ["Ry"])
    bad_scene("geometry_line_finite_Ry", scene(L, "geometry.Ry", 0.02), ["geometry.Ry"])
    bad_scene("geometry_R1x_zero", scene(P, "geometry", {"R1x": 0.0, "R2x": math.inf, "R1y": 0.01, "R2y": math.inf}), ["geometry.R1x"])
    bad_scene("geometry_concave_wins", scene(P, "geometry", {"R1x": 0.01, "R2x": -0.005, "R1y": 0.01, "R2y": math.inf}), ["geometry"])
    bad_scene("geometry_theta_1000", scene(P, "geometry", {"Rx": 0.1, "Ry": 0.0001}, contact={"kind": "elliptic"}), ["theta"])
    bad_scene("geometry_theta_1000_solve", scene(P, "geometry", {"Rx": 0.1, "Ry": 0.0001}, contact={"kind": "elliptic"}),
              ["theta"], cmd="solve", extra=["--no-plots", "--out", "{dir}/o"])
    bad_scene("geometry_both_forms", scene(P, "geometry", {"Rx": 0.01, "R1x": 0.01}), ["[geometry]"])
    # solids
    bad_scene("solids_unknown_preset", scene(P, "solids.body1", "unobtainium"), ["solids.body1"])
    bad_scene("solids_E_negative", scene(P, "solids.body1", {"preset": "steel", "E": -2e11}), ["body1", "E"])
    bad_scene("solids_nu_too_big", scene(P, "solids.body1", {"preset": "steel", "nu": 0.7}), ["body1", "nu"])
    bad_scene("solids_E_reduced_zero", scene(P, "solids.E_reduced", 0.0), ["solids.E_reduced"])
    bad_scene("solids_E_reduced_text", scene(P, "solids.E_reduced", "stiff"), ["solids.E_reduced"])
    bad_scene("solids_body_number", scene(P, "solids.body2", 7), ["solids.body2"])
    # lubricant
    bad_scene("lubricant_unknown_preset", scene(P, "lubricant.preset", "olive-oil"), ["preset"])
    bad_scene("lubricant_eta0_negative", scene(P, "lubricant.eta0", -0.1), ["eta0"])
    bad_scene("lubricant_alpha_and_z", scene(P, "lubricant", {"preset": "T9", "alpha": 2e-8, "z": 0.6}), ["alpha", "z"])
    bad_scene("lubricant_alpha_negative", scene(P, "lubricant.alpha", -2e-8), ["alpha"])
    bad_scene("lubricant_tau0_zero", scene(P, "lubricant.tau0", 0.0), ["tau0"])
    bad_scene("lubricant_unknown_key", scene(P, "lubricant.colour", "amber"), ["colour"])
    bad_scene("lubricant_not_table", scene(P, "lubricant", "T9"), ["[lubricant]"])
    bad_scene("lubricant_missing", scene(P, "lubricant", delete=True), ["[lubricant]"])
    bad_scene("lubricant_oil_unknown", scene(P, "lubricant", {"oil": "mineral-VG9999"}), ["oil"])
    bad_scene("lubricant_vi_absurd", scene(P, "lubricant", {"iso_vg": 68, "vi": 1000, "rho15": 872.0}), ["vi"])
    bad_scene("lubricant_nu100_above_nu40", scene(P, "lubricant", {"nu40": "10 cSt", "nu100": "50 cSt", "rho15": 872.0}),
              ["nu100"])
    bad_scene("lubricant_eta0_units", scene(P, "lubricant.eta0", "3 m/s"), ["eta0"])
    # operating
    bad_scene("operating_load_and_pmax", scene(P, "operating.pmax", 1e9), ["load", "pmax"])
    bad_scene("operating_no_load", scene(P, "operating.load", delete=True), ["load", "pmax"])
    bad_scene("operating_load_negative", scene(P, "operating.load", -5.0), ["operating.load"])
    bad_scene("operating_load_zero", scene(P, "operating.load", 0.0), ["operating.load"])
    bad_scene("operating_load_inf", scene(P, "operating.load", math.inf), ["operating.load"])
    bad_scene("operating_pmax_absurd", scene(scene(P, "operating.load", delete=True), "operating.pmax", 1e12), ["operating.pmax"])
    bad_scene("operating_us_zero", scene(P, "operating.us", 0.0), ["operating.us"])
    bad_scene("operating_us_text", scene(P, "operating.us", "fast"), ["operating.us"])
    bad_scene("operating_us_absurd", scene(P, "operating.us", 1e9), ["operating.us"])
    bad_scene("operating_slip_3", scene(P, "operating.slip", 3.0), ["operating.slip"])
    bad_scene("operating_T_oil_cold", scene(P, "operating.T_oil", -300.0), ["operating.T_oil"])
    bad_scene("operating_T_oil_hot", scene(P, "operating.T_oil", 1000.0), ["operating.T_oil"])
    bad_scene("operating_T_surface_nan", scene(P, "operating.T_surface1", math.nan), ["operating.T_surface1"])
    bad_scene("operating_us_and_entrainment", scene(P, "operating.entrainment_speed", 4.0), ["us", "entrainment_speed"])
    bad_scene("operating_load_wrong_unit", scene(P, "operating.load", "100 m"), ["operating.load"])
    bad_scene("operating_unknown_key", scene(P, "operating.speed", 3.0), ["speed"])
    # ranges
    bad_scene("ranges_log_no", scene(P, "ranges.us", {"min": 0.1, "max": 10.0, "n": 5, "log": "no"}), ["ranges.us.log"])
    bad_scene("ranges_log_number", scene(P, "ranges.us", {"min": 0.1, "max": 10.0, "n": 5, "log": 1}), ["ranges.us.log"])
    bad_scene("ranges_max_below_min", scene(P, "ranges.us", {"min": 10.0, "max": 0.1, "n": 5}), ["ranges.us.max"])
    bad_scene("ranges_n_zero", scene(P, "ranges.us", {"min": 0.1, "max": 10.0, "n": 0}), ["ranges.us.n"])
    bad_scene("ranges_n_float", scene(P, "ranges.us", {"min": 0.1, "max": 10.0, "n": 5.5}), ["ranges.us.n"])
    bad_scene("ranges_empty_list", scene(P, "ranges.slip", []), ["ranges.slip"])
    bad_scene("ranges_text_item", scene(P, "ranges.slip", [0.1, "x"]), ["ranges.slip[1]"])
    bad_scene("ranges_slip_out", scene(P, "ranges.slip", [0.1, 5.0]), ["ranges.slip[1]"])
    bad_scene("ranges_unknown", scene(P, "ranges.temperature", [40, 60]), ["temperature"])
    bad_scene("ranges_not_table", scene(P, "ranges", [1, 2]), ["[ranges]"])
    bad_scene("ranges_log_negative_min", scene(P, "ranges.slip", {"min": -1.0, "max": 1.0, "n": 5, "log": True}), ["ranges.slip"])
    # roughness
    bad_scene("roughness_no_Rq", scene(P, "roughness.Rq", delete=True), ["roughness.Rq"])
    bad_scene("roughness_Rq_zero", scene(P, "roughness.Rq", 0.0), ["roughness.Rq"])
    bad_scene("roughness_Rq_metre", scene(P, "roughness.Rq", 1.0), ["roughness.Rq"])
    bad_scene("roughness_no_n", scene(P, "roughness.n", delete=True), ["roughness.n"])
    bad_scene("roughness_no_n_run", scene(P, "roughness.n", delete=True), ["roughness.n"], cmd="run",
              extra=["--no-plots", "--fidelity", "fast", "--out", "{dir}/o"])
    bad_scene("roughness_no_beta", scene(P, "roughness.beta", delete=True), ["roughness.beta"])
    bad_scene("roughness_fc_2", scene(P, "roughness.fc", 2.0), ["roughness.fc"])
    bad_scene("roughness_beta_negative", scene(P, "roughness.beta", -1e-5), ["roughness.beta"])
    bad_scene("roughness_unknown", scene(P, "roughness.Rz", 1e-7), ["Rz"])
    # supply
    bad_scene("supply_hoil_zero", scene(P, "supply.hoil", 0.0), ["supply.hoil"])
    bad_scene("supply_hos_not_list", scene(P, "supply.hoil_over_sigma", 3.0), ["supply.hoil_over_sigma"])
    bad_scene("supply_hos_negative", scene(P, "supply.hoil_over_sigma", [1.0, -1.0]), ["supply.hoil_over_sigma[1]"])
    bad_scene("supply_hos_no_roughness", scene(scene(P, "roughness", delete=True), "supply.hoil_over_sigma", [1.0]),
              ["hoil_over_sigma"])
    bad_scene("supply_delta_100", scene(P, "supply.delta", 100.0), ["supply.delta"])
    # solver tables
    bad_scene("solver_ehl_not_table", scene(P, "solver.ehl", 5), ["solver.ehl"])
    bad_scene("solver_unknown_layer", scene(P, "solver.magic", {}), ["magic"])
    bad_scene("solver_ehl_points_100", scene(P, "solver.ehl", {"points": 100}), ["points"], cmd="solve",
              extra=["--no-plots", "--out", "{dir}/o"])
    bad_scene("solver_ehl_unknown_option", scene(P, "solver.ehl", {"warp": 9}), ["warp"], cmd="solve",
              extra=["--no-plots", "--out", "{dir}/o"])
    bad_scene("solver_thermal_nx_negative", scene(P, "solver.thermal", {"nx": -5}), ["nx"], cmd="traction",
              extra=["--no-plots", "--out", "{dir}/o", "--slip", "0.1"])
    bad_scene("solver_thermal_unknown", scene(P, "solver.thermal", {"speed": 1}), ["speed"], cmd="traction",
              extra=["--no-plots", "--out", "{dir}/o", "--slip", "0.1"])
    # element and materials
    bad_scene("element_unknown_kind", {"name": "el", "element": {"kind": "flux_capacitor"}, "lubricant": {"preset": "T9"}},
              ["element"])
    bad_scene("element_missing_keys", {"name": "el", "element": {"kind": "ball_bearing"}, "lubricant": {"preset": "T9"}},
              ["element"])
    bad_scene("element_negative_speed", {
        "name": "el", "lubricant": {"preset": "T9"}, "operating": {"T_oil": 70.0},
        "element": {"kind": "ball_bearing", "ball_diameter": "7.938 mm", "pitch_diameter": "38.5 mm", "n_balls": 9,
                    "f_inner": 0.52, "f_outer": 0.525, "race": "inner", "shaft_speed": "-1500 rpm", "radial_load": "350 N"}},
        ["shaft_speed"])
    bad_scene("materials_E_negative", scene(P, "materials", {"mine": {"E": -1.0, "nu": 0.3}}, solids={"body1": "mine"}),
              ["mine", "E"])
    # files: binary, empty, truncated, not UTF-8, directory, missing
    bad_scene("file_binary", bytes(range(256)) * 8, ["not"], expect="error")
    bad_scene("file_empty", b"", ["[contact]"])
    bad_scene("file_truncated", toml_text(P)[:57], ["TOML"])
    bad_scene("file_latin1", ('name = "caf\xe9"\n' + toml_text(scene(P, "name", delete=True))).encode("latin-1"), ["UTF-8"])
    C.append(Case("files", "scene_is_directory", ["show", "{dir}"], "error", ["{dir}"]))
    C.append(Case("files", "scene_missing_file", ["show", "{dir}/nope.toml"], "error", ["nope.toml"]))
    C.append(Case("files", "scene_unknown_name", ["show", "no_such_scene"], "error", ["no_such_scene"]))
    C.append(Case("files", "scene_dev_zero", ["show", "/dev/zero"], "error", ["/dev/zero"], timeout=30))
    C.append(Case("files", "scene_dev_null_toml", ["show", "/dev/null"], "error", ["/dev/null"], timeout=30))

    # -- scenes / show ------------------------------------------------------------------------
    C.append(Case("scenes", "scenes_ok", ["scenes", "--json"], "ok"))
    C.append(Case("scenes", "scenes_unknown_flag", ["scenes", "--bogus"], "error", ["--bogus"]))
    C.append(Case("show", "show_ok", ["show", "default", "--json"], "ok"))
    C.append(Case("show", "show_no_argument", ["show"], "error", ["scene"]))
    C.append(Case("cli", "no_command_unknown", ["frobnicate"], "error", ["frobnicate"]))

    # -- fits ---------------------------------------------------------------------------------
    fits = ["fits", "--contact", "point"]
    C.append(Case("fits", "fits_ok", fits + ["--M", "20", "--L", "10"], "ok"))
    C.append(Case("fits", "fits_M_negative", fits + ["--M=-1", "--L", "10"], "error", ["M"]))
    C.append(Case("fits", "fits_M_zero", fits + ["--M", "0", "--L", "10"], "error", ["M"]))
    C.append(Case("fits", "fits_M_nan", fits + ["--M", "nan", "--L", "10"], "error", ["M"]))
    C.append(Case("fits", "fits_M_inf", fits + ["--M", "inf", "--L", "10"], "error", ["M"]))
    C.append(Case("fits", "fits_M_text", fits + ["--M", "big", "--L", "10"], "error", ["--M"]))
    C.append(Case("fits", "fits_L_negative", fits + ["--M", "20", "--L=-3"], "error", ["L"]))
    C.append(Case("fits", "fits_contact_unknown", ["fits", "--contact", "ring", "--M", "20", "--L", "10"], "error", ["--contact"]))
    C.append(Case("fits", "fits_ellipticity_zero", ["fits", "--contact", "elliptic", "--M", "20", "--L", "10", "--ellipticity", "0"],
                  "error", ["ellipticity"]))
    C.append(Case("fits", "fits_ellipticity_line", ["fits", "--contact", "line", "--M", "20", "--L", "10", "--ellipticity", "4"],
                  "error", ["--ellipticity"]))
    C.append(Case("fits", "fits_gamma1_below_1", fits + ["--M", "20", "--L", "10", "--gamma1", "0.5"], "error", ["gamma1"]))
    C.append(Case("fits", "fits_M_1e9_warns", fits + ["--M", "1e9", "--L", "10"], "warn", ["extrapolat"]))
    C.append(Case("fits", "fits_L_1e4_warns", ["fits", "--contact", "line", "--M", "20", "--L", "1e4"], "warn", ["extrapolat"]))
    C.append(Case("fits", "fits_missing_M", ["fits", "--contact", "line", "--L", "10"], "error", ["--M"]))

    # -- plan ---------------------------------------------------------------------------------
    C.append(Case("plan", "plan_ok", ["plan", "default", "--json"], "ok"))
    C.append(Case("plan", "plan_tolerance_negative", ["plan", "default", "--tolerance=-1"], "error", ["tolerance"]))
    C.append(Case("plan", "plan_tolerance_nan", ["plan", "default", "--tolerance", "nan"], "error", ["tolerance"]))
    C.append(Case("plan", "plan_tolerance_text", ["plan", "default", "--tolerance", "tight"], "error", ["--tolerance"]))
    C.append(Case("plan", "plan_fidelity_unknown", ["plan", "default", "--fidelity", "perfect"], "error", ["--fidelity"]))

    # -- run ----------------------------------------------------------------------------------
    run_fast = ["--tolerance", "0.5", "--no-plots"]
    C.append(Case("run", "run_ok_fit_only", ["run", "appendix_c_line_4240N"] + run_fast + ["--out", "{dir}/o", "--json"], "ok",
                  check="run_complete"))
    C.append(Case("run", "run_tolerance_zero", ["run", "default", "--tolerance", "0", "--out", "{dir}/o"], "error", ["tolerance"]))
    C.append(Case("run", "run_tolerance_2", ["run", "default", "--tolerance", "2", "--out", "{dir}/o"], "error", ["tolerance"]))
    C.append(Case("run", "run_out_is_file", ["run", "appendix_c_line_4240N"] + run_fast + ["--out", "{dir}/afile"], "error", ["--out"],
                  files={"afile": "not a folder"}, check="no_run_output"))
    C.append(Case("run", "run_out_under_file", ["run", "appendix_c_line_4240N"] + run_fast + ["--out", "{dir}/afile/sub"], "error",
                  ["--out"], files={"afile": "not a folder"}))
    C.append(Case("run", "run_out_readonly_fs", ["run", "appendix_c_line_4240N"] + run_fast + ["--out", "/proc/ehl_hostile"], "error",
                  ["--out"]))
    C.append(Case("run", "run_out_sysfs", ["run", "default", "--fidelity", "fast", "--out", "/sys/ehl_hostile"], "error", ["--out"],
                  timeout=60))
    C.append(Case("run", "run_two_scenes_one_folder", ["run", "appendix_c_line_4240N"] + run_fast + ["--out", "{dir}/o"], "ok",
                  check="run_two_scenes"))
    C.append(Case("run", "run_rerun_leaves_no_stale_figures", ["run", "appendix_c_line_4240N", "--tolerance", "0.5", "--out",
                                                              "{dir}/o"], "ok", check="run_no_stale"))

    # -- path tricks (scene names) --------------------------------------------------------------
    for tag, nm in (("abs", "{dir}/escaped_abs"), ("dotdot", "../../escaped_up"), ("slash", "a/b/c"), ("dots", ".."),
                    ("empty", ""), ("long", "x" * 400), ("nul", "nul\u0000byte"), ("newline", "two\nlines")):
        d = scene(LINE, "name", nm)
        fname = f"name_{tag}.toml"
        C.append(Case("paths", f"name_{tag}_run", ["run", "{dir}/" + fname] + run_fast + ["--out", "{dir}/w/o"], "refuse_or_ok",
                      ["name"], check="inside_out", files={fname: d}))
    d = scene(LINE, "name", "../../escaped_solve")
    C.append(Case("paths", "name_dotdot_solve", ["solve", "{dir}/ns.toml", "--no-plots", "--out", "{dir}/w/o"],
                  "refuse_or_ok", ["name"], check="inside_out", files={"ns.toml": d}))
    d = scene(LINE, "name", "../../escaped_traction")
    C.append(Case("paths", "name_dotdot_traction", ["traction", "{dir}/nt.toml", "--slip", "0.1", "--nx", "20", "--nz", "5",
                                                    "--no-plots", "--out", "{dir}/w/o"], "refuse_or_ok", ["name"],
                  check="inside_out", files={"nt.toml": d}))
    d = scene(P, "name", "/tmp/../escaped_stribeck")
    C.append(Case("paths", "name_abs_stribeck", ["stribeck", "{dir}/nst.toml", "--n", "5", "--no-plots", "--out", "{dir}/w/o"],
                  "refuse_or_ok", ["name"], check="inside_out", files={"nst.toml": d}))
    C.append(Case("paths", "surface_file_dotdot_stem", ["surface", "{dir}/w/../map.csv", "--dx", "1um", "--no-plots", "--out",
                                                        "{dir}/w/o"], "ok", check="inside_out",
                  files={"map.csv": "rough", "w/.keep": ""}))

    # -- solve --------------------------------------------------------------------------------
    sl = ["solve", "--contact", "line", "--M", "20", "--L", "10", "--no-plots", "--out", "{dir}/o"]
    sp = ["solve", "--contact", "point", "--M", "20", "--L", "10", "--no-plots", "--out", "{dir}/o"]
    C.append(Case("solve", "solve_line_ok", sl, "ok"))
    C.append(Case("solve", "solve_line_csv_ok", sl + ["--csv"], "ok", check="csv_written"))
    C.append(Case("solve", "solve_coarse_grid_inaccurate_exit3", sl + ["--points", "129"], "noconv", ["accuracy"]))
    C.append(Case("solve", "solve_unconverged_exit3", sl + ["--points", "257", "--max-cycles", "0", "--cycles", "1", "--tol", "1e-12"],
                  "noconv", ["converge"]))
    C.append(Case("solve", "solve_points_100", sl + ["--points", "100"], "error", ["points"]))
    C.append(Case("solve", "solve_points_zero", sl + ["--points", "0"], "error", ["points"]))
    C.append(Case("solve", "solve_points_huge", sl + ["--points", "1000000001"], "error", ["points"], timeout=60))
    C.append(Case("solve", "solve_point_points_huge", sp + ["--points", "65537"], "error", ["points"], timeout=60))
    C.append(Case("solve", "solve_threads_zero", sl + ["--threads", "0"], "error", ["threads"]))
    C.append(Case("solve", "solve_threads_1000", sl + ["--threads", "1000"], "error", ["threads"]))
    C.append(Case("solve", "solve_threads_negative", sp + ["--threads=-2"], "error", ["threads"]))
    C.append(Case("solve", "solve_levels_zero", sl + ["--levels", "0"], "error", ["levels"]))
    C.append(Case("solve", "solve_levels_50", sp + ["--levels", "50"], "error", ["levels"]))
    C.append(Case("solve", "solve_cycles_zero", sl + ["--cycles", "0"], "error", ["cycles"]))
    C.append(Case("solve", "solve_max_cycles_negative", sl + ["--max-cycles=-1"], "error", ["max_cycles", "max-cycles"]))
    C.append(Case("solve", "solve_tol_negative", sl + ["--tol=-1"], "error", ["tol"]))
    C.append(Case("solve", "solve_tol_load_zero", sp + ["--tol-load", "0"], "error", ["tol_load", "tol-load"]))
    C.append(Case("solve", "solve_xmin_positive", sp + ["--xmin", "5"], "error", ["xmin"]))
    C.append(Case("solve", "solve_xmax_negative", sl + ["--xmax=-3"], "error", ["xmax"]))
    C.append(Case("solve", "solve_ymax_negative", sp + ["--ymax=-1"], "error", ["ymax"]))
    C.append(Case("solve", "solve_only_M", ["solve", "--contact", "line", "--M", "20", "--no-plots", "--out", "{dir}/o"], "error", ["--L"]))
    C.append(Case("solve", "solve_scene_and_M", ["solve", "default", "--M", "20", "--L", "10", "--out", "{dir}/o"], "error", ["--M"]))
    C.append(Case("solve", "solve_no_contact", ["solve", "--M", "20", "--L", "10", "--out", "{dir}/o"], "error", ["--contact"]))
    C.append(Case("solve", "solve_elliptic_no_theta", ["solve", "--contact", "elliptic", "--M", "20", "--L", "10", "--out", "{dir}/o"],
                  "error", ["--ellipticity"]))
    C.append(Case("solve", "solve_ellipticity_1000", ["solve", "--contact", "elliptic", "--M", "20", "--L", "10", "--ellipticity",
                                                      "1000", "--no-plots", "--out", "{dir}/o"], "error", ["theta", "ellipticity"]))
    C.append(Case("solve", "solve_ellipticity_zero", ["solve", "--contact", "elliptic", "--M", "20", "--L", "10", "--ellipticity",
                                                      "0", "--no-plots", "--out", "{dir}/o"], "error", ["theta", "ellipticity"]))
    C.append(Case("solve", "solve_M_negative", ["solve", "--contact", "line", "--M=-5", "--L", "10", "--no-plots", "--out", "{dir}/o"],
                  "error", ["M"]))
    C.append(Case("solve", "solve_L_nan", ["solve", "--contact", "point", "--M", "20", "--L", "nan", "--no-plots", "--out", "{dir}/o"],
                  "error", ["L"]))
    C.append(Case("solve", "solve_alpha_negative", sl + ["--alpha=-1e-8"], "error", ["alpha"]))
    C.append(Case("solve", "solve_eta0_zero", sp + ["--eta0", "0"], "error", ["eta0"]))
    C.append(Case("solve", "solve_p0_negative", sl + ["--p0=-1"], "error", ["p0"]))
    C.append(Case("solve", "solve_newton_line", sl + ["--solver", "newton"], "error", ["--solver"]))
    C.append(Case("solve", "solve_half_line", sl + ["--half"], "error", ["--half"]))
    C.append(Case("solve", "solve_rigid_newton", sp + ["--solver", "newton", "--rigid"], "error", ["--rigid"]))
    C.append(Case("solve", "solve_cycle_unknown", sl + ["--cycle", "Z"], "error", ["--cycle"]))
    C.append(Case("solve", "solve_M_huge", ["solve", "--contact", "line", "--M", "1e9", "--L", "10", "--no-plots", "--out", "{dir}/o"],
                  "error", ["M"], timeout=60))
    C.append(Case("solve", "solve_out_is_file", sl + ["--points", "129", "--out", "{dir}/afile"], "error", ["--out"],
                  files={"afile": "x"}))

    # -- sweep --------------------------------------------------------------------------------
    sw = ["sweep", "page63_line_500N", "--workers", "1", "--out", "{dir}/sw"]
    C.append(Case("sweep", "sweep_ok", sw + ["--param", "operating.us=0.1,1"], "ok"))
    C.append(Case("sweep", "sweep_param_no_equals", sw + ["--param", "operating.us"], "error", ["--param"]))
    C.append(Case("sweep", "sweep_param_text", sw + ["--param", "operating.us=abc"], "error", ["operating.us"]))
    C.append(Case("sweep", "sweep_param_two_colons", sw + ["--param", "operating.us=1:2"], "error", ["operating.us"]))
    C.append(Case("sweep", "sweep_param_n_zero", sw + ["--param", "operating.us=1:10:0"], "error", ["operating.us"]))
    C.append(Case("sweep", "sweep_param_n_text", sw + ["--param", "operating.us=1:10:x"], "error", ["operating.us"]))
    C.append(Case("sweep", "sweep_param_log_negative", sw + ["--param", "operating.us=-1:10:5:log"], "error", ["operating.us"]))
    C.append(Case("sweep", "sweep_param_huge", sw + ["--param", "operating.us=0.1:10:1000000000"], "error", ["operating.us", "cases"],
                  timeout=60))
    C.append(Case("sweep", "sweep_grid_huge", sw + ["--param", "operating.us=0.1:10:10000", "--param", "operating.load=1:100:10000"],
                  "error", ["cases"], timeout=60))
    C.append(Case("sweep", "sweep_unknown_path", sw + ["--param", "operating.sped=1,2"], "error", ["sped"]))
    C.append(Case("sweep", "sweep_unknown_task", sw + ["--task", "teleport", "--param", "operating.us=1"], "error", ["teleport"]))
    C.append(Case("sweep", "sweep_option_no_equals", sw + ["--param", "operating.us=1", "--option", "x"], "error", ["--option"]))
    C.append(Case("sweep", "sweep_option_not_taken", sw + ["--param", "operating.us=1", "--option", "x=1"], "error", ["option"]))
    C.append(Case("sweep", "sweep_option_bad_json", sw + ["--param", "operating.us=1", "--option", "x=[1,"], "error", ["--option"]))
    C.append(Case("sweep", "sweep_workers_zero", sw + ["--param", "operating.us=1", "--workers", "0"], "error", ["--workers"]))
    C.append(Case("sweep", "sweep_workers_negative", sw + ["--param", "operating.us=1", "--workers=-4"], "error", ["--workers"]))
    C.append(Case("sweep", "sweep_workers_10000", sw + ["--param", "operating.us=1", "--workers", "10000"], "error", ["--workers"]))
    C.append(Case("sweep", "sweep_no_param", sw, "error", ["--param"]))
    C.append(Case("sweep", "sweep_values_change_refused_or_rerun", sw + ["--param", "operating.us=0.1,1"], "ok", check="sweep_rerun"))
    C.append(Case("sweep", "sweep_out_is_file", ["sweep", "default", "--param", "operating.us=1", "--workers", "1", "--out", "{dir}/afile"],
                  "error", ["--out"], files={"afile": "x"}))
    C.append(Case("sweep", "sweep_scheduler_bogus", sw + ["--param", "operating.us=1", "--scheduler", "tcp://127.0.0.1:9"], "error",
                  ["scheduler"], timeout=90))

    # -- traction -----------------------------------------------------------------------------
    tr = ["traction", "appendix_c_line_42400N", "--no-plots", "--out", "{dir}/o"]
    C.append(Case("traction", "traction_ok", tr + ["--slip", "0.1", "--nx", "20", "--nz", "5"], "ok"))
    C.append(Case("traction", "traction_nx_huge", tr + ["--slip", "0.1", "--nx", "100000"], "error", ["nx"], timeout=60))
    C.append(Case("traction", "traction_nx_zero", tr + ["--nx", "0"], "error", ["nx"]))
    C.append(Case("traction", "traction_nz_huge", tr + ["--slip", "0.1", "--nz", "10000"], "error", ["nz"], timeout=60))
    C.append(Case("traction", "traction_slices_zero", ["traction", "appendix_d_point", "--slices", "0", "--out", "{dir}/o"], "error",
                  ["slices"]))
    C.append(Case("traction", "traction_slip_text", tr + ["--slip", "abc"], "error", ["--slip"]))
    C.append(Case("traction", "traction_slip_5", tr + ["--slip", "5"], "error", ["slip"]))
    C.append(Case("traction", "traction_slip_n_zero", tr + ["--slip", "0:1:0"], "error", ["--slip"]))
    C.append(Case("traction", "traction_slip_many", tr + ["--slip", "0:1:100000"], "error", ["slip"], timeout=60))
    C.append(Case("traction", "traction_ehl_no_file", tr + ["--input", "ehl"], "error", ["--ehl-file"]))
    C.append(Case("traction", "traction_ehl_file_text", tr + ["--input", "ehl", "--ehl-file", "{dir}/notes.h5"], "error",
                  ["notes.h5"], files={"notes.h5": "this is not HDF5"}))
    C.append(Case("traction", "traction_ehl_file_missing", tr + ["--input", "ehl", "--ehl-file", "{dir}/nope.h5"], "error",
                  ["nope.h5"]))
    C.append(Case("traction", "traction_ehl_file_foreign_h5", tr + ["--input", "ehl", "--ehl-file", "{dir}/foreign.h5"], "error",
                  ["foreign.h5"], files={"foreign.h5": "HDF5:foreign"}))
    C.append(Case("traction", "traction_x_in_positive", tr + ["--x-in", "5"], "error", ["x_in", "x-in"]))
    C.append(Case("traction", "traction_tol_negative", tr + ["--tol=-1"], "error", ["tol"]))
    C.append(Case("traction", "traction_ehl_file_without_input", tr + ["--ehl-file", "{dir}/nope.h5"], "error", ["--ehl-file"]))

    # -- stribeck -----------------------------------------------------------------------------
    st = ["stribeck", "page63_line_500N", "--no-plots", "--out", "{dir}/o"]
    C.append(Case("stribeck", "stribeck_ok", st + ["--n", "10"], "ok"))
    C.append(Case("stribeck", "stribeck_smooth_scene", ["stribeck", "appendix_c_line_4240N", "--out", "{dir}/o"], "error",
                  ["[roughness]"]))
    C.append(Case("stribeck", "stribeck_n_zero", st + ["--n", "0"], "error", ["--n"]))
    C.append(Case("stribeck", "stribeck_n_huge", st + ["--n", "100000000"], "error", ["--n"], timeout=60))
    C.append(Case("stribeck", "stribeck_us_min_negative", st + ["--us-min=-1"], "error", ["us-min", "us_min"]))
    C.append(Case("stribeck", "stribeck_us_reversed", st + ["--us-min", "10", "--us-max", "1"], "error", ["us-max", "us_max"]))
    C.append(Case("stribeck", "stribeck_load_negative", st + ["--load=-5"], "error", ["load"]))
    C.append(Case("stribeck", "stribeck_slip_5", st + ["--slip", "5"], "error", ["slip"]))
    C.append(Case("stribeck", "stribeck_bl_fraction_2", st + ["--bl-fraction", "2"], "error", ["bl_fraction", "bl-fraction"]))
    C.append(Case("stribeck", "stribeck_fractions_crossed", st + ["--bl-fraction", "0.1", "--ehl-fraction", "0.5"], "error",
                  ["fraction"]))
    C.append(Case("stribeck", "stribeck_hoil_text", st + ["--hoil", "abc"], "error", ["--hoil"]))
    C.append(Case("stribeck", "stribeck_hoil_negative", st + ["--hoil=-1"], "error", ["hoil"]))
    C.append(Case("stribeck", "stribeck_thermal_n_huge", st + ["--thermal", "--n", "20000"], "error", ["--n"], timeout=60))

    # -- surface ------------------------------------------------------------------------------
    su = ["--no-plots", "--out", "{dir}/o"]
    C.append(Case("surface", "surface_ok", ["surface", "{dir}/map.csv", "--dx", "1um"] + su, "ok", files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_missing_file", ["surface", "{dir}/none.csv", "--dx", "1um"] + su, "error", ["none.csv"]))
    C.append(Case("surface", "surface_binary", ["surface", "{dir}/bin.csv", "--dx", "1um"] + su, "error", ["bin.csv"],
                  files={"bin.csv": bytes(range(256)) * 16}))
    C.append(Case("surface", "surface_empty", ["surface", "{dir}/empty.csv", "--dx", "1um"] + su, "error", ["empty.csv"],
                  files={"empty.csv": ""}))
    C.append(Case("surface", "surface_truncated", ["surface", "{dir}/trunc.csv", "--dx", "1um"] + su, "error", ["trunc.csv"],
                  files={"trunc.csv": "truncated"}))
    C.append(Case("surface", "surface_constant_map", ["surface", "{dir}/flat.csv", "--dx", "1um"] + su, "error", ["flat"],
                  files={"flat.csv": "flat"}))
    C.append(Case("surface", "surface_one_by_one", ["surface", "{dir}/one.csv", "--dx", "1um"] + su, "error", ["height map"],
                  files={"one.csv": "1e-6\n"}))
    C.append(Case("surface", "surface_all_nan", ["surface", "{dir}/nan.csv", "--dx", "1um"] + su, "error", ["height map"],
                  files={"nan.csv": "nan"}))
    C.append(Case("surface", "surface_no_dx", ["surface", "{dir}/map.csv"] + su, "error", ["dx"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_dx_negative", ["surface", "{dir}/map.csv", "--dx=-1um"] + su, "error", ["dx"],
                  files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_dx_text", ["surface", "{dir}/map.csv", "--dx", "wide"] + su, "error", ["dx"],
                  files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_units_parsec", ["surface", "{dir}/map.csv", "--dx", "1um", "--units", "parsec"] + su, "error",
                  ["units"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_filter_bogus", ["surface", "{dir}/map.csv", "--dx", "1um", "--filter", "magic"] + su, "error",
                  ["filter"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_lowpass_negative", ["surface", "{dir}/map.csv", "--dx", "1um", "--filter", "lowpass:-1"] + su,
                  "error", ["filter"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_lowpass_huge", ["surface", "{dir}/map.csv", "--dx", "1um", "--filter", "lowpass:100000000"] + su,
                  "error", ["filter"], files={"map.csv": "rough"}, timeout=60))
    C.append(Case("surface", "surface_form_order_negative", ["surface", "{dir}/map.csv", "--dx", "1um", "--level", "form",
                                                             "--form-order=-1"] + su, "error", ["form"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_target_psi_negative", ["surface", "{dir}/map.csv", "--dx", "1um", "--filter", "until-psi",
                                                             "--target-psi=-1"] + su, "error", ["psi"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_E_negative", ["surface", "{dir}/map.csv", "--dx", "1um", "--E-reduced=-1"] + su, "error",
                  ["--E-reduced"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_fc_5", ["surface", "{dir}/map.csv", "--dx", "1um", "--scene", "default", "--write-scene",
                                              "{dir}/new.toml", "--fc", "5"] + su, "error", ["--fc"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_counter_negative", ["surface", "{dir}/map.csv", "--dx", "1um", "--counter-sigma-s=-1"] + su,
                  "error", ["counter", "sigma_s"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_dataset_in_csv", ["surface", "{dir}/map.csv", "--dx", "1um", "--dataset", "z"] + su,
                  "error", ["dataset"], files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_h5_not_hdf5", ["surface", "{dir}/fake.h5", "--dx", "1um"] + su, "error", ["fake.h5"],
                  files={"fake.h5": "not hdf5"}))
    C.append(Case("surface", "surface_npy_garbage", ["surface", "{dir}/g.npy", "--dx", "1um"] + su, "error", ["g.npy"],
                  files={"g.npy": b"\x93NUMPY garbage"}))
    C.append(Case("surface", "surface_write_scene_into_dir", ["surface", "{dir}/map.csv", "--dx", "1um", "--scene", "default",
                                                              "--write-scene", "{dir}"] + su, "error", ["--write-scene"],
                  files={"map.csv": "rough"}))
    C.append(Case("surface", "surface_huge_map", ["surface", "{dir}/huge.npy", "--dx", "1um"] + su, "refuse_or_ok", ["huge"],
                  files={"huge.npy": "huge"}, timeout=120))
    C += wrong_answer_cases()
    return C


# -- wrong answers with exit 0: starved, thermal and traction combinations --------------------------
LINE_STARVED = {
    # the line contact of the report: R 10 mm on a flat, 10 mm long, T9, 5000 N, 60 degC
    "name": "line_starved",
    "contact": {"kind": "line", "length": 0.01},
    "geometry": {"R1x": 0.01, "R2x": math.inf},
    "solids": {"body1": "steel", "body2": "steel"},
    "lubricant": {"preset": "T9"},
    "operating": {"load": 5000.0, "us": 2.0, "slip": 0.05, "T_oil": 60.0},
    "supply": {"hoil": 2e-8},
}
POINT_STARVED = {
    # the point contact of the report: a 10 mm ball on a flat, T9, 50 N
    "name": "point_starved",
    "contact": {"kind": "point"},
    "geometry": {"R1x": 0.01, "R1y": 0.01, "R2x": math.inf, "R2y": math.inf},
    "solids": {"body1": "steel", "body2": "steel"},
    "lubricant": {"preset": "T9"},
    "operating": {"load": 50.0, "us": 2.0, "slip": 0.05, "T_oil": 60.0},
    "roughness": {"Rq": 2.8e-8, "n": 5.816e10, "beta": 6.12e-5},
    "supply": {"hoil": 2e-8},
}


def wrong_answer_cases() -> list[Case]:
    """Every physics x every supply: a starved scene must give a film that carries no more oil
    than supplied, a clear refusal, or exit 3 -- never a flooded film with exit 0 (expect
    ``"starved"``); plausibility warnings for the unit mistakes of the report; options a path
    does not honour refused."""
    C: list[Case] = []
    o = ["--out", "{dir}/o"]
    for base, tag in ((LINE_STARVED, "line"), (POINT_STARVED, "point")):
        for hoil, htag in ((2e-8, "20nm"), (5e-9, "5nm"), (1e-9, "1nm")):
            d = scene(base, "supply.hoil", hoil)
            f = {"s.toml": d}
            sc = "{dir}/s.toml"
            names = ["hoil", "supply"]
            pts = ["--max-points", "513" if tag == "point" else "4097"]
            C.append(Case("starved", f"starved_{tag}_{htag}_solve", ["solve", sc, "--no-plots", "--json", *pts, *o],
                          "starved", names, 600, files=f))
            C.append(Case("starved", f"starved_{tag}_{htag}_solve_thermal",
                          ["solve", sc, "--thermal", "--no-plots", "--json", "--time-budget", "120", *o],
                          "starved", names, 900, files=f))
            C.append(Case("starved", f"starved_{tag}_{htag}_run", ["run", sc, "--no-plots", "--json", "--fidelity", "fast", *o],
                          "starved", names, 900, files=f))
            C.append(Case("starved", f"starved_{tag}_{htag}_traction",
                          ["traction", sc, "--slip", "0.05", "--no-plots", "--json", *o],
                          "starved", names, 900, files=f))
        d = scene(scene(base, "supply.hoil", 2e-8), "feature", {"kind": "dent", "amplitude": "50 nm", "width": "20 um"})
        C.append(Case("starved", f"starved_{tag}_transient", ["transient", "{dir}/s.toml", "--no-plots", *o],
                      "error", ["hoil"], 300, files={"s.toml": d}))
    d = scene(scene(LINE_STARVED, "supply", delete=True), "feature", {"kind": "dent", "amplitude": "50 nm", "width": "20 um",
                                                                     "x0": math.nan})
    C.append(Case("options", "transient_x0_nan_refused", ["transient", "{dir}/s.toml", "--no-plots", *o], "error", ["x0"],
                  files={"s.toml": d}))
    C.append(Case("starved", "starved_line_tehl", ["tehl", "{dir}/s.toml", "--points", "257", "--json"],
                  "starved", ["hoil"], 600, files={"s.toml": LINE_STARVED}))
    # options a path does not honour
    th = ["solve", "appendix_c_line_4240N", "--thermal", "--no-plots", *o]
    C.append(Case("options", "thermal_rigid_refused", th + ["--rigid"], "error", ["--rigid"]))
    C.append(Case("options", "thermal_slip_5_refused", th + ["--slip", "5"], "error", ["slip"]))
    C.append(Case("options", "thermal_solver_newton_refused", th + ["--solver", "newton"], "error", ["--solver"]))
    C.append(Case("options", "thermal_deformation_refused", th + ["--deformation", "fft"], "error", ["--deformation"]))
    C.append(Case("options", "traction_foreign_film_refused", ["solve", "appendix_d_point", "--no-plots", "--accuracy", "0.05", *o],
                  "ok", check="traction_foreign_film", timeout=600))
    # the unit mistakes of the report: warned (exit 0 with the field named), refused with --strict
    plaus = {
        "load_1e12": ("operating.load", 1e12, ["load"]),
        "radius_10m": ("geometry", {"R1x": 10.32, "R1y": 10.32, "R2x": math.inf, "R2y": math.inf}, ["R1x"]),
        "eta0_1e6": ("lubricant.eta0", 1e6, ["eta0"]),
        "T_oil_343": ("operating.T_oil", 343.0, ["T_oil"]),
    }
    for k, (path, value, names) in plaus.items():
        d = scene(POINT_STARVED, path, value)
        d = scene(d, "supply", delete=True)
        C.append(Case("plausibility", f"plausible_{k}_warns", ["show", "{dir}/s.toml"], "warn", names, files={"s.toml": d}))
        C.append(Case("plausibility", f"plausible_{k}_strict", ["--strict", "show", "{dir}/s.toml"], "error", names,
                      files={"s.toml": d}))
    d = scene(LINE_STARVED, "contact.length", 10.0)
    C.append(Case("plausibility", "plausible_line_10m_warns", ["show", "{dir}/s.toml"], "warn", ["length"],
                  files={"s.toml": scene(d, "supply", delete=True)}))
    el = {"name": "el", "lubricant": {"preset": "T9"}, "operating": {"T_oil": 70.0},
          "element": {"kind": "ball_bearing", "ball_diameter": "7.938 mm", "pitch_diameter": "38.5 mm", "n_balls": 9,
                      "f_inner": 0.52, "f_outer": 0.525, "race": "inner", "shaft_speed": 3000.0, "radial_load": "350 N"}}
    C.append(Case("plausibility", "plausible_shaft_3000_rad_s_warns", ["show", "{dir}/s.toml"], "warn", ["shaft_speed"],
                  files={"s.toml": el}))
    C.append(Case("plausibility", "fit_outside_range_6205_warns", ["show", "bearing_6205_inner_race"], "warn", ["range"]))
    C.append(Case("faults", "show_into_closed_pipe", ["show", "default"], "ok", check="broken_pipe"))
    C.append(Case("faults", "two_runs_one_folder", ["run", "appendix_c_line_4240N", "--tolerance", "0.5", "--no-plots", *o],
                  "ok", check="concurrent_run", timeout=300))
    return C


def _json_payload(out: str) -> dict | None:
    try:
        v = json.loads(out)
    except ValueError:
        return None
    return v if isinstance(v, dict) else None


def _payload_failed(p: Any) -> bool:
    """A payload (or a stage or sub-payload) that says it did not converge or fell back."""
    if not isinstance(p, dict):
        return False
    st = p.get("status")
    if p.get("converged") is False or p.get("solver_fallback") or (isinstance(st, str) and st not in ("converged", "ok")):
        return True
    return any(_payload_failed(v) for v in p.values() if isinstance(v, dict))


#: keys under which a payload reports the central film it used [m]
FILM_KEYS = ("hc", "h_uniform", "hc_estimate")


def _films(p: Any) -> list[float]:
    """Every central film [m] a payload reports (:data:`FILM_KEYS`, at any depth, lists included)."""
    found: list[float] = []
    if isinstance(p, dict):
        for k, v in p.items():
            if k in FILM_KEYS and isinstance(v, (int, float)):
                found.append(float(v))
            elif k in FILM_KEYS and isinstance(v, list):
                found += [float(x) for x in v if isinstance(x, (int, float))]
            else:
                found += _films(v)
    elif isinstance(p, list):
        for v in p:
            found += _films(v)
    return found


def starved_verdict(c: Case, rc: int | None, out: str, hoil: float) -> tuple[str, str]:
    """A starved scene: exit 0 must come with films that carry no more oil than supplied
    (rho_c hc <= hoil, rho_c >= 1, so hc <= hoil; 5 % for the film's own error)."""
    p = _json_payload(out)
    if p is None:
        return "silent", "exit 0 without a JSON payload to judge the film by"
    if _payload_failed(p):
        return "exit-0 failure", "exit 0 while the payload says it did not converge or fell back"
    films = _films(p)
    if not films:
        return "silent", "exit 0 and no film reported for a starved scene"
    worst = max(films)
    if worst > 1.05 * hoil:
        return "silent", f"film hc {worst * 1e9:.4g} nm carries more oil than the {hoil * 1e9:.4g} nm supplied"
    return "ok", f"starved film hc {worst * 1e9:.4g} nm <= supply"


# -- files ----------------------------------------------------------------------------------------
def _height_map(kind: str) -> str | bytes:
    rng = np.random.default_rng(3)
    if kind == "rough":
        z = rng.normal(0.0, 1e-7, (64, 64))
        return "\n".join(",".join(f"{v:.6e}" for v in row) for row in z) + "\n"
    if kind == "flat":
        return "\n".join(",".join(["1.5e-6"] * 32) for _ in range(32)) + "\n"
    if kind == "truncated":
        z = rng.normal(0.0, 1e-7, (16, 16))
        text = "\n".join(",".join(f"{v:.6e}" for v in row) for row in z)
        return text[: len(text) // 2 + 7]
    if kind == "nan":
        return "\n".join(",".join(["nan"] * 8) for _ in range(8)) + "\n"
    raise ValueError(kind)


def write_files(c: Case, d: Path) -> None:
    for rel, content in c.files.items():
        p = d / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, dict):
            txt = toml_text(json.loads(json.dumps(content).replace("{dir}", str(d)), parse_constant=float))
            p.write_text(txt)
        elif isinstance(content, bytes):
            p.write_bytes(content)
        elif content in ("rough", "flat", "truncated", "nan"):
            p.write_text(_height_map(content))
        elif content == "huge":
            # 8000 x 8000 doubles = 512 MB would be a real instrument's size; 4000^2 = 128 MB here
            np.save(p, np.random.default_rng(0).normal(0.0, 1e-7, (4000, 4000)))
        elif content.startswith("HDF5:"):
            import h5py

            with h5py.File(p, "w") as f:
                f.create_dataset("x", data=np.arange(5.0))
        else:
            p.write_text(content)


# -- checks after a run ---------------------------------------------------------------------------
def _files_outside(root: Path, allowed: Path, before: set[str]) -> list[str]:
    bad = []
    for p in root.rglob("*"):
        if p.is_file() and allowed not in p.parents and str(p) not in before:
            bad.append(str(p))
    return bad


def check(c: Case, d: Path, rc: int, before: set[str]) -> str:
    """'' if the check passes, else what went wrong (``before``: the files of ``d`` before the run).

    Second runs start in ``d`` like the case itself: ``python -m`` puts the working folder first
    on ``sys.path``, so starting in a source tree would import that tree's package."""
    if c.check == "inside_out":
        out = d / "w" / "o"
        bad = _files_outside(d, out, before)
        for p in (d / "escaped_abs.h5", d.parent / "escaped_up.h5", Path("/tmp/escaped_stribeck.h5")):
            if p.exists():
                bad.append(str(p))
        return f"files written outside --out: {bad}" if bad else ""
    if c.check == "run_complete":
        import h5py

        h5 = next((d / "o").glob("*.h5"), None)
        if h5 is None:
            return "no HDF5 written"
        with h5py.File(h5, "r") as f:
            if f.attrs.get("complete") is not np.True_ and f.attrs.get("complete") is not True:
                return "HDF5 of a finished run has no complete = True attribute"
        mode = h5.stat().st_mode & 0o777
        if mode & 0o044 != 0o044:
            return f"result file mode {oct(mode)}: not readable by group/others under umask 022"
        return ""
    if c.check == "no_run_output":
        return ""
    if c.check == "csv_written":
        files = sorted((d / "o").glob("*.csv"))
        return "" if files and files[0].read_text().startswith("X,P,H") else "no profile CSV written"
    if c.check == "run_no_stale":
        pngs = sorted(p.name for p in (d / "o").glob("*.png"))
        if not pngs:
            return "the first run wrote no figures"
        r = subprocess.run([sys.executable, "-m", "ehl_multigrid.app.cli", "run", "appendix_c_line_4240N", "--tolerance", "0.5",
                            "--no-plots", "--out", str(d / "o")], capture_output=True, text=True, timeout=300, cwd=d)
        if r.returncode != 0:
            return f"second run failed: {r.stderr.strip().splitlines()[-1:]}"
        stale = sorted(p.name for p in (d / "o").glob("*.png"))
        return f"figures of the previous run left beside the new results: {stale}" if stale else ""
    if c.check == "run_two_scenes":
        # a second scene into the same folder must not overwrite the first scene's report
        before = sorted(p.name for p in (d / "o").iterdir() if not p.name.startswith("."))
        r = subprocess.run([sys.executable, "-m", "ehl_multigrid.app.cli", "run", "appendix_c_line_42400N", "--tolerance", "0.5",
                            "--no-plots", "--out", str(d / "o")], capture_output=True, text=True, timeout=300, cwd=d)
        if r.returncode != 0:
            return f"second run failed: {r.stderr.strip().splitlines()[-1:]}"
        after = sorted(p.name for p in (d / "o").iterdir() if not p.name.startswith("."))
        lost = [n for n in before if n not in after]
        reports = [n for n in after if n.endswith(".md")]
        if lost or len(reports) < 2:
            return f"second scene replaced the first's outputs: before {before}, after {after}"
        return ""
    if c.check == "traction_foreign_film":
        # a film of another contact fed to the traction of this scene must be refused
        h5 = next((d / "o").glob("*.h5"), None)
        if h5 is None:
            return "the film solve wrote no HDF5"
        r = subprocess.run([sys.executable, "-m", "ehl_multigrid.app.cli", "traction", "ball_on_disc_tribometer", "--input", "ehl",
                            "--ehl-file", str(h5), "--slip", "0.05", "--no-plots", "--out", str(d / "t")],
                           capture_output=True, text=True, timeout=600, cwd=d)
        if r.returncode == 2 and "Traceback" not in r.stderr:
            return ""
        return f"traction on another contact's film: exit {r.returncode}, {r.stderr.strip().splitlines()[-1:]}"
    if c.check == "broken_pipe":
        r = subprocess.run(f"{sys.executable} -m ehl_multigrid.app.cli show default | head -2", shell=True,
                           capture_output=True, text=True, timeout=120, cwd=d)
        r2 = subprocess.run(f"{sys.executable} -m ehl_multigrid.app.cli scenes --json | head -c 600", shell=True,
                            capture_output=True, text=True, timeout=120, cwd=d)
        bad = [x.stderr.strip().splitlines()[-1] for x in (r, r2) if "Traceback" in x.stderr or "Error" in x.stderr]
        return f"closed pipe: {bad}" if bad else ""
    if c.check == "concurrent_run":
        # two runs into one folder at the same time: the second must be refused (or wait), never
        # both exit 0 with one silently overwriting the other
        argv = [sys.executable, "-m", "ehl_multigrid.app.cli", "run", "appendix_c_line_42400N", "--tolerance", "0.5",
                "--no-plots", "--out", str(d / "c")]
        a = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=d)
        time.sleep(1.0)
        b = subprocess.run(argv, capture_output=True, text=True, timeout=300, cwd=d)
        a_out, a_err = a.communicate(timeout=300)
        codes = sorted((a.returncode, b.returncode))
        if codes == [0, 2] and "Traceback" not in b.stderr + a_err:
            return ""
        return f"two concurrent runs into one folder: exits {codes}"
    if c.check == "sweep_rerun":
        # rerun into the same folder with other values: must compute, not return the old rows
        r = subprocess.run([sys.executable, "-m", "ehl_multigrid.app.cli", "sweep", "page63_line_500N", "--workers", "1",
                            "--out", str(d / "sw"), "--param", "operating.us=5,50", "--json"],
                           capture_output=True, text=True, timeout=300, cwd=d)
        if r.returncode == 2 and "Traceback" not in r.stderr:
            return ""  # refused with a clear message: acceptable
        if r.returncode != 0:
            return f"rerun exit {r.returncode}: {r.stderr.strip().splitlines()[-1:]}"
        table = json.loads((d / "sw" / "table.json").read_text())
        us = sorted(row["operating.us"] for row in table["rows"])
        return "" if us == [5.0, 50.0] else f"rerun with us = 5, 50 returned rows for us = {us}"
    return ""


# -- running --------------------------------------------------------------------------------------
def run_case(c: Case, workdir: Path) -> dict[str, Any]:
    d = workdir / c.name
    if d.exists():
        shutil.rmtree(d)
    d.mkdir(parents=True)
    write_files(c, d)
    before = {str(p) for p in d.rglob("*")}
    argv = [a.replace("{dir}", str(d)) for a in c.argv]
    names = [n.replace("{dir}", str(d)) for n in c.names]
    env = dict(os.environ, NUMBA_NUM_THREADS="1", OMP_NUM_THREADS="1", PYTHONWARNINGS="ignore::DeprecationWarning")
    t0 = time.perf_counter()
    try:
        r = subprocess.run([sys.executable, "-m", "ehl_multigrid.app.cli", *argv], capture_output=True, text=True,
                           timeout=c.timeout, cwd=d, env=env, errors="replace", start_new_session=True, umask=0o022)
        rc, out, err = r.returncode, r.stdout, r.stderr
        timed_out = False
    except subprocess.TimeoutExpired as exc:
        rc, timed_out = None, True
        out = exc.stdout.decode(errors="replace") if isinstance(exc.stdout, bytes) else (exc.stdout or "")
        err = exc.stderr.decode(errors="replace") if isinstance(exc.stderr, bytes) else (exc.stderr or "")
    wall = time.perf_counter() - t0
    problem = "" if timed_out else check(c, d, rc, before)
    cls, why = classify(c, rc, out, err, timed_out, names, problem)
    lines = [ln for ln in err.strip().splitlines() if ln.strip()]
    return {**{k: v for k, v in asdict(c).items() if k != "files"}, "argv": argv, "exit": rc, "wall_s": round(wall, 2),
            "class": cls, "why": why, "stderr_last": lines[-1][:400] if lines else "",
            "stderr_lines": len(lines)}


def classify(c: Case, rc: int | None, out: str, err: str, timed_out: bool, names: list[str], problem: str) -> tuple[str, str]:
    if timed_out:
        return "silent", f"no answer within {c.timeout:g} s"
    if "Traceback (most recent call last)" in err or rc == 1 or (rc is not None and rc < 0):
        return "traceback", "traceback or internal error"
    named = any(n.lower() in err.lower() for n in names) if names else True
    if problem:
        return "silent", problem
    if c.expect == "ok":
        return ("ok", "") if rc == 0 else ("unclear error", f"valid input refused with exit {rc}")
    if c.expect == "starved":
        if rc == 3:
            return "ok", "exit 3 (did not converge)"
        if rc == 2:
            return ("clear error", "refused") if named else ("unclear error", "refused without naming the supply")
        if rc == 0:
            return starved_verdict(c, rc, out, _hoil_of(c))
        return "unclear error", f"exit {rc}"
    if rc == 0 and (p := _json_payload(out)) is not None and _payload_failed(p):
        return "exit-0 failure", "exit 0 while the payload says it did not converge or fell back"
    if c.expect == "warn":
        if rc == 0:
            warned = any(n.lower() in (err + out).lower() for n in names) and "warn" in (err + out).lower()
            return ("warned", "") if warned else ("silent", "no warning")
        return "unclear error", f"exit {rc} where a warning was expected"
    if c.expect == "noconv":
        if rc == 3:
            return "ok", "exit 3 (did not converge)"
        return ("silent", "exit 0 for an unconverged result") if rc == 0 else ("unclear error", f"exit {rc}")
    if c.expect == "refuse_or_ok":
        if rc in (0, 3):  # 3: computed and written, short of its accuracy; the check judges the paths
            return "ok", "accepted (sanitised)"
        if rc == 2:
            return ("clear error", "") if named else ("unclear error", "refused without naming the field")
        return "unclear error", f"exit {rc}"
    # expect == "error"
    if rc == 0:
        return "silent", "exit 0 on a bad input"
    if rc == 2:
        return ("clear error", "") if named else ("unclear error", f"message does not name {names}")
    return "unclear error", f"exit {rc} for a bad input"


def _hoil_of(c: Case) -> float:
    d = c.files.get("s.toml")
    return float(d["supply"]["hoil"]) if isinstance(d, dict) and "supply" in d else math.inf


def package_version() -> str:
    """The installed package's version (the report block says what it measured, not when)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("ehl-multigrid")
    except PackageNotFoundError:
        return "not installed"


def write_report(results: list[dict[str, Any]], label: str) -> str:
    counts = {k: 0 for k in CLASSES}
    for r in results:
        counts[r["class"]] += 1
    groups: dict[str, dict[str, int]] = {}
    for r in results:
        g = groups.setdefault(r["group"], {k: 0 for k in CLASSES})
        g[r["class"]] += 1
    lines = [f"<!-- counts:{label} -->", "",
             f"**{label}** ({len(results)} inputs, package {package_version()}): "
             + ", ".join(f"{k} {v}" for k, v in counts.items()), "",
             "| group | " + " | ".join(CLASSES) + " |", "|---|" + "---|" * len(CLASSES)]
    for g, cnt in groups.items():
        lines.append(f"| {g} | " + " | ".join(str(cnt[k]) for k in CLASSES) + " |")
    lines.append("| **all** | " + " | ".join(f"**{counts[k]}**" for k in CLASSES) + " |")
    bad = [r for r in results if r["class"] in ("traceback", "silent", "exit-0 failure", "unclear error")]
    if bad:
        lines += ["", "Cases not yet right:", ""]
        for r in bad:
            lines.append(f"- `{r['name']}` ({r['class']}): {r['why']}; `{r['stderr_last'][:160]}`")
    lines += ["", f"<!-- end:{label} -->"]
    return "\n".join(lines)


def update_report(block: str, label: str) -> None:
    text = REPORT.read_text() if REPORT.exists() else "# Hostile inputs\n"
    start, end = f"<!-- counts:{label} -->", f"<!-- end:{label} -->"
    if start in text and end in text:
        a, b = text.index(start), text.index(end) + len(end)
        text = text[:a] + block + text[b:]
    else:
        text = text.rstrip() + "\n\n" + block + "\n"
    REPORT.write_text(text)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", default=None, help="run the cases whose name contains this text")
    ap.add_argument("--jobs", type=int, default=2, help="cases run at the same time (default 2)")
    ap.add_argument("--label", default="after", help="name of the counts block in REPORT.md")
    ap.add_argument("--list", action="store_true", help="list the cases and exit")
    a = ap.parse_args()
    todo = [c for c in cases() if a.only is None or a.only in c.name]
    if a.list:
        for c in todo:
            print(f"{c.group:<9} {c.name:<40} {c.expect:<12} ehl {' '.join(c.argv)}")
        print(len(todo), "cases")
        return 0
    OUT.mkdir(parents=True, exist_ok=True)
    workdir = Path(tempfile.mkdtemp(prefix="ehl_hostile_"))
    results: list[dict[str, Any]] = []
    try:
        with cf.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
            futs = {ex.submit(run_case, c, workdir): c for c in todo}
            for fut in cf.as_completed(futs):
                r = fut.result()
                results.append(r)
                print(f"{len(results):3d}/{len(todo)} {r['class']:<13} {r['name']:<40} exit {r['exit']} "
                      f"{r['wall_s']:6.1f} s  {r['stderr_last'][:90]}", flush=True)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    order = {c.name: i for i, c in enumerate(todo)}
    results.sort(key=lambda r: order[r["name"]])
    if a.only is None:
        (OUT / f"hostile_{a.label}.json").write_text(json.dumps(results, indent=1))
        (OUT / "hostile.json").write_text(json.dumps(results, indent=1))
        update_report(write_report(results, a.label), a.label)
    counts = {k: sum(r["class"] == k for r in results) for k in CLASSES}
    print(json.dumps(counts))
    return 0


if __name__ == "__main__":
    sys.exit(main())
