"""The quasi-static solution as plain SI numpy arrays (the dynamic model starts from it)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from solver.inputs import OperatingPoint


@dataclass
class QuasiStaticSolution:
    """Jones–Harris equilibrium of one operating point. SI units, angles in rad.

    Per ball (Z) and per contact (Z, 2) with columns [inner, outer]. Positions are inertial with the
    origin at the outer ring centre on the plane of the ball centres in the just-touching state;
    ``ball_center`` columns are (axial x, radial r) in the ball's meridian plane at
    ``ball_azimuth``. ``ball_angular_velocity`` is inertial (x, y, z). Deflections, loads are 0 at
    open contacts; the contact angle is then the geometric one of the line between the two groove
    curvature centres (where the ball would touch if the gap closed; a ball without any contact sits
    on that line). ``applied_moment`` (y, z) is the moment acting on the inner ring: the given one
    when the tilt is solved, otherwise the moment needed to hold the imposed tilt.
    ``race_traction`` is the friction force on the ball in the meridian plane that takes the
    gyroscopic moment: at the inner contact along (cos alpha_i e_x - sin alpha_i e_r), at the outer
    along (-cos alpha_o e_x + sin alpha_o e_r) (race control: lambda M_g / D; traction balance: the
    integrated tractions).
    """

    ball_azimuth: np.ndarray
    ball_center: np.ndarray
    contact_angle: np.ndarray
    contact_load: np.ndarray
    contact_deflection: np.ndarray
    orbital_speed: np.ndarray
    spin_speed: np.ndarray
    attitude_angle: np.ndarray
    ball_angular_velocity: np.ndarray
    race_control: np.ndarray  # str "inner" / "outer"
    inner_ring_offset: np.ndarray  # (3,) m
    inner_ring_tilt: np.ndarray  # (2,) rad, rotation vector (theta_y, theta_z)
    cage_speed: float  # rad/s, mean of the balls' orbital speeds
    centrifugal_force: np.ndarray
    gyroscopic_moment: np.ndarray
    applied_moment: np.ndarray  # (2,) N m
    inner_ring_speed: float  # rad/s
    outer_ring_speed: float  # rad/s
    converged: bool
    residual: float  # scaled ring residual norm (relative to the force scale)
    iterations: int
    force_scale: float  # N
    race_control_note: str = ""
    race_traction: np.ndarray = field(
        default=None, repr=False
    )  # (Z, 2) [inner, outer] transverse friction on the ball [N], see below
    ball_speeds: str = "race_control"  # "race_control" or "traction" (where the speeds came from)
    ball_speeds_note: str = ""  # why the traction balance was asked for but not used, else ""
    ball_position: np.ndarray = field(
        default=None, repr=False
    )  # (Z, 2) relative to the outer groove centre
    operating: OperatingPoint | None = field(default=None, repr=False)
