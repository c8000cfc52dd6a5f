"""Write tests/thermal/regression_thermal.json: pinned results of high-resolution runs of this
code, for the regression test (tests/thermal/test_thermal_regression.py).

Run: python validation/thermal/make_regression_data.py   (about 5 s)
Re-run only when a deliberate model change moves the numbers, and say why in the commit.
"""

from __future__ import annotations

import json
from pathlib import Path

from ehl_multigrid.model.scene import load_scene
from thermal import solve_traction

CASES = [
    {"scene": "appendix_c_line_42400N", "slip": 0.4, "nx": 320, "nz": 40},
    {"scene": "appendix_c_line_42400N", "slip": 2.0, "nx": 320, "nz": 40},
    {"scene": "appendix_c_line_4240N", "slip": 1.0, "nx": 320, "nz": 40},
    {"scene": "appendix_d_point", "slip": 0.5, "nx": 160, "nz": 20, "slices": 16},
]


def run(case: dict) -> dict:
    kw = {k: v for k, v in case.items() if k not in ("scene", "slip")}
    tp = solve_traction(load_scene(case["scene"]), case["slip"], **kw)
    return {
        **case,
        "force": tp.force,
        "max_temperature_rise": tp.max_temperature_rise,
        "mean_temperature_rise": tp.mean_temperature_rise,
        "converged": tp.converged,
    }


def main() -> None:
    out = {
        "produced_by": "python validation/thermal/make_regression_data.py",
        "model": "thermal Roelands-Eyring, Hertz pressure + Moes/Nijenbanning film, default options otherwise",
        "cases": [run(c) for c in CASES],
    }
    path = Path(__file__).resolve().parents[2] / "tests" / "thermal" / "regression_thermal.json"
    path.write_text(json.dumps(out, indent=1))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
