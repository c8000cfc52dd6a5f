"""``ehl traction --input ehl --ehl-file F`` uses the film only when the file's contact is the
scene's: the scene stored beside the film is compared (load, radii, moduli, oil, speed,
supply) and a film of another contact is refused naming the quantity and both values."""

import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import Scene, load_scene
from thermal.traction import check_ehl_contact, ehl_result_from, solve_traction


def hertz_film(scene, n: int = 41) -> Result:
    """Hertz pressure and the fitted uniform film of ``scene`` as an EHL result beside it."""
    hz = scene.hertz
    h = scene.central_film_fit()[1]
    if scene.kind == "line":
        x = np.linspace(-2.5 * hz.b, 1.0 * hz.b, n)
        return ehl_result_from((x, hz.pmax * np.sqrt(np.clip(1 - (x / hz.b) ** 2, 0, None)), np.full(n, h)), scene)
    x = np.linspace(-2.5 * hz.a, 1.0 * hz.a, n)
    y = np.linspace(0.0, hz.b, 11)
    P = hz.pmax * np.sqrt(np.clip(1 - (x[:, None] / hz.a) ** 2 - (y[None, :] / hz.b) ** 2, 0, None))
    return ehl_result_from((x, y, P, np.full_like(P, h)), scene)


def test_a_film_of_another_contact_is_refused_naming_the_quantity_and_both_values(tmp_path, capsys):
    # the issue: a ball-on-glass film under the appendix D scene gave the scene's 42.8 N and
    # 1 GPa in the header and half the friction of the Hertz input
    path = hertz_film(load_scene("ball_on_disc_tribometer")).save(tmp_path / "bod.h5")
    code = main(["traction", "appendix_d_point", "--input", "ehl", "--ehl-file", str(path), "--slip", "0.1",
                 "--json", "--no-plots", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2
    assert "load" in err and "20" in err and "42.8" in err
    assert not (tmp_path / "o").exists() or not list((tmp_path / "o").iterdir())


@pytest.mark.parametrize(("change", "quantity"), [
    ({"load": 4000.0}, "load"),
    ({"us": 4.0}, "us"),
    ({"T_oil": 80.0}, "viscosity at T_oil"),
])
def test_each_operating_difference_is_named(change, quantity):
    sc = load_scene("appendix_c_line_4240N")
    with pytest.raises(InputError, match=quantity):
        check_ehl_contact(sc.with_operating(**change), sc)


def test_other_radii_moduli_length_kind_and_supply_are_refused():
    line = load_scene("appendix_c_line_4240N")
    point = load_scene("appendix_d_point")
    ball_on_glass = load_scene("ball_on_disc_tribometer")
    with pytest.raises(InputError, match="contact.kind"):
        check_ehl_contact(point, line)
    with pytest.raises(InputError, match="Rx"):
        check_ehl_contact(ball_on_glass.with_operating(load=point.load, us=point.us), point)
    glass = line.to_dict()
    glass["solids"]["E_reduced"] = 0.5 * line.E_reduced  # another material pair
    with pytest.raises(InputError, match="E_reduced"):
        check_ehl_contact(Scene.from_dict(glass), line)
    with pytest.raises(InputError, match=r"\[supply\] hoil"):
        check_ehl_contact(line.with_supply(hoil=2e-8), line)
    check_ehl_contact(load_scene("appendix_c_line_4240N"), line)  # the same contact passes


def test_the_api_refuses_a_result_of_another_contact_too():
    sc = load_scene("appendix_c_line_4240N")
    other = hertz_film(sc.with_operating(load=2.0 * sc.load))
    with pytest.raises(InputError, match="load"):
        solve_traction(sc, 0.1, input="ehl", ehl=other, nx=20, nz=5)


def test_a_film_file_without_a_scene_needs_the_explicit_flag(tmp_path, capsys):
    sc = load_scene("appendix_c_line_4240N")
    film = hertz_film(sc)
    bare = Result("ehl_line")
    bare.add_coord("x", film["x"], "m")
    bare.add_field("p", film["p"], "Pa", ("x",))
    bare.add_field("h", film["h"], "m", ("x",))
    path = bare.save(tmp_path / "bare.h5")
    args = ["traction", "appendix_c_line_4240N", "--input", "ehl", "--ehl-file", str(path), "--slip", "0.1",
            "--nx", "20", "--nz", "5", "--json", "--no-plots", "--out", str(tmp_path / "o")]
    assert main(args) == 2
    err = capsys.readouterr().err
    # names the file, what it lacks and the flag that accepts it anyway
    assert path.name in err and "scene" in err and "--unchecked-ehl-file" in err
    assert main([*args, "--unchecked-ehl-file"]) == 0
