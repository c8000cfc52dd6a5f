"""Extra cycles for the oil balance of a mass-conserving time step.

A step's tolerances bound the scaled residual of each node and the load error, not the sum of
the residuals over the grid, which is the oil the step gains (the domain mass error). With
the squeeze term the sum is stiff: a film-constant offset the load tolerance allows changes
``ct theta rho H`` over the whole contact (circular (20, 10), 129^2, a dent at S = 1, default
tolerances: 3e-4 of the inflow from an offset of 2e-7 of the film). Two to three more cycles
remove it (docs/transient.md).
"""

from __future__ import annotations

from typing import Any

from ..model.errors import InputError, require_range

#: default largest oil gained or lost by a mass-conserving step, relative to the inflow
MASS_TOL = 1e-6
#: the cycles stop asking when the balance fell by less than this factor over this many cycles
MASS_FLOOR_RATE, MASS_FLOOR_CYCLES = 0.5, 5


def require_mass_tol(mass_tol: float | None, cavitation: str = "mass-conserving") -> float | None:
    """``mass_tol`` checked: None (no criterion) or in ``[1e-12, 1]`` (oil per step over the
    inflow); with the projection (no oil balance) only None or the default."""
    if cavitation == "projection" and mass_tol is not None and mass_tol != MASS_TOL:
        raise InputError(f"mass_tol = {mass_tol!r} applies to cavitation = 'mass-conserving'; the "
                         f"projection P >= 0 has no oil balance to hold")
    return None if mass_tol is None else require_range("mass_tol", mass_tol, 1e-12, 1.0)


class OilBalanceCycles:
    """Mixin of the mass-conserving step hierarchies: :meth:`wants_cycles` (the driver's hook)
    asks for finest-grid cycles while the step's domain mass error exceeds :attr:`mass_tol`
    and still falls (by :data:`MASS_FLOOR_RATE` over :data:`MASS_FLOOR_CYCLES` cycles: near
    1e-6 the balance can rise for a cycle or two before it falls on); the cycle limit ends
    them with the step converged, its mass error recorded in the run's series."""

    mass_tol: float | None = MASS_TOL

    def step_mass_error(self) -> float:
        """The finest grid's oil gained in the step over the inflow."""
        raise NotImplementedError

    def wants_cycles(self, solver: Any) -> bool:
        if self.mass_tol is None:
            return False
        if getattr(self, "_mass_solver", None) is not solver:
            self._mass_solver, self._mass_trace = solver, []
        err = abs(self.step_mass_error())
        trace = self._mass_trace
        trace.append(err)
        if not err > self.mass_tol:  # within it, or NaN (nothing to balance)
            return False
        n = MASS_FLOOR_CYCLES
        return not (len(trace) > n and trace[-1] > MASS_FLOOR_RATE * trace[-1 - n])
