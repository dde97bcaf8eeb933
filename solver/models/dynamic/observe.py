"""Per-sample contact quantities of the dynamic model (numba), from stored states.

For every output sample the right-hand side is evaluated once; it fills the per-contact records
(layout ``K_*``). This step adds the record slots that only output needs (latitude and longitude on
the ball, spin-to-roll ratio, film thickness) and keeps the whole record per sample; the table
``CONTACT_OUTPUTS`` of ``output.py`` then names which slots become results variables. Races: index
0 inner, 1 outer.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from solver.physics.ehl import film_thickness_central
from solver.physics.hertz_fast import curvature_sum_and_difference_fast, hertz_coefficients_fast

from . import layout as L
from .kernels import quaternion_to_matrix, rhs


@njit(cache=True)
def observe(states, par, quad, viscosity, pressure_viscosity, records, pocket_out):
    """Fill ``records`` (S, Z, 2, N_CONTACT_RECORD) and ``pocket_out`` (S, Z) for the states
    (S, n)."""
    z = par.ball_count
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
                nx, ny, nz = r[L.K_NORMAL], r[L.K_NORMAL + 1], r[L.K_NORMAL + 2]
                # ball-fixed components e_b = R^T n
                ebx = rot[0, 0] * nx + rot[1, 0] * ny + rot[2, 0] * nz
                eby = rot[0, 1] * nx + rot[1, 1] * ny + rot[2, 1] * nz
                ebz = rot[0, 2] * nx + rot[1, 2] * ny + rot[2, 2] * nz
                r[L.K_LATITUDE] = math.asin(min(1.0, max(-1.0, ebz)))
                r[L.K_LONGITUDE] = math.atan2(eby, ebx)
                roll = r[L.K_ROLL]
                r[L.K_SPIN_TO_ROLL] = r[L.K_SPIN] / roll if abs(roll) > 1e-12 else 0.0
                conf = par.inner_conformity if k == 0 else par.outer_conformity
                gamma = d * math.cos(r[L.K_ANGLE]) / par.pitch_diameter
                _, fdiff = curvature_sum_and_difference_fast(d, conf, gamma, k == 0)
                kappa, _, _ = hertz_coefficients_fast(fdiff)
                r[L.K_FILM] = film_thickness_central(
                    r[L.K_ENTRAIN],
                    viscosity,
                    pressure_viscosity,
                    eprime,
                    r[L.K_RX],
                    r[L.K_LOAD],
                    kappa,
                )
                for i in range(L.N_CONTACT_RECORD):
                    records[s, j, k, i] = r[i]
