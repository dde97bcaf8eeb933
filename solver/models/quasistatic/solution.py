"""The quasi-static solution as plain SI numpy arrays (the dynamic model starts from it)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class OperatingPoint:
    """Operating condition in SI units, loads on the inner ring (case-format.md signs).

    ``misalignment`` is the imposed tilt angle [rad] about the axis at azimuth
    ``misalignment_axis``; when ``tilting_moment`` [N m] is not None the tilt is solved instead and
    the moment acts about the axis at azimuth ``moment_axis`` (0 = moment-free tilt).
    """

    inner_ring_speed: float = 0.0  # rad/s about +x
    outer_ring_speed: float = 0.0  # rad/s about +x
    axial_load: float = 0.0  # N, +x presses the inner ring into the balls
    radial_load: float = 0.0  # N
    radial_load_angle: float = 0.0  # rad, azimuth psi of the radial load
    misalignment: float = 0.0  # rad
    misalignment_axis: float = 0.5 * np.pi  # rad
    misalignment_frame: str = "space"
    tilting_moment: float | None = None  # N m; None = tilt imposed
    moment_axis: float = 0.5 * np.pi  # rad

    @property
    def tilt_is_free(self) -> bool:
        return self.tilting_moment is not None

    def applied_loads(self) -> np.ndarray:
        """(Fx, Fy, Fz, My, Mz) [N, N m] applied to the inner ring (moments zero for imposed
        tilt)."""
        moment = self.tilting_moment if self.tilting_moment is not None else 0.0
        return np.array(
            [
                self.axial_load,
                self.radial_load * np.cos(self.radial_load_angle),
                self.radial_load * np.sin(self.radial_load_angle),
                moment * np.cos(self.moment_axis),
                moment * np.sin(self.moment_axis),
            ]
        )

    def imposed_tilt(self) -> np.ndarray:
        """(theta_y, theta_z) [rad] of the imposed misalignment: rotation vector along the tilt
        axis."""
        if self.tilt_is_free:
            return np.zeros(2)
        return self.misalignment * np.array(
            [np.cos(self.misalignment_axis), np.sin(self.misalignment_axis)]
        )


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
    ball_position: np.ndarray = field(
        default=None, repr=False
    )  # (Z, 2) relative to the outer groove centre
    operating: OperatingPoint | None = field(default=None, repr=False)
