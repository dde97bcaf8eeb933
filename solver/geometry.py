"""Derived internal geometry of an angular contact ball bearing, in SI units.

One place for every geometric quantity of physics.md §2.2. Frames (case-format.md): x is the bearing
axis, pointing where the inner ring carries thrust; the outer contact lies on the +x side of the
ball centre, the inner contact on the -x side. Positions here are those of the *just-touching*
reference state: rings concentric, every ball touching both races at the free contact angle, no
load.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .materials import Material, effective_modulus


@dataclass(frozen=True)
class BearingGeometry:
    """Bearing geometry and materials, SI units (m, rad, kg, Pa).

    :func:`solver.inputs.bearing_geometry` builds it from a case; tests build it directly.
    """

    ball_count: int
    ball_diameter: float  # D, m
    pitch_diameter: float  # d_m, m (diameter of the ball-centre circle)
    inner_conformity: float  # f_i = r_i / D
    outer_conformity: float  # f_o = r_o / D
    free_contact_angle: float  # alpha_0, rad
    ball_material: Material
    ring_material: Material
    inner_shoulder_diameter: float = math.nan  # m, NaN when not given
    outer_shoulder_diameter: float = math.nan  # m, NaN when not given
    #: nominal contact angle alpha, rad, the angle ISO 281 rates the bearing at: 0 for a radial
    #: deep-groove bearing (a case that gives the diametral clearance), NaN for the free contact
    #: angle (an angular contact bearing)
    nominal_contact_angle: float = math.nan

    @property
    def rating_contact_angle(self) -> float:
        """The nominal contact angle ISO 281 rates the bearing at, rad: ``nominal_contact_angle``,
        or the free contact angle when that is NaN."""
        if math.isnan(self.nominal_contact_angle):
            return self.free_contact_angle
        return self.nominal_contact_angle

    # ---- groove geometry ----------------------------------------------------------------------
    @property
    def inner_groove_radius(self) -> float:
        """r_i = f_i D, m."""
        return self.inner_conformity * self.ball_diameter

    @property
    def outer_groove_radius(self) -> float:
        """r_o = f_o D, m."""
        return self.outer_conformity * self.ball_diameter

    @property
    def total_conformity(self) -> float:
        """B = f_i + f_o - 1."""
        return self.inner_conformity + self.outer_conformity - 1.0

    @property
    def curvature_center_distance(self) -> float:
        """A_0 = B D: unloaded distance between the groove curvature centres, m."""
        return self.total_conformity * self.ball_diameter

    @property
    def diametral_clearance(self) -> float:
        """P_d = 2 A_0 (1 - cos alpha_0), m."""
        return 2.0 * self.curvature_center_distance * (1.0 - math.cos(self.free_contact_angle))

    @property
    def free_end_play(self) -> float:
        """P_e = 2 A_0 sin alpha_0, m."""
        return 2.0 * self.curvature_center_distance * math.sin(self.free_contact_angle)

    @property
    def inner_curvature_center_radius(self) -> float:
        """rho_i^c: radius of the inner groove curvature-centre circle (ring frame), m."""
        D, a0 = self.ball_diameter, self.free_contact_angle
        return 0.5 * self.pitch_diameter + (self.inner_conformity - 0.5) * D * math.cos(a0)

    @property
    def inner_curvature_center_axial(self) -> float:
        """x_i^c: axial position of the inner groove curvature-centre circle, m."""
        return (
            (self.inner_conformity - 0.5) * self.ball_diameter * math.sin(self.free_contact_angle)
        )

    @property
    def outer_curvature_center_radius(self) -> float:
        """rho_o^c: radius of the outer groove curvature-centre circle, m."""
        D, a0 = self.ball_diameter, self.free_contact_angle
        return 0.5 * self.pitch_diameter - (self.outer_conformity - 0.5) * D * math.cos(a0)

    @property
    def outer_curvature_center_axial(self) -> float:
        """x_o^c: axial position of the outer groove curvature-centre circle, m."""
        return (
            -(self.outer_conformity - 0.5) * self.ball_diameter * math.sin(self.free_contact_angle)
        )

    @property
    def inner_groove_bottom_diameter(self) -> float:
        """d_i = 2 rho_i^c - 2 r_i, m."""
        return 2.0 * self.inner_curvature_center_radius - 2.0 * self.inner_groove_radius

    @property
    def outer_groove_bottom_diameter(self) -> float:
        """d_o = 2 rho_o^c + 2 r_o, m."""
        return 2.0 * self.outer_curvature_center_radius + 2.0 * self.outer_groove_radius

    # ---- ball ---------------------------------------------------------------------------------
    @property
    def ball_mass(self) -> float:
        """m = rho pi D^3 / 6, kg."""
        return self.ball_material.density * math.pi * self.ball_diameter**3 / 6.0

    @property
    def ball_inertia(self) -> float:
        """J = m D^2 / 10 (solid sphere), kg m^2."""
        return self.ball_mass * self.ball_diameter**2 / 10.0

    @property
    def effective_modulus(self) -> float:
        """E' = 2 / eta of the ball-ring material pair, Pa."""
        return effective_modulus(self.ball_material, self.ring_material)

    def gamma(self, contact_angle: float) -> float:
        """gamma = D cos(alpha) / d_m (dimensionless)."""
        return self.ball_diameter * math.cos(contact_angle) / self.pitch_diameter

    @property
    def gamma_prime(self) -> float:
        """gamma' = D / d_m."""
        return self.ball_diameter / self.pitch_diameter


def free_contact_angle_from_clearance(
    ball_diameter: float,
    inner_conformity: float,
    outer_conformity: float,
    diametral_clearance: float,
) -> float:
    """alpha_0 = arccos(1 - P_d / (2 A_0)), rad. Lengths in m; P_d must lie in [0, 2 A_0]."""
    a0 = (inner_conformity + outer_conformity - 1.0) * ball_diameter
    return math.acos(1.0 - diametral_clearance / (2.0 * a0))
