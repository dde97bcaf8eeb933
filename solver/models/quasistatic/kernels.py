"""Numba kernels of the Jones–Harris quasi-static model (physics.md §2.5): one ball, and the ring
solve.

Geometry (physics.md §2.1, §2.5.1), per ball j at azimuth psi_j, in the ball's meridian plane with
components (axial x, radial r):

- the outer groove curvature centre is fixed at (x_o^c, rho_o^c);
- the ball centre is X = (X1, X2) relative to it, so the outer deflection is |X| - (f_o - 1/2) D and
  alpha_o = atan2(X1, X2);
- the inner groove curvature centre is A = (A1, A2) relative to the outer one, with the inner ring's
  small displacement q = (dx, dy, dz, theta_y, theta_z) (rotation vector (0, theta_y, theta_z)):

      A1 = (x_i^c - x_o^c) + dx + rho_i^c (theta_y sin psi - theta_z cos psi)
      A2 = (rho_i^c - rho_o^c) + dy cos psi + dz sin psi

  (the linearised rigid motion theta x p of the ring point p = rho_i^c e_r, the tilt turning the
  ring about its reference point: on the axis, in the plane of the inner groove curvature-centre
  circle, where the applied loads act); the inner
  deflection is |A - X| - (f_i - 1/2) D and alpha_i = atan2(A1 - X1, A2 - X2).

Forces on the ball (physics.md §2.5.4, sign re-derived in
solver.physics.kinematics.gyroscopic_moment): -Q_o u(alpha_o) + T_o from the outer ring,
+Q_i u(alpha_i) + T_i from the inner ring, +F_c e_r, with
T_o = (lambda_o M_g / D)(-cos alpha_o e_x + sin alpha_o e_r),
T_i = (lambda_i M_g / D)(cos alpha_i e_x - sin alpha_i e_r); (lambda_o, lambda_i) = (2, 0) under
outer control, (1, 1) under inner control. Their moment about the ball centre is M_g e_theta, the
rate of change of the ball's angular momentum.

The ball exerts -(Q_i u(alpha_i) + T_i) on the inner ring. Its moment about the ring centre (the
point of the inner ring that sits at the origin in the just-touching state) uses the lever arms of
the ring's own geometry (small-displacement statics), about the ring's reference point defined
above: the normal force acts along a line through the inner groove curvature centre C = rho_i^c e_r
(axial lever 0), the friction force at the contact point C + (r_i + delta_i/2)(-u(alpha_i)). Only
the e_theta component is non-zero: m = -rho_i^c F_x - (r_i + delta_i/2) lambda_i M_g / D.

Centrifugal force F_c = m r_orbit omega_c^2 with the ball's actual orbit radius
r_orbit = rho_o^c + X2 (the dynamic model sees the same force through r theta_dot^2).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from solver.physics.hertz_fast import contact_stiffness_fast, curvature_sum_and_difference_fast
from solver.physics.kinematics import attitude_angle, gyroscopic_moment, orbital_and_spin_speed


class BallModel(NamedTuple):
    """Constants of the ball model, SI units (m, Pa, kg, kg m^2, rad/s). Built by ``ball_model``."""

    ball_diameter: float
    pitch_diameter: float
    inner_conformity: float
    outer_conformity: float
    inner_center_offset: float  # (f_i - 1/2) D: ball centre to inner groove centre, unloaded
    outer_center_offset: float  # (f_o - 1/2) D
    inner_groove_radius: float  # r_i = f_i D
    effective_modulus: float  # E'
    ball_mass: float
    ball_inertia: float
    inner_center_axial: float  # x_i^c (ring frame)
    inner_center_radius: float  # rho_i^c
    outer_center_axial: float  # x_o^c
    outer_center_radius: float  # rho_o^c
    inner_ring_speed: float  # rad/s about +x
    outer_ring_speed: float  # rad/s about +x
    gamma_prime: float  # D / d_m


def ball_model(geometry, inner_ring_speed: float, outer_ring_speed: float) -> BallModel:
    """BallModel of a :class:`solver.geometry.BearingGeometry` at the given ring speeds [rad/s]."""
    D = geometry.ball_diameter
    return BallModel(
        ball_diameter=D,
        pitch_diameter=geometry.pitch_diameter,
        inner_conformity=geometry.inner_conformity,
        outer_conformity=geometry.outer_conformity,
        inner_center_offset=(geometry.inner_conformity - 0.5) * D,
        outer_center_offset=(geometry.outer_conformity - 0.5) * D,
        inner_groove_radius=geometry.inner_groove_radius,
        effective_modulus=geometry.effective_modulus,
        ball_mass=geometry.ball_mass,
        ball_inertia=geometry.ball_inertia,
        inner_center_axial=geometry.inner_curvature_center_axial,
        inner_center_radius=geometry.inner_curvature_center_radius,
        outer_center_axial=geometry.outer_curvature_center_axial,
        outer_center_radius=geometry.outer_curvature_center_radius,
        inner_ring_speed=float(inner_ring_speed),
        outer_ring_speed=float(outer_ring_speed),
        gamma_prime=geometry.gamma_prime,
    )


@njit(cache=True)
def contact_stiffness(model, contact_angle, is_inner):
    """Hertz load-deflection constant K [N/m^1.5] of one contact at the current contact angle."""
    gamma = model.ball_diameter * math.cos(contact_angle) / model.pitch_diameter
    if is_inner:
        conformity = model.inner_conformity
    else:
        conformity = model.outer_conformity
    sum_rho, f_rho = curvature_sum_and_difference_fast(
        model.ball_diameter, conformity, gamma, is_inner
    )
    return contact_stiffness_fast(sum_rho, f_rho, model.effective_modulus)


# ---- per-ball kinematics record: one row of ``control`` (Z, CONTROL_SIZE) per ball ------------
CONTROL_MODE = 0  # OUTER_CONTROL, INNER_CONTROL or TRACTION_BALANCE
CONTROL_ORBITAL = 1  # TRACTION_BALANCE: orbital speed omega_c [rad/s]
CONTROL_SPIN = 2  # TRACTION_BALANCE: spin speed omega_R relative to the cage [rad/s]
CONTROL_ATTITUDE = 3  # TRACTION_BALANCE: attitude angle beta [rad]
CONTROL_GYRO = 4  # TRACTION_BALANCE: gyroscopic moment M_g along e_theta [N m]
CONTROL_TAU_INNER = 5  # TRACTION_BALANCE: traction on the ball at the inner contact [N], along
#                        (cos alpha_i e_x - sin alpha_i e_r)
CONTROL_TAU_OUTER = 6  # TRACTION_BALANCE: the same at the outer contact [N], along
#                        (-cos alpha_o e_x + sin alpha_o e_r)
CONTROL_YAW = 7  # TRACTION_BALANCE: e_theta component of the ball's spin relative to the cage
CONTROL_SIZE = 8
OUTER_CONTROL = 0
INNER_CONTROL = 1
TRACTION_BALANCE = 2


class BallState(NamedTuple):
    """One ball at a trial position (:func:`ball_state`). SI units, angles in rad; forces and
    moments in the ball's meridian plane (axial e_x, radial e_r, moments along e_theta)."""

    residual_axial: float  # net force on the ball [N] (zero in equilibrium), axial
    residual_radial: float  # the same, radial
    ring_force_axial: float  # force the ball exerts on the inner ring [N], axial
    ring_force_radial: float  # the same, radial
    ring_moment: float  # its moment about the ring centre along e_theta [N m]
    inner_load: float  # contact loads [N]
    outer_load: float
    inner_deflection: float  # contact deflections [m] (negative = gap)
    outer_deflection: float
    inner_angle: float  # contact angles [rad]
    outer_angle: float
    attitude_angle: float  # beta [rad]
    orbital_speed: float  # omega_c [rad/s]
    spin_speed: float  # omega_R relative to the cage [rad/s]
    centrifugal_force: float  # F_c [N]
    gyroscopic_moment: float  # M_g along e_theta [N m]


class BallStates(NamedTuple):
    """Every ball's :class:`BallState` at its current position (:func:`evaluate_balls`): per ball
    (Z) or per contact (Z, 2) with columns [inner, outer]. Units as in :class:`BallState`."""

    ring_moment: np.ndarray  # (Z) [N m]
    contact_load: np.ndarray  # (Z, 2) [N]
    contact_deflection: np.ndarray  # (Z, 2) [m], negative = gap
    contact_angle: np.ndarray  # (Z, 2) [rad]
    attitude_angle: np.ndarray  # (Z) [rad]
    orbital_speed: np.ndarray  # (Z) [rad/s]
    spin_speed: np.ndarray  # (Z) [rad/s]
    centrifugal_force: np.ndarray  # (Z) [N]
    gyroscopic_moment: np.ndarray  # (Z) [N m]


class RingLoad(NamedTuple):
    """What the inner-ring equilibrium is solved for (:func:`solve_ring`): the applied loads
    ``applied`` (Fx, Fy, Fz [N], My, Mz [N m]), the balls' azimuths [rad] and kinematics records
    ``control`` (Z, CONTROL_SIZE), the :class:`BallModel` and the force scale [N] of the
    residuals."""

    applied: np.ndarray
    azimuth: np.ndarray
    control: np.ndarray
    model: BallModel
    force_scale: float


def race_control_rows(inner_control) -> np.ndarray:
    """``control`` array (Z, CONTROL_SIZE) of a race-control decision (bool per ball: True =
    inner control)."""
    inner = np.asarray(inner_control, dtype=np.bool_)
    out = np.zeros((inner.size, CONTROL_SIZE))
    out[:, CONTROL_MODE] = np.where(inner, INNER_CONTROL, OUTER_CONTROL)
    return out


@njit(cache=True)
def ball_state(x1, x2, a1, a2, control, model):
    """Everything about one ball whose centre is (x1, x2) and inner groove centre (a1, a2), both
    relative to the outer groove centre in the ball's meridian plane [m].

    ``control`` (CONTROL_SIZE) says how the ball's speeds and race friction are found: from race
    control (OUTER_CONTROL / INNER_CONTROL: rolling kinematics, gyroscopic moment taken by friction
    with the lambda split of the module docstring) or given (TRACTION_BALANCE: orbital and spin
    speed, attitude, gyroscopic moment and the transverse tractions of both contacts from the
    traction balance, :mod:`.traction_balance`).

    Returns a :class:`BallState`.
    """
    D = model.ball_diameter
    l_o = math.sqrt(x1 * x1 + x2 * x2)
    d_o = l_o - model.outer_center_offset
    alpha_o = math.atan2(x1, x2)
    e1 = a1 - x1
    e2 = a2 - x2
    l_i = math.sqrt(e1 * e1 + e2 * e2)
    d_i = l_i - model.inner_center_offset
    alpha_i = math.atan2(e1, e2)

    # A contact needs overlap on the raceway side of the groove-centre circle (cos(alpha) > 0): the
    # other half of the torus is not ring material (only reached far from equilibrium).
    q_o = 0.0
    if d_o > 0.0 and x2 > 0.0:
        q_o = contact_stiffness(model, alpha_o, False) * d_o * math.sqrt(d_o)
    q_i = 0.0
    if d_i > 0.0 and e2 > 0.0:
        q_i = contact_stiffness(model, alpha_i, True) * d_i * math.sqrt(d_i)

    # Kinematics with the inner angle kept within 1 rad of the outer one: the geometric angle of a
    # wide open inner contact (possible in trial iterates far from equilibrium) can point anywhere,
    # while rolling kinematics need both contacts on opposite sides of the ball. Continuous, and
    # inactive for any real contact.
    mode = int(control[CONTROL_MODE])
    if mode == TRACTION_BALANCE:
        beta = control[CONTROL_ATTITUDE]
        omega_c = control[CONTROL_ORBITAL]
        omega_r = control[CONTROL_SPIN]
        m_g = control[CONTROL_GYRO]
        t_i = control[CONTROL_TAU_INNER]
        t_o = control[CONTROL_TAU_OUTER]
    else:
        inner_control = mode == INNER_CONTROL
        kin_alpha_i = min(max(alpha_i, alpha_o - 1.0), alpha_o + 1.0)
        beta = attitude_angle(kin_alpha_i, alpha_o, model.gamma_prime, inner_control)
        omega_c, omega_r = orbital_and_spin_speed(
            kin_alpha_i,
            alpha_o,
            beta,
            model.gamma_prime,
            model.inner_ring_speed,
            model.outer_ring_speed,
        )
        m_g = gyroscopic_moment(model.ball_inertia, omega_r, omega_c, beta)
        if inner_control:
            lam_o = 1.0
            lam_i = 1.0
        else:
            lam_o = 2.0
            lam_i = 0.0
        t_o = lam_o * m_g / D
        t_i = lam_i * m_g / D
    f_c = model.ball_mass * (model.outer_center_radius + x2) * omega_c * omega_c

    s_o = math.sin(alpha_o)
    c_o = math.cos(alpha_o)
    s_i = math.sin(alpha_i)
    c_i = math.cos(alpha_i)
    res_x = -q_o * s_o - t_o * c_o + q_i * s_i + t_i * c_i
    res_r = -q_o * c_o + t_o * s_o + q_i * c_i - t_i * s_i + f_c

    ring_fx = -(q_i * s_i + t_i * c_i)
    ring_fr = -(q_i * c_i - t_i * s_i)
    lever = model.inner_groove_radius + (0.5 * d_i if q_i > 0.0 else 0.0)
    ring_moment = -model.inner_center_radius * ring_fx - lever * t_i
    return BallState(
        residual_axial=res_x,
        residual_radial=res_r,
        ring_force_axial=ring_fx,
        ring_force_radial=ring_fr,
        ring_moment=ring_moment,
        inner_load=q_i,
        outer_load=q_o,
        inner_deflection=d_i,
        outer_deflection=d_o,
        inner_angle=alpha_i,
        outer_angle=alpha_o,
        attitude_angle=beta,
        orbital_speed=omega_c,
        spin_speed=omega_r,
        centrifugal_force=f_c,
        gyroscopic_moment=m_g,
    )


@njit(cache=True)
def inner_center(q, psi, model):
    """(A1, A2): inner groove curvature centre relative to the outer one for ring displacement
    q = (dx, dy, dz, theta_y, theta_z) [m, rad] at azimuth psi [rad] (module docstring)."""
    s = math.sin(psi)
    c = math.cos(psi)
    rc = model.inner_center_radius
    a1 = (model.inner_center_axial - model.outer_center_axial) + q[0] + rc * (q[3] * s - q[4] * c)
    a2 = (rc - model.outer_center_radius) + q[1] * c + q[2] * s
    return a1, a2


@njit(cache=True)
def _residual_norm(x1, x2, a1, a2, control, model):
    st = ball_state(x1, x2, a1, a2, control, model)
    return st.residual_axial, st.residual_radial


@njit(cache=True)
def _fd_step(x1, x2, a1, a2, model):
    """Finite-difference step [m] for one ball: 1e-9 D, but at most 1e-3 of the larger contact
    deflection (tiny loads have tiny deflections), and no smaller than ~10 ulp of the positions."""
    d_o = math.sqrt(x1 * x1 + x2 * x2) - model.outer_center_offset
    e1 = a1 - x1
    e2 = a2 - x2
    d_i = math.sqrt(e1 * e1 + e2 * e2) - model.inner_center_offset
    h = 1e-9 * model.ball_diameter
    deflection = max(d_o, d_i)
    if deflection > 0.0:
        h = min(h, 1e-3 * deflection)
    floor = 1e-15 * (model.outer_center_offset + model.inner_center_offset)
    return max(h, floor)


@njit(cache=True)
def _ball_tolerance(x1, x2, a1, a2, control, model, force_scale):
    """Residual tolerance [N] of one ball: 1e-12 of its own largest force (contact loads,
    centrifugal force, gyroscopic friction), but not below what round-off of the positions allows
    (contact stiffness times a few ulp of the coordinates) nor 1e-16 of the bearing's force
    scale."""
    st = ball_state(x1, x2, a1, a2, control, model)
    own = max(
        max(st.inner_load, st.outer_load),
        max(abs(st.centrifugal_force), 2.0 * abs(st.gyroscopic_moment) / model.ball_diameter),
    )
    stiffness = 0.0
    if st.inner_deflection > 0.0:
        stiffness += 1.5 * st.inner_load / st.inner_deflection
    if st.outer_deflection > 0.0:
        stiffness += 1.5 * st.outer_load / st.outer_deflection
    coordinates = abs(x1) + abs(x2) + abs(a1) + abs(a2)
    round_off = 8.0 * 2.220446049250313e-16 * coordinates * stiffness
    return max(max(1e-12 * own, 1e-16 * force_scale), round_off)


@njit(cache=True)
def _static_ball(a1, a2, model):
    """Closed-form ball position without speed: on the line between the groove centres, the total
    approach split so that Q_i = Q_o (same contact angle at both), or mid-gap when there is no
    contact."""
    length = math.sqrt(a1 * a1 + a2 * a2)
    if length <= 0.0:
        return model.outer_center_offset, 0.0
    n1 = a1 / length
    n2 = a2 / length
    total = length - model.inner_center_offset - model.outer_center_offset
    if total <= 0.0:
        d_o = 0.5 * total
    else:
        alpha = math.atan2(a1, a2)
        k_i = contact_stiffness(model, alpha, True)
        k_o = contact_stiffness(model, alpha, False)
        d_o = total / (1.0 + (k_o / k_i) ** (2.0 / 3.0))
    r = model.outer_center_offset + d_o
    return n1 * r, n2 * r


@njit(cache=True)
def solve_ball(a1, a2, x1, x2, control, model, force_scale):
    """Equilibrium position (x1, x2) [m] of one ball for the inner groove centre (a1, a2), starting
    from (x1, x2). Returns (x1, x2, ok). Damped Newton with a finite-difference 2x2 Jacobian;
    without speed the closed form of :func:`_static_ball` is used.
    """
    if model.inner_ring_speed == 0.0 and model.outer_ring_speed == 0.0:
        x1, x2 = _static_ball(a1, a2, model)
        return x1, x2, True
    D = model.ball_diameter
    tol = 1e-13 * force_scale
    h = 1e-9 * D
    # A ball clear of the outer race is first put onto it (centrifugal force holds it there).
    l_o = math.sqrt(x1 * x1 + x2 * x2)
    if l_o - model.outer_center_offset <= 0.0 or l_o == 0.0:
        st = ball_state(x1, x2, a1, a2, control, model)
        if l_o == 0.0:
            n1, n2 = 0.0, 1.0
        else:
            n1, n2 = x1 / l_o, x2 / l_o
        k_o = contact_stiffness(model, math.atan2(n1, n2), False)
        d_guess = (max(st.centrifugal_force, 1e-12 * force_scale) / k_o) ** (2.0 / 3.0)
        x1 = n1 * (model.outer_center_offset + d_guess)
        x2 = n2 * (model.outer_center_offset + d_guess)
    # Newton in polar coordinates about the outer groove centre (rho = |X|, phi = alpha_o): a ball
    # held by the outer race alone slides along the groove (phi) at constant deflection, which a
    # Cartesian step cannot follow.
    rho = math.sqrt(x1 * x1 + x2 * x2)
    phi = math.atan2(x1, x2)
    r1, r2 = _residual_norm(x1, x2, a1, a2, control, model)
    norm = math.hypot(r1, r2)
    for _ in range(60):
        tol = _ball_tolerance(x1, x2, a1, a2, control, model, force_scale)
        if norm <= tol:
            return x1, x2, True
        h = _fd_step(x1, x2, a1, a2, model)
        hp = h / rho
        p1, p2 = _residual_norm(
            (rho + h) * math.sin(phi), (rho + h) * math.cos(phi), a1, a2, control, model
        )
        s1, s2 = _residual_norm(
            rho * math.sin(phi + hp), rho * math.cos(phi + hp), a1, a2, control, model
        )
        j11 = (p1 - r1) / h
        j21 = (p2 - r2) / h
        j12 = (s1 - r1) / hp
        j22 = (s2 - r2) / hp
        det = j11 * j22 - j12 * j21
        scale = abs(j11 * j22) + abs(j12 * j21)
        if scale == 0.0 or abs(det) <= 1e-14 * scale:
            return x1, x2, False
        d_rho = -(j22 * r1 - j12 * r2) / det
        d_phi = -(-j21 * r1 + j11 * r2) / det
        # keep a step within a fraction of the groove-centre offset and 0.3 rad along the groove
        factor = 1.0
        limit = 0.05 * model.outer_center_offset
        if abs(d_rho) > limit:
            factor = limit / abs(d_rho)
        if abs(d_phi) * factor > 0.3:
            factor = 0.3 / abs(d_phi)
        d_rho *= factor
        d_phi *= factor
        step = math.hypot(d_rho, rho * d_phi)
        t = 1.0
        accepted = False
        for _ls in range(30):
            n_rho = rho + t * d_rho
            n_phi = phi + t * d_phi
            n1 = n_rho * math.sin(n_phi)
            n2 = n_rho * math.cos(n_phi)
            q1, q2 = _residual_norm(n1, n2, a1, a2, control, model)
            new_norm = math.hypot(q1, q2)
            if new_norm < (1.0 - 1e-4 * t) * norm or new_norm <= tol:
                accepted = True
                break
            t *= 0.5
        if not accepted:
            # no decrease possible: converged to round-off if the step is negligible
            return x1, x2, step <= 1e-13 * D or norm <= 1e3 * tol
        rho, phi = n_rho, n_phi
        x1, x2, r1, r2, norm = n1, n2, q1, q2, new_norm
        if t * step <= 1e-15 * D:
            return x1, x2, True
    return x1, x2, norm <= 1e3 * tol


@njit(cache=True)
def _generalised(fx, fr, moment, psi, out):
    """Map (axial force, radial force, e_theta moment) at azimuth psi onto (Fx, Fy, Fz, My, Mz)."""
    s = math.sin(psi)
    c = math.cos(psi)
    out[0] = fx
    out[1] = fr * c
    out[2] = fr * s
    out[3] = -moment * s
    out[4] = moment * c


@njit(cache=True)
def ring_residual_and_jacobian(q, position, ring, want_jacobian, residual, jacobian):
    """Solve every ball for the ring displacement q and sum their forces on the inner ring.

    ``position`` (Z, 2) holds the ball positions (warm start in, solution out); ``ring`` is the
    :class:`RingLoad`. Fills ``residual`` (5) = applied + sum of the balls' generalised forces on
    the ring (Fx, Fy, Fz [N], My, Mz [N m]) and, if ``want_jacobian``, ``jacobian`` (5, 5) =
    d residual / d q by the implicit-function theorem on each ball's equilibrium. Returns False if
    a ball could not be solved.
    """
    applied, azimuth, control, model = ring.applied, ring.azimuth, ring.control, ring.model
    force_scale = ring.force_scale
    z = azimuth.shape[0]
    for k in range(5):
        residual[k] = applied[k]
        for m in range(5):
            jacobian[k, m] = 0.0
    gen = np.empty(5)
    h = 1e-9 * model.ball_diameter
    ok_all = True
    for j in range(z):
        psi = azimuth[j]
        a1, a2 = inner_center(q, psi, model)
        x1, x2, ok = solve_ball(
            a1, a2, position[j, 0], position[j, 1], control[j], model, force_scale
        )
        if not ok:
            ok_all = False
        position[j, 0] = x1
        position[j, 1] = x2
        st = ball_state(x1, x2, a1, a2, control[j], model)
        _generalised(st.ring_force_axial, st.ring_force_radial, st.ring_moment, psi, gen)
        for k in range(5):
            residual[k] += gen[k]
        if not want_jacobian or st.inner_load <= 0.0:
            continue  # a ball without inner contact exerts no force on the ring
        h = _fd_step(x1, x2, a1, a2, model)
        # finite-difference partial derivatives w.r.t. (x1, x2, a1, a2)
        d = np.empty((5, 4))  # rows: res_x, res_r, ring_fx, ring_fr, ring_moment
        for col in range(4):
            y1, y2, b1, b2 = x1, x2, a1, a2
            if col == 0:
                y1 += h
            elif col == 1:
                y2 += h
            elif col == 2:
                b1 += h
            else:
                b2 += h
            sp = ball_state(y1, y2, b1, b2, control[j], model)
            d[0, col] = (sp.residual_axial - st.residual_axial) / h
            d[1, col] = (sp.residual_radial - st.residual_radial) / h
            d[2, col] = (sp.ring_force_axial - st.ring_force_axial) / h
            d[3, col] = (sp.ring_force_radial - st.ring_force_radial) / h
            d[4, col] = (sp.ring_moment - st.ring_moment) / h
        det = d[0, 0] * d[1, 1] - d[0, 1] * d[1, 0]
        scale = abs(d[0, 0] * d[1, 1]) + abs(d[0, 1] * d[1, 0])
        if scale == 0.0 or abs(det) <= 1e-14 * scale:
            continue
        # dX/dA = -J_XX^-1 J_XA
        dxda = np.empty((2, 2))
        for col in range(2):
            b1 = d[0, 2 + col]
            b2 = d[1, 2 + col]
            dxda[0, col] = -(d[1, 1] * b1 - d[0, 1] * b2) / det
            dxda[1, col] = -(-d[1, 0] * b1 + d[0, 0] * b2) / det
        # total derivative of (ring_fx, ring_fr, ring_moment) w.r.t. (a1, a2)
        dfda = np.empty((3, 2))
        for row in range(3):
            for col in range(2):
                dfda[row, col] = (
                    d[2 + row, 2 + col]
                    + d[2 + row, 0] * dxda[0, col]
                    + d[2 + row, 1] * dxda[1, col]
                )
        s = math.sin(psi)
        c = math.cos(psi)
        rc = model.inner_center_radius
        dadq = np.zeros((2, 5))
        dadq[0, 0] = 1.0
        dadq[0, 3] = rc * s
        dadq[0, 4] = -rc * c
        dadq[1, 1] = c
        dadq[1, 2] = s
        for m in range(5):
            dfx = dfda[0, 0] * dadq[0, m] + dfda[0, 1] * dadq[1, m]
            dfr = dfda[1, 0] * dadq[0, m] + dfda[1, 1] * dadq[1, m]
            dmo = dfda[2, 0] * dadq[0, m] + dfda[2, 1] * dadq[1, m]
            _generalised(dfx, dfr, dmo, psi, gen)
            for k in range(5):
                jacobian[k, m] += gen[k]
    return ok_all


@njit(cache=True)
def _merit(residual, free, scale):
    total = 0.0
    for k in range(5):
        if free[k]:
            v = residual[k] / scale[k]
            total += v * v
    return math.sqrt(total)


@njit(cache=True)
def solve_ring(q, position, ring, free, length_scale, tolerance, max_iterations):
    """Newton / Levenberg–Marquardt solve of the inner-ring equilibrium (the :class:`RingLoad`
    ``ring``) for the free components of q = (dx, dy, dz, theta_y, theta_z); the others stay as
    given. ``q`` and ``position`` are updated in place. Residuals are scaled by
    ``ring.force_scale`` [N] (moments by force_scale * d_m / 2), unknowns by ``length_scale`` [m]
    (tilts by length_scale / (d_m / 2)).

    Returns (converged, iterations, scaled residual norm).
    """
    model, force_scale = ring.model, ring.force_scale
    half_pitch = 0.5 * model.pitch_diameter
    rscale = np.empty(5)
    qscale = np.empty(5)
    for k in range(5):
        if k < 3:
            rscale[k] = force_scale
            qscale[k] = length_scale
        else:
            rscale[k] = force_scale * half_pitch
            qscale[k] = length_scale / half_pitch
    idx = np.empty(5, dtype=np.int64)
    n = 0
    for k in range(5):
        if free[k]:
            idx[n] = k
            n += 1
    residual = np.empty(5)
    jacobian = np.empty((5, 5))
    trial_res = np.empty(5)
    dummy = np.empty((5, 5))
    trial_pos = position.copy()
    trial_q = q.copy()
    # plain bools, not literals: numba compiles one variant of ring_residual_and_jacobian
    with_jacobian, without_jacobian = np.bool_(True), np.bool_(False)
    ok = ring_residual_and_jacobian(q, position, ring, with_jacobian, residual, jacobian)
    merit = _merit(residual, free, rscale)
    mu = 0.0
    iterations = 0
    while iterations < max_iterations:
        if ok and merit <= tolerance:
            return True, iterations, merit
        iterations += 1
        # scaled Jacobian and residual of the free components
        jac = np.empty((n, n))
        rhs = np.empty(n)
        for a in range(n):
            rhs[a] = -residual[idx[a]] / rscale[idx[a]]
            for b in range(n):
                jac[a, b] = jacobian[idx[a], idx[b]] * qscale[idx[b]] / rscale[idx[a]]
        # Directions the balls do not resist at all (e.g. a tangential shift with a single loaded
        # ball) have zero columns: leave them out of this step.
        col_norm = np.zeros(n)
        row_norm = np.zeros(n)
        for a in range(n):
            for b in range(n):
                col_norm[b] += jac[a, b] * jac[a, b]
                row_norm[a] += jac[a, b] * jac[a, b]
        big = max(np.max(col_norm), 1e-300) if n > 0 else 1.0
        active = np.zeros(n, dtype=np.bool_)
        for a in range(n):
            active[a] = col_norm[a] > 1e-24 * big or row_norm[a] > 1e-24 * big
        accepted = False
        for _attempt in range(12):
            step = np.zeros(n)
            solved = True
            if mu == 0.0:
                # plain Newton on the active block if it is well conditioned
                m_act = 0
                for a in range(n):
                    if active[a]:
                        m_act += 1
                sub = np.empty((m_act, m_act))
                sub_rhs = np.empty(m_act)
                ia = 0
                for a in range(n):
                    if not active[a]:
                        continue
                    sub_rhs[ia] = rhs[a]
                    ib = 0
                    for b in range(n):
                        if active[b]:
                            sub[ia, ib] = jac[a, b]
                            ib += 1
                    ia += 1
                cond = np.linalg.cond(sub) if m_act > 0 else 1.0
                if np.isfinite(cond) and cond <= 1e12:
                    sub_step = np.linalg.solve(sub, sub_rhs) if m_act > 0 else np.zeros(0)
                    ia = 0
                    for a in range(n):
                        if active[a]:
                            step[a] = sub_step[ia]
                            ia += 1
                else:
                    mu = 1e-6
            if mu > 0.0:
                # Levenberg–Marquardt with Marquardt's diagonal scaling
                jtj = jac.T @ jac
                diag_max = 0.0
                for a in range(n):
                    diag_max = max(diag_max, jtj[a, a])
                if diag_max == 0.0:
                    diag_max = 1.0
                for a in range(n):
                    jtj[a, a] = jtj[a, a] * (1.0 + mu) + 1e-15 * diag_max
                step = np.linalg.solve(jtj, jac.T @ rhs)
            if not np.all(np.isfinite(step)):
                solved = False
            if not solved:
                mu = 1e-3 if mu == 0.0 else mu * 10.0
                continue
            norm = math.sqrt(np.sum(step * step))
            limit = max(
                20.0, 0.05 * (model.inner_center_offset + model.outer_center_offset) / length_scale
            )
            if norm > limit:
                step *= limit / norm
            # backtracking line search on the scaled residual norm
            t = 1.0
            for _ls in range(12):
                for k in range(5):
                    trial_q[k] = q[k]
                for a in range(n):
                    trial_q[idx[a]] = q[idx[a]] + t * step[a] * qscale[idx[a]]
                trial_pos[:, :] = position
                tok = ring_residual_and_jacobian(
                    trial_q, trial_pos, ring, without_jacobian, trial_res, dummy
                )
                tmerit = _merit(trial_res, free, rscale)
                if tok and tmerit < (1.0 - 1e-4 * t) * merit:
                    accepted = True
                    break
                t *= 0.5
            if accepted:
                break
            mu = 1e-3 if mu == 0.0 else mu * 10.0
        if not accepted:
            # no further decrease: accept a residual within 100x the tolerance as round-off limited
            # (tiny loads on a large bearing), otherwise report failure
            return ok and merit <= 100.0 * tolerance, iterations, merit
        for k in range(5):
            q[k] = trial_q[k]
        position[:, :] = trial_pos
        if tok and tmerit <= tolerance:
            # converged at the accepted trial: its residual is the one a new evaluation at q (the
            # balls already solved there) would give, and the Jacobian is not needed
            return True, iterations, tmerit
        mu = 0.0 if t == 1.0 else mu * 0.1
        if mu < 1e-9:
            mu = 0.0
        ok = ring_residual_and_jacobian(q, position, ring, with_jacobian, residual, jacobian)
        merit = _merit(residual, free, rscale)
    return ok and merit <= tolerance, iterations, merit


@njit(cache=True)
def evaluate_balls(q, azimuth, position, control, model):
    """:class:`BallStates`: :func:`ball_state` of every ball at its current ``position`` (Z, 2)
    for the ring displacement ``q`` and the kinematics records ``control``."""
    z = azimuth.shape[0]
    out = BallStates(
        ring_moment=np.empty(z),
        contact_load=np.empty((z, 2)),
        contact_deflection=np.empty((z, 2)),
        contact_angle=np.empty((z, 2)),
        attitude_angle=np.empty(z),
        orbital_speed=np.empty(z),
        spin_speed=np.empty(z),
        centrifugal_force=np.empty(z),
        gyroscopic_moment=np.empty(z),
    )
    for j in range(z):
        a1, a2 = inner_center(q, azimuth[j], model)
        st = ball_state(position[j, 0], position[j, 1], a1, a2, control[j], model)
        out.ring_moment[j] = st.ring_moment
        out.contact_load[j, 0] = st.inner_load
        out.contact_load[j, 1] = st.outer_load
        out.contact_deflection[j, 0] = st.inner_deflection
        out.contact_deflection[j, 1] = st.outer_deflection
        out.contact_angle[j, 0] = st.inner_angle
        out.contact_angle[j, 1] = st.outer_angle
        out.attitude_angle[j] = st.attitude_angle
        out.orbital_speed[j] = st.orbital_speed
        out.spin_speed[j] = st.spin_speed
        out.centrifugal_force[j] = st.centrifugal_force
        out.gyroscopic_moment[j] = st.gyroscopic_moment
    return out


@njit(cache=True)
def _static_excess(q, k, applied, azimuth, model, direction):
    """Static residual (applied + balls, closed-form ball positions) of component k along
    ``direction``: k = 0 axial force, k = 1 radial force, k = 2 moment. Second value: loaded
    balls."""
    total = 0.0
    loaded = 0
    gen = np.empty(5)
    outer_control = np.zeros(CONTROL_SIZE)  # no speed: the kinematics do not matter
    for j in range(azimuth.shape[0]):
        psi = azimuth[j]
        a1, a2 = inner_center(q, psi, model)
        x1, x2 = _static_ball(a1, a2, model)
        st = ball_state(x1, x2, a1, a2, outer_control, model)
        _generalised(st.ring_force_axial, st.ring_force_radial, st.ring_moment, psi, gen)
        total += _along(gen, k, direction)
        if st.inner_load > 0.0:
            loaded += 1
    return total + _along(applied, k, direction), loaded


@njit(cache=True, inline="always")
def _along(generalised, k, direction):
    """Component ``k`` of a generalised force (Fx, Fy, Fz, My, Mz): 0 the axial force, 1 the radial
    force along ``direction`` (y, z), 2 the moment about it."""
    if k == 0:
        return generalised[0]
    if k == 1:
        return generalised[1] * direction[0] + generalised[2] * direction[1]
    return generalised[3] * direction[0] + generalised[4] * direction[1]


@njit(cache=True)
def _set_component(q, k, value, direction):
    if k == 0:
        q[0] = value
    elif k == 1:
        q[1] = value * direction[0]
        q[2] = value * direction[1]
    else:
        q[3] = value * direction[0]
        q[4] = value * direction[1]


@njit(cache=True)
def _bisect_component(q, k, applied, azimuth, model, direction, lo, hi, resolution):
    """Set component k of q (see :func:`_static_excess`) in [lo, hi] (widened if needed) so that the
    static residual along ``direction`` vanishes; it decreases as the component grows. The root is
    bracketed and then found by the Illinois variant of regula falsi (a secant step inside the
    bracket, the retained end's residual halved when the same end is kept twice), stopped when the
    bracket or the last step is within ``resolution``. Left unchanged when no ball is loaded
    anywhere in the bracket (the residual carries no information there)."""
    if k == 0:
        start = q[0]
    elif k == 1:
        start = q[1] * direction[0] + q[2] * direction[1]
    else:
        start = q[3] * direction[0] + q[4] * direction[1]
    _set_component(q, k, lo, direction)
    f_lo, n_lo = _static_excess(q, k, applied, azimuth, model, direction)
    _set_component(q, k, hi, direction)
    f_hi, n_hi = _static_excess(q, k, applied, azimuth, model, direction)
    for _ in range(30):
        if f_lo > 0.0 and f_hi < 0.0:
            break
        width = hi - lo
        if f_lo <= 0.0:
            lo -= width
            _set_component(q, k, lo, direction)
            f_lo, n_lo = _static_excess(q, k, applied, azimuth, model, direction)
        if f_hi >= 0.0:
            hi += width
            _set_component(q, k, hi, direction)
            f_hi, n_hi = _static_excess(q, k, applied, azimuth, model, direction)
    if not (f_lo > 0.0 and f_hi < 0.0):
        _set_component(q, k, start, direction)
        return False
    kept = 0  # +1: lo kept in a row, -1: hi kept in a row
    previous = lo
    for _ in range(100):
        if hi - lo <= resolution:
            break
        x = lo + (hi - lo) * f_lo / (f_lo - f_hi)
        # keep the trial strictly inside the bracket (rounding at a nearly flat end)
        x = min(max(x, lo + 0.25 * resolution), hi - 0.25 * resolution)
        _set_component(q, k, x, direction)
        f_x, _n = _static_excess(q, k, applied, azimuth, model, direction)
        if f_x == 0.0:
            return True
        if f_x > 0.0:
            lo, f_lo = x, f_x
            if kept == -1:
                f_hi *= 0.5
            kept = -1
        else:
            hi, f_hi = x, f_x
            if kept == 1:
                f_lo *= 0.5
            kept = 1
        if abs(x - previous) <= resolution:
            return True
        previous = x
    _set_component(q, k, 0.5 * (lo + hi), direction)
    return True


#: Half-width of the bracket of the static start's later passes, relative to the first pass's
#: (the coupling of the radial, axial and tilt balances moves each root by far less)
STATIC_REFINE_WIDTH = 1.0 / 32.0


@njit(cache=True)
def static_start(q, applied, free_tilt, azimuth, model, length_scale, passes):
    """Starting ring displacement without speed: find in turn (:func:`_bisect_component`) the
    radial shift (along the radial load), the axial shift and, when the tilt is free, the tilt along
    the applied moment, each so that its static force (moment) balances, ``passes`` times. The
    first pass brackets each component over the whole range of the groove clearance; the later
    ones start from a bracket of STATIC_REFINE_WIDTH of that range about the previous pass's value
    (widened when it does not hold the root). ``q`` is updated in place."""
    radial = np.array([1.0, 0.0])
    fr = math.hypot(applied[1], applied[2])
    if fr > 0.0:
        radial[0] = applied[1] / fr
        radial[1] = applied[2] / fr
    moment_dir = np.array([0.0, 1.0])
    mm = math.hypot(applied[3], applied[4])
    if mm > 0.0:
        moment_dir[0] = applied[3] / mm
        moment_dir[1] = applied[4] / mm
    a0 = model.inner_center_offset + model.outer_center_offset
    span = 2.0 * a0 + 100.0 * length_scale
    shift = model.inner_center_axial - model.outer_center_axial  # A0 sin(alpha0)
    tilt_span = span / model.inner_center_radius
    dummy = np.zeros(2)
    resolution = 1e-3 * length_scale  # a starting point; Newton takes it from there
    # the component index as an int64 variable, not a literal: numba compiles one variant of
    # _bisect_component (and _static_excess, _set_component) for the three components
    radial_k, axial_k, tilt_k = np.int64(1), np.int64(0), np.int64(2)
    radial_centre = 0.0
    axial_centre = -shift
    tilt_centre = 0.0
    width = 1.0
    for _ in range(passes):
        if fr > 0.0:
            _bisect_component(
                q,
                radial_k,
                applied,
                azimuth,
                model,
                radial,
                radial_centre - width * span,
                radial_centre + width * span,
                resolution,
            )
        _bisect_component(
            q,
            axial_k,
            applied,
            azimuth,
            model,
            dummy,
            axial_centre - width * span,
            axial_centre + width * span,
            resolution,
        )
        if free_tilt and mm > 0.0:
            _bisect_component(
                q,
                tilt_k,
                applied,
                azimuth,
                model,
                moment_dir,
                tilt_centre - width * tilt_span,
                tilt_centre + width * tilt_span,
                resolution / model.inner_center_radius,
            )
        radial_centre = q[1] * radial[0] + q[2] * radial[1]
        axial_centre = q[0]
        tilt_centre = q[3] * moment_dir[0] + q[4] * moment_dir[1]
        width = STATIC_REFINE_WIDTH
