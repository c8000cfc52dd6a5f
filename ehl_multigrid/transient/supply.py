"""The oil supply of a transient scene: the projection cavitation models a flooded inlet
only (mass-conserving cavitation takes a finite layer, :func:`supply_notes`).

A scene's ``[supply] hoil`` (the oil layer ahead of the contact, both surfaces together, at
ambient density) starves the contact when it is not well above what the flooded contact lets
through. Chevalier et al.'s reduction of the central film (thesis (6.1)-(6.3))

``Hcs/Hc = r / (1 + r^delta)^(1/delta)``,  ``r = hoil / (rho(pmax) hc)``,

(``hc`` the flooded central film, ``rho(pmax)`` the density ratio at the Hertzian pressure,
(2.7)) says how far the film falls. A supply is taken as flooded when the film it predicts is
within :data:`FLOODED_REDUCTION` of the flooded film; the feature's height is added to the
film the layer has to fill (a dent or a waviness trough passing through the inlet carries its
own volume). The flooded film is the scene's fitted central film (Moes line, Nijenbanning
point): it is known before the run, and it lies at or above the solver's own film on the
default inlet, so the check errs on the side of refusing.
"""

from __future__ import annotations

import math
from typing import Any

from ..model.errors import InputError
from ..model.lubricant import density_ratio_dh
from ..model.starvation import chevalier_reduction

#: a supply whose Chevalier film reduction leaves the film within this fraction of the
#: flooded film counts as flooded
FLOODED_REDUCTION = 0.01
#: Chevalier's exponent when the scene gives ``delta = "inlet"``: the low end of the range
#: 2-5 the thesis quotes (section 6.2.1), which asks for the thickest layer
DELTA_LOW = 2.0


def flooded_ratio(delta: float, reduction: float = FLOODED_REDUCTION) -> float:
    """The supply ratio ``r`` at which Chevalier's (6.1) film is ``1 - reduction`` of the
    flooded film: ``r = ((1 - reduction)^(-delta) - 1)^(-1/delta)``."""
    return ((1.0 - reduction) ** (-delta) - 1.0) ** (-1.0 / delta)


def check_flooded_supply(scene: Any, feature_height: float = 0.0,
                         density: str = "dowson-higginson") -> str | None:
    """Refuse a scene whose ``[supply] hoil`` starves the contact (:class:`InputError` naming
    ``[supply] hoil``, its value and the layer that counts as flooded); return a note when a
    finite supply is thick enough to count as flooded, None for a flooded scene.

    Parameters
    ----------
    scene : the :class:`~ehl_multigrid.model.scene.Scene` (``supply``, fitted film, Hertz).
    feature_height : the feature's largest height or depth [m] (added to the film to fill).
    density : the solver's density model (``"incompressible"``: ``rho = 1``).
    """
    sup = scene.supply
    layers = list(sup.hoil_profile[1]) if sup.hoil_profile else [sup.hoil]
    hoil = min(float(h) for h in layers)
    if math.isinf(hoil):
        return None
    name = "[supply] hoil_profile (its thinnest layer)" if sup.hoil_profile else "[supply] hoil"
    delta = float(sup.delta) if not isinstance(sup.delta, str) else DELTA_LOW
    _, hc = scene.central_film_fit()
    rho = density_ratio_dh(scene.hertz.pmax) if density == "dowson-higginson" else 1.0
    need = rho * hc + abs(float(feature_height))
    r_flooded = flooded_ratio(delta)
    least = r_flooded * need
    if not hoil >= least:
        film = float(chevalier_reduction(hoil / need, delta))
        raise InputError(
            f"{name} = {hoil:.4g} m is outside the range the transient solver can take, "
            f"[{least:.4g}, inf] m with the projection cavitation model: it models flooded inlets, "
            f"and this layer starves the "
            f"contact (Chevalier's reduction (6.1) with delta = {delta:g}: about {film:.0%} of the "
            f"flooded central film {hc:.4g} m); mass-conserving cavitation takes it "
            f"(--cavitation mass-conserving), or remove hoil for a flooded run")
    return (f"{name} = {hoil:.4g} m is {hoil / need:.3g} times the flooded contact's inlet "
            f"requirement rho h = {need:.4g} m (at least {r_flooded:.3g} times counts as flooded: "
            f"Chevalier's film reduction (6.1) below {FLOODED_REDUCTION:.0%}); solved as a "
            f"flooded contact")


def feature_height(feature: Any, scale: float) -> float:
    """The largest height or depth [m] of a dimensionless ``feature`` (film units times
    ``scale`` [m]): the volume a dent or trough passing through the inlet adds to the film the
    supply has to fill (0 for a smooth surface)."""
    if feature.kind in ("height_map", "profile"):
        return float(abs(feature.z).max()) * scale
    if feature.kind == "smooth":
        return 0.0
    return abs(float(feature.amplitude)) * scale


def supply_notes(scene: Any, feature: Any, scale: float, starved_ok: bool = False) -> list[str]:
    """The scene's supply checked against the flooded inlet of the projection model
    (:func:`check_flooded_supply`: raises for a starving supply); the note of a finite supply
    that counts as flooded. ``starved_ok`` (a line or point contact with mass-conserving
    cavitation): a finite ``[supply] hoil`` is solved as given, and the note says so (a
    ``hoil_profile`` across the track of a point contact is fed as it is, too)."""
    sup = scene.supply
    if starved_ok and sup.hoil_profile:
        layers = sup.hoil_profile[1]
        return [f"[supply] hoil_profile: the inlet is fed this layer across the track "
                f"({min(layers):.4g} .. {max(layers):.4g} m; mass-conserving cavitation)"]
    if starved_ok and math.isfinite(sup.hoil):
        return [f"[supply] hoil = {sup.hoil:.4g} m: the inlet is fed this layer (mass-conserving "
                f"cavitation; a layer above the flooded contact's flux floods it)"]
    note = check_flooded_supply(scene, feature_height(feature, scale))
    return [] if note is None else [note]

