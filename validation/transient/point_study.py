"""Validation of the transient point-contact solver (ehl_multigrid.transient.solve_transient_point).

Parts (``--part``): ``steady`` (zero feature against the core steady solution; start-up from
another speed), ``time`` (BDF2 time-step refinement on one grid), ``waviness`` (amplitude
reduction Ad/Ai of transverse waviness, circular contacts, pure rolling), ``dent`` (a dent
through a circular contact, rolling and slip: profiles at several positions), ``cost`` (time
per step at 257^2 and 513^2), ``rough`` (a synthetic surface with the statistics of a series-B
disc through the contact: the load carried where the film is thin, against the mixed layer's
Greenwood-Williamson asperity share), ``cavitation`` (dents through the contact, projection
against mass-conserving cavitation: films, mass error, stalls, and the cost per step at 129^2,
257^2 and 513^2), ``starved`` (dents through a starved circular contact, mass-conserving
cavitation), ``adaptive`` (adaptive time steps against a 32 times smaller fixed step, and the
time error stated for them). Each part writes ``build/validation/transient/point_<part>.json`` and a PNG.

Moes-only circular problems (default oil of the core), Roelands + Dowson-Higginson, domain
X in [-4.5, 1.5], |Y| <= 3 (the core's default box) unless stated.
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

from ehl_multigrid.model.fits import nijenbanning_central  # noqa: E402
from ehl_multigrid.point.problem import problem_from_moes, problem_from_scene  # noqa: E402
from ehl_multigrid.point.solve import solve_fas  # noqa: E402
from ehl_multigrid.transient import (  # noqa: E402
    Dent2D,
    HeightMap,
    Waviness2D,
    point_transient_options,
    solve_transient_point,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("transient")


def save(name: str, data: dict) -> None:
    common.write_json(OUT, name, data)
    print(f"wrote {OUT / name}.json")


def hc_fit(M: float, L: float) -> float:
    """Nijenbanning-fit central film in the point contact's units (H = h Rx/a^2)."""
    pb = problem_from_moes(M, L)
    return float(nijenbanning_central(M, L, 1.0)) / pb.moes_factor


# -- steady limit --------------------------------------------------------------------------
def part_steady(quick: bool) -> None:
    pb = problem_from_moes(20, 10)
    rows = []
    for n in ((65,) if quick else (129, 257)):
        res = solve_transient_point(pb, Dent2D(0.0, 0.5, x0=-2.5), dt=0.05, steps=20, points=n,
                                    snapshot_every=20)
        rows.append({"points": n, "Hc_core": res.Hc_steady, "Hm_core": res.Hm_steady,
                     "max_rel_dHc": float(np.max(np.abs(res.Hc / res.Hc_steady - 1))),
                     "max_rel_dHm": float(np.max(np.abs(res.Hm / res.Hm_steady - 1))),
                     "max_dP": float(np.max(np.abs(res.snapshots[20]["P"] - res.steady.P))),
                     "cycles_max": res.summary()["cycles_max"]})
        print(rows[-1])
    # start-up: the steady film of M' = 1.2 M at the same load (a speed step), then smooth steps
    n = 65 if quick else 129
    M2 = 1.2 * pb.M
    other = problem_from_moes(M2, pb.L * (pb.M / M2) ** (1.0 / 3.0))  # same alpha_bar = g L M^(1/3)
    start = solve_fas(other, point_transient_options(points=n))
    res = solve_transient_point(pb, None, dt=0.1, steps=80, points=n, initial=(start.P, start.H0),
                                snapshot_every=1000)
    err = np.abs(res.Hc / res.Hc_steady - 1)
    startup = {"points": n, "dt": 0.1, "T": res.T.tolist(), "rel_dHc": err.tolist(),
               "alpha_bar_start": other.alpha_bar, "alpha_bar": pb.alpha_bar}
    print({k: startup["rel_dHc"][k] for k in (0, 10, 20, 40, 60, 80)})
    save("point_steady", {"zero_feature": rows, "startup": startup})
    common.plot_startup(OUT / "point_steady_startup.png", res.T, err, "T = t u_m / a",
                 f"Point start-up from M' = 1.2 M (M = 20, L = 10, {n}^2)")


# -- time-step refinement ------------------------------------------------------------------
def part_time(quick: bool) -> None:
    pb = problem_from_moes(20, 10)
    bump = Dent2D(0.1, 0.8, x0=-2.4, shape="gaussian")
    n = 65 if quick else 129
    dts = (0.1, 0.05, 0.025) if quick else (0.1, 0.05, 0.025, 0.0125)
    runs = []
    for dt in dts:
        r = solve_transient_point(pb, bump, dt=dt, steps=round(1.6 / dt), points=n, tol=1e-8,
                                  tol_load=1e-10, snapshot_every=100000)
        runs.append(r)
        print(dt, r.summary()["cycles_mean"])
    dhc = common.successive(runs, lambda a, b: np.max(np.abs(a.Hc - b.Hc[::2])))
    dfield = common.successive(runs, lambda a, b: np.mean(np.abs(a.snapshots[a.steps]["H"] - b.snapshots[b.steps]["H"])))
    o_hc = common.log2_ratios(dhc)
    o_f = common.log2_ratios(dfield)
    data = {"points": n, "dt": list(dts), "max_dHc_successive": dhc, "order_Hc": o_hc,
            "mean_dH_final_successive": dfield, "order_H_final": o_f,
            "cycles_mean": [r.summary()["cycles_mean"] for r in runs]}
    print(data)
    save("point_time", data)


# -- waviness amplitude reduction --------------------------------------------------------------
WAVINESS_CASES = {(20.0, 10.0): (0.5, 1.0, 2.0, 3.0), (50.0, 10.0): (0.5, 1.0, 2.0), (10.0, 5.0): (1.0, 2.0)}


def part_waviness(quick: bool) -> None:
    cases = {(20.0, 10.0): (1.0,)} if quick else WAVINESS_CASES
    name = "point_waviness_quick" if quick else "point_waviness"
    path = OUT / f"{name}.json"
    rows = json.loads(path.read_text())["rows"] if path.exists() else []
    done = {(r["M"], r["L"], r["wavelength"], r["points"]) for r in rows}
    todo = [(M, L, lam, 129) for (M, L), lams in cases.items() for lam in lams]
    if not quick:
        # one grid finer (129^2 resolves lambda = 1 with 21 points only)
        todo += [(20.0, 10.0, 1.0, 257), (20.0, 10.0, 0.5, 257), (20.0, 10.0, 2.0, 257),
                 (50.0, 10.0, 1.0, 257), (10.0, 5.0, 2.0, 257), (50.0, 10.0, 0.5, 257)]
    for M, L, lam, n in todo:
        if (M, L, lam, n) in done:
            continue
        pb = problem_from_moes(M, L)
        Ai = 0.05 * hc_fit(M, L)
        t0 = time.perf_counter()
        # one transit of the domain plus two periods; Ad over the last period
        res = solve_transient_point(pb, Waviness2D(Ai, lam), points=n, t_end=6.0 + 2.0 * lam,
                                    snapshot_every=100000)
        s = res.summary()
        row = {"M": M, "L": L, "wavelength": lam, "points": n, "Ai": Ai, "nabla": common.nabla(lam, M, L),
               "Ad_over_Ai": s["Ad_over_Ai"], "Ad_over_Ai_previous_period": common.previous_period_amplitude(res, res.feature.wavelength_x) / Ai,
               "recalled_line_curve": float(common.amplitude_curve(np.array(common.nabla(lam, M, L)))),
               "Hc_steady": s["Hc_steady"], "steps": s["steps"], "dt": s["dt"],
               "cycles_mean": s["cycles_mean"], "wall_s": time.perf_counter() - t0}
        print(row)
        rows.append(row)
        save(name, {"rows": rows})
    fig, ax = common.amplitude_figure("recalled line fit 1/(1+0.15n+0.015n^2)", lw=0.8)
    line = OUT / "waviness.json"
    if line.exists():
        lr = [r for r in json.loads(line.read_text())["rows"] if r["xmin"] == -4.5]
        ax.plot([r["nabla"] for r in lr], [r["Ad_over_Ai"] for r in lr], ".", color="0.6",
                label="line contact (this package)")
    # rows with fewer than 20 points per wavelength are grid-limited (34 % low at 11): not plotted
    rows = [r for r in rows if r["wavelength"] * (r["points"] - 1) / 6.0 >= 20.0]
    for (M, L), mk in zip(WAVINESS_CASES, ("o", "s", "^"), strict=False):
        sel = [r for r in rows if r["M"] == M and r["L"] == L and r["points"] == 129]
        ax.plot([r["nabla"] for r in sel], [r["Ad_over_Ai"] for r in sel], mk, label=f"circular M = {M:g}, L = {L:g}")
    sel = [r for r in rows if r["points"] == 257]
    if sel:
        ax.plot([r["nabla"] for r in sel], [r["Ad_over_Ai"] for r in sel], "x", ms=9, label="257^2")
    common.finish_amplitude_figure(fig, ax, OUT / f"{name}_amplitude.png", "a", "X = Y = 0",
                            "Transverse waviness on one surface, pure rolling", legend_size=7)


def nabla_circular(wavelength: float, M: float, L: float) -> float:
    """``(lambda/a) (M/L)^(1/2)``: the circular-contact form of the wavelength parameter as
    recalled from the amplitude-reduction literature (Venner & Lubrecht; Hooke) -- like the
    curve, not confirmed against a stored copy (REPORT.md 8.3)."""
    return wavelength * math.sqrt(M / L)


def part_collapse(quick: bool) -> None:
    """Which parameter collapses the circular waviness runs: the line contact's nabla or
    nabla_c = (lambda/a)(M/L)^(1/2). Reads build/validation/transient/point_waviness.json (no new solves): rows with
    at least 40 points per wavelength (resolved to 0.003, REPORT.md 8.3); deviation from the
    recalled curve and the spread between operating conditions at equal parameter."""
    path = require(OUT / "point_waviness.json", "python validation/transient/point_study.py --part waviness")
    rows = [r for r in json.loads(path.read_text())["rows"]
            if r["wavelength"] * (r["points"] - 1) / 6.0 >= 40.0]
    # the finest run of each (M, L, lambda)
    best: dict[tuple, dict] = {}
    for r in rows:
        k = (r["M"], r["L"], r["wavelength"])
        if k not in best or r["points"] > best[k]["points"]:
            best[k] = r
    out = []
    for (M, L, lam), r in sorted(best.items()):
        nl, nc = common.nabla(lam, M, L), nabla_circular(lam, M, L)
        out.append({"M": M, "L": L, "wavelength": lam, "points": r["points"], "Ad_over_Ai": r["Ad_over_Ai"],
                    "nabla_line": nl, "nabla_circular": nc,
                    "curve_at_nabla_line": float(common.amplitude_curve(np.array(nl))),
                    "curve_at_nabla_circular": float(common.amplitude_curve(np.array(nc)))})
    summary = {}
    for key in ("line", "circular"):
        dev = [o["Ad_over_Ai"] - o[f"curve_at_nabla_{key}"] for o in out]
        summary[key] = {"max_abs_deviation_from_curve": float(np.max(np.abs(dev))),
                        "rms_deviation_from_curve": float(np.sqrt(np.mean(np.square(dev))))}
    data = {"rows": out, "summary": summary,
            "note": "rows with >= 40 points per wavelength; curve 1/(1+0.15n+0.015n^2) recalled"}
    print(json.dumps(summary, indent=1))
    save("point_waviness_collapse", data)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    nb = np.linspace(0.3, 25, 300)
    for ax, key, label in zip(axes, ("line", "circular"),
                              ("nabla = (lambda/a) M^(3/4)/L^(1/2) (line form)",
                               "nabla_c = (lambda/a) (M/L)^(1/2) (circular form)"), strict=True):
        ax.plot(nb, common.amplitude_curve(nb), "k-", lw=0.8, label="recalled 1/(1+0.15n+0.015n^2)")
        for (M, L), mk in zip(WAVINESS_CASES, ("o", "s", "^"), strict=False):
            sel = [o for o in out if o["M"] == M and o["L"] == L]
            ax.plot([o[f"nabla_{key}"] for o in sel], [o["Ad_over_Ai"] for o in sel], mk,
                    label=f"circular M = {M:g}, L = {L:g}")
        ax.set_xscale("log")
        ax.set_xlabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.set_title(f"rms deviation {summary[key]['rms_deviation_from_curve']:.3f}")
    axes[0].set_ylabel("Ad / Ai at X = Y = 0")
    axes[1].legend(fontsize=7)
    fig.suptitle("Transverse waviness through circular contacts: which parameter collapses them")
    fig.tight_layout()
    fig.savefig(OUT / "point_waviness_collapse.png", dpi=120)
    plt.close(fig)


# -- dent passing --------------------------------------------------------------------------
DENT_CASES = (("dent", 0.0), ("dent", 1.0), ("dent", -1.0))
POSITIONS = (-1.0, -0.5, 0.0, 0.5, 1.0)


def part_dent(quick: bool) -> None:
    pb = problem_from_moes(20, 10)
    n = 65 if quick else 257  # 21 points across the dent's width W = 0.5
    A = -0.5 * hc_fit(20, 10)
    rows, prof = [], {}
    for kind, S in DENT_CASES[:1] if quick else DENT_CASES:
        f = Dent2D(A, 0.5, x0=-2.5)
        speed = 1.0 + 0.5 * S
        t0 = time.perf_counter()
        res = solve_transient_point(pb, f, slide_roll=S, points=n, snapshot_every=1,
                                    t_end=(1.5 + 2.5) / speed)
        s = res.summary()
        j = int(np.argmin(np.abs(res.Y)))
        Hs = res.steady.H[j]
        snaps = {}
        rise_up, rise_down = [], []
        for xf in POSITIONS:
            k = int(np.argmin(np.abs(res.xf - xf)))
            sn = res.snapshots[k]
            snaps[xf] = {"T": float(res.T[k]), "xf": float(res.xf[k]), "H": sn["H"][j].tolist(),
                         "P": sn["P"][j].tolist()}
            # film rise beside the dent: largest H - H_smooth on the centre line inside the Hertzian
            # zone, outside the dent's reach (|X - xf| > W), upstream and downstream of it
            dH = sn["H"][j] - Hs
            hz_ = np.abs(res.X) <= 1.0
            up = hz_ & (res.X < res.xf[k] - 0.5)
            down = hz_ & (res.X > res.xf[k] + 0.5)
            rise_up.append(float(np.max(dH[up])) if up.any() else math.nan)
            rise_down.append(float(np.max(dH[down])) if down.any() else math.nan)
        # the film the dent leaves at X = 0: min and max of H(0, 0, T) - Hc_steady
        row = {"case": kind, "S": S, "feature_speed": speed, "points": n, "A": A, "W": 0.5,
               "Hc_steady": s["Hc_steady"], "Hm_steady": s["Hm_steady"],
               "Hc_min": s["Hc_min"], "Hc_max": s["Hc_max"], "Hm_min": s["Hm_min"],
               "Pmax": s["Pmax_max"], "dP_max": s["dP_max"],
               "depth_in_film_at_centre_over_A": s["Ad_over_Ai"],
               "film_rise_upstream_of_dent_max": float(np.nanmax(rise_up)),
               "film_rise_downstream_of_dent_max": float(np.nanmax(rise_down)),
               "rise_upstream_at_positions": dict(zip(map(str, POSITIONS), rise_up, strict=True)),
               "rise_downstream_at_positions": dict(zip(map(str, POSITIONS), rise_down, strict=True)),
               "cycles_mean": s["cycles_mean"], "cycles_max": s["cycles_max"],
               "mass_balance_max": s["mass_balance_max"], "steps": s["steps"],
               "stalled_steps": s["stalled_steps"],
               "wall_s": time.perf_counter() - t0}
        print(row)
        rows.append(row)
        prof[f"{kind}_S{S:g}"] = {"X": res.X.tolist(), "H_smooth": Hs.tolist(), "snapshots": snaps}
    save("point_dent" + ("_quick" if quick else ""), {"rows": rows, "profiles": prof})
    fig, axes = plt.subplots(2, len(prof), figsize=(4.2 * len(prof), 6), squeeze=False, sharex=True)
    for c, (key, d) in enumerate(prof.items()):
        X = np.array(d["X"])
        axes[0, c].plot(X, d["H_smooth"], "k:", lw=1, label="smooth")
        for xf, sn in d["snapshots"].items():
            axes[0, c].plot(X, sn["H"], lw=1, label=f"xf = {xf:g}")
            axes[1, c].plot(X, sn["P"], lw=1)
        axes[0, c].set_ylim(0, 3 * rows[0]["Hc_steady"])
        axes[0, c].set_title(key)
    _save_profiles(fig, axes, "point_dent_profiles", quick)


def _save_profiles(fig, axes, name: str, quick: bool) -> None:
    """Axes labels and limits of a figure of centre-line films (top row) and pressures (bottom
    row) against X, written as ``name[_quick].png``."""
    for ax in axes[1]:
        ax.set_xlim(-2, 1.5)
        ax.set_xlabel("X = x/a (Y = 0)")
    axes[0, 0].set_ylabel("H")
    axes[1, 0].set_ylabel("P")
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / (name + ("_quick" if quick else "") + ".png"), dpi=110)
    plt.close(fig)


# -- cost ----------------------------------------------------------------------------------
def part_cost(quick: bool) -> None:
    pb = problem_from_moes(20, 10)
    A = -0.5 * hc_fit(20, 10)
    rows = []
    for n, steps in (((129, 10),) if quick else ((257, 30), (513, 12))):
        # dent of 0.5 Hc entering the Hertzian zone (centre from X = -1.0), Courant 1
        res = solve_transient_point(pb, Dent2D(A, 0.5, x0=-1.0), points=n, steps=steps,
                                    snapshot_every=100000)
        s = res.summary()
        rows.append({"points": n, "dt": s["dt"], "steps": steps, "cycles_mean": s["cycles_mean"],
                     "cycles_max": s["cycles_max"], "work_units_per_step": s["work_units_per_step"],
                     "s_per_step": s["wall_per_step_s"], "setup_s": s["setup_s"],
                     "pass_estimate_s": s["wall_per_step_s"] * 4.0 / s["dt"]})
        print(rows[-1])
    save("point_cost" + ("_quick" if quick else ""), {"rows": rows})


# -- rough surface through a series-B contact -------------------------------------------------
def part_rough(quick: bool) -> None:
    from ehl_multigrid.model.scene import Scene, load_scene
    from mixed.sharing import load_sharing
    from mixed.surface.synthetic import gaussian_random_surface

    name = "series_B_disc1_0.78GPa"
    base = load_scene(name).to_dict()
    rows = []
    runs = [(129, 12.0)] if quick else [(129, 12.0), (129, 8.0), (129, 6.0), (257, 12.0), (257, 8.0), (257, 6.0)]
    for n, us in runs:
        d = json.loads(json.dumps(base))
        d["operating"]["us"] = us
        sc = Scene.from_dict(d)
        pb = problem_from_scene(sc)
        rough = sc.roughness
        share = float(load_sharing(sc, us).asperity_fraction[0])
        a, Rx = pb.a, pb.Rx
        h_grid = 6.0 * a / (n - 1)
        ell = 4.0 * h_grid  # the shortest correlation length the grid resolves
        dx = 0.5 * h_grid
        Lx, Ly = 2.5 * a, 3.0 * a
        hmap = gaussian_random_surface((int(Ly / dx) + 1, int(Lx / dx) + 1), dx, rough.Rq,
                                       corr_length=ell, seed=7)
        z = np.asarray(hmap.z) * Rx / a**2
        # taper the patch's edges to zero over 0.3 a (cosine ramps): a cut edge would be a step
        # of ~2 Rq that the grid cannot resolve
        ny_, nx_ = z.shape
        ramp = 0.3 * a / dx

        def window(m: int, ramp: float = ramp) -> np.ndarray:
            i = np.arange(m, dtype=float)
            e = np.minimum(i, m - 1 - i) / ramp
            return np.where(e >= 1.0, 1.0, 0.5 - 0.5 * np.cos(np.pi * np.clip(e, 0.0, 1.0)))

        z = z * window(ny_)[:, None] * window(nx_)[None, :]
        x_start = -4.4
        feat = HeightMap(z, dx / a, dx / a, x_start, -0.5 * Ly / a)
        t0 = time.perf_counter()
        res = solve_transient_point(pb, feat, slide_roll=sc.slip, points=n, snapshot_every=2,
                                    t_end=(1.0 - (x_start + 0.5 * Lx / a)) / (1 + 0.5 * sc.slip),
                                    on_film_collapse="stop")
        s = res.summary()
        scale = a**2 / Rx
        hc_smooth = s["Hc_steady"] * scale
        inside = res.within(1.0)
        # kept steps with the patch's downstream (tapered) part inside the Hertzian circle
        half = 0.5 * Lx / a
        over = [k for k in sorted(res.snapshots) if k > 0 and res.xf[k] + half - 0.3 >= -0.5]
        thresholds = {"0.5 Rq": 0.5 * rough.Rq, "1 Rq": rough.Rq, "2 Rq": 2 * rough.Rq,
                      "3 sigma_s": 3 * rough.sigma_s}
        frac = {}
        for key, th in thresholds.items():
            vals = []
            for k in over:
                P, H = res.snapshots[k]["P"], res.snapshots[k]["H"]
                vals.append(float(P[H * scale <= th].sum() / P.sum()))
            frac[key] = {"mean": float(np.mean(vals)) if vals else math.nan,
                         "max": float(np.max(vals)) if vals else math.nan,
                         "last": vals[-1] if vals else math.nan}
        dev = [float(np.std((res.snapshots[k]["H"] - res.steady.H)[inside])) * scale for k in over]
        rows.append({"us": us, "M": pb.M, "L": pb.L, "a": a, "points": n, "Rq": rough.Rq,
                     "sigma_s": rough.sigma_s, "corr_length": ell,
                     "hc_smooth_m": hc_smooth, "Lambda_smooth": hc_smooth / rough.Rq,
                     "hm_min_m": s["Hm_min"] * scale, "hc_min_m": s["Hc_min"] * scale,
                     "film_closed_at_step": res.failed_step, "stop_reason": res.stop_reason,
                     "T_end": float(res.T[-1]), "patch_centre_at_end": float(res.xf[-1]),
                     "steps_with_patch_in_contact": len(over),
                     "load_fraction_below": frac, "film_rms_deviation_in_contact_m": float(np.mean(dev)) if dev else math.nan,
                     "film_rms_over_Rq": float(np.mean(dev)) / rough.Rq if dev else math.nan,
                     "gw_asperity_share": share, "steps": s["steps"], "cycles_mean": s["cycles_mean"],
                     "stalled_steps": s["stalled_steps"], "wall_s": time.perf_counter() - t0})
        print(rows[-1])
        save("point_rough" + ("_quick" if quick else ""), {"scene": name, "rows": rows})
        if not over:
            continue
        k = min(over, key=lambda j: abs(res.xf[j]))  # the patch centred on the contact, or closest
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        im = ax[0].pcolormesh(res.X, res.Y, res.snapshots[k]["H"] * scale * 1e9, shading="auto",
                              vmin=0.0, vmax=2.5 * hc_smooth * 1e9)
        ax[0].contour(res.X, res.Y, res.snapshots[k]["P"], levels=[0.25, 0.5, 0.75, 1.0], colors="w",
                      linewidths=0.4)
        ax[0].set_xlim(-1.5, 1.5)
        ax[0].set_ylim(-1.5, 1.5)
        ax[0].set_aspect("equal")
        fig.colorbar(im, ax=ax[0], label="h [nm]")
        ax[0].set_title(f"{n}^2, us = {us:g} m/s, T = {res.T[k]:.2f}", fontsize=9)
        H = np.concatenate([res.snapshots[j]["H"][inside] for j in over]) * scale * 1e9
        ax[1].hist(H, bins=60, density=True)
        ax[1].axvline(hc_smooth * 1e9, color="k", ls=":", label="smooth hc")
        ax[1].set_xlabel("h in the Hertzian circle [nm] (kept steps with the patch inside)")
        ax[1].legend()
        fig.tight_layout()
        fig.savefig(OUT / f"point_rough_{n}_us{us:g}.png", dpi=110)
    save("point_rough" + ("_quick" if quick else ""), {"scene": name, "rows": rows})


# -- cavitation models --------------------------------------------------------------------------
#: (name, M, dent depth, dent width, slip S, points, start X, end X or None for the number of
#: steps in the last field); the depth in the point contact's film units (H = h Rx/a^2)
CAVITATION_CASES = (
    ("(20, 10) dent 1.0 (2.4 Hc), S = 1", 20.0, 1.0, 1.0, 1.0, 65, -2.0, 1.5, None),
    ("(20, 10) dent 1.0 (2.4 Hc), S = 1", 20.0, 1.0, 1.0, 1.0, 129, -2.0, 1.5, None),
    ("(100, 10) dent 0.7 (5.3 Hc), S = +1", 100.0, 0.7, 0.5, 1.0, 129, -1.6, 1.1, None),
    ("(100, 10) dent 0.7 (5.3 Hc), S = -1", 100.0, 0.7, 0.5, -1.0, 129, -1.6, 1.1, None),
    ("(100, 10) dent 0.7 (5.3 Hc), S = 0", 100.0, 0.7, 0.5, 0.0, 129, -1.6, 1.1, None),
    ("(100, 10) dent 0.7 (5.3 Hc), S = 0, step tolerance 1e-7", 100.0, 0.7, 0.5, 0.0, 129, -1.6, 1.1, None),
    ("cost: (100, 10) dent 0.7 entering, S = +1", 100.0, 0.7, 0.5, 1.0, 257, -1.6, None, 20),
    ("cost: (100, 10) dent 0.7 entering, S = +1", 100.0, 0.7, 0.5, 1.0, 513, -1.6, None, 8),
)


def part_cavitation(quick: bool) -> None:
    """Each case twice, with the projection ``P >= 0`` and with mass-conserving cavitation, at
    the default step and step tolerance: wall time per step, stalled steps, the mass error of
    the mass-conserving run (oil gained per step over the inflow), Hm min of both, and the
    largest differences of Hm and Hc between the two runs over the steps, with both models'
    centre-line film and pressure at the step of the largest Hc difference."""
    rows, prof = [], {}
    for name, M, depth, W, S, n, x0, x1, steps in CAVITATION_CASES[:1] if quick else CAVITATION_CASES:
        pb = problem_from_moes(M, 10.0)
        speed = 1.0 + 0.5 * S
        runs = {}
        for cav in ("projection", "mass-conserving"):
            kw = {"steps": steps} if x1 is None else {"t_end": (x1 - x0) / speed}
            t = time.perf_counter()
            try:
                if "tolerance 1e-7" in name:
                    kw["tol"] = 1e-7
                runs[cav] = solve_transient_point(pb, Dent2D(-depth, W, x0=x0), slide_roll=S, points=n,
                                                  cavitation=cav, snapshot_every=1, **kw)
            except Exception as exc:  # a failed run is a result of the study
                runs[cav] = str(exc).splitlines()[0]
            print(name, n, cav, f"{time.perf_counter() - t:.1f} s", flush=True)
        row = {"case": name, "M": M, "depth": depth, "width": W, "S": S, "points": n}
        ok = {k: r for k, r in runs.items() if not isinstance(r, str)}
        for cav, r in runs.items():
            key = "mc" if cav == "mass-conserving" else "pr"
            if isinstance(r, str):
                row[f"failed_{key}"] = r
                continue
            s = r.summary()
            row.update({f"steps_{key}": s["steps"], f"wall_per_step_{key}": s["wall_per_step_s"],
                        f"stalled_{key}": s["stalled_steps"], f"Hm_min_{key}": s["Hm_min"],
                        f"Hc_min_{key}": s["Hc_min"], f"Hc_max_{key}": s["Hc_max"],
                        f"Hc_steady_{key}": s["Hc_steady"]})
            if key == "mc":
                err = np.asarray(r.series["mass_error"][1:], dtype=float)
                row.update({"mass_error_max": float(np.nanmax(np.abs(err))),
                            "mass_error_mean": float(np.nanmean(err))})
        if len(ok) == 2:
            a, b = ok["projection"], ok["mass-conserving"]
            m = min(a.Hc.size, b.Hc.size)
            kc = int(np.argmax(np.abs(a.Hc[:m] - b.Hc[:m])))
            row.update({"max_abs_dHm": float(np.max(np.abs(a.Hm[:m] - b.Hm[:m]))),
                        "max_abs_dHc": float(np.abs(a.Hc[kc] - b.Hc[kc])), "T_max_dHc": float(a.T[kc]),
                        "feature_x_at_max_dHc": float(a.xf[kc]),
                        "Hc_at_max_dHc": {"pr": float(a.Hc[kc]), "mc": float(b.Hc[kc])}})
            # centre-line film and pressure of both models where their central films differ most
            j = int(np.argmin(np.abs(a.Y)))
            if kc in a.snapshots and kc in b.snapshots:
                prof[name + f", {n} points"] = {
                    "X": a.X.tolist(), "T": float(a.T[kc]), "xf": float(a.xf[kc]),
                    **{f"{c}_{q}": r.snapshots[kc][q][j].tolist() for c, r in (("pr", a), ("mc", b))
                       for q in ("H", "P")}}
        print({k: v for k, v in row.items()}, flush=True)
        rows.append(row)
    save("point_cavitation" + ("_quick" if quick else ""), {"rows": rows, "profiles": prof})
    if prof:
        fig, axes = plt.subplots(2, len(prof), figsize=(4.2 * len(prof), 6), squeeze=False, sharex=True)
        for c, (key, d) in enumerate(prof.items()):
            X = np.array(d["X"])
            for m_, style in (("pr", "-"), ("mc", "--")):
                axes[0, c].plot(X, d[f"{m_}_H"], style, lw=1, label={"pr": "projection", "mc": "mass-conserving"}[m_])
                axes[1, c].plot(X, d[f"{m_}_P"], style, lw=1)
            axes[0, c].set_title(f"{key}\nT = {d['T']:.3g}, dent at X = {d['xf']:.2f}", fontsize=7)
            axes[0, c].set_ylim(0.0, 0.5)
        _save_profiles(fig, axes, "point_cavitation_profiles", quick)


#: the starved part: the supplied layer (point units H = h Rx/a^2; the flooded (20, 10) contact
#: carries about 0.5) and the dents through it: (depth, slip S)
STARVED_HOIL = 0.1
STARVED_DENTS = ((0.2, 0.0), (0.2, 1.0), (0.4, 1.0))
#: supply steps: (layer after the step, end time)
SUPPLY_STEPS = ((0.05, 7.0),)


def part_starved(quick: bool) -> None:
    """(20, 10) fed a layer ``STARVED_HOIL`` at the inlet, mass-conserving, 129^2 (65^2 quick),
    default steps and tolerances: dents of width 0.5 from X = -1.6 until they are at X = 1.1,
    the film's extremes against the starved steady film, the mass error and stalls; the supply
    stepped at T = 0.05 to half the layer, Hc(T) against the new starved steady film."""
    pb = problem_from_moes(20, 10)
    n = 65 if quick else 129
    Hc0, Hm0, rows = common.starved_dents(solve_transient_point, pb, Dent2D, STARVED_HOIL, n,
                                          STARVED_DENTS[:1] if quick else STARVED_DENTS)
    steps = common.supply_steps(solve_transient_point, pb, STARVED_HOIL, n, SUPPLY_STEPS)
    save("point_starved" + ("_quick" if quick else ""), {"M": 20, "L": 10, "hoil": STARVED_HOIL,
                                                         "Hc_starved": Hc0, "Hm_starved": Hm0, "rows": rows,
                                                         "supply_steps": steps})


def part_adaptive(quick: bool) -> None:
    """Adaptive steps (``time_tol``) through a dent passage, (20, 10), 65^2, a dent 1.0 deep
    (2.4 Hc) of width 1 from X = -2 at S = 1, mass-conserving, step tolerance 1e-8, 30 output
    steps of 0.06: the largest error of Hc(T) and Hm(T) against fixed steps 32 times smaller,
    relative to the smooth film, and the time error :func:`adaptive_time_error` states."""
    from ehl_multigrid.transient import adaptive_time_error
    from ehl_multigrid.transient.accuracy import tighter_run_options

    pb = problem_from_moes(20, 10)
    dt, n_out = 0.06, 10 if quick else 30

    def run(steps: int, tt: float | None, step: float = dt):
        return solve_transient_point(pb, Dent2D(-1.0, 1.0, x0=-2.0), points=65, dt=step, steps=steps,
                                     slide_roll=1.0, cavitation="mass-conserving", time_tol=tt,
                                     snapshot_every=10**5, tol=1e-8, tol_load=1e-9)

    ref = run(n_out * 32, None, dt / 32)
    refs = {"Hc": ref.Hc[::32], "Hm": ref.Hm[::32]}
    rows = []
    for tt in ((1e-2,) if quick else (1e-2, 1e-3)):
        a = run(n_out, tt)
        o = tighter_run_options(a, tt)
        b = run(o["steps"], o["time_tol"], o["dt"])
        est = adaptive_time_error(a, b)
        true = {k: float(np.max(np.abs(getattr(a, k) - refs[k])) / a.steady_film(k)) for k in refs}
        rows.append({"time_tol": tt, "solves": int(np.sum(a.series["substeps"][1:])),
                     "solves_second_run": int(np.sum(b.series["substeps"][1:])),
                     **{f"true_{k}": true[k] for k in refs}, **{f"est_{k}": est[k] for k in refs},
                     **{f"true_over_est_{k}": true[k] / est[k] for k in refs}})
        print(rows[-1])
    save("point_adaptive" + ("_quick" if quick else ""), {"M": 20, "L": 10, "points": 65, "rows": rows})


PARTS = {"steady": part_steady, "time": part_time, "waviness": part_waviness, "dent": part_dent,
         "cost": part_cost, "rough": part_rough, "collapse": part_collapse, "cavitation": part_cavitation,
         "starved": part_starved, "adaptive": part_adaptive}

if __name__ == "__main__":
    common.main(__doc__, PARTS, sys.modules[__name__])
