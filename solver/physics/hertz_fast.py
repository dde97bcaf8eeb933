"""Fast Hertz point contact for numba kernels (tabulated exact solution), SI units.

Scalar ``@njit(cache=True)`` functions, callable from other numba code, that reproduce
:mod:`solver.physics.hertz` (the exact solution) without root finding:

* ``hertz_coefficients_fast(F) -> (kappa, elliptic_k, elliptic_e)``
* ``contact_stiffness_fast(curvature_sum, F, effective_modulus) -> K`` [N/m^1.5]
* ``contact_ellipse_fast(load, curvature_sum, F, effective_modulus) -> (a, b, delta, p_max)``
* ``hertz_contact_fast(load, curvature_sum, F, effective_modulus) -> (a, b, delta, p_max, K)``
* ``curvature_sum_and_difference_fast(ball_diameter, conformity, gamma, is_inner) -> (Σρ, F)``
* ``equivalent_radii_fast(ball_diameter, conformity, gamma, is_inner) -> (R_x, R_y)``
* ``stiffness_from_coefficients`` / ``ellipse_from_coefficients``: the same from one table look-up

Method. The exact solution is tabulated once, at import, on a uniform grid of
x = ln(R_y/R_x) = 2 artanh F(ρ) over 0 ≤ x ≤ 10 (F from 0, the circle, to F_MAX = tanh 5 ≈ 0.99991,
i.e. R_y/R_x from 1 to 22 026; ball bearings use F ≈ 0.5-0.9995). Stored per node: ln κ, K(m), E(m)
and their slopes (from a not-a-knot cubic spline through the exact values); evaluation is the cubic
Hermite interpolant on the node interval, i.e. exactly that spline. The table is a module-level
read-only array (numba freezes it into the compiled code as a constant).

Measured accuracy (dense sweep: 200 001 points uniform in x plus two points inside every table
interval, against :func:`solver.physics.hertz.hertz_contact`; the test in
tests/unit/physics/test_hertz_fast.py repeats it):
max relative error 3.2e-12 in κ, 4.4e-13 in 𝒦, 1.7e-12 in ℰ, 2.2e-12 in a, 1.1e-12 in b,
1.7e-12 in δ, 1.1e-12 in p_max and 2.6e-12 in K over the whole table (0 ≤ F ≤ F_MAX), and
5.7e-13 for every output over the ball-bearing range 0.5 ≤ F ≤ 0.9995.
Stated (and tested) bound: **≤ 1e-10 relative** for every output, 0 ≤ F ≤ F_MAX.

The table is built from :mod:`solver.physics.hertz` at import (~50 ms) and frozen into the cached
machine code; numba's cache is keyed on this file only, so after changing the exact solver in
hertz.py, touch this file (the dense-sweep test catches a stale table).

Out-of-range behaviour (no exception, no NaN inside numba): F < 0 is clamped to 0 (the circular
contact); F > F_MAX (including F ≥ 1) is clamped to F_MAX, so κ, 𝒦, ℰ saturate at κ ≈ 373 — such
contacts (R_y/R_x > 22 000) do not occur with real conformities (f ≥ 0.5001). A NaN F gives NaN
outputs. ``load`` ≤ 0 (or NaN) gives a = b = δ = p_max = 0 (no tension). Non-positive Σρ or E' are
the caller's responsibility (the exact module validates them).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.interpolate import CubicSpline

from .hertz import ellipticity_exact

__all__ = [
    "X_MAX",
    "F_MAX",
    "TABLE_STEP",
    "hertz_coefficients_fast",
    "contact_stiffness_fast",
    "contact_ellipse_fast",
    "hertz_contact_fast",
    "curvature_sum_and_difference_fast",
    "equivalent_radii_fast",
]

X_MAX = 10.0  # upper end of the table in x = ln(R_y/R_x)
TABLE_STEP = 1.0 / 200.0  # uniform node spacing in x
_N_NODES = int(round(X_MAX / TABLE_STEP)) + 1
F_MAX = math.tanh(0.5 * X_MAX)  # F at the end of the table


def _build_table() -> np.ndarray:
    """(6, N) array: rows ln κ, 𝒦, ℰ at the nodes, then their slopes d/dx."""
    x = np.linspace(0.0, X_MAX, _N_NODES)
    kappa, big_k, big_e = ellipticity_exact(np.tanh(0.5 * x))
    values = np.vstack((np.log(kappa), big_k, big_e))
    slopes = np.vstack([CubicSpline(x, row, bc_type="not-a-knot")(x, 1) for row in values])
    table = np.ascontiguousarray(np.vstack((values, slopes)))
    table.flags.writeable = False
    return table


_TABLE = _build_table()
_INV_STEP = 1.0 / TABLE_STEP


@njit(cache=True, inline="always")
def hermite_cell(u, node_count):
    """Cell and cubic Hermite basis at ``u`` (in node spacings from the first of ``node_count``
    equally spaced nodes, u >= 0): (i, h00, h10, h01, h11), the value weights of nodes i and i + 1
    and their slope weights per node spacing (multiply those by the spacing). Beyond the last
    cell, the last cell's polynomial continues."""
    i = int(u)
    if i > node_count - 2:
        i = node_count - 2
    s = u - i
    s2 = s * s
    s3 = s2 * s
    return i, 2.0 * s3 - 3.0 * s2 + 1.0, s3 - 2.0 * s2 + s, -2.0 * s3 + 3.0 * s2, s3 - s2


@njit(cache=True)
def hertz_coefficients_fast(curvature_difference):
    """(κ, 𝒦, ℰ) for a curvature difference F(ρ) [-]: ellipticity a/b, complete elliptic integrals.

    Tabulated exact solution (see module docstring for accuracy and clamping of F outside
    [0, F_MAX]).
    """
    f = curvature_difference
    if f != f:
        return math.nan, math.nan, math.nan
    if f <= 0.0:
        x = 0.0
    elif f >= F_MAX:
        x = X_MAX
    else:
        x = 2.0 * math.atanh(f)
        if x > X_MAX:
            x = X_MAX
    i, h00, h10, h01, h11 = hermite_cell(x * _INV_STEP, _N_NODES)
    t = _TABLE
    h = TABLE_STEP
    log_kappa = h00 * t[0, i] + h10 * h * t[3, i] + h01 * t[0, i + 1] + h11 * h * t[3, i + 1]
    big_k = h00 * t[1, i] + h10 * h * t[4, i] + h01 * t[1, i + 1] + h11 * h * t[4, i + 1]
    big_e = h00 * t[2, i] + h10 * h * t[5, i] + h01 * t[2, i + 1] + h11 * h * t[5, i + 1]
    return math.exp(log_kappa), big_k, big_e


@njit(cache=True)
def stiffness_from_coefficients(kappa, big_k, big_e, curvature_sum, effective_modulus):
    """K [N/m^1.5] from the table's (kappa, K(m), E(m)) of ``hertz_coefficients_fast``."""
    return (
        math.pi
        * kappa
        * effective_modulus
        * math.sqrt(2.0 * big_e / (9.0 * curvature_sum * big_k * big_k * big_k))
    )


@njit(cache=True)
def contact_stiffness_fast(curvature_sum, curvature_difference, effective_modulus):
    """Load-deflection constant K [N/m^1.5] (Q = K δ^1.5) from Σρ [1/m], F [-], E' [Pa]."""
    kappa, big_k, big_e = hertz_coefficients_fast(curvature_difference)
    return stiffness_from_coefficients(kappa, big_k, big_e, curvature_sum, effective_modulus)


@njit(cache=True)
def ellipse_from_coefficients(load, kappa, big_k, big_e, curvature_sum, effective_modulus):
    """(a, b, delta, p_max) from the table's (kappa, K(m), E(m)), as ``contact_ellipse_fast``: a
    kernel that needs both the stiffness and the ellipse looks the table up once."""
    if not load > 0.0:
        return 0.0, 0.0, 0.0, 0.0
    r = 1.0 / curvature_sum
    qr = load * r
    c = np.cbrt(6.0 * big_e * qr / (math.pi * effective_modulus))
    k3 = np.cbrt(kappa)
    a = c * k3 * k3
    b = c / k3
    w = load / (math.pi * kappa * effective_modulus)
    delta = big_k * np.cbrt(4.5 / (big_e * r) * w * w)
    p_max = 1.5 * load / (math.pi * a * b)
    return a, b, delta, p_max


@njit(cache=True)
def contact_ellipse_fast(load, curvature_sum, curvature_difference, effective_modulus):
    """(a, b, δ, p_max): semi-major [m] (transverse), semi-minor [m] (rolling), approach [m] and
    peak pressure [Pa] for a normal load Q [N] (Q ≤ 0 → all zero), Σρ [1/m], F [-], E' [Pa]."""
    kappa, big_k, big_e = hertz_coefficients_fast(curvature_difference)
    return ellipse_from_coefficients(load, kappa, big_k, big_e, curvature_sum, effective_modulus)


@njit(cache=True)
def hertz_contact_fast(load, curvature_sum, curvature_difference, effective_modulus):
    """(a, b, δ, p_max, K) in one table look-up; units as in contact_ellipse_fast and
    contact_stiffness_fast."""
    kappa, big_k, big_e = hertz_coefficients_fast(curvature_difference)
    a, b, delta, p_max = ellipse_from_coefficients(
        load, kappa, big_k, big_e, curvature_sum, effective_modulus
    )
    return (
        a,
        b,
        delta,
        p_max,
        stiffness_from_coefficients(kappa, big_k, big_e, curvature_sum, effective_modulus),
    )


@njit(cache=True)
def curvature_sum_and_difference_fast(ball_diameter, conformity, gamma, is_inner):
    """(Σρ [1/m], F [-]) of a ball-race contact; D [m], f = r/D, γ = D cos α / d_m, is_inner: bool.

    Same closed forms as :func:`solver.physics.hertz.curvature_sum_and_difference` (no validation).
    """
    if is_inner:
        race_term = 2.0 * gamma / (1.0 - gamma)
    else:
        race_term = -2.0 * gamma / (1.0 + gamma)
    d_sum = 4.0 - 1.0 / conformity + race_term
    return d_sum / ball_diameter, (1.0 / conformity + race_term) / d_sum


@njit(cache=True)
def equivalent_radii_fast(ball_diameter, conformity, gamma, is_inner):
    """(R_x, R_y) [m]: R_x = (D/2)(1 ∓ γ) (− inner, + outer), R_y = f D / (2f − 1)."""
    if is_inner:
        r_x = 0.5 * ball_diameter * (1.0 - gamma)
    else:
        r_x = 0.5 * ball_diameter * (1.0 + gamma)
    return r_x, conformity * ball_diameter / (2.0 * conformity - 1.0)
