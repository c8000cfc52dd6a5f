"""An outer iteration's multilevel solve whose V cycles diverge or stall is solved again from
the same start with W cycles (thermal.tehl.line.LineContact.multilevel): the spur gear at
S = 0.5 on 4097 points, where V cycles drove the residual from 5e-7 to 8e-6 and W cycles
converge in three."""

import re
from types import SimpleNamespace

import numpy as np

import thermal.tehl.line as tl
from ehl_multigrid.model.scene import load_scene
from thermal.tehl.options import TEHLOptions
from thermal.tehl.outer import surroundings


def _contact(monkeypatch, statuses):
    scene = load_scene("spur_gear_pitch_point")
    opts = TEHLOptions(points=257, nz=8)
    con = tl.LineContact(scene, tl.line_problem(scene, opts), opts, surroundings(scene, 0.5))
    cycles = []

    def fake(self, lopts):
        cycles.append(lopts.cycle)
        status = statuses[len(cycles) - 1]
        return SimpleNamespace(success=status == "converged", status_name=status, message=f"{status} on grid 2",
                               P=np.zeros(3), H=np.ones(3), H0=0.0)

    monkeypatch.setattr(tl.LineContact, "_cycles", fake)
    return con, cycles


def test_diverged_v_cycles_are_solved_again_with_w_cycles_and_said_once(monkeypatch):
    con, cycles = _contact(monkeypatch, ["diverged", "converged", "stalled", "converged"])
    assert con.multilevel()[0].success and cycles == ["V", "W"]
    assert con.multilevel()[0].success and cycles == ["V", "W", "V", "W"]
    assert len(con.notes) == 1 and re.search(r"W cycles: converged \(2\b", con.notes[0])


def test_a_converged_or_floor_ended_solve_is_not_repeated(monkeypatch):
    con, cycles = _contact(monkeypatch, ["converged", "residual_floor"])
    con.multilevel()
    con.multilevel()
    assert cycles == ["V", "V"] and con.notes == []
