"""Accuracy of the Greenwood-Williamson functions F_j against adaptive quadrature.

Run: ``python validation/mixed/fj_accuracy.py``. Writes build/validation/mixed/fj_accuracy.json and fj_accuracy.png:
the largest relative error over lam in [-10, 8] (361 points) for several orders, for this
package's F_j and, for comparison, for scipy's parabolic-cylinder function pbdv.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
from scipy import integrate, special

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import OUT, plt, write_json  # noqa: E402

from mixed.gw import gw_f  # noqa: E402


def reference(j: float, lam: float) -> float:
    if lam >= 0:
        v, _ = integrate.quad(lambda t: t**j * math.exp(-lam * t - 0.5 * t * t), 0, np.inf, epsabs=0, epsrel=1e-13, limit=500)
        return v * math.exp(-0.5 * lam * lam) / math.sqrt(2 * math.pi)
    f = lambda s: (s - lam) ** j * math.exp(-0.5 * s * s) / math.sqrt(2 * math.pi)  # noqa: E731
    return integrate.quad(f, lam, 0, epsabs=0, epsrel=1e-13, limit=500)[0] + integrate.quad(f, 0, np.inf, epsabs=0, epsrel=1e-13, limit=500)[0]


def main() -> dict:
    lam = np.linspace(-10, 8, 361)
    out = {"lam_range": [-10, 8, lam.size], "orders": {}}
    p = plt()
    fig, ax = p.subplots(figsize=(6.4, 4.4))
    for j in (0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.7, 5.3, 10.0):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ref = np.array([reference(j, x) for x in lam])
        err = np.abs(np.asarray(gw_f(j, lam)) / ref - 1)
        d, _ = special.pbdv(-j - 1, lam)
        pb = math.gamma(j + 1) * np.exp(-lam * lam / 4) * d / math.sqrt(2 * math.pi)
        err_pb = np.abs(pb / ref - 1)
        out["orders"][str(j)] = {"max_rel_error": float(err.max()), "at_lam": float(lam[err.argmax()]),
                                 "pbdv_max_rel_error": float(err_pb.max()), "pbdv_at_lam": float(lam[err_pb.argmax()])}
        if j in (1.5, 3.7):
            ax.semilogy(lam, np.maximum(err, 1e-17), label=f"mixed.gw, j = {j}")
            ax.semilogy(lam, np.maximum(err_pb, 1e-17), "--", label=f"scipy pbdv, j = {j}")
        print(j, out["orders"][str(j)])
    ax.axhline(1e-8, color="k", lw=0.6)
    ax.set(xlabel="lam", ylabel="relative error vs quadrature", title="F_j accuracy (quadrature reference ~1e-13)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "fj_accuracy.png", dpi=100)
    p.close(fig)
    write_json("fj_accuracy.json", out)
    return out


if __name__ == "__main__":
    main()
