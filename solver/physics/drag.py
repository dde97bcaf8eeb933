"""Drag of the oil-air mixture on the cage (pure numba kernel, SI units).

The cage's side faces are taken as a flat annulus (inner radius ``r_in``, outer radius ``r_out``)
turning about its axis at ``omega`` [rad/s] in a mixture at rest far from it. The moment on both
faces is that of von Karman's free rotating disc (Schlichting & Gersten, *Boundary-Layer Theory*,
free disc in a fluid at rest), with the moment coefficient of a full disc of radius R defined by

    M_disc = 1/2 C_M rho omega^2 R^5   (both faces),    Re = omega R^2 / nu,  nu = eta / rho

    laminar    C_M = 3.87 Re^(-1/2)   (exact similarity solution: wall shear ~ r)
    turbulent  C_M = 0.146 Re^(-1/5)  (1/7-power-law boundary layer: wall shear ~ r^(8/5))

Because the laminar wall shear grows as r and the turbulent one as r^(8/5), the moment of the
annulus is the disc's times (1 - k^4) (laminar) or (1 - k^(23/5)) (turbulent), k = r_in / r_out.
The larger of the two is taken (continuous; the turbulent branch wins above Re ~ 5.5e4 for the
full disc) [M]. Assumptions [E]: the mixture is a homogeneous Newtonian fluid with the mixture's
density and viscosity, at rest in the housing (as for the ball drag); the faces are unconfined
(no wall close by); the cage's cylindrical surfaces, pockets and the balls' wakes are not counted.
"""

from __future__ import annotations

import math

from numba import njit

#: a of the laminar and turbulent free-disc moment coefficients C_M = a Re^-n
LAMINAR_COEFFICIENT = 3.87
TURBULENT_COEFFICIENT = 0.146


def cage_drag_coefficients(density, viscosity, r_out, r_in):
    """(laminar, turbulent) coefficients of :func:`cage_drag_moment_from`, fixed for a mixture
    (``density`` [kg/m^3], ``viscosity`` [Pa s]) and the annular side faces (radii [m],
    0 <= r_in < r_out): with Re = rho omega R^2 / eta the two moments above become
    laminar 1/2 3.87 (1 - k^4) R^4 (rho eta)^1/2 omega^3/2 and
    turbulent 1/2 0.146 (1 - k^23/5) R^23/5 rho^4/5 eta^1/5 omega^9/5."""
    k = r_in / r_out
    laminar = 0.5 * LAMINAR_COEFFICIENT * (1.0 - k**4) * r_out**4 * math.sqrt(density * viscosity)
    turbulent = (
        0.5 * TURBULENT_COEFFICIENT * (1.0 - k**4.6) * r_out**4.6 * density**0.8 * viscosity**0.2
    )
    return laminar, turbulent


@njit(cache=True)
def cage_drag_moment_from(omega, laminar, turbulent):
    """Moment [N m] about the cage axis, opposing ``omega`` [rad/s], from the coefficients of
    :func:`cage_drag_coefficients`: -sign(omega) max(laminar |omega|^3/2,
    turbulent |omega|^9/5)."""
    w = abs(omega)
    if w == 0.0:
        return 0.0
    m = max(laminar * w * math.sqrt(w), turbulent * w**1.8)
    return -m if omega > 0.0 else m


@njit(cache=True)
def cage_drag_moment(omega, density, viscosity, r_out, r_in):
    """Moment [N m] of the mixture on the cage about its axis, opposing ``omega`` [rad/s]
    (relative to the mixture at rest). ``density`` [kg/m^3], ``viscosity`` [Pa s], radii [m] of
    the annular side faces (0 <= r_in < r_out). Zero at rest or with a zero density."""
    w = abs(omega)
    if w == 0.0 or density <= 0.0:
        return 0.0
    re = density * w * r_out * r_out / viscosity
    k = r_in / r_out
    scale = 0.5 * density * w * w * r_out**5
    lam = LAMINAR_COEFFICIENT / math.sqrt(re) * (1.0 - k**4)
    turb = TURBULENT_COEFFICIENT * re**-0.2 * (1.0 - k**4.6)
    m = scale * max(lam, turb)
    return -m if omega > 0.0 else m
