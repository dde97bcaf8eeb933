"""Per-sample contact quantities of the dynamic model (numba), from stored states.

For every output sample the right-hand side is evaluated once (it fills the contact records); the
quantities of results-schema.md are then derived here. Races: index 0 inner, 1 outer.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from solver.physics.ehl import film_thickness_central
from solver.physics.hertz_fast import curvature_sum_and_difference_fast, hertz_coefficients_fast

from . import layout as L
from .kernels import quaternion_to_matrix, rhs

O_LOAD = 0  # N
O_ANGLE = 1  # rad
O_DEFLECTION = 2  # m, clipped at 0
O_SEMI_MAJOR = 3  # m
O_SEMI_MINOR = 4  # m
O_PMAX = 5  # Pa
O_AZIMUTH = 6  # rad, ring frame, wrapped to [0, 2 pi)
O_POINT = 7  # (3) m, ring frame
O_LATITUDE = 10  # rad, on the ball
O_LONGITUDE = 11  # rad
O_SPIN_TO_ROLL = 12
O_SLIDE = 13  # m/s
O_FILM = 14  # m, central film thickness
N_OBS = 15


@njit(cache=True)
def observe(states, par, quad, viscosity, pressure_viscosity, obs, pocket_out):
    """Fill ``obs`` (S, Z, 2, N_OBS) and ``pocket_out`` (S, Z) for the states (S, n)."""
    z = int(par.ball_count)
    n = states.shape[1]
    dydt = np.empty(n)
    rec = np.empty((2, z, L.N_CONTACT_RECORD))
    pocket = np.empty(z)
    rot = np.empty((3, 3))
    eprime = par.eprime
    d = par.ball_diameter
    for s in range(states.shape[0]):
        y = states[s]
        rhs(y, par, quad, dydt, rec[0], rec[1], pocket)
        for j in range(z):
            pocket_out[s, j] = pocket[j]
            b = L.BALL_STRIDE * j
            quaternion_to_matrix(
                y[b + L.B_QUAT], y[b + L.B_QUAT + 1], y[b + L.B_QUAT + 2], y[b + L.B_QUAT + 3], rot
            )
            for k in range(2):
                r = rec[k, j]
                o = obs[s, j, k]
                q = r[L.K_LOAD]
                o[O_LOAD] = q
                o[O_ANGLE] = r[L.K_ANGLE]
                o[O_DEFLECTION] = max(r[L.K_DEFLECTION], 0.0)
                o[O_SEMI_MAJOR] = r[L.K_SEMI_MAJOR]
                o[O_SEMI_MINOR] = r[L.K_SEMI_MINOR]
                o[O_PMAX] = r[L.K_PMAX]
                az = r[L.K_AZIMUTH] % (2.0 * math.pi)
                o[O_AZIMUTH] = az
                for i in range(3):
                    o[O_POINT + i] = r[L.K_POINT + i]
                nx, ny, nz = r[L.K_NORMAL], r[L.K_NORMAL + 1], r[L.K_NORMAL + 2]
                # ball-fixed components e_b = R^T n
                ebx = rot[0, 0] * nx + rot[1, 0] * ny + rot[2, 0] * nz
                eby = rot[0, 1] * nx + rot[1, 1] * ny + rot[2, 1] * nz
                ebz = rot[0, 2] * nx + rot[1, 2] * ny + rot[2, 2] * nz
                o[O_LATITUDE] = math.asin(min(1.0, max(-1.0, ebz)))
                o[O_LONGITUDE] = math.atan2(eby, ebx)
                roll = r[L.K_ROLL]
                o[O_SPIN_TO_ROLL] = r[L.K_SPIN] / roll if abs(roll) > 1e-12 else 0.0
                o[O_SLIDE] = r[L.K_SLIDE]
                conf = par.inner_conformity if k == 0 else par.outer_conformity
                gamma = d * math.cos(r[L.K_ANGLE]) / par.pitch_diameter
                _, fdiff = curvature_sum_and_difference_fast(d, conf, gamma, k == 0)
                kappa, _, _ = hertz_coefficients_fast(fdiff)
                o[O_FILM] = film_thickness_central(
                    r[L.K_ENTRAIN], viscosity, pressure_viscosity, eprime, r[L.K_RX], q, kappa
                )
