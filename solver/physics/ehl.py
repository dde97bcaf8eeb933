"""Isothermal elastohydrodynamic film thickness of a ball-race contact (Hamrock-Dowson), SI units.

physics.md §2.6.4 [Hamrock & Dowson, "Isothermal elastohydrodynamic lubrication of point contacts",
Parts I-III, ASME J. Lubr. Technol. 1976-77]:

    h_c   / R_x = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 e^(-0.73 κ))
    h_min / R_x = 3.63 U^0.68 G^0.49 W^-0.073 (1 - e^(-0.68 κ))

with U = η0 u_e / (E' R_x) (speed), G = α_p E' (material), W = Q / (E' R_x²) (load), κ = a/b.
Inputs: entrainment (rolling) speed u_e [m/s] (its magnitude is used), dynamic viscosity η0 [Pa s],
pressure-viscosity coefficient α_p [1/Pa], effective modulus E' = 2/η [Pa], R_x [m] (equivalent
radius in the rolling direction), normal load Q [N], ellipticity κ [-].

Edge behaviour (numba functions never raise):
* u_e = 0 (or η0 ≤ 0, or α_p ≤ 0) → h = 0 (no entrainment, no film).
* Load: W is floored at ``W_FLOOR`` = 1e-9 (Q ≤ W_FLOOR E' R_x², including Q ≤ 0, all use the film
  at W_FLOOR) because W^-0.067 diverges as Q → 0. W_FLOOR is ~2-3 decades below the loads of real
  ball-race contacts (W ~ 1e-7-1e-5) and the film there is only ~1.6× that at W = 1e-6: a finite,
  documented cap for unloaded balls, not a prediction (the regression is fitted for W ≈ 1e-7-1e-5).
* R_x ≤ 0, E' ≤ 0 or κ ≤ 0: h = 0 (invalid geometry; the plain wrapper raises instead).
"""

from __future__ import annotations

import math

from numba import njit

__all__ = [
    "W_FLOOR",
    "film_thickness_central",
    "film_thickness_minimum",
    "film_thickness",
]

W_FLOOR = 1.0e-9  # smallest dimensionless load W used in the film formulas


@njit(cache=True)
def _groups(u_e, viscosity, pressure_viscosity, effective_modulus, r_x, load):
    """(U, G, W) or (-1, -1, -1) when there is no film (zero speed or invalid inputs)."""
    speed = abs(u_e)
    if not (
        speed > 0.0
        and viscosity > 0.0
        and pressure_viscosity > 0.0
        and effective_modulus > 0.0
        and r_x > 0.0
    ):
        return -1.0, -1.0, -1.0
    u = viscosity * speed / (effective_modulus * r_x)
    g = pressure_viscosity * effective_modulus
    w = load / (effective_modulus * r_x * r_x)
    if not w > W_FLOOR:  # also catches NaN and negative loads
        w = W_FLOOR
    return u, g, w


@njit(cache=True)
def film_thickness_central(u_e, viscosity, pressure_viscosity, effective_modulus, r_x, load, kappa):
    """Hamrock-Dowson central film thickness h_c [m] (see module docstring for units and limits)."""
    u, g, w = _groups(u_e, viscosity, pressure_viscosity, effective_modulus, r_x, load)
    if u < 0.0 or not kappa > 0.0:
        return 0.0
    return 2.69 * r_x * u**0.67 * g**0.53 * w ** (-0.067) * (1.0 - 0.61 * math.exp(-0.73 * kappa))


@njit(cache=True)
def film_thickness_minimum(u_e, viscosity, pressure_viscosity, effective_modulus, r_x, load, kappa):
    """Hamrock-Dowson minimum film thickness h_min [m] (units and limits: module docstring)."""
    u, g, w = _groups(u_e, viscosity, pressure_viscosity, effective_modulus, r_x, load)
    if u < 0.0 or not kappa > 0.0:
        return 0.0
    return 3.63 * r_x * u**0.68 * g**0.49 * w ** (-0.073) * (1.0 - math.exp(-0.68 * kappa))


def film_thickness(
    u_e: float,
    viscosity: float,
    pressure_viscosity: float,
    effective_modulus: float,
    r_x: float,
    load: float,
    kappa: float,
) -> tuple[float, float]:
    """(h_c, h_min) [m] with input validation (plain Python wrapper of the numba functions).

    Raises ValueError naming the argument for NaN speed, viscosity ≤ 0, pressure_viscosity < 0,
    effective_modulus ≤ 0, r_x ≤ 0, negative or NaN load, or kappa < 1.
    """
    checks = (
        ("u_e", u_e, math.isfinite(u_e), "a finite speed in m/s"),
        ("viscosity", viscosity, viscosity > 0.0, "> 0 (Pa s)"),
        ("pressure_viscosity", pressure_viscosity, pressure_viscosity >= 0.0, ">= 0 (1/Pa)"),
        ("effective_modulus", effective_modulus, effective_modulus > 0.0, "> 0 (Pa)"),
        ("r_x", r_x, r_x > 0.0, "> 0 (m)"),
        ("load", load, load >= 0.0, ">= 0 (N)"),
        ("kappa", kappa, kappa >= 1.0, ">= 1 (ellipticity a/b)"),
    )
    for name, value, ok, allowed in checks:
        if not ok:
            raise ValueError(f"{name} = {value!r}: must be {allowed}")
    args = (u_e, viscosity, pressure_viscosity, effective_modulus, r_x, load, kappa)
    return film_thickness_central(*args), film_thickness_minimum(*args)
