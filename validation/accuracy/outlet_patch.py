"""Local refinement of a line contact's outlet (FAS multilevel adaptive technique) against uniform
refinement: can a finer patch over the outlet replace the uniform grids that the minimum film
needs (issue "Accuracy per second", line contacts at M >= 1500)?

A converged uniform solve on ``base`` points is the coarse grid. Over the window
``[X_c - up, X_c + down]`` (``X_c`` the cavitation point, window ends on base nodes) sit ``K``
patch grids, each twice as fine as the one below (Brandt, Math. Comp. 31, 1977: FAS with local
refinement). The composite pressure is the base's piecewise constant cells outside the window
and the finest patch's cells inside; every grid sees the composite film:

* a patch grid's film is its own Toeplitz deformation plus the cells outside the window (the
  far ones by one FFT of the base grid interpolated by a cubic spline, the nearest ``m`` cells
  and the two partial cells at the window ends exactly) plus a film tau from the grid above it;
* the base grid's film is its own deformation plus the film tau of the composite at every node
  (inside the window from the first patch, outside from the finest patch's cells minus the base's
  window cells: exact near the window, a multipole expansion far from it);
* the base's Reynolds equations inside the window carry the FAS tau of the first patch, those
  outside are the finest equations there (right-hand side 0); its load target carries the
  difference between its load and the composite load.

A cycle relaxes the patches from the finest down (collective line relaxation, ends fixed),
restricts, runs one cycle of the base hierarchy (which moves H0 and the load), corrects upwards,
and post-relaxes each patch with the local Newton at the outlet. FMG over the patches, then cycles
until the patch and base residuals and the composite load error are below ``--tol``.

For each K the study records Hc, Hm, cycles and the composite's wall time, and the uniform
solves on ``base 2^k`` points (tolerance 1e-9) beside them:

    python validation/accuracy/outlet_patch.py --M 1500 --L 8 --base 16385 --K 4 --uniform 131073

writes ``build/validation/accuracy/outlet_patch_M<M>_L<L>_<base>.json``.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
from numba import njit
from scipy.interpolate import CubicSpline

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

from ehl_multigrid.line.discrete import projected  # noqa: E402
from ehl_multigrid.line.level import LineLevel  # noqa: E402
from ehl_multigrid.line.newton import local_newton  # noqa: E402
from ehl_multigrid.line.problem import LineProblem  # noqa: E402
from ehl_multigrid.line.solver import LOCAL_NEWTON_FACTOR, LOCAL_NEWTON_HALF, line_solver  # noqa: E402
from ehl_multigrid.multigrid.options import LineOptions  # noqa: E402
from ehl_multigrid.multigrid.transfer import (  # noqa: E402
    full_weighting,
    interpolate_cubic,
    interpolate_linear,
)

OUT = out_dir("accuracy")


@njit(cache=True)
def cell_sums(x, a, b, w):  # pragma: no cover - numba
    """``sum_j w_j int_{a_j}^{b_j} ln|x - s| ds`` at each ``x`` (exact cell integrals)."""
    out = np.zeros(x.shape[0])
    for i in range(x.shape[0]):
        acc = 0.0
        for j in range(a.shape[0]):
            if w[j] == 0.0:
                continue
            u = x[i] - a[j]
            v = x[i] - b[j]
            fu = u * math.log(abs(u)) - u if u != 0.0 else 0.0
            fv = v * math.log(abs(v)) - v if v != 0.0 else 0.0
            acc += w[j] * (fu - fv)
        out[i] = acc
    return out


def far_field(x: np.ndarray, a: np.ndarray, b: np.ndarray, w: np.ndarray, c: float,
              order: int = 20) -> np.ndarray:
    """The same sum far from the cells by its multipole expansion about ``c``:
    ``M_0 ln|x - c| - sum_k M_k / (k (x - c)^k)``, ``M_k = sum_j w_j int (s - c)^k ds``."""
    d = x - c
    out = np.zeros_like(x)
    t = np.ones_like(d)
    for k in range(order + 1):
        Mk = float(np.sum(w * ((b - c) ** (k + 1) - (a - c) ** (k + 1)) / (k + 1)))
        if k == 0:
            out += Mk * np.log(np.abs(d))
        else:
            t = t / d
            out -= Mk * t / k
    return out


def brandt_cryer(fine_P: np.ndarray) -> np.ndarray:
    """Coarse points frozen because a fine neighbour is cavitated (as the line solver's FAS)."""
    free = fine_P > 0.0
    cfree = free[::2].copy()
    cfree[1:] &= free[1::2]
    cfree[:-1] &= free[1::2]
    frozen = ~cfree
    frozen[0] = frozen[-1] = False
    return frozen


class OutletComposite:
    """The converged base hierarchy of ``solver`` plus ``K`` patch grids over ``window``."""

    def __init__(self, solver: Any, window: tuple[float, float], K: int, m: int = 16,
                 nu: tuple[int, int] = (2, 1)) -> None:
        self.solver, self.hz, self.s = solver, solver.hierarchy, solver.settings
        self.base = b = self.hz.levels[-1]
        self.K, self.m, self.nu = K, m, nu
        self.ja = ja = int(round((window[0] - b.xmin) / b.h))
        self.jb = jb = int(round((window[1] - b.xmin) / b.h))
        b.dW = np.zeros(b.n)
        b.deform = lambda P, b=b: b.op.apply(P) + b.dW
        self.patches: list[LineLevel] = []
        prev = b.P[ja:jb + 1]
        for k in range(1, K + 1):
            lv = LineLevel((jb - ja) * 2**k + 1, float(b.X[ja]), float(b.X[jb]), b.par, b.lam,
                           b.elastic, "fft", b.order)
            lv.W_ext, lv.dW, lv.H0 = np.zeros(lv.n), np.zeros(lv.n), b.H0
            lv.deform = lambda P, lv=lv: lv.op.apply(P) + lv.W_ext + lv.dW
            lv.P = np.maximum(interpolate_cubic(prev), 0.0)
            prev = lv.P
            self.patches.append(lv)
        self.refresh()

    def refresh(self) -> None:
        """Films of the patches from the base cells outside the window; ends and H0 from the base."""
        b, ja, jb, m = self.base, self.ja, self.jb, self.m
        lo, hi = max(ja - m, 0), min(jb + m + 1, b.n)
        Pf = b.P.copy()
        Pf[lo:hi] = 0.0
        sl = slice(max(ja - 8, 0), min(jb + 9, b.n))
        spline = CubicSpline(b.X[sl], b.op.apply(Pf)[sl])
        near = np.r_[np.arange(lo, ja), np.arange(jb + 1, hi)]
        for lv in self.patches:
            a = np.r_[b.X[near] - b.h / 2, b.X[ja] - b.h / 2, b.X[jb] + lv.h / 2]
            c = np.r_[b.X[near] + b.h / 2, b.X[ja] - lv.h / 2, b.X[jb] + b.h / 2]
            w = np.r_[b.P[near], b.P[ja], b.P[jb]]
            lv.W_ext = spline(lv.X) + cell_sums(lv.X, a, c, w)
            lv.P[0], lv.P[-1] = b.P[ja], b.P[jb]
            lv.H0 = b.H0

    def composite_load(self) -> float:
        b, top, ja, jb = self.base, self.patches[-1], self.ja, self.jb
        outside = b.h * (b.P[:ja].sum() + b.P[jb + 1:].sum())
        return outside + 0.5 * (b.h - top.h) * (b.P[ja] + b.P[jb]) + top.h * top.P.sum()

    def relax_patch(self, lv: LineLevel, sweeps: int, post: bool) -> None:
        s, hz = self.s, self.hz
        st = None
        for _ in range(sweeps):
            ends = lv.P[0], lv.P[-1]
            st = lv.relax(s.switch, s.omega, s.omega_jd, hz.options.band, switch_h=s.switch_h,
                          switch_eps=hz.switch_eps)
            lv.P[0], lv.P[-1] = ends
        if post and st is not None and hz.local_newton is not None:
            rp = np.abs(projected(st.r, lv.P))[1:-1]
            c = int(np.argmax(rp)) + 1
            if rp[c - 1] > LOCAL_NEWTON_FACTOR * float(np.mean(rp)):
                local_newton(lv, c, LOCAL_NEWTON_HALF)

    def restrict_patch(self, lv: LineLevel, cv: LineLevel) -> np.ndarray:
        st = lv.state()
        rf = projected(st.r, lv.P)
        rf[0] = rf[-1] = 0.0
        W_fine = lv.deform(lv.P)
        cv.P = lv.P[::2].copy()
        cv.frozen = brandt_cryer(lv.P)
        start = cv.P.copy()
        cv.dW = np.zeros(cv.n)
        cv.dW = W_fine[::2] - cv.deform(cv.P)
        cv.f = np.zeros(cv.n)
        cv.f = -cv.state().r + full_weighting(rf)
        cv.f[0] = cv.f[-1] = 0.0
        return start

    def restrict_base(self) -> tuple[np.ndarray, float]:
        lv, b, ja, jb = self.patches[0], self.base, self.ja, self.jb
        st = lv.state()
        rf = projected(st.r, lv.P)
        rf[0] = rf[-1] = 0.0
        W_fine = lv.deform(lv.P)
        b.P[ja:jb + 1] = lv.P[::2]
        b.frozen = np.zeros(b.n, dtype=bool)
        b.frozen[ja:jb + 1] = brandt_cryer(lv.P)
        start = (b.P.copy(), b.H0)
        b.dW = np.zeros(b.n)
        dW = np.zeros(b.n)
        dW[ja:jb + 1] = W_fine[::2] - b.deform(b.P)[ja:jb + 1]
        top = self.patches[-1]
        bw = np.arange(ja, jb + 1)
        a = np.r_[top.X - top.h / 2, b.X[ja] - b.h / 2, b.X[jb] + top.h / 2, b.X[bw] - b.h / 2]
        c = np.r_[top.X + top.h / 2, b.X[ja] - top.h / 2, b.X[jb] + b.h / 2, b.X[bw] + b.h / 2]
        w = np.r_[top.P, b.P[ja], b.P[jb], -b.P[bw]]
        reach = 3 * (jb - ja) + 32
        lo, hi = max(ja - reach, 0), min(jb + reach + 1, b.n)
        near = np.r_[np.arange(lo, ja), np.arange(jb + 1, hi)]
        far = np.r_[np.arange(0, lo), np.arange(hi, b.n)]
        dW[near] = cell_sums(b.X[near], a, c, w)
        dW[far] = far_field(b.X[far], a, c, w, 0.5 * (b.X[ja] + b.X[jb]))
        b.dW = dW
        b.f = np.zeros(b.n)
        cst = b.state()
        b.f[ja + 1:jb] = -cst.r[ja + 1:jb] + full_weighting(rf)[1:-1]
        b.g = 0.5 * math.pi + (b.load() - self.composite_load())
        return start

    def correct_patch(self, lv: LineLevel, cv_frozen: np.ndarray, change: np.ndarray) -> None:
        corr = interpolate_linear(np.where(cv_frozen, 0.0, change))
        corr[lv.P <= 0.0] = 0.0
        ends = lv.P[0], lv.P[-1]
        lv.P = np.maximum(lv.P + corr, 0.0)
        lv.P[0], lv.P[-1] = ends

    def cycle(self, top: int) -> dict[str, float]:
        nu1, nu2 = self.nu
        starts = {}
        for k in range(top, 0, -1):
            self.relax_patch(self.patches[k - 1], nu1, False)
            if k > 1:
                starts[k] = self.restrict_patch(self.patches[k - 1], self.patches[k - 2])
        P0, _ = self.restrict_base()
        kb = len(self.hz.levels) - 1
        self.solver._cycle(kb, kb, self.s.cycle)
        b, ja, jb = self.base, self.ja, self.jb
        self.correct_patch(self.patches[0], b.frozen[ja:jb + 1], (b.P - P0)[ja:jb + 1])
        self.refresh()
        self.relax_patch(self.patches[0], nu2, True)
        for k in range(2, top + 1):
            cv = self.patches[k - 2]
            self.correct_patch(self.patches[k - 1], cv.frozen, cv.P - starts[k])
            self.relax_patch(self.patches[k - 1], nu2, True)
        return self.measure(top)

    def measure(self, top: int) -> dict[str, float]:
        lv, b = self.patches[top - 1], self.base
        st = lv.state()
        res_patch = float(np.mean(np.abs(projected(st.r, lv.P)[1:-1]))) / (st.scale / (lv.n - 2))
        bst = b.state()
        rb = projected(bst.r, b.P)
        rb[self.ja + 1:self.jb] = 0.0
        res_base = float(np.mean(np.abs(rb[1:-1]))) / (bst.scale / (b.n - 2))
        return {"res_patch": res_patch, "res_base": res_base,
                "Hc": float(np.interp(0.0, b.X, bst.H)), "Hm": float(np.min(st.H)),
                "load_error": self.composite_load() / (0.5 * math.pi) - 1.0}

    def solve(self, tol: float, cycles_per_level: int = 2, max_cycles: int = 40) -> dict[str, Any]:
        history = []
        for k in range(1, self.K + 1):
            if k > 1:
                lv = self.patches[k - 1]
                lv.P = np.maximum(interpolate_cubic(self.patches[k - 2].P), 0.0)
                self.refresh()
            for _ in range(cycles_per_level):
                history.append(self.cycle(k))
        for _ in range(max_cycles):
            m = history[-1]
            if max(m["res_patch"], m["res_base"], abs(m["load_error"])) < tol:
                break
            history.append(self.cycle(self.K))
        m = history[-1]
        m["converged"] = max(m["res_patch"], m["res_base"], abs(m["load_error"])) < tol
        m["cycles"] = len(history)
        return m


def uniform(pb: LineProblem, n: int) -> tuple[Any, dict[str, Any]]:
    t0 = time.perf_counter()
    s = line_solver(pb, LineOptions.build(None, points=n, tol=1e-9, tol_load=1e-10, max_cycles=300))
    r = s.solve()
    lv = s.hierarchy.levels[-1]
    st = lv.state()
    zone = (np.abs(lv.X) <= 1.5) | (lv.P > 0)
    return s, {"points": n, "status": r.status_name, "Hc": float(np.interp(0.0, lv.X, st.H)),
               "Hm": float(np.min(st.H[zone])), "wall_s": time.perf_counter() - t0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--M", type=float, required=True)
    ap.add_argument("--L", type=float, required=True)
    ap.add_argument("--base", type=int, default=16385)
    ap.add_argument("--K", type=int, default=4, help="patch grids 1..K (ratio 2^K)")
    ap.add_argument("--uniform", type=int, default=0, help="uniform references up to this many points")
    ap.add_argument("--up", type=float, default=0.008)
    ap.add_argument("--down", type=float, default=0.004)
    ap.add_argument("--tol", type=float, default=1e-8)
    a = ap.parse_args()
    pb = LineProblem.from_moes(a.M, a.L)
    rows: dict[str, Any] = {"M": a.M, "L": a.L, "base": a.base, "window": [a.up, a.down],
                            "uniform": [], "composite": []}
    n = a.base
    while a.uniform and n <= a.uniform:
        _, u = uniform(pb, n)
        rows["uniform"].append(u)
        print(f"uniform {n}: {u['status']} Hc {u['Hc']:.9e} Hm {u['Hm']:.9e} ({u['wall_s']:.2f} s)", flush=True)
        n = 2 * (n - 1) + 1
    for K in range(1, a.K + 1):
        s, base = uniform(pb, a.base)
        lv = s.hierarchy.levels[-1]
        Xc = float(lv.X[np.flatnonzero(lv.P > 0)[-1]])
        t0 = time.perf_counter()
        comp = OutletComposite(s, (Xc - a.up, Xc + a.down), K)
        m = comp.solve(a.tol)
        m.update(K=K, ratio=2**K, patch_points=comp.patches[-1].n, wall_s=time.perf_counter() - t0,
                 base_wall_s=base["wall_s"])
        rows["composite"].append(m)
        print(f"composite K {K} ({m['patch_points']} patch points): converged {m['converged']} "
              f"Hc {m['Hc']:.9e} Hm {m['Hm']:.9e} cycles {m['cycles']} ({m['wall_s']:.2f} s)", flush=True)
    path = Path(OUT) / f"outlet_patch_M{a.M:g}_L{a.L:g}_{a.base}.json"
    path.write_text(json.dumps(rows, indent=1))
    print(path)


if __name__ == "__main__":
    main()
