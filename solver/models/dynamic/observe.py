"""Per-sample quantities of the dynamic model (numba), from stored states.

For every output sample the right-hand side is evaluated once; it fills the per-contact records
(layout ``K_*``). This step adds the record slots that only output needs (latitude and longitude on
the ball, spin-to-roll ratio: spin / roll, and spin roll / roll_min^2 below the rolling speed
roll_min = 2 u_min / D of the entrainment floor u_min of solver.physics.rheology) and keeps the
whole record per sample; the table ``CONTACT_OUTPUTS`` of ``output.py`` names which slots
become results variables. It also fills a per-ball record
(``BO_*``: pocket force, pocket and drag power) and a bearing record (``RO_*``: land power, cage
drag power, friction torque and drive power of the inner ring, and the elastic energy of the
ball-race contacts). Races: index 0 inner, 1 outer.

Powers: an interaction between two bodies dissipates minus the work rate of its forces and moments
on both (sum of F . v + M . omega over the pair, velocities of the points the forces act on).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from solver.history import N_CHANNELS, channel_value, drive_at
from solver.physics.rheology import ENTRAINMENT_FLOOR

from . import layout as L
from .kernels import (
    TRACTION_WORK_SIZE,
    ball_drag,
    cage_drag,
    cage_frame,
    cage_land,
    cage_pocket,
    quaternion_to_matrix,
    rhs,
    ring_frame_arrays,
    ring_frames,
)


@njit(cache=True)
def observe(states, times, history, par, quad, records, balls, bearing):
    """Fill ``records`` (S, Z, 2, N_CONTACT_RECORD), ``balls`` (S, Z, N_BALL_OUTPUT) and
    ``bearing`` (S, N_BEARING_OUTPUT) for the states (S, n) at ``times`` (S,) [s] (the operating
    history ``history`` is read there)."""
    z = par.ball_count
    n = states.shape[1]
    dydt = np.empty(n)
    rec = np.empty((2, z, L.N_CONTACT_RECORD))
    pocket = np.empty(z)
    rot = np.empty((3, 3))
    irot, iorg, ivel, iome, orot, oome = ring_frame_arrays()
    crot = np.empty((3, 3))
    come = np.empty(3)
    pk = np.empty(12)
    ld = np.empty(5)
    work = np.empty(TRACTION_WORK_SIZE)
    rb = L.BALL_STRIDE * z
    cb = rb + L.RING_SIZE
    roll_min = 2.0 * ENTRAINMENT_FLOOR / par.ball_diameter  # [rad/s]
    for s in range(states.shape[0]):
        y = states[s]
        t = times[s]
        drive = drive_at(history, t, y[rb + L.R_PHI_INNER])
        rhs(y, t, history, par, quad, dydt, rec[0], rec[1], pocket)
        ring_frames(y, par, drive, irot, iorg, ivel, iome, orot, oome)
        cage_frame(y, cb, crot, come)
        vcx, vcy, vcz = y[cb + L.C_VEL], y[cb + L.C_VEL + 1], y[cb + L.C_VEL + 2]
        # moments of the contacts on the inner ring about its centre
        mix = miy = miz = 0.0
        mox = 0.0
        elastic = 0.0
        for j in range(z):
            b = L.BALL_STRIDE * j
            mix += rec[0, j, L.K_M_RING]
            miy += rec[0, j, L.K_M_RING + 1]
            miz += rec[0, j, L.K_M_RING + 2]
            mox += rec[1, j, L.K_M_RING]
            quaternion_to_matrix(
                y[b + L.B_QUAT], y[b + L.B_QUAT + 1], y[b + L.B_QUAT + 2], y[b + L.B_QUAT + 3], rot
            )
            for k in range(2):
                r = rec[k, j]
                if r[L.K_DEFLECTION] > 0.0:
                    elastic += 0.4 * r[L.K_ELASTIC] * r[L.K_DEFLECTION]
                nx, ny, nz = r[L.K_NORMAL], r[L.K_NORMAL + 1], r[L.K_NORMAL + 2]
                # ball-fixed components e_b = R^T n
                ebx = rot[0, 0] * nx + rot[1, 0] * ny + rot[2, 0] * nz
                eby = rot[0, 1] * nx + rot[1, 1] * ny + rot[2, 1] * nz
                ebz = rot[0, 2] * nx + rot[1, 2] * ny + rot[2, 2] * nz
                r[L.K_LATITUDE] = math.asin(min(1.0, max(-1.0, ebz)))
                r[L.K_LONGITUDE] = math.atan2(eby, ebx)
                # spin / roll, continued below the rolling speed of the entrainment floor as
                # spin roll / roll_min^2 (0 without rolling)
                roll = r[L.K_ROLL]
                r[L.K_SPIN_TO_ROLL] = r[L.K_SPIN] * roll / max(roll * roll, roll_min * roll_min)
                for i in range(L.N_CONTACT_RECORD):
                    records[s, j, k, i] = r[i]
            balls[s, j, L.BO_POCKET_FORCE] = pocket[j]
            power = 0.0
            if par.cage and pocket[j] > 0.0:
                cage_pocket(y, b, cb, j, par, crot, come, work, pk)
                for i in range(3):
                    power -= pk[i] * y[b + L.B_VEL + i] + pk[3 + i] * y[b + L.B_OMEGA + i]
                    power -= pk[9 + i] * come[i]
                power -= pk[6] * vcx + pk[7] * vcy + pk[8] * vcz
            balls[s, j, L.BO_POCKET_POWER] = power
            _, _, drag = ball_drag(y, b, par)
            balls[s, j, L.BO_DRAG_POWER] = drag
        # cage land: force F and moment T on the cage, -F and T_ring on the guiding ring
        land = 0.0
        ring_torque = 0.0
        wring = 0.0
        if par.cage and par.guidance != L.GUIDE_BALL:
            cage_land(y, cb, iorg, ivel, drive.inner_speed, drive.outer_speed, par, work, ld)
            ring_torque = ld[4]
            if par.guidance == L.GUIDE_INNER_RING:
                vr0, vr1, vr2, wring = ivel[0], ivel[1], ivel[2], iome[0]
            else:
                vr0, vr1, vr2, wring = 0.0, 0.0, 0.0, oome[0]
            land = -(
                ld[0] * (vcx - vr0)
                + ld[1] * (vcy - vr1)
                + ld[2] * (vcz - vr2)
                + ld[3] * come[0]
                + ld[4] * wring
            )
        bearing[s, L.RO_LAND_POWER] = land
        cage_drag_power = 0.0
        if par.cage:
            _, cage_drag_power = cage_drag(y, cb, par)
        bearing[s, L.RO_CAGE_DRAG_POWER] = cage_drag_power
        # the imposed ring spins take the torques that hold the rings at their speeds
        wi = drive.inner_speed
        drive_inner = -(mix * iome[0] + miy * iome[1] + miz * iome[2])
        if par.tilt_mode == L.TILT_FREE:  # only the imposed spin is driven, not the tilt rates
            drive_inner += miy * y[rb + L.R_TILT_RATE] + miz * y[rb + L.R_TILT_RATE + 1]
        if par.guidance == L.GUIDE_INNER_RING:
            drive_inner -= ring_torque * wring
        drive_outer = -mox * oome[0]
        if par.guidance == L.GUIDE_OUTER_RING:
            drive_outer -= ring_torque * wring
        bearing[s, L.RO_DRIVE_POWER] = drive_inner + drive_outer
        bearing[s, L.RO_FRICTION_TORQUE] = drive_inner / wi if wi != 0.0 else 0.0
        bearing[s, L.RO_ELASTIC_ENERGY] = elastic


@njit(cache=True)
def channel_series(history, times, out):
    """``out`` (N_CHANNELS, S) <- every channel of ``history`` at ``times`` (S,) [s]."""
    for c in range(N_CHANNELS):
        for k in range(times.shape[0]):
            out[c, k] = channel_value(history, c, times[k])


@njit(cache=True)
def applied_load_work(states, times, history, par, events, work):
    """``work`` (S,) <- the work [J] of the applied force and moment (of the operating history
    ``history``) on the inner ring since the first state: the Stieltjes sum of F . dx
    (translations free) and M . d(tilt) (free tilt) over the sample intervals cut at ``events``
    (increasing times [s]), F and M at the middle of each piece, the state at a cut interpolated
    linearly (output.load_work adds gravity)."""
    z = par.ball_count
    rb = L.BALL_STRIDE * z
    free_tilt = par.tilt_mode == L.TILT_FREE
    work[0] = 0.0
    e = 0
    for k in range(1, times.shape[0]):
        a = times[k - 1]
        b = times[k]
        while e < events.shape[0] and events[e] <= a:
            e += 1
        step = 0.0
        t0 = a
        last = False
        while not last:
            if e < events.shape[0] and events[e] < b:
                t1 = events[e]
                e += 1
            else:
                t1 = b
                last = True
            s0 = (t0 - a) / (b - a)
            s1 = (t1 - a) / (b - a)
            frac = s1 - s0
            phi0 = states[k - 1, rb + L.R_PHI_INNER]
            angle = phi0 + 0.5 * (s0 + s1) * (states[k, rb + L.R_PHI_INNER] - phi0)
            drive = drive_at(history, 0.5 * (t0 + t1), angle)
            if par.ring_free:
                p = rb + L.R_POS
                step += frac * (
                    drive.force_x * (states[k, p] - states[k - 1, p])
                    + drive.force_y * (states[k, p + 1] - states[k - 1, p + 1])
                    + drive.force_z * (states[k, p + 2] - states[k - 1, p + 2])
                )
            if free_tilt:
                g = rb + L.R_TILT
                step += frac * (
                    drive.moment_y * (states[k, g] - states[k - 1, g])
                    + drive.moment_z * (states[k, g + 1] - states[k - 1, g + 1])
                )
            t0 = t1
        work[k] = work[k - 1] + step
