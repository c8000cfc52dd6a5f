"""Machine elements to contacts: reduced radii, surface velocities and load from catalogue data.

Every helper returns an :class:`ElementContact`: the contact kind (line, point, elliptic), the
reduced radii ``Rx`` (rolling direction) and ``Ry``, the surface velocities ``u1`` (body 1) and
``u2`` (body 2) in the rolling direction, the normal load (and the line length of line
contacts), plus the intermediate numbers a designer checks (cage speed, contact ratio ...).
``us = u1 + u2`` is the sum velocity, ``(u1 + u2)/2`` the entrainment (mean) speed and
``S = 2 (u1 - u2)/(u1 + u2)`` the slip, as everywhere in the package.

Inputs are SI, angles in degrees; the scene reader accepts strings with units, where a speed
of rotation may be given as ``"1500 rpm"``, ``"25 Hz"`` (revolutions per second) or ``"157 rad/s"``;
a plain number is rad/s. A scene's ``[element]`` values are also checked for plausibility
(:func:`~ehl_multigrid.model.plausibility.check_plausible`: a shaft speed of 3000 rad/s, 28648 rpm,
warns and asks whether rpm were meant).

Sources
-------
* Rolling bearings: T. A. Harris and M. N. Kotzalas, *Essential Concepts of Bearing Technology*
  (5th ed., CRC 2007): curvature sums of ball-raceway contacts (ch. 2), pure-rolling kinematics
  with the cage speed (ch. 8), Stribeck's maximum rolling-element load (ch. 7). The same
  entrainment speed is B. J. Hamrock and D. Dowson, *Ball Bearing Lubrication* (Wiley 1981):
  ``u = |w_o - w_i| (dm^2 - D^2 cos^2 a)/(4 dm)``.
* Gears: involute geometry of ISO 21771 and the radii of curvature, base helix angle and normal
  force of ISO 6336-2 (``rho_n = rho_t / cos(beta_b)``); rolling speeds ``u_i = w_i rho_i``
  (D. Dowson and G. R. Higginson, *Elasto-hydrodynamic Lubrication*, 1977, ch. 12).
* Tribometers: rigid-body kinematics of the disc, ball and reciprocating flat.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ehl_multigrid.model.errors import (
    InputError,
    reject_unknown_keys,
    require_choice,
    require_positive,
    require_range,
    warn_implausible,
)
from ehl_multigrid.model.plausibility import check_plausible
from ehl_multigrid.model.units import convert_table

#: Stribeck's factor for the most heavily loaded ball, ``Q_max = 5 Fr/(Z cos a)`` (ball bearing
#: with nominal diametral clearance; 4.37 with zero clearance), Harris & Kotzalas ch. 7.
STRIBECK_BALL = 5.0
#: The line-contact value for a roller bearing with zero clearance, ``Q_max = 4.08 Fr/Z``
#: (Harris & Kotzalas ch. 7).
STRIBECK_ROLLER = 4.08


@dataclass(frozen=True)
class ElementContact:
    """One lubricated contact of a machine element, ready for a scene.

    Attributes
    ----------
    element : str
        What produced it (``"ball_bearing"``, ``"spur_gear"`` ...).
    kind : str
        ``"line"``, ``"point"`` (Rx = Ry) or ``"elliptic"``.
    Rx, Ry : float
        Reduced radii of curvature in and across the rolling direction [m]; ``Ry = inf`` for a
        line contact.
    u1, u2 : float
        Surface velocities of body 1 and body 2 in the rolling direction [m/s].
    load : float
        Normal load [N] (over ``length`` for a line contact).
    length : float
        Line length B [m] (line contacts; nan otherwise).
    details : dict
        Intermediate quantities, each a float in SI (or degrees), for ``ehl show``.
    """

    element: str
    kind: str
    Rx: float
    Ry: float
    u1: float
    u2: float
    load: float
    length: float = math.nan
    details: dict[str, Any] = field(default_factory=dict, compare=False)

    @property
    def us(self) -> float:
        """Sum velocity ``u1 + u2`` [m/s]."""
        return self.u1 + self.u2

    @property
    def entrainment_speed(self) -> float:
        """Mean (entrainment) speed ``(u1 + u2)/2`` [m/s]."""
        return 0.5 * self.us

    @property
    def slip(self) -> float:
        """``S = 2 (u1 - u2)/(u1 + u2)`` [-]."""
        return 2.0 * (self.u1 - self.u2) / self.us

    @property
    def theta(self) -> float:
        """``Rx/Ry`` (0 for a line contact)."""
        return self.Rx / self.Ry

    @property
    def load_per_length(self) -> float:
        """``w = load/length`` [N/m] (line contacts; nan otherwise)."""
        return self.load / self.length

    def describe(self) -> dict[str, Any]:
        """The contact as a flat dict (SI, angles in degrees)."""
        out: dict[str, Any] = {
            "element": self.element, "contact": self.kind, "Rx": self.Rx, "Ry": self.Ry,
            "theta": self.theta, "u1": self.u1, "u2": self.u2, "us": self.us,
            "entrainment_speed": self.entrainment_speed, "slip": self.slip, "load": self.load,
        }
        if self.kind == "line":
            out["length"] = self.length
            out["load_per_length"] = self.load_per_length
        out.update(self.details)
        return out


def _check_speed_sum(element: str, u1: float, u2: float) -> None:
    if not u1 + u2 > 0.0:
        raise InputError(
            f"{element}: the sum velocity u1 + u2 = {u1 + u2:.6g} m/s must be > 0 "
            "(no entrainment, no film); check the speeds and their signs"
        )


# -- rolling bearings -----------------------------------------------------------------------
def _bearing_geometry(D: float, dm: float, angle_deg: float, prefix: str) -> tuple[float, float]:
    require_positive(f"{prefix}.pitch_diameter", dm, "m")
    require_range(f"{prefix}.contact_angle", angle_deg, 0.0, 60.0, "deg")
    gamma = D * math.cos(math.radians(angle_deg)) / dm
    require_range(f"{prefix} gamma = D cos(a)/dm", gamma, 0.0, 0.5, "-", lo_open=True)
    return gamma, math.radians(angle_deg)


def _rolling_element_load(
    prefix: str, n: int, alpha: float, factor: float,
    element_load: float | None, radial_load: float | None, axial_load: float | None,
) -> tuple[float, str]:
    given = [k for k, v in (("ball_load", element_load), ("radial_load", radial_load),
                            ("axial_load", axial_load)) if v is not None]
    if len(given) != 1:
        raise InputError(
            f"{prefix} needs exactly one of ball_load/roller_load (N, on the element), "
            f"radial_load (N, bearing) or axial_load (N, bearing); got {given or 'none'}"
        )
    if element_load is not None:
        return require_positive(f"{prefix}.{given[0]}", element_load, "N"), "given"
    if radial_load is not None:
        Fr = require_positive(f"{prefix}.radial_load", radial_load, "N")
        return factor * Fr / (n * math.cos(alpha)), f"Stribeck Q_max = {factor:g} Fr/(Z cos a)"
    Fa = require_positive(f"{prefix}.axial_load", axial_load, "N")
    if alpha <= 0.0:
        raise InputError(f"{prefix}.axial_load needs a contact angle > 0 (got 0 deg)")
    return Fa / (n * math.sin(alpha)), "Q = Fa/(Z sin a), equal share"


def _bearing_kinematics(shaft_speed: float, dm: float, gamma: float) -> tuple[float, float, float]:
    """Pure rolling, inner ring at ``shaft_speed`` [rad/s], outer ring fixed (Harris ch. 8).

    Returns the cage speed [rad/s], the ball (roller) speed about its own axis [rad/s] and the
    rolling speed of every contact surface relative to the cage [m/s]:
    ``w_c = w_i (1 - gamma)/2``, ``u = w_i dm (1 - gamma^2)/4``.
    """
    w_cage = 0.5 * shaft_speed * (1.0 - gamma)
    u = 0.25 * shaft_speed * dm * (1.0 - gamma**2)
    return w_cage, u, u


def ball_bearing(
    ball_diameter: float,
    pitch_diameter: float,
    n_balls: int,
    f_inner: float,
    f_outer: float,
    shaft_speed: float,
    race: str = "inner",
    contact_angle: float = 0.0,
    ball_load: float | None = None,
    radial_load: float | None = None,
    axial_load: float | None = None,
    stribeck_factor: float = STRIBECK_BALL,
) -> ElementContact:
    """Ball-raceway contact of a deep-groove or angular-contact ball bearing.

    Body 1 is the ball, body 2 the raceway. Curvatures (Harris & Kotzalas ch. 2), with
    ``gamma = D cos(a)/dm``: ball ``2/D`` in both planes; inner raceway ``2 gamma/(D (1 - gamma))``
    along the rolling direction and ``-1/(f_i D)`` across it; outer raceway
    ``-2 gamma/(D (1 + gamma))`` and ``-1/(f_o D)``. Hence ``Rx = D (1 -+ gamma)/2`` and
    ``Ry = f D/(2 f - 1)``. Kinematics: pure rolling, inner ring rotating, outer fixed, ball speed
    from the cage speed ``w_c = w_i (1 - gamma)/2``: ``u1 = u2 = w_i dm (1 - gamma^2)/4``.

    Parameters
    ----------
    ball_diameter : float
        D [m].
    pitch_diameter : float
        dm [m] (mean of bore and outside diameter is close for catalogue bearings).
    n_balls : int
        Z.
    f_inner, f_outer : float
        Groove curvature ratios ``f = r_groove/D`` (0.5 < f; usually 0.515-0.53).
    shaft_speed : float
        Inner-ring angular speed [rad/s] ("1500 rpm" in scenes).
    race : {"inner", "outer"}
        Which ball-raceway contact.
    contact_angle : float
        a [deg]; 0 for a radially loaded deep-groove bearing.
    ball_load, radial_load, axial_load : float, optional
        Exactly one: the ball's normal load Q [N]; or the bearing's radial load Fr [N], giving
        the most heavily loaded ball by Stribeck ``Q_max = stribeck_factor Fr/(Z cos a)``; or
        the axial load Fa [N], shared equally, ``Q = Fa/(Z sin a)``.
    stribeck_factor : float
        5 for nominal clearance (default), 4.37 for zero clearance.
    """
    p = "element (ball_bearing)"
    D = require_range(f"{p}.ball_diameter", ball_diameter, 1e-4, 1.0, "m")
    gamma, alpha = _bearing_geometry(D, pitch_diameter, contact_angle, p)
    race = require_choice(f"{p}.race", race, ("inner", "outer"))
    Z = int(require_range(f"{p}.n_balls", n_balls, 3, 200, "-"))
    fi = require_range(f"{p}.f_inner", f_inner, 0.5, 0.7, "-", lo_open=True)
    fo = require_range(f"{p}.f_outer", f_outer, 0.5, 0.7, "-", lo_open=True)
    w = require_positive(f"{p}.shaft_speed", shaft_speed, "rad/s")
    require_range(f"{p}.stribeck_factor", stribeck_factor, 4.0, 6.0, "-")
    f = fi if race == "inner" else fo
    Rx = 0.5 * D * (1.0 - gamma) if race == "inner" else 0.5 * D * (1.0 + gamma)
    Ry = f * D / (2.0 * f - 1.0)
    Q, how = _rolling_element_load(p, Z, alpha, stribeck_factor, ball_load, radial_load, axial_load)
    w_cage, u_ball, u_race = _bearing_kinematics(w, pitch_diameter, gamma)
    details = {
        "gamma": gamma, "cage_speed": w_cage, "ball_rotation_speed": w * pitch_diameter
        / (2.0 * D) * (1.0 - gamma**2), "curvature_sum": 1.0 / Rx + 1.0 / Ry,
        "curvature_difference": (1.0 / Rx - 1.0 / Ry) / (1.0 / Rx + 1.0 / Ry),
    }
    if how != "given":
        details["load_rule"] = how
    kind = "point" if math.isclose(Rx, Ry, rel_tol=1e-12) else "elliptic"
    return ElementContact("ball_bearing", kind, Rx, Ry, u_ball, u_race, Q, details=details)


def roller_bearing(
    roller_diameter: float,
    pitch_diameter: float,
    n_rollers: int,
    roller_length: float,
    shaft_speed: float,
    race: str = "inner",
    roller_load: float | None = None,
    radial_load: float | None = None,
    stribeck_factor: float = STRIBECK_ROLLER,
) -> ElementContact:
    """Roller-raceway line contact of a cylindrical roller bearing (body 1 roller, body 2 race).

    ``gamma = D/dm``; ``Rx = D (1 - gamma)/2`` (inner) or ``D (1 + gamma)/2`` (outer); kinematics
    as :func:`ball_bearing`. ``roller_length`` is the effective (straight) length B; load either
    the roller's Q or the radial load with Stribeck ``Q_max = 4.08 Fr/Z`` (zero clearance).
    """
    p = "element (roller_bearing)"
    D = require_range(f"{p}.roller_diameter", roller_diameter, 1e-4, 1.0, "m")
    gamma, _ = _bearing_geometry(D, pitch_diameter, 0.0, p)
    race = require_choice(f"{p}.race", race, ("inner", "outer"))
    Z = int(require_range(f"{p}.n_rollers", n_rollers, 3, 200, "-"))
    B = require_range(f"{p}.roller_length", roller_length, 1e-4, 1.0, "m")
    w = require_positive(f"{p}.shaft_speed", shaft_speed, "rad/s")
    require_range(f"{p}.stribeck_factor", stribeck_factor, 3.5, 6.0, "-")
    Rx = 0.5 * D * (1.0 - gamma) if race == "inner" else 0.5 * D * (1.0 + gamma)
    Q, how = _rolling_element_load(p, Z, 0.0, stribeck_factor, roller_load, radial_load, None)
    w_cage, u_roller, u_race = _bearing_kinematics(w, pitch_diameter, gamma)
    details: dict[str, Any] = {"gamma": gamma, "cage_speed": w_cage}
    if how != "given":
        details["load_rule"] = how
    return ElementContact("roller_bearing", "line", Rx, math.inf, u_roller, u_race, Q, B, details)


# -- gears ----------------------------------------------------------------------------------
def spur_gear(
    module: float,
    z1: int,
    z2: int,
    face_width: float,
    pinion_speed: float,
    pressure_angle: float = 20.0,
    helix_angle: float = 0.0,
    position: float = 0.0,
    torque: float | None = None,
    power: float | None = None,
) -> ElementContact:
    """Tooth contact of a standard spur or helical gear pair at a point of the path of contact.

    Standard gears (no profile shift, addendum = module, standard centre distance). Body 1 is the
    pinion flank, body 2 the wheel flank. In the transverse plane (ISO 21771, ISO 6336-2):
    ``tan(a_t) = tan(a_n)/cos(b)``, ``m_t = m_n/cos(b)``, pitch radii ``r_i = m_t z_i/2``, base
    radii ``r_bi = r_i cos(a_t)``; the radii of curvature at distance ``s`` from the pitch point
    along the line of action (``position``, positive towards the pinion tip) are
    ``rho1 = r1 sin(a_t) + s``, ``rho2 = r2 sin(a_t) - s``. In the normal section
    ``rho_n = rho_t/cos(b_b)`` with ``sin(b_b) = sin(b) cos(a_n)``, so
    ``Rx = rho1 rho2/((rho1 + rho2) cos(b_b))``. Rolling speeds ``u_i = w_i rho_i`` (the flank
    velocity relative to the contact point, normal to the contact line); the sliding speed is
    ``u1 - u2 = (w1 + w2) s``.

    Load: normal force ``F_n = F_t/(cos(a_t) cos(b_b))`` with ``F_t = T1/r1``. A spur pair
    carries it alone in the single-pair zone and half of it (equal sharing, the simplest rule)
    where two pairs mesh; a helical pair spreads it over the mean contact-line length
    ``b eps_a/cos(b_b)`` (ISO 6336-2). The returned line length is the face width for spur gears
    and that mean length for helical gears.

    Parameters
    ----------
    module : float
        Normal module m_n [m].
    z1, z2 : int
        Teeth of pinion and wheel.
    face_width : float
        b [m].
    pinion_speed : float
        w1 [rad/s].
    pressure_angle, helix_angle : float
        Normal pressure angle a_n and helix angle b [deg].
    position : float
        s [m] from the pitch point along the line of action; must lie on the path of contact.
    torque, power : float, optional
        Exactly one: pinion torque T1 [N m] or transmitted power P [W] (T1 = P/w1).
    """
    p = "element (spur_gear)"
    mn = require_range(f"{p}.module", module, 1e-5, 0.1, "m")
    z1 = int(require_range(f"{p}.z1", z1, 5, 1000, "-"))
    z2 = int(require_range(f"{p}.z2", z2, 5, 10000, "-"))
    b = require_range(f"{p}.face_width", face_width, 1e-4, 2.0, "m")
    w1 = require_positive(f"{p}.pinion_speed", pinion_speed, "rad/s")
    an = math.radians(require_range(f"{p}.pressure_angle", pressure_angle, 10.0, 35.0, "deg"))
    beta = math.radians(require_range(f"{p}.helix_angle", helix_angle, 0.0, 45.0, "deg"))
    if (torque is None) == (power is None):
        raise InputError(f"{p} needs exactly one of torque (N m, pinion) or power (W)")
    T1 = (require_positive(f"{p}.torque", torque, "N m") if torque is not None
          else require_positive(f"{p}.power", power, "W") / w1)

    at = math.atan(math.tan(an) / math.cos(beta))
    mt = mn / math.cos(beta)
    r1, r2 = 0.5 * mt * z1, 0.5 * mt * z2
    rb1, rb2 = r1 * math.cos(at), r2 * math.cos(at)
    ra1, ra2 = r1 + mn, r2 + mn
    beta_b = math.asin(math.sin(beta) * math.cos(an))
    g_f = math.sqrt(ra1**2 - rb1**2) - r1 * math.sin(at)  # pitch point to pinion-tip contact
    g_a = math.sqrt(ra2**2 - rb2**2) - r2 * math.sin(at)  # wheel-tip contact to pitch point
    p_bt = math.pi * mt * math.cos(at)
    eps_a = (g_a + g_f) / p_bt
    s = require_range(f"{p}.position", position, -g_a, g_f, "m")
    rho1 = r1 * math.sin(at) + s
    rho2 = r2 * math.sin(at) - s
    if rho1 <= 0.0 or rho2 <= 0.0:
        raise InputError(
            f"{p}.position = {s:.6g} m reaches a base circle (rho1 = {rho1:.6g}, rho2 = {rho2:.6g} m)"
        )
    Rx = rho1 * rho2 / ((rho1 + rho2) * math.cos(beta_b))
    w2 = w1 * z1 / z2
    u1, u2 = w1 * rho1, w2 * rho2
    Ft = T1 / r1
    Fn = Ft / (math.cos(at) * math.cos(beta_b))
    if beta == 0.0:
        single = (g_f - p_bt) <= s <= (p_bt - g_a)
        share = 1.0 if single or eps_a < 1.0 else 0.5
        length = b
    else:
        share = 1.0
        length = b * eps_a / math.cos(beta_b)
    details: dict[str, Any] = {
        "pitch_radius_1": r1, "pitch_radius_2": r2, "base_radius_1": rb1, "base_radius_2": rb2,
        "rho1": rho1, "rho2": rho2, "transverse_pressure_angle": math.degrees(at),
        "base_helix_angle": math.degrees(beta_b), "contact_ratio": eps_a,
        "path_start": -g_a, "path_end": g_f, "base_pitch": p_bt, "wheel_speed": w2,
        "pinion_torque": T1, "tangential_force": Ft, "normal_force": Fn, "load_share": share,
        "sliding_speed": u1 - u2,
    }
    return ElementContact("spur_gear", "line", Rx, math.inf, u1, u2, share * Fn, length, details)


# -- tribometers ----------------------------------------------------------------------------
def ball_on_disc(
    ball_radius: float,
    track_radius: float,
    disc_speed: float,
    load: float,
    ball_speed: float | None = None,
) -> ElementContact:
    """Ball on a rotating flat disc (optical EHL rigs, MTM, pin-on-disc).

    Body 1 is the ball, body 2 the disc. ``Rx = Ry = ball_radius``; the disc surface moves at
    ``u2 = disc_speed track_radius``. Without ``ball_speed`` the ball rolls freely on the disc
    (``u1 = u2``, pure rolling); a given ``ball_speed`` [m/s] is the ball's surface speed at the
    contact (an independently driven ball, MTM style; 0 for a fixed ball, pure sliding).
    """
    p = "element (ball_on_disc)"
    R = require_range(f"{p}.ball_radius", ball_radius, 1e-5, 1.0, "m")
    rt = require_range(f"{p}.track_radius", track_radius, 1e-4, 2.0, "m")
    wd = require_positive(f"{p}.disc_speed", disc_speed, "rad/s")
    P = require_positive(f"{p}.load", load, "N")
    u2 = wd * rt
    u1 = u2 if ball_speed is None else require_range(f"{p}.ball_speed", ball_speed, -1e3, 1e3, "m/s")
    _check_speed_sum(p, u1, u2)
    details = {"disc_surface_speed": u2, "ball_surface_speed": u1}
    return ElementContact("ball_on_disc", "point", R, R, u1, u2, P, details=details)


def ball_on_flat(
    ball_radius: float,
    stroke: float,
    frequency: float,
    load: float,
) -> ElementContact:
    """Ball reciprocating on a fixed flat (HFRR, SRV), at the middle of the stroke.

    Body 1 is the ball, body 2 the flat. Sinusoidal motion ``x = (L/2) sin(2 pi f t)`` over the
    full stroke ``L``: the maximum speed, at mid-stroke, is ``u1 = pi f L``; the flat is at rest,
    so the contact slides purely (S = 2). The cycle-mean speed is ``2 f L``.
    """
    p = "element (ball_on_flat)"
    R = require_range(f"{p}.ball_radius", ball_radius, 1e-5, 1.0, "m")
    L = require_range(f"{p}.stroke", stroke, 1e-6, 1.0, "m")
    f = require_range(f"{p}.frequency", frequency, 0.0, 1e4, "Hz", lo_open=True)
    P = require_positive(f"{p}.load", load, "N")
    u1 = math.pi * f * L
    details = {"max_speed": u1, "mean_speed": 2.0 * f * L}
    return ElementContact("ball_on_flat", "point", R, R, u1, 0.0, P, details=details)


# -- from a scene table ---------------------------------------------------------------------
#: For each element kind: the helper and the kind of quantity of each of its keys.
ELEMENT_KINDS: dict[str, tuple[Callable[..., ElementContact], dict[str, str]]] = {
    "ball_bearing": (ball_bearing, {
        "ball_diameter": "length", "pitch_diameter": "length", "n_balls": "dimensionless",
        "f_inner": "dimensionless", "f_outer": "dimensionless", "shaft_speed": "angular_speed",
        "race": "", "contact_angle": "angle", "ball_load": "force", "radial_load": "force",
        "axial_load": "force", "stribeck_factor": "dimensionless",
    }),
    "roller_bearing": (roller_bearing, {
        "roller_diameter": "length", "pitch_diameter": "length", "n_rollers": "dimensionless",
        "roller_length": "length", "shaft_speed": "angular_speed", "race": "",
        "roller_load": "force", "radial_load": "force", "stribeck_factor": "dimensionless",
    }),
    "spur_gear": (spur_gear, {
        "module": "length", "z1": "dimensionless", "z2": "dimensionless",
        "face_width": "length", "pinion_speed": "angular_speed", "pressure_angle": "angle",
        "helix_angle": "angle", "position": "length", "torque": "torque", "power": "power",
    }),
    "ball_on_disc": (ball_on_disc, {
        "ball_radius": "length", "track_radius": "length", "disc_speed": "angular_speed",
        "load": "force", "ball_speed": "speed",
    }),
    "ball_on_flat": (ball_on_flat, {
        "ball_radius": "length", "stroke": "length", "frequency": "frequency", "load": "force",
    }),
}


#: a speed of rotation [rad/s] given as a plain number at or above this is warned about: such
#: speeds are usually quoted in rpm, and 1500 rpm read as rad/s runs 9.5 times too fast
PLAIN_RAD_S = 100.0

#: Quantity of :data:`~ehl_multigrid.model.plausibility.PLAUSIBLE` of each ``[element]`` value.
ELEMENT_PLAUSIBLE: dict[str, str] = {
    "ball_diameter": "rolling_element_diameter", "roller_diameter": "rolling_element_diameter",
    "pitch_diameter": "pitch_diameter", "n_balls": "rolling_elements", "n_rollers": "rolling_elements",
    "roller_length": "roller_length", "shaft_speed": "angular_speed", "pinion_speed": "angular_speed",
    "disc_speed": "angular_speed", "ball_load": "load", "radial_load": "load", "axial_load": "load",
    "roller_load": "load", "load": "load", "module": "module", "z1": "teeth", "z2": "teeth",
    "face_width": "face_width", "torque": "torque", "power": "power", "ball_radius": "ball_radius",
    "track_radius": "track_radius", "ball_speed": "surface_speed", "stroke": "stroke",
    "frequency": "frequency",
}


def element_contact(table: dict[str, Any], section: str = "element", check: bool = True) -> ElementContact:
    """Build the contact of a scene's ``[element]`` table: ``kind`` plus the helper's arguments.

    Values may carry units (``ball_diameter = "7.938 mm"``, ``shaft_speed = "1500 rpm"``);
    plain numbers are SI, angles in degrees, speeds of rotation rad/s. With ``check``, every
    value outside the plausible range of real machine elements (:data:`ELEMENT_PLAUSIBLE`)
    warns (:func:`~ehl_multigrid.model.plausibility.check_plausible`), after the hard checks passed.
    """
    if not isinstance(table, dict):
        raise InputError(f"[{section}] must be a table with a 'kind' key")
    kind = require_choice(f"{section}.kind", table.get("kind"), tuple(ELEMENT_KINDS))
    helper, kinds = ELEMENT_KINDS[kind]
    args = {k: v for k, v in table.items() if k != "kind"}
    reject_unknown_keys(f"{section} ({kind})", args, set(kinds))
    unit_kinds = {k: q for k, q in kinds.items() if q}
    values = convert_table(section, args, unit_kinds)
    for key in ("n_balls", "n_rollers", "z1", "z2"):
        if key in values:
            v = values[key]
            if not float(v).is_integer():
                raise InputError(f"{section}.{key} = {v!r} must be a whole number")
            values[key] = int(v)
    try:
        contact = helper(**values)
    except TypeError as exc:  # a required argument is missing
        raise InputError(f"[{section}] kind = {kind!r}: {exc}") from None
    if check:
        for key, value in values.items():
            if key in ELEMENT_PLAUSIBLE and value is not None:
                given = isinstance(args.get(key), str) and any(c.isalpha() for c in args[key])
                ok = check_plausible(f"{section}.{key}", value, ELEMENT_PLAUSIBLE[key], units_given=given)
                if ok and not given and unit_kinds.get(key) == "angular_speed" and value >= PLAIN_RAD_S:
                    warn_implausible(
                        f"{section}.{key} = {value:g} is a plain number, taken as rad/s ({value * 30.0 / math.pi:.0f} "
                        f"rpm); speeds of rotation are usually quoted in rpm: if you meant {value:g} rpm, write "
                        f"'{value:g} rpm' (a value with its unit, '{value:g} rad/s', is taken as given)")
    return contact
