"""Initial state of the dynamic model: a quasi-static equilibrium of the model's own contact laws.

physics.md §2.7: starting from rest or from kinematic speeds with zero deflection causes impact
transients lasting tens of revolutions. The state built here is an equilibrium of the *same* Hertz
contact kernel the dynamic model integrates, so a run starts without an elastic transient:

1. every ball sits at its azimuth psi_j = 2 pi j / Z, orbiting at the cage speed omega_c;
2. ball centres (axial, radial) and the inner-ring translation (and tilt, when a tilting moment is
   given) solve the force balance of the normal contact forces, the centrifugal force
   m r omega_c^2 and the applied loads (scipy least_squares on the numba right-hand side with
   traction, damping, cage and gravity switched off);
   (The tangential balance is not imposed: with the inner ring offset, the inner contact normal
   leaves the inertial meridian plane by ~offset/pitch radius, a tangential force of order 1e-4 Q
   that traction or the cage carry in the dynamic run.)
3. omega_c and each ball's spin follow outer-raceway control (physics.md §2.5.3) evaluated with the
   solved contact angles (two fixed-point passes);
4. ball orientation: the ball-fixed frame of the quasi-static convention, z_b = cos(beta) e_x -
   sin(beta) e_r, y_b = e_theta, x_b = sin(beta) e_x + cos(beta) e_r.

The gyroscopic moment is not balanced here (it needs traction): the dynamic model establishes the
small slips that carry it within the first fraction of a revolution. This initialiser is the model's
own; the project's quasi-static solver (solver.models.quasistatic) is used for validation.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares

from solver.errors import NoSolutionError
from solver.models.quasistatic.solver import solve_operating_point

from . import layout as L
from .kernels import rhs
from .params import drive_at_start


def matrix_to_quaternion(m: np.ndarray) -> np.ndarray:
    """Unit quaternion [w, x, y, z] of a rotation matrix (Shepperd's method)."""
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    if tr > 0.0:
        s = math.sqrt(tr + 1.0) * 2.0
        q = [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2.0
        q = [(m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s]
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2.0
        q = [(m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s]
    else:
        s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2.0
        q = [(m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s]
    q = np.array(q)
    if q[0] < 0:
        q = -q
    return q / np.linalg.norm(q)


def outer_control_kinematics(alpha_i: float, alpha_o: float, gamma_prime: float):
    """(omega_c / omega, omega_R / omega, beta) for outer-raceway control (physics.md §2.5.3), with
    omega the inner-ring speed relative to the outer ring."""
    beta = math.atan2(math.sin(alpha_o), math.cos(alpha_o) + gamma_prime)
    tb = math.tan(beta)
    ratio_c = (1.0 - gamma_prime * math.cos(alpha_i)) / (1.0 + math.cos(alpha_i - alpha_o))
    den = (
        gamma_prime
        * math.cos(beta)
        * (
            (math.cos(alpha_o) + tb * math.sin(alpha_o)) / (1.0 + gamma_prime * math.cos(alpha_o))
            + (math.cos(alpha_i) + tb * math.sin(alpha_i)) / (1.0 - gamma_prime * math.cos(alpha_i))
        )
    )
    return ratio_c, -1.0 / den, beta


def ball_frame(psi: float, beta: float) -> np.ndarray:
    """Rotation matrix (ball-fixed -> inertial) of the quasi-static ball frame at azimuth psi."""
    ex = np.array([1.0, 0.0, 0.0])
    er = np.array([0.0, math.cos(psi), math.sin(psi)])
    et = np.array([0.0, -math.sin(psi), math.cos(psi)])
    xb = math.sin(beta) * ex + math.cos(beta) * er
    zb = math.cos(beta) * ex - math.sin(beta) * er
    return np.column_stack((xb, et, zb))


def _static_par(par):
    """The parameters of the static force balance: no traction, damping, cage or gravity; ring
    free."""
    return par._replace(traction=False, damping_ratio=0.0, cage=False, gravity=0.0, ring_free=True)


def _state_from_unknowns(u, z, base_state, tilt_dof, length_scale, pitch_radius):
    """State from the static unknowns: per ball (axial, radial) offsets from the nominal position on
    the pitch circle, then the ring translation and (tilt DOF only) tilt x pitch radius; all in
    units of ``length_scale``."""
    y = base_state.copy()
    rb = L.ring_base(z)
    for j in range(z):
        psi = 2.0 * math.pi * j / z
        b = L.ball_base(j)
        rr = pitch_radius + u[2 * j + 1] * length_scale
        y[b + L.B_POS] = u[2 * j] * length_scale
        y[b + L.B_POS + 1] = rr * math.cos(psi)
        y[b + L.B_POS + 2] = rr * math.sin(psi)
    k = 2 * z
    y[rb + L.R_POS : rb + L.R_POS + 3] = u[k : k + 3] * length_scale
    if tilt_dof:
        y[rb + L.R_TILT : rb + L.R_TILT + 2] = u[k + 3 : k + 5] * length_scale / pitch_radius
    return y


def _contact_angles(y, history, par, quad):
    z = int(par.ball_count)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    dydt = np.zeros_like(y)
    rhs(y, 0.0, history, _static_par(par), quad, dydt, rec_i, rec_o, np.zeros(z))
    return rec_i, rec_o


def initial_state(history, par, quad: np.ndarray, passes: int = 3) -> np.ndarray:
    """Initial state vector (layout ``L``) in quasi-static equilibrium for the parameters ``par``
    under the imposed inputs of the operating history ``history`` at t = 0.

    Raises NoSolutionError when the force balance cannot be solved (e.g. no load holds the balls).
    """
    z = int(par.ball_count)
    d, dm = par.ball_diameter, par.pitch_diameter
    n = L.state_size(z)
    rb = L.ring_base(z)
    cb = L.cage_base(z)
    gamma_prime = d / dm
    alpha0 = math.atan2(
        par.inner_centre_axial - par.outer_centre_axial,
        par.inner_centre_radius - par.outer_centre_radius,
    )  # free contact angle from the curvature-centre circles
    tilt_dof = par.tilt_mode == L.TILT_FREE
    base = np.zeros(n)
    for j in range(z):
        psi = 2.0 * math.pi * j / z
        b = L.ball_base(j)
        base[b + 1] = 0.5 * dm * math.cos(psi)
        base[b + 2] = 0.5 * dm * math.sin(psi)
        base[b + L.B_QUAT] = 1.0
    drive = drive_at_start(history)
    if not tilt_dof:
        base[rb + L.R_TILT] = drive.tilt_y
        base[rb + L.R_TILT + 1] = drive.tilt_z
    pstat = _static_par(par)
    mb = par.ball_mass
    mr = par.ring_mass
    wrel = drive.inner_speed - drive.outer_speed
    load = max(abs(drive.force_x), math.hypot(drive.force_y, drive.force_z), 1e-3)
    fscale = load / z
    ls = 1e-6  # unknowns in micrometres
    ird = par.ring_diametral_inertia
    # first guess: rigid axial shift sharing the axial load, balls on the pitch circle
    u0 = np.zeros(2 * z + (5 if tilt_dof else 3))
    u0[2 * z] = 1.0
    omega_c = drive.outer_speed + wrel * 0.5 * (1.0 - gamma_prime * math.cos(alpha0))
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    dydt = np.zeros(n)
    pocket = np.zeros(z)

    def residual(u, omega_c):
        y = _state_from_unknowns(u, z, base, tilt_dof, ls, 0.5 * dm)
        rhs(y, 0.0, history, pstat, quad, dydt, rec_i, rec_o, pocket)
        res = np.empty_like(u)
        for j in range(z):
            b = L.ball_base(j)
            psi = 2.0 * math.pi * j / z
            # net force plus the centripetal requirement m omega_c^2 (0, y, z) must vanish
            w2 = omega_c**2
            fy = (dydt[b + L.B_VEL + 1] + w2 * y[b + 1]) * mb
            fz = (dydt[b + L.B_VEL + 2] + w2 * y[b + 2]) * mb
            ax = dydt[b + L.B_VEL] * mb
            rad = fy * math.cos(psi) + fz * math.sin(psi)
            res[2 * j] = ax / fscale + 1e-9 * u[2 * j]
            res[2 * j + 1] = rad / fscale + 1e-9 * u[2 * j + 1]
        k = 2 * z
        res[k : k + 3] = dydt[rb + L.R_VEL : rb + L.R_VEL + 3] * mr / fscale
        if tilt_dof:
            res[k + 3 : k + 5] = (
                dydt[rb + L.R_TILT_RATE : rb + L.R_TILT_RATE + 2] * ird / (fscale * 0.5 * dm)
            )
        return res

    def balanced(u, omega_c, tolerance):
        """The unknowns that balance the forces at cage speed ``omega_c``, from ``u`` (least
        squares, ``tolerance`` on the step, the cost and the gradient)."""
        return least_squares(
            residual,
            u,
            args=(omega_c,),
            x_scale="jac",
            xtol=tolerance,
            ftol=tolerance,
            gtol=tolerance,
            max_nfev=4000,
        ).x

    u = u0
    for _ in range(passes):
        u = balanced(u, omega_c, 1e-13)
        y = _state_from_unknowns(u, z, base, tilt_dof, ls, 0.5 * dm)
        rec_i, rec_o = _contact_angles(y, history, par, quad)
        loaded = (rec_i[:, L.K_LOAD] > 0) & (rec_o[:, L.K_LOAD] > 0)
        if not loaded.any():
            raise NoSolutionError(
                "dynamic model initialisation: no ball is loaded at both races in the quasi-static "
                "equilibrium; give an axial load (or a larger one) so that the balls are held"
            )
        ai = float(np.mean(rec_i[loaded, L.K_ANGLE]))
        ao = float(np.mean(rec_o[loaded, L.K_ANGLE]))
        ratio_c, _, _ = outer_control_kinematics(ai, ao, gamma_prime)
        omega_c = drive.outer_speed + wrel * ratio_c
    u = balanced(u, omega_c, 1e-14)
    if np.max(np.abs(residual(u, omega_c))) > 1e-4:
        raise NoSolutionError(
            "dynamic model initialisation: the quasi-static force balance did not converge "
            f"(largest residual {np.max(np.abs(residual(u, omega_c))):.2e} of the mean ball load); "
            "check the loads and the speed"
        )
    y = _state_from_unknowns(u, z, base, tilt_dof, ls, 0.5 * dm)
    rec_i, rec_o = _contact_angles(y, history, par, quad)
    for j in range(z):
        b = L.ball_base(j)
        psi = 2.0 * math.pi * j / z
        ai = rec_i[j, L.K_ANGLE] if rec_i[j, L.K_LOAD] > 0 else alpha0
        ao = rec_o[j, L.K_ANGLE] if rec_o[j, L.K_LOAD] > 0 else alpha0
        _, ratio_r, beta = outer_control_kinematics(ai, ao, gamma_prime)
        pos = y[b : b + 3]
        y[b + L.B_VEL : b + L.B_VEL + 3] = np.cross([omega_c, 0.0, 0.0], pos)
        rot = ball_frame(psi, beta)
        y[b + L.B_QUAT : b + L.B_QUAT + 4] = matrix_to_quaternion(rot)
        spin = ratio_r * wrel
        # omega_b = omega_R z_b + omega_c e_x  (z_b = cos(beta) e_x - sin(beta) e_r)
        y[b + L.B_OMEGA : b + L.B_OMEGA + 3] = spin * rot[:, 2] + np.array([omega_c, 0.0, 0.0])
    y[rb + L.R_VEL : rb + L.R_VEL + 3] = 0.0
    y[cb + L.C_POS] = float(np.mean([y[L.ball_base(j)] for j in range(z)]))
    y[cb + L.C_SPEED] = omega_c
    return y


def quasistatic_solution(inputs):
    """The project's Jones–Harris solution (solver.models.quasistatic) for ``inputs``
    (:class:`solver.inputs.Inputs`)."""
    return solve_operating_point(inputs.geometry, inputs.operating)


def initial_state_from_quasistatic(par, qs) -> np.ndarray:
    """Initial state (layout ``L``) from a :class:`QuasiStaticSolution`: ball centres (axial, radial
    at each ball azimuth), orbital speeds, attitude and angular velocity (inertial) per ball,
    inner-ring offset and tilt, cage centred at the mean ball plane turning at the mean orbital
    speed.

    The quasi-static model carries the gyroscopic moment by race friction under its race-control
    assumption; in the dynamic model the same moment needs traction slips that develop in the first
    fraction of a revolution.
    """
    z = int(par.ball_count)
    y = np.zeros(L.state_size(z))
    rb = L.ring_base(z)
    cb = L.cage_base(z)
    for j in range(z):
        b = L.ball_base(j)
        psi = float(qs.ball_azimuth[j])
        x, r = float(qs.ball_center[j, 0]), float(qs.ball_center[j, 1])
        pos = np.array([x, r * math.cos(psi), r * math.sin(psi)])
        y[b + L.B_POS : b + L.B_POS + 3] = pos
        y[b + L.B_VEL : b + L.B_VEL + 3] = np.cross([float(qs.orbital_speed[j]), 0.0, 0.0], pos)
        y[b + L.B_QUAT : b + L.B_QUAT + 4] = matrix_to_quaternion(
            ball_frame(psi, float(qs.attitude_angle[j]))
        )
        y[b + L.B_OMEGA : b + L.B_OMEGA + 3] = np.asarray(qs.ball_angular_velocity[j], dtype=float)
    y[rb + L.R_POS : rb + L.R_POS + 3] = np.asarray(qs.inner_ring_offset, dtype=float)
    y[rb + L.R_TILT : rb + L.R_TILT + 2] = np.asarray(qs.inner_ring_tilt, dtype=float)
    y[cb + L.C_POS] = float(np.mean(qs.ball_center[:, 0]))
    y[cb + L.C_SPEED] = float(qs.cage_speed)
    return y
