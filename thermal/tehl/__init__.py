"""Thermal elastohydrodynamic lubrication (TEHL): pressure, film and temperature solved
together with the generalised Reynolds equation (Yang & Wen 1990) and the Eyring law of the
thermal layer acting on the flow.

A TEHL film is solved through the front door :func:`ehl_multigrid.solve` (``physics=
"thermal"``, registered by :mod:`thermal.front`; docs/api.md); :func:`estimate_error` is the
error budget of a TEHL solution. The solvers behind the front door are internal -- importable
from here for the package itself, its tests and validation scripts, but not part of the public
API (``__all__``): :func:`solve_tehl_line` (line contacts; starved by the inlet meniscus when
the scene has a finite ``[supply] hoil``, :func:`solve_tehl_line_starved`),
:func:`tehl_traction_curve` (slips continuing from each other), :func:`isothermal_start`,
:func:`solve_tehl_point` (point contacts, flooded inlets) and :func:`solve_tehl_to_accuracy`
(solve, estimate, refine to an accuracy target).
"""

from ehl_multigrid.lazy import lazy_exports

#: public name -> submodule, loaded on first use (the command line registers 'ehl tehl' at every
#: start of 'ehl' and must not import the solver)
_LAZY = {
    "film_factors": "coefficients", "flux_integrals": "coefficients",
    "FactorLevel": "hierarchy", "FactorLineHierarchy": "hierarchy",
    "TEHLLineResult": "line", "TEHLOptions": "options",
    "isothermal_start": "line", "solve_tehl_line": "line", "tehl_traction_curve": "line",
    "solve_tehl_line_starved": "line", "find_meniscus": "starved", "tehl_face_fluxes": "starved",
    "TEHLPointResult": "point", "solve_tehl_point": "point",
    "TEHLErrorEstimate": "accuracy", "estimate_error": "accuracy", "solve_tehl_to_accuracy": "accuracy",
}

#: the solvers behind the front door: importable from here, not public
INTERNAL = ("isothermal_start", "solve_tehl_line", "tehl_traction_curve", "solve_tehl_line_starved",
            "solve_tehl_point", "solve_tehl_to_accuracy")

__all__ = [name for name in _LAZY if name not in INTERNAL]


__getattr__, __dir__ = lazy_exports(__name__, _LAZY, globals())
