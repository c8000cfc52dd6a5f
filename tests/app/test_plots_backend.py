"""Plotting never changes matplotlib's process-wide backend: every figure of the package is a
``matplotlib.figure.Figure`` saved by itself, so a program that embeds the package in a GUI
keeps its own backend."""

from __future__ import annotations

import ast
from pathlib import Path

import matplotlib
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.app.mainjob import hertz_result, plot_hertz
from ehl_multigrid.model.scene import load_scene

ROOT = Path(__file__).resolve().parents[2]

#: a non-interactive backend other than the Agg the test session uses
OTHER = "pdf"


@pytest.fixture
def other_backend():
    before = matplotlib.get_backend()
    matplotlib.use(OTHER)
    try:
        yield
    finally:
        matplotlib.use(before)


@pytest.mark.solver
@pytest.mark.parametrize("argv", [
    ["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "129", "--accuracy", "none"],
    ["solve", "--contact", "point", "--M", "20", "--L", "10", "--points", "65", "--accuracy", "none"],
    ["traction", "appendix_c_line_4240N", "--isothermal", "--nx", "30", "--nz", "8", "--slip", "0.01,0.1"],
    ["stribeck", "series_A_disc1_1GPa", "--n", "5"],
], ids=["solve-line", "solve-point", "traction", "stribeck"])
def test_commands_that_plot_leave_the_backend_alone(argv, tmp_path, capsys, other_backend):
    assert main([*argv, "--json", "--out", str(tmp_path)]) == 0
    assert list(tmp_path.glob("*.png"))
    assert matplotlib.get_backend() == OTHER


@pytest.mark.solver
def test_main_job_and_surface_figures_leave_the_backend_alone(tmp_path, other_backend):
    from mixed.surface import analyse_surface, gaussian_random_surface
    from mixed.surface.plots import plot_analysis

    assert plot_hertz(hertz_result(load_scene("appendix_d_point")), tmp_path / "hertz.png").is_file()
    hm = gaussian_random_surface(64, 0.5e-6, 0.2e-6, corr_length=4e-6, seed=3)
    assert Path(plot_analysis(analyse_surface(hm), tmp_path / "surface.png")).is_file()
    assert matplotlib.get_backend() == OTHER


def test_no_module_of_the_package_selects_a_backend_or_uses_pyplot():
    found = []
    for pkg in ("ehl_multigrid", "thermal", "mixed"):
        for path in (ROOT / pkg).rglob("*.py"):
            text = path.read_text()
            if "matplotlib" not in text:
                continue  # neither a call matplotlib.use nor an import of matplotlib.pyplot can be in it
            for node in ast.walk(ast.parse(text)):
                if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "use" \
                        and getattr(node.func.value, "id", "") == "matplotlib":
                    found.append(f"{path.relative_to(ROOT)}:{node.lineno} matplotlib.use")
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                    [f"{node.module}.{a.name}" for a in node.names] if isinstance(node, ast.ImportFrom) else []
                found += [f"{path.relative_to(ROOT)}:{node.lineno} imports {n}" for n in names
                          if n.startswith("matplotlib.pyplot")]
    assert found == []
