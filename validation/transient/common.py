"""Helpers shared by the transient studies (line_study.py, point_study.py): JSON output,
successive differences and their observed orders, the waviness parameter and the recalled
amplitude-reduction curve, the periodicity check of a waviness run, the start-up figure.

The studies run as scripts (``python validation/transient/line_study.py``), so this folder
is on ``sys.path`` and they import it as ``common``."""

from __future__ import annotations

import argparse
import json
import math
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def write_json(folder: Path, name: str, data: dict) -> Path:
    """``folder/name.json`` (the folder made when missing); returns the path."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.json"
    path.write_text(json.dumps(data, indent=1, default=float))
    return path


def successive(runs: Sequence[Any], diff: Callable[[Any, Any], float]) -> list[float]:
    """``diff(run_k, run_k+1)`` of successive runs (a refinement sequence)."""
    return [float(diff(a, b)) for a, b in zip(runs, runs[1:], strict=False)]


def log2_ratios(d: Sequence[float]) -> list[float]:
    """Observed orders ``log2(d_k / d_k+1)`` of successive differences at halved steps."""
    return [math.log2(a / b) for a, b in zip(d, d[1:], strict=False)]


def nabla(wavelength: float, M: float, L: float) -> float:
    """Venner, Couhier, Lubrecht & Greenwood (1997): ``nabla = (lambda/b) M^(3/4) / L^(1/2)``
    (a point contact: evaluated with its Moes M, L and the semi-axis a)."""
    return wavelength * M**0.75 / math.sqrt(L)


def amplitude_curve(nb: np.ndarray) -> np.ndarray:
    """``Ad/Ai = 1/(1 + 0.15 nabla + 0.015 nabla^2)``: the pure-rolling fit quoted in the
    amplitude-reduction literature (Venner & Lubrecht; Hooke) -- recalled, not confirmed (see
    REPORT.md)."""
    return 1.0 / (1.0 + 0.15 * nb + 0.015 * nb**2)


def previous_period_amplitude(res: Any, wavelength: float) -> float:
    """Half peak-to-peak of Hc over the period before the last (periodicity check of a
    waviness run; ``wavelength`` along the rolling direction)."""
    period = wavelength / abs(res.speed)
    T, Hc = res.T, res.Hc
    win = (T >= T[-1] - 2 * period) & (T < T[-1] - period)
    return 0.5 * float(Hc[win].max() - Hc[win].min()) if win.any() else math.nan


def plot_startup(path: Path, T: np.ndarray, err: np.ndarray, time_label: str, title: str,
                 which: str = "major") -> None:
    """``|Hc(T)/Hc_steady - 1|`` of a start-up run on a log scale."""
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogy(T, err)
    ax.set_xlabel(time_label)
    ax.set_ylabel("|Hc(T)/Hc_steady - 1|")
    ax.set_title(title)
    ax.grid(True, which=which, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def amplitude_figure(curve_label: str, **style: Any) -> tuple[Any, Any]:
    """``(fig, ax)`` of an Ad/Ai-against-nabla figure holding the recalled curve."""
    fig, ax = plt.subplots(figsize=(6, 4))
    nb = np.linspace(0.1, 25, 300)
    ax.plot(nb, amplitude_curve(nb), "k-", label=curve_label, **style)
    return fig, ax


def finish_amplitude_figure(fig: Any, ax: Any, path: Path, length: str, centre: str, title: str,
                            legend_size: int = 8) -> None:
    """Axes of an Ad/Ai figure (``length``: the unit of lambda; ``centre``: where Ad is read),
    then :func:`finish_figure`."""
    ax.set_xlabel(f"nabla = (lambda/{length}) M^(3/4) / L^(1/2)")
    ax.set_ylabel(f"Ad / Ai (film amplitude at {centre})")
    ax.set_xscale("log")
    ax.set_title(title)
    finish_figure(fig, ax, path, legend_size)


def finish_figure(fig: Any, ax: Any, path: Path, legend_size: int = 8) -> None:
    """Legend, grid on major and minor ticks, tight layout, PNG at 120 dpi."""
    ax.legend(fontsize=legend_size)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(doc: str, parts: dict[str, Callable[[bool], None]], study: Any) -> None:
    """Command line of a study: ``--part`` (repeatable) runs those parts; ``--quick`` a smaller
    set, written below ``build/validation/transient/quick/`` (the study module's ``OUT`` is redirected there, so the
    measured full runs are never overwritten)."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--part", choices=sorted(parts), action="append", required=True)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    if args.quick:
        study.OUT = study.OUT / "quick"
    for p in args.part:
        parts[p](args.quick)


def dent_rows(run: Callable[[float, float], Any], dents: Sequence[tuple[float, float]], Hc: float,
              points: int) -> list[dict[str, Any]]:
    """One row per dent ``(depth, slip S)`` of ``run(depth, S)`` (a mass-conserving transient
    run): the film's extremes (over the smooth film ``Hc``), the mass error per step, stalls and
    wall time; a run that fails is a row with the failure and the steps it completed."""
    import time

    rows = []
    for depth, S in dents:
        t = time.perf_counter()
        row: dict[str, Any] = {"depth": depth, "depth_over_Hc": depth / Hc, "S": S, "points": points}
        try:
            res = run(depth, S)
        except Exception as exc:  # a failed run is a result of the study
            part = getattr(exc, "partial", None)
            row.update({"failed": str(exc).splitlines()[0], "steps_done": part.steps if part is not None else 0})
        else:
            err = np.asarray(res.series["mass_error"][1:], dtype=float)
            s = res.summary()
            row.update({"steps": s["steps"], "wall_s": time.perf_counter() - t, "stalled": s["stalled_steps"],
                        "Hc_min": s["Hc_min"], "Hc_max": s["Hc_max"], "Hm_min": s["Hm_min"],
                        "mass_error_max": float(np.max(np.abs(err))), "mass_error_mean": float(np.mean(err)),
                        "mass_error_sum": float(np.sum(err))})
        print(row)
        rows.append(row)
    return rows


def starved_dents(solve: Callable[..., Any], problem: Any, feature: Callable[..., Any], hoil: float,
                  points: int, dents: Sequence[tuple[float, float]]) -> tuple[float, float, list[dict[str, Any]]]:
    """The starved steady films ``(Hc, Hm)`` of ``problem`` fed ``hoil`` and :func:`dent_rows`
    of dents of width 0.5 (``feature(amplitude, width, x0=...)``) from X = -1.6 until they are
    at X = 1.1, mass-conserving runs of ``solve`` (the line or point transient solver)."""
    kw = {"points": points, "cavitation": "mass-conserving", "hoil": hoil, "snapshot_every": 10**5}
    smooth = solve(problem, None, steps=1, dt=0.05, **kw)
    Hc, Hm = float(smooth.Hc[0]), float(smooth.Hm[0])
    rows = dent_rows(lambda depth, S: solve(problem, feature(-depth, 0.5, x0=-1.6), slide_roll=S,
                                            t_end=2.7 / (1.0 + 0.5 * S), **kw), dents, Hc, points)
    return Hc, Hm, rows


def supply_steps(solve: Callable[..., Any], problem: Any, hoil: float, points: int,
                 steps: Sequence[tuple[float, float]], dt: float = 0.1) -> list[dict[str, Any]]:
    """Mass-conserving runs of ``solve`` (the line or point transient solver) on smooth
    surfaces fed ``hoil``, the supplied layer stepped at T = 0.05 to each ``(after, t_end)``
    of ``steps``: Hc(T) against the starved steady film of the new layer, the mass error and
    the steps accepted as stalled."""
    rows = []
    for after, t_end in steps:
        row: dict[str, Any] = {"from": hoil, "to": after, "points": points}
        try:  # the starved steady film of the new layer, where its coupled solve converges
            row["Hc_new_steady"] = float(solve(problem, None, points=points, steps=1, dt=0.05,
                                               cavitation="mass-conserving", hoil=after,
                                               snapshot_every=10**5).Hc[0])
        except Exception as exc:
            row["new_steady_failed"] = str(exc).splitlines()[0]
        t0 = time.perf_counter()
        try:
            res = solve(problem, None, points=points, dt=dt, t_end=t_end, cavitation="mass-conserving",
                        hoil=lambda T, a=after: hoil if T < 0.05 else a, snapshot_every=10**5)
            row["completed"] = True
        except Exception as exc:
            res = getattr(exc, "partial", None)
            row.update({"completed": False, "failed": str(exc).splitlines()[0]})
        row["wall_s"] = time.perf_counter() - t0
        if res is not None and res.steps:
            err = np.abs(np.asarray(res.series["mass_error"][1:]))
            row.update({"Hc_before": float(res.Hc[0]), "T": res.T.tolist(), "Hc": res.Hc.tolist(),
                        "mass_error_max": float(np.max(err)), "stalled": int(np.sum(res.stalled)),
                        "Hc_at": {f"{T:g}": float(np.interp(T, res.T, res.Hc))
                                  for T in (3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0) if T <= res.T[-1]}})
        rows.append(row)
        print({k: v for k, v in row.items() if k not in ("T", "Hc")})
    return rows
