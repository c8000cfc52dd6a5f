"""Importing the packages changes nothing in the process: no environment variable (the OpenMP
wait policy is the ``ehl`` command's choice, :func:`passive_openmp_wait`, not an import's) and no
import hook on ``sys.meta_path``. Checked in a fresh interpreter on this checkout."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from ehl_multigrid.multigrid.threads import passive_openmp_wait

ROOT = Path(__file__).resolve().parents[2]

PROBE = r"""
import importlib, json, os, pkgutil, sys

def state():
    return dict(os.environ), list(sys.meta_path)

def changes(before):
    env, finders = before
    return {"set": {k: v for k, v in os.environ.items() if env.get(k) != v},
            "removed": sorted(k for k in env if k not in os.environ),
            "finders": [f"{type(f).__module__}.{type(f).__qualname__}" for f in sys.meta_path
                        if f not in finders],
            "files": [m.__file__ for m in map(sys.modules.get, ("ehl_multigrid", "thermal", "mixed"))
                      if m is not None]}

TOPS = ("ehl_multigrid", "thermal", "mixed")
before = state()
for top in TOPS:
    importlib.import_module(top)
out = {"packages": changes(before)}
# every module of the three packages (the numba kernels, the thread control, the command line)
before = state()
for top in TOPS:
    pkg = sys.modules[top]
    for info in pkgutil.walk_packages(pkg.__path__, top + "."):
        if not info.name.endswith("__main__"):
            importlib.import_module(info.name)
out["modules"] = changes(before)
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def imported():
    env = {k: v for k, v in os.environ.items() if k != "OMP_WAIT_POLICY"}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    run = subprocess.run([sys.executable, "-c", PROBE], cwd=ROOT, env=env, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.strip().splitlines()[-1])


@pytest.mark.xdist_group("import_side_effects_imported")
def test_the_probe_imports_this_checkout(imported):
    for f in imported["packages"]["files"]:
        assert Path(f).resolve().is_relative_to(ROOT), f


@pytest.mark.xdist_group("import_side_effects_imported")
def test_importing_the_packages_leaves_the_environment_unchanged(imported):
    for phase in ("packages", "modules"):
        assert imported[phase]["set"] == {} and imported[phase]["removed"] == [], phase


@pytest.mark.xdist_group("import_side_effects_imported")
def test_importing_the_packages_installs_no_import_hook(imported):
    assert imported["packages"]["finders"] == []
    # every module: none of ours (a third-party library they load may bring its own: six's)
    ours = [f for f in imported["modules"]["finders"] if f.split(".")[0] in ("ehl_multigrid", "thermal", "mixed")]
    assert ours == []


def test_passive_openmp_wait_defaults_the_policy_and_keeps_an_explicit_one(monkeypatch):
    monkeypatch.delenv("OMP_WAIT_POLICY", raising=False)
    assert passive_openmp_wait() is True
    assert os.environ["OMP_WAIT_POLICY"] == "PASSIVE"
    monkeypatch.setenv("OMP_WAIT_POLICY", "ACTIVE")
    assert passive_openmp_wait() is False
    assert os.environ["OMP_WAIT_POLICY"] == "ACTIVE"


SOLVE_PROBE = r"""
import os, sys
import ehl_multigrid
from ehl_multigrid.solution import MoesProblem
before = os.environ.get("OMP_WAIT_POLICY")
ehl_multigrid.solve(MoesProblem("line", M=20, L=10), accuracy=None, options={"points": 129})
print(before, os.environ.get("OMP_WAIT_POLICY"))
"""


@pytest.mark.parametrize("given, after", [(None, "PASSIVE"), ("ACTIVE", "ACTIVE")])
def test_the_front_door_defaults_a_passive_openmp_wait_before_its_first_solve(given, after):
    # a library user's solve waits passively, as the ehl command's (a spinning thread takes
    # the working thread's core on a busy machine); an explicit policy wins
    env = {k: v for k, v in os.environ.items() if k != "OMP_WAIT_POLICY"}
    if given is not None:
        env["OMP_WAIT_POLICY"] = given
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    run = subprocess.run([sys.executable, "-c", SOLVE_PROBE], cwd=ROOT, env=env, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == [str(given), after]
