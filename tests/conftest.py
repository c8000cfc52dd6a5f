import os

import matplotlib
import pytest

# Tests never open windows; numba uses its on-disk cache (cache=True kernels).
matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")


@pytest.fixture
def scene_with_feature():
    """``make(name, feature)``: the built-in scene ``name`` with its ``[feature]`` table
    replaced by ``feature``."""
    from ehl_multigrid.model.scene import Scene, load_scene

    def make(name, feature):
        d = load_scene(name).to_dict()
        d["feature"] = feature
        return Scene.from_dict(d)

    return make
