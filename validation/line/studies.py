"""Validation studies of the line-contact solver. Writes JSON + PNG to build/validation/line/.

    python validation/line/studies.py [--study grid|fit|limits|extremes|cost|all] [--full]

Quick mode (default) runs a subset in a few minutes; ``--full`` runs the whole study.
Every finished case is written to ``build/validation/line/<study>[_quick].json`` at once, so an interrupted
run keeps its work (a rerun recomputes).

1. grid: Hc, Hm, p_spike at (M, L) = (20,10), (100,10), (1000,10) on 257 .. 8193 points;
   observed order and Richardson extrapolation from the three finest converged grids.
2. fit: Hc vs the Moes line fit over M x L, Barus + incompressible and Roelands +
   Dowson-Higginson; each case also on the half grid to estimate its grid error.
3. limits: rigid-isoviscous (deformation off; and L = 0, M small, long inlet) vs Martin's
   2.45/M; high M vs the Hertzian pressure.
4. extremes: the Roelands map of the fit study plus M = 1, 5000 and L = 25, counted.
5. cost: wall time and work units vs N at (100, 10) for V/W and MLMI/FFT; time to Hc within
   1 % and 0.1 % of the extrapolated value.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from tqdm import tqdm  # noqa: E402

from ehl_multigrid.line import solve_line  # noqa: E402
from ehl_multigrid.model.errors import ConvergenceError  # noqa: E402
from ehl_multigrid.model.fits import moes_line_central  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("line")
DPI = 100


def run_case(M: float, L: float, trace: bool = False, **kw) -> dict:
    """One solve; a ConvergenceError is recorded (never hidden) as ``error``."""
    t0 = time.perf_counter()
    log: list[tuple[float, int, float]] = []

    def cb(d):
        log.append((time.perf_counter() - t0, d["points"], d["Hc_venner"] * 8 * M / math.pi))

    keep = kw.pop("keep_fields", False)
    row = {"M": M, "L": L, **{k: v for k, v in kw.items() if isinstance(v, (int, float, str, bool))}}
    try:
        s = solve_line(M, L, callback=cb if trace else None, **kw)
        row.update(Hc=s.Hc, Hm=s.Hm, X_Hm=s.X_Hm, p_spike=s.p_spike, X_spike=s.X_spike,
                   converged=s.converged, cycles=s.cycles, finest_cycles=s.finest_cycles,
                   work_units=s.work_units, load_error=s.load_error, residual=s.residual,
                   wall_s=time.perf_counter() - t0, actions=s.report.extra.get("actions", []))
        if trace:
            row["trace"] = log
        if keep:
            row["X"], row["P"] = s.X.tolist(), s.P.tolist()
    except ConvergenceError as exc:
        row.update(converged=False, error=str(exc).splitlines()[0], wall_s=time.perf_counter() - t0)
    return row


class Store:
    def __init__(self, name: str, full: bool) -> None:
        OUT.mkdir(exist_ok=True)
        self.path = OUT / f"{name}{'' if full else '_quick'}.json"
        self.data: dict = {"mode": "full" if full else "quick", "rows": []}

    def add(self, row: dict) -> None:
        self.data["rows"].append(row)
        self.save()

    def save(self) -> None:
        self.path.write_text(json.dumps(self.data, separators=(",", ":"), default=float))


def richardson(ns, vals):
    """Observed order and extrapolated value from the last three grids (ratio 2)."""
    if len(vals) < 3:
        return math.nan, math.nan
    a, b, c = vals[-3:]
    if (a - b) * (b - c) <= 0 or b == c:
        return math.nan, c
    p = math.log2(abs(a - b) / abs(b - c))
    return p, c + (c - b) / (2**p - 1)


def grid(full: bool) -> dict:
    st = Store("grid", full)
    cases = [(20, 10), (100, 10), (1000, 10)]
    grids = [257, 513, 1025, 2049, 4097, 8193] if full else [257, 513, 1025, 2049]
    for M, L in cases:
        for n in tqdm(grids, desc=f"grid M={M}"):
            if M >= 1000 and n < 1025:
                continue
            st.add(run_case(M, L, points=n))
    summ = []
    fig, axs = plt.subplots(1, 3, figsize=(11, 3.4))
    for ax, (M, L) in zip(axs, cases, strict=True):
        ok = [r for r in st.data["rows"] if r["M"] == M and r.get("converged")]
        ns = [r["points"] for r in ok]
        ent = {"M": M, "L": L, "points": ns}
        for q in ("Hc", "Hm", "p_spike"):
            v = [r[q] for r in ok]
            p, ext = richardson(ns, v)
            ent[q] = v
            ent[f"{q}_order"] = p
            ent[f"{q}_richardson"] = ext
        ext = ent["Hc_richardson"]
        if math.isfinite(ext):
            ent["Hc_error_pct"] = [100 * (v / ext - 1) for v in ent["Hc"]]
            ax.loglog(ns, np.abs(np.array(ent["Hc"]) - ext) / ext, "o-", label="|Hc - Hc_rich|/Hc_rich")
            ax.loglog(ns, 0.5 * (np.array(ns, float) / ns[0]) ** -2 * abs(ent["Hc"][0] - ext) / ext * 2,
                      "k:", label="slope -2")
        ax.set_title(f"M = {M}, L = {L}", fontsize=9)
        ax.set_xlabel("points")
        ax.legend(fontsize=7)
        summ.append(ent)
    fig.tight_layout()
    fig.savefig(OUT / f"grid{'' if full else '_quick'}.png", dpi=DPI)
    plt.close(fig)
    st.data["summary"] = summ
    st.save()
    return {"summary": summ}


def fit_points(M: float) -> int:
    return 2049 if M <= 100 else (4097 if M <= 500 else 8193)


def fit(full: bool) -> dict:
    st = Store("fit", full)
    Ms = [2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000] if full else [5, 20, 100]
    Ls = [0, 2, 5, 10, 15, 20] if full else [0, 5, 10]
    models = (("barus", "incompressible"), ("roelands", "dowson-higginson"))
    for visc, dens in models:
        for M in tqdm(Ms, desc=f"fit {visc}"):
            for L in Ls:
                n = fit_points(M) if full else 1025
                r = run_case(M, L, points=n, viscosity=visc, density=dens)
                r["fit"] = float(moes_line_central(M, L))
                if r.get("converged"):
                    r["dev"] = r["Hc"] / r["fit"] - 1.0
                if r.get("converged") and M < 1000:  # M >= 1000: see the grid study instead
                    half = run_case(M, L, points=(n - 1) // 2 + 1, viscosity=visc, density=dens)
                    if half.get("converged"):
                        # second-order Richardson estimate of the grid error at n points
                        r["grid_error_est"] = (r["Hc"] - half["Hc"]) / 3.0 / r["Hc"]
                st.add(r)
    _fit_maps(st, Ms, Ls, models, full)
    return {k: v for k, v in st.data.items() if k != "rows"}


def fitfine(full: bool) -> dict:
    """High-M columns of the fit study on doubled grids (M = 500: 8193, M >= 1000: 16385),
    so their grid error falls to ~0.5 % (the grid study shows 0.65 % at M = 1000, 8193)."""
    st = Store("fit_fine", full)
    coarse_path = OUT / f"fit{'' if full else '_quick'}.json"
    coarse = json.loads(require(coarse_path, f"python validation/line/studies.py --study fit{' --full' if full else ''}")
                        .read_text())["rows"]
    Ms = [500, 1000, 2000] if full else [500]
    Ls = [0, 2, 5, 10, 15, 20] if full else [10]
    for visc, dens in (("barus", "incompressible"), ("roelands", "dowson-higginson")):
        for M in tqdm(Ms, desc=f"fitfine {visc}"):
            for L in Ls:
                n = 2 * fit_points(M) - 1
                r = run_case(M, L, points=n, viscosity=visc, density=dens)
                r["fit"] = float(moes_line_central(M, L))
                c = next((x for x in coarse if x.get("viscosity") == visc and x["M"] == M and x["L"] == L), {})
                if r.get("converged"):
                    r["dev"] = r["Hc"] / r["fit"] - 1.0
                    if c.get("converged"):
                        r["grid_error_est"] = (r["Hc"] - c["Hc"]) / 3.0 / r["Hc"]
                st.add(r)
    return {"rows": len(st.data["rows"])}


def _fit_maps(st: Store, Ms, Ls, models, full: bool) -> None:
    fig, axs = plt.subplots(1, 2, figsize=(11, 4))
    summary = {}
    for ax, (visc, dens) in zip(axs, models, strict=True):
        D = np.full((len(Ls), len(Ms)), np.nan)
        for r in st.data["rows"]:
            if r.get("viscosity") == visc and "dev" in r:
                D[Ls.index(r["L"]), Ms.index(r["M"])] = 100 * r["dev"]
        im = ax.imshow(D, origin="lower", cmap="RdBu_r", vmin=-40, vmax=40, aspect="auto")
        for i in range(len(Ls)):
            for j in range(len(Ms)):
                ax.text(j, i, "fail" if np.isnan(D[i, j]) else f"{D[i, j]:.0f}", ha="center",
                        va="center", fontsize=6)
        ax.set_xticks(range(len(Ms)), [str(m) for m in Ms], fontsize=7)
        ax.set_yticks(range(len(Ls)), [str(v) for v in Ls], fontsize=7)
        ax.set_xlabel("M")
        ax.set_ylabel("L")
        ax.set_title(f"{visc} + {dens}: (Hc/Hc_fit - 1) [%]", fontsize=9)
        fig.colorbar(im, ax=ax)
        ok = [r for r in st.data["rows"] if r.get("viscosity") == visc and "dev" in r]
        if ok:
            worst = max(ok, key=lambda r: abs(r["dev"]))
            summary[visc] = {
                "n_cases": sum(r.get("viscosity") == visc for r in st.data["rows"]),
                "n_converged": len(ok),
                "mean_dev_pct": 100 * float(np.mean([r["dev"] for r in ok])),
                "worst_dev_pct": 100 * worst["dev"], "worst_at": [worst["M"], worst["L"]],
                "over_5pct": [[r["M"], r["L"], round(100 * r["dev"], 2)] for r in ok if abs(r["dev"]) > 0.05],
                "failed": [[r["M"], r["L"], r.get("error", "")] for r in st.data["rows"]
                           if r.get("viscosity") == visc and not r.get("converged")],
            }
    fig.tight_layout()
    fig.savefig(OUT / f"fit_map{'' if full else '_quick'}.png", dpi=DPI)
    plt.close(fig)
    st.data["summary"] = summary
    st.save()


def limits(full: bool) -> dict:
    st = Store("limits", full)
    grids = [1025, 2049, 4097] if full else [1025, 2049]
    # rigid, isoviscous: deformation off; Hc M must tend to Martin's 2.45 (2.4494)
    for M in ([5, 10, 20] if full else [10]):
        for n in grids:
            r = run_case(M, 0.0, points=n, elastic=False, xmin=-6.0, xmax=1.0, fmg_start_points=257)
            r["case"] = "rigid"
            st.add(r)
    # elastic, isoviscous, small M, long inlet: the rigid limit is approached as M -> 0
    for M in ([0.5, 1.0] if full else [0.5]):
        r = run_case(M, 0.0, points=4097 if full else 2049, xmin=-60.0, xmax=10.0)
        r["case"] = "elastic_small_M"
        st.add(r)
    # high M: the pressure approaches Hertz
    for M in ([1000, 2000, 5000] if full else [1000]):
        r = run_case(M, 10.0, points=8193 if full else 4097, keep_fields=True)
        if r.get("converged"):
            X, P = np.array(r.pop("X")), np.array(r.pop("P"))
            inside = np.abs(X) < 0.9
            hz = np.sqrt(np.clip(1 - X**2, 0, None))
            r["max_dev_from_hertz_inner"] = float(np.max(np.abs(P - hz)[inside]))
            r["l1_dev_from_hertz"] = float(np.sum(np.abs(P - hz)) * (X[1] - X[0]) / (math.pi / 2))
        r["case"] = "high_M"
        st.add(r)
    rows = st.data["rows"]
    summ = {"rigid": [], "elastic_small_M": [], "high_M": []}
    for M in sorted({r["M"] for r in rows if r["case"] == "rigid"}):
        ok = [r for r in rows if r["case"] == "rigid" and r["M"] == M and r.get("converged")]
        ns, v = [r["points"] for r in ok], [r["Hc"] * M for r in ok]
        p, ext = richardson(ns, v) if len(v) >= 3 else (math.nan, v[-1] if v else math.nan)
        summ["rigid"].append({"M": M, "points": ns, "HcM": v, "HmM": [r["Hm"] * M for r in ok],
                              "order": p, "HcM_extrapolated": ext, "vs_2.45_pct": 100 * (ext / 2.45 - 1)})
    for r in rows:
        if r["case"] == "elastic_small_M" and r.get("converged"):
            summ["elastic_small_M"].append({"M": r["M"], "HcM": r["Hc"] * r["M"], "HmM": r["Hm"] * r["M"]})
        if r["case"] == "high_M" and r.get("converged"):
            summ["high_M"].append({k: r[k] for k in ("M", "L", "points", "Hc", "Hm", "p_spike",
                                                   "max_dev_from_hertz_inner", "l1_dev_from_hertz")})
    st.data["summary"] = summ
    st.save()
    return summ


def extremes(full: bool) -> dict:
    st = Store("extremes", full)
    fitrows = []
    fp = OUT / f"fit{'' if full else '_quick'}.json"
    if fp.is_file():
        fitrows = [r for r in json.loads(fp.read_text())["rows"] if r.get("viscosity") == "roelands"]
    Ms = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000] if full else [1, 20, 5000]
    Ls = [0, 2, 5, 10, 15, 20, 25] if full else [0, 25]
    done = {(r["M"], r["L"]) for r in fitrows}
    for r in fitrows:
        st.add({**r, "source": "fit study"})
    for M in tqdm(Ms, desc="extremes"):
        for L in Ls:
            if (M, L) in done:
                continue
            r = run_case(M, L, points=fit_points(M) if full else 1025)
            r["source"] = "extremes"
            st.add(r)
    rows = st.data["rows"]
    st.data["summary"] = {
        "cases": len(rows), "converged": sum(bool(r.get("converged")) for r in rows),
        "failed": [[r["M"], r["L"], r.get("points"), r.get("error", "not converged")]
                   for r in rows if not r.get("converged")],
        "with_actions": sum(bool(r.get("actions")) for r in rows),
        "max_wall_s": max(r["wall_s"] for r in rows),
    }
    st.save()
    return st.data["summary"]


def cost(full: bool) -> dict:
    st = Store("cost", full)
    grids = [257, 513, 1025, 2049, 4097, 8193, 16385] if full else [257, 513, 1025, 2049]
    for dfm in ("mlmi", "fft"):  # untimed warm-up: numba cache load, MLMI plans, FFT plans
        for n in grids:
            run_case(100.0, 10.0, points=n, deformation=dfm)
    for cyc in ("V", "W"):
        for dfm in ("mlmi", "fft"):
            for n in tqdm(grids, desc=f"cost {cyc} {dfm}"):
                st.add(run_case(100.0, 10.0, trace=True, points=n, cycle=cyc, deformation=dfm))
    rows = st.data["rows"]
    # extrapolated Hc from the V/FFT grid sequence
    seq = [r for r in rows if r["cycle"] == "V" and r["deformation"] == "fft" and r.get("converged")]
    _, ext = richardson([r["points"] for r in seq], [r["Hc"] for r in seq])
    summ = {"Hc_extrapolated": ext, "paths": []}
    fig, ax = plt.subplots(figsize=(6, 4))
    for cyc in ("V", "W"):
        for dfm in ("mlmi", "fft"):
            sel = [r for r in rows if r["cycle"] == cyc and r["deformation"] == dfm and r.get("converged")]
            if not sel:
                continue
            N = np.array([r["points"] for r in sel], float)
            t = np.array([r["wall_s"] for r in sel])
            wu = np.array([r["work_units"] for r in sel])
            big = N >= 1025
            slope = float(np.polyfit(np.log(N[big]), np.log(t[big]), 1)[0]) if big.sum() >= 2 else math.nan
            ent = {"cycle": cyc, "deformation": dfm, "points": N.tolist(), "wall_s": t.tolist(),
                   "work_units": wu.tolist(), "time_exponent_N>=1025": slope,
                   "time_over_NlogN_us": (t / (N * np.log2(N)) * 1e6).tolist()}
            for tol in (0.01, 0.001):
                best = math.inf
                for r in sel:  # first moment a finest-grid cycle has Hc within tol
                    for tt, n, hc in r["trace"]:
                        if n == r["points"] and abs(hc / ext - 1) <= tol:
                            best = min(best, tt)
                            break
                ent[f"time_to_{tol:g}"] = best if math.isfinite(best) else None
            summ["paths"].append(ent)
            ax.loglog(N, t, "o-", label=f"{cyc} {dfm} (slope {slope:.2f})")
    ax.set_xlabel("points")
    ax.set_ylabel("wall time [s]")
    ax.set_title("(M, L) = (100, 10): cost to converge", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / f"cost{'' if full else '_quick'}.png", dpi=DPI)
    plt.close(fig)
    for r in rows:
        r.pop("trace", None) if r["points"] < 1025 else None
    st.data["summary"] = summ
    st.save()
    return summ


STUDIES = {"grid": grid, "fit": fit, "limits": limits, "extremes": extremes, "cost": cost,
           "fitfine": fitfine}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--study", default="all", choices=[*STUDIES, "all"])
    ap.add_argument("--full", action="store_true", help="the whole study (about 30-40 min)")
    a = ap.parse_args()
    for name in ([k for k in STUDIES if k != "fitfine"] if a.study == "all" else [a.study]):
        t = time.perf_counter()
        res = STUDIES[name](a.full)
        print(f"{name}: {time.perf_counter() - t:.0f} s")
        print(json.dumps(res, default=float)[:3000])


if __name__ == "__main__":
    main()
