"""Fill numba's on-disk cache of the solvers' kernels before the xdist workers start.

With an empty cache (a fresh clone, CI) each worker compiles every kernel it calls, and the first
tests of both workers call the same ones. When the cache is :func:`cold`, ``tests/conftest.py``
runs this file once per part of :data:`PARTS`, in parallel processes, while the workers start;
the workers wait for them and then load the kernels from the cache (docs/testing.md,
"Workers"). A part is a few small solves, which compile exactly what the solvers call.

Run as ``python tests/kernel_cache.py PART`` with the package of the test run on ``PYTHONPATH``.
"""

from __future__ import annotations

import importlib
import sys

#: parts filled in parallel processes, about as long each (the TEHL march alone is one)
PARTS = ("line", "point")
#: a kernel every part compiles first: missing from the cache means a fresh cache
SENTINEL = ("ehl_multigrid.multigrid.rheology", "density")


def cold() -> bool:
    """Whether numba's cache lacks :data:`SENTINEL` for its current source (numba's own index;
    a stale one reads as empty)."""
    module, name = SENTINEL
    try:
        return not getattr(importlib.import_module(module), name)._cache._cache_file._load_index()
    except Exception:  # caching off, or another numba: say warm, the workers compile as before
        return False


def fill(part: str) -> None:
    """Compile the kernels of ``part`` by solving small problems: ``"line"`` a TEHL line contact
    (the thermal march is the largest kernel), ``"point"`` the steady, starved and transient
    point contacts, then the starved and transient line contacts."""
    import ehl_multigrid as ehl
    from ehl_multigrid.model.scene import Scene, load_scene

    def scene(name: str, **tables: dict) -> Scene:
        return Scene.from_dict({**load_scene(name).to_dict(), **tables})

    if part == "line":  # the TEHL march alone is about as long to compile as the other part
        from thermal.tehl import solve_tehl_line

        solve_tehl_line(load_scene("appendix_c_line_4240N"), 0.5, points=65, nz=8)
    elif part == "point":  # the starved and transient line kernels last: the line part has the line's
        ehl.solve(ehl.MoesProblem("point", 20, 10), accuracy=None, options={"points": 65})
        ehl.solve(scene("appendix_d_point", supply={"hoil": 5e-8}), accuracy=None, options={"points": 65})
        ehl.solve(scene("default", feature={"kind": "dent", "amplitude": 5e-9, "width": 2e-5, "x0": -2.5}),
                  physics="transient", accuracy=None, options={"points": 65, "steps": 2})
        ehl.solve(scene("page63_line_500N", supply={"hoil": 1.5e-8}), accuracy=None, options={"points": 129})
        ehl.solve(scene("page63_line_2000N", feature={"kind": "bump", "amplitude": 1e-8, "width": 1e-5, "x0": -3.0}),
                  physics="transient", accuracy=None, options={"points": 129, "steps": 2})
    else:
        raise ValueError(f"part = {part!r}: one of {PARTS}")


if __name__ == "__main__":
    fill(sys.argv[1])
