"""Starved thermal EHL line contact: the inlet meniscus that makes the contact carry the supply.

A finite oil layer ``hoil`` on the surfaces ahead of the contact (both surfaces together, at
the ambient density ``rho0``) starves the inlet: the gap fills completely only from the
meniscus ``X_m`` on, where the pressure starts to build up (Wedeven, Evans & Cameron 1971;
Chiu 1974; Hamrock & Dowson 1981, ch. 11: the film is set by the meniscus position). Ahead of
the meniscus the layer travels at the mean speed ``(u1 + u2)/2`` at zero pressure and
carries the mass flux ``rho0 hoil (u1 + u2)/2`` -- in Venner's units (``H = h R/b^2``,
density over ``rho0``) the flux ``Hoil = hoil R/b^2``.

Downstream of the meniscus the solution is the flooded-inlet TEHL solution on the box
``[X_m, xmax]``, and the meniscus is where that solution's mass flux equals the supply,
``F(X_m) = Hoil``. ``F`` is the flux of the generalised Reynolds equation the TEHL solve
satisfies (:func:`tehl_face_fluxes`: the Couette flux ``c rho H`` of the sheared, heated film
plus its pressure flow ``-a eps dP/dX``), measured at the first face of the box. It grows from
0 (meniscus at the Hertzian edge) to the flooded flux; a supply at or above the flooded flux
floods the contact.

The root is found in the log-distance from the Hertzian edge, ``s = ln(-1 - X_m)`` (``ln F``
is close to linear in it, and no step crosses the edge), from a seed meniscus (the isothermal
starved solver's, :func:`ehl_multigrid.starved.solve_starved_line`, on the same grid), by a
bracket search and the Illinois variant of regula falsi (Dowell & Jarratt 1971), until
``|F/Hoil - 1|`` is below the tolerance.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.starved.discrete import face_fluxes

#: farthest meniscus the search goes to (the TEHL box limit, :class:`~thermal.tehl.options.TEHLOptions`)
FAR_MENISCUS = -1000.0
#: first step of the bracket search in ``ln(-1 - X_m)`` (a 10 % change of the distance from
#: the Hertzian edge); doubled at each step
FIRST_STEP = 0.1
#: most TEHL box solves one search makes
MAX_SOLVES = 40

HINT = ("the supply may be too small for the grid near the Hertzian edge: more points, or a "
        "larger [supply] hoil")


def tehl_face_fluxes(level: Any, P: np.ndarray, H0: float) -> np.ndarray:
    """Mass flux (Venner units) through every face of a :class:`~thermal.tehl.hierarchy.FactorLevel`
    whose flow and Couette factors are set: ``Q_{i+1/2} - a eps_{i+1/2} (P_{i+1} - P_i)/h`` with
    the upwind face value ``Q`` of ``c rho H`` -- the fluxes whose differences are the level's
    discrete generalised Reynolds operator (the core's scheme written in flux form,
    :func:`ehl_multigrid.starved.discrete.face_fluxes` with a full film)."""
    st = level.state(P, H0)
    q = st.rho * st.H  # rho carries the Couette factor c (FactorLevel.state)
    return face_fluxes(np.asarray(P, dtype=float), np.ones(P.shape[0]), q, st.eps, level.h, level.order, False,
                       level.face)


def flux_summary(F: np.ndarray, P: np.ndarray) -> tuple[float, float]:
    """``(inlet flux, imbalance)``: the flux through the first face and the largest relative
    deviation from it over the faces up to the pressure maximum (the pressurised inlet zone,
    where the discrete equation holds as an equality)."""
    F0 = float(F[0])
    k = min(int(np.argmax(P)), F.shape[0] - 1)
    dev = float(np.max(np.abs(F[: k + 1] - F0)) / abs(F0)) if F0 != 0.0 else math.inf
    return F0, dev


@dataclass
class MeniscusSearch:
    """Outcome of :func:`find_meniscus`: the meniscus ``x``, the box solve there, its flux
    ``F``, the supply mismatch ``|F/Hoil - 1|`` and every box solve made (``history``)."""

    x: float
    result: Any
    flux: float
    mismatch: float
    history: list[dict[str, Any]] = field(default_factory=list)


def find_meniscus(solve_box: Callable[[float], Any], flux_of: Callable[[Any], float], hoil: float,
                  seed: float, tol: float, max_solves: int = MAX_SOLVES) -> MeniscusSearch:
    """The meniscus ``X_m`` whose box solve carries the supply ``hoil`` (Venner units) to within
    ``tol`` (relative).

    ``solve_box(X_m)`` solves the flooded-inlet contact on ``[X_m, xmax]`` (raises
    :class:`ConvergenceError` when it fails); ``flux_of(result)`` its mass flux; ``seed`` a
    meniscus near the root. Raises :class:`ConvergenceError` when no bracket is found or the
    search does not reach ``tol`` (the best mismatch found is then named) within ``max_solves``.
    """
    history: list[dict[str, Any]] = []
    cache: dict[float, tuple[float, Any]] = {}
    s_max = math.log(-1.0 - FAR_MENISCUS)
    target = math.log(hoil)

    def g(s: float) -> float:
        if s not in cache:
            if len(cache) >= max_solves:
                raise ConvergenceError(f"meniscus search: {max_solves} box solves did not bring the flux within "
                                       f"{tol:g} of the supply (best mismatch {_best()[2]:.3g})", None, HINT)
            x = -1.0 - math.exp(s)
            try:
                r = solve_box(x)
            except ConvergenceError as exc:
                history.append({"meniscus_x": x, "flux": math.nan, "status": str(exc).splitlines()[0][:160]})
                raise ConvergenceError(f"meniscus search: the TEHL solve with the inlet at X_m = {x:.6g} did not "
                                       f"converge ({str(exc).splitlines()[0][:160]})", exc.report, HINT) from None
            F = float(flux_of(r))
            history.append({"meniscus_x": x, "flux": F, "status": "converged"})
            if not (math.isfinite(F) and F > 0.0):
                raise ConvergenceError(f"meniscus search: the box solve at X_m = {x:.6g} carries a flux of {F!r}",
                                       None, HINT)
            cache[s] = (math.log(F) - target, r)
        return cache[s][0]

    def _best() -> tuple[float, Any, float]:
        s = min(cache, key=lambda k: abs(cache[k][0]))
        return s, cache[s][1], abs(math.expm1(cache[s][0]))

    def done(s: float) -> MeniscusSearch:
        gs, r = cache[s]
        return MeniscusSearch(-1.0 - math.exp(s), r, float(flux_of(r)), abs(math.expm1(gs)), history)

    tol_g = math.log1p(tol)
    s0 = math.log(max(-1.0 - seed, 1e-6))
    g0 = g(s0)
    if abs(g0) <= tol_g:
        return done(s0)
    # too much flux: the meniscus moves towards the edge (s down), too little: away from it
    direction = -1.0 if g0 > 0.0 else 1.0
    step = FIRST_STEP
    sa, ga = s0, g0
    while True:
        sb = min(sa + direction * step, s_max)
        gb = g(sb)
        if abs(gb) <= tol_g:
            return done(sb)
        if gb * ga < 0.0:
            break
        if sb >= s_max:
            raise ConvergenceError(f"meniscus search: even a meniscus at X_m = {FAR_MENISCUS:g} carries less than "
                                   f"the supply (flux {math.exp(gb + target):.4g} < Hoil {hoil:.4g})", None, HINT)
        sa, ga = sb, gb
        step *= 2.0
    # Illinois regula falsi on the bracket [sa, sb]
    while True:
        sc = (sa * gb - sb * ga) / (gb - ga)
        gc = g(sc)
        if abs(gc) <= tol_g:
            return done(sc)
        if gc * gb < 0.0:
            sa, ga = sb, gb
        else:
            ga *= 0.5  # the end kept twice: halved, so the next estimate moves past the root
        sb, gb = sc, gc
        if abs(sb - sa) < 1e-12:
            s, _, mis = _best()
            raise ConvergenceError(f"meniscus search: the bracket closed at X_m = {-1.0 - math.exp(s):.8g} with the "
                                   f"flux {mis:.3g} from the supply (tolerance {tol:g}): the flux is not smooth "
                                   f"at this resolution", None, HINT)
