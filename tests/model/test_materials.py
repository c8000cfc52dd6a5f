"""Materials table: sources, reuse of the thesis's steel, user tables with units, bad input."""

import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.materials import (
    MATERIALS,
    material,
    material_from_table,
    materials_from_tables,
)
from ehl_multigrid.model.solids import STEEL, reduced_modulus_of


def test_every_material_has_a_source_and_valid_properties():
    for name, m in MATERIALS.items():
        assert m.source, name
        assert m.solid.name == name or name == "steel"


def test_steel_is_the_solids_module_preset_not_a_copy_of_its_numbers():
    assert material("steel") is STEEL
    a = material("AISI-52100")
    assert (a.E, a.nu, a.rho, a.k, a.cp, a.hardness) == (STEEL.E, STEEL.nu, STEEL.rho, STEEL.k, STEEL.cp, STEEL.hardness)


def test_steel_on_bk7_reduced_modulus_by_hand():
    # 2/E' = (1 - 0.3^2)/210e9 + (1 - 0.206^2)/82e9 (Schott N-BK7: E 82 GPa, nu 0.206)
    expected = 2.0 / ((1 - 0.3**2) / 210e9 + (1 - 0.206**2) / 82e9)
    assert reduced_modulus_of(STEEL, material("glass-BK7")) == pytest.approx(expected, rel=1e-12)
    assert expected == pytest.approx(1.249e11, rel=1e-3)


def test_user_table_with_units_and_a_preset():
    m = material_from_table("CuSn12", {"preset": "bronze", "E": "95 GPa", "rho": "8.7 g/cm^3", "source": "supplier"})
    assert m.solid.E == pytest.approx(95e9) and m.solid.rho == pytest.approx(8700.0)
    assert m.solid.nu == MATERIALS["bronze"].solid.nu
    assert "supplier" in m.source


def test_scene_materials_may_build_on_each_other():
    mats = materials_from_tables({"a": {"preset": "Si3N4", "E": "300 GPa"}, "b": {"preset": "a", "nu": 0.27}})
    assert mats["b"].solid.E == pytest.approx(300e9) and mats["b"].solid.nu == 0.27


def test_unknown_material_lists_the_known_ones():
    with pytest.raises(InputError, match="'unobtainium'.*'Si3N4', 'WC-Co'"):
        material("unobtainium")


def test_table_without_preset_needs_all_properties():
    with pytest.raises(InputError, match=r"materials.x.*\['cp', 'hardness', 'k', 'rho'\]"):
        material_from_table("x", {"E": 1e11, "nu": 0.3})


def test_out_of_range_property_names_field_value_and_range():
    with pytest.raises(InputError, match=r"materials.x.*nu = 0.6.*\[0, 0.5\)"):
        material_from_table("x", {"preset": "steel", "nu": 0.6})
