"""Hertz coefficients of one ball-race contact tabulated against the cosine of its contact angle.

For a given race (ball diameter D, pitch diameter d_m, conformity f, inner or outer) the Hertz
point contact depends on the contact angle alone, through γ = D cos α / d_m. This module tabulates,
once per bearing, everything the dynamic model needs from the exact solution
(:func:`solver.physics.hertz.ellipticity_exact`) as functions of c = cos α on 0 ≤ c ≤ 1:

* κ, the ellipticity a/b [-];
* S = π κ √(2 ℰ / (9 Σρ 𝒦³)) [m^0.5]: the load-deflection constant is K = S E' [N/m^1.5];
* A = (6 ℰ κ² / (π Σρ))^(1/3) and B = (6 ℰ / (π κ Σρ))^(1/3) [m^(2/3)]: the semi-axes are
  a = A (Q/E')^(1/3) (transverse) and b = B (Q/E')^(1/3) (rolling direction), so a contact needs
  one cube root and no table look-up in F, no logarithm or exponential;
* the two ellipticity terms of the film and EHL rolling-force laws,
  :func:`solver.physics.rheology.film_ellipticity_factor` and
  :func:`solver.physics.rheology.rolling_ellipticity_log` of κ.

Each row is stored with its slopes d/dc from a not-a-knot cubic spline through the exact values
at ``RACE_TABLE_NODES`` uniform nodes; :func:`race_coefficients` evaluates the cubic Hermite
interpolant on the node interval (that spline). Measured accuracy against the exact solution
(tests/unit/physics/test_hertz_race.py, dense sweep over four races from very close to very open
grooves): relative error ≤ 1e-10 in κ, K, a and b and in the two ellipticity terms (absolute for
the logarithm).

Outside 0 ≤ c ≤ 1 (a contact angle beyond ±90°, not a ball bearing's running state),
:func:`race_coefficients` returns NaN: the caller falls back to :func:`race_coefficients_direct`
(the closed forms and F table of :mod:`solver.physics.hertz_fast`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.interpolate import CubicSpline

from .hertz import ellipticity_exact
from .hertz_fast import (
    curvature_sum_and_difference_fast,
    hermite_cell,
    hertz_coefficients_fast,
)
from .rheology import film_ellipticity_factor, rolling_ellipticity_log

__all__ = [
    "RACE_TABLE_NODES",
    "race_table",
    "race_coefficients",
    "race_coefficients_direct",
    "coefficients_from_elliptic",
]

#: nodes of the table over 0 <= cos(alpha) <= 1
RACE_TABLE_NODES = 257
#: rows of the table: values, then their slopes d/dc
ROW_KAPPA = 0
ROW_STIFFNESS = 1
ROW_A = 2
ROW_B = 3
ROW_FILM = 4
ROW_ROLLING = 5
N_ROWS = 6


@njit(cache=True)
def coefficients_from_elliptic(kappa, big_k, big_e, curvature_sum):
    """(κ, S, A, B) of the module docstring from κ, 𝒦(m), ℰ(m) and Σρ [1/m] (floats, or numpy
    arrays through ``.py_func``)."""
    return (
        kappa,
        math.pi * kappa * np.sqrt(2.0 * big_e / (9.0 * curvature_sum * big_k**3)),
        np.cbrt(6.0 * big_e * kappa**2 / (math.pi * curvature_sum)),
        np.cbrt(6.0 * big_e / (math.pi * kappa * curvature_sum)),
    )


@njit(cache=True, inline="always")
def _with_film_terms(kappa, stiffness, coef_a, coef_b):
    """The table's six values: (κ, S, A, B) and the two ellipticity terms of the film laws."""
    return (
        kappa,
        stiffness,
        coef_a,
        coef_b,
        film_ellipticity_factor(kappa),
        rolling_ellipticity_log(kappa),
    )


@njit(cache=True)
def race_coefficients_direct(ball_diameter, conformity, gamma, is_inner):
    """The six values of :func:`race_coefficients` without the race table, from the closed forms
    and the F table of :mod:`solver.physics.hertz_fast` at γ = D cos α / d_m (any γ)."""
    csum, fdiff = curvature_sum_and_difference_fast(ball_diameter, conformity, gamma, is_inner)
    kappa, big_k, big_e = hertz_coefficients_fast(fdiff)
    kappa, stiffness, coef_a, coef_b = coefficients_from_elliptic(kappa, big_k, big_e, csum)
    return _with_film_terms(kappa, stiffness, coef_a, coef_b)


def race_table(ball_diameter, pitch_diameter, conformity, is_inner) -> np.ndarray:
    """(2 N_ROWS, RACE_TABLE_NODES) table of one race (module docstring): rows κ, S, A, B and the
    film laws' two ellipticity terms at the nodes c_k = k / (RACE_TABLE_NODES - 1), then their
    slopes d/dc. ``ball_diameter`` D [m],
    ``pitch_diameter`` d_m [m], ``conformity`` f = r / D, ``is_inner`` bool."""
    c = np.linspace(0.0, 1.0, RACE_TABLE_NODES)
    gamma = ball_diameter * c / pitch_diameter
    csum = np.empty_like(c)
    fdiff = np.empty_like(c)
    for k, g in enumerate(gamma):
        csum[k], fdiff[k] = curvature_sum_and_difference_fast(
            ball_diameter, conformity, float(g), bool(is_inner)
        )
    kappa, big_k, big_e = ellipticity_exact(fdiff)
    values = np.vstack(
        coefficients_from_elliptic.py_func(kappa, big_k, big_e, csum)
        + (
            np.array([film_ellipticity_factor(k) for k in kappa]),
            np.array([rolling_ellipticity_log(k) for k in kappa]),
        )
    )
    slopes = np.vstack([CubicSpline(c, row, bc_type="not-a-knot")(c, 1) for row in values])
    return np.ascontiguousarray(np.vstack((values, slopes)))


@njit(cache=True, inline="always")
def race_coefficients(table, cos_alpha):
    """(κ, S [m^0.5], A, B [m^(2/3)], film ellipticity factor, rolling ellipticity logarithm) of
    the race tabulated in ``table`` (:func:`race_table`) at c = ``cos_alpha``: K = S E',
    a = A (Q/E')^(1/3), b = B (Q/E')^(1/3). NaN outside 0 <= c <= 1 (and for a NaN c)."""
    if not (0.0 <= cos_alpha <= 1.0):
        return math.nan, math.nan, math.nan, math.nan, math.nan, math.nan
    n = table.shape[1]
    h = 1.0 / (n - 1)
    i, h00, h10, h01, h11 = hermite_cell(cos_alpha * (n - 1), n)
    h10 *= h
    h11 *= h
    t = table
    d = N_ROWS
    return (
        h00 * t[0, i] + h10 * t[d, i] + h01 * t[0, i + 1] + h11 * t[d, i + 1],
        h00 * t[1, i] + h10 * t[d + 1, i] + h01 * t[1, i + 1] + h11 * t[d + 1, i + 1],
        h00 * t[2, i] + h10 * t[d + 2, i] + h01 * t[2, i + 1] + h11 * t[d + 2, i + 1],
        h00 * t[3, i] + h10 * t[d + 3, i] + h01 * t[3, i + 1] + h11 * t[d + 3, i + 1],
        h00 * t[4, i] + h10 * t[d + 4, i] + h01 * t[4, i + 1] + h11 * t[d + 4, i + 1],
        h00 * t[5, i] + h10 * t[d + 5, i] + h01 * t[5, i + 1] + h11 * t[d + 5, i + 1],
    )
