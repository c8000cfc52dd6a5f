"""Starved lubrication (thesis chapter 6: starved film Hcs, limiting inlet film (6.4)).

* Chevalier's reduction (6.1-6.4): ``Hcs = Hc r/(1 + r^delta)^(1/delta)``,
  ``r = Hoil/(Hc rho_bar(pmax))``; delta between 2 and 5, 3.5 by default. As the speed grows
  ``Hc -> inf`` and ``Hcs -> Hoil/rho_bar(pmax)``: the inlet oil, compressed to the density at
  pmax (isothermal Dowson-Higginson (2.7)), bounds the film.
* ``delta = "inlet"``: the exponent from the flooded inlet instead of a constant (the thesis's
  range 2-5, section 6.2.1). Circular contacts: ``delta = 2.37 - 0.95 log10(Hc_ff)`` with
  ``Hc_ff = hc Rx/a^2`` the flooded central film in Venner units (inlet length ~ Hc_ff^(2/3)),
  fitted to the package's mass-conserving starved point solver and held at its ends outside
  Hc_ff = 0.063-0.447 (docs/fits.md); in the spirit of Damiens et al. (2004), whose one inlet
  parameter collapses circular contacts. Elliptic contacts (theta = Rx/Ry in 0.25-4): the
  circular rule plus ``t (-0.202 + 2.152 log10(Hc_ff)) + 1.574 t^2``, ``t = log10(theta)``
  (wide contacts lose less oil sideways: a sharper knee); refused outside that range. Line
  contacts (no side flow): the starved line solver gives
  ``Hc/Hc_ff = min(r, 1)``, which (6.1) approaches at its largest admitted ``delta`` (20).
* ``hs_min``: the separation at which the asperities alone carry the load (gamma2 = 1). When the
  starved film cannot keep ``hs`` above it the contact is in boundary lubrication (Fig. 6.1).
* The limiting inlet film ``hoil = varsigma sigma`` below which all load is on the asperities
  at every speed (section 6.4), from the exact ``F_3/2`` and, beside it, from the thesis's
  approximation ``F_n(lam) ~ (-lam)^n`` (6.11).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from ehl_multigrid.model.errors import InputError, require_positive
from ehl_multigrid.model.starvation import (  # noqa: F401  (chapter 6's film lives in the model)
    DELTA_RANGE,
    INLET,
    INLET_DELTA_FIT,
    INLET_HC_RANGE,
    LINE_INLET_DELTA,
    chevalier_reduction,
    density_ratio_at,
    inlet_delta,
    log_starved_film,
    require_delta,
)

from .film import johnson_film
from .gw import asperity_pressure_coefficient, gw_f_inverse

ArrayLike = float | np.ndarray

def hss_min(load: float, area: float, n: float, beta: float, sigma_s: float, E_reduced: float) -> float:
    """Summit-plane separation [m] at which GW asperities carry the whole load:
    ``area pa(hss) = load`` with (4.18)."""
    c = asperity_pressure_coefficient(n, beta, sigma_s, E_reduced)
    target = require_positive("load", load, "N") / (require_positive("area", area, "m^2") * c)
    return sigma_s * float(gw_f_inverse(1.5, target))


@dataclass(frozen=True)
class LimitingFilm:
    """Limiting inlet film of section 6.4 (all load on the asperities for ``hoil < varsigma sigma``).

    ``F32`` is the value ``F_3/2(hss/sigma_s)`` must take (6.10); ``lam`` the corresponding
    ``hss/sigma_s``; ``t = hs/sigma``; ``varsigma = hf,r/sigma`` at that separation.
    ``varsigma_compressed = rho_bar(pmax) varsigma``: with Chevalier's formula the starved film
    tends to ``hoil/rho_bar``, so this is the inlet film below which the film model itself can
    never lift any load off the asperities.
    """

    pmax: float
    F32: float
    lam_exact: float
    lam_approx: float
    t_exact: float
    t_approx: float
    varsigma_exact: float
    varsigma_approx: float
    difference: float
    rho_bar: float
    varsigma_compressed: float

    def to_dict(self) -> dict:
        return asdict(self)


def limiting_inlet_film(
    pmax: float,
    *,
    n_beta_sigma_s: float = 0.05,
    psi: float = 1.0,
    hardness: float = 5e9,
    dd_over_sigma: float = 0.82,
    sigma_s_over_sigma: float = 0.7,
    contact: str = "point",
) -> LimitingFilm:
    """Section 6.4: varsigma from (6.7)-(6.14), exact and with the thesis's approximation.

    (6.7) writes (4.18) as ``pa = (4/3) H' (n beta sigma_s) psi F_3/2(hss/sigma_s)`` (with
    ``psi = (E'_GW/H') sqrt(sigma_s/beta)``, ``E'_GW = E'/2``); all load on the asperities means
    ``pa = mean Hertz pressure`` (point ``2/3 pmax``, line ``pi/4 pmax``). Defaults are the
    thesis's "standard values": ``n beta sigma_s = 0.05``, ``psi = 1``, ``H' = 5 GPa`` and the
    Whitehouse-Archard planes ``hs/sigma = 0.82 + 0.7 hss/sigma_s`` (6.12). Then
    ``varsigma = hf,r/sigma = t Phi(t) + phi(t)`` (6.13)-(6.14), ``t = hs/sigma``.
    The exact path inverts ``F_3/2``; the approximate one uses ``F_3/2(lam) ~ (-lam)^(3/2)``
    (6.11), which the thesis applies and which gives its 0.10 (1.93 GPa) and 0.46 (0.5 GPa).
    """
    pmax = require_positive("pmax", pmax, "Pa")
    if contact == "point":
        mean = 2.0 / 3.0 * pmax
    elif contact == "line":
        mean = math.pi / 4.0 * pmax
    else:
        raise InputError(f"contact = {contact!r} is not one of ['line', 'point']")
    coeff = 4.0 / 3.0 * require_positive("hardness", hardness, "Pa") * require_positive(
        "n_beta_sigma_s", n_beta_sigma_s, "-") * require_positive("psi", psi, "-")
    F = mean / coeff
    lam_e = float(gw_f_inverse(1.5, F))
    lam_a = -(F ** (2.0 / 3.0))
    t_e = dd_over_sigma + sigma_s_over_sigma * lam_e
    t_a = dd_over_sigma + sigma_s_over_sigma * lam_a
    v_e = float(johnson_film(t_e, 1.0))
    v_a = float(johnson_film(t_a, 1.0))
    rb = density_ratio_at(pmax)
    return LimitingFilm(pmax, F, lam_e, lam_a, t_e, t_a, v_e, v_a, v_e - v_a, rb, rb * v_e)


def limiting_inlet_film_for_roughness(
    load: float, area: float, pmax: float, E_reduced: float, Rq: float, sigma_s: float, dd: float, n: float, beta: float
) -> LimitingFilm:
    """varsigma for a given contact and roughness (no standard values): exact ``F_3/2``
    inversion of ``area pa(hss) = load`` beside the ``(-lam)^(3/2)`` approximation."""
    c = asperity_pressure_coefficient(n, beta, sigma_s, E_reduced)
    F = require_positive("load", load, "N") / (require_positive("area", area, "m^2") * c)
    lam_e = float(gw_f_inverse(1.5, F))
    lam_a = -(F ** (2.0 / 3.0))
    t_e = (dd + sigma_s * lam_e) / Rq
    t_a = (dd + sigma_s * lam_a) / Rq
    v_e = float(johnson_film(t_e, 1.0))
    v_a = float(johnson_film(t_a, 1.0))
    rb = density_ratio_at(pmax)
    return LimitingFilm(pmax, F, lam_e, lam_a, t_e, t_a, v_e, v_a, v_e - v_a, rb, rb * v_e)
