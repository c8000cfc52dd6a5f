"""How the line deformation's cell quadrature converges on a pressure with a square-root edge.

The line film uses the pressure piecewise constant on cells centred on the nodes
(``ehl_multigrid.line.kernel``): second order where the pressure is smooth. A Hertzian pressure
``P = sqrt(1 - X^2)`` ends in a square root; its film shape is known exactly (constant inside
the contact, ``H(X) - H(0) = (|X| sqrt(X^2 - 1) - acosh|X|)/2`` outside, Venner units), so the
error of the discrete film ``H(X) - H(0)`` can be measured on nested grids. The circular contact's
deformation (``ehl_multigrid.point.deformation``) is checked the same way on its exact Hertzian
deformation. An EHL pressure at
high M looks like this on every grid that does not resolve its outlet (the drop from the spike
to zero over a few cells), which is where the line's minimum film and the isoviscous central
film converge irregularly (docs/accuracy.md, "Why line films converge irregularly").

    python validation/accuracy/edge_quadrature.py

prints the errors and the ratios of successive errors, and how far the package's grid-error
rules (``multigrid.accuracy.richardson``) fall short on such sequences over many placements of
the edges within their cells (largest true error over stated error), and writes
``build/validation/accuracy/edge_quadrature.json``.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

from ehl_multigrid.line.deformation import make_deformation as line_deformation  # noqa: E402
from ehl_multigrid.multigrid.accuracy import GRID_SAFETY, line_hm_richardson, richardson  # noqa: E402
from ehl_multigrid.point.deformation import make_deformation  # noqa: E402

#: boxes: edges on nodes of every grid, and two placements that move them within their cells
BOXES = {"edges on nodes": (-2.0, 2.0), "edges between nodes (shifted box)": (-2.1, 1.9),
         "edges between nodes (longer outlet)": (-2.0, 2.3)}
#: where the film shape is compared: inside the contact and just behind the outlet edge
POINTS = (0.5, 1.02)
GRIDS = [2**k + 1 for k in range(8, 17)]


def hertz_shape(X: float) -> float:
    """Exact ``H(X) - H(0)`` of the Hertzian line pressure (Venner units)."""
    x = abs(X)
    return 0.5 * (x * math.sqrt(x * x - 1.0) - math.acosh(x)) if x > 1.0 else 0.0


def film_shape_error(n: int, box: tuple[float, float], X: float) -> float:
    """Discrete minus exact ``H(X) - H(0)`` on ``n`` nodes of ``box``."""
    nodes = np.linspace(box[0], box[1], n)
    h = nodes[1] - nodes[0]
    P = np.sqrt(np.clip(1.0 - nodes**2, 0.0, None))
    H = 0.5 * nodes**2 - line_deformation(n, h).apply(P) / math.pi
    H -= np.interp(0.0, nodes, H)
    return float(np.interp(X, nodes, H) - hertz_shape(X))


#: the rules compared: the central film's, the line minimum film's three-grid rule without and
#: with its look one grid further back, and the first-order envelope of four grids
#: ``max(|d_k|, |d_(k-1)|/2, |d_(k-2)|/4)``
RULES = {
    "Hc rule (order cap 2)": lambda v: richardson(v[-3:]).error,
    "first order, three grids": lambda v: richardson(v[-3:], max_order=1.0).error,
    "line Hm rule (look back)": lambda v: line_hm_richardson(v[-4:]).error,
    "first-order envelope, four grids": lambda v: GRID_SAFETY * max(
        abs(v[-1] - v[-2]), abs(v[-2] - v[-3]) / 2, abs(v[-3] - v[-4]) / 4),
}
#: box placements: the inlet end from -2.3 to -1.7, the box 4.13 long
SHIFTS = np.arange(-2.3, -1.69, 0.025)


def worst_ratios() -> dict[str, float]:
    """Largest true error / stated grid error of each rule over box placements, at X = 0.5,
    1.02 and 1.1, on every grid with four below it."""
    worst = dict.fromkeys(RULES, 0.0)
    for lo in SHIFTS:
        box = (float(lo), float(lo) + 4.13)
        for X in (0.5, 1.02, 1.1):
            exact = hertz_shape(X)
            films = [exact + film_shape_error(n, box, X) for n in GRIDS]
            for k in range(3, len(films)):
                true = abs(films[k] - exact)
                for name, rule in RULES.items():
                    worst[name] = max(worst[name], true / rule(films[:k + 1]))
    return worst


#: the circular contact's grids (points per side of a square box 4 long)
POINT_GRIDS = [65, 129, 257, 513, 1025]


def circular_deformation(r: float) -> float:
    """Exact ``W(r) = int int P/|r - r'| dA'`` of the circular Hertzian pressure
    ``P = sqrt(1 - r^2)`` (unit contact radius)."""
    if r <= 1.0:
        return 0.25 * math.pi**2 * (2.0 - r * r)
    return 0.5 * math.pi * ((2.0 - r * r) * math.asin(1.0 / r) + math.sqrt(r * r - 1.0))


def circular_error(n: int, x_lo: float, X: float) -> float:
    """Discrete minus exact ``W(X, 0) - W(0, 0)`` on ``n x n`` nodes of
    ``[x_lo, x_lo + 4] x [-2, 2]`` (``point.deformation``, cells centred on the nodes)."""
    xs = np.linspace(x_lo, x_lo + 4.0, n)
    ys = np.linspace(-2.0, 2.0, n)
    P = np.sqrt(np.clip(1.0 - xs[None, :]**2 - ys[:, None]**2, 0.0, None))
    W = make_deformation("fft", n, n, xs[1] - xs[0], ys[1] - ys[0])(P)[n // 2]
    return float(np.interp(X, xs, W) - np.interp(0.0, xs, W)
                 - (circular_deformation(abs(X)) - circular_deformation(0.0)))


def main() -> None:
    rows = []
    for name, box in BOXES.items():
        for X in POINTS:
            err = [film_shape_error(n, box, X) for n in GRIDS]
            ratios = [a / b for a, b in zip(err[:-1], err[1:], strict=True)]
            rows.append({"box": name, "X": X, "points": GRIDS, "error": err, "ratios": ratios})
            print(f"{name:36s} X = {X:4.2f}: error on {GRIDS[-1]} points {err[-1]:.2e}; ratios "
                  + " ".join(f"{r:6.2f}" for r in ratios))
    point_rows = []
    for x_lo in (-2.0, -2.05, -2.1, -2.2):
        for X in (0.5, 1.05):
            err = [circular_error(n, x_lo, X) for n in POINT_GRIDS]
            ratios = [a / b for a, b in zip(err[:-1], err[1:], strict=True)]
            point_rows.append({"x_lo": x_lo, "X": X, "points": POINT_GRIDS, "error": err, "ratios": ratios})
            print(f"circular, box from X = {x_lo:5.2f}, X = {X:4.2f}: ratios "
                  + " ".join(f"{r:6.2f}" for r in ratios))
    worst = worst_ratios()
    for name, q in worst.items():
        print(f"{name:34s} largest true/stated error {q:.2f}")
    out = out_dir("accuracy") / "edge_quadrature.json"
    out.write_text(json.dumps({"sequences": rows, "circular": point_rows,
                                "worst_true_over_stated": worst}, indent=1))
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
