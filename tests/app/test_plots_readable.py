"""Plots a tribologist can read: films in nm with a physical scale, colour bars in the scaling
of the title, and slender ellipses drawn in panels of a sensible shape, not as thin strips."""

import numpy as np
import pytest

from ehl_multigrid.app.film_plots import (
    MAX_TRUE_ASPECT,
    map_scales,
    maps_figure,
    plane_aspect,
    plot_result,
)
from ehl_multigrid.model.results import Result


def _point_result(b_over_a: float, physical: bool) -> Result:
    """A synthetic point result on X in [-4.5, 1.5], Y in [-3, 3] b/a: Hertz pressure and a
    parabolic film (shape only matters for the plots)."""
    X = np.linspace(-4.5, 1.5, 49)
    Y = np.linspace(-3.0, 3.0, 41) * b_over_a
    XX, YY = np.meshgrid(X, Y, indexing="ij")
    P = np.sqrt(np.clip(1.0 - XX**2 - (YY / b_over_a) ** 2, 0.0, None))
    H = 0.5 + 0.5 * (XX**2 + (YY / b_over_a) ** 2)
    res = Result("ehl_point")
    res.add_coord("X", X, "-", "x / a")
    res.add_coord("Y", Y, "-", "y / a")
    res.add_field("P", P, "-", ("X", "Y"))
    res.add_field("H", H, "-", ("X", "Y"))
    a, pmax, h_per_H = 1e-4, 1.5e9, 2e-7  # 0.1 mm, 1.5 GPa, 200 nm per Venner unit
    if physical:
        res.add_coord("x", X * a, "m")
        res.add_coord("y", Y * a, "m")
        res.add_field("p", P * pmax, "Pa", ("x", "y"))
        res.add_field("h", H * h_per_H, "m", ("x", "y"))
    res.scalars.update(Hc=2.0, Hm=1.5, Hc_venner=0.5, Hm_venner=0.375, hc=0.5 * h_per_H, hm=0.4 * h_per_H,
                       X_Hm=0.8, Y_Hm=0.0, M=20.0, L=10.0, theta=1.0 / b_over_a**2, pmax=pmax)
    return res


def _colourbar_labels(fig):
    return [ax.get_ylabel() for ax in fig.axes if ax.get_label() == "<colorbar>"]


def test_physical_maps_show_the_film_in_nm_like_the_title():
    res = _point_result(1.0, physical=True)
    sc = map_scales(res, "ball")
    assert sc.hlabel == "h [nm]" and sc.plabel == "p [GPa]"
    assert sc.hc == pytest.approx(100.0) and "hc = 100 nm" in sc.title
    np.testing.assert_allclose(sc.h, res["h"].T * 1e9)  # the plotted film is h in nm
    fig = maps_figure(res, "ball")
    labels = _colourbar_labels(fig)
    assert labels[0] == "p [GPa]" and labels[1].startswith("h [nm]")
    assert "nm" in fig._suptitle.get_text()


def test_moes_only_maps_use_the_moes_scaling_of_the_title():
    res = _point_result(1.0, physical=False)
    sc = map_scales(res)
    # the title quotes Hc in Moes's scaling: the map shows H (Venner) x Hc/Hc_venner
    np.testing.assert_allclose(sc.h, res["H"].T * 4.0)
    assert sc.hlabel == "H (Moes)" and "(Moes)" in sc.title and sc.hc == 2.0
    assert _colourbar_labels(maps_figure(res))[1].startswith("H (Moes)")


@pytest.mark.parametrize("b_over_a", [1.0, 2.0, 9.0, 30.0, 1 / 30.0])
def test_map_panels_keep_a_readable_shape(b_over_a):
    res = _point_result(b_over_a, physical=True)
    sc = map_scales(res)
    box, stretch = plane_aspect(sc.x, sc.y)
    true = (sc.y[-1] - sc.y[0]) / (sc.x[-1] - sc.x[0])
    assert 1 / MAX_TRUE_ASPECT <= box <= MAX_TRUE_ASPECT
    fig = maps_figure(res)
    w, h = fig.get_size_inches()
    assert 0.25 < h / w < 1.5  # never a 30:1 strip
    if 1 / MAX_TRUE_ASPECT <= true <= MAX_TRUE_ASPECT:
        assert stretch == pytest.approx(1.0)  # true proportions: equal axes
        assert all(ax.get_aspect() == 1.0 for ax in fig.axes[:2])
    else:
        assert "not to scale" in fig.axes[0].get_title()


def test_plot_result_writes_three_pngs(tmp_path):
    files = plot_result(_point_result(9.0, physical=True), tmp_path, "slender")
    assert [f.name for f in files] == ["slender_maps.png", "slender_profiles.png", "slender_interference.png"]
    assert all(f.stat().st_size > 1000 for f in files)


def test_line_plots_label_the_film_in_the_titles_scaling():
    from ehl_multigrid.app.film_plots import line_scales
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.model.scene import load_scene

    sol = solve_line(scene=load_scene("page63_line_2000N"), points=257, accuracy=None)
    sc = line_scales(sol)
    assert sc["hlabel"] == "h [nm]" and sc["hc"] == pytest.approx(sol.scalars["hc"] * 1e9)
    assert float(np.interp(0.0, sc["x"], sc["h"])) == pytest.approx(sc["hc"], rel=0.05)
    moes = line_scales(solve_line(20, 10, points=257, accuracy=None))
    assert moes["hlabel"] == "H (Moes)"
    assert float(np.interp(0.0, moes["x"], moes["h"])) == pytest.approx(moes["hc"], rel=0.05)


def test_maps_of_a_fine_grid_are_drawn_on_every_fourth_point_with_the_edges_kept():
    from ehl_multigrid.app.film_plots import MAP_POINTS, thinned

    sc = map_scales(_point_result(1.0, physical=False))
    fine = type(sc)(**{**vars(sc), "x": np.linspace(-4.5, 1.5, 1025), "y": np.linspace(-3, 3, 1025),
                       "p": np.random.default_rng(0).random((1025, 1025)), "h": np.ones((1025, 1025))})
    th = thinned(fine)
    assert th.x.size == th.y.size == MAP_POINTS == 257
    assert (th.x[0], th.x[-1], th.y[-1]) == (-4.5, 1.5, 3.0)
    np.testing.assert_array_equal(th.p, fine.p[::4, ::4])
    assert thinned(fine, 2 * MAP_POINTS - 1).x.size == 513  # the interference image's
    assert thinned(sc).p.shape == sc.p.shape  # coarse maps unchanged
