"""One table holds each fidelity's settings (``ehl_multigrid.model.fidelity.FIDELITIES``): the
planner's tolerance, the traction stage's thermal grid per contact and the Stribeck stage's
thermal grid are all read from it."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest

from ehl_multigrid.app.plan import make_plan
from ehl_multigrid.app.stages import RunContext
from ehl_multigrid.model.fidelity import FIDELITIES
from ehl_multigrid.model.scene import load_scene

pytest.importorskip("thermal.options")
pytest.importorskip("mixed.stage")

import mixed.stribeck  # noqa: E402
from mixed.stage import stribeck_stage  # noqa: E402
from thermal.options import ThermalOptions  # noqa: E402


class _Captured(Exception):
    """Stops the Stribeck stage where it hands its thermal grid to the curves."""


def _stribeck_grid(scene, fidelity: str, monkeypatch) -> dict | None:
    """The thermal options the Stribeck stage gives its curves for ``fidelity``, thermal on."""

    def capture(*args, thermal_options=None, **kwargs):
        raise _Captured(thermal_options)

    monkeypatch.setattr(mixed.stribeck, "stribeck_cases", capture)
    plan = SimpleNamespace(fidelity=fidelity, tolerance=FIDELITIES[fidelity].tolerance,
                           includes=lambda model: model == "thermal",
                           get=lambda model: SimpleNamespace(setting="fit"))
    ctx = RunContext(scene, plan, Path("."), plots=False, progress=False)
    with pytest.raises(_Captured) as caught:
        stribeck_stage(ctx)
    return caught.value.args[0]


@pytest.mark.parametrize("fidelity", list(FIDELITIES))
def test_the_plan_the_traction_options_and_the_stribeck_stage_read_each_fidelity_from_the_one_table(
        fidelity, monkeypatch):
    level = FIDELITIES[fidelity]
    line, point = load_scene("page63_line_2000N"), load_scene("default")  # no [solver.thermal] grid
    assert line.kind == "line" and point.kind != "line"
    assert not any(s.solver.get("thermal") for s in (line, point))
    # the planner's target accuracy
    plan = make_plan(line, fidelity=fidelity)
    assert plan.fidelity == fidelity and plan.tolerance == level.tolerance
    # the traction stage's thermal grid, per contact
    opts = ThermalOptions.for_fidelity(line, fidelity)
    assert (opts.nx, opts.nz) == (level.traction_line.nx, level.traction_line.nz)
    opts = ThermalOptions.for_fidelity(point, fidelity)
    assert (opts.nx, opts.nz, opts.slices) == (level.traction_point.nx, level.traction_point.nz,
                                               level.traction_point.slices)
    # the Stribeck stage's thermal film-friction grid (a rough scene without its own grid)
    rough = load_scene("series_C_disc3_1.93GPa")
    assert not {"nx", "nz"} & set(rough.solver.get("thermal", {}))
    assert _stribeck_grid(rough, fidelity, monkeypatch) == {"nx": level.stribeck.nx, "nz": level.stribeck.nz}


def test_the_table_holds_the_measured_settings():
    # the values the accuracy-cost studies chose (docs/thermal.md, docs/mixed.md)
    assert {f: s.tolerance for f, s in FIDELITIES.items()} == {"fast": 0.1, "standard": 0.02, "reference": 0.002}
    assert {f: s.traction_grid("line").as_options() for f, s in FIDELITIES.items()} == {
        "fast": {"nx": 20, "nz": 5}, "standard": {"nx": 40, "nz": 10}, "reference": {"nx": 160, "nz": 40}}
    assert {f: s.traction_grid("point").as_options() for f, s in FIDELITIES.items()} == {
        "fast": {"nx": 20, "nz": 5, "slices": 5}, "standard": {"nx": 40, "nz": 10, "slices": 5},
        "reference": {"nx": 80, "nz": 20, "slices": 10}}
    assert {f: s.stribeck.as_options() for f, s in FIDELITIES.items()} == {
        "fast": {"nx": 20, "nz": 5}, "standard": {"nx": 40, "nz": 10}, "reference": {"nx": 80, "nz": 20}}
