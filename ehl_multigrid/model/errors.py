"""Error types shared by every layer.

Bad input raises :class:`InputError` naming the field, the value, the units and the allowed
range; a numerical failure raises :class:`ConvergenceError` carrying the solver's report.

A value that is possible but implausible for a real contact (a ball radius of 10 m: millimetres
typed as metres) is warned about with a :class:`PlausibilityWarning` (:func:`warn_implausible`).
Strict mode turns these warnings into :class:`InputError`: the ``EHL_STRICT=1`` environment
variable, ``ehl --strict``, :func:`strict_plausibility`, or any ``warnings`` filter that makes
:class:`PlausibilityWarning` an error (``warnings.simplefilter("error", PlausibilityWarning)``).
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

#: Environment variable that turns plausibility warnings into input errors ("1", "true", "yes").
STRICT_ENV = "EHL_STRICT"


class InputError(ValueError):
    """A value outside its allowed range, an unknown key, or an unknown preset."""


class PlausibilityWarning(UserWarning):
    """A value inside its allowed range but outside what real contacts (ball and roller
    bearings, gears, cams, tribometers) have, usually a unit mistake; the message names the
    field, the value, the plausible range and the probable mistake."""


class ModelRangeWarning(UserWarning):
    """A contact the model used describes only as an extrapolation (a film of a few molecular
    layers, pressures beyond those the viscosity laws were measured at, an isothermal film of a
    contact whose heat changes it by more than the target): the answer is the model's, which the
    contact may not follow. Not a unit mistake, so ``--strict`` does not refuse it; the message
    names the quantity, its value and why."""


def strict_from_environment() -> bool:
    """Whether ``EHL_STRICT`` asks for strict plausibility (any value but "", 0, false, no, off)."""
    return os.environ.get(STRICT_ENV, "").strip().lower() not in ("", "0", "false", "no", "off")


def warn_implausible(message: str, stacklevel: int = 2) -> None:
    """Warn with a :class:`PlausibilityWarning`, or raise :class:`InputError` in strict mode.

    Strict mode: ``EHL_STRICT`` set (:func:`strict_from_environment`) or a ``warnings`` filter
    turning :class:`PlausibilityWarning` into an error (:func:`strict_plausibility`).
    """
    refused = f"{message} [refused: strict plausibility checks (ehl --strict or {STRICT_ENV}=1)]"
    if strict_from_environment():
        raise InputError(refused)
    try:
        warnings.warn(message, PlausibilityWarning, stacklevel=stacklevel + 1)
    except PlausibilityWarning:
        raise InputError(refused) from None


@contextmanager
def strict_plausibility(enabled: bool = True) -> Iterator[None]:
    """Within the block, implausible values raise :class:`InputError` (``enabled``) instead of
    warning; the previous warning filters are restored on exit."""
    with warnings.catch_warnings():
        if enabled:
            warnings.simplefilter("error", PlausibilityWarning)
        yield


class ConvergenceError(RuntimeError):
    """A solver diverged, stalled or produced NaN.

    Attributes
    ----------
    report : object
        The solver's convergence report at the time of failure (may be ``None``).
    hint : str
        What to try (more levels, W cycles, smaller H0 factor, longer inlet ...).
    """

    def __init__(self, message: str, report: Any = None, hint: str = "") -> None:
        full = message if not hint else f"{message}\n  what to try: {hint}"
        super().__init__(full)
        self.report = report
        self.hint = hint


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value)


def require_range(
    field: str,
    value: Any,
    lo: float = -math.inf,
    hi: float = math.inf,
    units: str = "-",
    lo_open: bool = False,
    hi_open: bool = False,
) -> float:
    """Return ``float(value)`` or raise :class:`InputError` naming field, value, units and range."""
    lb = "(" if lo_open else "["
    rb = ")" if hi_open else "]"
    allowed = f"{lb}{_fmt(lo)}, {_fmt(hi)}{rb}"
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        try:
            import numpy as np

            if isinstance(value, np.generic) and np.isreal(value):
                value = float(value)
            else:
                raise TypeError
        except TypeError:
            raise InputError(
                f"{field} = {_fmt(value)} is not a number; expected a number in {allowed}"
                + ("" if units in ("-", "") else f" {units}")
            ) from None
    v = float(value)
    bad = (
        math.isnan(v)
        or (v <= lo if lo_open else v < lo)
        or (v >= hi if hi_open else v > hi)
    )
    if bad:
        if units in ("-", ""):  # dimensionless: no unit to repeat
            raise InputError(f"{field} = {_fmt(v)} is outside the allowed range {allowed} (dimensionless)")
        raise InputError(f"{field} = {_fmt(v)} {units} is outside the allowed range {allowed} {units}")
    return v


def require_positive(field: str, value: Any, units: str = "-", allow_inf: bool = False) -> float:
    """Strictly positive, finite unless ``allow_inf``."""
    hi = math.inf
    return require_range(field, value, 0.0, hi, units, lo_open=True, hi_open=not allow_inf)


#: The slide-to-roll ratio's definition, for messages.
SLIP_DEFINITION = "S = 2(u1-u2)/(u1+u2): 0 pure rolling, 2 pure sliding (thesis 100 % = 1)"


def require_slip(field: str, value: Any) -> float:
    """A slide-to-roll ratio in [-2, 2] (|S| = 2: one surface at rest; beyond, the surfaces
    move in opposite directions, which the package's solvers do not take), or
    :class:`InputError` naming field, value, range and the definition of S."""
    try:
        return require_range(field, value, -2.0, 2.0, "-")
    except InputError as exc:
        raise InputError(f"{exc} ({SLIP_DEFINITION})") from None


def require_choice(field: str, value: Any, choices: list[str] | tuple[str, ...]) -> str:
    if value not in choices:
        raise InputError(f"{field} = {value!r} is not one of the allowed values {list(choices)}")
    return value


def reject_unknown_keys(section: str, given: dict, allowed: set[str] | list[str]) -> None:
    unknown = sorted(set(given) - set(allowed))
    if unknown:
        raise InputError(
            f"unknown key(s) {unknown} in [{section}]; allowed keys are {sorted(allowed)}"
        )


class Terminated(BaseException):
    """SIGTERM, turned into an exception by the command line so that ``finally`` blocks run
    (sweep workers are stopped, partial results are written and marked incomplete)."""


def signal_cause(exc: BaseException) -> BaseException | None:
    """The Ctrl-C or SIGTERM exception ``exc`` is, or the one behind a chain of ``SystemError``,
    else None. A signal handler that raises while compiled code calls back into Python reaches
    the caller as a ``SystemError`` caused by it (numba's dispatcher does this)."""
    seen: set[int] = set()
    e: BaseException | None = exc
    while e is not None and id(e) not in seen:
        if isinstance(e, (KeyboardInterrupt, Terminated)):
            return e
        if not isinstance(e, SystemError):
            return None
        seen.add(id(e))
        e = e.__cause__ or e.__context__
    return None
