"""The Roelands and Dowson-Higginson constants and the Moes-only oil defaults are defined once,
in ehl_multigrid.model.constants, and every solver reads them from there."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from ehl_multigrid.model import constants

ROOT = Path(__file__).resolve().parents[2]
NAMES = {"ETA_INF", "P_R", "DH_A", "DH_B", "MOES_ONLY_DEFAULTS"}


def test_values_are_the_thesis_constants():
    # Roelands (2.6): eta_inf = 6.31e-5 Pa s, pr = 1.962e8 Pa; Dowson-Higginson (2.7)
    assert (constants.ETA_INF, constants.P_R) == (6.31e-5, 1.962e8)
    assert (constants.DH_A, constants.DH_B) == (0.59263e9, 0.34615)
    assert constants.MOES_ONLY_DEFAULTS == {"p0": 1.96e8, "alpha": 2.2e-8, "eta0": 0.04}


def test_no_other_module_defines_them():
    defined = []
    for pkg in ("ehl_multigrid", "thermal", "mixed"):
        for path in (ROOT / pkg).rglob("*.py"):
            if path == ROOT / "ehl_multigrid" / "model" / "constants.py":
                continue
            text = path.read_text()
            if not any(name in text for name in NAMES):
                continue  # no assignment to one of the names can be in it
            for node in ast.parse(text).body:
                targets = node.targets if isinstance(node, ast.Assign) else \
                    [node.target] if isinstance(node, ast.AnnAssign) else []
                defined += [f"{path.relative_to(ROOT)}:{node.lineno} {t.id}" for t in targets
                            if isinstance(t, ast.Name) and t.id in NAMES]
    assert defined == []


@pytest.mark.parametrize("module", ["ehl_multigrid.model.lubricant", "ehl_multigrid.point.numerics",
                                    "thermal.properties"])
def test_solvers_read_the_same_objects(module):
    import importlib

    mod = importlib.import_module(module)
    for name in NAMES & set(vars(mod)):
        assert getattr(mod, name) is getattr(constants, name), name


def test_moes_only_problems_default_to_the_same_oil():
    from ehl_multigrid.line.problem import LineProblem
    from ehl_multigrid.point.problem import PointProblem

    assert PointProblem(M=20, L=10).p_r == constants.MOES_ONLY_DEFAULTS["p0"]
    assert LineProblem.from_moes(20, 10).p0 == constants.MOES_ONLY_DEFAULTS["p0"]
