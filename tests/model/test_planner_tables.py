"""The planner's data tables (``ehl_multigrid/data/``) say where they came from and still match
the solver: each records the package version, date, command and a solver fingerprint (Hc, Hm of
two tiny fixed-grid solves), which is recomputed here."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from functools import cache
from importlib import resources
from typing import Any

import pytest

from ehl_multigrid.model import fits

TABLES = ("fit_deviation_line", "fit_deviation_point", "grid_error_line", "grid_error_point")
REGENERATE = "python -m validation.plan.planner_tables"
#: the fingerprint solves run on fixed grids without an accuracy loop: only a change of the
#: solver's numbers moves them by more than this
REL = 1e-9


def load(name: str) -> dict[str, Any]:
    return json.loads((resources.files("ehl_multigrid") / "data" / f"{name}.json").read_text())


def missing_provenance(tab: dict[str, Any]) -> list[str]:
    """The provenance entries ``tab`` lacks (empty when it has them all)."""
    prov = tab.get("provenance") or {}
    missing = [k for k in ("package_version", "date", "command") if not prov.get(k)]
    prints = prov.get("fingerprint") or []
    if not prints:
        missing.append("fingerprint")
    for f in prints:
        if not all(isinstance(f.get(q), float) and math.isfinite(f[q]) for q in ("Hc", "Hm")):
            missing.append(f"fingerprint Hc, Hm of {f.get('solver')} ({f.get('M')}, {f.get('L')})")
    return missing


def stale_entries(tab: dict[str, Any], solve: Callable[[dict[str, Any]], tuple[float, float]]) -> list[str]:
    """The fingerprint films of ``tab`` that ``solve`` no longer reproduces to :data:`REL`."""
    out = []
    for f in tab["provenance"]["fingerprint"]:
        for q, now in zip(("Hc", "Hm"), solve(f), strict=True):
            if not abs(now - f[q]) <= REL * abs(f[q]):
                out.append(f"{f['solver']} (M, L) = ({f['M']:g}, {f['L']:g}) {f['options']}: "
                           f"{q} stored {f[q]!r}, now {now!r}")
    return out


@cache
def _solve(solver: str, M: float, L: float, options: str) -> tuple[float, float]:
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    s = (solve_line if solver == "line" else solve_point)(M, L, **json.loads(options))
    assert s.converged, f"fingerprint solve {solver} ({M:g}, {L:g}) {options}: {s.status_name}"
    return float(s.Hc), float(s.Hm)


def solve_now(f: dict[str, Any]) -> tuple[float, float]:
    """Hc, Hm of a fingerprint entry solved with today's solver (each distinct solve once)."""
    return _solve(f["solver"], f["M"], f["L"], json.dumps(f["options"], sort_keys=True))


@pytest.mark.parametrize("name", TABLES)
def test_planner_table_records_version_date_command_and_solver_fingerprint(name):
    missing = missing_provenance(load(name))
    assert not missing, (f"ehl_multigrid/data/{name}.json has no provenance {missing}: "
                         f"regenerate it with `{REGENERATE}`")


@pytest.mark.parametrize("name", TABLES)
def test_planner_table_fingerprint_matches_the_solver_now(name):
    stale = stale_entries(load(name), solve_now)
    assert not stale, (f"ehl_multigrid/data/{name}.json was written by another solver (fingerprint "
                       f"beyond {REL:g} relative: {'; '.join(stale)}): regenerate it with `{REGENERATE}` "
                       f"(or `{REGENERATE} --check`, which re-solves a sample of its cases and refreshes "
                       "the provenance only when they are unchanged)")


def test_a_fingerprint_film_moved_beyond_1e9_is_reported_stale_and_named():
    tab = {"provenance": {"fingerprint": [{"solver": "line", "M": 100.0, "L": 10.0,
                                           "options": {"points": 257}, "Hc": 2.5, "Hm": 2.0}]}}
    assert stale_entries(tab, lambda f: (2.5 * (1 + 0.5e-9), 2.0)) == []
    stale = stale_entries(tab, lambda f: (2.5, 2.0 * (1 + 2e-9)))
    assert len(stale) == 1 and "Hm" in stale[0] and "(100, 10)" in stale[0]


def test_a_table_without_provenance_or_fingerprint_films_is_reported():
    assert missing_provenance({"M": [1.0], "C": [2.0]}) == ["package_version", "date", "command", "fingerprint"]
    prov = {"package_version": "0.1.0", "date": "2026-11-28", "command": REGENERATE,
            "fingerprint": [{"solver": "point", "M": 20.0, "L": 10.0, "Hc": float("nan"), "Hm": 1.0}]}
    missing = missing_provenance({"provenance": prov})
    assert len(missing) == 1 and "point" in missing[0]


def test_the_fit_deviation_loader_carries_the_tables_provenance():
    for contact in ("line", "point"):
        prov = fits.deviation_table(contact)["provenance"]
        assert prov == load(f"fit_deviation_{contact}")["provenance"] and prov["package_version"]
