"""The planner's data tables (package data in ``ehl_multigrid/data/``), solved and written by one
command, each with the provenance that tests/model/test_planner_tables.py checks.

* ``fit_deviation_line.json`` / ``fit_deviation_point.json``: the relative deviation
  ``(Hc_fit - Hc_solver) / Hc_solver`` of the Moes line fit (thesis 2.17-2.22) and the
  Nijenbanning fit (2.23-2.29) from converged Roelands (2.6) + Dowson-Higginson (2.7) solves on
  an M x L map (point contacts at theta = 1; ``null`` where the solve did not converge). Same
  grids and calls as the fit-check studies ``validation/line/studies.py --study fit --full``
  and ``validation/point/fit_check.py --roelands``.
* ``grid_error_line.json`` / ``grid_error_point.json``: the constant ``C(M)`` of the
  second-order grid error of Hc, ``|error| = C / (N - 1)^2``, from V cycles with FFT
  deformation against a reference grid: ``C = |e| / ((N-1)^-2 - (N_ref-1)^-2)``, median over
  the listed grids (the settings of ``validation/pareto/pareto.py``).

Each table carries ``provenance``: the package version and git commit, the date, the command,
whether its data were solved by that command or re-solved on a sample and found unchanged, and
a solver fingerprint: Hc and Hm (exact floats) of two tiny fixed-grid solves, recomputed by the
test, which fails when the solver's numbers moved since the tables were written.

Usage (from the repository root)::

    python -m validation.plan.planner_tables            # solve every case, write all four tables
    python -m validation.plan.planner_tables --check    # re-solve a sample of each table's cases;
                                                        # unchanged: refresh the provenance only,
                                                        # changed: name the stale entries, exit 1

``--tables`` restricts either mode to some of the tables. The full run solves 60 line and 48
point fit-check cases and 20 grid-error solves (up to 16385 line and 1025 point points): about
14 minutes on a loaded 2-core machine; ``--check`` about 2.5 minutes.
"""

from __future__ import annotations

import argparse
import datetime
import importlib.metadata
import json
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
# the tables describe this tree's solver, also when run as a file with another copy installed
sys.path.insert(0, str(ROOT))

from ehl_multigrid.model.errors import ConvergenceError  # noqa: E402
from ehl_multigrid.model.fits import moes_line_central, nijenbanning_central  # noqa: E402

DATA = ROOT / "ehl_multigrid" / "data"
COMMAND = "python -m validation.plan.planner_tables"
TABLES = ("fit_deviation_line", "fit_deviation_point", "grid_error_line", "grid_error_point")

#: the fit-check maps (validation/line/studies.py, validation/point/fit_check.py)
FIT_MAP = {"line": ((2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0),
                    (0.0, 2.0, 5.0, 10.0, 15.0, 20.0)),
           "point": ((5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0),
                     (0.0, 2.5, 5.0, 10.0, 15.0, 20.0))}
#: the accuracy-cost study's operating points, grids and reference grid (validation/pareto)
GRID_STUDY = {"line": (((20.0, 10.0), (100.0, 10.0), (500.0, 10.0)), (1025, 2049, 4097), 16385),
              "point": (((20.0, 10.0), (100.0, 10.0)), (129, 257, 513), 1025)}
#: cases re-solved by --check: a spread over M and L, including one a solve failed on
CHECK_SAMPLE = {"fit_deviation_line": ((2.0, 0.0), (20.0, 10.0), (200.0, 5.0), (1000.0, 10.0), (2000.0, 0.0)),
                "fit_deviation_point": ((5.0, 0.0), (20.0, 10.0), (100.0, 0.0), (200.0, 15.0), (1000.0, 5.0)),
                "grid_error_line": (100.0,), "grid_error_point": (20.0,)}
#: largest change --check accepts: a deviation is read to the percent, and a factor 2 in C moves
#: the chosen grid by one level
CHECK_TOL = {"deviation": 1e-3, "C": 0.02}
#: the fingerprint solves: (solver, M, L, keyword arguments); fixed grids, no accuracy loop
FINGERPRINT = (("line", 100.0, 10.0, {"points": 257, "estimate": False}),
               ("point", 20.0, 10.0, {"points": 65, "estimate": False}))
DEFINITIONS = {"fit_deviation": "(Hc_fit - Hc_solver) / Hc_solver, Roelands + Dowson-Higginson, converged solves",
               "grid_error": "relative error of Hc = C / (points - 1)^2 (Roelands + Dowson-Higginson)"}


def log(text: str) -> None:
    print(text, file=sys.stderr, flush=True)


# -- the solves ---------------------------------------------------------------------------------
def fit_points(contact: str, M: float) -> int:
    """Points along X of a fit-check case (line: validation/line/studies.py ``fit_points``;
    point: at least 129 and the point solver's ``min_points``)."""
    if contact == "line":
        return 2049 if M <= 100 else (4097 if M <= 500 else 8193)
    from ehl_multigrid.point.problem import hertz_shape, min_points

    return max(129, min_points(M, hertz_shape(1.0)[2]))


def fit_case_hc(contact: str, M: float, L: float) -> float | None:
    """Hc of a converged Roelands + Dowson-Higginson fit-check solve, ``None`` when it failed."""
    n = fit_points(contact, M)
    try:
        if contact == "line":
            from ehl_multigrid.line import solve_line

            s = solve_line(M, L, points=n, viscosity="roelands", density="dowson-higginson")
            return float(s.Hc) if s.converged else None
        from ehl_multigrid.point import build_result, problem_from_moes, solve_fas

        pb = problem_from_moes(M, L, 1.0, "roelands", "dowson-higginson")
        sc = build_result(solve_fas(pb, points=n, max_cycles=25), fields=False).scalars
        return float(sc["Hc"]) if sc["converged"] and sc.get("Hc") else None
    except ConvergenceError:
        return None


def fit_deviation(contact: str, M: float, L: float) -> float | None:
    """``(Hc_fit - Hc_solver) / Hc_solver`` at (M, L), ``None`` without a converged solve."""
    hc = fit_case_hc(contact, M, L)
    if hc is None:
        return None
    fit = float(moes_line_central(M, L) if contact == "line" else nijenbanning_central(M, L))
    return (fit - hc) / hc


def grid_hc(contact: str, M: float, L: float, points: int) -> float:
    """Hc of the accuracy-cost study's V-cycle, FFT-deformation solve; raises when not converged."""
    if contact == "line":
        from ehl_multigrid.line import solve_line as solve
    else:
        from ehl_multigrid.point import solve_point as solve
    s = solve(M, L, points=points, cycle="V", deformation="fft")
    if not s.converged:
        raise RuntimeError(f"{contact} ({M:g}, {L:g}) on {points} points: {s.status_name}; C not measured")
    return float(s.Hc)


def grid_constant(contact: str, M: float, L: float) -> float:
    """Median over the study's grids of ``|Hc - Hc_ref| / Hc_ref / ((N-1)^-2 - (N_ref-1)^-2)``."""
    _cases, grids, n_ref = GRID_STUDY[contact]
    ref = grid_hc(contact, M, L, n_ref)
    cs = [abs(grid_hc(contact, M, L, n) - ref) / abs(ref) / ((n - 1) ** -2 - (n_ref - 1) ** -2)
          for n in grids]
    return float(np.median(cs))


def fingerprint() -> list[dict[str, Any]]:
    """Hc and Hm of the :data:`FINGERPRINT` solves, as the test recomputes them."""
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    out = []
    for solver, M, L, kw in FINGERPRINT:
        s = (solve_line if solver == "line" else solve_point)(M, L, **kw)
        if not s.converged:
            raise RuntimeError(f"fingerprint solve {solver} ({M:g}, {L:g}) {kw}: {s.status_name}")
        out.append({"solver": solver, "M": M, "L": L, "options": dict(kw), "Hc": float(s.Hc), "Hm": float(s.Hm)})
    return out


# -- the tables ---------------------------------------------------------------------------------
def solve_table(name: str) -> dict[str, Any]:
    """Every case of table ``name`` solved now."""
    kind, contact = name.rsplit("_", 1)
    if kind == "fit_deviation":
        Ms, Ls = FIT_MAP[contact]
        dev = []
        for M in Ms:
            row = []
            for L in Ls:
                t0 = time.perf_counter()
                row.append(fit_deviation(contact, M, L))
                log(f"{name}: M={M:g} L={L:g}: {row[-1]} ({time.perf_counter() - t0:.1f} s)")
            dev.append(row)
        study = ("validation/line/studies.py --study fit --full" if contact == "line"
                 else "validation/point/fit_check.py --roelands")
        return {"M": list(Ms), "L": list(Ls), "deviation": dev, "definition": DEFINITIONS[kind],
                "source": f"{COMMAND} (the grids and calls of {study})"}
    cases, grids, n_ref = GRID_STUDY[contact]
    Cs = []
    for M, L in cases:
        t0 = time.perf_counter()
        Cs.append(grid_constant(contact, M, L))
        log(f"{name}: M={M:g}: C = {Cs[-1]!r} ({time.perf_counter() - t0:.1f} s)")
    return {"M": [M for M, _L in cases], "L": [L for _M, L in cases], "C": Cs, "order": 2,
            "reference_points": n_ref, "grids": list(grids), "definition": DEFINITIONS[kind],
            "source": f"{COMMAND} (the settings of validation/pareto/pareto.py)"}


def check_table(name: str, tab: dict[str, Any]) -> list[dict[str, Any]]:
    """The :data:`CHECK_SAMPLE` cases of ``name`` re-solved: ``{case, stored, now, change, ok}``."""
    kind, contact = name.rsplit("_", 1)
    out = []
    for case in CHECK_SAMPLE[name]:
        t0 = time.perf_counter()
        if kind == "fit_deviation":
            M, L = case
            stored = tab["deviation"][tab["M"].index(M)][tab["L"].index(L)]
            now = fit_deviation(contact, M, L)
            change = None if stored is None or now is None else abs(now - stored)
            ok = (stored is None and now is None) or (change is not None and change <= CHECK_TOL["deviation"])
            rec = {"M": M, "L": L, "deviation_stored": stored, "deviation_now": now, "change": change}
        else:
            M = case
            i = tab["M"].index(M)
            stored, now = tab["C"][i], grid_constant(contact, M, tab["L"][i])
            change = abs(now / stored - 1.0)
            ok = change <= CHECK_TOL["C"]
            rec = {"M": M, "L": tab["L"][i], "C_stored": stored, "C_now": now, "relative_change": change}
        rec["agrees"] = bool(ok)
        out.append(rec)
        log(f"{name}: {rec} ({time.perf_counter() - t0:.1f} s)")
    return out


def git_commit() -> str:
    """``HEAD`` of the repository, with ``+local changes`` when the tree differs from it."""
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT,
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + (" +local changes" if dirty else "")


def run_record(fp: list[dict[str, Any]]) -> dict[str, Any]:
    """Version, commit, start time and command of this run (its code is the one imported at the
    start, so a commit made while it runs does not describe it), and the fingerprint."""
    return {"package_version": importlib.metadata.version("ehl-multigrid"), "git_commit": git_commit(),
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "command": " ".join([COMMAND, *sys.argv[1:]]), "fingerprint": fp}


def provenance(run: dict[str, Any], data: str, extra: dict[str, Any] | None = None) -> dict[str, Any]:
    return {**{k: v for k, v in run.items() if k != "fingerprint"}, "data": data, **(extra or {}),
            "fingerprint": run["fingerprint"]}


def write_table(name: str, tab: dict[str, Any]) -> None:
    """Write ``tab`` as ``ehl_multigrid/data/<name>.json`` through a temporary file."""
    path = DATA / f"{name}.json"
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(json.dumps(tab, indent=1, allow_nan=False) + "\n")
    os.replace(tmp, path)


def read_table(name: str) -> dict[str, Any]:
    return json.loads((DATA / f"{name}.json").read_text())


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true",
                    help="re-solve a sample of each table's cases; refresh only the provenance when they agree")
    ap.add_argument("--tables", default=",".join(TABLES), help=f"comma-separated subset of {','.join(TABLES)}")
    a = ap.parse_args(argv)
    names = [t.strip() for t in a.tables.split(",") if t.strip()]
    unknown = sorted(set(names) - set(TABLES))
    if unknown:
        ap.error(f"--tables {','.join(unknown)}: not one of {','.join(TABLES)}")
    run = run_record(fp := fingerprint())
    log("fingerprint: " + "; ".join(f"{f['solver']} ({f['M']:g}, {f['L']:g}) {f['options']}: "
                                     f"Hc {f['Hc']!r}, Hm {f['Hm']!r}" for f in fp))
    stale = []
    for name in names:
        if not a.check:
            tab = solve_table(name)
            tab["provenance"] = provenance(run, "solved by this command")
            write_table(name, tab)
            log(f"{name}: written")
            continue
        tab = read_table(name)
        old = tab.get("provenance", {})
        sample = check_table(name, tab)
        bad = [r for r in sample if not r["agrees"]]
        if bad:
            stale.append(name)
            log(f"{name}: STALE, {len(bad)} of {len(sample)} re-solved cases differ beyond {CHECK_TOL}: {bad}; "
                f"run `{COMMAND}`")
            continue
        origin = old.get("data_origin") or (
            f"solved on {old['date']} by `{old['command']}`" if old.get("data") == "solved by this command"
            else f"written before provenance was recorded ({tab.get('source', '')})")
        tab["provenance"] = provenance(run, "re-solved on a sample of cases and found unchanged",
                                       {"data_origin": origin, "check_tolerance": CHECK_TOL, "checked": sample})
        write_table(name, tab)
        log(f"{name}: sample agrees; provenance refreshed")
    if stale:
        log(f"stale tables (not rewritten): {', '.join(stale)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
