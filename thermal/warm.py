"""The thermal layer's kernels compiled ahead of its stage (entry-point group ``ehl.warmups``,
run by :mod:`ehl_multigrid.app.warmup` in a helper process during the film stage)."""

from __future__ import annotations

import os

#: a built-in scene of each kind whose traction calls the kernels the stage calls
SCENES = {"line": "appendix_c_line_4240N", "point": "default"}


def cold(kind: str) -> bool:
    """Whether the thermal march is missing from numba's cache (a first use)."""
    from . import kernels

    try:
        return not os.path.exists(kernels.march_line._cache._cache_file._index_path)
    except AttributeError:  # caching off, or another numba: nothing to say
        return False


def compile_kernels(kind: str) -> None:
    """Compile the thermal and isothermal traction kernels of a ``kind`` contact: one coarse
    traction point each (Hertz input, the "fast" grid), which writes them to the cache."""
    from ehl_multigrid.model.scene import load_scene

    from .options import ThermalOptions
    from .traction import solve_traction

    scene = load_scene(SCENES[kind])
    options = ThermalOptions.for_fidelity(scene, "fast")
    for thermal in (True, False):
        solve_traction(scene, 0.5, options=options.with_changes(thermal=thermal))
