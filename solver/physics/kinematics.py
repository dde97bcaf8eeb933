"""Rolling kinematics of a ball between two rings under race control (physics.md §2.5.3-2.5.7).

Pure numba functions, SI units (rad, rad/s, kg m², N m). Frames (physics.md §2.1): the azimuth frame
of a ball has the unit vectors (e_x, e_r, e_theta) = (bearing axis, radial outward,
circumferential), right handed. The outer contact lies on the +x side of the ball centre along
u(alpha_o) = sin(alpha_o) e_x + cos(alpha_o) e_r, the inner contact on the -x side along
-u(alpha_i).

Everything is written in the cage frame, which rotates with the ball's orbital speed omega_c about
e_x, so that a rotating outer ring is handled the same way as a rotating inner ring. The ball's
angular velocity relative to the cage is

    omega_b = omega_R * z_b,   z_b = cos(beta) e_x - sin(beta) e_r      (attitude direction)

with beta the attitude angle and omega_R the signed spin speed (omega_R < 0 when the inner ring
turns at omega > 0 with the outer ring fixed).

Ball-fixed frame at t = 0 (used for the ball latitude/longitude of a contact, and by the dynamic
model for its initial orientation): z_b as above, y_b = e_theta,
x_b = y_b x z_b = sin(beta) e_x + cos(beta) e_r. The latitude of a contact whose unit vector from
the ball centre is e is asin(e . z_b), its longitude atan2(e . y_b, e . x_b); for the outer contact
this gives alpha_o - beta (longitude 0), for the inner one -(alpha_i - beta) (longitude 180°):
Kingsbury's regular-precession latitudes (physics.md §1.5).
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def attitude_angle(inner_contact_angle, outer_contact_angle, gamma_prime, inner_control):
    """Attitude angle beta [rad] of the spin axis from the bearing axis, from zero spin at the
    controlling contact: outer control tan(beta) = sin(alpha_o) / (cos(alpha_o) + gamma'), inner
    control tan(beta) = sin(alpha_i) / (cos(alpha_i) - gamma'). ``gamma_prime`` = D / d_m.
    """
    if inner_control:
        return math.atan2(
            math.sin(inner_contact_angle), math.cos(inner_contact_angle) - gamma_prime
        )
    return math.atan2(math.sin(outer_contact_angle), math.cos(outer_contact_angle) + gamma_prime)


@njit(cache=True)
def rolling_coefficients(inner_contact_angle, outer_contact_angle, beta, gamma_prime):
    """(c_i, c_o): c_o = cos(alpha_o - beta) / (1 + gamma' cos alpha_o),
    c_i = cos(alpha_i - beta) / (1 - gamma' cos alpha_i): the ring-to-ball speed ratios of pure
    rolling at the contact centres (see :func:`orbital_and_spin_speed`)."""
    c_o = math.cos(outer_contact_angle - beta) / (1.0 + gamma_prime * math.cos(outer_contact_angle))
    c_i = math.cos(inner_contact_angle - beta) / (1.0 - gamma_prime * math.cos(inner_contact_angle))
    return c_i, c_o


@njit(cache=True)
def orbital_and_spin_speed(
    inner_contact_angle, outer_contact_angle, beta, gamma_prime, inner_ring_speed, outer_ring_speed
):
    """Orbital speed omega_c and spin speed omega_R [rad/s] from pure rolling at both contact
    centres.

    In the cage frame, rolling at the outer contact gives omega_R gamma' c_o = omega_o - omega_c and
    at the inner contact -omega_R gamma' c_i = omega_i - omega_c, so

        omega_c = (omega_i c_o + omega_o c_i) / (c_i + c_o),
        omega_R = (omega_o - omega_i) / (gamma' (c_i + c_o)).

    Ring speeds are about +x (right-hand rule), rad/s.
    """
    c_i, c_o = rolling_coefficients(inner_contact_angle, outer_contact_angle, beta, gamma_prime)
    total = c_i + c_o
    omega_c = (inner_ring_speed * c_o + outer_ring_speed * c_i) / total
    omega_r = (outer_ring_speed - inner_ring_speed) / (gamma_prime * total)
    return omega_c, omega_r


@njit(cache=True)
def gyroscopic_moment(ball_inertia, spin_speed, orbital_speed, beta):
    """Signed gyroscopic moment M_g [N m] that the contacts must apply to the ball, along +e_theta.

    The ball's spin angular momentum H = J omega_R z_b is fixed in the cage frame, which turns at
    omega_c e_x, so dH/dt = omega_c e_x x H = -J omega_c omega_R sin(beta) e_theta. The returned
    value is M_g = -J omega_c omega_R sin(beta): positive for either direction of shaft rotation
    with the outer ring fixed (omega_c and omega_R have opposite signs).
    """
    return -ball_inertia * orbital_speed * spin_speed * math.sin(beta)


@njit(cache=True)
def race_control_is_inner(
    inner_load,
    outer_load,
    inner_semi_major,
    outer_semi_major,
    inner_elliptic_e,
    outer_elliptic_e,
    inner_contact_angle,
    outer_contact_angle,
):
    """Jones criterion: inner-race control when Q_i a_i E_i cos(alpha_i - alpha_o) > Q_o a_o E_o.

    E_i, E_o are the complete elliptic integrals of the second kind of the two contact ellipses. A
    ball with no load at either contact is given outer control.
    """
    lhs = (
        inner_load
        * inner_semi_major
        * inner_elliptic_e
        * math.cos(inner_contact_angle - outer_contact_angle)
    )
    rhs = outer_load * outer_semi_major * outer_elliptic_e
    return lhs > rhs


@njit(cache=True)
def ball_angular_velocity(spin_speed, beta, orbital_speed):
    """Inertial ball angular velocity in azimuth-frame components (x, r, theta), rad/s:
    omega_c e_x + omega_R (cos(beta) e_x - sin(beta) e_r)."""
    return (orbital_speed + spin_speed * math.cos(beta), -spin_speed * math.sin(beta), 0.0)


@njit(cache=True)
def spin_and_roll(contact_angle, beta, spin_speed, ring_speed_in_cage):
    """(omega_spin, omega_roll) [rad/s] of a contact (physics.md §2.5.7), any race control.

    omega_rel = omega_b - Omega e_x with Omega the ring speed relative to the cage;
    omega_spin = omega_rel . u(alpha), omega_roll = omega_rel . (cos(alpha) e_x - sin(alpha) e_r).
    The same formula serves both contacts (flipping the normal flips both projections).
    """
    wx = spin_speed * math.cos(beta) - ring_speed_in_cage
    wr = -spin_speed * math.sin(beta)
    sa = math.sin(contact_angle)
    ca = math.cos(contact_angle)
    return wx * sa + wr * ca, wx * ca - wr * sa


@njit(cache=True)
def contact_latitude_longitude(e_x, e_r, e_theta, beta):
    """(latitude, longitude) [rad] on the ball of the unit vector (e_x, e_r, e_theta) from the ball
    centre, in the ball-fixed frame at t = 0 (module docstring). Longitude in (-pi, pi]."""
    sb = math.sin(beta)
    cb = math.cos(beta)
    along_z = e_x * cb - e_r * sb
    along_x = e_x * sb + e_r * cb
    along_z = min(1.0, max(-1.0, along_z))
    # "+ 0.0" turns a negative zero into +0 so that a contact exactly opposite x_b reads +180°, not
    # -180°.
    return math.asin(along_z), math.atan2(e_theta + 0.0, along_x)
