"""Dimensionless groups (Dowson-Higginson G, U, W; Moes M, L, thesis 2.1.4 and (2.23)) and
the film-scale conversions between Moes and Venner's dimensionless films.

``us`` is always the *sum* velocity u1 + u2. The Moes groups are built on
``U = eta0 us / (E' R)``, which equals Venner's 2U (U on the mean velocity).
"""

from __future__ import annotations

import math

import numpy as np

from .errors import require_positive, require_range

ArrayLike = float | np.ndarray


def dowson_higginson_line(w: float, us: float, eta0: float, alpha: float, E_reduced: float, R: float) -> tuple[float, float, float]:
    """Dowson-Higginson groups ``(G, U, W) = (alpha E', eta0 us/(E' R), w/(E' R))``.

    ``w`` is the load per unit length [N/m].
    """
    w = require_positive("w (load per length)", w, "N/m")
    us = require_positive("us", us, "m/s")
    eta0 = require_positive("eta0", eta0, "Pa s")
    alpha = require_range("alpha", alpha, 0.0, 1e-6, "1/Pa")
    E = require_positive("E_reduced", E_reduced, "Pa")
    R = require_positive("R", R, "m")
    return alpha * E, eta0 * us / (E * R), w / (E * R)


def moes_line(w: float, us: float, eta0: float, alpha: float, E_reduced: float, R: float) -> tuple[float, float]:
    """Moes line groups (2.1.4): ``M = W U^(-1/2)``, ``L = G U^(1/4)``."""
    G, U, W = dowson_higginson_line(w, us, eta0, alpha, E_reduced, R)
    return W / math.sqrt(U), G * U**0.25


def moes_point(load: float, us: float, eta0: float, alpha: float, E_reduced: float, Rx: float) -> tuple[float, float]:
    """Moes point groups (used with 2.23): ``M = P/(E' Rx^2) U^(-3/4)``, ``L = alpha E' U^(1/4)``,
    ``U = eta0 us / (E' Rx)``."""
    P = require_positive("load", load, "N")
    us = require_positive("us", us, "m/s")
    eta0 = require_positive("eta0", eta0, "Pa s")
    alpha = require_range("alpha", alpha, 0.0, 1e-6, "1/Pa")
    E = require_positive("E_reduced", E_reduced, "Pa")
    Rx = require_positive("Rx", Rx, "m")
    U = eta0 * us / (E * Rx)
    return P / (E * Rx * Rx) * U**-0.75, alpha * E * U**0.25


def moes_film_scale(us: float, eta0: float, E_reduced: float, R: float) -> float:
    """Length that turns a Moes film H into metres: ``h = H R sqrt(eta0 us / (E' R))`` [m].

    ``R`` is the reduced radius of a line contact or ``Rx`` of a point contact.
    """
    return R * math.sqrt(eta0 * us / (E_reduced * R))


def venner_line(M: ArrayLike, L: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
    """Venner line parameters ``lambda = 3 pi^2 / (8 M^2)``, ``alpha_bar = L sqrt(M / (2 pi))``."""
    M = np.asarray(M, dtype=float)
    L = np.asarray(L, dtype=float)
    lam = 3.0 * math.pi**2 / (8.0 * M**2)
    abar = L * np.sqrt(M / (2.0 * math.pi))
    return _scalar(lam), _scalar(abar)


def venner_point(M: ArrayLike, L: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
    """Venner circular-contact parameters ``lambda = (128 pi^3 / (3 M^4))^(1/3)``,
    ``alpha_bar = (L / pi) (3 M / 2)^(1/3)``."""
    M = np.asarray(M, dtype=float)
    L = np.asarray(L, dtype=float)
    lam = (128.0 * math.pi**3 / (3.0 * M**4)) ** (1.0 / 3.0)
    abar = L / math.pi * (1.5 * M) ** (1.0 / 3.0)
    return _scalar(lam), _scalar(abar)


def moes_from_venner_line(H_venner: ArrayLike, M: ArrayLike) -> ArrayLike:
    """``H_Moes = H_Venner 8 M / pi`` (line)."""
    return _scalar(np.asarray(H_venner) * 8.0 * np.asarray(M) / math.pi)


def venner_from_moes_line(H_moes: ArrayLike, M: ArrayLike) -> ArrayLike:
    return _scalar(np.asarray(H_moes) * math.pi / (8.0 * np.asarray(M)))


def venner_from_moes_point(H_moes: ArrayLike, M: ArrayLike) -> ArrayLike:
    """``H_Venner = H_Moes / (3 M / 2)^(2/3)`` (circular)."""
    return _scalar(np.asarray(H_moes) / (1.5 * np.asarray(M)) ** (2.0 / 3.0))


def _scalar(x: np.ndarray) -> ArrayLike:
    x = np.asarray(x)
    return float(x) if x.ndim == 0 else x
