"""Time-dependent (transient) isothermal EHL: surface features passing through a line contact.

Public API: :func:`solve_transient_line`, the features :class:`Waviness` and :class:`Bump`,
:class:`TransientResult`. Venner's dimensionless time ``T = t u_m / b`` (line contact,
``u_m = (u1 + u2)/2``, ``b`` the Hertzian half-width).
"""

from .accuracy import solve_with_time_error, time_error
from .features import Bump, Profile, Smooth, Waviness, feature_from_table, feature_speed
from .result import TransientResult, load_series
from .solve import max_time_step, solve_transient_line, transient_options

__all__ = ["Bump", "Profile", "Smooth", "TransientResult", "Waviness", "feature_from_table", "feature_speed",
           "load_series", "max_time_step", "solve_transient_line", "solve_with_time_error",
           "time_error", "transient_options"]
