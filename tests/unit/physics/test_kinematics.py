"""Rolling-kinematics identities of solver.physics.kinematics, checked with independent 3-D vector
algebra in the cage frame (numpy cross products), not with the module's own closed forms."""

import math

import numpy as np
import pytest

from solver.physics import kinematics as kin

E_X = np.array([1.0, 0.0, 0.0])  # components in (e_x, e_r, e_theta)
E_R = np.array([0.0, 1.0, 0.0])


def u(alpha):
    return np.array([math.sin(alpha), math.cos(alpha), 0.0])


def state(alpha_i, alpha_o, gamma_p, omega_i, omega_o, inner_control):
    beta = kin.attitude_angle(alpha_i, alpha_o, gamma_p, inner_control)
    omega_c, omega_r = kin.orbital_and_spin_speed(alpha_i, alpha_o, beta, gamma_p, omega_i, omega_o)
    return beta, omega_c, omega_r


ANGLES = [(0.3, 0.3), (0.7, 0.5), (0.45, 0.6), (0.2, -0.1), (-0.05, 0.1)]


@pytest.mark.parametrize("alpha", [0.0, 0.26, 0.7])
@pytest.mark.parametrize("inner_control", [False, True])
def test_cage_speed_is_kinematic_for_equal_contact_angles(alpha, inner_control):
    D, dm = 0.0127, 0.065
    gamma = D * math.cos(alpha) / dm
    _, omega_c, _ = state(alpha, alpha, D / dm, 100.0, 0.0, inner_control)
    assert omega_c == pytest.approx(0.5 * (1.0 - gamma) * 100.0, rel=1e-13)
    # outer ring turning, inner fixed: the cage follows at (1 + gamma)/2
    _, omega_c, _ = state(alpha, alpha, D / dm, 0.0, 100.0, inner_control)
    assert omega_c == pytest.approx(0.5 * (1.0 + gamma) * 100.0, rel=1e-13)


@pytest.mark.parametrize("alpha_i, alpha_o", ANGLES)
@pytest.mark.parametrize("omega_i, omega_o", [(1000.0, 0.0), (-700.0, 0.0), (300.0, -200.0)])
@pytest.mark.parametrize("inner_control", [False, True])
def test_rolling_without_slip_at_both_contact_centres(
    alpha_i, alpha_o, omega_i, omega_o, inner_control
):
    """In the cage frame (ball centre fixed) the ball surface and the ring surface move together at
    both contact points, and there is no spin at the controlling contact."""
    D, dm = 0.01, 0.06
    beta, omega_c, omega_r = state(alpha_i, alpha_o, D / dm, omega_i, omega_o, inner_control)
    w_ball = omega_r * (math.cos(beta) * E_X - math.sin(beta) * E_R)
    centre = np.array([0.0, 0.5 * dm, 0.0])  # ball centre relative to the bearing axis
    for alpha, ring_speed, side in ((alpha_o, omega_o, 1.0), (alpha_i, omega_i, -1.0)):
        lever = side * 0.5 * D * u(alpha)
        v_ball = np.cross(w_ball, lever)
        # cross product in (e_x, e_r, e_theta): right-handed, so numpy's cross applies
        v_ring = np.cross((ring_speed - omega_c) * E_X, centre + lever)
        np.testing.assert_allclose(v_ball, v_ring, atol=1e-12 * abs(omega_i - omega_o) * dm)
        spin, roll = kin.spin_and_roll(alpha, beta, omega_r, ring_speed - omega_c)
        w_rel = w_ball - (ring_speed - omega_c) * E_X
        assert spin == pytest.approx(float(w_rel @ u(alpha)), abs=1e-9)
        controlling = (side < 0) == inner_control
        if controlling:
            assert abs(spin) <= 1e-12 * abs(omega_r)
        else:
            assert abs(spin) > 1e-6 * abs(omega_r) or abs(alpha_i - alpha_o) < 1e-12


@pytest.mark.parametrize("alpha_i, alpha_o", ANGLES)
def test_orbital_speed_closed_forms(alpha_i, alpha_o):
    """physics.md §2.5.3: outer control omega_c/omega = (1 - g' cos a_i)/(1 + cos(a_i - a_o)),
    inner control (cos(a_i - a_o) - g' cos a_o)/(1 + cos(a_i - a_o))."""
    gp = 0.18
    _, omega_c, _ = state(alpha_i, alpha_o, gp, 1.0, 0.0, False)
    assert omega_c == pytest.approx(
        (1 - gp * math.cos(alpha_i)) / (1 + math.cos(alpha_i - alpha_o)), rel=1e-12
    )
    _, omega_c, _ = state(alpha_i, alpha_o, gp, 1.0, 0.0, True)
    expected = (math.cos(alpha_i - alpha_o) - gp * math.cos(alpha_o)) / (
        1 + math.cos(alpha_i - alpha_o)
    )
    assert omega_c == pytest.approx(expected, rel=1e-12)


def test_spin_speed_sign_and_magnitude():
    """Spin opposes the shaft (omega_R < 0 for omega > 0); at alpha = 0 (beta = 0) its magnitude is
    the classic ball spin frequency (d_m / 2D) omega (1 - gamma^2) (physics.md §2.8.5, BSF)."""
    D, dm = 0.0127, 0.065
    beta, omega_c, omega_r = state(0.0, 0.0, D / dm, 10.0, 0.0, False)
    assert beta == 0.0
    gamma = D / dm
    assert omega_r < 0.0
    assert -omega_r == pytest.approx(dm / (2 * D) * 10.0 * (1 - gamma**2), rel=1e-13)


@pytest.mark.parametrize("omega", [1500.0, -1500.0])
def test_gyroscopic_moment_is_rate_of_angular_momentum(omega):
    """M_g e_theta = omega_c e_x x (J omega_b) for either direction of rotation (physics.md
    §2.5.4)."""
    J = 2.0e-8
    beta, omega_c, omega_r = state(0.6, 0.45, 0.17, omega, 0.0, False)
    h = J * omega_r * (math.cos(beta) * E_X - math.sin(beta) * E_R)
    rate = np.cross(omega_c * E_X, h)
    m_g = kin.gyroscopic_moment(J, omega_r, omega_c, beta)
    np.testing.assert_allclose(rate, [0.0, 0.0, m_g], atol=1e-15)
    assert m_g > 0.0


@pytest.mark.parametrize("alpha_i, alpha_o", ANGLES)
def test_kingsbury_latitudes(alpha_i, alpha_o):
    beta = kin.attitude_angle(alpha_i, alpha_o, 0.15, False)
    lat_o, lon_o = kin.contact_latitude_longitude(*u(alpha_o), beta)
    lat_i, lon_i = kin.contact_latitude_longitude(*(-u(alpha_i)), beta)
    assert lat_o == pytest.approx(alpha_o - beta, abs=1e-14)
    assert lat_i == pytest.approx(-(alpha_i - beta), abs=1e-14)
    assert lon_o == pytest.approx(0.0, abs=1e-15)
    assert lon_i == pytest.approx(math.pi, abs=1e-15)


def test_latitude_of_the_spin_axis_and_equator():
    beta = 0.4
    lat, _ = kin.contact_latitude_longitude(math.cos(beta), -math.sin(beta), 0.0, beta)
    assert lat == pytest.approx(0.5 * math.pi)
    lat, lon = kin.contact_latitude_longitude(0.0, 0.0, 1.0, beta)  # e_theta = y_b
    assert lat == pytest.approx(0.0, abs=1e-15)
    assert lon == pytest.approx(0.5 * math.pi)


def test_jones_race_control_criterion():
    assert kin.race_control_is_inner(100.0, 90.0, 1e-3, 1e-3, 1.1, 1.1, 0.3, 0.3)
    assert not kin.race_control_is_inner(100.0, 90.0, 1e-3, 1e-3, 1.1, 1.1, 1.5, 0.0)
    assert not kin.race_control_is_inner(0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.3, 0.2)
