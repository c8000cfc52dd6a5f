"""Random-process predictions of summit statistics for isotropic Gaussian surfaces.

Continuous surface (Nayak 1971), from the profile spectral moments m0 = sigma^2,
m2 = <z_x^2>, m4 = <z_xx^2> and the bandwidth alpha = m0 m4 / m2^2:

* summit density ``n = m4 / (6 pi sqrt(3) m2)``;
* mean summit curvature ``kappa = (8/3) sqrt(m4/pi)`` with ``kappa = -(z_xx + z_yy)/2``;
* mean summit height ``dd = 4 sigma / sqrt(pi alpha)``;
* summit height std ``sigma_s = sigma sqrt(1 - 0.8968/alpha)``.

Discrete 9-point rule on a grid (what a measurement counts): the 9 heights of a 3 x 3
neighbourhood are jointly Gaussian with covariances ``R(distance)`` from the autocorrelation
function, so the probability that the centre exceeds its 8 neighbours, and the conditional
means of the 3-point curvature and the centre height, follow from that 9-dimensional normal
distribution alone. :func:`nine_point_prediction` evaluates them by Monte Carlo sampling of
it (no surface is generated). As the sampling interval goes to zero the discrete values tend
to Nayak's; at intervals beyond the correlation length the heights decorrelate and the
density tends to ``1/(9 dx dy)``, the thesis's warning that n, beta and sigma_s depend on the
sampling interval (4.3.2, 4.4.1).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ehl_multigrid.model.errors import InputError, require_positive

SIGMA_S_COEFF = 0.8968  # Nayak (1971): sigma_s^2 = sigma^2 (1 - 0.8968/alpha)


def nayak_continuous(m0: float, m2: float, m4: float) -> dict[str, float]:
    """Nayak's summit statistics of a continuous isotropic Gaussian surface (module docstring).

    Returns n [1/m^2], kappa_mean [1/m], beta = 1/kappa_mean [m], dd [m], sigma_s [m], alpha.
    """
    for name, v in (("m0", m0), ("m2", m2), ("m4", m4)):
        require_positive(name, v, "-")
    alpha = m0 * m4 / m2**2
    if alpha < 1.5:
        raise InputError(f"Nayak bandwidth alpha = {alpha:.4g} must be >= 1.5 for an isotropic surface")
    sigma = math.sqrt(m0)
    kappa = 8.0 / 3.0 * math.sqrt(m4 / math.pi)
    return {
        "n": m4 / (6.0 * math.pi * math.sqrt(3.0) * m2),
        "kappa_mean": kappa,
        "beta": 1.0 / kappa,
        "dd": 4.0 * sigma / math.sqrt(math.pi * alpha),
        "sigma_s": sigma * math.sqrt(1.0 - SIGMA_S_COEFF / alpha),
        "alpha": alpha,
    }


def gaussian_acf(corr_length: float) -> Callable[[np.ndarray], np.ndarray]:
    """Normalised Gaussian autocorrelation ``exp(-(r/l)^2)``."""
    ell = require_positive("corr_length", corr_length, "m")
    return lambda r: np.exp(-((np.asarray(r) / ell) ** 2))


def nine_point_prediction(
    acf: Callable[[np.ndarray], np.ndarray],
    Rq: float,
    dx: float,
    dy: float | None = None,
    n_samples: int = 2_000_000,
    seed: int | None = 0,
    batch: int = 500_000,
) -> dict[str, float]:
    """Expected 9-point summit statistics of a Gaussian surface sampled at (dx, dy).

    ``acf(r)`` is the normalised autocorrelation (1 at r = 0); ``Rq`` scales heights.
    Returns n [1/m^2], kappa_mean [1/m], beta [m], sigma_s [m], dd [m], the summit probability
    per grid point, and Monte Carlo standard errors (``*_se``).
    """
    dxm = require_positive("dx", dx, "m")
    dym = dxm if dy is None else require_positive("dy", dy, "m")
    rq = require_positive("Rq", Rq, "m")
    # points of the 3x3 stencil, centre first: (iy, ix)
    offs = [(0, 0), (0, 1), (0, -1), (1, 0), (-1, 0), (1, 1), (1, -1), (-1, 1), (-1, -1)]
    py = np.array([o[0] * dym for o in offs])
    px = np.array([o[1] * dxm for o in offs])
    dist = np.hypot(py[:, None] - py[None, :], px[:, None] - px[None, :])
    C = np.asarray(acf(dist), dtype=float)
    w, V = np.linalg.eigh(C)
    if w.min() < -1e-8 * w.max():
        raise InputError("the autocorrelation gives a covariance matrix that is not positive semi-definite")
    L = V * np.sqrt(np.clip(w, 0.0, None))
    rng = np.random.default_rng(seed)
    count = 0
    s_k = s_k2 = s_h = s_h2 = 0.0
    done = 0
    while done < n_samples:
        m = min(batch, n_samples - done)
        Z = rng.standard_normal((m, 9)) @ L.T
        c = Z[:, 0]
        summit = np.all(c[:, None] > Z[:, 1:], axis=1)
        Zs = Z[summit]
        kap = -0.5 * ((Zs[:, 1] + Zs[:, 2] - 2 * Zs[:, 0]) / dxm**2 + (Zs[:, 3] + Zs[:, 4] - 2 * Zs[:, 0]) / dym**2)
        h = Zs[:, 0]
        count += Zs.shape[0]
        s_k += kap.sum()
        s_k2 += (kap**2).sum()
        s_h += h.sum()
        s_h2 += (h**2).sum()
        done += m
    if count < 2:
        raise InputError("too few summits sampled; raise n_samples")
    p = count / n_samples
    km = s_k / count
    kv = s_k2 / count - km**2
    hm = s_h / count
    hv = s_h2 / count - hm**2
    return {
        "n": p / (dxm * dym),
        "n_se": math.sqrt(p * (1 - p) / n_samples) / (dxm * dym),
        "p_summit": p,
        "kappa_mean": km * rq,
        "kappa_mean_se": math.sqrt(kv / count) * rq,
        "beta": 1.0 / (km * rq),
        "dd": hm * rq,
        "dd_se": math.sqrt(hv / count) * rq,
        "sigma_s": math.sqrt(hv) * rq,
        "n_summits_sampled": count,
    }
