"""Time-dependent (transient) isothermal EHL: surface features passing through a line or a
point (circular, elliptic) contact.

Public API: line -- :func:`solve_transient_line`, the features :class:`Waviness`,
:class:`Bump`, :class:`Profile`, :class:`TransientResult`; point --
:func:`solve_transient_point`, the features :class:`Waviness2D` (any angle), :class:`Dent2D`,
:class:`HeightMap`, :class:`PointTransientResult`. Venner's dimensionless time
``T = t u_m / b`` (line, ``b`` the Hertzian half-width) or ``t u_m / a`` (point, ``a`` the Hertz
semi-axis along the rolling direction), ``u_m = (u1 + u2)/2``.
"""

from .accuracy import solve_with_time_error, time_error
from .features import Bump, Profile, Smooth, Waviness, feature_from_table, feature_speed
from .point_features import Dent2D, HeightMap, Smooth2D, Waviness2D, point_feature_from_table
from .point_solve import (
    PointTransientResult,
    max_point_time_step,
    point_mass_balance,
    point_transient_options,
    solve_transient_point,
)
from .result import TransientResult, load_series
from .solve import solve_transient_line, transient_options
from .stepping import max_time_step

__all__ = ["Bump", "Dent2D", "HeightMap", "PointTransientResult", "Profile", "Smooth", "Smooth2D",
           "TransientResult", "Waviness", "Waviness2D", "feature_from_table", "feature_speed",
           "load_series", "max_point_time_step", "max_time_step", "point_feature_from_table",
           "point_mass_balance", "point_transient_options", "solve_transient_line",
           "solve_transient_point", "solve_with_time_error", "time_error", "transient_options"]
