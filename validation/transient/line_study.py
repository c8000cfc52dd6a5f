"""Validation of the transient line-contact solver (ehl_multigrid.transient).

Parts (``--part``): ``steady`` (zero feature against the core steady solution; start-up from
another speed), ``time`` (BDF2/Euler time-step refinement at a fixed grid), ``grid`` (grid
refinement at Courant number 1), ``waviness`` (amplitude reduction Ad/Ai against Venner &
Lubrecht's wavelength parameter, pure rolling), ``bump`` (dent and bump passing under rolling
and with slip: profiles at several positions), ``cost`` (time per step against grid size),
``cavitation`` (a deep dent under rolling and SRR -+0.5: projection against mass-conserving
cavitation), ``adaptive`` (adaptive time steps: the film error over a dent passage against a
run at a 64 times smaller fixed step, and the time error the front door states for it),
``starved`` (a starved inlet in time: dents through a starved contact, and the film's response
to a step in the supplied layer), ``control`` (the front door's time step refined to a target:
the runs made, wall time, stated time part against the true time error).
Each part writes ``build/validation/transient/<part>.json`` and a PNG; ``--quick`` runs a smaller set into ``build/validation/transient/quick/``.

Moes-only problems (default oil of the core), Roelands + Dowson-Higginson, domain
X in [-4.5, 1.5] (Venner & Lubrecht's box) unless stated.
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import common  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from ehl_multigrid.line.problem import LineProblem  # noqa: E402
from ehl_multigrid.line.solver import solve_line_problem  # noqa: E402
from ehl_multigrid.model.fits import moes_line_central  # noqa: E402
from ehl_multigrid.transient import (  # noqa: E402
    Bump,
    Waviness,
    adaptive_time_error,
    solve_transient_line,
    time_error,
    transient_options,
)
from ehl_multigrid.transient.accuracy import tighter_run_options  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("transient")


def save(name: str, data: dict) -> None:
    common.write_json(OUT, name, data)
    print(f"wrote {OUT / name}.json")


def problem(M: float, L: float, xmin: float = -4.5) -> LineProblem:
    return LineProblem.from_moes(M, L, xmin=xmin)


def hc_fit(M: float, L: float) -> float:
    """Moes-fit central film in Venner units (H = H_moes pi/(8 M))."""
    return float(moes_line_central(M, L)) * math.pi / (8.0 * M)


# -- steady limit --------------------------------------------------------------------------
def part_steady(quick: bool) -> None:
    pb = problem(20, 10)
    rows = []
    for n in ((257,) if quick else (257, 1025)):
        res = solve_transient_line(pb, Bump(0.0, 0.5, x0=-3.0), dt=0.05, steps=40, points=n,
                                   snapshot_every=40)
        st = res.steady
        rows.append({"points": n, "Hc_core": st.Hc_venner, "Hm_core": st.Hm_venner,
                     "dHc_rel_max": float(np.max(np.abs(res.Hc / st.Hc_venner - 1))),
                     "dHm_rel_max": float(np.max(np.abs(res.Hm / st.Hm_venner - 1))),
                     "dP_max": float(np.max(res.dP)), "cycles_mean": res.summary()["cycles_mean"]})
        print(rows[-1])
    # start-up: steady film at 1.2x M (same load, lambda changed: a speed step), then run
    n = 257
    M2 = 1.2 * pb.M
    other = problem(M2, pb.L * math.sqrt(pb.M / M2))
    opts = transient_options(points=n)
    start = solve_line_problem(other, opts)
    target = solve_line_problem(pb, opts).Hc_venner
    res = solve_transient_line(pb, None, dt=0.05, steps=400, points=n, initial=(start.P, start.H0),
                               snapshot_every=1000)
    err = np.abs(res.Hc / target - 1.0)
    settle = {f"T={T:g}": float(np.interp(T, res.T, err)) for T in (0, 1, 2, 4, 6, 8, 12, 16, 20)}
    print(settle)
    save("steady", {"zero_feature": rows, "startup": {"points": n, "M_start": M2, "Hc_target": target,
                                                      "relative_error_at": settle,
                                                      "T": res.T.tolist(), "Hc": res.Hc.tolist()}})
    common.plot_startup(OUT / "steady_startup.png", res.T, err, "T = t u_m / b",
                 "Start-up from the steady film at 1.2 M (M = 20, L = 10, 257 points)", which="both")


# -- time-step refinement ------------------------------------------------------------------
def part_time(quick: bool) -> None:
    pb = problem(20, 10)
    n = 257
    feat = Bump(0.02, 0.8, x0=-2.4, shape="gaussian")
    T_end = 3.0
    dts = (0.04, 0.02, 0.01) if quick else (0.04, 0.02, 0.01, 0.005)
    out = {}
    for scheme in ("bdf2", "euler"):
        runs = []
        for dt in dts:
            t0 = time.perf_counter()
            res = solve_transient_line(pb, feat, dt=dt, steps=int(round(T_end / dt)), points=n,
                                       scheme=scheme, tol=1e-8, tol_load=1e-10, snapshot_every=10**5)
            every = int(round(dts[0] / dt))
            runs.append({"dt": dt, "Hc": res.Hc[::every], "H": res.snapshots[res.steps]["H"],
                         "wall_s": time.perf_counter() - t0})
            print(scheme, dt, res.Hc[-1], runs[-1]["wall_s"])
        d_series = common.successive(runs, lambda a, b: np.max(np.abs(a["Hc"] - b["Hc"])))
        d_film = common.successive(runs, lambda a, b: np.mean(np.abs(a["H"] - b["H"])))
        out[scheme] = {"dt": list(dts), "max_dHc_series": d_series, "mean_dH_final": d_film,
                       "order_Hc_series": common.log2_ratios(d_series), "order_H_final": common.log2_ratios(d_film),
                       "T": (np.arange(len(runs[-1]["Hc"])) * dts[0]).tolist(),
                       "Hc_finest": runs[-1]["Hc"].tolist()}
        print(scheme, out[scheme]["order_Hc_series"], out[scheme]["order_H_final"])
    save("time", {"M": 20, "L": 10, "points": n, "feature": feat.describe(), "T_end": T_end, **out})
    fig, ax = plt.subplots(figsize=(6, 4))
    for scheme, mk in (("bdf2", "o-"), ("euler", "s--")):
        ax.loglog(dts[:-1], out[scheme]["max_dHc_series"], mk, label=f"{scheme}: max |Hc(dT) - Hc(dT/2)|")
    ref = np.array(dts[:-1])
    ax.loglog(ref, out["bdf2"]["max_dHc_series"][0] * (ref / ref[0]) ** 2, "k:", label="slope 2")
    ax.loglog(ref, out["euler"]["max_dHc_series"][0] * (ref / ref[0]), "k-.", label="slope 1")
    ax.set_xlabel("dT")
    ax.set_ylabel("successive difference of Hc(T), T in [0, 3]")
    common.finish_figure(fig, ax, OUT / "time_convergence.png")


# -- grid refinement -----------------------------------------------------------------------
def part_grid(quick: bool) -> None:
    pb = problem(20, 10)
    feat = Bump(0.02, 0.8, x0=-2.4, shape="gaussian")
    T_end = 3.0
    grids = (129, 257, 513) if quick else (129, 257, 513, 1025, 2049)
    dt = 6.0 / 256  # the Courant-1 step of 257 points; the same dT on every grid
    runs = []
    for n in grids:
        t0 = time.perf_counter()
        res = solve_transient_line(pb, feat, dt=dt, steps=int(round(T_end / dt)), points=n,
                                   tol=1e-7, tol_load=1e-9, snapshot_every=10**5)
        runs.append({"points": n, "Hc": res.Hc, "Hm": res.Hm, "H": res.snapshots[res.steps]["H"][:: (n - 1) // 128],
                     "wall_s": time.perf_counter() - t0, "Hc_steady": res.steady.Hc_venner})
        print(n, res.Hc[-1], res.Hm[-1], runs[-1]["wall_s"])
    d_Hc = common.successive(runs, lambda a, b: np.max(np.abs(a["Hc"] - b["Hc"])))
    d_Hm = common.successive(runs, lambda a, b: np.max(np.abs(a["Hm"] - b["Hm"])))
    d_H = common.successive(runs, lambda a, b: np.mean(np.abs(a["H"] - b["H"])))
    data = {"M": 20, "L": 10, "feature": feat.describe(), "dt": dt, "T_end": T_end, "points": list(grids),
            "Hc_final": [float(r["Hc"][-1]) for r in runs], "Hm_final": [float(r["Hm"][-1]) for r in runs],
            "Hc_steady": [r["Hc_steady"] for r in runs],
            "max_dHc_series": d_Hc, "max_dHm_series": d_Hm, "mean_dH_final_on_129": d_H,
            "order_Hc_series": common.log2_ratios(d_Hc), "order_Hm_series": common.log2_ratios(d_Hm),
            "order_H_final": common.log2_ratios(d_H),
            "wall_s": [r["wall_s"] for r in runs]}
    print(data["order_Hc_series"], data["order_Hm_series"], data["order_H_final"])
    save("grid", data)
    fig, ax = plt.subplots(figsize=(6, 4))
    T = np.arange(len(runs[0]["Hc"])) * dt
    for r in runs:
        ax.plot(T, r["Hc"], label=f"{r['points']} points")
    ax.set_xlabel("T = t u_m / b")
    ax.set_ylabel("Hc(T)")
    ax.set_title("Gaussian bump A = 0.02, W = 0.8 entering the contact (M = 20, L = 10)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "grid_convergence.png", dpi=120)


# -- waviness amplitude reduction ----------------------------------------------------------
WAVINESS_CASES = {
    (20.0, 10.0): (0.25, 0.5, 1.0, 2.0, 3.0),
    (10.0, 5.0): (0.5, 1.0, 2.0, 4.0),
    (50.0, 10.0): (0.5, 1.0, 2.0),
}


#: checks of the measured points: one grid finer, and a longer inlet (the core's default box)
WAVINESS_CHECKS = [(20.0, 10.0, 1.0, -4.5, 513), (20.0, 10.0, 2.0, -4.5, 513),
                   (20.0, 10.0, 2.0, -10.0, None), (10.0, 5.0, 1.0, -10.0, None),
                   (10.0, 5.0, 0.5, -4.5, 1025)]


def part_waviness(quick: bool) -> None:
    cases = {(20.0, 10.0): (0.5, 2.0)} if quick else WAVINESS_CASES
    path = OUT / "waviness.json"
    rows = json.loads(path.read_text())["rows"] if path.exists() and not quick else []
    done = {(r["M"], r["L"], r["wavelength"], r["points"], r["xmin"]) for r in rows}
    todo = [(M, L, lam, -4.5) for (M, L), lams in cases.items() for lam in lams]
    todo = [(M, L, lam, xmin, None) for M, L, lam, xmin in todo]
    if not quick:
        todo += WAVINESS_CHECKS
    for M, L, lam, xmin, n_given in todo:
        n = 257
        while (1.5 - xmin) / (n - 1) > lam / 24.0:
            n = 2 * n - 1
        n = n_given or n
        if (M, L, lam, n, xmin) in done:
            continue
        Ai = 0.05 * hc_fit(M, L)
        t0 = time.perf_counter()
        res = solve_transient_line(problem(M, L, xmin), Waviness(Ai, lam), points=n, snapshot_every=10**5)
        s = res.summary()
        row = {"M": M, "L": L, "wavelength": lam, "xmin": xmin, "points": n, "Ai": Ai,
               "nabla": common.nabla(lam, M, L), "Ad_over_Ai": s["Ad_over_Ai"],
               "Ad_over_Ai_previous_period": common.previous_period_amplitude(res, lam) / Ai,
               "curve": float(common.amplitude_curve(np.array(common.nabla(lam, M, L)))),
               "Hc_steady": s["Hc_steady"], "steps": s["steps"], "dt": s["dt"],
               "cycles_mean": s["cycles_mean"], "wall_s": time.perf_counter() - t0}
        print(row)
        rows.append(row)
        save("waviness", {"rows": rows})
    save("waviness", {"rows": rows})
    fig, ax = common.amplitude_figure("1/(1 + 0.15 nabla + 0.015 nabla^2)")
    for (M, L), mk in zip(WAVINESS_CASES, ("o", "s", "^"), strict=False):
        sel = [r for r in rows if r["M"] == M and r["L"] == L and r["xmin"] == -4.5]
        ax.plot([r["nabla"] for r in sel], [r["Ad_over_Ai"] for r in sel], mk, label=f"M = {M:g}, L = {L:g}")
    sel = [r for r in rows if r["xmin"] != -4.5]
    if sel:
        ax.plot([r["nabla"] for r in sel], [r["Ad_over_Ai"] for r in sel], "x", ms=9, label="inlet at X = -10")
    common.finish_amplitude_figure(fig, ax, OUT / "waviness_amplitude.png", "b", "X = 0",
                            "Waviness on one surface, pure rolling")


# -- bump and dent passing -----------------------------------------------------------------
BUMP_CASES = (("dent", -1, 0.0), ("dent", -1, 1.0), ("dent", -1, -1.0), ("bump", 1, 0.0), ("bump", 1, 1.0))
POSITIONS = (-1.0, -0.5, 0.0, 0.5, 1.0)


def part_bump(quick: bool) -> None:
    M, L = 20.0, 10.0
    n = 257 if quick else 513
    Hc = hc_fit(M, L)
    A = 0.5 * Hc
    rows = []
    fig, axes = plt.subplots(len(BUMP_CASES), 2, figsize=(11, 2.6 * len(BUMP_CASES)), sharex=True)
    for (name, sign, S), ax in zip(BUMP_CASES, axes, strict=False):
        feat = Bump(sign * A, 0.5, x0=-3.0)
        t0 = time.perf_counter()
        res = solve_transient_line(problem(M, L), feat, slide_roll=S, points=n, snapshot_every=1)
        s = res.summary()
        wall = time.perf_counter() - t0
        X = res.X
        prof = {}
        for xf in POSITIONS:
            k = int(np.argmin(np.abs(res.xf - xf)))
            snap = res.snapshots[int(res.step[k])]
            prof[f"{xf:g}"] = {"T": float(res.T[k]), "xf": float(res.xf[k]),
                               "Hc": float(res.Hc[k]), "Hm": float(res.Hm[k]), "Pmax": float(res.Pmax[k]),
                               "H_at_feature": float(np.interp(res.xf[k], X, snap["H"])),
                               "H_smooth_at_feature": float(np.interp(res.xf[k], X, res.steady.H))}
            ax[0].plot(X, snap["H"], lw=1, label=f"xf = {res.xf[k]:.2f}")
            ax[1].plot(X, snap["P"], lw=1)
        ax[0].plot(X, res.steady.H, "k:", lw=1, label="smooth")
        ax[1].plot(X, res.steady.P, "k:", lw=1)
        ax[0].set_ylim(0, 3 * Hc)
        ax[0].set_ylabel(f"H ({name}, S = {S:g})")
        ax[1].set_ylabel("P")
        ax[0].legend(fontsize=6, ncol=3)
        # film behind the dent: largest film rise above the smooth film within 1.5 of the
        # feature, upstream side (X < xf), while the feature is in the contact
        rise = []
        for k in range(len(res.T)):
            xf = res.xf[k]
            if not -1.0 <= xf <= 1.0:
                continue
            snap = res.snapshots[int(res.step[k])]
            m = (X < xf) & (X > xf - 1.5) & (np.abs(X) <= 1.0)
            if m.any():
                rise.append(float(np.max(snap["H"][m] - res.steady.H[m])))
        row = {"case": name, "amplitude": feat.amplitude, "width": feat.width, "slide_roll": S,
               "feature_speed": res.speed, "points": n, "dt": res.dt, "steps": s["steps"],
               "Hc_steady": s["Hc_steady"], "Hm_steady": s["Hm_steady"],
               "Hc_min": s["Hc_min"], "Hc_max": s["Hc_max"], "Hm_min": s["Hm_min"],
               "dP_max": s["dP_max"], "Pmax_max": s["Pmax_max"], "Ad_over_Ai": s["Ad_over_Ai"],
               "film_rise_upstream_max": max(rise) if rise else math.nan,
               "cycles_mean": s["cycles_mean"], "cycles_max": s["cycles_max"],
               "wall_per_step_s": s["wall_per_step_s"], "wall_s": wall, "profiles": prof}
        print({k: v for k, v in row.items() if k != "profiles"})
        rows.append(row)
    axes[-1][0].set_xlabel("X")
    axes[-1][1].set_xlabel("X")
    for ax in axes:
        ax[0].set_xlim(-2, 1.5)
    fig.suptitle(f"Cosine-Gaussian feature |A| = 0.5 Hc, W = 0.5 on body 1 (M = 20, L = 10, {n} points)")
    fig.tight_layout()
    fig.savefig(OUT / "bump_profiles.png", dpi=110)
    save("bump", {"M": M, "L": L, "rows": rows})


# -- cost per step -------------------------------------------------------------------------
def part_cost(quick: bool) -> None:
    pb = problem(20, 10)
    rows = []
    for n in ((257, 513) if quick else (257, 513, 1025, 2049, 4097)):
        h = 6.0 / (n - 1)
        steps = 60
        feat = Bump(0.5 * hc_fit(20, 10), 0.5, x0=-0.5 - steps * h / 2)  # passes X = 0 mid-run
        res = solve_transient_line(pb, feat, dt=h, steps=steps, points=n, snapshot_every=10**5)
        s = res.summary()
        rows.append({"points": n, "dt": h, "steps": steps, "wall_per_step_s": s["wall_per_step_s"],
                     "cycles_mean": s["cycles_mean"], "cycles_max": s["cycles_max"],
                     "work_units_per_step": s["work_units_per_step"], "setup_s": s["setup_s"]})
        print(rows[-1])
    save("cost", {"M": 20, "L": 10, "rows": rows})


def _dent_profiles(res, W: float, Hs: np.ndarray) -> list[dict]:
    """Per kept step with the dent inside ``|X| <= 1``: the film's largest rise (the bump) and
    fall (the reduction) over the smooth film ``Hs`` in ``|X| <= 1`` away from the dent
    (``|X - xf| > 0.6 W``), and the minimum film there."""
    X, rows = res.X, []
    for k in sorted(res.snapshots):
        xf = float(res.xf[k])
        if not -1.0 <= xf <= 1.0:
            continue
        m = (np.abs(X) <= 1.0) & (np.abs(X - xf) > 0.6 * W)
        d = (res.snapshots[k]["H"] - Hs)[m]
        rows.append({"step": int(k), "xf": xf, "bump": float(d.max()), "reduction": float(d.min()),
                     "Hmin": float(res.snapshots[k]["H"][np.abs(X) <= 1.0].min())})
    return rows


def part_cavitation(quick: bool) -> None:
    """A dent 5.3x the central film deep through the contact under pure rolling and SRR -0.5 /
    +0.5 (S = -1 / +1), projection against mass-conserving cavitation, at the step tolerance
    1e-6 (the default) and 1e-8: the film bump behind the dent and the reduction after it,
    Hm, the mass error per step, stalled steps and wall time; profiles at four positions."""
    pb = problem(20, 10)
    n = 129 if quick else 257
    A, W = -0.45, 0.5
    runs, fig_rows = [], []
    for S in (0.0, -1.0, 1.0):
        for tol in ((1e-6,) if quick else (1e-6, 1e-8)):
            pair = {}
            for cav in ("projection", "mass-conserving"):
                speed = 1.0 + 0.5 * S
                x0 = -1.6
                steps = int(round((1.1 - x0) / speed / (6.0 / (n - 1) / max(speed, 1.0))))
                t = time.perf_counter()
                try:
                    res = solve_transient_line(pb, Bump(A, W, x0=x0), slide_roll=S, points=n, steps=steps,
                                               cavitation=cav, tol=tol, snapshot_every=4)
                except Exception as exc:  # a failed run is a result of the study
                    part = getattr(exc, "partial", None)
                    runs.append({"S": S, "tol": tol, "cavitation": cav, "failed": str(exc).splitlines()[0],
                                 "steps_done": part.steps if part is not None else 0})
                    print(runs[-1])
                    continue
                wall = time.perf_counter() - t
                err = np.asarray(res.series["mass_error"][1:])
                prof = _dent_profiles(res, W, res.snapshots[0]["H"])
                row = {"S": S, "SRR": S / 2, "tol": tol, "cavitation": cav, "points": n, "steps": steps,
                       "dt": res.dt, "wall_s": wall, "stalled": int(np.sum(res.stalled)),
                       "substeps_gt1": int(np.sum(np.asarray(res.series["substeps"]) > 1)),
                       "Hm_min": float(res.Hm.min()), "Hc_min": float(res.Hc.min()),
                       "bump_max": max(r["bump"] for r in prof), "reduction_min": min(r["reduction"] for r in prof),
                       "mass_error_max": float(np.nanmax(np.abs(err))) if np.any(np.isfinite(err)) else None,
                       "mass_error_mean": float(np.nanmean(err)) if np.any(np.isfinite(err)) else None,
                       "profiles": prof}
                runs.append(row)
                pair[cav] = res
                print({k: v for k, v in row.items() if k != "profiles"})
            if len(pair) == 2 and tol == 1e-6:
                fig_rows.append((S, pair))
    save("cavitation", {"M": 20, "L": 10, "dent": {"amplitude": A, "width": W}, "runs": runs})
    if fig_rows:
        fig, axes = plt.subplots(len(fig_rows), 4, figsize=(16, 3.2 * len(fig_rows)), squeeze=False)
        for row, (S, pair) in zip(axes, fig_rows, strict=False):
            pr, mc = pair["projection"], pair["mass-conserving"]
            keys = [k for k in sorted(pr.snapshots) if -1.0 <= pr.xf[k] <= 1.0]
            for ax, k in zip(row, keys[:: max(1, len(keys) // 4)][:4], strict=False):
                ax.plot(pr.X, pr.snapshots[k]["H"], label="projection")
                ax.plot(mc.X, mc.snapshots[k]["H"], "--", label="mass-conserving")
                ax.plot(mc.X, mc.snapshots[k]["P"] * 0.1, ":", label="P/10 (m.-c.)")
                ax.set_xlim(-1.5, 1.5)
                ax.set_ylim(0.0, 0.2)
                ax.set_title(f"S = {S:g}, dent at X = {pr.xf[k]:.2f}")
            row[0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(OUT / "cavitation_profiles.png", dpi=110)
        plt.close(fig)


#: the adaptive part's dents: (amplitude, slip S, start X, output steps of 0.04)
ADAPTIVE_CASES = ((-0.1, 1.0, -1.2, 30), (-0.12, 0.0, -1.6, 45))


def part_adaptive(quick: bool) -> None:
    """Adaptive steps (``time_tol``) through a dent passage, 65 points, mass-conserving, step
    tolerance 1e-9: the largest error of Hc(T) and Hm(T) over the run against fixed steps 64
    times smaller, relative to the smooth film, and the time error :func:`adaptive_time_error`
    states for it (a second run at an eighth of the tolerance and half the output step)."""
    pb = problem(20, 10)
    rows = []
    for amp, S, x0, n_out in ADAPTIVE_CASES[:1] if quick else ADAPTIVE_CASES:
        def run(steps: int, tt: float | None, dt: float = 0.04, amp=amp, S=S, x0=x0):
            return solve_transient_line(pb, Bump(amp, 0.5, x0=x0), points=65, dt=dt, steps=steps,
                                        slide_roll=S, cavitation="mass-conserving", time_tol=tt,
                                        snapshot_every=10**5, tol=1e-9, tol_load=1e-10)

        ref = run(n_out * 64, None, 0.04 / 64)
        refs = {"Hc": ref.Hc[::64], "Hm": ref.Hm[::64]}
        for tt in ((1e-2,) if quick else (3e-2, 1e-2, 1e-3, 1e-4)):
            t = time.perf_counter()
            a = run(n_out, tt)
            wall = time.perf_counter() - t
            o = tighter_run_options(a, tt)
            b = run(o["steps"], o["time_tol"], o["dt"])
            est = adaptive_time_error(a, b)
            true = {k: float(np.max(np.abs(getattr(a, k) - refs[k])) / ref.steady_film(k)) for k in refs}
            rows.append({"amplitude": amp, "S": S, "x0": x0, "output_steps": n_out, "time_tol": tt,
                         "solves": int(np.sum(a.series["substeps"][1:])),
                         "solves_second_run": int(np.sum(b.series["substeps"][1:])), "wall_s": wall,
                         "true_Hc": true["Hc"], "true_Hm": true["Hm"], "est_Hc": est["Hc"], "est_Hm": est["Hm"],
                         "true_over_est_Hc": true["Hc"] / est["Hc"], "true_over_est_Hm": true["Hm"] / est["Hm"]})
            print(rows[-1])
    save("adaptive" + ("_quick" if quick else ""), {"M": 20, "L": 10, "points": 65, "rows": rows})


#: the starved part: the supplied layer (Venner units; the flooded contact carries about 0.09)
STARVED_HOIL = 0.05
#: dents through the starved contact: (depth, slip S)
STARVED_DENTS = ((0.1, 0.0), (0.1, 1.0), (0.2, 0.0), (0.2, 1.0))
#: supply steps: (layer after the step, end time)
SUPPLY_STEPS = ((0.025, 8.0), (0.075, 10.0))


def part_starved(quick: bool) -> None:
    """Mass-conserving runs fed a layer ``STARVED_HOIL`` at the inlet, 257 points (129 quick),
    default steps and tolerances: (1) dents from X = -1.6 to 1.1 through the starved contact,
    the film's extremes, the mass error and stalls; (2) the supply stepped at T = 0.05 to a
    thinner and a thicker layer, Hc(T) against the new starved steady film."""
    pb = problem(20, 10)
    n = 129 if quick else 257
    Hc0, Hm0, dents = common.starved_dents(solve_transient_line, pb, Bump, STARVED_HOIL, n,
                                           STARVED_DENTS[:1] if quick else STARVED_DENTS)
    steps = common.supply_steps(solve_transient_line, pb, STARVED_HOIL, n,
                                SUPPLY_STEPS[:1] if quick else SUPPLY_STEPS)
    save("starved" + ("_quick" if quick else ""), {"M": 20, "L": 10, "hoil": STARVED_HOIL, "Hc_starved": Hc0,
                                                   "Hm_starved": Hm0, "dents": dents, "supply_steps": steps})


#: the control part: dents through page63_line_2000N (depth in metres, target), from dT = CONTROL_DT
CONTROL_CASES = ((1e-8, 0.005), (2e-8, 0.01), (2e-8, 0.005))
CONTROL_DT = 0.01171875


def part_control(quick: bool) -> None:
    """The front door with a target and ``time_error`` (the accuracy controller halving the
    time step): page63_line_2000N, 129 points, a dent of width 100 um from X = -1.5 to T = 1,
    first step CONTROL_DT. For each target: the runs made (points, dT), wall time, the stated
    time part of the answer, and its true time error against a run at a quarter of its step and
    against a run at 1/32 of CONTROL_DT (relative to the smooth film, as stated)."""
    import ehl_multigrid as ehl
    from ehl_multigrid import Scene, load_scene
    from ehl_multigrid.transient import solve as line_solve

    calls: list[tuple[int, float]] = []
    original = line_solve.solve_transient_line

    def spy(*args, **kw):
        calls.append((kw.get("points"), kw.get("dt")))
        return original(*args, **kw)

    line_solve.solve_transient_line = spy
    rows = []
    refs: dict[float, object] = {}
    for amp, acc in CONTROL_CASES[:1] if quick else CONTROL_CASES:
        d = load_scene("page63_line_2000N").to_dict()
        d["feature"] = {"kind": "dent", "amplitude": amp, "width": 1e-4, "x0": -1.5}
        scene = Scene.from_dict(d)

        def run(dt: float, steps: int, scene=scene):
            return ehl.solve(scene, physics="transient", accuracy=None,
                             options={"points": 129, "dt": dt, "steps": steps}).raw

        calls.clear()
        t = time.perf_counter()
        sol = ehl.solve(scene, physics="transient", accuracy=acc,
                        options={"points": 129, "dt": CONTROL_DT, "t_end": 1.0, "time_error": True})
        wall = time.perf_counter() - t
        runs = list(calls)
        a = sol.raw
        quarter = run(a.dt / 4, 4 * a.planned_steps)
        if amp not in refs:
            refs[amp] = run(CONTROL_DT / 32, 32 * 86)
        fine = refs[amp]
        k = round(a.dt / fine.dt)
        true_q = {n: float(np.max(np.abs(getattr(a, n) - getattr(quarter, n)[::4])) / a.steady_film(n))
                  for n in ("Hc", "Hm")}
        true_f = {n: float(np.max(np.abs(getattr(a, n) - getattr(fine, n)[::k][:getattr(a, n).size]))
                           / a.steady_film(n)) for n in ("Hc", "Hm")}
        t_part = sol.error.parts["time"]
        rows.append({"amplitude": amp, "accuracy": acc, "runs": runs, "wall_s": wall, "dt": a.dt,
                     "steps": a.steps, "status": sol.status.label, "stated_Hc": t_part.Hc,
                     "stated_Hm": t_part.Hm, "true_quarter_Hc": true_q["Hc"], "true_quarter_Hm": true_q["Hm"],
                     "true_fine_Hc": true_f["Hc"], "true_fine_Hm": true_f["Hm"], "actions": list(sol.outcome.actions)})
        print(rows[-1])
    line_solve.solve_transient_line = original
    # the stated time part against the true error at every step from CONTROL_DT to 1/16 of it
    ladder = []
    for amp, fine in refs.items():
        d = load_scene("page63_line_2000N").to_dict()
        d["feature"] = {"kind": "dent", "amplitude": amp, "width": 1e-4, "x0": -1.5}
        scene = Scene.from_dict(d)
        runs = {k: ehl.solve(scene, physics="transient", accuracy=None,
                             options={"points": 129, "dt": CONTROL_DT * 2.0**-k, "steps": int(86 * 2.0**k)}).raw
                for k in range(-1, 5)}
        for k in range(5):
            est = time_error(runs[k], runs[k - 1])
            for n in ("Hc", "Hm"):
                true = float(np.max(np.abs(getattr(runs[k], n) - getattr(fine, n)[::2 ** (5 - k)]))
                             / fine.steady_film(n))
                ladder.append({"amplitude": amp, "dt": runs[k].dt, "film": n, "stated": est[n], "true": true,
                               "true_over_stated": true / est[n]})
                print(ladder[-1])
    save("control" + ("_quick" if quick else ""), {"scene": "page63_line_2000N", "points": 129, "rows": rows,
                                                   "ladder": ladder})


PARTS = {"steady": part_steady, "time": part_time, "grid": part_grid, "waviness": part_waviness,
         "bump": part_bump, "cost": part_cost, "cavitation": part_cavitation, "adaptive": part_adaptive,
         "starved": part_starved, "control": part_control}

if __name__ == "__main__":
    common.main(__doc__, PARTS, sys.modules[__name__])
