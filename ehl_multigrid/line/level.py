"""One grid of the multilevel line solver: coordinates, kernel, deformation operator, the
FAS right-hand sides and the current iterate (P, H0), with the operations the cycles need."""

from __future__ import annotations

import threading
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from scipy.linalg.lapack import dgbsv

from ..multigrid.flux import face_coefficients
from .deformation import make_deformation
from .discrete import fluid_state, projected, relaxation_sweep, residual_from_faces


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
    #: Poiseuille face coefficients of ``eps`` (None: computed where needed); keyword only, so
    #: the positional fields of subclasses (the starved state's theta, q) keep their places
    faces: np.ndarray | None = field(default=None, kw_only=True)


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
        #: the last state computed, with what it was computed from (:meth:`state`)
        self._last_state: tuple | None = None

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
        """Film, fluid properties and residual of ``(P, H0)`` (default: the iterate). The
        last one is kept: a cycle asks again for the state it measured (the finest grid's
        measurement, then its first relaxation sweep), which is returned without a second
        deformation when the pressures, film constant, right-hand side and lubricant are the
        same (compared by value, so changes in place count)."""
        P = self.P if P is None else P
        H0 = self.H0 if H0 is None else H0
        key = (H0, self.lam, self.elastic, self.order, self.face)
        last = self._last_state
        if last is not None and last[0] == key and np.array_equal(last[1], P) \
                and np.array_equal(last[2], self.f) and np.array_equal(last[3], self.par):
            return last[4]
        W = self.deform(P)
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, self.elastic)
        faces = face_coefficients(eps, self.face)
        r, scale = residual_from_faces(P, H, rho, faces, self.h, self.f, self.order)
        st = State(H, rho, drho, lne, dlne, eps, r, scale, faces=faces)
        self._last_state = (key, P.copy(), self.f.copy(), self.par.copy(), st)
        return st

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
        """One collective line-relaxation sweep (discrete.relaxation_sweep: the system of
        discrete.line_relaxation_system, solved and applied in one kernel) at fixed H0;
        Jacobi-distributive also where ``eps < switch_eps``.
        Returns the state *before* the sweep (its residual is the one the sweep reduced)."""
        st = self.state() if st is None else st
        faces = face_coefficients(st.eps, self.face) if st.faces is None else st.faces
        self.P = relaxation_sweep(
            self.P, st.H, st.rho, st.drho, st.eps, faces, st.r, self.kernel, self.h, self.order,
            self.elastic, switch, band, self.frozen, switch_h, True, switch_eps,
            omega, omega_jd, _band_work(band, self.n - 2))
        return st


def solve_band(ab: np.ndarray, rhs: np.ndarray, band: int) -> np.ndarray:
    """Solve a collective line-relaxation system in LAPACK band storage (``band`` sub- and
    super-diagonals); a singular system (a film collapsed to zero) falls back to point Jacobi.

    LAPACK's ``gbsv`` is called directly, as ``scipy.linalg.solve_banded`` calls it (the same
    answer, bit for bit), on a work array kept per thread and size: the fresh work array of
    each call (page faults on 10 MB at 131073 points) cost as much as the solve
    (docs/performance.md, "Line relaxation: banded systems"). The starved and transient
    line solvers solve their systems here; the steady one in its sweep kernel
    (:meth:`LineLevel.relax`)."""
    n = ab.shape[1]
    if band >= 2 and n > 1:
        ext = _lapack_work(band, n)
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
    """The thread's work array of an ``n``-unknown banded system (:mod:`~ehl_multigrid.line.band`
    column storage, ``3 band + 1`` entries per column)."""
    return _work(("columns", band, n), (n, 3 * band + 1))


def _lapack_work(band: int, n: int) -> np.ndarray:
    """The thread's work array for :func:`solve_band` (gbsv's storage, ``3 band + 1`` rows)."""
    return _work(("lapack", band, n), (3 * band + 1, n))


def _work(key: tuple, shape: tuple[int, int]) -> np.ndarray:
    arrays = getattr(_WORK, "arrays", None)
    if arrays is None:
        arrays = _WORK.arrays = {}
    if key not in arrays:
        arrays[key] = np.empty(shape)
    return arrays[key]
