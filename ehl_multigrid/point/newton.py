"""Second solution path: Newton semi-system iteration with pyamg-preconditioned GMRES.

Each outer step linearises the discrete Reynolds equation (the same operator as the FAS
solver, :mod:`.numerics`) about the current pressure with

* eps, rho frozen (Picard in the coefficients),
* the film response to pressure kept only in a ``(2m+1)^2`` neighbourhood of each point
  (the deformation is otherwise lagged: the far field of ``cd K`` enters through the full
  H recomputed every step by FFT),
* H00 as an extra unknown tied to the load balance, eliminated by two solves with the same
  AMG preconditioner (bordered system).

Cavitation by an active set: points with P = 0 whose residual pushes P negative are frozen.
The linear systems are solved by GMRES preconditioned with pyamg smoothed aggregation.
Nested iteration over a short grid sequence gives the starting guess. When the neglected
far-field coupling dominates (high M, high L) the iteration converges slowly or diverges:
the report says so.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..model.convergence import ConvergenceReport
from ..model.errors import ConvergenceError, InputError
from ..multigrid.result import EHLResult
from ..multigrid.rheology import log_derivatives
from ..multigrid.threads import serial_blas
from . import numerics as nm
from .deformation import cell_kernel, make_deformation
from .fas import load_integral
from .problem import PointProblem, resolve_domain

if TYPE_CHECKING:
    import scipy.sparse as sp


@dataclass
class NewtonOptions:
    points: int = 129
    xmin: float | None = None  # None: problem.default_domain (as the FAS path)
    xmax: float | None = None
    ymax: float | None = None
    m: int = 2
    max_iter: int = 60
    damping: float = 1.0
    tol: float = 1e-4
    tol_load: float = 1e-5
    lin_tol: float = 1e-6
    order: int = 2
    deformation: str = "fft"
    start_points: int = 33
    half: bool = False
    raise_on_failure: bool = False
    verbose: bool = False


@dataclass
class NewtonOutput:
    problem: PointProblem
    options: NewtonOptions
    X: np.ndarray
    Y: np.ndarray
    P: np.ndarray
    H: np.ndarray
    H00: float
    report: ConvergenceReport
    levels: int = 1
    half: bool = False
    solver_name: str = "newton-pyamg"
    cycle_Hc: list = field(default_factory=list)


class _Grid:
    def __init__(self, pb: PointProblem, n: int, opt: NewtonOptions) -> None:
        self.n = n
        xmin, xmax, ymax = resolve_domain(pb, opt.xmin, opt.xmax, opt.ymax)
        self.hx = (xmax - xmin) / (n - 1)
        self.hy = 2.0 * ymax / (n - 1)
        self.X = xmin + self.hx * np.arange(n)
        self.Y = -ymax + self.hy * np.arange(n)
        self.defo = make_deformation(opt.deformation, n, n, self.hx, self.hy, False)
        self.K = pb.cd * cell_kernel(opt.m + 3, opt.m + 1, self.hx, self.hy)
        self.K00 = float(pb.cd * cell_kernel(1, 1, self.hx, self.hy)[0, 0])


def _jacobian(g: _Grid, P, H, rho, eps, m: int, order: int, active: np.ndarray,
              deps: np.ndarray | None = None, drho: np.ndarray | None = None) -> sp.csr_matrix:
    import scipy.sparse as sp  # the Newton path only: not paid by every point solve's import

    n = g.n
    hx2, hy2 = g.hx**2, g.hy**2
    idx = np.arange(n * n).reshape(n, n)
    interior = np.zeros((n, n), bool)
    interior[1:-1, 1:-1] = True
    free = interior & ~active
    rows, cols, vals = [], [], []
    e = eps
    exm = 0.5 * (e[1:-1, :-2] + e[1:-1, 1:-1])
    exp_ = 0.5 * (e[1:-1, 2:] + e[1:-1, 1:-1])
    eym = 0.5 * (e[:-2, 1:-1] + e[1:-1, 1:-1])
    eyp = 0.5 * (e[2:, 1:-1] + e[1:-1, 1:-1])
    coef = {(0, 0): np.zeros((n, n)), (-1, 0): np.zeros((n, n)), (1, 0): np.zeros((n, n)),
            (0, -1): np.zeros((n, n)), (0, 1): np.zeros((n, n))}
    coef[(0, 0)][1:-1, 1:-1] = -(exm + exp_) / hx2 - (eym + eyp) / hy2
    coef[(-1, 0)][1:-1, 1:-1] = exm / hx2
    coef[(1, 0)][1:-1, 1:-1] = exp_ / hx2
    coef[(0, -1)][1:-1, 1:-1] = eym / hy2
    coef[(0, 1)][1:-1, 1:-1] = eyp / hy2
    if deps is not None:
        # eps(P) through eta and rho: d/dP of 0.5 (eps_i + eps_nb) (P_nb - P_i)/h^2
        c = P[1:-1, 1:-1]
        dW = (P[1:-1, :-2] - c) / hx2
        dE = (P[1:-1, 2:] - c) / hx2
        dS = (P[:-2, 1:-1] - c) / hy2
        dN = (P[2:, 1:-1] - c) / hy2
        coef[(0, 0)][1:-1, 1:-1] += 0.5 * deps[1:-1, 1:-1] * (dW + dE + dS + dN)
        coef[(-1, 0)][1:-1, 1:-1] += 0.5 * deps[1:-1, :-2] * dW
        coef[(1, 0)][1:-1, 1:-1] += 0.5 * deps[1:-1, 2:] * dE
        coef[(0, -1)][1:-1, 1:-1] += 0.5 * deps[:-2, 1:-1] * dS
        coef[(0, 1)][1:-1, 1:-1] += 0.5 * deps[2:, 1:-1] * dN
    if drho is not None:
        # wedge through rho(P): -(1/hx) w_s rho'_{i-s} H_{i-s}
        for s_, dx in ((0, 0), (1, -1), (2, -2)):
            ws = np.zeros((n, n))
            if order == 2:
                ws[:, 2:] = (1.5, -2.0, 0.5)[s_]
                if s_ < 2:
                    ws[:, 1] = (1.0, -1.0)[s_]
            elif s_ < 2:
                ws[:, 1:] = (1.0, -1.0)[s_]
            t = np.zeros((n, n))
            t[:, s_:] = (drho * H)[:, : n - s_]
            coef.setdefault((dx, 0), np.zeros((n, n)))
            coef[(dx, 0)] = coef[(dx, 0)] - ws * t / g.hx
    # wedge: -(1/hx) sum_s w_s rho[i-s] dH[i-s]/dP[q], dH/dP = cd K (local part)
    I = np.arange(n)[None, :]
    w2 = (1.5, -2.0, 0.5)
    w1 = (1.0, -1.0)
    for dx in range(-m - 2, m + 1):
        for dy in range(-m, m + 1):
            c = np.zeros((n, n))
            for s in range(3):
                if abs(s + dx) > m:
                    continue
                kv = g.K[abs(dy), abs(s + dx)]
                ws = np.where(I >= 2, w2[s], (w1[s] if s < 2 else 0.0)) if order == 2 else (w1[s] if s < 2 else 0.0)
                rs = np.zeros((n, n))
                rs[:, s:] = rho[:, : n - s]
                c -= ws * rs * kv / g.hx
            coef.setdefault((dx, dy), np.zeros((n, n)))
            coef[(dx, dy)] = coef[(dx, dy)] + c
    jj, ii = np.nonzero(free)
    rid = idx[jj, ii]
    for (dx, dy), c in coef.items():
        j2, i2 = jj + dy, ii + dx
        ok = (j2 >= 0) & (j2 < n) & (i2 >= 0) & (i2 < n)
        ok &= free[np.clip(j2, 0, n - 1), np.clip(i2, 0, n - 1)]
        rows.append(rid[ok])
        cols.append(idx[j2[ok], i2[ok]])
        vals.append(c[jj[ok], ii[ok]])
    fixed = np.nonzero(~free.ravel())[0]
    rows.append(fixed)
    cols.append(fixed)
    vals.append(np.ones(fixed.size))
    J = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n * n, n * n))
    return J


def solve_newton_amg(problem: PointProblem, options: NewtonOptions | None = None, **kw) -> EHLResult:
    """Newton semi-system solve with AMG-preconditioned GMRES (see module docstring). The
    coarse-level factorisations run on one BLAS thread (:func:`serial_blas`): pyamg's
    pseudo-inverse on two OpenBLAS threads took 5.6 s against 0.23 s with the other core busy."""
    with serial_blas():
        return _solve_newton_amg(problem, options, **kw)


def _solve_newton_amg(problem: PointProblem, options: NewtonOptions | None, **kw: Any) -> EHLResult:
    import pyamg
    import scipy.sparse.linalg as spla

    opt = NewtonOptions(**{**(vars(options) if options else {}), **kw})
    if opt.half:
        raise InputError("the Newton/pyamg path solves the full domain only (half = False)")
    if (opt.points - 1) % 16:
        raise InputError(f"points = {opt.points} must be 16 k + 1")
    pb = problem
    t0 = time.perf_counter()
    par = pb.rheology()
    sizes = [opt.points]
    while sizes[-1] > opt.start_points and (sizes[-1] - 1) % 2 == 0 and (sizes[-1] - 1) // 2 >= 16:
        sizes.append((sizes[-1] - 1) // 2 + 1)
    sizes = sizes[::-1]
    res_hist, load_hist, hc_hist, lin_iters, actions = [], [], [], [], []
    P = None
    H00 = None
    converged = False
    g = None
    for n in sizes:
        g = _Grid(pb, n, opt)
        if P is None:
            P = np.sqrt(np.clip(1.0 - g.X[None, :] ** 2 - (g.Y[:, None] / pb.b_over_a) ** 2, 0.0, None))
            from ..model.fits import nijenbanning_central

            Hc_fit = nijenbanning_central(pb.M, pb.L, pb.theta) / pb.moes_factor
            W = g.defo(P)
            H00 = float(Hc_fit - pb.cd * W[(n - 1) // 2, int(np.argmin(np.abs(g.X)))])
        else:
            P = nm.interpolate_cubic(P, False)
        P[0], P[-1], P[:, 0], P[:, -1] = 0.0, 0.0, 0.0, 0.0
        H = np.empty_like(P)
        rho = np.empty_like(P)
        eps = np.empty_like(P)
        r = np.empty_like(P)
        f = np.zeros_like(P)
        damp = opt.damping
        best = math.inf
        final = n == sizes[-1]
        maxit = opt.max_iter if final else 8
        for it in range(maxit):
            W = g.defo(P)
            nm.film(W, g.X, g.Y, H00, pb.theta, pb.cd, H)
            nm.fluid_properties(P, H, par, pb.lam, rho, eps)
            nm.residual(P, H, rho, eps, f, g.hx, g.hy, False, opt.order, r)
            sr = np.empty_like(r)
            nm.scaled_residual(r, H, rho, eps, g.K00, g.hx, g.hy, False, sr)
            rel = math.sqrt(float(np.mean(sr[1:-1, 1:-1] ** 2))) / max(P.max(), 1e-300)
            lerr = abs(load_integral(P, g.hx, g.hy, False) - pb.load) / pb.load
            if not (math.isfinite(rel) and math.isfinite(H00)):
                raise ConvergenceError("Newton/pyamg path produced NaN", None,
                                       "use the FAS solver (solve_fas) for this case")
            if final:
                res_hist.append(rel)
                load_hist.append(lerr)
                hc_hist.append(float(H[(n - 1) // 2, int(np.argmin(np.abs(g.X)))]))
                if opt.verbose:
                    print(f"newton {it}: res {rel:.3e} load {lerr:.3e} Hc {hc_hist[-1]:.6g} damp {damp}")
                if rel < opt.tol and lerr < opt.tol_load:
                    converged = True
                    break
                if rel > 2.0 * best:
                    damp = max(0.1, 0.5 * damp)
                    actions.append(f"step {it}: residual rose to {rel:.3g}, damping -> {damp:g}")
                elif rel < best and damp < opt.damping:
                    damp = min(opt.damping, 1.5 * damp)
                best = min(best, rel)
            # linear system: L(P) = -r at free points; active set where P = 0 and r >= 0
            Lfull = np.empty_like(P)
            nm.operator(P, H, rho, eps, g.hx, g.hy, False, opt.order, Lfull)
            rhs = f - Lfull
            active = (P <= 0.0) & (rhs >= 0.0)
            dlr, dle = np.empty_like(P), np.empty_like(P)
            log_derivatives(P, par, dlr, dle)
            J = _jacobian(g, P, H, rho, eps, opt.m, opt.order, active, eps * (dlr - dle), dlr * rho)
            if not np.all(np.isfinite(J.data)):
                raise ConvergenceError(
                    f"Newton/pyamg path: non-finite Jacobian on the {n}^2 grid (step {it})", None,
                    "the lagged far-field deformation diverged here; use the FAS solver (solve_fas)")
            free = np.zeros_like(P, bool)
            free[1:-1, 1:-1] = True
            free &= ~active
            b1 = np.where(free, rhs, 0.0).ravel()
            # dL/dH00 = -(1/hx) sum_s w_s rho[i-s]
            dLdH = np.zeros_like(P)
            dLdH[:, 2:] = -(1.5 * rho[:, 2:] - 2.0 * rho[:, 1:-1] + 0.5 * rho[:, :-2]) / g.hx
            dLdH[:, 1] = -(rho[:, 1] - rho[:, 0]) / g.hx
            # plus the Poiseuille terms through eps ~ H^3
            de = 3.0 * eps / np.maximum(H, 1e-12)
            c = P[1:-1, 1:-1]
            hx2, hy2 = g.hx**2, g.hy**2
            dLdH[1:-1, 1:-1] += (0.5 * (de[1:-1, 1:-1] + de[1:-1, :-2]) * (P[1:-1, :-2] - c) / hx2
                                 + 0.5 * (de[1:-1, 1:-1] + de[1:-1, 2:]) * (P[1:-1, 2:] - c) / hx2
                                 + 0.5 * (de[1:-1, 1:-1] + de[:-2, 1:-1]) * (P[:-2, 1:-1] - c) / hy2
                                 + 0.5 * (de[1:-1, 1:-1] + de[2:, 1:-1]) * (P[2:, 1:-1] - c) / hy2)
            b2 = np.where(free, dLdH, 0.0).ravel()
            # classical (Ruge-Stuben) AMG: on these nonsymmetric, badly scaled Jacobians it
            # converged in ~15 GMRES steps where smoothed aggregation was slower to set up
            ml = pyamg.ruge_stuben_solver(J, max_coarse=400)
            Mpre = ml.aspreconditioner(cycle="V")
            cnt = [0]

            def _cb(_x, cnt=cnt):
                cnt[0] += 1

            try:
                d1, i1 = spla.gmres(J, b1, M=Mpre, rtol=opt.lin_tol, restart=50, maxiter=6,
                                    callback=_cb, callback_type="pr_norm")
                d2, i2 = spla.gmres(J, b2, M=Mpre, rtol=opt.lin_tol, restart=50, maxiter=6,
                                    callback=_cb, callback_type="pr_norm")
            except ValueError as exc:  # NaN/inf inside the AMG hierarchy
                raise ConvergenceError(
                    f"Newton/pyamg path diverged on the {n}^2 grid (step {it}): {exc}", None,
                    "the lagged far-field deformation dominates here; use the FAS solver") from None
            if i1 or i2:
                actions.append(f"n={n} step {it}: GMRES did not reach rtol {opt.lin_tol:g}")
            lin_iters.append(cnt[0])
            # J d + b2 dH = b1 with d = d1 - dH d2; load: sum(P + d) hx hy = target
            w = g.hx * g.hy
            s1 = load_integral(P, g.hx, g.hy, False) + w * d1.sum()
            s2 = w * d2.sum()
            dH = (s1 - pb.load) / s2 if s2 != 0 else 0.0
            d = (d1 - dH * d2).reshape(P.shape)
            P = np.maximum(P + damp * d, 0.0)
            P[0], P[-1], P[:, 0], P[:, -1] = 0.0, 0.0, 0.0, 0.0
            H00 += damp * dH
            if opt.verbose:
                print(f"  n={n} it={it} dH={dH:.3g} H00={H00:.4g} |d|={np.abs(d).max():.3g} gmres={i1},{i2} lin={cnt[0]}")
    wall = time.perf_counter() - t0
    msg = "converged" if converged else (
        f"not converged in {opt.max_iter} Newton steps: residual {res_hist[-1]:.3g} (tol {opt.tol:g}), "
        f"load error {load_hist[-1]:.3g} (tol {opt.tol_load:g})")
    report = ConvergenceReport(
        converged=converged, message=msg, iterations=len(res_hist), residual_history=np.array(res_hist),
        load_error_history=np.array(load_hist), tolerances={"residual": opt.tol, "load": opt.tol_load},
        work_units=math.nan, wall_s=wall,
        extra={"actions": actions, "gmres_iterations": np.array(lin_iters), "cycle_Hc": np.array(hc_hist)},
    )
    if not converged and opt.raise_on_failure:
        raise ConvergenceError(msg, report, "the lagged far-field deformation is too stiff here: use solve_fas")
    return newton_result(NewtonOutput(pb, opt, g.X, g.Y, P, H, H00, report, len(sizes), False,
                                      "newton-pyamg", hc_hist))


def newton_result(out: NewtonOutput, scene=None) -> EHLResult:
    """The Newton path's answer as the package's one EHL result type."""
    from .postprocess import build_result

    rep = out.report
    sol = EHLResult(
        status=0 if rep.converged else 1, message=rep.message, cycles=rep.iterations,
        residual_history=rep.residual_history, load_error_history=rep.load_error_history,
        work_units=rep.work_units, wall_s=rep.wall_s, actions=list(rep.extra.get("actions", [])),
        tolerances=dict(rep.tolerances), contact="point", solver="newton", problem=out.problem,
        options=out.options, X=out.X, Y=out.Y, P=out.P, H=out.H, H0=out.H00, half=out.half,
        levels=out.levels, scene=scene, builder=build_result,
        extra={k: v for k, v in rep.extra.items() if k != "actions"})
    sol.scalars = dict(build_result(sol, scene).scalars)
    return sol
