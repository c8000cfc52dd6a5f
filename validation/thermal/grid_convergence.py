"""Validation 3: grid convergence in nx, nz (line) and slices (point).

For each case the friction force (and temperature rises) on a refinement sequence (ratio 2),
the observed order from the three finest grids, the Richardson-extrapolated value and the error
of the default resolution (nx = 80, nz = 20, 10 midpoint slices) against it. Also measures the
Hertz-edge effect of keeping the pressure-gradient term with a uniform film (momentum="on").

Run: python validation/thermal/grid_convergence.py [--quick]     (about 1 min)
"""

from __future__ import annotations

from common import OUT, plt, quick_flag, richardson_resolved, write_json

from ehl_multigrid.model.scene import load_scene
from thermal import solve_traction

DEFAULT = {"nx": 80, "nz": 20, "slices": 10}
#: iteration tolerances far below the discretization error, so observed orders are not
#: polluted by the 1e-5 default tolerances (which move the force by ~1e-6 relative)
TIGHT = {"tol_T": 1e-10, "tol_tau": 1e-10, "max_inner": 1000, "max_sweeps": 200}


def sequence(scene, slip, param, values, fixed):
    rows = []
    for v in values:
        kw = dict(fixed) | TIGHT
        kw[param] = v
        tp = solve_traction(scene, slip, **kw)
        rows.append({param: v, "force": tp.force, "max_rise": tp.max_temperature_rise,
                     "mean_rise": tp.mean_temperature_rise, "converged": tp.converged, "wall_s": tp.report.wall_s})
    # mesh size ~ 1/(n - 1) for nx (nodes), 1/n for nz and slices (intervals / slices)
    h = [1.0 / (r[param] - 1 if param == "nx" else r[param]) for r in rows]
    out = {"param": param, "values": list(values), "fixed": fixed, "rows": rows}
    for q in ("force", "max_rise", "mean_rise"):
        rich = richardson_resolved(h, [r[q] for r in rows])
        default = solve_traction(scene, slip, **DEFAULT).__getattribute__(
            {"force": "force", "max_rise": "max_temperature_rise", "mean_rise": "mean_temperature_rise"}[q])
        rich["default"] = default
        rich["default_rel_error"] = default / rich["extrapolated"] - 1 if rich["extrapolated"] else float("nan")
        out[q] = rich
    return out


def main() -> None:
    quick = quick_flag()
    # nx - 1 a multiple of 7: X = -2.5, -1 and 1 are all nodes, so the inlet does not move
    # between grids (the default nx = 80 snaps the inlet to X = -2.511)
    nxs = [36, 71, 141, 281] if quick else [36, 71, 141, 281, 561]
    nzs = [5, 10, 20, 40] if quick else [5, 10, 20, 40, 80]
    sls = [4, 8, 16, 32] if quick else [2, 4, 8, 16, 32, 64]
    studies = []
    for name, slip in (("appendix_c_line_42400N", 0.05), ("appendix_c_line_42400N", 0.4),
                       ("appendix_c_line_42400N", 1.0), ("appendix_c_line_4240N", 0.4)):
        sc = load_scene(name)
        for param, values, fixed in (("nx", nxs, {"nz": 40}), ("nz", nzs, {"nx": 281})):
            s = sequence(sc, slip, param, values, fixed)
            s.update({"scene": name, "slip": slip})
            studies.append(s)
    sc = load_scene("appendix_d_point")
    for rule in ("midpoint", "cosine"):
        s = sequence(sc, 0.5, "slices", sls, {"nx": 80, "nz": 20, "slice_rule": rule})
        s.update({"scene": "appendix_d_point", "slip": 0.5})
        studies.append(s)
    s = sequence(sc, 0.5, "nx", nxs[:-1], {"nz": 20, "slices": 10})
    s.update({"scene": "appendix_d_point", "slip": 0.5})
    studies.append(s)

    # Hertz input with the pressure-gradient term kept (momentum = on): edge hot spot grows
    edge = []
    for name in ("appendix_c_line_4240N", "appendix_c_line_42400N"):
        sc = load_scene(name)
        for nx in nxs:
            on = solve_traction(sc, 0.4, nx=nx, momentum="on")
            off = solve_traction(sc, 0.4, nx=nx)
            edge.append({"scene": name, "nx": nx, "force_on": on.force, "force_off": off.force,
                         "max_rise_on": on.max_temperature_rise, "max_rise_off": off.max_temperature_rise,
                         "converged_on": on.converged})
    write_json("grid_convergence.json", {"studies": studies, "hertz_edge_momentum_on": edge})

    fig, axs = plt().subplots(1, 3, figsize=(12, 3.6))
    for s in studies:
        p = s["param"]
        ax = axs[{"nx": 0, "nz": 1, "slices": 2}[p]]
        ext = s["force"]["extrapolated"]
        err = [abs(r["force"] / ext - 1) for r in s["rows"][:-1]]
        lab = f"{s['scene'].replace('appendix_', '')} S={s['slip']}" + (f" {s['fixed'].get('slice_rule', '')}" if p == "slices" else "")
        ax.loglog(s["values"][:-1], err, "o-", ms=3, label=f"{lab} (p={s['force']['order']:.2f})")
        ax.set_xlabel(p)
    axs[0].set_ylabel("|F / F_extrapolated - 1|")
    for ax in axs:
        ax.legend(fontsize=6)
        ax.grid(alpha=0.3, which="both")
    fig.suptitle("friction force: error against the Richardson-extrapolated value", fontsize=9)
    fig.tight_layout()
    fig.savefig(OUT / "grid_convergence.png", dpi=100)
    for s in studies:
        f = s["force"]
        print(f"{s['scene']:24s} S={s['slip']:<5g} {s['param']:6s} order {f['order']:.2f}  extrap {f['extrapolated']:.6g}  "
              f"default err {f['default_rel_error'] * 100:+.3f} %   max-rise order {s['max_rise']['order']:.2f} "
              f"default err {s['max_rise']['default_rel_error'] * 100:+.2f} %")
    for e in edge:
        print(e)


if __name__ == "__main__":
    main()
