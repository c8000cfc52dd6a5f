"""At a stationary surface (S = 2) the temperature at a node of the far inlet, on the layer
dividing the forward from the reverse flow, jumps by kelvins whenever an inner multilevel solve
takes one more cycle, while the films, friction and largest temperature stay put
(docs/thermal.md, "Limits"). The outer iteration then converges on what it reports
(thermal.tehl.outer.films_settled), the window's drift and spread as their iteration error; a
steady drift of the films is not settled."""

import numpy as np
import pytest

from thermal.tehl.outer import NOISE_WINDOW, films_settled

TOL = {"tol_P": 1e-4, "tol_H": 1e-4, "tol_T": 1e-2}
W = 1.0 / 64.0

# page 63 at 2000 N, 5 m/s, S = 2, 513 points: outer iterations 38-47 at damping 1/64 (Hc, Hm,
# friction [N], T_max [degC]); iteration 43 is an inner solve with one more cycle
HC = [3.31734644, 3.31734462, 3.31734275, 3.31734082, 3.31733885, 3.31714253, 3.31714221, 3.31714202,
      3.31714196, 3.31714202]
HM = [2.8652982, 2.86529694, 2.86529572, 2.86529452, 2.86529334, 2.86522705, 2.8652269, 2.86522674,
      2.86522656, 2.86522639]
FRICTION = [3498.90173, 3498.90262, 3498.90338, 3498.90417, 3498.90492, 3498.93397, 3498.93389, 3498.93382,
            3498.93374, 3498.93367]
TMAX = [89.5899, 89.5899, 89.5899, 89.5899, 89.5899, 89.5903, 89.5902, 89.5902, 89.5902, 89.5902]
DP = [9.23e-05, 4.18e-06, 4.05e-06, 3.92e-06, 3.78e-06, 1.84e-4, 4.4e-06, 4.28e-06, 4.13e-06, 3.99e-06]


def _window(hc=HC, jumps=(0, 5)):
    P0 = np.linspace(0.0, 1.0, 200) ** 0.5
    outer, fields = [], []
    for k in range(NOISE_WINDOW):
        T = np.full((200, 21), 80.0)
        T[2, 7] += 8.0 if sum(k >= j for j in jumps) % 2 else 0.0  # the node that jumps
        P = P0 * (1.0 + 1e-4 * sum(k >= j for j in jumps))
        fields.append((P, T))
        outer.append({"Hc": hc[k], "Hm": HM[k], "friction": FRICTION[k], "T_max": TMAX[k], "dP": DP[k],
                      "dHc": abs(hc[k] - hc[k - 1]) / hc[k] if k else 0.0, "dHm": 0.0, "relax": W,
                      "film_noise": 1e-8})
    return outer, fields


def test_films_that_settle_while_one_temperature_node_jumps_are_settled_with_their_spread():
    outer, fields = _window()
    floor = films_settled(outer, fields, **TOL)
    assert floor is not None and floor["films_only"]
    assert floor["node"] == (2, 7) and floor["dT"] == pytest.approx(8.0)
    # the jump of iteration 43 is in the spread (6e-5 of Hc), the steady steps in the drift
    assert floor["spread_Hc"] == pytest.approx((max(HC) - min(HC)) / HC[-1])
    assert floor["Hc"] == pytest.approx(abs(np.median(np.diff(HC))) / HC[-1] / W)
    assert floor["Hc"] + floor["spread_Hc"] < 2e-4


def test_a_steady_drift_of_the_films_is_not_settled():
    # Hc moving by 2e-6 per iteration (1.3e-4 from the fixed point at damping 1/64): above tol_H
    drifting = [HC[0] * (1.0 - 2e-6 * k) for k in range(NOISE_WINDOW)]
    outer, fields = _window(hc=drifting)
    assert films_settled(outer, fields, **TOL) is None


def test_pressure_changes_above_the_noise_bound_are_not_settled():
    outer, fields = _window()
    outer[4]["dP"] = 6e-4  # six tolerances in one iteration
    assert films_settled(outer, fields, **TOL) is None
    assert films_settled(outer[1:], fields[1:], **TOL) is None  # a short window


@pytest.mark.slow
def test_a_stationary_surface_converges_on_its_films_and_two_iteration_paths_agree_within_their_errors():
    """Page 63 at 2000 N, 5 m/s, S = 2 on 513 points was declared divergent after 47 outer
    iterations (the temperature at the far inlet's dividing streamline jumping by kelvins); it
    converges on its films now. A second iteration path (starting damping 0.2 instead of 0.5)
    lands on the same films within the two stated iteration errors."""
    from ehl_multigrid.model.scene import load_scene
    from thermal.tehl.accuracy import estimate_error
    from thermal.tehl.line import solve_tehl_line
    from thermal.tehl.options import TEHLOptions

    scene = load_scene("page63_line_2000N").with_operating(us=5.0)
    results = [solve_tehl_line(scene, 2.0, TEHLOptions(points=513, relax=relax)) for relax in (0.5, 0.2)]
    assert any("still changes by up to" in a for a in results[0].report.extra["actions"])
    parts = [estimate_error(r, domain=False, extrapolate=False).budget for r in results]
    for key in ("Hc", "Hm"):
        a, b = (getattr(r, key) for r in results)
        assert abs(a - b) / b <= parts[0][key]["iteration"] + parts[1][key]["iteration"]
    assert abs(results[0].T_max - results[1].T_max) <= parts[0]["T_max"]["iteration"] + parts[1]["T_max"]["iteration"]
