"""How much oil the balls and the cage move through, by lubrication method (pure functions, SI).

The dynamic model's drag laws (ball drag, cage-face drag: solver.models.dynamic.kernels,
solver.physics.drag) act in a homogeneous oil-air mixture of oil volume fraction ``phi``. This
module gives ``phi`` for each lubrication method of docs/lubrication.md; every law is a closed form
of the geometry and the supply, each marked there [E] (estimate) with its basis:

- **oil supply through the bearing** (oil-air, oil mist, oil jet): the oil supplied at the volume
  flow ``Q`` [m^3/s] stays in the bearing's free cavity for one cage revolution before the balls
  and the cage fling it out, so the cavity holds ``Q T_cage`` of oil and
  ``phi = min(1, Q T_cage / V_cavity)``, ``T_cage = 2 pi / |omega_cage|``. Zero flow: air only;
  ``phi`` grows in proportion to the flow and falls as 1 / speed.
- **oil bath**: each ball dips into the bath over part of its orbit; ``phi`` is the orbit-averaged
  fraction of a ball's volume below the oil level (the mixture seen by the balls as a time average).
  A level at or below the lowest point of the lowest ball: no oil (no churning); a level above the
  highest ball: 1 (submerged).

The free cavity is the annulus between the rings that the balls and the cage sweep: radially
``d_m / 2 +- CAVITY_HALF_HEIGHT D`` (the band between the estimated ring shoulders, where the cage's
side faces are also taken to lie, solver.models.dynamic.params), axially one ball diameter, less
the volume of the balls.
"""

from __future__ import annotations

import math

import numpy as np

#: Radial half-height of the bearing's free cavity about the pitch circle, in ball diameters.
CAVITY_HALF_HEIGHT = 0.35
#: Orbit angles of the bath average (midpoint rule; the integrand is smooth and periodic).
BATH_ORBIT_POINTS = 720


def cavity_volume(pitch_diameter: float, ball_diameter: float, ball_count: int) -> float:
    """Free volume [m^3] of the bearing's cavity: the annulus of radial height
    ``2 CAVITY_HALF_HEIGHT D`` and axial width D on the pitch circle, less the balls."""
    if not (pitch_diameter > 0.0 and ball_diameter > 0.0 and ball_count > 0):
        raise ValueError("pitch diameter, ball diameter and ball count must be positive")
    annulus = math.pi * pitch_diameter * 2.0 * CAVITY_HALF_HEIGHT * ball_diameter * ball_diameter
    balls = ball_count * math.pi * ball_diameter**3 / 6.0
    return annulus - balls


def epicyclic_cage_speed(
    inner_speed: float,
    outer_speed: float,
    pitch_diameter: float,
    ball_diameter: float,
    angle: float,
) -> float:
    """Cage speed [rad/s] of rolling without slip: ``((1 - g) w_i + (1 + g) w_o) / 2`` with
    ``g = D cos(alpha) / d_m`` (ring speeds [rad/s], contact angle ``angle`` [rad])."""
    g = ball_diameter * math.cos(angle) / pitch_diameter
    return 0.5 * ((1.0 - g) * inner_speed + (1.0 + g) * outer_speed)


def supply_oil_fraction(oil_flow: float, cage_speed: float, cavity: float) -> float:
    """Oil volume fraction of the mixture fed by a supply of ``oil_flow`` [m^3/s] that stays one
    cage revolution (``cage_speed`` [rad/s]) in the free ``cavity`` [m^3]:
    ``min(1, Q 2 pi / |omega_cage| / V)``. 0 for no flow; 1 (the cavity fills) for a cage at
    rest with a flow."""
    if oil_flow < 0.0 or cavity <= 0.0:
        raise ValueError("the oil flow must be >= 0 and the cavity volume > 0")
    if oil_flow == 0.0:
        return 0.0
    if cage_speed == 0.0:
        return 1.0
    return min(1.0, oil_flow * 2.0 * math.pi / abs(cage_speed) / cavity)


def immersed_ball_fraction(depth: np.ndarray | float, ball_diameter: float):
    """Fraction of a ball's volume below a level ``depth`` [m] above the ball's lowest point
    (a spherical cap: ``x^2 (3 - 2 x)`` with ``x = depth / D`` clipped to [0, 1])."""
    x = np.clip(np.asarray(depth, dtype=float) / ball_diameter, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


def bath_oil_fraction(oil_level: float, pitch_diameter: float, ball_diameter: float) -> float:
    """Orbit-averaged fraction of a ball's volume below the bath's surface, ``oil_level`` [m]
    above the lowest point of the lowest ball (the bottom of the outer raceway; horizontal
    axis). A ball at orbit angle theta (0 at the bottom) has its lowest point
    ``d_m / 2 (1 - cos theta)`` above that of the lowest ball."""
    if pitch_diameter <= 0.0 or ball_diameter <= 0.0:
        raise ValueError("pitch and ball diameters must be positive")
    theta = (np.arange(BATH_ORBIT_POINTS) + 0.5) * (2.0 * math.pi / BATH_ORBIT_POINTS)
    lowest = 0.5 * pitch_diameter * (1.0 - np.cos(theta))
    return float(np.mean(immersed_ball_fraction(oil_level - lowest, ball_diameter)))


__all__ = [
    "BATH_ORBIT_POINTS",
    "CAVITY_HALF_HEIGHT",
    "bath_oil_fraction",
    "cavity_volume",
    "epicyclic_cage_speed",
    "immersed_ball_fraction",
    "supply_oil_fraction",
]
