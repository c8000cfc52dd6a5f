"""An independent thermal inlet solution of a line contact, to check the coupled TEHL's
response to inlet heating (issue 44, "the thermal slip effect decided").

    python validation/tehl/inlet_reference.py [--load N] [--us M_PER_S] [--slips 0 0.5 1]

The classic inlet-zone model the thermal-reduction correlations rest on (Murch & Wilson 1975;
Wilson & Sheu 1983 for sliding), written here from its equations and sharing no code with the
package: rigid surfaces with the Hertzian gap outside the contact (``x < -b``), surfaces held
at the oil temperature, a Newtonian incompressible oil ``eta = eta0 exp(alpha p - beta dT)``,
and the thin-film energy equation with convection along and across the film (reverse flow
upwinded) and conduction across it:

    rho c (u dT/dx + W dT/dzeta) = k/h^2 d2T/dzeta2 + eta (du/dz)^2,   zeta = z/h,

``h W = -d/dx (h int_0^zeta u)`` from continuity. The pressure enters through the reduced
pressure ``q = (1 - exp(-alpha p))/alpha``: at each station the generalised Reynolds flux
(fluidity integrals of ``exp(beta dT)/eta0``) gives ``dq/dx``, and the central film ``hc`` is
the one whose ``q`` reaches ``1/alpha`` at ``x = -b`` (Grubin's condition). The isothermal
limit is Grubin's inlet integral (checked against its closed form, ``grubin_film``).

Under sliding the Newtonian heating ``exp(alpha p)(tau*)^2/eta*`` grows without bound as
``x -> -b`` (the Couette stress of an oil whose viscosity runs to infinity): the analysis needs a
pressure up to which the heating is taken, here ``p_cap`` in units of the Hertzian maximum
(``--caps``); the answer's dependence on it is part of the result.

The oil data come from a package scene (appendix C, T9 at 60 degC): ``eta0``, the
pressure-viscosity coefficient (the Roelands law's slope at ambient pressure), ``beta`` (its
temperature slope), ``k``, ``rho c``. Writes ``build/validation/tehl/inlet_reference.json``.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.integrate import cumulative_trapezoid
from scipy.optimize import brentq

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))   # slip_references, the study's scene
from _paths import out_dir  # noqa: E402


@dataclass(frozen=True)
class Inlet:
    """A line contact's data for the inlet model (SI units)."""

    R: float          # reduced radius [m]
    w: float          # load per unit length [N/m]
    E: float          # reduced modulus E' [Pa]
    eta0: float       # ambient viscosity [Pa s]
    alpha: float      # pressure-viscosity coefficient [1/Pa]
    beta: float       # temperature-viscosity coefficient -d ln eta/dT [1/K]
    k: float          # oil conductivity [W/(m K)]
    rho_c: float      # oil volumetric heat capacity [J/(m^3 K)]
    um: float         # mean (entrainment) speed [m/s]
    S: float = 0.0    # slide-to-roll ratio 2 (u1 - u2)/(u1 + u2)
    roelands: tuple[float, float, float, float] | None = None   # (eta at T_ref, T_ref, z, S0)
    T_oil: float = 0.0  # oil temperature [degC] (Roelands only)

    @property
    def b(self) -> float:
        return math.sqrt(8.0 * self.w * self.R / (math.pi * self.E))

    @property
    def pmax(self) -> float:
        return 2.0 * self.w / (math.pi * self.b)

    @property
    def thermal_loading(self) -> float:
        return self.beta * self.eta0 * self.um**2 / self.k


ETA_INF, P_ROELANDS = 6.31e-5, 1.96e8   # Roelands' constants [Pa s], [Pa] (thesis (2.6))


def fluidity(c: Inlet, p: float, dT: np.ndarray) -> np.ndarray:
    """``eta0 exp(alpha p) / eta(p, T)``: 1 for the isothermal Barus oil, ``exp(beta dT)`` for the
    exponential temperature law; with ``c.roelands`` the Roelands law in pressure and temperature,
    whose temperature coefficient grows with pressure."""
    if c.roelands is None:
        return np.exp(c.beta * dT)
    eta_r, T_r, z, S0 = c.roelands
    T = c.T_oil + dT
    ln_eta = math.log(ETA_INF) + math.log(eta_r / ETA_INF) * (1.0 + p / P_ROELANDS) ** z * (
        (T_r + 135.0) / (T + 135.0)) ** S0
    return np.exp(math.log(c.eta0) + c.alpha * p - ln_eta)


def hertz_gap(xi: np.ndarray, b: float, R: float) -> np.ndarray:
    """Separation of the undeformed-plus-Hertzian surfaces outside the contact (|xi| >= 1)."""
    a = np.abs(xi)
    r = np.sqrt(np.maximum(a * a - 1.0, 0.0))
    return b * b / (2.0 * R) * (a * r - np.log(a + r))


def grubin_film(c: Inlet) -> float:
    """Grubin's closed form ``hc/R = 1.95 (G U)^(8/11) W^(-1/11)`` (rigid inlet, Barus)."""
    U = c.eta0 * c.um / (c.E * c.R)
    return c.R * 1.95 * (c.alpha * c.E * U) ** (8.0 / 11.0) * (c.w / (c.E * c.R)) ** (-1.0 / 11.0)


class InletSolver:
    """Fixed point between the Grubin film and the inlet temperature field."""

    def __init__(self, c: Inlet, nx: int = 320, nz: int = 32, span: float = 30.0, p_cap: float = 1.0):
        self.c = c
        s = span * (np.arange(nx + 1) / nx) ** 2          # clustered towards the contact entry
        self.xi = -1.0 - s[::-1]                            # inlet ... -1
        self.x = self.xi * c.b
        self.g = hertz_gap(self.xi, c.b, c.R)
        self.zeta = np.linspace(0.0, 1.0, nz + 1)
        self.dT = np.zeros((nx + 1, nz + 1))                # temperature rise [K], walls 0
        self.ua = c.um * (1.0 + c.S / 2.0)
        self.ub = c.um * (1.0 - c.S / 2.0)
        self.exp_cap = math.exp(c.alpha * p_cap * c.pmax)

    # -- flow of one temperature field ---------------------------------------------------------
    def _fluidity(self, p: np.ndarray | None = None):
        if self.c.roelands is None:
            phi = np.exp(self.c.beta * self.dT)             # eta0/eta*
        else:
            phi = np.array([fluidity(self.c, pi, d) for pi, d in zip(p, self.dT, strict=True)])
        z = self.zeta
        f0 = _cumtrapz(phi, z)                              # int_0^zeta phi
        f1 = _cumtrapz(phi * z, z)                          # int_0^zeta zeta' phi
        J0 = np.trapezoid(f0, z, axis=1)
        C = f1 - (f1[:, -1] / f0[:, -1])[:, None] * f0
        D = np.trapezoid(C, z, axis=1)                      # < 0
        return phi, f0, C, J0, D

    def _q_of(self, hc: float, fl) -> tuple[np.ndarray, np.ndarray, float]:
        phi, f0, C, J0, D = fl
        c = self.c
        h = hc + self.g
        du = self.ub - self.ua
        couette = h * (self.ua + du * J0 / f0[:, -1])       # flux without pressure gradient
        Q = couette[-1]                                     # at x = -b, where the film is hc
        qp = c.eta0 * (Q - couette) / (h**3 * D)            # dq/dx
        q = np.concatenate(([0.0], np.cumsum(0.5 * (qp[1:] + qp[:-1]) * np.diff(self.x))))
        return q, qp, Q

    def _march(self, hc: float) -> np.ndarray:
        """Reduced pressure along the inlet for a pressure-dependent fluidity (rolling: the flux
        is ``um hc``), by Heun's rule; NaN beyond the station where ``q`` reaches 1/alpha."""
        c = self.c
        h = hc + self.g
        z = self.zeta
        Q = c.um * hc

        def slope(i, qi):
            if c.alpha * qi >= 1.0:
                return math.nan
            phi = fluidity(c, -math.log1p(-c.alpha * qi) / c.alpha, self.dT[i])
            f0 = _cumtrapz(phi[None, :], z)[0]
            f1 = _cumtrapz((phi * z)[None, :], z)[0]
            D = np.trapezoid(f1 - f1[-1] / f0[-1] * f0, z)
            return c.eta0 * (Q - c.um * h[i]) / (h[i] ** 3 * D)

        q = np.full(h.size, math.nan)
        q[0] = 0.0
        s0 = slope(0, 0.0)
        for i in range(h.size - 1):
            dx = self.x[i + 1] - self.x[i]
            s1 = slope(i + 1, q[i] + s0 * dx)
            if not math.isfinite(s1):
                break
            q[i + 1] = q[i] + 0.5 * (s0 + s1) * dx
            s0 = slope(i + 1, q[i + 1]) if i + 1 < h.size - 1 else s1
            if not math.isfinite(s0):
                break
        return q

    def film(self, fl) -> float:
        """The central film whose reduced pressure reaches 1/alpha at x = -b."""
        target = 1.0 / self.c.alpha

        def miss(hc):
            if self.c.roelands is not None:
                q = self._march(hc)
                reached = np.isfinite(q)
                # beyond 1/alpha before the entry: too thin, by how far short of it the march ended
                return q[-1] - target if reached[-1] else target * (2.0 - reached.mean())
            return self._q_of(hc, fl)[0][-1] - target

        h0 = grubin_film(self.c)
        lo, hi = 0.2 * h0, 5.0 * h0
        return brentq(miss, lo, hi, xtol=1e-14 * h0, rtol=1e-12)

    # -- energy equation -----------------------------------------------------------------------
    def _energy(self, hc: float, fl) -> np.ndarray:
        c = self.c
        if c.roelands is not None:
            q = self._march(hc)
            p_cap = math.log(self.exp_cap) / c.alpha
            p = np.where(c.alpha * q < 1.0, -np.log1p(-np.minimum(c.alpha * q, 1.0 - 1e-16)) / c.alpha, p_cap)
            fl = self._fluidity(np.minimum(np.nan_to_num(p, nan=p_cap), p_cap))
            qp = self._q_of(hc, fl)[1]
        else:
            q, qp, _ = self._q_of(hc, fl)
        phi, f0, C, J0, D = fl
        h = hc + self.g
        nxp, nzp = self.dT.shape
        z = self.zeta
        du = self.ub - self.ua
        # velocity u(zeta) and stress (reduced): tau* = tau0* + z q', tau = exp(alpha p) tau*
        u = self.ua + du * f0 / f0[:, -1:] + (qp * h * h / c.eta0)[:, None] * C
        # tau0* from u(h) = ub: (h/eta0) f0(1) tau0* + (h^2/eta0) f1(1) q' = du
        f1_end = _cumtrapz(phi * z, z)[:, -1]
        tau0s = (du - qp * h * h * f1_end / c.eta0) * c.eta0 / (h * f0[:, -1])
        taus = tau0s[:, None] + (h * qp)[:, None] * z[None, :]
        ep = 1.0 / np.maximum(1.0 - c.alpha * q, 1e-300)
        ep = np.minimum(ep, self.exp_cap)
        heat = ep[:, None] * taus**2 * phi / c.eta0       # eta (du/dz)^2 = tau^2/eta
        # continuity: h W = -d/dx (h int_0^zeta u)
        psi = h[:, None] * _cumtrapz(u, z)
        dpsi = np.gradient(psi, self.x, axis=0)
        W = -dpsi / h[:, None]
        # rho c (u dT/dx + W dT/dzeta) - k/h^2 d2T/dzeta2 = heat on the interior zeta nodes;
        # both convections upwinded, the walls at the oil temperature, inflow at the inlet too
        nzi = nzp - 2
        dz = z[1] - z[0]
        ui, wi, qi = u[:, 1:-1], W[:, 1:-1], heat[:, 1:-1]
        kd = np.broadcast_to((c.k / (h**2 * dz * dz))[:, None], ui.shape)
        dxb = np.diff(self.x, prepend=2 * self.x[0] - self.x[1])[:, None]   # backward steps
        dxf = np.diff(self.x, append=2 * self.x[-1] - self.x[-2])[:, None]  # forward steps
        west = np.where(ui > 0, c.rho_c * ui / dxb, 0.0)
        east = np.where(ui < 0, -c.rho_c * ui / dxf, 0.0)
        east[-1] = 0.0    # no heat enters from the contact (u > 0 there below S = 2)
        below = np.where(wi > 0, c.rho_c * wi / dz, 0.0) + kd
        above = np.where(wi < 0, -c.rho_c * wi / dz, 0.0) + kd
        diag = west + east + below + above
        idx = np.arange(nxp * nzi).reshape(nxp, nzi)
        rows, cols, vals = [idx.ravel()], [idx.ravel()], [diag.ravel()]
        for coef, di, dk in ((west, -1, 0), (east, 1, 0), (below, 0, -1), (above, 0, 1)):
            ii, kk = np.meshgrid(np.arange(nxp), np.arange(nzi), indexing="ij")
            inside = (ii + di >= 0) & (ii + di < nxp) & (kk + dk >= 0) & (kk + dk < nzi) & (coef != 0)
            rows.append(idx[inside])
            cols.append(idx[ii[inside] + di, kk[inside] + dk])
            vals.append(-coef[inside])
        A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(nxp * nzi, nxp * nzi))
        sol = spla.spsolve(A.tocsc(), qi.ravel())
        out = np.zeros_like(self.dT)
        out[:, 1:-1] = sol.reshape(nxp, nzi)
        return out

    def solve(self, thermal: bool = True, tol: float = 1e-8, max_iter: int = 200,
              relax: float = 0.5) -> dict:
        fl = self._fluidity() if self.c.roelands is None else None
        hc = self.film(fl)
        hist = [hc]
        if thermal:
            for _ in range(max_iter):
                new = self._energy(hc, fl)
                self.dT = self.dT + relax * (new - self.dT)
                fl = self._fluidity() if self.c.roelands is None else None
                hc_new = self.film(fl)
                hist.append(hc_new)
                if abs(hc_new - hc) < tol * hc:
                    hc = hc_new
                    break
                hc = hc_new
            else:
                raise RuntimeError(f"inlet fixed point did not settle: last changes {np.diff(hist[-4:])}")
        return {"hc": hc, "iterations": len(hist) - 1, "dT_max": float(self.dT.max())}


def _cumtrapz(f: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Running trapezoidal integral along the film (axis 1), from 0 at the lower wall."""
    return cumulative_trapezoid(f, z, axis=1, initial=0.0)


def inlet_from_scene(load: float, us: float, S: float, roelands: bool = False) -> Inlet:
    """The oil and contact data of the appendix C line contact (T9, 60 degC); ``roelands``
    takes the oil's Roelands law in pressure and temperature instead of Barus with ``beta``."""
    from slip_references import SCENE

    from ehl_multigrid.model.scene import load_scene

    sc = load_scene(SCENE).with_operating(us=us, load=load)
    lub, T = sc.lubricant, sc.T_oil
    rho_c = float(lub.density(0.0, T)) * float(lub.specific_heat(T))
    return Inlet(R=sc.Rx, w=load / sc.length, E=sc.E_reduced, eta0=sc.eta0, alpha=sc.alpha,
                 beta=lub.beta(T), k=float(lub.conductivity(0.0)), rho_c=rho_c, um=us / 2.0, S=S,
                 roelands=(lub.eta0, lub.T0, lub.z, lub.S0) if roelands else None, T_oil=T)


def package_ratio(load: float, us: float, S: float, inlet_assumptions: bool) -> dict:
    """The package's coupled TEHL Hc/Hc_iso (front door, 1 %) on the same contact, with the
    inlet analysis's assumptions (surfaces at the oil temperature, Newtonian, no expansion) or
    as the scene is (steel, Eyring, expanding oil)."""
    from slip_references import scene

    import ehl_multigrid as ehl

    variant = dict(cold_walls=True, newtonian=True, expansion=False) if inlet_assumptions else {}
    sc = scene(**variant).with_operating(us=us, load=load)
    s = ehl.solve(sc, physics="thermal", accuracy=0.01, options={"slip": S})
    sm = s.summary()
    return {"status": sm["status"], "ratio": sm["Hc"] / s.details.Hc_isothermal, "Hc_error": sm["Hc_error"],
            "M": sc.moes()[0], "T_max": s.details.T_max}


def run_case(load: float, us: float, S: float, cap: float, nx: int, nz: int) -> dict:
    c = inlet_from_scene(load, us, S)
    iso = InletSolver(c, nx, nz, p_cap=cap).solve(thermal=False)["hc"]
    row = {"S": S, "us": us, "load": load, "p_cap": cap, "L": c.thermal_loading, "hc_iso": iso,
           "hc_grubin": grubin_film(c), "Pe": c.rho_c * c.um * iso**2 / (c.k * c.b),
           "murch_wilson": 3.94 / (3.94 + c.thermal_loading**0.62)}
    try:
        th = InletSolver(c, nx, nz, p_cap=cap).solve()
        row.update(hc=th["hc"], ratio=th["hc"] / iso, dT_max=th["dT_max"], iterations=th["iterations"])
    except (RuntimeError, ValueError, FloatingPointError) as exc:   # a thermal runaway is an outcome
        row.update(ratio=None, failure=f"{type(exc).__name__}: {exc}"[:200])
    return row


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--load", type=float, default=42400.0)
    ap.add_argument("--speeds", type=float, nargs="+", default=[20.6, 41.2, 82.4], help="sum speeds [m/s]")
    ap.add_argument("--slips", type=float, nargs="+", default=[0.0, 0.5, 1.0])
    ap.add_argument("--caps", type=float, nargs="+", default=[0.1, 0.3, 1.0],
                    help="pressures (in pmax) up to which the sliding heating is taken")
    ap.add_argument("--nx", type=int, default=320)
    ap.add_argument("--nz", type=int, default=32)
    ap.add_argument("--no-package", action="store_true", help="the inlet model only")
    a = ap.parse_args()
    path = out_dir("tehl") / "inlet_reference.json"
    rows = json.loads(path.read_text()) if path.exists() else []
    done = {(r["load"], r["us"], r["S"], r["p_cap"], r.get("nx"), r.get("nz")) for r in rows}
    for us in a.speeds:
        for S in a.slips:
            for cap in (a.caps if S else [1.0]):
                if (a.load, us, S, cap, a.nx, a.nz) in done:
                    continue
                row = run_case(a.load, us, S, cap, a.nx, a.nz)
                row.update(nx=a.nx, nz=a.nz)
                if not a.no_package and cap == (a.caps if S else [1.0])[0]:
                    row["package_inlet_assumptions"] = package_ratio(a.load, us, S, True)
                    row["package_scene"] = package_ratio(a.load, us, S, False)
                rows.append(row)
                print(json.dumps(row), flush=True)
                tmp = path.with_suffix(".tmp")
                tmp.write_text(json.dumps(rows, indent=1))
                tmp.replace(path)


if __name__ == "__main__":
    main()
