"""Quasi-static Jones–Harris model: equilibrium, classic static limits, kinematics, trends,
symmetry, robustness. References are independent of the solver: equilibrium is recomputed from the
outputs, Hertz constants come from the exact module (solver.physics.hertz), static load
distributions from closed forms / quadrature / a scalar root finder."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from solver.errors import NoSolutionError
from solver.geometry import BearingGeometry, free_contact_angle_from_clearance
from solver.materials import BUILTIN_MATERIALS
from solver.models.quasistatic import solve_operating_point
from solver.physics.hertz import race_contact
from tests.helpers.cases import bearing_218, operating_point, spindle_bearing, spindle_geometry

STEEL = BUILTIN_MATERIALS["bearing_steel"]
SI3N4 = BUILTIN_MATERIALS["silicon_nitride"]
RPM = math.pi / 30.0


def spindle(ball_count=18):
    return spindle_bearing(ball_count=ball_count)


def deep_groove(clearance, ball_count=9):
    alpha0 = free_contact_angle_from_clearance(12.7e-3, 0.52, 0.52, clearance)
    return BearingGeometry(ball_count, 12.7e-3, 65.0e-3, 0.52, 0.52, alpha0, STEEL, STEEL)


def stiffness(geometry, alpha, race):
    return float(race_contact(geometry, alpha, 1.0, race).stiffness)


# ---- independent equilibrium check ------------------------------------------------------------
def check_equilibrium(geometry, op, sol, rel=1e-8):
    """Recompute every ball's and the ring's balance from the outputs alone."""
    D = geometry.ball_diameter
    z = geometry.ball_count
    psi = sol.ball_azimuth
    a_i, a_o = sol.contact_angle[:, 0], sol.contact_angle[:, 1]
    q_i, q_o = sol.contact_load[:, 0], sol.contact_load[:, 1]
    inner = sol.race_control == "inner"
    traction = sol.race_control == "traction"
    lam_o = np.where(inner, 1.0, 2.0)
    lam_i = np.where(inner, 1.0, 0.0)
    m_g = sol.gyroscopic_moment
    f_c = sol.centrifugal_force
    # friction taking the gyroscopic moment: lambda M_g / D under race control (checked against the
    # reported values), the integrated tractions of the traction balance as reported
    t_i = np.where(traction, sol.race_traction[:, 0], lam_i * m_g / D)
    t_o = np.where(traction, sol.race_traction[:, 1], lam_o * m_g / D)
    np.testing.assert_allclose(sol.race_traction[:, 0], t_i, rtol=1e-12, atol=0)
    np.testing.assert_allclose(sol.race_traction[:, 1], t_o, rtol=1e-12, atol=0)
    assert np.all(np.isfinite(sol.contact_load)) and np.all(np.isfinite(sol.contact_angle))
    # 1. geometry: deflections and angles from the ball centres and the ring displacement
    x_o, r_o = geometry.outer_curvature_center_axial, geometry.outer_curvature_center_radius
    theta_y, theta_z = sol.inner_ring_tilt
    ci_x = (
        geometry.inner_curvature_center_axial
        + sol.inner_ring_offset[0]
        + geometry.inner_curvature_center_radius * (theta_y * np.sin(psi) - theta_z * np.cos(psi))
    )
    ci_r = (
        geometry.inner_curvature_center_radius
        + sol.inner_ring_offset[1] * np.cos(psi)
        + sol.inner_ring_offset[2] * np.sin(psi)
    )
    bx, br = sol.ball_center[:, 0], sol.ball_center[:, 1]
    d_o = np.hypot(bx - x_o, br - r_o) - (geometry.outer_conformity - 0.5) * D
    d_i = np.hypot(ci_x - bx, ci_r - br) - (geometry.inner_conformity - 0.5) * D
    # contact only with overlap on the raceway side of the groove-centre circle (cos(alpha) > 0)
    d_o = np.where(br - r_o > 0, np.maximum(d_o, 0), 0.0)
    d_i = np.where(ci_r - br > 0, np.maximum(d_i, 0), 0.0)
    np.testing.assert_allclose(sol.contact_deflection[:, 1], d_o, rtol=1e-9, atol=1e-9 * D * 1e-3)
    np.testing.assert_allclose(sol.contact_deflection[:, 0], d_i, rtol=1e-9, atol=1e-9 * D * 1e-3)
    # loaded contacts: direction between the ball centre and the groove centre; open contacts: the
    # line between the two groove centres
    line = np.arctan2(ci_x - x_o, ci_r - r_o)
    expected_o = np.where(q_o > 0, np.arctan2(bx - x_o, br - r_o), line)
    expected_i = np.where(q_i > 0, np.arctan2(ci_x - bx, ci_r - br), line)
    np.testing.assert_allclose(a_o, expected_o, atol=1e-12)
    np.testing.assert_allclose(a_i, expected_i, atol=1e-12)
    # 2. Hertz: Q = K(alpha) delta^1.5 with the exact constant
    for j in range(z):
        for k, race in enumerate(("inner", "outer")):
            delta = sol.contact_deflection[j, k]
            if delta == 0.0:
                assert sol.contact_load[j, k] == 0.0
                continue
            expected = stiffness(geometry, sol.contact_angle[j, k], race) * delta**1.5
            assert sol.contact_load[j, k] == pytest.approx(expected, rel=1e-8, abs=1e-12)
    # 3. ball force balance (physics.md §2.5.4)
    fx = -q_o * np.sin(a_o) - t_o * np.cos(a_o) + q_i * np.sin(a_i) + t_i * np.cos(a_i)
    fr = -q_o * np.cos(a_o) + t_o * np.sin(a_o) + q_i * np.cos(a_i) - t_i * np.sin(a_i) + f_c
    # relative to the ball's own largest force; a ball carrying less than 1e-4 of the bearing's
    # force scale (e.g. an unloaded ball held only by a minute centrifugal force) is held to 1e-12
    # of it
    scale = np.maximum.reduce(
        [
            q_i,
            q_o,
            np.abs(f_c),
            2 * np.abs(m_g) / D,
            np.abs(t_i),
            np.abs(t_o),
            np.full(z, 1e-4 * sol.force_scale),
        ]
    )
    assert np.max(np.hypot(fx, fr) / scale) < rel
    # ball moment balance: friction moment about the ball centre = M_g (lambda_o + lambda_i = 2);
    # the traction balance's moments are checked in tests/unit/quasistatic/test_traction_balance.py
    np.testing.assert_allclose(0.5 * (lam_o + lam_i) * m_g, m_g, rtol=0)
    # 4. inner ring: forces the balls exert, moments about the ring centre (groove plane)
    ring_x = -(q_i * np.sin(a_i) + t_i * np.cos(a_i))
    ring_r = -(q_i * np.cos(a_i) - t_i * np.sin(a_i))
    lever = geometry.inner_groove_radius + 0.5 * sol.contact_deflection[:, 0]
    m_theta = -geometry.inner_curvature_center_radius * ring_x - lever * t_i
    applied = op.applied_loads()
    total = np.array(
        [
            applied[0] + ring_x.sum(),
            applied[1] + np.sum(ring_r * np.cos(psi)),
            applied[2] + np.sum(ring_r * np.sin(psi)),
        ]
    )
    assert np.max(np.abs(total)) / sol.force_scale < rel
    moments = np.array([np.sum(-m_theta * np.sin(psi)), np.sum(m_theta * np.cos(psi))])
    arm = 0.5 * geometry.pitch_diameter
    np.testing.assert_allclose(sol.applied_moment + moments, 0.0, atol=rel * sol.force_scale * arm)
    if op.tilt_is_free:
        np.testing.assert_allclose(
            sol.applied_moment, applied[3:], atol=rel * sol.force_scale * arm
        )
    else:
        np.testing.assert_allclose(sol.inner_ring_tilt, op.imposed_tilt(), atol=1e-15)
    # 5. body forces from the kinematics outputs
    r_orbit = sol.ball_center[:, 1]
    np.testing.assert_allclose(f_c, geometry.ball_mass * r_orbit * sol.orbital_speed**2, rtol=1e-12)
    w = sol.ball_angular_velocity
    w_rel_x = w[:, 0] - sol.orbital_speed
    w_rel_r = w[:, 1] * np.cos(psi) + w[:, 2] * np.sin(psi)
    # M_g e_theta = omega_c e_x x J omega_rel  -> theta component = -omega_c J w_rel_r
    np.testing.assert_allclose(
        m_g, sol.orbital_speed * geometry.ball_inertia * w_rel_r, rtol=1e-10, atol=1e-15
    )
    del w_rel_x


CASES = [
    ("218 combined 10k", bearing_218(), operating_point(10000 * RPM, 0.0, 17800.0, 8900.0)),
    ("218 thrust 10k", bearing_218(), operating_point(10000 * RPM, 0.0, 17800.0)),
    ("spindle 30k light", spindle(), operating_point(30000 * RPM, 0.0, 100.0)),
    (
        "spindle combined 20k at 30 deg",
        spindle(),
        operating_point(20000 * RPM, 0.0, 300.0, 300.0, math.radians(30)),
    ),
    (
        "spindle misaligned",
        spindle(),
        operating_point(20000 * RPM, 0.0, 300.0, misalignment=math.radians(0.1)),
    ),
    (
        "spindle moment",
        spindle(),
        operating_point(15000 * RPM, 0.0, 300.0, 100.0, tilting_moment=1.5, moment_axis=0.3),
    ),
    (
        "spindle moment-free tilt",
        spindle(),
        operating_point(15000 * RPM, 0.0, 300.0, 200.0, tilting_moment=0.0),
    ),
    ("outer ring turning", spindle(), operating_point(0.0, 12000 * RPM, 400.0, 100.0)),
    (
        "deep groove zero clearance radial",
        deep_groove(0.0),
        operating_point(8000 * RPM, 0.0, 0.0, 4000.0),
    ),
    (
        "deep groove clearance combined",
        deep_groove(20e-6),
        operating_point(8000 * RPM, 0.0, 600.0, 3000.0),
    ),
    ("218 reversed rotation", bearing_218(), operating_point(-6000 * RPM, 0.0, 9000.0, 2000.0)),
]


@pytest.mark.parametrize("name, geometry, op", CASES, ids=[c[0] for c in CASES])
def test_every_solution_is_in_equilibrium(name, geometry, op):
    sol = solve_operating_point(geometry, op)
    assert sol.converged
    check_equilibrium(geometry, op, sol)


def test_equilibrium_check_detects_an_unbalanced_solution():
    geometry, op = bearing_218(), operating_point(10000 * RPM, 0.0, 17800.0, 8900.0)
    sol = solve_operating_point(geometry, op)
    sol.contact_load[3, 0] *= 1.0 + 1e-6
    with pytest.raises(AssertionError):
        check_equilibrium(geometry, op, sol)


# ---- classic static limits ----------------------------------------------------------------------
@pytest.mark.parametrize(
    "geometry, axial", [(bearing_218(), 17800.0), (spindle(), 300.0), (bearing_218(), 500.0)]
)
def test_pure_axial_load_at_rest_matches_the_classic_equation(geometry, axial):
    sol = solve_operating_point(geometry, operating_point(0.0, 0.0, axial))
    z = geometry.ball_count
    q = sol.contact_load
    np.testing.assert_allclose(q, q[0, 0], rtol=1e-9)
    alpha = sol.contact_angle
    np.testing.assert_allclose(alpha, alpha[0, 0], atol=1e-12)
    assert z * q[0, 0] * math.sin(alpha[0, 0]) == pytest.approx(axial, rel=1e-9)
    a0, bd = geometry.free_contact_angle, geometry.curvature_center_distance

    def k_n(a):
        k_i, k_o = stiffness(geometry, a, "inner"), stiffness(geometry, a, "outer")
        return (k_i ** (-2 / 3) + k_o ** (-2 / 3)) ** -1.5

    def implicit(a):
        return (
            axial / (z * k_n(a) * bd**1.5) - math.sin(a) * (math.cos(a0) / math.cos(a) - 1) ** 1.5
        )

    expected = brentq(implicit, a0 + 1e-12, 1.5, xtol=1e-15)
    assert alpha[0, 0] == pytest.approx(expected, abs=1e-9)
    # the axial displacement follows from the geometry: A0 sin(alpha) - A0 sin(alpha0) + ... cos law
    delta_a = bd * math.cos(a0) * math.tan(expected) - bd * math.sin(a0)
    assert sol.inner_ring_offset[0] == pytest.approx(delta_a, rel=1e-7)


@pytest.mark.parametrize("ball_count", [9, 12])
def test_radial_load_at_rest_zero_clearance_discrete_distribution(ball_count):
    """Rigid rings, zero clearance, alpha0 = 0: delta_j = delta_r cos psi_j, Q_j = K_n delta_j^1.5,
    F_r = sum Q_j cos psi_j (exact for the discrete ball set)."""
    geometry = deep_groove(0.0, ball_count)
    fr = 5000.0
    sol = solve_operating_point(geometry, operating_point(0.0, 0.0, 0.0, fr))
    psi = sol.ball_azimuth
    cos = np.clip(np.cos(psi), 0.0, None)
    k_i, k_o = stiffness(geometry, 0.0, "inner"), stiffness(geometry, 0.0, "outer")
    k_n = (k_i ** (-2 / 3) + k_o ** (-2 / 3)) ** -1.5
    delta_r = (fr / (k_n * np.sum(cos**2.5))) ** (2 / 3)
    np.testing.assert_allclose(
        sol.contact_load[:, 0], k_n * (delta_r * cos) ** 1.5, rtol=1e-8, atol=1e-9 * fr
    )
    assert sol.inner_ring_offset[1] == pytest.approx(delta_r, rel=1e-8)
    assert np.all(sol.contact_load[np.cos(psi) < 0] == 0.0)


def test_radial_load_at_rest_large_ball_count_matches_stribeck_integral():
    """Q_max = F_r / (Z J_r(0.5)), J_r(0.5) = (1/2pi) int cos^2.5 over the loaded half (≈ 0.2288,
    Q_max ≈ 4.37 F_r / Z)."""
    z = 60
    geometry = BearingGeometry(z, 5.0e-3, 120.0e-3, 0.52, 0.52, 0.0, STEEL, STEEL)
    fr = 20000.0
    sol = solve_operating_point(geometry, operating_point(0.0, 0.0, 0.0, fr))
    j_r = quad(lambda p: math.cos(p) ** 2.5, -math.pi / 2, math.pi / 2)[0] / (2 * math.pi)
    assert j_r == pytest.approx(0.2288, abs=1e-4)
    assert sol.contact_load.max() == pytest.approx(fr / (z * j_r), rel=2e-3)


def test_radial_load_with_clearance_at_rest():
    """Deep groove with diametral clearance P_d: ring centred axially,
    delta_j = delta_r cos psi_j - P_d/2; delta_r from the force balance solved independently."""
    clearance = 20e-6
    geometry = deep_groove(clearance)
    fr = 3000.0
    sol = solve_operating_point(geometry, operating_point(0.0, 0.0, 0.0, fr))
    k_i, k_o = stiffness(geometry, 0.0, "inner"), stiffness(geometry, 0.0, "outer")
    k_n = (k_i ** (-2 / 3) + k_o ** (-2 / 3)) ** -1.5
    cos = np.cos(sol.ball_azimuth)

    def balance(delta_r):
        d = np.clip(delta_r * cos - clearance / 2, 0.0, None)
        return np.sum(k_n * d**1.5 * cos) - fr

    delta_r = brentq(balance, clearance / 2, clearance / 2 + 1e-3, xtol=1e-16)
    assert sol.inner_ring_offset[1] == pytest.approx(delta_r, rel=1e-7)
    assert sol.inner_ring_offset[0] == pytest.approx(-0.5 * geometry.free_end_play, rel=1e-9)
    np.testing.assert_allclose(sol.contact_angle, 0.0, atol=1e-9)
    d = np.clip(delta_r * cos - clearance / 2, 0.0, None)
    np.testing.assert_allclose(sol.contact_load[:, 0], k_n * d**1.5, rtol=1e-6, atol=1e-8 * fr)


# ---- trends with speed, symmetry ----------------------------------------------------------------
def test_trends_with_speed():
    """Centrifugal force pushes the balls out: the inner contact angle rises, the outer falls, and
    the cage speed ratio rises above the kinematic (1 - gamma)/2 (outer-race control:
    omega_c/omega = (1 - gamma' cos a_i)/(1 + cos(a_i - a_o)) grows as the angles split)."""
    geometry = spindle()
    speeds = [0.0, 5000.0, 10000.0, 20000.0, 30000.0, 45000.0]
    previous = None
    a_i, a_o, ratio = [], [], []
    for rpm in speeds:
        previous = solve_operating_point(geometry, operating_point(rpm * RPM, 0.0, 300.0), previous)
        a_i.append(previous.contact_angle[0, 0])
        a_o.append(previous.contact_angle[0, 1])
        if rpm:
            ratio.append(previous.cage_speed / (rpm * RPM))
    assert np.all(np.diff(a_i) > 0) and np.all(np.diff(a_o) < 0)
    assert np.all(np.diff(ratio) > 0)
    alpha_static = a_i[0]
    kinematic = 0.5 * (1 - geometry.gamma(alpha_static))
    assert ratio[0] > kinematic - 1e-4 and ratio[-1] > kinematic + 1e-3


def test_radial_load_at_90_degrees_rotates_the_solution():
    geometry = spindle(16)
    op0 = operating_point(20000 * RPM, 0.0, 300.0, 400.0, 0.0)
    op90 = operating_point(20000 * RPM, 0.0, 300.0, 400.0, math.pi / 2)
    s0 = solve_operating_point(geometry, op0)
    s90 = solve_operating_point(geometry, op90)
    shift = geometry.ball_count // 4
    np.testing.assert_allclose(
        s90.contact_load, np.roll(s0.contact_load, shift, axis=0), rtol=1e-7, atol=1e-9 * 400
    )
    np.testing.assert_allclose(
        s90.contact_angle, np.roll(s0.contact_angle, shift, axis=0), atol=1e-9
    )
    np.testing.assert_allclose(
        s90.inner_ring_offset,
        [s0.inner_ring_offset[0], -s0.inner_ring_offset[2], s0.inner_ring_offset[1]],
        atol=1e-12,
    )


def test_pure_tilt_sign():
    """A tilt vector along +y moves the inner ring point at psi = 90° (the +z side) in +x
    (theta x p): that ball becomes the most loaded, the one at 270° less; the moment needed to hold
    the tilt acts along +y (the balls resist it)."""
    geometry = spindle(16)
    op = operating_point(0.0, 0.0, 300.0, misalignment=math.radians(0.05), misalignment_axis=0.0)
    sol = solve_operating_point(geometry, op)
    q = sol.contact_load[:, 0]
    assert q[4] == q.max() and q[4] > q[12]  # ball 4 at 90°, ball 12 at 270°
    assert sol.applied_moment[0] > 0.0  # the moment holding the tilt acts along the tilt
    assert abs(sol.applied_moment[1]) < 1e-9 * abs(sol.applied_moment[0])


# ---- robustness --------------------------------------------------------------------------------
def test_unloaded_balls_give_zeros_no_nan_no_warning():
    geometry = deep_groove(15e-6)
    for rpm in (0.0, 6000.0):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            sol = solve_operating_point(geometry, operating_point(rpm * RPM, 0.0, 0.0, 2000.0))
        open_inner = sol.contact_load[:, 0] == 0.0
        assert open_inner.sum() >= 3
        assert np.all(sol.contact_deflection[open_inner, 0] == 0.0)
        for field in (
            "contact_angle",
            "contact_load",
            "contact_deflection",
            "orbital_speed",
            "attitude_angle",
            "ball_angular_velocity",
            "gyroscopic_moment",
        ):
            assert np.all(np.isfinite(getattr(sol, field))), field
        if rpm:
            assert np.all(sol.contact_load[:, 1] > 0.0)  # centrifugal force holds them outside


def test_creeping_speed_is_in_equilibrium_without_nan():
    """At a fraction of an rpm the body forces are minute; unloaded balls still sit on the outer
    race and every ball balances."""
    geometry = BearingGeometry(6, 3e-3, 11.459e-3, 0.5625, 0.5625, math.radians(31), STEEL, STEEL)
    op = operating_point(0.0436 * RPM, 0.0, 54.0, 54.0)
    sol = solve_operating_point(geometry, op)
    check_equilibrium(geometry, op, sol)


@pytest.mark.parametrize("rpm", [60000.0, 100000.0, 150000.0])
def test_spindle_light_preload_to_very_high_speed(rpm):
    geometry = spindle()
    op = operating_point(rpm * RPM, 0.0, 100.0)
    sol = solve_operating_point(geometry, op)
    check_equilibrium(geometry, op, sol)
    assert sol.contact_angle[0, 1] < math.radians(3.0)  # the outer contact angle has collapsed


def test_heavy_combined_load_218():
    geometry = bearing_218()
    op = operating_point(10000 * RPM, 0.0, 17800.0, 8900.0)
    sol = solve_operating_point(geometry, op)
    check_equilibrium(geometry, op, sol)
    assert sol.contact_load.max() > 17800.0 / 16


def test_speed_is_solved_from_outer_race_control_in_one_ring_solve(monkeypatch):
    """From the static solution the full speed starts from outer race control, not from the
    Jones decision at rest, which without rolling says nothing about the one at speed (for this
    case inner control for every ball, which took a whole extra ring solve at full speed to
    undo): one ring solve at rest, one at speed, and the decision there is a fixed point."""
    from solver.models.quasistatic import solver as driver

    speeds = []
    original = driver._ring_solve

    def counting(problem, state, speed_fraction, load_fraction):
        speeds.append(speed_fraction)
        return original(problem, state, speed_fraction, load_fraction)

    monkeypatch.setattr(driver, "_ring_solve", counting)
    geometry = bearing_218()
    op = operating_point(10000 * RPM, 0.0, 17800.0, 8900.0)
    sol = solve_operating_point(geometry, op)
    check_equilibrium(geometry, op, sol)
    assert speeds == [0.0, 1.0]
    assert set(sol.race_control) == {"outer"}


def test_a_result_at_rest_keeps_the_race_control_decided_at_rest():
    """Without speed the result reports the Jones decision at rest, as before the start from
    outer control at speed (which only a case with speed takes)."""
    geometry = bearing_218()
    sol = solve_operating_point(geometry, operating_point(0.0, 0.0, 17800.0, 8900.0))
    assert set(sol.race_control) == {"inner"}


def test_no_static_solution_is_reported_with_a_reason(monkeypatch):
    """When the ring solve cannot converge, the error says so and suggests what to try."""
    from solver.models.quasistatic import solver as driver

    monkeypatch.setattr(driver, "MAX_RING_ITERATIONS", 0)
    with pytest.raises(NoSolutionError, match="no static equilibrium.*Try"):
        solve_operating_point(spindle(), operating_point(1000 * RPM, 0.0, 300.0, 100.0))


def test_lost_solution_at_speed_names_the_speed_and_the_remedy(monkeypatch):
    """If the equilibrium is lost part-way through the speed continuation, the message gives the
    speed reached, the outer contact angle there and the remedies."""
    from solver.models.quasistatic import solver as driver

    original = driver._solve_with_race_control

    def failing_beyond_half_speed(problem, state, speed_fraction, load_fraction):
        if speed_fraction > 0.5:
            return False, 0, 1.0, ""
        return original(problem, state, speed_fraction, load_fraction)

    monkeypatch.setattr(driver, "_solve_with_race_control", failing_beyond_half_speed)
    with pytest.raises(NoSolutionError) as info:
        solve_operating_point(spindle(), operating_point(40000 * RPM, 0.0, 100.0))
    message = str(info.value)
    assert "20000 rpm (of 40000 rpm)" in message
    assert "outer contact angle" in message and "more axial preload" in message


# ---- gyroscopic moment: friction forces in the ball kernel --------------------------------------
@pytest.mark.parametrize("inner_control", [False, True])
@pytest.mark.parametrize("omega", [1500.0, -1500.0])
def test_friction_moment_about_the_ball_centre_is_the_gyroscopic_rate(inner_control, omega):
    """Take the friction forces the kernel applies to a ball (net force minus normal and centrifugal
    forces), put them at the contact points and compare their moment about the ball centre with
    omega_c e_x x (J omega_b), omega_b the ball's angular velocity relative to the cage."""
    from solver.models.quasistatic import kernels

    geometry = bearing_218()
    model = kernels.ball_model(geometry, omega, 0.0)
    g_i = (geometry.inner_conformity - 0.5) * geometry.ball_diameter
    g_o = (geometry.outer_conformity - 0.5) * geometry.ball_diameter
    alpha_o, alpha_i = math.radians(33.0), math.radians(45.0)
    x = (g_o + 8e-6) * np.array([math.sin(alpha_o), math.cos(alpha_o)])
    a = x + (g_i + 9e-6) * np.array([math.sin(alpha_i), math.cos(alpha_i)])
    control = kernels.race_control_rows([inner_control])[0]
    st = kernels.ball_state(x[0], x[1], a[0], a[1], control, model)
    res = np.array([st.residual_axial, st.residual_radial])
    q_i, q_o, a_i, a_o = st.inner_load, st.outer_load, st.inner_angle, st.outer_angle
    beta, omega_c, omega_r, f_c = (
        st.attitude_angle,
        st.orbital_speed,
        st.spin_speed,
        st.centrifugal_force,
    )
    assert a_i == pytest.approx(alpha_i) and a_o == pytest.approx(alpha_o)

    def u(angle):  # (x, r) components
        return np.array([math.sin(angle), math.cos(angle)])

    normal = -q_o * u(a_o) + q_i * u(a_i) + np.array([0.0, f_c])
    friction = res - normal  # total friction force on the ball, (x, r)
    D = geometry.ball_diameter
    # split between the contacts: each friction force is tangent to its contact (perpendicular to u)
    t_o_dir = np.array([-math.cos(a_o), math.sin(a_o)])
    t_i_dir = np.array([math.cos(a_i), -math.sin(a_i)])
    coeffs = np.linalg.solve(np.column_stack([t_o_dir, t_i_dir]), friction)
    if not inner_control:
        assert abs(coeffs[1]) <= 1e-9 * abs(coeffs[0])  # outer control: all at the outer contact

    def to3(v):  # (x, r) -> (x, r, theta)
        return np.array([v[0], v[1], 0.0])

    moment = np.cross(to3(0.5 * D * u(a_o)), to3(coeffs[0] * t_o_dir)) + np.cross(
        to3(-0.5 * D * u(a_i)), to3(coeffs[1] * t_i_dir)
    )
    w_b = omega_r * np.array([math.cos(beta), -math.sin(beta), 0.0])
    rate = np.cross(np.array([omega_c, 0.0, 0.0]), geometry.ball_inertia * w_b)
    np.testing.assert_allclose(moment, rate, rtol=1e-9, atol=1e-14)
    assert rate[2] > 0.0  # along +e_theta for either direction of rotation


def test_race_control_cycle_is_reported(monkeypatch):
    """If the Jones decision flips back and forth, the last solution is kept and the note says
    so."""
    from solver.models.quasistatic import solver as driver

    calls = {"n": 0}

    def flipping(states, model):
        calls["n"] += 1
        return np.full(states.orbital_speed.size, calls["n"] % 2 == 1)

    monkeypatch.setattr(driver, "_race_control", flipping)
    geometry, op = spindle(), operating_point(0.0, 0.0, 300.0, 100.0)
    sol = solve_operating_point(geometry, op)
    assert "cycles" in sol.race_control_note
    check_equilibrium(geometry, op, sol)


def test_race_control_inner_at_high_speed_is_consistent():
    """Per-ball decisions are a fixed point of the Jones criterion (recomputed from the outputs with
    the exact Hertz solution)."""
    geometry = deep_groove(15e-6)
    op = operating_point(6000 * RPM, 0.0, 300.0, 2000.0)
    sol = solve_operating_point(geometry, op)
    assert sol.race_control_note == ""
    for j in range(geometry.ball_count):
        q_i, q_o = sol.contact_load[j]
        if q_i == 0.0:
            assert sol.race_control[j] == "outer"
            continue
        ci = race_contact(geometry, sol.contact_angle[j, 0], q_i, "inner")
        co = race_contact(geometry, sol.contact_angle[j, 1], q_o, "outer")
        lhs = (
            q_i
            * ci.semi_major
            * ci.elliptic_e
            * math.cos(sol.contact_angle[j, 0] - sol.contact_angle[j, 1])
        )
        rhs = q_o * co.semi_major * co.elliptic_e
        assert (sol.race_control[j] == "inner") == (lhs > rhs)


@pytest.mark.parametrize("field", ["contact_load", "cage_speed", "inner_ring_tilt"])
def test_a_solution_that_is_not_finite_is_no_solution(monkeypatch, field, capsys):
    """Whatever overflows inside the iteration, NaN or inf never leaves as a solution: the solver
    raises NoSolutionError, and the CLI exits 3 with the reason and valid JSON."""
    import json

    from racetrace.cli import main
    from solver.models.quasistatic import solver as qs_solver

    real = qs_solver._pack

    def overflowing(*args, **kwargs):
        solution = real(*args, **kwargs)
        value = getattr(solution, field)
        if np.ndim(value):
            value = np.array(value, dtype=float)
            value.flat[0] = np.nan
        else:
            value = math.inf
        setattr(solution, field, value)
        return solution

    monkeypatch.setattr(qs_solver, "_pack", overflowing)
    with pytest.raises(NoSolutionError, match=f"not finite numbers \\({field}\\)"):
        solve_operating_point(spindle_geometry(), operating_point(2094.4, 0.0, 500.0, 300.0))
    assert main(["quasistatic", "spindle-combined-load", "--json"]) == 3
    out = capsys.readouterr().out
    assert json.loads(out)["error"]["kind"] == "no solution"
