"""Right-hand side of the dynamic model of a bearing set on one rigid shaft.

State vector of a set of B bearings (SI): the state of each bearing in its own frame, laid out as
the single-bearing model's (:mod:`.layout`: balls, inner ring, cage), one after the other from
``SetShaft.starts[b]``, then the shaft block of :data:`layout.RING_SIZE` slots at
``SetShaft.starts[B]``, laid out as an inner-ring block: ``R_POS`` (3) displacement u of the shaft
at the set's load point [m], ``R_VEL`` (3), ``R_TILT`` (2) tilt (about y, z) [rad],
``R_TILT_RATE`` (2), ``R_PHI_INNER``/``R_PHI_OUTER`` spin angles [rad], shaft frame (x along the
shaft axis, gravity along -z).

Bearing b's frame is the shaft frame, mirrored (x -> -x) for a bearing with direction "-x", with
its origin on its outer ring's centre at its ball-centre plane, the plane at the arm L_b from the
load point. Its inner ring moves rigidly with the shaft (small rotations):

    q_b = T_b G_b u + (c_b, 0, 0, 0, 0),    q_b = (x, y, z, tilt_y, tilt_z) of its ring block,

G_b u = (u_x, u_y + L_b tilt_z, u_z - L_b tilt_y, tilt_y, tilt_z), T_b = diag(s, 1, 1, s, s) with
s = -1 for a mirrored bearing (tilts and moments are axial vectors), c_b the axial offset of its
rings (fixed-position preload), as in :mod:`solver.models.quasistatic.bearing_set`. The ring blocks
of the bearings are therefore not free: their rates are those of the shaft mapped by T_b G_b, so
that they stay q_b(u) along the integration (the map is linear, so every Runge-Kutta stage keeps
them so too). The spin angles of every ring block follow the speeds of the bearing's own history.

Each bearing's balls and cage see the single-bearing right-hand side
(:func:`.kernels.rhs_into`) on its slice of the state, which also returns the force and moment of
its balls on its inner ring (``RhsWork.ring_load``). The shaft's generalised force is

    Q = F_ext + sum_b G_b^T T_b R_b + Q_gravity + Q_gyro,     M_shaft du''/dt = Q

with R_b = (F_x, F_y, F_z, M_y, M_z) of the balls on ring b (own frame, about its centre), the
shaft's mass matrix M_shaft = sum_b G_b^T diag(m_b, m_b, m_b, I_d,b, I_d,b) G_b (the shaft is the
inner rings, rigidly joined), gravity sum_b G_b^T (0, 0, -m_b g, 0, 0) and the gyroscopic moment
I_p omega (-tilt_z', tilt_y') of the spinning rings (I_p = sum_b I_p,b).

The outer rings are fixed, except under a spring preload: the outer rings of the spring side
(``SetShaft.floating[b]`` = 1) then float axially as one body of mass M_o
(``1 / SetShaft.spring_mass_inverse``), held radially and in tilt by the housing, pushed by the
spring force F_s (``SetShaft.spring_force``) onto their balls. Its degree of freedom is the shift
w [m] of those bearings' inner rings relative to their outer rings due to the outer rings' motion
(the outer rings move by -w along the bearings' own x; the quasi-static set model's
``spring_shift``), in the two slots ``SetShaft.spring_slot`` (w) and the one after it (w' [m/s]),
after the shaft block. A floating bearing's state is in the frame of its outer ring, which
translates by -w along x: its ring block is q_b + (w, 0, 0, 0, 0), and its balls and cage, whose
positions and velocities are relative to the outer ring, feel the frame's inertial force
+m w'' along x. The outer rings' equation (own frame, F_o,b the axial force of bearing b's balls
on its outer ring):

    M_o w'' = F_s - sum_(floating b) F_o,b

which at rest is the quasi-static set's F_s + sum R_b,x = 0 (each ball carries its axial load from
the inner to the outer ring).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from .kernels import post_step, rhs_into
from .layout import (
    B_VEL,
    BALL_STRIDE,
    C_VEL,
    CAGE_SIZE,
    K_F_RING,
    R_PHI_INNER,
    R_PHI_OUTER,
    R_POS,
    R_TILT,
    R_TILT_RATE,
    R_VEL,
    RING_SIZE,
)


class SetShaft(NamedTuple):
    """The shaft's record (SI, shaft frame)."""

    starts: np.ndarray  # (B + 1,) int64: first slot of each bearing's state, then of the shaft
    sign: np.ndarray  # (B,) +1 or -1 (a bearing mirrored: direction "-x")
    arm: np.ndarray  # (B,) arm L_b of each ball-centre plane from the load point [m]
    mass_inverse: np.ndarray  # (5, 5) inverse of the shaft's mass matrix [1/kg, 1/(kg m), ...]
    applied: np.ndarray  # (5,) F_x, F_y, F_z [N], M_y, M_z [N m] at the load point
    weight: np.ndarray  # (5,) generalised force of gravity at the load point [N, N m]
    polar_inertia: float  # sum of the rings' polar moments of inertia [kg m^2]
    floating: np.ndarray  # (B,) 1.0 for a bearing whose outer ring floats (spring side), else 0.0
    spring_slot: int  # slot of the spring shift w [m] (w' [m/s] after it); -1: no spring preload
    spring_force: float  # spring force F_s on the floating outer rings [N]
    spring_mass_inverse: float  # 1 / M_o of the floating outer rings [1/kg]; 0: no spring


class SetWork(NamedTuple):
    """Scratch of one set evaluation: each bearing's :class:`.kernels.RhsWork` and the shaft's
    generalised force and rates."""

    bearings: tuple  # (B,) RhsWork
    force: np.ndarray  # (5,) generalised force on the shaft
    rate: np.ndarray  # (5,) shaft velocity (x, y, z, tilt_y, tilt_z)
    acceleration: np.ndarray  # (5,) shaft acceleration


@njit(cache=True)
def ring_block_from_shaft(sign, arm, rate, out, base):
    """``out[base : base + 5]`` <- T_b G_b ``rate`` for the 5-vector ``rate`` (x, y, z, tilt_y,
    tilt_z) of the shaft: bearing b's ring rates (own frame) from the shaft's."""
    out[base] = sign * rate[0]
    out[base + 1] = rate[1] + arm * rate[4]
    out[base + 2] = rate[2] - arm * rate[3]
    out[base + 3] = sign * rate[3]
    out[base + 4] = sign * rate[4]


@njit(cache=True)
def set_rhs_into(y, t, bearings, shaft, dydt, work, observed):
    """dy/dt of the set at state ``y`` and time ``t`` [s] into ``dydt``, with the scratch ``work``
    (:class:`SetWork`). ``bearings``: a tuple of :class:`.integrate.model.BearingModel`, one per
    bearing (its parameters, history, quadrature and contact records, own frame; each record is
    written as by the single-bearing right-hand side); ``shaft``: :class:`SetShaft`;
    ``observed``: as for :func:`.kernels.rhs_into`."""
    nb = len(bearings)
    q = work.force
    for i in range(5):
        q[i] = shaft.applied[i] + shaft.weight[i]
    for b in range(nb):
        m = bearings[b]
        s0 = shaft.starts[b]
        s1 = shaft.starts[b + 1]
        w = work.bearings[b]
        rhs_into(
            y[s0:s1],
            t,
            m.history,
            m.par,
            m.quad,
            dydt[s0:s1],
            m.rec_inner,
            m.rec_outer,
            m.pocket,
            w,
            observed,
        )
        rl = w.ring_load  # own frame: F (3), M (3) about the ring centre
        sgn = shaft.sign[b]
        arm = shaft.arm[b]
        fy = rl[1]
        fz = rl[2]
        q[0] += sgn * rl[0]
        q[1] += fy
        q[2] += fz
        q[3] += sgn * rl[4] - arm * fz
        q[4] += sgn * rl[5] + arm * fy
    # the floating outer rings: the axial force of their balls on them, own frame
    spring_acc = 0.0
    if shaft.spring_slot >= 0:
        outer_force = 0.0
        for b in range(nb):
            if shaft.floating[b] > 0.0:
                rec = bearings[b].rec_outer
                for j in range(rec.shape[0]):
                    outer_force += rec[j, K_F_RING]
        spring_acc = (shaft.spring_force - outer_force) * shaft.spring_mass_inverse
        ws = shaft.spring_slot
        dydt[ws] = y[ws + 1]
        dydt[ws + 1] = spring_acc
    sb = shaft.starts[nb]
    rate = work.rate
    acc = work.acceleration
    for i in range(3):
        rate[i] = y[sb + R_VEL + i]
    rate[3] = y[sb + R_TILT_RATE]
    rate[4] = y[sb + R_TILT_RATE + 1]
    # the rings' spin: bearing 0's ring speed of this evaluation (every bearing's history turns
    # its inner ring at the shaft's speed)
    first_ring = shaft.starts[1] - RING_SIZE - CAGE_SIZE
    spin = dydt[first_ring + R_PHI_INNER]
    ip = shaft.polar_inertia
    q[3] -= ip * spin * rate[4]
    q[4] += ip * spin * rate[3]
    minv = shaft.mass_inverse
    for i in range(5):
        a = 0.0
        for k in range(5):
            a += minv[i, k] * q[k]
        acc[i] = a
    for i in range(3):
        dydt[sb + R_POS + i] = rate[i]
        dydt[sb + R_VEL + i] = acc[i]
    for i in range(2):
        dydt[sb + R_TILT + i] = rate[3 + i]
        dydt[sb + R_TILT_RATE + i] = acc[3 + i]
    dydt[sb + R_PHI_INNER] = spin
    dydt[sb + R_PHI_OUTER] = dydt[first_ring + R_PHI_OUTER]
    # the ring blocks follow the shaft
    for b in range(nb):
        rb = shaft.starts[b + 1] - RING_SIZE - CAGE_SIZE
        sgn = shaft.sign[b]
        arm = shaft.arm[b]
        ring_block_from_shaft(sgn, arm, rate, q, 0)
        for i in range(3):
            dydt[rb + R_POS + i] = q[i]
        dydt[rb + R_TILT] = q[3]
        dydt[rb + R_TILT + 1] = q[4]
        ring_block_from_shaft(sgn, arm, acc, q, 0)
        for i in range(3):
            dydt[rb + R_VEL + i] = q[i]
        dydt[rb + R_TILT_RATE] = q[3]
        dydt[rb + R_TILT_RATE + 1] = q[4]
        if shaft.floating[b] > 0.0:
            # the frame of the floating outer ring: the ring block moves by w relative to it,
            # and every body in it feels the frame's inertial force
            ws = shaft.spring_slot
            dydt[rb + R_POS] += y[ws + 1]
            dydt[rb + R_VEL] += spring_acc
            s0 = shaft.starts[b]
            for j in range(bearings[b].rec_outer.shape[0]):
                dydt[s0 + BALL_STRIDE * j + B_VEL] += spring_acc
            if bearings[b].par.cage:
                dydt[rb + RING_SIZE + C_VEL] += spring_acc


@njit(cache=True)
def set_post_step(y, bearings, shaft):
    """:func:`.kernels.post_step` on every bearing's slice; False when a ball of any bearing left
    its raceways."""
    ok = True
    for b in range(len(bearings)):
        m = bearings[b]
        if not post_step(y[shaft.starts[b] : shaft.starts[b + 1]], m.par, m.rec_inner, m.rec_outer):
            ok = False
    return ok
