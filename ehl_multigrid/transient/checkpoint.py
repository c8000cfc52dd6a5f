"""Checkpoints of a transient run: the completed steps written while it runs, so that a run
that is killed (even by SIGKILL) leaves its last checkpoint, and a continued run picks up
after the last completed step.

A checkpoint is the run's own HDF5 file (:meth:`~.result.TransientResult.to_hdf5`, written
through a temporary file and a rename) with ``complete = False``, ``stop_reason`` saying that
the run was still going, and the group ``state``: the unknowns ``(P, H0)`` of the last two
steps and their films ``rho H``, which is all the next BDF2 step needs (its history term and
its extrapolated start iterate). Continuing from it therefore repeats the steps an
uninterrupted run would have taken.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ..model.atomic import deferred_signals
from ..model.errors import InputError

#: default interval between checkpoints [s]
EVERY_S = 30.0
#: checkpoints are spaced so that writing them takes at most this share of the wall time
MAX_SHARE = 0.05


class Checkpoint:
    """Writes a run to ``path`` after a completed step when one is due: every ``every_s``
    seconds (stretched so that writing takes at most ``max_share`` of the run), every
    ``every_steps`` steps when given (0: by time only), and after the start.

    ``write`` writes the run as it stands (a run that ended early: its final, incomplete
    file). ``run``: the parameters of the run, stored with it (what ``--resume`` compares).
    ``writes`` counts the writes.
    """

    def __init__(self, path: str | os.PathLike, every_s: float = EVERY_S, every_steps: int = 0,
                 max_share: float = MAX_SHARE, run: dict[str, Any] | None = None,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.path = os.fspath(path)
        self.run = run
        self.every_s = float(every_s)
        self.every_steps = int(every_steps)
        self.max_share = float(max_share)
        self.clock = clock
        self.last: float | None = None
        self.cost = 0.0
        self.writes = 0

    def due(self, out: Any) -> bool:
        """Whether the run ``out`` (its last step just completed) is to be written now."""
        if self.last is None:
            return True
        if self.every_steps and out.steps % self.every_steps == 0:
            return True
        wait = max(self.every_s, self.cost / self.max_share)
        return self.clock() - self.last >= wait

    def step(self, out: Any) -> None:
        """After a completed step of ``out``: a checkpoint when one is due."""
        if self.due(out):
            self.write(out, running=True)

    def write(self, out: Any, running: bool = False) -> str:
        """Write ``out`` to :attr:`path`; ``running``: a checkpoint of a run that goes on
        (marked incomplete, the run itself unchanged)."""
        t = self.clock()
        if self.run is not None:
            out.run = self.run
        saved = (out.complete, out.stop_reason)
        if running:
            out.complete = False
            out.stop_reason = (f"running: checkpoint after step {out.steps} of {out.planned_steps} "
                               f"(T = {out.series['T'][-1]:.5g}); the run had not finished when "
                               f"this was written")
        try:
            with deferred_signals():  # a stop request waits for the file it would cut short
                path = out.to_hdf5(self.path)
        finally:
            out.complete, out.stop_reason = saved
        self.last = self.clock()
        self.cost = self.last - t
        self.writes += 1
        return path


def read_checkpoint(path: str | os.PathLike, run: dict[str, Any]) -> dict[str, Any]:
    """The incomplete run at ``path`` (:func:`~.result.load_series` with its ``state``) to be
    continued by a run with the parameters ``run``, or :class:`InputError` when there is
    none, it is complete, or it was written with other parameters (naming them)."""
    from .result import load_series  # h5py: not at the command line's start

    path = os.fspath(path)
    if not os.path.isfile(path):
        raise InputError(f"--resume: there is no checkpoint {path} to continue from (run without "
                         f"--resume first)")
    try:
        saved = load_series(path)
    except (OSError, KeyError, ValueError) as exc:
        raise InputError(f"--resume: {path} is not a transient result file ({exc})") from None
    if saved["complete"]:
        raise InputError(f"--resume: {path} holds a complete run; there is nothing to continue")
    if "state" not in saved:
        raise InputError(f"--resume: {path} holds no state to continue from (it ended before its "
                         f"first step)")
    differ = same_run(saved["run"], run)
    if differ:
        raise InputError(f"--resume: {path} was written by another run ({'; '.join(differ)}); "
                         f"continue it with the same scene and options")
    return saved


def same_run(saved: dict[str, Any], run: dict[str, Any]) -> list[str]:
    """The parameters in which ``run`` differs from ``saved`` (compared as JSON), as
    ``"key: saved -> now"`` texts (the scene by name only)."""
    def norm(v: Any) -> str:
        return json.dumps(v, sort_keys=True, default=str)

    # files written before these options existed ran the projection at fixed steps, without
    # the oil-balance cycles
    saved = {**{k: v for k, v in (("cavitation", "projection"), ("time_tol", None), ("mass_tol", None))
                if k in run},
             **saved}
    out = []
    for key in sorted(set(saved) | set(run)):
        a, b = saved.get(key), json.loads(norm(run.get(key)))
        if norm(a) != norm(b):
            out.append(f"{key} differs" if key == "scene" else f"{key}: {a!r} -> {b!r}")
    return out


def restore(out: Any, saved: dict[str, Any], snapshot_every: int) -> None:
    """Put the completed steps and the state of a checkpoint (:func:`read_checkpoint`) into
    the fresh result ``out`` of a continued run."""
    state = dict(saved["state"])
    if np.shape(state["P"]) != np.shape(out.steady.P):
        raise InputError(f"--resume: the checkpoint's grid {np.shape(state['P'])} is not this run's "
                         f"{np.shape(out.steady.P)}")
    out.series = {k: [int(x) if k in ("step", "cycles") else float(x) for x in v]
                  for k, v in saved["series"].items()}
    snaps = saved["snapshots"]
    out.snapshots = {int(n): {k: snaps[k][i] for k in ("P", "H", "rho", "theta") if k in snaps}
                     for i, n in enumerate(snaps["step"])}
    last = int(state["step"])
    # the last step is among the snapshots whether or not it is a kept one
    out._unkept = last if last % snapshot_every else None
    state["step"] = last
    out.state = state
