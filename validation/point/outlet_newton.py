"""Would a point analogue of the line solver's local Newton converge the Barus contacts at
alpha_bar 20-73 that diverge on fine grids? (What-if study; the package is not changed.)

The line solver ends its relaxations on fine grids with a windowed Newton solve at the largest
complementarity residual (``ehl_multigrid.line.newton.local_newton``): the collective line
relaxation freezes ``eps``, which cannot settle the outlet pressure drop of Barus oils at high
``alpha_bar``. Here the point hierarchy's ``relax`` is wrapped so that after each relaxation on
grids of at least ``--min-nx`` points along X, windows of ``(2 wy + 1) x (2 wx + 1)`` points
around the largest scaled residuals (above 20 times their mean, up to 40 windows, not
overlapping) are solved by damped semismooth Newton on ``min(P, s r)``: the window's pressures
unknown, everything else fixed; the Jacobian by finite differences of the package's own residual
with the film's response through the exact cell kernel (mirror rows on the half domain), so it
holds ``d eps/d P`` and the local deformation. The whole film is refreshed once after the windows.

    NUMBA_NUM_THREADS=1 python validation/point/outlet_newton.py [--points 1025] [--min-nx 513]

Writes ``build/validation/point/outlet_newton.json`` (status, films, work units, windows, Newton steps, wall time,
with and without the windows).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ehl_multigrid.point import fas, solve_point
from ehl_multigrid.point import numerics as nm
from ehl_multigrid.point.deformation import cell_kernel

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("point") / "outlet_newton.json"
STATS = {"windows": 0, "newton_steps": 0}


def window_newton(hz, lev, jc: int, ic: int, wy: int = 4, wx: int = 8, max_iter: int = 10,
                  reduce: float = 1e-3) -> None:
    """Semismooth Newton on the window around ``(jc, ic)``; writes the window's P."""
    sym, order, ct = hz.options.half, hz.options.wedge_order, hz.ct
    ny, nx = lev.P.shape
    j0, j1 = max(0 if sym else 1, jc - wy), min(ny - 1, jc + wy + 1)
    i0, i1 = max(1, ic - wx), min(nx - 1, ic + wx + 1)
    ja, jb, ia, ib = max(j0 - 1, 0), min(j1 + 1, ny), max(i0 - 2, 0), min(i1 + 1, nx)
    wj, wi = slice(j0 - ja, j1 - ja), slice(i0 - ia, i1 - ia)
    ej, ei, wjg, wig = np.arange(ja, jb), np.arange(ia, ib), np.arange(j0, j1), np.arange(i0, i1)
    K = cell_kernel(ib - ia + 1, jb + j1 + 1, lev.hx, lev.hy) * hz.cd  # [dj, di]
    dI = np.abs(ei[:, None] - wig[None, :])
    Km = K[np.abs(ej[:, None] - wjg[None, :])[:, None, :, None], dI[None, :, None, :]]
    if sym:  # the mirror image of a window row j > 0 at -j
        Ks = K[(ej[:, None] + wjg[None, :])[:, None, :, None], dI[None, :, None, :]]
        Km = Km + np.where((wjg > 0)[None, None, :, None], Ks, 0.0)
    Km = Km.reshape(len(ej) * len(ei), len(wjg) * len(wig))
    P0 = np.ascontiguousarray(lev.P[ja:jb, ia:ib])
    H0 = np.ascontiguousarray(lev.H[ja:jb, ia:ib])
    f = np.ascontiguousarray(lev.f[ja:jb, ia:ib])
    Pw0 = P0[wj, wi].copy()
    shape = Pw0.shape
    rho, eps, Lp = np.empty_like(P0), np.empty_like(P0), np.empty_like(P0)

    def residual(Pw: np.ndarray) -> np.ndarray:
        Pe = P0.copy()
        Pe[wj, wi] = Pw.reshape(shape)
        He = H0 + (Km @ (Pw - Pw0.ravel())).reshape(H0.shape)
        nm.fluid_properties(Pe, He, hz.par, hz.lam, rho, eps)
        nm.operator(Pe, He, rho, eps, lev.hx, lev.hy, sym and ja == 0, order, Lp, ct)
        return (f - Lp)[wj, wi].ravel()

    Pw = Pw0.ravel().copy()
    r = residual(Pw)
    merit0 = None
    for _ in range(max_iter):
        J = np.empty((Pw.size, Pw.size))
        for q in range(Pw.size):
            d = 1e-7 * max(abs(Pw[q]), 1e-3)
            Pt = Pw.copy()
            Pt[q] += d
            J[:, q] = (residual(Pt) - r) / d
        s = 1.0 / np.maximum(np.abs(np.diagonal(J)), 1e-300)
        phi = np.minimum(Pw, s * r)
        merit = float(np.linalg.norm(phi))
        merit0 = merit if merit0 is None else merit0
        if not np.isfinite(merit) or merit <= reduce * merit0 or merit == 0.0:
            break
        active = Pw <= s * r
        Jm = J * s[:, None]
        Jm[active] = 0.0
        idx = np.flatnonzero(active)
        Jm[idx, idx] = 1.0
        try:
            step = np.linalg.solve(Jm, -phi)
        except np.linalg.LinAlgError:
            break
        t = 1.0
        while t >= 1e-4:
            Pt = Pw + t * step
            rt = residual(Pt)
            m = float(np.linalg.norm(np.minimum(Pt, s * rt)))
            if np.isfinite(m) and m <= (1.0 - 1e-4 * t) * merit:
                break
            t *= 0.5
        else:
            break
        Pw, r = Pt, rt
        STATS["newton_steps"] += 1
    lev.P[j0:j1, i0:i1] = np.maximum(Pw.reshape(shape), 0.0)


def windows(hz, lev, factor: float = 20.0, max_windows: int = 40, wy: int = 4, wx: int = 8) -> int:
    """Newton windows at the largest scaled residuals above ``factor`` times their mean."""
    r = hz.residual(lev).copy()
    sr = np.empty_like(r)
    nm.scaled_residual(r, lev.H, lev.rho, lev.eps, float(lev.Kc[0, 0]), lev.hx, lev.hy,
                       hz.options.half, sr, hz.ct)
    a = np.abs(sr)
    mean = float(a.mean())
    taken = np.zeros(a.shape, bool)
    n = 0
    for q in np.argsort(a.ravel())[::-1][:5000]:
        j, i = np.unravel_index(q, a.shape)
        if a[j, i] <= factor * mean or n >= max_windows:
            break
        if taken[j, i]:
            continue
        window_newton(hz, lev, int(j), int(i), wy, wx)
        taken[max(0, j - wy):j + wy + 1, max(0, i - wx):i + wx + 1] = True
        n += 1
    if n:
        hz.update_film(lev)
        STATS["windows"] += n
    return n


def install(min_nx: int) -> None:
    plain = fas.PointHierarchy.relax

    def relax(self, k, sweeps, s, coarse, post=False):
        w = plain(self, k, sweeps, s, coarse, post)
        lev = self.levels[k]
        if lev.nx >= min_nx and np.all(np.isfinite(lev.P)) and windows(self, lev):
            w += self.work(k)
        return w

    fas.PointHierarchy.relax = relax


def run(M: float, L: float, theta: float, points: int) -> dict:
    t = time.perf_counter()
    s = solve_point(M, L, theta=theta, viscosity="barus", density="incompressible", points=points,
                    half=True, accuracy=None)
    return {"status": s.status_name, "message": s.message[:300], "Hc": s.Hc, "Hm": s.Hm,
            "work_units": s.work_units, "wall_s": time.perf_counter() - t, **STATS}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", type=float, nargs=3, default=(20.0, 20.0, 4.0), metavar=("M", "L", "THETA"))
    ap.add_argument("--points", type=int, nargs="+", default=[257, 1025])
    ap.add_argument("--min-nx", type=int, default=257)
    a = ap.parse_args()
    out = {"case": a.case, "min_nx": a.min_nx, "runs": []}
    for n in a.points:
        out["runs"].append({"points": n, "windows": False, **run(*a.case, n)})
    install(a.min_nx)
    for n in a.points:
        STATS.update(windows=0, newton_steps=0)
        out["runs"].append({"points": n, "windows": True, **run(*a.case, n)})
    OUT.write_text(json.dumps(out, indent=1))
    for r in out["runs"]:
        print(r)


if __name__ == "__main__":
    main()
