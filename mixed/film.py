"""Film thickness and separation of a rough contact (thesis 4.2.2, 2.4.3; Johnson's film
definition (4.20), planes (4.28)).

Planes (Fig. 2.6): ``hs`` is the separation between the mean plane of the surface heights and
the smooth counter-surface, ``hss = hs - dd`` (4.28) the separation from the mean plane of the
summits, ``dd`` the mean summit height above the mean plane.

Johnson's film (4.20): ``hf,r = int_-inf^hs (hs - z) phi(z) dz`` with a Gaussian height density
of standard deviation ``sigma = Rq``; in closed form ``hf,r/sigma = t Phi(t) + phi(t) = F_1(-t)``,
``t = hs/sigma`` (the thesis's (6.13)-(6.14) are its two branches). ``hf,r > 0`` for every
``hs``, which is what lets the model run at loads where ``hs < 0``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special

from ehl_multigrid.model.errors import InputError, require_positive
from ehl_multigrid.model.scene import Roughness

from .gw import gw_f1, gw_log_f

ArrayLike = float | np.ndarray


def johnson_film(hs: ArrayLike, sigma: float) -> ArrayLike:
    """Film thickness (4.20) ``hf,r = sigma F_1(-hs/sigma)`` [m] for separation ``hs`` [m].

    Tends to ``hs`` for ``hs >> sigma`` and to ``sigma phi(t)/t^2`` (positive) for ``hs << -sigma``.
    """
    sigma = require_positive("sigma (Rq)", sigma, "m")
    out = sigma * np.asarray(gw_f1(-np.asarray(hs, dtype=float) / sigma))
    return float(out) if out.ndim == 0 else out


def log_johnson_film_ratio(t: np.ndarray) -> np.ndarray:
    """``ln(hf,r/sigma)`` as a function of ``t = hs/sigma``; finite even where ``hf,r`` underflows."""
    t = np.asarray(t, dtype=float)
    direct = np.asarray(gw_f1(-t), dtype=float)
    with np.errstate(divide="ignore"):
        out = np.log(direct)
    far = t < -30.0
    if np.any(far):
        out = np.where(far, np.asarray(gw_log_f(1.0, np.where(far, -t, 31.0))), out)
    return out


def separation_from_film(hfr: ArrayLike, sigma: float) -> ArrayLike:
    """Inverse of (4.20): the separation ``hs`` [m] whose Johnson film is ``hfr`` [m] (> 0).

    Newton on ``ln(hf,r/sigma)`` in ``t = hs/sigma`` (``d(hf,r/sigma)/dt = Phi(t)``, so the
    function is increasing and concave in log form) inside a maintained bracket; converges to
    rounding in a handful of steps for any ``hfr`` from 1e-300 sigma to 1e6 sigma.
    """
    sigma = require_positive("sigma (Rq)", sigma, "m")
    h = np.asarray(hfr, dtype=float)
    if np.any(~(h > 0)) or np.any(~np.isfinite(h)):
        raise InputError(f"film thickness hf,r = {h[~(h > 0) | ~np.isfinite(h)].ravel()[:3]} m must be finite and > 0")
    return _separation_from_log_film(np.log(h / sigma), sigma, h.shape)


def separation_from_log_film(log_hfr_over_sigma: np.ndarray, sigma: float) -> np.ndarray:
    """As :func:`separation_from_film` with ``ln(hf,r/sigma)`` given (no underflow)."""
    lg = np.asarray(log_hfr_over_sigma, dtype=float)
    return _separation_from_log_film(lg, sigma, lg.shape)


def _separation_from_log_film(target: np.ndarray, sigma: float, shape: tuple[int, ...]) -> ArrayLike:
    y = np.ravel(target).astype(float)
    # bracket: for y >= 0, t <= hf/sigma <= t + phi(0) (t >= 0); for y < 0, hf/sigma < phi(t)/t^2
    # gives |t| < sqrt(-2 y), and hf/sigma(1) > 1 bounds t above.
    e = np.exp(np.minimum(y, 700.0))
    root = np.sqrt(np.maximum(-2.0 * y, 0.0))
    lo = np.where(y >= 0.0, e - 1.0, -root - 3.0)
    hi = np.where(y >= 0.0, e + 1e-9, 1.0)
    t = np.where(y >= 0.0, e, -root)
    for _ in range(100):
        g = log_johnson_film_ratio(t) - y
        lo = np.where(g < 0.0, t, lo)
        hi = np.where(g > 0.0, t, hi)
        # d ln(hf/sigma)/dt = Phi(t) / (hf/sigma)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            dlog = np.exp(np.log(0.5 * special.erfc(-t / math.sqrt(2.0))) - log_johnson_film_ratio(t))
            step = g / dlog
        tn = t - step
        bad = ~np.isfinite(tn) | (tn <= lo) | (tn >= hi)
        tn = np.where(bad, 0.5 * (lo + hi), tn)
        done = np.abs(tn - t) <= 4e-16 * np.maximum(1.0, np.abs(t))
        t = tn
        if np.all(done):
            break
    out = sigma * t
    return float(out[0]) if shape == () else out.reshape(shape)


def equivalent_surface(r1: Roughness, r2: Roughness) -> Roughness:
    """Equivalent single rough surface against a smooth one (Greenwood & Tripp).

    ``Rq = sqrt(Rq1^2 + Rq2^2)``, ``sigma_s = sqrt(sigma_s1^2 + sigma_s2^2)`` (the thesis's
    combined roughness, footnote of Table 4.3), ``dd = sqrt(dd1^2 + dd2^2)`` (consistent with the
    Whitehouse-Archard proportions when each surface follows them). Summit density and radius are
    taken from the rougher surface (larger ``sigma_s``), as the thesis does for disc 1 (ball
    sigma_s = 0.0225 um, disc parameters otherwise); ``fc`` from the rougher surface; hardness the
    lower of the two (the softer body yields first).
    """
    for tag, r in (("surface 1", r1), ("surface 2", r2)):
        if not isinstance(r, Roughness):
            raise InputError(f"{tag} must be a Roughness, got {type(r).__name__}")
    rough, _ = (r1, r2) if r1.sigma_s >= r2.sigma_s else (r2, r1)
    Ra = math.nan
    if math.isfinite(r1.Ra) and math.isfinite(r2.Ra):
        Ra = math.hypot(r1.Ra, r2.Ra)
    return Roughness(
        Rq=math.hypot(r1.Rq, r2.Rq),
        sigma_s=math.hypot(r1.sigma_s, r2.sigma_s),
        dd=math.copysign(math.hypot(r1.dd, r2.dd), r1.dd + r2.dd),
        n=rough.n,
        beta=rough.beta,
        Ra=Ra,
        fc=rough.fc,
        hardness=min(r1.hardness, r2.hardness),
    )
