"""Contacts long in the rolling direction (theta = Rx/Ry > 1): solver against the published
ellipticity forms, and checks of the solver that depend on no fit (issue 44).

    python validation/theta/study.py [--quick]

Writes ``build/validation/theta/study.json`` (every solve as it finishes) and ``study.md``.

What is compared, all on the fits' own model (Barus viscosity, incompressible oil):

1. The point solver's ``Hc``, ``Hm`` (Moes units, status, estimated error) for (M, L) in
   {(20, 10), (100, 10), (50, 5)} and theta in {0.25, 0.5, 1, 2, 4}, accuracy 2 %, at most
   513 points.
2. Nijenbanning et al. (1994), thesis (2.23)-(2.29).
3. Chittenden, Dowson, Dunn & Taylor (1985, Proc. R. Soc. Lond. A 397, 271-294), fitted for
   entrainment along either principal axis::

       Hc = 4.31 U^0.68 G^0.49 W^-0.073 {1 - exp[-1.23 (Rs/Rx)^(2/3)]}
       Hm = 3.68 U^0.68 G^0.49 W^-0.073 {1 - exp[-0.67 (Rs/Rx)^(2/3)]}

   with ``Rx`` the reduced radius along the entraining direction, ``Rs`` across it (so
   ``Rs/Rx = 1/theta`` here), ``H = h/Rx``, ``U = eta0 u/(E' Rx)`` on the mean speed
   ``u = us/2``, ``W = w/(E' Rx^2)``, ``G = alpha E'``.
4. Hamrock & Dowson (1977, J. Lubr. Technol. 99, 264-276), central film, for comparison at
   theta <= 1 (their range, k = 1-8): ``Hc = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k))``,
   ``k = 1.03 (Ry/Rx)^0.64``.

Conversion to Moes groups (package convention, docs/conventions.md): ``Us = eta0 us/(E' Rx)
= 2 U``, ``M = W Us^(-3/4)``, ``L = G Us^(1/4)``, ``h = H_Moes Rx Us^(1/2)``. Hence
``W = M Us^(3/4)``, ``G = L Us^(-1/4)`` and, for a formula ``H = k U^a G^b W^c f(theta)``::

    H_Moes = k 2^(-a) Us^(a - b/4 + 3c/4 - 1/2) L^b M^c f(theta).

The exponent of ``Us`` is 0.00275 for Chittenden et al. and -0.01275 for Hamrock-Dowson: the
power-law fits are not functions of (M, L) alone. They are evaluated at ``Us = 1e-11`` (G = 5600
at L = 10, a steel/mineral-oil value); a decade of ``Us`` changes them by 0.6 % and 3 %
respectively, and the ratios at equal (M, L) not at all.

Checks of the solver independent of any fit, at theta = 4:

* grid: the same box on 257 and 513 points (fixed grids);
* box: 513 points on the default box and on one twice as large (same mesh size is not kept:
  the doubled box halves the resolution, so it is read together with the grid pair);
* the rigid-isoviscous limit: an own Reynolds solution (Swift-Stieber cavitation by an
  active set) in coordinates scaled on the rigid inlet, ``x = (2 Rx h0)^(1/2) xi``,
  ``y = (2 Ry h0)^(1/2) zeta``, gives ``d(H^3 p_xi)/dxi + theta d(H^3 p_zeta)/dzeta = dH/dxi``,
  ``H = 1 + xi^2 + zeta^2`` and, with the load balance, ``H_Moes = 288 I^2/(theta M^2)``
  (``I`` the integral of the scaled pressure). Its theta dependence checks the rigid term
  HRI of (2.26) on both sides of theta = 1 (truncation of the inlet changes I, so only the
  ratio to theta = 1 on the same scaled box is used).

X/Y exchange: a contact at theta and one at 1/theta are the same bodies turned by 90 degrees,
but the entrainment stays along X, so Reynolds' wedge term ``d(rho h)/dx`` turns from the
major to the minor axis: they are different lubrication problems and no identity links their
films. Only the dry part is shared (Hertz ellipse with a and b exchanged, same deformation
operator), which the package checks against the exact Hertz solution already.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

from ehl_multigrid.model.fits import nijenbanning_central, nijenbanning_terms  # noqa: E402

CASES = [(20.0, 10.0), (100.0, 10.0), (50.0, 5.0)]
THETAS = [0.25, 0.5, 1.0, 2.0, 4.0]
MODEL = {"viscosity": "barus", "density": "incompressible"}
US = 1e-11  # Us = eta0 us/(E' Rx) at which the power-law fits are evaluated


def _moes(k: float, a: float, b: float, c: float, M: float, L: float, us: float = US) -> float:
    """``k U^a G^b W^c`` (U on the mean speed) in Moes units at ``Us = us``."""
    return k * 2.0 ** (-a) * us ** (a - b / 4.0 + 3.0 * c / 4.0 - 0.5) * L**b * M**c


def chittenden(M: float, L: float, theta: float, us: float = US) -> tuple[float, float]:
    """Central and minimum film of Chittenden et al. (1985) in Moes units; ``Rs/Rx = 1/theta``."""
    r = (1.0 / theta) ** (2.0 / 3.0)
    hc = _moes(4.31, 0.68, 0.49, -0.073, M, L, us) * (1.0 - math.exp(-1.23 * r))
    hm = _moes(3.68, 0.68, 0.49, -0.073, M, L, us) * (1.0 - math.exp(-0.67 * r))
    return hc, hm


def hamrock_dowson_central(M: float, L: float, theta: float, us: float = US) -> float:
    """Hamrock & Dowson (1977) central film in Moes units, ``k = 1.03 (Ry/Rx)^0.64``."""
    k = 1.03 * (1.0 / theta) ** 0.64
    return _moes(2.69, 0.67, 0.53, -0.067, M, L, us) * (1.0 - 0.61 * math.exp(-0.73 * k))


def rigid_integral(theta: float, n: int = 161, box: float = 1.0) -> float:
    """Integral of the scaled rigid-isoviscous pressure on ``xi in [-12, 4] box``,
    ``zeta in [-8, 8] box`` (module docstring), cavitation by an active set."""
    xi = np.linspace(-12.0 * box, 4.0 * box, n)
    ze = np.linspace(-8.0 * box, 8.0 * box, n)
    hx, hy = xi[1] - xi[0], ze[1] - ze[0]
    Z, X = np.meshgrid(ze, xi, indexing="ij")
    e = (1.0 + X**2 + Z**2) ** 3
    rhs = 2.0 * X
    ny, nx = e.shape
    idx = np.arange(nx * ny).reshape(ny, nx)
    active = np.zeros((ny, nx), bool)
    p = np.zeros((ny, nx))
    for _ in range(200):
        free = np.zeros((ny, nx), bool)
        free[1:-1, 1:-1] = True
        free &= ~active
        jj, ii = np.nonzero(free)
        cw = 0.5 * (e[jj, ii - 1] + e[jj, ii]) / hx**2
        ce = 0.5 * (e[jj, ii + 1] + e[jj, ii]) / hx**2
        cs = theta * 0.5 * (e[jj - 1, ii] + e[jj, ii]) / hy**2
        cn = theta * 0.5 * (e[jj + 1, ii] + e[jj, ii]) / hy**2
        rows, cols, vals = [], [], []
        for dj, di, v in ((0, 0, -(cw + ce + cs + cn)), (0, -1, cw), (0, 1, ce), (-1, 0, cs), (1, 0, cn)):
            ok = free[jj + dj, ii + di]
            rows.append(idx[jj, ii][ok])
            cols.append(idx[jj + dj, ii + di][ok])
            vals.append(v[ok])
        fixed = idx[~free]
        rows.append(fixed)
        cols.append(fixed)
        vals.append(np.ones(fixed.size))
        A = sp.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(nx * ny, nx * ny))
        b = np.where(free, rhs, 0.0)
        p = spla.spsolve(A, b.ravel()).reshape(ny, nx)
        res = np.zeros_like(p)  # Poiseuille(P) - wedge; > 0 at a cavitated point asks for P > 0
        c = p[1:-1, 1:-1]
        res[1:-1, 1:-1] = (
            (0.5 * (e[1:-1, 2:] + e[1:-1, 1:-1]) * (p[1:-1, 2:] - c)
             - 0.5 * (e[1:-1, :-2] + e[1:-1, 1:-1]) * (c - p[1:-1, :-2])) / hx**2
            + theta * (0.5 * (e[2:, 1:-1] + e[1:-1, 1:-1]) * (p[2:, 1:-1] - c)
                       - 0.5 * (e[:-2, 1:-1] + e[1:-1, 1:-1]) * (c - p[:-2, 1:-1])) / hy**2
            - rhs[1:-1, 1:-1])
        new = (active | ((p < 0.0) & free)) & ~(active & (res > 0.0))
        if np.array_equal(new, active):
            break
        active = new
    return float(np.maximum(p, 0.0).sum() * hx * hy)


def solve(M: float, L: float, theta: float, **kw) -> dict:
    from ehl_multigrid.point import solve_point

    t0 = time.perf_counter()
    try:
        s = solve_point(M, L, theta=theta, **MODEL, **kw)
    except Exception as exc:  # an error is an outcome: recorded, the study goes on
        return {"status": "error", "message": f"{type(exc).__name__}: {exc}".splitlines()[0]}
    return {"status": s.status_name, "Hc": s.scalars.get("Hc"), "Hm": s.scalars.get("Hm"),
            "Hc_error": s.scalars.get("Hc_error"), "Hm_error": s.scalars.get("Hm_error"),
            "points": int(s.X.shape[0]), "domain": list(s.extra.get("domain", ())),
            "wall_s": round(time.perf_counter() - t0, 1)}


def _save(path: Path, data: dict) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1))
    os.replace(tmp, path)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="(20, 10) only, no rigid reference")
    a = ap.parse_args()
    out = out_dir("theta")
    path = out / ("study_quick.json" if a.quick else "study.json")
    data = json.loads(path.read_text()) if path.exists() else {}
    cases = CASES[:1] if a.quick else CASES

    def once(key: str, fn) -> dict:
        if key not in data:
            data[key] = fn()
            _save(path, data)
            print(key, data[key], flush=True)
        return data[key]

    for M, L in cases:
        for th in THETAS:
            once(f"acc_{M:g}_{L:g}_{th:g}", lambda M=M, L=L, th=th: solve(M, L, th, accuracy=0.02, max_points=513))
    # fit-independent checks at theta = 4 (and theta = 1 for the ratio)
    from ehl_multigrid.point.problem import default_domain, problem_from_moes

    for th in (4.0, 1.0):
        pb = problem_from_moes(20.0, 10.0, th, **MODEL)
        x0, x1, y1 = default_domain(pb)
        for n in (257, 513):
            once(f"grid_20_10_{th:g}_{n}", lambda n=n, th=th: solve(20.0, 10.0, th, points=n))
        once(f"box2_20_10_{th:g}_513", lambda th=th, x0=x0, x1=x1, y1=y1:
             solve(20.0, 10.0, th, points=513, xmin=2 * x0, xmax=2 * x1, ymax=2 * y1))
    if not a.quick:
        for th in THETAS:
            for box in (1.0, 2.0):
                once(f"rigid_{th:g}_{box:g}", lambda th=th, box=box: {"I": rigid_integral(th, box=box)})
    report(data, out / ("study_quick.md" if a.quick else "study.md"), cases)


def _cell(v: float | None, e: float | None) -> str:
    return f"{v:.4g} [{100 * e:.2f}]" if v is not None and e is not None else "-"


def report(data: dict, path: Path, cases: list) -> None:
    lines = ["# theta > 1 study (Barus, incompressible; Moes units)", "",
             "| M | L | theta | status | Hc [err %] | Hm [err %] | Nij Hc | Chit Hc | Chit Hm | HD Hc | "
             "Hc/Nij | Hc/Chit | Hm/Chit |", "|" + "---|" * 13]
    for M, L in cases:
        for th in THETAS:
            r = data.get(f"acc_{M:g}_{L:g}_{th:g}", {})
            nij = float(nijenbanning_central(M, L, th))
            ch, cm = chittenden(M, L, th)
            hd = hamrock_dowson_central(M, L, th)
            hc, hm = r.get("Hc"), r.get("Hm")
            ok = r.get("status") == "converged"
            lines.append(
                f"| {M:g} | {L:g} | {th:g} | {r.get('status', '-')} ({r.get('points', '-')}) | "
                f"{_cell(hc, r.get('Hc_error'))} | {_cell(hm, r.get('Hm_error'))} | {nij:.4g} | {ch:.4g} | {cm:.4g} | "
                f"{hd:.4g} | " + " | ".join(f"{v:.3f}" if ok else "-" for v in
                                             ((hc or 0) / nij, (hc or 0) / ch, (hm or 0) / cm)) + " |")
    lines += ["", "Ratios Hc(theta)/Hc(theta = 1) at equal (M, L) (converged solves only):", "",
              "| M | L | theta | solver | Nijenbanning | Chittenden | Hamrock-Dowson |", "|---|---|---|---|---|---|---|"]
    for M, L in cases:
        r1 = data.get(f"acc_{M:g}_{L:g}_1", {})
        for th in THETAS:
            r = data.get(f"acc_{M:g}_{L:g}_{th:g}", {})
            sv = (f"{r['Hc'] / r1['Hc']:.3f}" if r.get("status") == "converged" and r1.get("status") == "converged"
                  else "-")
            lines.append(f"| {M:g} | {L:g} | {th:g} | {sv} | "
                         f"{nijenbanning_central(M, L, th) / nijenbanning_central(M, L, 1.0):.3f} | "
                         f"{chittenden(M, L, th)[0] / chittenden(M, L, 1.0)[0]:.3f} | "
                         f"{hamrock_dowson_central(M, L, th) / hamrock_dowson_central(M, L, 1.0):.3f} |")
    lines += ["", "Fixed-grid checks, (M, L) = (20, 10):", "", "| run | status | Hc | Hm |", "|---|---|---|---|"]
    for k, r in data.items():
        if k.startswith(("grid_", "box2_")):
            lines.append(f"| {k} | {r.get('status')} | {r.get('Hc')} | {r.get('Hm')} |")
    if any(k.startswith("rigid_") for k in data):
        lines += ["", "Rigid-isoviscous: C(theta) = M^2 Hc = 288 I^2/theta, ratio to theta = 1 on the same scaled "
                  "box; HRI of (2.26) for comparison:", "", "| theta | box | C | C/C(1) | HRI M^2 | HRI ratio |",
                  "|---|---|---|---|---|---|"]
        for box in (1.0, 2.0):
            c1 = 288 * data[f"rigid_1_{box:g}"]["I"] ** 2
            h1 = float(nijenbanning_terms(1.0, 0.0, 1.0)["HRI"])
            for th in THETAS:
                c = 288 * data[f"rigid_{th:g}_{box:g}"]["I"] ** 2 / th
                h = float(nijenbanning_terms(1.0, 0.0, th)["HRI"])
                lines.append(f"| {th:g} | {box:g} | {c:.4g} | {c / c1:.4f} | {h:.4g} | {h / h1:.4f} |")
    tmp = path.with_suffix(".tmp")
    tmp.write_text("\n".join(lines) + "\n")
    os.replace(tmp, path)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
