"""The outer iteration settles at the inner solves' noise floor (thermal.tehl.outer.settled):
changes that jitter within a few tolerances without drift are converged, with the window's
spread as their iteration error; a drift, even below the changes' jitter, is not."""

import numpy as np
import pytest

from thermal.tehl.outer import NOISE_RAW, NOISE_WINDOW, settled

TOL = {"tol_P": 1e-4, "tol_H": 1e-4, "tol_T": 1e-2}


def _window(rng, drift_T=0.0, jitter_T=0.01, w=0.25):
    """Iterates of a 1-D pressure and a temperature field whose outlet nodes flip between two
    values (the free boundary moving by a node), with a drift per iteration of ``drift_T`` K."""
    P0 = np.linspace(0.0, 1.0, 200) ** 0.5
    T0 = np.full((200, 5), 80.0)
    fields, outer = [], []
    for k in range(NOISE_WINDOW):
        T = T0 + drift_T * k
        T[180:185] += jitter_T * rng.integers(0, 2, size=(5, 5))
        P = P0 * (1.0 + 2e-5 * rng.standard_normal())
        fields.append((P, T))
        outer.append({"Hc": 5.19 * (1.0 + 3e-6 * rng.standard_normal()),
                      "Hm": 4.08 * (1.0 + 1e-5 * rng.standard_normal()),
                      "T_max": float(T.max()), "dP": 2e-5})
    raw = [float(np.max(np.abs(b[1] - a[1]))) / TOL["tol_T"] for a, b in zip(fields, fields[1:], strict=False)]
    return outer, fields, [raw[0]] + raw, w


def test_a_jitter_within_the_tolerances_without_drift_is_settled_with_its_spread():
    outer, fields, raw, w = _window(np.random.default_rng(3))
    assert max(raw) <= NOISE_RAW
    floor = settled(outer, fields, raw, w, **TOL)
    assert floor is not None
    assert floor["T"] < TOL["tol_T"] and floor["P"] < TOL["tol_P"]
    hc = [o["Hc"] for o in outer]
    assert floor["spread_Hc"] == pytest.approx((max(hc) - min(hc)) / hc[-1])


def test_a_drift_below_the_jitter_is_not_settled():
    # 0.004 K per iteration at damping 1/4: 0.016 K from the fixed point by the changes' own
    # measure, above tol_T, though every change stays within the jitter's 1-2 tolerances
    outer, fields, raw, w = _window(np.random.default_rng(3), drift_T=0.004)
    assert max(raw) <= NOISE_RAW
    assert settled(outer, fields, raw, w, **TOL) is None


def test_changes_above_the_noise_bound_or_a_short_window_are_not_settled():
    outer, fields, raw, w = _window(np.random.default_rng(3), jitter_T=0.05)
    assert max(raw) > NOISE_RAW and settled(outer, fields, raw, w, **TOL) is None
    outer, fields, raw, w = _window(np.random.default_rng(3))
    assert settled(outer[1:], fields[1:], raw[1:], w, **TOL) is None
