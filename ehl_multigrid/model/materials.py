"""Materials of bearing, gear and tribometer bodies, with the source of every number.

Each entry is a :class:`~ehl_multigrid.model.solids.Solid` (E, nu, rho, k, cp, hardness, the
fields the solids module and the scenes use) plus a source note. ``steel`` is the thesis's
bearing steel (appendices C and D) and is taken from the solids module, not repeated here.
Scenes name a material (``body1 = "Si3N4"``) or give a table ``{preset, E, nu, rho, k, cp,
hardness}``; a scene may add its own named materials in a ``[materials.NAME]`` table, and
Python code may call :func:`material_from_table`.

Values of anisotropic or variable materials (sapphire, bronze) are representative: use a
measured table when the result depends on them.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from ehl_multigrid.model.errors import InputError, reject_unknown_keys
from ehl_multigrid.model.solids import STEEL, Solid
from ehl_multigrid.model.units import convert_table


@dataclass(frozen=True)
class Material:
    """A named solid and where its numbers come from."""

    solid: Solid
    source: str

    def describe(self) -> dict[str, Any]:
        d = self.solid.to_dict()
        d["source"] = self.source
        return d


#: Keys of a material table and the kind of quantity each holds (units accepted as strings).
MATERIAL_KEYS: dict[str, str] = {
    "E": "pressure",
    "nu": "dimensionless",
    "rho": "density",
    "k": "conductivity",
    "cp": "specific_heat",
    "hardness": "pressure",
}

_STEEL_NOTE = (
    "thesis appendices C, D (E' = 2.3e11 Pa steel on steel, rho 7875, k 67, Cp 400, H' = 5 GPa); "
    "E = 210 GPa, nu = 0.3 give E' = 2.308e11 Pa"
)

MATERIALS: dict[str, Material] = {
    "steel": Material(STEEL, _STEEL_NOTE),
    # Same numbers as the thesis's bearing steel: the package has one steel.
    "AISI-52100": Material(replace(STEEL, name="AISI-52100"), "alias of 'steel': " + _STEEL_NOTE),
    "Si3N4": Material(
        Solid(name="Si3N4", E=310e9, nu=0.26, rho=3200.0, k=30.0, cp=700.0, hardness=15e9),
        "hot-isostatically pressed bearing-grade silicon nitride (ASTM F2094 class I balls): "
        "E 310 GPa, nu 0.26, rho 3.2 g/cm^3 as in Harris & Kotzalas, Essential Concepts of "
        "Bearing Technology (2007) ch. 4; k 20-30 W/(m K), cp 680-800 J/(kg K), HV about "
        "1500 (15 GPa) from producers' data sheets",
    ),
    "bronze": Material(
        Solid(name="bronze", E=110e9, nu=0.34, rho=8800.0, k=62.0, cp=380.0, hardness=1.5e9),
        "phosphor bronze CuSn8 (UNS C52100): E 110 GPa, nu 0.34, rho 8.8 g/cm^3, k 62 W/(m K), "
        "cp 380 J/(kg K) (Copper Development Association data); hardness about HV 150 "
        "(annealed to half-hard: HV 80-200)",
    ),
    "glass-BK7": Material(
        Solid(name="glass-BK7", E=82e9, nu=0.206, rho=2510.0, k=1.114, cp=858.0, hardness=6.1e9),
        "Schott N-BK7 data sheet: E 82 GPa, nu 0.206, rho 2.51 g/cm^3, lambda 1.114 W/(m K), "
        "cp 0.858 J/(g K), Knoop hardness HK0.1/20 = 610 (about 6 GPa)",
    ),
    "sapphire": Material(
        Solid(name="sapphire", E=345e9, nu=0.29, rho=3980.0, k=40.0, cp=760.0, hardness=20e9),
        "single-crystal Al2O3, representative values (anisotropic: E 335-470 GPa with "
        "orientation, nu 0.25-0.30); rho 3.98 g/cm^3, k about 40 W/(m K) at 20 degC, "
        "cp 760 J/(kg K), Knoop hardness 1800-2200 (about 20 GPa)",
    ),
    "WC-Co": Material(
        Solid(name="WC-Co", E=620e9, nu=0.24, rho=14900.0, k=85.0, cp=210.0, hardness=15e9),
        "cemented tungsten carbide with about 6 % Co (tribometer balls), representative: "
        "E 600-650 GPa, nu 0.22-0.24, rho 14.9 g/cm^3, k 80-100 W/(m K), cp about 210 "
        "J/(kg K), HV about 1500",
    ),
}


def material(name: str, extra: dict[str, Material] | None = None) -> Solid:
    """The solid named ``name``, from ``extra`` (materials a scene defines) or the built-in table.

    Raises
    ------
    InputError
        Naming the unknown material and the known ones.
    """
    table = {**MATERIALS, **(extra or {})}
    try:
        return table[name].solid
    except (KeyError, TypeError):
        raise InputError(
            f"solid preset {name!r} is not known; known materials are {sorted(table)} "
            "(or give a table {preset, E, nu, rho, k, cp, hardness})"
        ) from None


def material_from_table(
    name: str, table: dict[str, Any], extra: dict[str, Material] | None = None
) -> Material:
    """A material from a table ``{preset, E, nu, rho, k, cp, hardness, source}``.

    Values may carry units (``E = "115 GPa"``, ``rho = "8.9 g/cm^3"``). Without ``preset`` all
    six properties are required; with it, the table overrides the preset's values.

    Parameters
    ----------
    name : str
        Name of the new material (used in messages and in ``Solid.name``).
    table : dict
        The properties; plain numbers are SI.
    extra : dict, optional
        Further named materials a ``preset`` may refer to.
    """
    section = f"materials.{name}"
    if not isinstance(table, dict):
        raise InputError(f"[{section}] must be a table {{preset, E, nu, rho, k, cp, hardness}}")
    reject_unknown_keys(section, table, set(MATERIAL_KEYS) | {"preset", "source", "name"})
    values = convert_table(section, table, MATERIAL_KEYS)
    source = str(values.pop("source", "user table"))
    values.pop("name", None)
    preset = values.pop("preset", None)
    if preset is None:
        missing = sorted(set(MATERIAL_KEYS) - set(values))
        if missing:
            raise InputError(f"[{section}] without a preset must give {missing}")
        try:
            solid = Solid(name=name, **values)
        except InputError as exc:
            raise InputError(f"[{section}]: {exc}") from None
        return Material(solid, source)
    base = material(str(preset), extra)
    try:
        solid = replace(base.with_changes(**values), name=name)
    except InputError as exc:
        raise InputError(f"[{section}]: {exc}") from None
    return Material(solid, f"{source} (from preset {preset!r})")


def materials_from_tables(tables: dict[str, Any]) -> dict[str, Material]:
    """Named materials from a scene's ``[materials]`` table, in order (later may use earlier)."""
    if not isinstance(tables, dict):
        raise InputError("[materials] must be a table of named material tables")
    out: dict[str, Material] = {}
    for name, table in tables.items():
        out[name] = material_from_table(name, table, out)
    return out
