"""Mass-conservation gate of the starved solvers: a result that does not conserve mass failed.

A starved (Elrod-Adams) solve is judged by its iteration (residual and load error) and, for
the film, by the mass balance that defines it: the supplied layer is all the oil the contact
gets, so the boundary flows must balance (the discrete sum of the residuals of the flux-form
Reynolds equation, thesis (2.1)) and the central film cannot carry more than the supply
(``rho_c Hc <= Hoil``: downstream of the meniscus the pressure flow only takes oil away from
the centre line, sideways and back into the inlet; Chevalier et al. 1998, Damiens et al. 2004:
``rho_c Hc -> Hoil`` in the starved limit). A scaled residual can sit at its floor while one
cell at the meniscus creates oil (measured: a point contact at M = 741, L = 6.3 stopped with
the flooded film, ``rho_c Hc / Hoil = 3.5`` and an imbalance of 33 times the inflow), so
the gate looks at the balance itself and relabels such a result as failed, whatever its
iteration said.
"""

from __future__ import annotations

import math

from ..multigrid.result import STATUS, EHLResult

#: largest relative imbalance of the boundary flows (|in - out - side| / in, line: also the supply
#: mismatch |F - Hoil| / Hoil) a starved result may have: 1e-3 of the film in the starved limit,
#: far above what the solvers reach (docs/starvation.md, "The mass gate").
MASS_GATE = 1e-3
#: largest ``rho_c Hc / Hoil - 1``: the central film carrying more oil than the supplied layer
#: (an oil source at the meniscus). Converged solves give line 1 + 1e-8, point 0.996 ... 0.9999
#: at 257^2 (below 1 where the side flow takes oil away).
SUPPLY_GATE = 0.05

#: status of a result that fails the gate
MASS_STATUS = next(k for k, v in STATUS.items() if v == "mass_not_conserved")


def mass_violation(mass_balance_error: float, rho_c_hc_over_hoil: float = math.nan) -> str | None:
    """Why the balance fails the gate (the numbers and the allowed ranges), or ``None``.

    Parameters
    ----------
    mass_balance_error : relative imbalance of the result's boundary flows (NaN fails).
    rho_c_hc_over_hoil : central mass flow over the supplied layer (NaN: not checked).
    """
    why = []
    mb = float(mass_balance_error)
    if not mb <= MASS_GATE:
        why.append(f"mass-balance error {mb:.3g} of the inflow (allowed <= {MASS_GATE:g})")
    r = float(rho_c_hc_over_hoil)
    if math.isfinite(r) and r > 1.0 + SUPPLY_GATE:
        why.append(f"rho_c Hc / Hoil = {r:.3g}: the central film carries more oil than the supplied "
                   f"layer (allowed <= {1.0 + SUPPLY_GATE:g})")
    if not why:
        return None
    return "mass is not conserved: " + "; ".join(why)


def apply_mass_gate(sol: EHLResult, mass_balance_error: float,
                    rho_c_hc_over_hoil: float = math.nan) -> bool:
    """Give ``sol`` the failed status :data:`MASS_STATUS` when its balance fails the gate
    (:func:`mass_violation`), the message naming the numbers and the iteration's own verdict;
    ``scalars['converged']`` false. Returns True when the gate failed the result."""
    why = mass_violation(mass_balance_error, rho_c_hc_over_hoil)
    if why is None:
        return False
    before = f"{sol.status_name}: {sol.message}" if sol.message else sol.status_name
    sol.set_status(MASS_STATUS, f"{why}; not a solution of the starved contact (the iteration "
                                f"ended {before})")
    sol.scalars["converged"] = False
    sol.scalars["mass_gate"] = why
    sol.actions.append(f"mass gate: {why}")
    return True
