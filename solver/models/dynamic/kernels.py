"""Numba kernels of the dynamic model: contact laws and the right-hand side.

Units SI, vectors in inertial components unless stated. Frames (physics.md §2.1 and §2.6.3):

- inertial: x = bearing axis, gravity along -z, origin = outer-ring centre on the plane of the ball
  centres in the just-touching state;
- ring frame: attached to a ring, columns of ``ring_rot`` (3x3) are the ring axes in inertial
  components, so ``inertial = ring_origin + ring_rot @ ring_frame``;
- contact: ``n`` = unit vector from the ball centre towards the contact (outwards from the ball),
  ``t1`` = rolling direction (ring-frame e_theta), ``t2 = n x t1`` across the groove.

Every kernel reads the flat arrays described in :mod:`solver.models.dynamic.layout`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from solver.history import drive_at
from solver.physics.cage_contact import (
    LAND_KIN_SIZE,
    LAND_OUT_SIZE,
    LK_CAGE_SPEED,
    LK_OFFSET,
    LK_RING_SPEED,
    LK_VELOCITY,
    LO_FORCE,
    LO_RING_TORQUE,
    LO_TORQUE,
    PK_OMEGA,
    PK_POSITION,
    PK_VELOCITY,
    PO_FORCE,
    PO_MOMENT_BALL,
    PO_NORMAL_FORCE,
    PO_POINT,
    POCKET_KIN_SIZE,
    POCKET_OUT_SIZE,
    land_force,
    pocket_contact,
)
from solver.physics.drag import cage_drag_moment_from
from solver.physics.hertz_fast import equivalent_radii_fast
from solver.physics.hertz_race import race_coefficients, race_coefficients_direct
from solver.physics.lanes import exp_lanes, log_lanes
from solver.physics.rheology import ENTRAINMENT_FLOOR, film_and_rolling_lanes, film_law_constants
from solver.physics.traction import (
    CONTACT_SIZE,
    CT_CURVATURE,
    CT_LOAD,
    CT_NORMAL,
    CT_POINT,
    CT_ROLLING,
    CT_SEMI_MAJOR,
    CT_SEMI_MINOR,
    KIN_BALL_CENTRE,
    KIN_BALL_OMEGA,
    KIN_BALL_VELOCITY,
    KIN_RING_OMEGA,
    KIN_RING_POINT,
    KIN_RING_VELOCITY,
    KIN_SIZE,
    NODE_BATCH,
    NODE_BATCH_ROWS,
    TR_FORCE,
    TR_MOMENT_BALL,
    TR_MOMENT_POINT,
    TR_POWER_SLIDING,
    TR_POWER_SPIN,
    TRACTION_OUT_SIZE,
    damped_normal_force,
    ellipse_traction_into,
)

from .borrow import borrowed, borrowed_record
from .layout import (
    B_OMEGA,
    B_POS,
    B_QUAT,
    B_VEL,
    BALL_STRIDE,
    C_ANGLE,
    C_POS,
    C_SPEED,
    C_TILT,
    C_TILT_RATE,
    C_VEL,
    CAGE_SIZE,
    GUIDE_BALL,
    GUIDE_INNER_RING,
    GUIDE_OUTER_RING,
    K_ANGLE,
    K_AZIMUTH,
    K_DEFLECTION,
    K_ELASTIC,
    K_ENTRAIN,
    K_F_BALL,
    K_F_RING,
    K_FILM,
    K_LOAD,
    K_M_BALL,
    K_M_RING,
    K_NORMAL,
    K_PMAX,
    K_POINT,
    K_POWER_ROLLING,
    K_POWER_SLIDING,
    K_POWER_SPIN,
    K_ROLL,
    K_RX,
    K_RY,
    K_SEMI_MAJOR,
    K_SEMI_MINOR,
    K_SLIDE,
    K_SPIN,
    R_PHI_INNER,
    R_PHI_OUTER,
    R_POS,
    R_TILT,
    R_TILT_RATE,
    R_VEL,
    RING_SIZE,
    TILT_FREE,
    TILT_TURNING_WITH_RING,
)
from .unliteral import runtime_bool

# ---------------------------------------------------------------------------------------------
# small vector helpers (tuples: no heap allocation inside the loops)
# ---------------------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@njit(cache=True)
def rotation_from_vector(v0, v1, v2, out):
    """Rotation matrix of the rotation vector (v0, v1, v2) [rad] (Rodrigues), written into
    ``out``."""
    th = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    if th < 1e-300:
        for i in range(3):
            for k in range(3):
                out[i, k] = 1.0 if i == k else 0.0
        return
    k0, k1, k2 = v0 / th, v1 / th, v2 / th
    c = math.cos(th)
    s = math.sin(th)
    t = 1.0 - c
    out[0, 0] = c + k0 * k0 * t
    out[0, 1] = k0 * k1 * t - k2 * s
    out[0, 2] = k0 * k2 * t + k1 * s
    out[1, 0] = k1 * k0 * t + k2 * s
    out[1, 1] = c + k1 * k1 * t
    out[1, 2] = k1 * k2 * t - k0 * s
    out[2, 0] = k2 * k0 * t - k1 * s
    out[2, 1] = k2 * k1 * t + k0 * s
    out[2, 2] = c + k2 * k2 * t


@njit(cache=True)
def quaternion_to_matrix(w, x, y, z, out):
    """Rotation matrix (body -> inertial) of the quaternion [w, x, y, z] (normalised here)."""
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    out[0, 0] = 1.0 - 2.0 * (y * y + z * z)
    out[0, 1] = 2.0 * (x * y - w * z)
    out[0, 2] = 2.0 * (x * z + w * y)
    out[1, 0] = 2.0 * (x * y + w * z)
    out[1, 1] = 1.0 - 2.0 * (x * x + z * z)
    out[1, 2] = 2.0 * (y * z - w * x)
    out[2, 0] = 2.0 * (x * z - w * y)
    out[2, 1] = 2.0 * (y * z + w * x)
    out[2, 2] = 1.0 - 2.0 * (x * x + y * y)


@njit(cache=True, inline="always")
def _then_about_x(rot, c, s):
    """``rot`` <- ``rot`` R_x (R_x: rotation by the angle of cosine c, sine s about x), in place."""
    for i in range(3):
        r1, r2 = rot[i, 1], rot[i, 2]
        rot[i, 1] = c * r1 + s * r2
        rot[i, 2] = -s * r1 + c * r2


@njit(cache=True, inline="always")
def _about_x_then(rot, c, s):
    """``rot`` <- R_x ``rot`` (R_x as in ``_then_about_x``), in place."""
    for k in range(3):
        r1, r2 = rot[1, k], rot[2, k]
        rot[1, k] = c * r1 - s * r2
        rot[2, k] = s * r1 + c * r2


@njit(cache=True)
def ring_frame_arrays():
    """New arrays for :func:`ring_frames` to fill: (inner rotation (3, 3), inner origin, inner
    velocity, inner angular velocity, outer rotation (3, 3), outer angular velocity)."""
    return (
        np.empty((3, 3)),
        np.empty(3),
        np.empty(3),
        np.empty(3),
        np.empty((3, 3)),
        np.empty(3),
    )


@njit(cache=True)
def ring_frames(
    y, par, drive, inner_rot, inner_origin, inner_vel, inner_omega, outer_rot, outer_omega
):
    """Orientation, origin, velocity and angular velocity of both rings at state ``y`` under the
    imposed inputs ``drive`` (:class:`solver.history.Drive` at the state's time: ring speeds and
    the imposed tilt's rate).

    Inner ring: tilt vector ``g`` (small rotation about y, z) and spin angle ``phi``. Mode 0 (tilt
    fixed in space) and 2 (tilt DOF): R = R(g) R_x(phi); mode 1 (tilt turning with the ring):
    R = R_x(phi) R(g). The tilt rate adds to the angular velocity (small tilts): the state's under
    a free tilt, the imposed one otherwise (in the ring's frame in mode 1). Outer ring:
    R = R_x(phi_o) about the fixed axis. Writes only into the given arrays (no allocation).
    """
    z = int(par.ball_count)
    rb = BALL_STRIDE * z
    rotation_from_vector(0.0, y[rb + R_TILT], y[rb + R_TILT + 1], inner_rot)  # R(g) for now
    phi = y[rb + R_PHI_INNER]
    c, s = math.cos(phi), math.sin(phi)
    mode = par.tilt_mode
    wi = drive.inner_speed
    gy_rate, gz_rate = drive.tilt_rate_y, drive.tilt_rate_z
    if mode == TILT_TURNING_WITH_RING:
        _about_x_then(inner_rot, c, s)
        inner_omega[0] = wi
        inner_omega[1] = c * gy_rate - s * gz_rate
        inner_omega[2] = s * gy_rate + c * gz_rate
    else:
        for i in range(3):  # first column of R(g) = first column of R(g) R_x
            inner_omega[i] = wi * inner_rot[i, 0]
        _then_about_x(inner_rot, c, s)
        if mode == TILT_FREE:
            gy_rate, gz_rate = y[rb + R_TILT_RATE], y[rb + R_TILT_RATE + 1]
        inner_omega[1] += gy_rate
        inner_omega[2] += gz_rate
    for i in range(3):
        inner_origin[i] = y[rb + R_POS + i]
        inner_vel[i] = y[rb + R_VEL + i]
    rotation_from_vector(y[rb + R_PHI_OUTER], 0.0, 0.0, outer_rot)
    outer_omega[0] = drive.outer_speed
    outer_omega[1] = 0.0
    outer_omega[2] = 0.0


# ---------------------------------------------------------------------------------------------
# ball-race contact (physics.md §2.6.3-2.6.6): geometry, Hertz, kinematics, traction helpers,
# inlined into contact_state
# ---------------------------------------------------------------------------------------------

#: scratch space of one traction, pocket or land evaluation: the input/output arrays of the
#: kernels of solver.physics.traction (with the traction's node batch) and
#: solver.physics.cage_contact
_BATCH_AT = CONTACT_SIZE + KIN_SIZE + TRACTION_OUT_SIZE
TRACTION_WORK_SIZE = max(
    _BATCH_AT + NODE_BATCH_ROWS * NODE_BATCH,
    POCKET_KIN_SIZE + POCKET_OUT_SIZE,
    LAND_KIN_SIZE + LAND_OUT_SIZE,
)


@njit(cache=True, inline="always")
def _groove(par, is_inner):
    """(curvature-centre axial position, circle radius, groove radius, conformity, hand sign)."""
    if is_inner:
        return (
            par.inner_centre_axial,
            par.inner_centre_radius,
            par.inner_groove_radius,
            par.inner_conformity,
            -1.0,
        )
    return (
        par.outer_centre_axial,
        par.outer_centre_radius,
        par.outer_groove_radius,
        par.outer_conformity,
        1.0,
    )


@njit(cache=True, inline="always")
def _to_inertial(R, x, y, z):
    """Ring-frame components (x, y, z) to inertial components (rotation only)."""
    return (
        R[0, 0] * x + R[0, 1] * y + R[0, 2] * z,
        R[1, 0] * x + R[1, 1] * y + R[1, 2] * z,
        R[2, 0] * x + R[2, 1] * y + R[2, 2] * z,
    )


@njit(cache=True, inline="always")
def _contact_geometry(pb, R, o, xc, rc, rg, rball, sgn):
    """Contact geometry of a ball with centre ``pb`` (inertial) in a groove of the ring with
    orientation ``R`` and origin ``o``.

    Returns (delta [m], the arguments (y, x) of atan2 for the contact angle alpha and for the
    ring-frame azimuth of the ball phi (4), ring-frame contact point (3), inertial normal n (3),
    inertial contact point P (3), inertial groove centre (3), rolling direction t1 (3),
    (cos phi, sin phi), (cos alpha, sin alpha)). The normal points from the groove centre through
    the ball centre to the contact. The angles themselves are left to the caller: only the
    observed evaluations record them."""
    dx, dy, dz = pb[0] - o[0], pb[1] - o[1], pb[2] - o[2]
    # ball centre in ring-frame components
    cx = R[0, 0] * dx + R[1, 0] * dy + R[2, 0] * dz
    cy = R[0, 1] * dx + R[1, 1] * dy + R[2, 1] * dz
    cz = R[0, 2] * dx + R[1, 2] * dy + R[2, 2] * dz
    inv_rho = 1.0 / math.sqrt(cy * cy + cz * cz)
    cph, sph = cy * inv_rho, cz * inv_rho
    # groove curvature centre at that azimuth, and the contact normal
    gx, gy, gz = xc, rc * cph, rc * sph
    ex, ey, ez = cx - gx, cy - gy, cz - gz
    length = math.sqrt(ex * ex + ey * ey + ez * ez)
    nx, ny, nz = ex / length, ey / length, ez / length
    delta = length - (rg - rball)
    n_rho = ny * cph + nz * sph
    # cos and sin of alpha without evaluating them: n lies in the meridional plane (e_x, e_rho)
    inv_r = 1.0 / math.sqrt(nx * nx + n_rho * n_rho)
    ca, sa = sgn * n_rho * inv_r, sgn * nx * inv_r
    reach = rg + 0.5 * max(delta, 0.0)
    prx, pry, prz = gx + reach * nx, gy + reach * ny, gz + reach * nz
    ni = _to_inertial(R, nx, ny, nz)
    pi_ = _to_inertial(R, prx, pry, prz)
    gi = _to_inertial(R, gx, gy, gz)
    # rolling direction t1 = ring-frame e_theta
    t1 = _to_inertial(R, 0.0, -sph, cph)
    return (
        delta,
        (sgn * nx, sgn * n_rho, cz, cy),
        (prx, pry, prz),
        ni,
        (o[0] + pi_[0], o[1] + pi_[1], o[2] + pi_[2]),
        (o[0] + gi[0], o[1] + gi[1], o[2] + gi[2]),
        t1,
        (cph, sph),
        (ca, sa),
    )


@njit(cache=True, inline="always")
def _hertz(dball, conf, cos_alpha, dm, is_inner, eprime, table):
    """(R_x, R_y [m], kappa, K [N/m^1.5], A, B [m^(2/3)], film ellipticity factor, rolling
    ellipticity logarithm) of a ball-groove contact at contact angle cosine ``cos_alpha``: one
    look-up in the race's table of solver.physics.hertz_race (semi-axes a = A (Q/E')^(1/3),
    b = B (Q/E')^(1/3)), its closed forms outside the table."""
    gamma = dball * cos_alpha / dm
    rx, ry = equivalent_radii_fast(dball, conf, gamma, is_inner)
    kappa, s, ca, cb, film_k, rolling_k = race_coefficients(table, cos_alpha)
    if not s == s:
        kappa, s, ca, cb, film_k, rolling_k = race_coefficients_direct(dball, conf, gamma, is_inner)
    return rx, ry, kappa, s * eprime, ca, cb, film_k, rolling_k


@njit(cache=True, inline="always")
def _contact_kinematics(pb, vb, wb, o, vr, wr, p, n, trig_alpha, trig_phi, R, sgn):
    """Surface kinematics at the contact point ``p`` with normal ``n`` (inertial); ``trig_alpha``
    and ``trig_phi`` are (cos, sin) of the contact angle and of the ball's ring-frame azimuth.

    Returns (sliding speed at P [m/s], spin [rad/s], rolling [rad/s], entrainment speed [m/s],
    roll axis (3, inertial)).
    Spin: component of ball-minus-ring angular velocity along the contact normal (sign by race
    hand); rolling: along the roll axis cos(alpha) e_x - sin(alpha) e_r (ring frame); entrainment:
    half the sum of the surface speeds relative to the contact, which orbits with the ball."""
    rbx, rby, rbz = p[0] - pb[0], p[1] - pb[1], p[2] - pb[2]
    a0, a1, a2 = _cross(wb[0], wb[1], wb[2], rbx, rby, rbz)
    vsbx, vsby, vsbz = vb[0] + a0, vb[1] + a1, vb[2] + a2  # ball surface
    a0, a1, a2 = _cross(wr[0], wr[1], wr[2], p[0] - o[0], p[1] - o[1], p[2] - o[2])
    vsrx, vsry, vsrz = vr[0] + a0, vr[1] + a1, vr[2] + a2  # ring surface
    dvx, dvy, dvz = vsbx - vsrx, vsby - vsry, vsbz - vsrz
    dvn = dvx * n[0] + dvy * n[1] + dvz * n[2]
    slide = math.sqrt(max((dvx * dvx + dvy * dvy + dvz * dvz) - dvn * dvn, 0.0))
    omx, omy, omz = wb[0] - wr[0], wb[1] - wr[1], wb[2] - wr[2]
    spin = sgn * (omx * n[0] + omy * n[1] + omz * n[2])
    ca, sa = trig_alpha
    cph, sph = trig_phi
    mix, miy, miz = _to_inertial(R, ca, -sa * cph, -sa * sph)
    roll = omx * mix + omy * miy + omz * miz
    rr2 = pb[1] * pb[1] + pb[2] * pb[2]
    orbit = (pb[1] * vb[2] - pb[2] * vb[1]) / rr2 if rr2 > 0.0 else 0.0
    a0, a1, a2 = _cross(orbit, 0.0, 0.0, rbx, rby, rbz)
    vpx, vpy, vpz = vb[0] + a0, vb[1] + a1, vb[2] + a2
    sx = vsbx + vsrx - 2.0 * vpx
    sy = vsby + vsry - 2.0 * vpy
    sz = vsbz + vsrz - 2.0 * vpz
    sn = sx * n[0] + sy * n[1] + sz * n[2]
    entrain = 0.5 * math.sqrt(max(sx * sx + sy * sy + sz * sz - sn * sn, 0.0))
    return slide, spin, roll, entrain, (mix, miy, miz)


@njit(cache=True, inline="always")
def _approach_rate(vb, o, vr, wr, g, n):
    """Rate of approach [m/s] (> 0 closing): ball-centre velocity relative to the ring-fixed groove
    centre point ``g``, along the normal."""
    a0, a1, a2 = _cross(wr[0], wr[1], wr[2], g[0] - o[0], g[1] - o[1], g[2] - o[2])
    return (vb[0] - vr[0] - a0) * n[0] + (vb[1] - vr[1] - a1) * n[1] + (vb[2] - vr[2] - a2) * n[2]


@njit(cache=True, inline="always")
def _traction(par, quad, work, p, n, t1, a, b, q, curvature, film, transit, pb, vb, wb, o, vr, wr):
    """Ellipse-integrated traction (solver.physics.traction.ellipse_traction_into, local law
    ``par.traction_law``, node batch in ``work``) on the ball: returns the output array (force on
    the ball, moments about the ball centre and about P, powers)."""
    ct = work[:CONTACT_SIZE]
    kin = work[CONTACT_SIZE : CONTACT_SIZE + KIN_SIZE]
    tout = work[CONTACT_SIZE + KIN_SIZE : _BATCH_AT]
    batch = work[_BATCH_AT : _BATCH_AT + NODE_BATCH_ROWS * NODE_BATCH].reshape(
        (NODE_BATCH_ROWS, NODE_BATCH)
    )
    for i in range(3):
        ct[CT_POINT + i] = p[i]
        ct[CT_NORMAL + i] = n[i]
        ct[CT_ROLLING + i] = t1[i]
        kin[KIN_BALL_CENTRE + i] = pb[i]
        kin[KIN_BALL_VELOCITY + i] = vb[i]
        kin[KIN_BALL_OMEGA + i] = wb[i]
        kin[KIN_RING_POINT + i] = o[i]
        kin[KIN_RING_VELOCITY + i] = vr[i]
        kin[KIN_RING_OMEGA + i] = wr[i]
    ct[CT_SEMI_MAJOR] = a
    ct[CT_SEMI_MINOR] = b
    ct[CT_LOAD] = q
    ct[CT_CURVATURE] = curvature
    ellipse_traction_into(
        ct,
        kin,
        par.traction_law,
        par.traction_curve,
        par.rheology,
        film,
        transit,
        par.slip_regularisation,
        quad,
        tout,
        batch,
    )
    return tout


# Per-contact values between the passes of the right-hand side (:func:`contact_state`,
# :func:`contact_films`, :func:`contact_forces`): rows of the stash array (``CS_SIZE``, columns),
# one column per ball-race contact (column ``race * Z + ball``, race 0 inner, 1 outer), the
# columns padded to a multiple of ``CS_LANES`` (:func:`stash_columns`) so that the film pass runs
# in whole vectors.
CS_ENTRAIN = 0  # entrainment speed [m/s]
CS_SLIDE_TO_ROLL = 1  # sliding / entrainment speed
CS_LOAD = 2  # normal load Q [N]
CS_RX = 3  # R_x [m]
CS_FILM_FACTOR = 4  # the film's ellipticity factor (race table)
CS_ROLLING_LOG = 5  # the rolling force's ellipticity logarithm (race table)
CS_PMAX = 6  # peak pressure [Pa]
CS_SEMI_MINOR = 7  # b [m]
CS_FILM = 8  # central film h_c [m] (output of the film pass)
CS_ROLLING_FORCE = 9  # rolling resistance force [N] (output of the film pass)
CS_POINT = 10  # contact point P, inertial (3) [m]
CS_ROLLING_DIR = 13  # rolling direction t1, inertial (3)
CS_ROLL_AXIS = 16  # roll axis, inertial (3)
CS_LOADED = 19  # 1.0 where the contact carries a load, else 0.0
CS_SIZE = 20
CS_LANES = 8


@njit(cache=True)
def stash_columns(ball_count):
    """Columns of the stash array for ``ball_count`` balls: 2 Z rounded up to ``CS_LANES``."""
    return (2 * ball_count + CS_LANES - 1) // CS_LANES * CS_LANES


@njit(cache=True, inline="always")
def contact_state(
    y,
    jb,
    ring_rot,
    ring_origin,
    ring_vel,
    ring_omega,
    is_inner,
    par,
    table,
    rec,
    stash,
    col,
    observed,
):
    """First pass of a ball-race contact (ball at state offset ``jb``, one ring): geometry,
    kinematics, Hertz load and ellipse into ``rec`` (layout K_*, forces zero), and what the film
    pass and :func:`contact_forces` need into column ``col`` of ``stash`` (CS_* rows).

    ``table``: the race's Hertz table (``par.inner_hertz`` or ``par.outer_hertz``, of
    solver.physics.hertz_race). ``observed`` False (the integrator's evaluations): ``rec`` gets
    only what the forces and the integrator's checks need; the contact angle, raceway azimuth and
    elastic load are NaN there. An unloaded contact's column holds neutral inputs for the film
    pass (unit speed, load and radius) and ``CS_LOADED`` 0.
    """
    dball = par.ball_diameter
    xc, rc, rg, conf, sgn = _groove(par, is_inner)
    pb = (y[jb + B_POS], y[jb + B_POS + 1], y[jb + B_POS + 2])
    vb = (y[jb + B_VEL], y[jb + B_VEL + 1], y[jb + B_VEL + 2])
    wb = (y[jb + B_OMEGA], y[jb + B_OMEGA + 1], y[jb + B_OMEGA + 2])
    o = (ring_origin[0], ring_origin[1], ring_origin[2])
    vr = (ring_vel[0], ring_vel[1], ring_vel[2])
    wr = (ring_omega[0], ring_omega[1], ring_omega[2])
    delta, angle_args, pr, n, p, g, t1, trig_phi, trig_alpha = _contact_geometry(
        pb, ring_rot, o, xc, rc, rg, 0.5 * dball, sgn
    )
    slide, spin, roll, entrain, axis = _contact_kinematics(
        pb, vb, wb, o, vr, wr, p, n, trig_alpha, trig_phi, ring_rot, sgn
    )
    eprime = par.eprime
    rx, ry, _, kh, coef_a, coef_b, film_k, rolling_k = _hertz(
        dball, conf, trig_alpha[0], par.pitch_diameter, is_inner, eprime, table
    )
    for i in range(K_F_BALL, K_M_RING + 3):
        rec[i] = 0.0
    rec[K_DEFLECTION] = delta
    if observed:
        rec[K_ANGLE] = math.atan2(angle_args[0], angle_args[1])
        # the contact point lies in the ball centre's meridional plane
        rec[K_AZIMUTH] = math.atan2(angle_args[2], angle_args[3])
    else:
        rec[K_ANGLE] = math.nan
        rec[K_AZIMUTH] = math.nan
    for i in range(3):
        rec[K_POINT + i] = pr[i]
        rec[K_NORMAL + i] = n[i]
        stash[CS_POINT + i, col] = p[i]
        stash[CS_ROLLING_DIR + i, col] = t1[i]
        stash[CS_ROLL_AXIS + i, col] = axis[i]
    rec[K_SPIN] = spin
    rec[K_ROLL] = roll
    rec[K_SLIDE] = slide
    rec[K_ENTRAIN] = entrain
    rec[K_RX] = rx
    rec[K_RY] = ry
    rec[K_LOAD] = 0.0
    rec[K_ELASTIC] = 0.0
    rec[K_FILM] = 0.0
    rec[K_POWER_ROLLING] = 0.0
    rec[K_POWER_SLIDING] = 0.0
    rec[K_POWER_SPIN] = 0.0
    rec[K_SEMI_MAJOR] = 0.0
    rec[K_SEMI_MINOR] = 0.0
    rec[K_PMAX] = 0.0
    stash[CS_LOADED, col] = 0.0
    stash[CS_ENTRAIN, col] = 1.0
    stash[CS_SLIDE_TO_ROLL, col] = 0.0
    stash[CS_LOAD, col] = 1.0
    stash[CS_RX, col] = 1.0
    stash[CS_FILM_FACTOR, col] = 1.0
    stash[CS_ROLLING_LOG, col] = 0.0
    stash[CS_PMAX, col] = 0.0
    stash[CS_SEMI_MINOR, col] = 0.0
    if delta <= 0.0:
        return
    # damped Hertz law of solver.physics.traction.damped_normal_force: c = 2 zeta sqrt(1.5 K
    # delta^0.5 m_ball), vanishing like delta^(1/4) at contact onset, never pulling
    ddelta = _approach_rate(vb, o, vr, wr, g, n)
    q = damped_normal_force(delta, ddelta, kh, par.damping_ratio, par.ball_mass)
    rec[K_LOAD] = q
    rec[K_ELASTIC] = kh * delta**1.5 if observed else math.nan
    if not q > 0.0:  # unloaded, or NaN from a non-finite state (kept in rec for the integrator)
        return
    q13 = np.cbrt(q / eprime)
    sa_ = coef_a * q13
    sb_ = coef_b * q13
    pmax = 1.5 * q / (math.pi * sa_ * sb_)
    rec[K_SEMI_MAJOR] = sa_
    rec[K_SEMI_MINOR] = sb_
    rec[K_PMAX] = pmax
    stash[CS_LOADED, col] = 1.0
    stash[CS_ENTRAIN, col] = entrain
    stash[CS_SLIDE_TO_ROLL, col] = slide / max(entrain, ENTRAINMENT_FLOOR)
    stash[CS_LOAD, col] = q
    stash[CS_RX, col] = rx
    stash[CS_FILM_FACTOR, col] = film_k
    stash[CS_ROLLING_LOG, col] = rolling_k
    stash[CS_PMAX, col] = pmax
    stash[CS_SEMI_MINOR, col] = sb_


@njit(cache=True, error_model="numpy")
def contact_films(par, stash, columns):
    """Film pass over the first ``columns`` columns of ``stash`` (a multiple of ``CS_LANES``; one
    loop over the contacts that LLVM vectorises): central film and rolling resistance force of
    each contact, CS_FILM and CS_ROLLING_FORCE. Hamrock-Dowson film and hydrodynamic inlet force
    at the inlet viscosity, both reduced for inlet shear heating
    (solver.physics.rheology.film_and_rolling_lanes, with the ellipticity terms of the race
    table), plus the elastic hysteresis force F_h = 3/16 alpha_h Q b / R_x (physics.md
    §2.6.5). Not inlined into the right-hand side: compiled on its own, it adds less compile
    time to the model's largest kernel; numpy's error model: no test before each division.

    Below the entrainment speed u_min (solver.physics.rheology.ENTRAINMENT_FLOOR) the film is
    that of u_min (the traction law reads it, with the transit time b / u_min:
    :func:`contact_forces`), and the inlet force that of u_min times (u_e / u_min)^0.66, its own
    speed law, so that the rolling resistance still vanishes with the entrainment."""
    eprime = par.eprime
    constants = film_law_constants(par.rheology, eprime)
    hysteresis = 0.1875 * par.hysteresis
    for col in range(columns):
        load = stash[CS_LOAD, col]
        rx = stash[CS_RX, col]
        entrain = stash[CS_ENTRAIN, col]
        floored = ENTRAINMENT_FLOOR > entrain  # a selection, not max(): the loop vectorises
        speed = ENTRAINMENT_FLOOR if floored else entrain
        film, _, f_ehl = film_and_rolling_lanes(
            speed,
            stash[CS_SLIDE_TO_ROLL, col],
            load,
            rx,
            stash[CS_FILM_FACTOR, col],
            stash[CS_ROLLING_LOG, col],
            stash[CS_PMAX, col],
            eprime,
            constants,
        )
        below = exp_lanes(0.66 * log_lanes(entrain / ENTRAINMENT_FLOOR))
        f_ehl = f_ehl * below if floored else f_ehl
        stash[CS_FILM, col] = film
        stash[CS_ROLLING_FORCE, col] = f_ehl + hysteresis * load * stash[CS_SEMI_MINOR, col] / rx


@njit(cache=True, inline="always")
def contact_forces(
    y, jb, ring_origin, ring_vel, ring_omega, is_inner, par, quad, rec, work, stash, col
):
    """Last pass of a loaded ball-race contact (after :func:`contact_state` and
    :func:`contact_films`): normal force, traction integrated over the ellipse, rolling
    resistance; forces and moments on ball and ring, film and powers into ``rec``. The traction
    law takes the film's transit time b / max(u_e, u_min) (u_min:
    solver.physics.rheology.ENTRAINMENT_FLOOR; :func:`contact_films`).

    ``quad``: node table of :func:`solver.physics.traction.ellipse_quadrature`; ``work``:
    scratch array of length ``TRACTION_WORK_SIZE``."""
    if stash[CS_LOADED, col] == 0.0:
        return
    dball = par.ball_diameter
    rg = par.inner_groove_radius if is_inner else par.outer_groove_radius
    pb = (y[jb + B_POS], y[jb + B_POS + 1], y[jb + B_POS + 2])
    vb = (y[jb + B_VEL], y[jb + B_VEL + 1], y[jb + B_VEL + 2])
    wb = (y[jb + B_OMEGA], y[jb + B_OMEGA + 1], y[jb + B_OMEGA + 2])
    o = (ring_origin[0], ring_origin[1], ring_origin[2])
    vr = (ring_vel[0], ring_vel[1], ring_vel[2])
    wr = (ring_omega[0], ring_omega[1], ring_omega[2])
    n = (rec[K_NORMAL], rec[K_NORMAL + 1], rec[K_NORMAL + 2])
    p = (stash[CS_POINT, col], stash[CS_POINT + 1, col], stash[CS_POINT + 2, col])
    t1 = (
        stash[CS_ROLLING_DIR, col],
        stash[CS_ROLLING_DIR + 1, col],
        stash[CS_ROLLING_DIR + 2, col],
    )
    axis = (stash[CS_ROLL_AXIS, col], stash[CS_ROLL_AXIS + 1, col], stash[CS_ROLL_AXIS + 2, col])
    q = rec[K_LOAD]
    sa_ = rec[K_SEMI_MAJOR]
    sb_ = rec[K_SEMI_MINOR]
    entrain = rec[K_ENTRAIN]
    roll = rec[K_ROLL]
    film = stash[CS_FILM, col]
    fr = stash[CS_ROLLING_FORCE, col]
    # below the entrainment floor the traction reads the film of u_min (contact_films); the film
    # reported is the Hamrock-Dowson film of the contact's own speed, h_c(u_min) (u_e / u_min)^0.67
    rec[K_FILM] = (
        film if entrain >= ENTRAINMENT_FLOOR else film * (entrain / ENTRAINMENT_FLOOR) ** 0.67
    )
    # normal force: -Q n on the ball (through its centre), +Q n on the ring at the contact point
    fbx, fby, fbz = -q * n[0], -q * n[1], -q * n[2]
    mbx = mby = mbz = 0.0
    frx, fry, frz = -fbx, -fby, -fbz
    lx, ly, lz = p[0] - o[0], p[1] - o[1], p[2] - o[2]
    mrx_, mry_, mrz_ = _cross(lx, ly, lz, frx, fry, frz)
    if par.traction:
        curvature = (2.0 * rg + dball) / (2.0 * rg * dball) if par.heathcote else 0.0
        transit = sb_ / max(entrain, ENTRAINMENT_FLOOR)
        tout = _traction(
            par, quad, work, p, n, t1, sa_, sb_, q, curvature, film, transit, pb, vb, wb, o, vr, wr
        )
        rec[K_POWER_SLIDING] = tout[TR_POWER_SLIDING]
        rec[K_POWER_SPIN] = tout[TR_POWER_SPIN]
        tfx, tfy, tfz = tout[TR_FORCE], tout[TR_FORCE + 1], tout[TR_FORCE + 2]
        fbx += tfx
        fby += tfy
        fbz += tfz
        mbx += tout[TR_MOMENT_BALL]
        mby += tout[TR_MOMENT_BALL + 1]
        mbz += tout[TR_MOMENT_BALL + 2]
        frx -= tfx
        fry -= tfy
        frz -= tfz
        # moment on the ring about its centre: -((P - c_r) x F + M_P)
        a0, a1, a2 = _cross(lx, ly, lz, tfx, tfy, tfz)
        mrx_ -= a0 + tout[TR_MOMENT_POINT]
        mry_ -= a1 + tout[TR_MOMENT_POINT + 1]
        mrz_ -= a2 + tout[TR_MOMENT_POINT + 2]
        # rolling resistance: a moment pair M = F_R D/2 about the roll axis, against the relative
        # rolling of ball and ring (the pressure centre shifted into the inlet)
        # against the rolling, smoothed below the regularisation speed (no moment without rolling)
        lever = 0.5 * dball
        direction = roll / (abs(roll) + par.slip_regularisation / lever)
        mr = -fr * lever * direction
        mbx += mr * axis[0]
        mby += mr * axis[1]
        mbz += mr * axis[2]
        mrx_ -= mr * axis[0]
        mry_ -= mr * axis[1]
        mrz_ -= mr * axis[2]
        rec[K_POWER_ROLLING] = fr * lever * direction * roll
    rec[K_F_BALL] = fbx
    rec[K_F_BALL + 1] = fby
    rec[K_F_BALL + 2] = fbz
    rec[K_M_BALL] = mbx
    rec[K_M_BALL + 1] = mby
    rec[K_M_BALL + 2] = mbz
    rec[K_F_RING] = frx
    rec[K_F_RING + 1] = fry
    rec[K_F_RING + 2] = frz
    rec[K_M_RING] = mrx_
    rec[K_M_RING + 1] = mry_
    rec[K_M_RING + 2] = mrz_


# ---------------------------------------------------------------------------------------------
# cage (physics.md §2.6.7)
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def cage_frame(y, cb, rot, omega):
    """Cage orientation ``rot`` = R(tilt) R_x(angle) (cage axes in inertial components) and angular
    velocity ``omega`` = speed * (R(tilt) e_x) + tilt rates (small-tilt kinematics), inertial.
    Writes only into the given arrays (no allocation)."""
    rotation_from_vector(0.0, y[cb + C_TILT], y[cb + C_TILT + 1], rot)  # R(tilt) for now
    wc = y[cb + C_SPEED]
    omega[0] = wc * rot[0, 0]
    omega[1] = wc * rot[1, 0] + y[cb + C_TILT_RATE]
    omega[2] = wc * rot[2, 0] + y[cb + C_TILT_RATE + 1]
    angle = y[cb + C_ANGLE]
    _then_about_x(rot, math.cos(angle), math.sin(angle))


@njit(cache=True, inline="always")
def cage_pocket(y, jb, cb, j, par, cage_rot, cage_omega, work, out):
    """Ball ``j`` against its cage pocket through the kernel of solver.physics.cage_contact.

    Pocket frame (x, r, theta): the cage axes ``cage_rot`` turned by the pocket angle 2 pi j / Z
    about the cage axis; pocket centre at the pocket radius along r. ``cage_omega``: cage angular
    velocity (inertial). ``work``: scratch of length ``POCKET_KIN_SIZE + POCKET_OUT_SIZE``.
    ``out`` (12, inertial): force on the ball (3), moment on the ball about its centre (3), force on
    the cage (3), moment on the cage about its centre (3). Returns the normal force [N] (>= 0).
    """
    for i in range(12):
        out[i] = 0.0
    z = int(par.ball_count)
    psi = 2.0 * math.pi * j / z
    cp, sp = math.cos(psi), math.sin(psi)
    R = cage_rot
    # pocket axes in inertial components
    exx, exy, exz = R[0, 0], R[1, 0], R[2, 0]
    erx = R[0, 1] * cp + R[0, 2] * sp
    ery = R[1, 1] * cp + R[1, 2] * sp
    erz = R[2, 1] * cp + R[2, 2] * sp
    etx = -R[0, 1] * sp + R[0, 2] * cp
    ety = -R[1, 1] * sp + R[1, 2] * cp
    etz = -R[2, 1] * sp + R[2, 2] * cp
    rp = par.pocket_radius
    ccx, ccy, ccz = y[cb + C_POS], y[cb + C_POS + 1], y[cb + C_POS + 2]
    wcx, wcy, wcz = cage_omega[0], cage_omega[1], cage_omega[2]
    pbx, pby, pbz = y[jb + B_POS], y[jb + B_POS + 1], y[jb + B_POS + 2]
    # ball centre relative to the pocket centre, and its rate seen from the cage
    dx = pbx - ccx - rp * erx
    dy = pby - ccy - rp * ery
    dz = pbz - ccz - rp * erz
    a0, a1, a2 = _cross(wcx, wcy, wcz, pbx - ccx, pby - ccy, pbz - ccz)
    vx = y[jb + B_VEL] - y[cb + C_VEL] - a0
    vy = y[jb + B_VEL + 1] - y[cb + C_VEL + 1] - a1
    vz = y[jb + B_VEL + 2] - y[cb + C_VEL + 2] - a2
    wx = y[jb + B_OMEGA] - wcx
    wy = y[jb + B_OMEGA + 1] - wcy
    wz = y[jb + B_OMEGA + 2] - wcz
    kin = work[:POCKET_KIN_SIZE]
    res = work[POCKET_KIN_SIZE : POCKET_KIN_SIZE + POCKET_OUT_SIZE]
    kin[PK_POSITION] = dx * exx + dy * exy + dz * exz
    kin[PK_POSITION + 1] = dx * erx + dy * ery + dz * erz
    kin[PK_POSITION + 2] = dx * etx + dy * ety + dz * etz
    kin[PK_VELOCITY] = vx * exx + vy * exy + vz * exz
    kin[PK_VELOCITY + 1] = vx * erx + vy * ery + vz * erz
    kin[PK_VELOCITY + 2] = vx * etx + vy * ety + vz * etz
    kin[PK_OMEGA] = wx * exx + wy * exy + wz * exz
    kin[PK_OMEGA + 1] = wx * erx + wy * ery + wz * erz
    kin[PK_OMEGA + 2] = wx * etx + wy * ety + wz * etz
    pocket_contact(kin, par.pocket, res)
    fn = res[PO_NORMAL_FORCE]
    if fn <= 0.0:
        return 0.0
    f0, f1, f2 = res[PO_FORCE], res[PO_FORCE + 1], res[PO_FORCE + 2]
    fx = f0 * exx + f1 * erx + f2 * etx
    fy = f0 * exy + f1 * ery + f2 * ety
    fz = f0 * exz + f1 * erz + f2 * etz
    m0, m1, m2 = res[PO_MOMENT_BALL], res[PO_MOMENT_BALL + 1], res[PO_MOMENT_BALL + 2]
    out[0], out[1], out[2] = fx, fy, fz
    out[3] = m0 * exx + m1 * erx + m2 * etx
    out[4] = m0 * exy + m1 * ery + m2 * ety
    out[5] = m0 * exz + m1 * erz + m2 * etz
    out[6], out[7], out[8] = -fx, -fy, -fz
    # contact point relative to the cage centre (pocket centre + PO_POINT), inertial
    q0, q1, q2 = res[PO_POINT], res[PO_POINT + 1] + rp, res[PO_POINT + 2]
    lx = q0 * exx + q1 * erx + q2 * etx
    ly = q0 * exy + q1 * ery + q2 * ety
    lz = q0 * exz + q1 * erz + q2 * etz
    c0, c1, c2 = _cross(lx, ly, lz, -fx, -fy, -fz)
    out[9], out[10], out[11] = c0, c1, c2
    return fn


@njit(cache=True)
def cage_land(y, cb, ring_origin, ring_vel, inner_speed, outer_speed, par, work, out):
    """Guiding-land force on the cage through solver.physics.cage_contact.land_force; the rings
    turn at ``inner_speed`` and ``outer_speed`` [rad/s].

    ``out`` (5): force on the cage (3; x = 0), moment on the cage about x (1), and the moment
    about x on the guiding ring about its centre (1; the ring also receives minus the force).
    Ball-guided cages: zeros.
    Outer-ring guidance: the land is on the outer ring (centre at the origin, speed omega_o);
    inner-ring guidance: on the inner ring (its centre and velocity, speed omega_i).
    """
    for i in range(5):
        out[i] = 0.0
    guide = par.guidance
    if guide == GUIDE_BALL:
        return
    kin = work[:LAND_KIN_SIZE]
    res = work[LAND_KIN_SIZE : LAND_KIN_SIZE + LAND_OUT_SIZE]
    if guide == GUIDE_OUTER_RING:
        kin[LK_OFFSET] = y[cb + C_POS + 1]
        kin[LK_OFFSET + 1] = y[cb + C_POS + 2]
        kin[LK_VELOCITY] = y[cb + C_VEL + 1]
        kin[LK_VELOCITY + 1] = y[cb + C_VEL + 2]
        kin[LK_RING_SPEED] = outer_speed
    else:
        kin[LK_OFFSET] = y[cb + C_POS + 1] - ring_origin[1]
        kin[LK_OFFSET + 1] = y[cb + C_POS + 2] - ring_origin[2]
        kin[LK_VELOCITY] = y[cb + C_VEL + 1] - ring_vel[1]
        kin[LK_VELOCITY + 1] = y[cb + C_VEL + 2] - ring_vel[2]
        kin[LK_RING_SPEED] = inner_speed
    kin[LK_CAGE_SPEED] = y[cb + C_SPEED]
    land_force(kin, par.land, res)
    out[1] = res[LO_FORCE]
    out[2] = res[LO_FORCE + 1]
    out[3] = res[LO_TORQUE]
    out[4] = res[LO_RING_TORQUE]


# ---------------------------------------------------------------------------------------------
# ball drag in the oil-air mixture (physics.md §2.6.5)
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def ball_drag(y, jb, par):
    """Drag of the oil-air mixture on ball (state offset ``jb``), the mixture taken at rest in the
    housing [E]: force -1/2 C_D rho |v| v (pi D^2 / 4) on the centre velocity v, C_D of a sphere
    (Schiller-Naumann below Re = 1000, 0.44 above), and the viscous moment -8 pi eta R^3 omega
    of a sphere turning in the mixture (Stokes) [M]. Returns (force (3), moment (3), power >= 0
    [W]); zeros when traction (lubrication) is off."""
    if not par.traction:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 0.0
    vx, vy, vz = y[jb + B_VEL], y[jb + B_VEL + 1], y[jb + B_VEL + 2]
    wx, wy, wz = y[jb + B_OMEGA], y[jb + B_OMEGA + 1], y[jb + B_OMEGA + 2]
    d = par.ball_diameter
    rho = par.mixture_density
    eta = par.mixture_viscosity
    v = math.sqrt(vx * vx + vy * vy + vz * vz)
    re = rho * v * d / eta
    cd = 0.44
    if re < 1000.0:
        cd = 24.0 / max(re, 1e-12) * (1.0 + 0.15 * re**0.687)
    c = -0.5 * cd * rho * v * 0.25 * math.pi * d * d
    cm = -8.0 * math.pi * eta * (0.5 * d) ** 3
    f = (c * vx, c * vy, c * vz)
    m = (cm * wx, cm * wy, cm * wz)
    power = -(c * v * v + cm * (wx * wx + wy * wy + wz * wz))
    return f, m, power


@njit(cache=True)
def cage_drag(y, cb, par):
    """Drag of the oil-air mixture on the cage (state offset ``cb``) about its own axis
    (solver.physics.drag: free-disc moment on its two side faces, mixture at rest in the housing
    as for the ball drag). Returns (moment [N m], power >= 0 [W]); zeros when traction
    (lubrication) is off."""
    if not par.traction:
        return 0.0, 0.0
    wc = y[cb + C_SPEED]
    m = cage_drag_moment_from(wc, par.cage_drag_laminar, par.cage_drag_turbulent)
    return m, -m * wc


# ---------------------------------------------------------------------------------------------
# post-step hook of the integrator
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def post_step(y, par, rec_inner, rec_outer):
    """Run after every accepted integrator step: renormalise the ball quaternions (projection onto
    the unit sphere) and check that every ball is still between the raceways. Returns False when a
    ball has left them: its centre is more than D/4 from the pitch circle, or a contact (records of
    the last right-hand-side evaluation) is compressed by more than 2 % of D, far beyond any
    realistic Hertz deflection."""
    z = par.ball_count
    d = par.ball_diameter
    rp = 0.5 * par.pitch_diameter
    ok = True
    for j in range(z):
        b = BALL_STRIDE * j + B_QUAT
        n = math.sqrt(y[b] ** 2 + y[b + 1] ** 2 + y[b + 2] ** 2 + y[b + 3] ** 2)
        for i in range(4):
            y[b + i] /= n
        b = BALL_STRIDE * j + B_POS
        r = math.sqrt(y[b + 1] ** 2 + y[b + 2] ** 2)
        if abs(r - rp) > 0.25 * d or abs(y[b]) > 0.25 * d:
            ok = False
        if rec_inner[j, K_DEFLECTION] > 0.02 * d or rec_outer[j, K_DEFLECTION] > 0.02 * d:
            ok = False
    return ok


# ---------------------------------------------------------------------------------------------
# right-hand side
# ---------------------------------------------------------------------------------------------


class RhsWork(NamedTuple):
    """Scratch arrays of one right-hand-side evaluation (:func:`rhs_into`), made once per
    run by :func:`rhs_work` (the stepper's workspace) so that the evaluations allocate nothing."""

    inner_rot: np.ndarray  # (3, 3) inner-ring axes, inertial components
    inner_origin: np.ndarray  # (3,) [m]
    inner_vel: np.ndarray  # (3,) [m/s]
    inner_omega: np.ndarray  # (3,) [rad/s]
    outer_rot: np.ndarray  # (3, 3)
    outer_omega: np.ndarray  # (3,) [rad/s]
    zero3: np.ndarray  # (3,) zeros: origin and velocity of the outer ring
    cage_rot: np.ndarray  # (3, 3)
    cage_omega: np.ndarray  # (3,) [rad/s]
    pocket: np.ndarray  # (12,) output of cage_pocket
    land: np.ndarray  # (5,) output of cage_land
    ring_speed: np.ndarray  # (2,) inner and outer ring speeds of the evaluation [rad/s]
    contact: np.ndarray  # (TRACTION_WORK_SIZE,) scratch of the contact kernels
    stash: np.ndarray  # (CS_SIZE, stash_columns(Z)) per-contact values between the passes
    ring_load: np.ndarray  # (6,) written: force [N] and moment about the ring centre [N m] of
    # the balls (and an inner-ring-guided cage's land) on the inner ring, inertial components


@njit(cache=True)
def rhs_work(ball_count):
    """A fresh :class:`RhsWork` for a bearing of ``ball_count`` balls."""
    return RhsWork(
        np.empty((3, 3)),
        np.empty(3),
        np.empty(3),
        np.empty(3),
        np.empty((3, 3)),
        np.empty(3),
        np.zeros(3),
        np.empty((3, 3)),
        np.empty(3),
        np.empty(12),
        np.empty(5),
        np.zeros(2),
        np.empty(TRACTION_WORK_SIZE),
        np.ones((CS_SIZE, stash_columns(ball_count))),
        np.zeros(6),
    )


@njit(cache=True)
def rhs(y, t, history, par, quad, dydt, rec_inner, rec_outer, pocket):
    """dy/dt of the whole bearing at state ``y`` and time ``t`` [s] (the time the operating history
    ``history``, a :class:`solver.history.HistoryRecord`, is read at). ``rec_inner``/``rec_outer``
    (Z, N_CONTACT_RECORD) and ``pocket`` (Z,) receive the contact records and pocket normal forces
    of this evaluation. :func:`rhs_into` with a fresh scratch record (integrators keep one and call
    that)."""
    scratch = rhs_work(int(par.ball_count))
    rhs_into(
        y, t, history, par, quad, dydt, rec_inner, rec_outer, pocket, scratch, runtime_bool(True)
    )


@njit(cache=True)
def rhs_into(y, t, history, par, quad, dydt, rec_inner, rec_outer, pocket, scratch, observed):
    """:func:`rhs` with the scratch record ``scratch`` (:func:`rhs_work`): no allocation. The
    imposed inputs are read once from ``history``, at ``t`` [s] (:func:`solver.history.drive_at`),
    and the body gets them as a :class:`solver.history.Drive` of floats. Callers pass
    ``observed`` explicitly (no default: an omitted argument is typed apart and would compile a
    second variant), from compiled code as ``runtime_bool(...)``, so that numba compiles one
    variant. The evaluation works on borrowed views of the arrays (:mod:`.borrow`), so that its
    many bindings and slices of them cost no atomic reference counts. ``observed`` False
    (integrators' stages, which pass it explicitly): the records hold only what the forces and
    ``post_step`` need (contact angle, raceway azimuth and elastic load NaN; see
    :func:`contact_state`)."""
    z = int(par.ball_count)
    phi = y[BALL_STRIDE * z + R_PHI_INNER]
    _rhs_borrowed(
        borrowed(y),
        drive_at(borrowed_record(history), t, phi),
        borrowed_record(par),
        borrowed(quad),
        borrowed(dydt),
        borrowed(rec_inner),
        borrowed(rec_outer),
        borrowed(pocket),
        runtime_bool(observed),
        RhsWork(
            borrowed(scratch.inner_rot),
            borrowed(scratch.inner_origin),
            borrowed(scratch.inner_vel),
            borrowed(scratch.inner_omega),
            borrowed(scratch.outer_rot),
            borrowed(scratch.outer_omega),
            borrowed(scratch.zero3),
            borrowed(scratch.cage_rot),
            borrowed(scratch.cage_omega),
            borrowed(scratch.pocket),
            borrowed(scratch.land),
            borrowed(scratch.ring_speed),
            borrowed(scratch.contact),
            borrowed(scratch.stash),
            borrowed(scratch.ring_load),
        ),
    )


@njit(cache=True, error_model="numpy")
def _rhs_borrowed(y, drive, par, quad, dydt, rec_inner, rec_outer, pocket, observed, scratch):
    """Body of :func:`rhs_into`, on the views it borrows, under the imposed inputs ``drive``
    (:class:`solver.history.Drive`). Compiled with numpy's error model: a
    division by zero gives inf or NaN (which the integrator's finiteness check turns into a
    failed step) instead of a test and a branch to an exception before every division."""
    z = int(par.ball_count)
    rb = BALL_STRIDE * z
    cb = rb + RING_SIZE
    irot = scratch.inner_rot
    iorg = scratch.inner_origin
    ivel = scratch.inner_vel
    iome = scratch.inner_omega
    orot = scratch.outer_rot
    oome = scratch.outer_omega
    ring_frames(y, par, drive, irot, iorg, ivel, iome, orot, oome)
    scratch.ring_speed[0] = drive.inner_speed
    scratch.ring_speed[1] = drive.outer_speed
    zero3 = scratch.zero3
    mb = par.ball_mass
    jinv = 1.0 / par.ball_inertia
    g = par.gravity
    cage_on = par.cage
    pk = scratch.pocket
    work = scratch.contact
    crot = scratch.cage_rot
    come = scratch.cage_omega
    cage_frame(y, cb, crot, come)
    hi = par.inner_hertz
    ho = par.outer_hertz
    # the ball-race contacts in three passes, one inlined copy of each for both races: state and
    # load of every contact, the film laws of all contacts in one vectorised loop, then forces
    stash = scratch.stash
    for j in range(z):
        jb = BALL_STRIDE * j
        for race in range(2):
            inner = race == 0
            contact_state(
                y,
                jb,
                irot if inner else orot,
                iorg if inner else zero3,
                ivel if inner else zero3,
                iome if inner else oome,
                inner,
                par,
                hi if inner else ho,
                rec_inner[j] if inner else rec_outer[j],
                stash,
                race * z + j,
                observed,
            )
    contact_films(par, stash, stash_columns(z))
    frx = fry = frz = 0.0
    mrx = mry = mrz = 0.0
    fcx = fcy = fcz = 0.0
    mcx = mcy = mcz = 0.0
    for j in range(z):
        jb = BALL_STRIDE * j
        ri = rec_inner[j]
        ro = rec_outer[j]
        for race in range(2):
            inner = race == 0
            contact_forces(
                y,
                jb,
                iorg if inner else zero3,
                ivel if inner else zero3,
                iome if inner else oome,
                inner,
                par,
                quad,
                ri if inner else ro,
                work,
                stash,
                race * z + j,
            )
        fx = ri[K_F_BALL] + ro[K_F_BALL]
        fy = ri[K_F_BALL + 1] + ro[K_F_BALL + 1]
        fz = ri[K_F_BALL + 2] + ro[K_F_BALL + 2] - mb * g
        mx = ri[K_M_BALL] + ro[K_M_BALL]
        my = ri[K_M_BALL + 1] + ro[K_M_BALL + 1]
        mz = ri[K_M_BALL + 2] + ro[K_M_BALL + 2]
        fd, md, _ = ball_drag(y, jb, par)
        fx += fd[0]
        fy += fd[1]
        fz += fd[2]
        mx += md[0]
        my += md[1]
        mz += md[2]
        pocket[j] = 0.0
        if cage_on:
            pocket[j] = cage_pocket(y, jb, cb, j, par, crot, come, work, pk)
            fx += pk[0]
            fy += pk[1]
            fz += pk[2]
            mx += pk[3]
            my += pk[4]
            mz += pk[5]
            fcx += pk[6]
            fcy += pk[7]
            fcz += pk[8]
            mcx += pk[9]
            mcy += pk[10]
            mcz += pk[11]
        frx += ri[K_F_RING]
        fry += ri[K_F_RING + 1]
        frz += ri[K_F_RING + 2]
        mrx += ri[K_M_RING]
        mry += ri[K_M_RING + 1]
        mrz += ri[K_M_RING + 2]
        for i in range(3):
            dydt[jb + B_POS + i] = y[jb + B_VEL + i]
        dydt[jb + B_VEL] = fx / mb
        dydt[jb + B_VEL + 1] = fy / mb
        dydt[jb + B_VEL + 2] = fz / mb
        qw, qx, qy, qz = y[jb + B_QUAT], y[jb + B_QUAT + 1], y[jb + B_QUAT + 2], y[jb + B_QUAT + 3]
        wx, wy, wz = y[jb + B_OMEGA], y[jb + B_OMEGA + 1], y[jb + B_OMEGA + 2]
        # q' = 1/2 (0, w_inertial) (x) q
        dydt[jb + B_QUAT] = -0.5 * (wx * qx + wy * qy + wz * qz)
        c0, c1, c2 = _cross(wx, wy, wz, qx, qy, qz)
        dydt[jb + B_QUAT + 1] = 0.5 * (qw * wx + c0)
        dydt[jb + B_QUAT + 2] = 0.5 * (qw * wy + c1)
        dydt[jb + B_QUAT + 3] = 0.5 * (qw * wz + c2)
        dydt[jb + B_OMEGA] = mx * jinv
        dydt[jb + B_OMEGA + 1] = my * jinv
        dydt[jb + B_OMEGA + 2] = mz * jinv
    # inner ring
    for i in range(RING_SIZE):
        dydt[rb + i] = 0.0
    dydt[rb + R_PHI_INNER] = drive.inner_speed
    dydt[rb + R_PHI_OUTER] = drive.outer_speed
    ld = scratch.land
    if cage_on:
        cage_land(y, cb, iorg, ivel, drive.inner_speed, drive.outer_speed, par, work, ld)
        if par.guidance == GUIDE_INNER_RING:  # reaction on the inner ring
            fry -= ld[1]
            frz -= ld[2]
    else:
        for i in range(5):
            ld[i] = 0.0
    rl = scratch.ring_load
    rl[0] = frx
    rl[1] = fry
    rl[2] = frz
    rl[3] = mrx
    rl[4] = mry
    rl[5] = mrz
    if par.ring_free:
        mr = par.ring_mass
        for i in range(3):
            dydt[rb + R_POS + i] = y[rb + R_VEL + i]
        dydt[rb + R_VEL] = (frx + drive.force_x) / mr
        dydt[rb + R_VEL + 1] = (fry + drive.force_y) / mr
        dydt[rb + R_VEL + 2] = (frz + drive.force_z) / mr - g
    if par.tilt_mode == TILT_FREE:
        ird, irp, wi = par.ring_diametral_inertia, par.ring_polar_inertia, drive.inner_speed
        gy_rate, gz_rate = y[rb + R_TILT_RATE], y[rb + R_TILT_RATE + 1]
        dydt[rb + R_TILT] = gy_rate
        dydt[rb + R_TILT + 1] = gz_rate
        dydt[rb + R_TILT_RATE] = (mry + drive.moment_y - irp * wi * gz_rate) / ird
        dydt[rb + R_TILT_RATE + 1] = (mrz + drive.moment_z + irp * wi * gy_rate) / ird
    else:  # the imposed tilt follows the history
        dydt[rb + R_TILT] = drive.tilt_rate_y
        dydt[rb + R_TILT + 1] = drive.tilt_rate_z
    # cage
    for i in range(CAGE_SIZE):
        dydt[cb + i] = 0.0
    if cage_on:
        mc = par.cage_mass
        for i in range(3):
            dydt[cb + C_POS + i] = y[cb + C_VEL + i]
        dydt[cb + C_VEL] = (fcx + ld[0]) / mc
        dydt[cb + C_VEL + 1] = (fcy + ld[1]) / mc
        dydt[cb + C_VEL + 2] = (fcz + ld[2]) / mc - g
        # spin about the cage's own axis, and the two tilts (rigid ring: polar inertia I_p,
        # diametral I_d; small tilts with the gyroscopic coupling as for the inner ring)
        icp, icd = par.cage_polar_inertia, par.cage_diametral_inertia
        ax = crot[0, 0] * mcx + crot[1, 0] * mcy + crot[2, 0] * mcz
        dydt[cb + C_ANGLE] = y[cb + C_SPEED]
        drag, _ = cage_drag(y, cb, par)
        dydt[cb + C_SPEED] = (ax + ld[3] + drag) / icp
        wc = y[cb + C_SPEED]
        ty_rate, tz_rate = y[cb + C_TILT_RATE], y[cb + C_TILT_RATE + 1]
        dydt[cb + C_TILT] = ty_rate
        dydt[cb + C_TILT + 1] = tz_rate
        dydt[cb + C_TILT_RATE] = (mcy - icp * wc * tz_rate) / icd
        dydt[cb + C_TILT_RATE + 1] = (mcz + icp * wc * ty_rate) / icd


@njit(cache=True)
def mechanical_energy(y, t, history, par, quad, rec_inner, rec_outer):
    """Kinetic + potential energy [J] at time ``t`` [s] (the operating history ``history`` read
    there) for the conservative model (traction, damping, cage off) under a constant applied
    force.

    Potential: Hertz 2/5 K delta^2.5 per loaded contact, -F_ext . r_ring for the applied force
    (a potential only while it is constant), m g z for gravity along -z (balls, and the inner ring
    when it is free). The inner ring's imposed spin is not included (it does no work on
    frictionless contacts). ``rec_inner`` and ``rec_outer`` receive each contact's state and
    load (:func:`contact_state`), not its forces.
    """
    z = int(par.ball_count)
    rb = BALL_STRIDE * z
    drive = drive_at(history, t, y[rb + R_PHI_INNER])
    irot, iorg, ivel, iome, orot, oome = ring_frame_arrays()
    ring_frames(y, par, drive, irot, iorg, ivel, iome, orot, oome)
    zero3 = np.zeros(3)
    stash = np.ones((CS_SIZE, 1))
    mb = par.ball_mass
    e = 0.0
    for j in range(z):
        jb = BALL_STRIDE * j
        ri, ro = rec_inner[j], rec_outer[j]
        contact_state(y, jb, irot, iorg, ivel, iome, True, par, par.inner_hertz, ri, stash, 0, True)
        contact_state(
            y, jb, orot, zero3, zero3, oome, False, par, par.outer_hertz, ro, stash, 0, True
        )
        for rec in (rec_inner[j], rec_outer[j]):
            d = rec[K_DEFLECTION]
            if d > 0.0:
                e += 0.4 * rec[K_ELASTIC] * d
        v2 = 0.0
        w2 = 0.0
        for i in range(3):
            v2 += y[jb + B_VEL + i] ** 2
            w2 += y[jb + B_OMEGA + i] ** 2
        e += 0.5 * mb * v2 + 0.5 * par.ball_inertia * w2 + mb * par.gravity * y[jb + B_POS + 2]
    if par.ring_free:
        v2 = 0.0
        for i in range(3):
            v2 += y[rb + R_VEL + i] ** 2
        e += 0.5 * par.ring_mass * v2
        e -= (
            drive.force_x * y[rb + R_POS]
            + drive.force_y * y[rb + R_POS + 1]
            + drive.force_z * y[rb + R_POS + 2]
        )
        e += par.ring_mass * par.gravity * y[rb + R_POS + 2]
    return e
