"""What the ``ehl`` commands read from the front door's answer.

Every ``ehl`` subcommand that solves a film calls :func:`ehl_multigrid.solve` and reads the
:class:`~ehl_multigrid.solution.Solution` it returns. The front door never raises for a
numerical failure; the command line keeps its exit codes by turning a solve that computed
nothing back into a :class:`~ehl_multigrid.model.errors.ConvergenceError` (exit 3, naming why)
and by writing what a failed solve computed, marked with its status.
"""

from __future__ import annotations

from typing import Any

from ..model.errors import ConvergenceError


def require_computed(sol: Any) -> Any:
    """The solver's own result of ``sol`` (``sol.raw``); a :class:`ConvergenceError` with the
    solution's message when the solver raised and nothing was computed (``raw`` is None)."""
    if sol.raw is None:
        raise ConvergenceError(sol.message)
    return sol.raw


def require_film(sol: Any, what: str) -> Any:
    """:func:`require_computed`, and a :class:`ConvergenceError` as well when the solve ended
    with no film (a failed start, a diverged iterate, a start no cycle touched: no ``fields``):
    writing its iterate would present zeros (a start guess) or a blown-up field as a film."""
    raw = require_computed(sol)
    if not sol.fields:
        hint = ("a larger --time-budget" if sol.status.label == "time_budget" else
                "check the inputs' magnitudes and units (load, speed, viscosity), or try --points or --cycle")
        raise ConvergenceError(f"{what} {sol.status.label}: {sol.message}", getattr(raw, "report", None),
                               f"{hint}; no film was computed, so nothing was written")
    return raw


def package_result(sol: Any) -> Any:
    """The HDF5 :class:`~ehl_multigrid.model.results.Result` of ``sol`` to write:
    ``sol.to_result()``, or for a solve that ended without fields the solver's result as it
    is, with the solution's outcome and error estimate
    (:func:`~ehl_multigrid.solution.record_solution`)."""
    from ..solution import record_solution

    if sol.fields:  # a film: the contract's own view
        return sol.to_result()
    return record_solution(sol.raw.to_result(sol.scene), sol)
