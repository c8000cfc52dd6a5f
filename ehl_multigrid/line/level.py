"""One grid of the multilevel line solver: coordinates, kernel, deformation operator, the
FAS right-hand sides and the current iterate (P, H0), with the operations the cycles need."""

from __future__ import annotations

import threading
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from scipy.linalg.lapack import dgbsv

from .deformation import make_deformation
from .discrete import (
    distribute_changes,
    fluid_state,
    line_relaxation_system,
    projected,
    reynolds_residual,
)


@dataclass
class State:
    """Film and fluid properties of an iterate, with its residual."""

    H: np.ndarray
    rho: np.ndarray
    drho: np.ndarray
    lne: np.ndarray
    dlne: np.ndarray
    eps: np.ndarray
    r: np.ndarray
    scale: float


@dataclass
class LineLevel:
    """Grid ``X_i = xmin + i h``, ``i = 0 .. n-1``, and its unknowns.

    ``f`` (Reynolds) and ``g`` (load) are the FAS right-hand sides: ``f = 0``, ``g = pi/2``
    on the finest grid.
    """

    n: int
    xmin: float
    xmax: float
    par: np.ndarray
    lam: float
    elastic: bool
    deformation: str
    order: int = 2
    mlmi_order: int = 12
    mlmi_radius: int = 48
    X: np.ndarray = field(init=False)
    h: float = field(init=False)
    P: np.ndarray = field(init=False)
    H0: float = 0.0
    f: np.ndarray = field(init=False)
    g: float = float(np.pi / 2)
    #: Poiseuille face coefficient (code of :data:`~ehl_multigrid.multigrid.flux.FACE_MODES`)
    face: int = 0

    def __post_init__(self) -> None:
        self.X = np.linspace(self.xmin, self.xmax, self.n)
        self.h = (self.xmax - self.xmin) / (self.n - 1)
        method = self.deformation if self.n > 129 else "direct"
        self.op = make_deformation(self.n, self.h, method, self.mlmi_order, self.mlmi_radius)
        self.kernel = self.op.kernel
        self.P = np.zeros(self.n)
        self.f = np.zeros(self.n)
        #: points kept unchanged on this grid (FAS coarse grids near the fine free boundary)
        self.frozen = np.zeros(self.n, dtype=np.bool_)

    @property
    def shape(self) -> tuple[int]:
        return (self.n,)

    @property
    def spacing(self) -> tuple[float]:
        return (self.h,)

    @property
    def npts(self) -> int:
        return self.n

    # -- evaluation -----------------------------------------------------------------------
    def deform(self, P: np.ndarray) -> np.ndarray:
        return self.op.apply(P) if self.elastic else np.zeros(self.n)

    def state(self, P: np.ndarray | None = None, H0: float | None = None) -> State:
        P = self.P if P is None else P
        H0 = self.H0 if H0 is None else H0
        W = self.deform(P)
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, self.elastic)
        r, scale = reynolds_residual(P, H, rho, eps, self.h, self.f, self.order, self.face)
        return State(H, rho, drho, lne, dlne, eps, r, scale)

    def load(self, P: np.ndarray | None = None) -> float:
        """``h sum P`` (trapezoid; P = 0 at the ends)."""
        return float(self.h * np.sum(self.P if P is None else P))

    def residual_norm(self, st: State) -> float:
        """Mean absolute complementarity residual (frozen points excluded)."""
        rp = projected(st.r, self.P)
        rp[self.frozen] = 0.0
        return float(np.mean(np.abs(rp[1:-1])))

    # -- relaxation -----------------------------------------------------------------------
    def relax(self, switch: float, omega: float, omega_jd: float, band: int = 4,
              st: State | None = None, switch_h: float = 0.0, switch_eps: float = 0.0) -> State:
        """One collective line-relaxation sweep (discrete.line_relaxation_system) at fixed H0;
        Jacobi-distributive also where ``eps < switch_eps``.
        Returns the state *before* the sweep (its residual is the one the sweep reduced)."""
        st = self.state() if st is None else st
        ab, rhs, jac = line_relaxation_system(
            self.P, st.H, st.rho, st.drho, st.eps, st.r, self.kernel, self.h, self.order,
            self.elastic, switch, band, self.frozen, switch_h, True, switch_eps, self.face)
        delta = solve_band(ab, rhs, band)
        damp = np.ones(self.n)
        self.P = distribute_changes(self.P, delta, jac, omega, omega_jd, damp, self.frozen)
        return st


def solve_band(ab: np.ndarray, rhs: np.ndarray, band: int) -> np.ndarray:
    """Solve a collective line-relaxation system in LAPACK band storage (``band`` sub- and
    super-diagonals); a singular system (a film collapsed to zero) falls back to point Jacobi.

    LAPACK's ``gbsv`` is called directly, as ``scipy.linalg.solve_banded`` calls it (the same
    answer, bit for bit), on a work array kept per thread and size: the fresh work array of
    each call (page faults on 10 MB at 131073 points) cost as much as the solve
    (docs/performance.md, "Line relaxation")."""
    n = ab.shape[1]
    if band >= 2 and n > 1:
        ext = _band_work(band, n)
        ext[:band] = 0.0
        ext[band:] = ab
        _, _, x, info = dgbsv(band, band, ext, rhs, overwrite_ab=1, overwrite_b=0)
        if info == 0:
            return x
        if info < 0:
            raise ValueError(f"illegal value in argument {-info} of LAPACK gbsv")
    else:
        try:
            return scipy.linalg.solve_banded((band, band), ab, rhs, check_finite=False)
        except (np.linalg.LinAlgError, ValueError):
            pass
    # singular line system (e.g. a film collapsed to zero): point Jacobi this sweep
    d = ab[band]
    return np.where(np.abs(d) > 0.0, rhs / np.where(d == 0.0, 1.0, d), 0.0)


_WORK = threading.local()


def _band_work(band: int, n: int) -> np.ndarray:
    """The thread's work array for :func:`solve_band` (gbsv's storage, ``3 band + 1`` rows)."""
    arrays = getattr(_WORK, "arrays", None)
    if arrays is None:
        arrays = _WORK.arrays = {}
    key = (band, n)
    if key not in arrays:
        arrays[key] = np.empty((3 * band + 1, n))
    return arrays[key]
