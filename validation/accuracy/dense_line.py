"""Dense direct solver of the discrete line-contact problem on ONE grid, independent of the
multigrid: a damped semismooth Newton iteration on all unknowns at once.

Unknowns ``P_1 .. P_{n-2}`` and ``H0``; equations: the Reynolds complementarity
``min(P_i, s_i r_i) = 0`` (``r = f - L(P)``, cavitation ``P >= 0``, ``r >= 0``, ``P r = 0``;
``s_i = 1/|dr_i/dP_i|`` a positive scaling that does not change the solution) and the load
``h sum P = pi/2``. The discrete equations are the package's (Venner's Reynolds operator with
the second-order upwind wedge term, the film with the dense log-kernel deformation ``W = K P``)
-- they *define* the discrete problem -- but nothing else is shared: the deformation is a dense
matrix product (not MLMI), the Jacobian is built column by column by finite differences of the
residual (exact in the film, since ``W`` is linear in ``P``), the linear systems are solved by
dense LU, and the iteration starts from the Hertzian pressure or from a solution of another
grid, never from the multigrid iterate of the same grid. Its answer is the exact solution of
the discrete equations to round-off, so ``|F_multigrid / F_dense - 1|`` is the multigrid's
true algebraic error on that grid.

    python validation/accuracy/dense_line.py      # writes build/validation/accuracy/dense_check.json
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np
import scipy.linalg

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
sys.path.insert(0, str(HERE.parent))

from ehl_multigrid.line.discrete import fluid_state, reynolds_residual  # noqa: E402
from ehl_multigrid.line.kernel import log_kernel  # noqa: E402
from ehl_multigrid.line.problem import LineProblem  # noqa: E402
from ehl_multigrid.model.fits import moes_line_central  # noqa: E402


class DenseFailure(RuntimeError):
    """The damped Newton iteration did not converge."""


class DenseLine:
    """The discrete line problem on ``n`` uniform points of ``[problem.xmin, problem.xmax]``."""

    def __init__(self, problem: LineProblem, n: int, order: int = 2) -> None:
        self.pb, self.n, self.order = problem, n, order
        self.X = np.linspace(problem.xmin, problem.xmax, n)
        self.h = (problem.xmax - problem.xmin) / (n - 1)
        self.par, self.lam = problem.rheology(), problem.lam
        self.K = scipy.linalg.toeplitz(log_kernel(n, self.h))
        self.f = np.zeros(n)

    def film(self, P: np.ndarray, H0: float) -> tuple[np.ndarray, np.ndarray]:
        W = self.K @ P
        return W, H0 + 0.5 * self.X**2 - W / math.pi

    def residual(self, P: np.ndarray, H0: float, W: np.ndarray | None = None) -> np.ndarray:
        W = self.K @ P if W is None else W
        H, rho, _, _, _, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, True)
        r, _ = reynolds_residual(P, H, rho, eps, self.h, self.f, self.order)
        return r

    def jacobian(self, P: np.ndarray, H0: float) -> tuple[np.ndarray, np.ndarray]:
        """``r`` and ``dr/d(P_1..P_{n-2}, H0)`` by forward differences, column by column."""
        n = self.n
        W = self.K @ P
        r = self.residual(P, H0, W)
        J = np.empty((n, n - 1))
        for c, j in enumerate(range(1, n - 1)):
            d = 1e-7 * max(1.0, abs(P[j]))
            Pj = P.copy()
            Pj[j] += d
            J[:, c] = (self.residual(Pj, H0, W + d * self.K[j]) - r) / d  # K symmetric: row = column
        d = 1e-7 * max(1e-3, abs(H0))
        J[:, -1] = (self.residual(P, H0 + d, W) - r) / d
        return r, J

    def phi(self, P: np.ndarray, H0: float, s: np.ndarray, r: np.ndarray | None = None) -> np.ndarray:
        r = self.residual(P, H0) if r is None else r
        out = np.empty(self.n - 1)
        with np.errstate(all="ignore"):
            out[:-1] = np.minimum(P[1:-1], s * r[1:-1])
        out[-1] = self.h * np.sum(P) - 0.5 * math.pi
        return out

    def hertz_start(self) -> tuple[np.ndarray, float]:
        """Hertzian pressure and the H0 that gives the Moes-fit central film."""
        X = self.X
        P = np.where(np.abs(X) < 1.0, np.sqrt(np.clip(1.0 - X**2, 0.0, None)), 0.0)
        P[0] = P[-1] = 0.0
        Hc = moes_line_central(self.pb.M, self.pb.L) * math.pi / (8.0 * self.pb.M)
        W = self.K @ P
        return P, Hc + float(np.interp(0.0, X, W)) / math.pi

    def solve(self, P: np.ndarray | None = None, H0: float | None = None, max_iter: int = 100,
              tol: float = 1e-12) -> dict:
        """Newton from ``(P, H0)`` (default: Hertz); returns the films and the iteration record."""
        if P is None:
            P, H0 = self.hertz_start()
        P = np.maximum(np.asarray(P, dtype=float).copy(), 0.0)
        P[0] = P[-1] = 0.0
        H0 = float(H0)
        inner = slice(1, self.n - 1)
        t0 = time.perf_counter()
        for it in range(max_iter + 1):
            r, Jr = self.jacobian(P, H0)
            diag = np.abs(Jr[np.arange(1, self.n - 1), np.arange(self.n - 2)])
            s = 1.0 / np.maximum(diag, 1e-300)
            phi = self.phi(P, H0, s, r)
            norm0 = float(np.linalg.norm(phi))
            if not math.isfinite(norm0):
                raise DenseFailure(f"non-finite residual at iteration {it}")
            if float(np.max(np.abs(phi))) < tol:
                break
            if it == max_iter:
                raise DenseFailure(f"no convergence in {max_iter} iterations (|phi| = {norm0:.3g})")
            # semismooth Newton on min(P, s r): P-branch rows are unit rows
            J = s[:, None] * Jr[inner]
            pbranch = P[inner] <= s * r[inner]
            J[pbranch] = 0.0
            J[np.flatnonzero(pbranch), np.flatnonzero(pbranch)] = 1.0
            J = np.vstack([J, np.r_[np.full(self.n - 2, self.h), 0.0]])
            step = scipy.linalg.lu_solve(scipy.linalg.lu_factor(J, overwrite_a=True, check_finite=False), -phi,
                                         check_finite=False)
            t = 1.0
            while True:
                Pt = P.copy()
                Pt[inner] = np.maximum(P[inner] + t * step[:-1], 0.0)
                H0t = H0 + t * step[-1]
                with np.errstate(all="ignore"):
                    norm = float(np.linalg.norm(self.phi(Pt, H0t, s)))
                if math.isfinite(norm) and norm <= (1.0 - 1e-4 * t) * norm0:
                    break
                t *= 0.5
                if t < 1e-8:
                    if float(np.max(np.abs(phi))) < 1e3 * tol:
                        break
                    raise DenseFailure(f"line search failed at iteration {it} (|phi| = {norm0:.3g})")
            P, H0 = Pt, H0t
        W, H = self.film(P, H0)
        zone = (np.abs(self.X) <= 1.5) | (P > 0)
        return {"Hc_venner": float(np.interp(0.0, self.X, H)), "Hm_venner": float(np.min(H[zone])),
                "H0": H0, "iterations": it, "max_phi": float(np.max(np.abs(phi))),
                "load_error": float(self.h * np.sum(P) / (0.5 * math.pi) - 1.0),
                "wall_s": time.perf_counter() - t0, "P": P}


def interpolate_start(X_from: np.ndarray, P_from: np.ndarray, X_to: np.ndarray) -> np.ndarray:
    return np.interp(X_to, X_from, P_from)


#: (M, L, points): one low-load, two moderate and one high-load case
CASES = [(5.0, 0.0, 513), (20.0, 10.0, 513), (20.0, 10.0, 1025), (100.0, 10.0, 1025),
         (1000.0, 20.0, 2049)]


def main() -> None:
    import json

    from _paths import out_dir
    from tqdm import tqdm

    from ehl_multigrid.line import solve_line

    out = out_dir("accuracy") / "dense_check.json"
    rows = json.loads(out.read_text()) if out.exists() else {}
    for M, L, n in tqdm(CASES, desc="dense line"):
        key = f"{M:g}_{L:g}_{n}"
        if key in rows:
            continue
        pb = LineProblem.from_moes(M, L)
        dl = DenseLine(pb, n)
        # start: Hertz, else the multigrid solution of the grid twice as coarse (never the
        # multigrid iterate of the same grid)
        start = "hertz"
        try:
            d = dl.solve()
        except DenseFailure:
            start = f"multigrid solution on {(n - 1) // 2 + 1} points, interpolated"
            c = solve_line(M, L, points=(n - 1) // 2 + 1, tol=1e-8, tol_load=1e-9, estimate=False)
            d = dl.solve(interpolate_start(c.X, c.P, dl.X), c.H0)
        row = {"M": M, "L": L, "points": n, "xmin": pb.xmin, "start": start,
               "dense": {k: v for k, v in d.items() if k != "P"}}
        for name, kw in (("mg_default", {}), ("mg_tight", {"tol": 1e-8, "tol_load": 1e-9}),
                         ("mg_tight_fft", {"tol": 1e-8, "tol_load": 1e-9, "deformation": "fft"})):
            s = solve_line(M, L, points=n, **kw)
            row[name] = {"Hc_venner": s.scalars["Hc_venner"], "Hm_venner": s.scalars["Hm_venner"],
                         "status": s.status_name, "cycles": int(s.cycles),
                         "dHc": s.scalars["Hc_venner"] / d["Hc_venner"] - 1.0,
                         "dHm": s.scalars["Hm_venner"] / d["Hm_venner"] - 1.0,
                         "max_dP": float(np.max(np.abs(s.P - d["P"]))),
                         "algebraic_estimate": s.error.budget["algebraic"] if s.error else None}
        rows[key] = row
        out.write_text(json.dumps(rows, indent=1))
    print("| (M, L) | points | dense Newton its | MG default: dHc, dHm (est. algebraic Hc, Hm) | "
          "MG tight: dHc, dHm, max dP | MG tight FFT: dHc |")
    print("|---|---|---|---|---|---|")
    for row in rows.values():
        a, t, f = row["mg_default"], row["mg_tight"], row["mg_tight_fft"]
        est = a["algebraic_estimate"] or {"Hc": math.nan, "Hm": math.nan}
        print(f"| ({row['M']:g}, {row['L']:g}) | {row['points']} | {row['dense']['iterations']} | "
              f"{a['dHc']:.1e}, {a['dHm']:.1e} ({est['Hc']:.1e}, {est['Hm']:.1e}) | "
              f"{t['dHc']:.1e}, {t['dHm']:.1e}, {t['max_dP']:.1e} | {f['dHc']:.1e} |")


if __name__ == "__main__":
    main()
