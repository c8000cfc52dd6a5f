"""The adaptive robustness policy of the multilevel solvers, and the per-solve settings it
adapts.

A cycle is *accepted* when its iterate is finite with a positive central film, its load error
stays bounded and its residual has not grown beyond ``growth`` times the recent best; otherwise
the state before the cycle is restored, the next step of the *reject ladder* is applied and
the cycle is repeated (at most ``max_retries`` times). When the finest-grid residual falls by
less than a factor ``stall_factor`` over ``stall_window`` cycles the next step of the *stall
ladder* is applied. The steps are

* ``"halve"``: halve both under-relaxations and the film-constant gain (down to floors);
* ``"W"``: switch V or F cycles to W cycles (coarse grids visited more often);
* ``"switch"``: widen the Jacobi-distributive zone (the contact's own rule,
  ``hierarchy.raise_switch``);
* ``"alternate"``: relax X and Y lines alternately on every grid (point contacts,
  ``hierarchy.alternate_all``; nothing elsewhere);
* ``"fail"``: give up (the driver reports a stall).

The same mechanism serves every contact; the contacts differ only in the
:class:`PolicyParameters` measured for them. After an accepted cycle the under-relaxations
recover by ``recover`` per cycle up to their option values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .options import MultigridOptions

STEPS = ("halve", "W", "switch", "alternate", "fail")


@dataclass(frozen=True)
class PolicyParameters:
    """Thresholds and ladders of :class:`RobustnessPolicy` for one contact.

    growth, growth_window : reject a cycle whose residual exceeds ``growth`` times the smallest
        of the last ``growth_window`` accepted residuals on that grid (None: all of them).
    residual_cap : reject a cycle whose relative residual is above this (and above tol).
    quiet_below : under the residual rule (no ``film_tol``), a cycle whose residual is below
        this is accepted whatever its growth, and a stall below it ends the solve
        (``residual_floor``) instead of stepping down the stall ladder: there the residual
        wanders by factors of 3-5 from cycle to cycle while the films barely move, which is
        no divergence, and a stall step only stirs the iterate (0: off). A film-stopped solve
        whose residual sits below it while its films jitter above ``film_tol`` ends there too
        (``Multigrid.films_at_floor``).
    load_cap, load_factor : reject when ``|load error| > max(load_cap, load_factor |previous|)``.
    first_load_error : the "previous" load error of a grid's first cycle.
    max_retries : repeated attempts of one cycle before the solve is declared diverged.
    stall_window, stall_factor : stall when ``r[-1] > stall_factor r[-stall_window]``.
    reject_ladder, stall_ladder : groups of steps applied in turn (cyclic when ``cyclic``).
    shared_ladder : one step counter for rejections and stalls.
    floors : lowest ``(omega, omega_jd, h00_gain)`` that ``"halve"`` reaches.
    recover : factor by which omega and the gain grow back after an accepted cycle.
    """

    growth: float = 20.0
    growth_window: int | None = 4
    residual_cap: float = 0.5
    quiet_below: float = 0.0
    load_cap: float = 0.1
    load_factor: float = 3.0
    first_load_error: float = 0.05
    max_retries: int = 7
    stall_window: int = 8
    stall_factor: float = 0.9
    reject_ladder: tuple[tuple[str, ...], ...] = (("halve",),)
    stall_ladder: tuple[tuple[str, ...], ...] = (("W",), ("switch",), ("fail",))
    cyclic_reject: bool = True
    cyclic_stall: bool = False
    shared_ladder: bool = False
    floors: tuple[float, float, float] = (0.0, 0.0, 0.0)
    recover: float = 1.25


@dataclass
class Settings:
    """What a solve may change while it runs (the options stay as given)."""

    cycle: str
    omega: float
    omega_jd: float
    h00_gain: float
    switch: float
    switch_h: float = 0.0
    defaults: tuple[float, float, float] = field(default=(math.nan,) * 3)

    @classmethod
    def start(cls, options: MultigridOptions, h00_gain: float, switch: float,
              switch_h: float = 0.0) -> Settings:
        return cls(options.cycle, options.omega, options.omega_jd, h00_gain, switch, switch_h,
                   (options.omega, options.omega_jd, h00_gain))


#: what :meth:`RobustnessPolicy.on_reject` says when adaptation is off
NOTHING_CHANGED = "adaptation disabled, nothing changed"


class RobustnessPolicy:
    """Decides whether a cycle is accepted and what to change when it is not (see module)."""

    def __init__(self, params: PolicyParameters, adapt: bool = True) -> None:
        self.params = params
        self.adapt = adapt
        self._reject_step = 0
        self._stall_step = 0
        self.stall_from = 0

    # -- verdicts -------------------------------------------------------------------------
    def accept(self, ok: bool, residual: float, load_error: float, recent: list[float],
               previous_load_error: float | None, tol: float) -> bool:
        p = self.params
        if not (ok and math.isfinite(residual) and math.isfinite(load_error)):
            return False
        prev = p.first_load_error if previous_load_error is None else abs(previous_load_error)
        if abs(load_error) > max(p.load_cap, p.load_factor * prev):
            return False
        if residual < tol:
            return True
        window = recent if p.growth_window is None else recent[-p.growth_window:]
        before = min(window) if window else math.inf
        return residual < p.growth * before and residual < p.residual_cap

    def stalled(self, residuals: list[float], tol: float) -> bool:
        p = self.params
        r = residuals[self.stall_from:]
        return len(r) >= p.stall_window and r[-1] > p.stall_factor * r[-p.stall_window] and r[-1] > tol

    # -- actions --------------------------------------------------------------------------
    def recover(self, s: Settings) -> None:
        f = self.params.recover
        if f != 1.0:
            s.omega = min(s.defaults[0], f * s.omega)
            s.omega_jd = min(s.defaults[1], f * s.omega_jd)
            s.h00_gain = min(s.defaults[2], f * s.h00_gain)

    def on_reject(self, s: Settings, hierarchy) -> str:
        """Apply the next reject step; return what changed."""
        p = self.params
        if p.shared_ladder:
            return self._next(s, hierarchy, "stall")
        return self._next(s, hierarchy, "reject")

    def on_stall(self, s: Settings, hierarchy, n_residuals: int) -> str | None:
        """Apply the next stall step; None means the ladder is exhausted (give up)."""
        self.stall_from = n_residuals
        msg = self._next(s, hierarchy, "stall")
        return None if msg == "fail" else msg

    def _next(self, s: Settings, hierarchy, which: str) -> str:
        p = self.params
        if not self.adapt:
            return NOTHING_CHANGED
        ladder = p.reject_ladder if which == "reject" else p.stall_ladder
        cyclic = p.cyclic_reject if which == "reject" else p.cyclic_stall
        for _ in range(len(ladder)):
            i = self._reject_step if which == "reject" else self._stall_step
            if i >= len(ladder):
                if not cyclic:
                    return "fail"
                i = 0
            group = ladder[i]
            if which == "reject":
                self._reject_step = i + 1
            else:
                self._stall_step = i + 1
            msg = self._apply(group, s, hierarchy)
            if msg:
                return msg
        return "fail"

    def _apply(self, group: tuple[str, ...], s: Settings, hierarchy) -> str:
        done = []
        for step in group:
            if step == "fail":
                return "fail"
            if step == "halve":
                f0, f1, f2 = self.params.floors
                s.omega, s.omega_jd = max(0.5 * s.omega, f0), max(0.5 * s.omega_jd, f1)
                s.h00_gain = max(0.5 * s.h00_gain, f2)
                done.append(f"omega = {s.omega:.3g}, omega_jd = {s.omega_jd:.3g}, "
                            f"h00_gain = {s.h00_gain:.3g}")
            elif step == "W" and s.cycle in ("V", "F"):
                done.append(f"{s.cycle} -> W cycles")
                s.cycle = "W"
            elif step == "alternate":
                msg = getattr(hierarchy, "alternate_all", lambda _s: "")(s)
                if msg:
                    done.append(msg)
            elif step == "switch":
                msg = hierarchy.raise_switch(s)
                if msg:
                    done.append(msg)
        return ", ".join(done)
