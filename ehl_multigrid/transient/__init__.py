"""Time-dependent (transient) isothermal EHL: surface features passing through a line or a
point (circular, elliptic) contact.

A run is solved through the front door :func:`ehl_multigrid.solve` (``physics="transient"``,
the scene's ``[feature]``; docs/api.md). Public here: line -- the features :class:`Waviness`,
:class:`Bump`, :class:`Profile`, :class:`TransientResult`; point -- the features
:class:`Waviness2D` (any angle), :class:`Dent2D`, :class:`HeightMap`,
:class:`PointTransientResult`; the time error of two runs (:func:`time_error`,
:func:`adaptive_time_error`). The solvers behind the front door,
:func:`~.solve.solve_transient_line` and :func:`~.point_solve.solve_transient_point`, are
internal: importable from here for the package itself, its tests and validation scripts, but
not part of the public API (``__all__``). Venner's dimensionless time
``T = t u_m / b`` (line, ``b`` the Hertzian half-width) or ``t u_m / a`` (point, ``a`` the Hertz
semi-axis along the rolling direction), ``u_m = (u1 + u2)/2``.

Runs keep what they computed: a :class:`Checkpoint` writes the completed steps while a run
goes on and when it ends early (a failed step, an interrupt, a signal), marked
``complete = False``; :func:`read_checkpoint` reads such a file back for the ``resume``
option of the front door. Cavitation is the projection ``P >= 0`` (a flooded inlet only:
:func:`check_flooded_supply` refuses a scene whose oil supply starves the contact) or, with
``cavitation="mass-conserving"``, Elrod-Adams film content, which also takes a starved inlet
(``hoil``).
"""

from ..lazy import lazy_exports

#: public name -> submodule, loaded on first use (the command line registers 'ehl transient' at
#: every start of 'ehl' and must not import the solvers)
_LAZY = {
    "Checkpoint": "checkpoint", "read_checkpoint": "checkpoint",
    "check_flooded_supply": "supply",
    "time_error": "accuracy", "adaptive_time_error": "accuracy",
    "Bump": "features", "Profile": "features", "Smooth": "features", "Waviness": "features",
    "feature_speed": "features",
    "Dent2D": "features", "HeightMap": "features", "Smooth2D": "features",
    "Waviness2D": "features",
    "PointTransientResult": "result", "max_point_time_step": "point_solve",
    "point_mass_balance": "result", "point_transient_options": "point_solve",
    "solve_transient_point": "point_solve",
    "TransientResult": "result", "load_series": "result",
    "solve_transient_line": "solve", "transient_options": "solve",
    "max_time_step": "stepping",
}


__getattr__, __dir__ = lazy_exports(__name__, _LAZY, globals())

#: the solvers behind the front door: importable from here, not public
INTERNAL = ("solve_transient_line", "solve_transient_point")

__all__ = sorted(set(_LAZY) - set(INTERNAL))
