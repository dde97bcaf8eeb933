"""Unit tests of the dynamic model's right-hand-side pieces against independent references."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy import integrate

from solver.history import steady_history
from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import ball_frame, matrix_to_quaternion
from solver.models.dynamic.kernels import quaternion_to_matrix, ring_frames, rotation_from_vector
from solver.models.dynamic.params import drive_at_start
from solver.physics.hertz import race_contact
from solver.physics.traction import LAW_SLIP_CURVE
from tests.helpers.cases import spindle_inputs
from tests.helpers.dyn_helpers import evaluate, setup, start


def _quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )


def _axis_angle_quat(w, t):
    th = np.linalg.norm(w) * t
    k = w / np.linalg.norm(w)
    return np.concatenate(([math.cos(th / 2)], math.sin(th / 2) * k))


def test_quaternion_rate_matches_exact_rotation():
    """q' from the RHS equals the derivative of q(t) = exp(w t) (x) q0 for constant inertial w."""
    history, par, quad, _ = setup(spindle_inputs(), traction=False, cage=False)
    rng = np.random.default_rng(1)
    y = np.zeros(L.state_size(18))
    for j in range(18):
        b = L.ball_base(j)
        y[b + 1] = 0.027 * math.cos(2 * math.pi * j / 18)
        y[b + 2] = 0.027 * math.sin(2 * math.pi * j / 18)
        q0 = rng.normal(size=4)
        y[b + L.B_QUAT : b + L.B_QUAT + 4] = q0 / np.linalg.norm(q0)
        y[b + L.B_OMEGA : b + L.B_OMEGA + 3] = rng.normal(size=3) * 100.0
    dydt, *_ = evaluate(y, history, par, quad)
    h = 1e-6
    for j in range(18):
        b = L.ball_base(j)
        q0 = y[b + L.B_QUAT : b + L.B_QUAT + 4]
        w = y[b + L.B_OMEGA : b + L.B_OMEGA + 3]
        fd = (_quat_mul(_axis_angle_quat(w, h), q0) - _quat_mul(_axis_angle_quat(w, -h), q0)) / (
            2 * h
        )
        np.testing.assert_allclose(dydt[b + L.B_QUAT : b + L.B_QUAT + 4], fd, rtol=1e-6, atol=1e-6)


def test_quaternion_matrix_round_trip_and_ball_frame():
    rot = ball_frame(0.7, math.radians(12.0))
    np.testing.assert_allclose(rot.T @ rot, np.eye(3), atol=1e-14)
    assert np.linalg.det(rot) == pytest.approx(1.0)
    q = matrix_to_quaternion(rot)
    m = np.empty((3, 3))
    quaternion_to_matrix(*q, m)
    np.testing.assert_allclose(m, rot, atol=1e-14)


def test_rotation_vector_is_rodrigues():
    m = np.empty((3, 3))
    rotation_from_vector(0.3, 0.0, 0.0, m)
    c, s = math.cos(0.3), math.sin(0.3)
    np.testing.assert_allclose(m, [[1, 0, 0], [0, c, -s], [0, s, c]], atol=1e-15)


@pytest.mark.parametrize("mode", [0, 1])
def test_ring_frames_tilt_modes(mode):
    """Space-fixed tilt: the ring axis stays put as the ring turns; ring-fixed tilt: it
    precesses."""
    history, par, quad, _ = setup(spindle_inputs(), traction=False, cage=False)
    par = par._replace(tilt_mode=mode)
    z = 18
    rb = L.ring_base(z)
    y = np.zeros(L.state_size(z))
    y[rb + L.R_TILT + 1] = 0.01  # tilt about z
    axes = []
    for phi in (0.0, math.pi / 2):
        y[rb + L.R_PHI_INNER] = phi
        rot, org, vel, om = np.empty((3, 3)), np.empty(3), np.empty(3), np.empty(3)
        orot, oom = np.empty((3, 3)), np.empty(3)
        ring_frames(y, par, drive_at_start(history), rot, org, vel, om, orot, oom)
        np.testing.assert_allclose(rot.T @ rot, np.eye(3), atol=1e-14)
        axes.append(rot[:, 0].copy())
    # tilt about z by 0.01 rad turns e_x towards +y
    np.testing.assert_allclose(axes[0], [math.cos(0.01), math.sin(0.01), 0.0], atol=1e-14)
    if mode == 0:
        np.testing.assert_allclose(axes[1], axes[0], atol=1e-14)
    else:
        np.testing.assert_allclose(axes[1], [math.cos(0.01), 0.0, math.sin(0.01)], atol=1e-14)


def _nominal_state(z, dm):
    y = np.zeros(L.state_size(z))
    for j in range(z):
        b = L.ball_base(j)
        psi = 2 * math.pi * j / z
        y[b + 1] = 0.5 * dm * math.cos(psi)
        y[b + 2] = 0.5 * dm * math.sin(psi)
        y[b + L.B_QUAT] = 1.0
    return y


def test_just_touching_state_has_zero_deflection_and_free_contact_angle():
    inp = spindle_inputs()
    history, par, quad, _ = setup(inp, traction=False, cage=False)
    y = _nominal_state(18, inp.geometry.pitch_diameter)
    _, ri, ro, _ = evaluate(y, history, par, quad)
    np.testing.assert_allclose(ri[:, L.K_DEFLECTION], 0.0, atol=1e-15)
    np.testing.assert_allclose(ro[:, L.K_DEFLECTION], 0.0, atol=1e-15)
    np.testing.assert_allclose(ri[:, L.K_ANGLE], inp.geometry.free_contact_angle, atol=1e-12)
    np.testing.assert_allclose(ro[:, L.K_ANGLE], inp.geometry.free_contact_angle, atol=1e-12)
    assert (
        ri[:, L.K_LOAD].max() < 1e-9 and ro[:, L.K_LOAD].max() < 1e-9
    )  # rounding-level approach only


def test_axial_shift_matches_rigid_ring_closed_form_and_exact_hertz():
    """physics.md §2.4: a pure axial shift da gives A1 = A0 sin a0 + da, A2 = A0 cos a0, total
    approach sqrt(A1^2 + A2^2) - A0 and contact angle atan2(A1, A2) at both races (ball on the line
    of the curvature centres). Loads must be the exact Hertz loads for those approaches."""
    inp = spindle_inputs()
    g = inp.geometry
    history, par, quad, _ = setup(inp, traction=False, cage=False, damping_ratio=0.0)
    z = g.ball_count
    y = _nominal_state(z, g.pitch_diameter)
    da = 8e-6
    rb = L.ring_base(z)
    y[rb] = da
    a0, A0 = g.free_contact_angle, g.curvature_center_distance
    A1, A2 = A0 * math.sin(a0) + da, A0 * math.cos(a0)
    total = math.hypot(A1, A2) - A0
    alpha = math.atan2(A1, A2)
    # ball centre on the line between the curvature centres, splitting the approach in half
    co = np.array([g.outer_curvature_center_axial, g.outer_curvature_center_radius])
    u = np.array([math.sin(alpha), math.cos(alpha)])
    centre = co + ((g.outer_conformity - 0.5) * g.ball_diameter + 0.5 * total) * u
    for j in range(z):
        b = L.ball_base(j)
        psi = 2 * math.pi * j / z
        y[b] = centre[0]
        y[b + 1] = centre[1] * math.cos(psi)
        y[b + 2] = centre[1] * math.sin(psi)
    _, ri, ro, _ = evaluate(y, history, par, quad)
    np.testing.assert_allclose(ri[:, L.K_DEFLECTION] + ro[:, L.K_DEFLECTION], total, rtol=1e-9)
    np.testing.assert_allclose(ri[:, L.K_ANGLE], alpha, atol=1e-10)
    np.testing.assert_allclose(ro[:, L.K_ANGLE], alpha, atol=1e-10)
    for rec, race in ((ri, "inner"), (ro, "outer")):
        exact = race_contact(g, alpha, rec[0, L.K_LOAD], race)
        assert rec[0, L.K_DEFLECTION] == pytest.approx(exact.approach, rel=1e-7)
        assert rec[0, L.K_SEMI_MAJOR] == pytest.approx(exact.semi_major, rel=1e-7)
        assert rec[0, L.K_PMAX] == pytest.approx(exact.max_pressure, rel=1e-7)


def test_initial_state_is_in_equilibrium():
    """At the quasi-static start the contact forces supply exactly the centripetal force and balance
    the applied load on the ring (traction and damping off, so only the normal laws act)."""
    inp = spindle_inputs(radial=300.0)
    history, par, quad, y0 = start(inp, traction=False, damping_ratio=0.0, cage=False, gravity=0.0)
    dydt, ri, ro, _ = evaluate(y0, history, par, quad)
    z = 18
    cb = L.cage_base(z)
    wc = y0[cb + L.C_SPEED]
    q_scale = ri[:, L.K_LOAD].max()
    mb = par.ball_mass
    for j in range(z):
        b = L.ball_base(j)
        pos = y0[b : b + 3]
        net = (dydt[b + 3 : b + 6] + wc**2 * np.array([0.0, pos[1], pos[2]])) * mb
        psi = math.atan2(pos[2], pos[1])
        e_r = np.array([0.0, math.cos(psi), math.sin(psi)])
        e_t = np.array([0.0, -math.sin(psi), math.cos(psi)])
        assert abs(net[0]) < 1e-6 * q_scale and abs(net @ e_r) < 1e-6 * q_scale
        # tangential: only the small out-of-meridian tilt of the offset inner ring's normal
        assert abs(net @ e_t) < 2e-4 * q_scale
    rb = L.ring_base(z)
    np.testing.assert_allclose(dydt[rb + 3 : rb + 6] * par.ring_mass, 0.0, atol=1e-5 * q_scale)
    # outer-race control start: the spin at the outer contact vanishes
    # (to 1e-4 of the roll rate: the cage speed is common, the per-ball angles differ slightly)
    np.testing.assert_allclose(ro[:, L.K_SPIN], 0.0, atol=1e-4 * abs(ro[:, L.K_ROLL]).max())
    assert abs(ri[:, L.K_SPIN]).max() > 1e-2 * abs(ri[:, L.K_ROLL]).max()  # inner contact spins


def test_newton_third_law_ball_inner_ring():
    """With traction on and arbitrary slips, the inner-ring contact forces and moments on the balls
    are equal and opposite to those on the ring (moments about the ring centre)."""
    inp = spindle_inputs(radial=300.0)
    history, par, quad, y0 = start(inp)
    rng = np.random.default_rng(3)
    y = y0.copy()
    for j in range(18):
        b = L.ball_base(j)
        y[b + L.B_VEL : b + L.B_VEL + 3] += rng.normal(size=3) * 0.5
        y[b + L.B_OMEGA : b + L.B_OMEGA + 3] += rng.normal(size=3) * 50.0
    _, ri, _, _ = evaluate(y, history, par, quad)
    rb = L.ring_base(18)
    ring_c = y[rb : rb + 3]
    f_ball = ri[:, L.K_F_BALL : L.K_F_BALL + 3].sum(axis=0)
    f_ring = ri[:, L.K_F_RING : L.K_F_RING + 3].sum(axis=0)
    np.testing.assert_allclose(f_ball, -f_ring, atol=1e-9 * np.abs(ri[:, L.K_LOAD]).sum())
    m_ball = np.zeros(3)
    for j in range(18):
        b = L.ball_base(j)
        m_ball += np.cross(y[b : b + 3] - ring_c, ri[j, L.K_F_BALL : L.K_F_BALL + 3])
        m_ball += ri[j, L.K_M_BALL : L.K_M_BALL + 3]
    m_ring = ri[:, L.K_M_RING : L.K_M_RING + 3].sum(axis=0)
    scale = np.abs(ri[:, L.K_LOAD]).sum() * 0.027
    np.testing.assert_allclose(m_ball, -m_ring, atol=1e-9 * scale)
    # the traction is not negligible in this test (otherwise it would test nothing)
    tang = (
        ri[:, L.K_F_BALL : L.K_F_BALL + 3] + ri[:, [L.K_LOAD]] * ri[:, L.K_NORMAL : L.K_NORMAL + 3]
    )
    assert np.abs(tang).max() > 0.01 * ri[:, L.K_LOAD].max()


def _outer_contact_setup(mu, heathcote=False, quadrature=(4, 8)):
    inp = spindle_inputs()
    history, par, quad, y0 = start(
        inp, heathcote=heathcote, quadrature=quadrature, damping_ratio=0.0
    )
    # the slip-curve law with a constant (Coulomb) coefficient
    par = par._replace(traction_law=LAW_SLIP_CURVE, traction_curve=(0.0, 0.0, 0.0, mu))
    par = par._replace(slip_regularisation=1e-9)
    y = y0.copy()
    b = L.ball_base(0)
    y[b + L.B_VEL : b + L.B_VEL + 3] = 0.0
    y[b + L.B_OMEGA : b + L.B_OMEGA + 3] = 0.0
    return history, par, quad, y, b


def test_pure_sliding_gives_coulomb_force_opposite_to_slip():
    mu = 0.07
    history, par, quad, y, b = _outer_contact_setup(mu)
    _, _, ro, _ = evaluate(y, history, par, quad)
    n = ro[0, L.K_NORMAL : L.K_NORMAL + 3]
    # rolling direction at ball 0 (azimuth 0): e_theta = +z
    y[b + L.B_VEL + 2] = 3.0
    _, _, ro, _ = evaluate(y, history, par, quad)
    q = ro[0, L.K_LOAD]
    f = ro[0, L.K_F_BALL : L.K_F_BALL + 3] + q * n
    np.testing.assert_allclose(f, [0.0, 0.0, -mu * q], atol=1e-9 * q)
    # lever arm: contact centre at (D/2 - delta/2) along n from the ball centre
    arm = 0.5 * par.ball_diameter - 0.5 * ro[0, L.K_DEFLECTION]
    np.testing.assert_allclose(
        ro[0, L.K_M_BALL : L.K_M_BALL + 3], np.cross(arm * n, f), atol=1e-9 * q * arm
    )


def test_pure_spin_moment_matches_ellipse_integral():
    """Spin about the contact normal with no centre slip: the moment about the normal equals
    -mu * integral of p(xi, eta) * radius over the Hertz ellipse (independent scipy integral); a
    single-point traction model would give zero."""
    mu = 0.05
    history, par, quad, y, b = _outer_contact_setup(mu, quadrature=(12, 24))
    _, _, ro, _ = evaluate(y, history, par, quad)
    n = ro[0, L.K_NORMAL : L.K_NORMAL + 3]
    y[b + L.B_OMEGA : b + L.B_OMEGA + 3] = 200.0 * n
    _, _, ro, _ = evaluate(y, history, par, quad)
    q, a, bb = ro[0, L.K_LOAD], ro[0, L.K_SEMI_MAJOR], ro[0, L.K_SEMI_MINOR]
    pmax = 1.5 * q / (math.pi * a * bb)

    def integrand(eta, xi):
        return pmax * math.sqrt(max(0.0, 1 - (xi / bb) ** 2 - (eta / a) ** 2)) * math.hypot(xi, eta)

    ref, _ = integrate.dblquad(
        integrand,
        -bb,
        bb,
        lambda x: -a * math.sqrt(1 - (x / bb) ** 2),
        lambda x: a * math.sqrt(1 - (x / bb) ** 2),
        epsrel=1e-8,
    )
    moment_n = float(np.dot(ro[0, L.K_M_BALL : L.K_M_BALL + 3], n))
    assert moment_n == pytest.approx(-mu * ref, rel=5e-3)
    f = ro[0, L.K_F_BALL : L.K_F_BALL + 3] + q * n
    assert np.linalg.norm(f) < 1e-6 * q  # symmetric spin: no net tangential force


@pytest.mark.parametrize("radial", [0.0, 300.0])
def test_contact_forces_nearly_balance_at_the_quasistatic_state(radial):
    """At the project's quasi-static solution (solver.models.quasistatic, an independent
    implementation of the same geometry) the dynamic model's normal contact forces supply the
    centripetal force of every ball and balance the applied load on the ring. What is left is the
    quasi-static gyroscopic friction (M_g / D ~ 0.6 % of Q here), which the dynamic model carries by
    traction slips."""
    from solver.models.dynamic.initial import initial_state_from_quasistatic, quasistatic_solution

    inp = spindle_inputs(radial=radial)
    history, par, quad, _ = setup(inp, traction=False, damping_ratio=0.0, cage=False, gravity=0.0)
    qs = quasistatic_solution(inp)
    y = initial_state_from_quasistatic(par, qs)
    dydt, ri, ro, _ = evaluate(y, history, par, quad)
    q_mean = float(np.mean(qs.contact_load))
    mb = par.ball_mass
    for j in range(18):
        b = L.ball_base(j)
        pos = y[b : b + 3]
        wc = float(qs.orbital_speed[j])
        net = (dydt[b + 3 : b + 6] + wc**2 * np.array([0.0, pos[1], pos[2]])) * mb
        assert np.linalg.norm(net) < 0.02 * q_mean
    np.testing.assert_allclose(
        ri[:, L.K_LOAD], qs.contact_load[:, 0], rtol=0.01, atol=1e-3 * q_mean
    )
    np.testing.assert_allclose(
        ro[:, L.K_LOAD], qs.contact_load[:, 1], rtol=0.01, atol=1e-3 * q_mean
    )
    np.testing.assert_allclose(ri[:, L.K_ANGLE], qs.contact_angle[:, 0], atol=1e-3)
    np.testing.assert_allclose(ro[:, L.K_ANGLE], qs.contact_angle[:, 1], atol=1e-3)
    rb = L.ring_base(18)
    assert np.linalg.norm(dydt[rb + 3 : rb + 6] * par.ring_mass) < 0.01 * 500.0


def test_pocket_force_frame_transform_and_cage_reaction():
    """A ball pushed circumferentially into its pocket wall (ball 3, azimuth 60 deg) is pushed back
    along -e_theta with the linear pocket law K_p * penetration; the cage receives the opposite
    force and the moment R x F about its axis."""
    from solver.models.dynamic.kernels import TRACTION_WORK_SIZE, cage_frame, cage_pocket

    history, par, quad, y0 = start(spindle_inputs(), friction_regularisation=1e-3)
    y = y0.copy()
    z = 18
    cb = L.cage_base(z)
    y[cb : cb + L.CAGE_SIZE] = 0.0  # cage centred, at rest, angle 0
    j = 3
    b = L.ball_base(j)
    psi = 2 * math.pi * j / z
    e_r = np.array([0.0, math.cos(psi), math.sin(psi)])
    e_t = np.array([0.0, -math.sin(psi), math.cos(psi)])
    pen = 2e-6
    shift = 0.5 * par.pocket_clearance + pen
    y[b : b + 3] = 0.5 * par.pitch_diameter * e_r + shift * e_t
    y[b + 3 : b + 6] = 0.0
    y[b + 10 : b + 13] = 0.0
    out = np.zeros(12)
    rot, om = np.empty((3, 3)), np.empty(3)
    cage_frame(y, cb, rot, om)
    fn = cage_pocket(y, b, cb, j, par, rot, om, np.zeros(TRACTION_WORK_SIZE), out)
    assert fn == pytest.approx(par.pocket_stiffness * pen, rel=1e-9)
    np.testing.assert_allclose(out[0:3], -fn * e_t, atol=1e-12 * fn)
    np.testing.assert_allclose(out[6:9], fn * e_t, atol=1e-12 * fn)
    # the force acts at the contact point at radius ~ d_m/2 (plus the shift): moment about x
    lever = 0.5 * par.pitch_diameter * e_r + (shift + 0.5 * par.ball_diameter) * e_t
    assert out[9] == pytest.approx(np.cross(lever, fn * e_t)[0], rel=1e-9)
    # inside the clearance: no force
    y[b : b + 3] = 0.5 * par.pitch_diameter * e_r + 0.4 * par.pocket_clearance * e_t
    assert cage_pocket(y, b, cb, j, par, rot, om, np.zeros(TRACTION_WORK_SIZE), out) == 0.0


def test_gravity_acts_along_minus_z_on_balls_cage_and_inner_ring():
    """Free balls (just-touching positions, no deflection), a centred cage at rest and the free
    inner ring fall with acceleration g along -z of the inertial frame."""
    inp = spindle_inputs(axial=0.0)
    history, par, quad, _ = setup(inp, gravity=9.81)
    history = steady_history(replace(inp.operating, axial_load=0.0))
    y = _nominal_state(18, inp.geometry.pitch_diameter)
    dydt, *_ = evaluate(y, history, par, quad)
    for j in range(18):
        b = L.ball_base(j)
        np.testing.assert_allclose(dydt[b + 3 : b + 6], [0.0, 0.0, -9.81], atol=1e-9)
    cb = L.cage_base(18)
    np.testing.assert_allclose(dydt[cb + 3 : cb + 6], [0.0, 0.0, -9.81], atol=1e-9)
    rb = L.ring_base(18)
    np.testing.assert_allclose(dydt[rb + 3 : rb + 6], [0.0, 0.0, -9.81], atol=1e-9)


def test_tilted_cage_pocket_follows_the_cage():
    """With the cage tilted (6-DOF cage), a ball at the tilted pocket centre feels nothing, and one
    pushed along the tilted pocket's circumferential axis is pushed back along that axis; the cage
    receives the moment of the reaction about its centre (which now has y/z components)."""
    from solver.models.dynamic.kernels import TRACTION_WORK_SIZE, cage_frame, cage_pocket

    history, par, quad, y0 = start(spindle_inputs())
    y = y0.copy()
    cb = L.cage_base(18)
    y[cb : cb + L.CAGE_SIZE] = 0.0
    y[cb + L.C_TILT + 1] = 0.01  # tilt about z
    rot, om = np.empty((3, 3)), np.empty(3)
    cage_frame(y, cb, rot, om)
    j = 4
    psi = 2 * math.pi * j / 18
    e_r = rot @ np.array([0.0, math.cos(psi), math.sin(psi)])
    e_t = rot @ np.array([0.0, -math.sin(psi), math.cos(psi)])
    b = L.ball_base(j)
    y[b + 3 : b + 6] = 0.0
    y[b + 10 : b + 13] = 0.0
    out = np.zeros(12)
    y[b : b + 3] = 0.5 * par.pitch_diameter * e_r
    assert cage_pocket(y, b, cb, j, par, rot, om, np.zeros(TRACTION_WORK_SIZE), out) == 0.0
    pen = 3e-6
    y[b : b + 3] = 0.5 * par.pitch_diameter * e_r + (0.5 * par.pocket_clearance + pen) * e_t
    fn = cage_pocket(y, b, cb, j, par, rot, om, np.zeros(TRACTION_WORK_SIZE), out)
    assert fn == pytest.approx(par.pocket_stiffness * pen, rel=1e-9)
    np.testing.assert_allclose(out[0:3], -fn * e_t, atol=1e-12 * fn)
    lever = (
        0.5 * par.pitch_diameter * e_r
        + (0.5 * par.pocket_clearance + pen + 0.5 * par.ball_diameter) * e_t
    )
    np.testing.assert_allclose(out[9:12], np.cross(lever, fn * e_t), atol=1e-9 * fn * 0.03)


def test_cage_drag_moment_acts_on_the_cage_spin():
    """The right-hand side adds the oil-air drag moment of solver.physics.drag (mixture of the
    case's oil fraction, side faces d_m/2 +- 0.35 D) to the cage's spin equation: the cage's spin
    acceleration differs by M / I_p from a cage without drag; its power is -M w_c > 0,
    zero with traction (lubrication) off; more oil in the mixture, more drag."""
    from dataclasses import replace

    from solver.models.dynamic.kernels import cage_drag
    from solver.physics.drag import cage_drag_moment

    inp = spindle_inputs(rpm=20000.0, axial=500.0)
    history, par, quad, y = start(inp)
    cb = L.cage_base(18)
    wc = y[cb + L.C_SPEED]
    assert wc > 0.0
    dm, d = inp.geometry.pitch_diameter, inp.geometry.ball_diameter
    oil = inp.lubricant
    rho = oil.oil_volume_fraction * oil.density + (1 - oil.oil_volume_fraction) * 1.13
    eta = oil.oil_volume_fraction * oil.viscosity + (1 - oil.oil_volume_fraction) * 1.9e-5
    m = cage_drag_moment(wc, rho, eta, 0.5 * dm + 0.35 * d, 0.5 * dm - 0.35 * d)
    assert m < 0.0
    moment, power = cage_drag(y, cb, par)
    assert moment == pytest.approx(m, rel=1e-12)
    assert power == pytest.approx(-m * wc, rel=1e-12)
    dydt, *_ = evaluate(y, history, par, quad)
    bare = par._replace(cage_drag_laminar=0.0, cage_drag_turbulent=0.0)
    dydt_bare, *_ = evaluate(y, history, bare, quad)
    accel = dydt[cb + L.C_SPEED] - dydt_bare[cb + L.C_SPEED]
    assert accel == pytest.approx(m / par.cage_polar_inertia, rel=1e-9)
    assert cage_drag(y, cb, par._replace(traction=False)) == (0.0, 0.0)
    wetter = replace(inp, lubricant=replace(oil, oil_volume_fraction=0.05))
    _, par_wet, *_ = setup(wetter)
    assert cage_drag(y, cb, par_wet)[0] < moment


def test_observed_and_stage_evaluations_share_one_compiled_body():
    """The integrators' stage evaluations (``observed`` False) give the same derivatives as an
    observed evaluation, leave the angles and the elastic load NaN, and run the same compiled body
    of the right-hand side (``runtime_bool``: compiled once, not once per flag; numba lists a
    kernel's signatures only where this process compiled or loaded it by itself, not where a cached
    caller brought it along, hence at most one per signature of its caller)."""
    from solver.models.dynamic.kernels import _rhs_borrowed, rhs_into, rhs_work

    history, par, quad, y0 = start(spindle_inputs(radial=300.0))
    z = int(par.ball_count)
    dydt, rec_i, rec_o, _ = evaluate(y0, history, par, quad)
    stage = np.zeros_like(y0)
    stage_i = np.zeros((z, L.N_CONTACT_RECORD))
    stage_o = np.zeros((z, L.N_CONTACT_RECORD))
    rhs_into(y0, 0.0, history, par, quad, stage, stage_i, stage_o, np.zeros(z), rhs_work(z), False)
    np.testing.assert_array_equal(stage, dydt)
    assert np.isfinite(rec_i[:, L.K_ANGLE]).all() and np.isnan(stage_i[:, L.K_ANGLE]).all()
    assert np.isnan(stage_o[:, L.K_ELASTIC]).all() and (rec_o[:, L.K_ELASTIC] > 0.0).all()
    # one compiled body per model record: other tests of this process may have compiled rhs_into
    # for other records (another traction law's parameter tuples), never twice for one record
    # with the flag typed apart (the flag is its last argument)
    signatures = rhs_into.signatures
    assert signatures and len({sig[:-1] for sig in signatures}) == len(signatures)
    assert len(_rhs_borrowed.signatures) <= len(signatures)


def test_right_hand_side_reads_the_operating_history_at_its_time():
    """The imposed inputs at the evaluation's time: the ring spin angles advance at the history's
    speeds, the imposed tilt at its rate (which also turns the inner ring's frame), and a load
    step changes the free ring's acceleration by dF / m from the step's time on (right-continuous),
    the contacts being the same."""
    from solver.history import (
        CH_INNER_SPEED,
        CH_MISALIGNMENT,
        CH_RADIAL_LOAD,
        ChannelHistory,
        drive_at,
    )
    from tests.helpers.histories import with_history

    inp = spindle_inputs(axial=500.0, radial=300.0, misalignment=math.radians(0.02))
    history, par, quad, y = start(inp)
    speed = inp.operating.inner_ring_speed
    channels = {
        CH_INNER_SPEED: ChannelHistory((0.0, 1e-3), (speed, 2.0 * speed)),
        CH_MISALIGNMENT: ChannelHistory((0.0, 1e-3), (math.radians(0.02), math.radians(0.06))),
        CH_RADIAL_LOAD: ChannelHistory((5e-4, 5e-4), (300.0, 900.0)),
    }
    history = with_history(inp, channels, 1e-3, 1e4).history
    rb = L.ring_base(18)
    t = 2.5e-4
    dydt, *_ = evaluate(y, history, par, quad, t)
    drive = drive_at(history, t, y[rb + L.R_PHI_INNER])
    assert dydt[rb + L.R_PHI_INNER] == pytest.approx(1.25 * speed, rel=1e-12)
    rate = math.radians(0.04) / 1e-3
    assert math.hypot(dydt[rb + L.R_TILT], dydt[rb + L.R_TILT + 1]) == pytest.approx(rate)
    assert (dydt[rb + L.R_TILT], dydt[rb + L.R_TILT + 1]) == (drive.tilt_rate_y, drive.tilt_rate_z)
    rot, org, vel, om = np.empty((3, 3)), np.empty(3), np.empty(3), np.empty(3)
    orot, oom = np.empty((3, 3)), np.empty(3)
    ring_frames(y, par, drive, rot, org, vel, om, orot, oom)
    still = drive._replace(tilt_rate_y=0.0, tilt_rate_z=0.0)
    om_still = np.empty(3)
    ring_frames(y, par, still, rot, org, vel, om_still, orot, oom)
    expected = [0.0, drive.tilt_rate_y, drive.tilt_rate_z]
    np.testing.assert_allclose(om - om_still, expected, atol=1e-12 * rate)
    before, *_ = evaluate(y, history, par, quad, np.nextafter(5e-4, 0.0))
    after, *_ = evaluate(y, history, par, quad, 5e-4)
    step = after[rb + L.R_VEL : rb + L.R_VEL + 3] - before[rb + L.R_VEL : rb + L.R_VEL + 3]
    np.testing.assert_allclose(step, [0.0, 600.0 / par.ring_mass, 0.0], rtol=1e-9, atol=1e-6)
