"""Lubricant rheology of an EHL contact: local shear stress from pressure, film and slip (SI units).

physics.md §2.6.4 ("how a rheological law is usually assembled, node by node"). At a point of the
Hertz ellipse with local pressure p and sliding speed u:

1. viscosity at the inlet temperature and local pressure, Barus: eta = eta_0 exp(alpha p), with the
   exponent capped at ``BARUS_EXPONENT_CAP`` (Barus over-predicts above ~1 GPa; the cap only keeps
   the number finite, the limiting shear stress below governs there);
2. shear rate over the central film, gamma_dot = u / h_c (h_c: Hamrock–Dowson, reduced for inlet
   shear heating by :func:`inlet_thermal_factor`);
3. viscous (Eyring) stress tau_v = tau_0 asinh(eta gamma_dot / tau_0) [Johnson & Tevaarwerk, Proc.
   R. Soc. A 356 (1977) 215];
4. elastic stress the film reaches in its transit through the contact, tau_e = G gamma_dot t with t
   = b / u_e (the Maxwell response that governs the linear region at small slide-to-roll ratio,
   Johnson & Tevaarwerk 1977); viscous and elastic responses act in series, combined here as
   tau_ve = tau_v tau_e / (tau_v + tau_e) [E: a closed-form stand-in for integrating the Maxwell
   equation along the transit];
5. limiting shear stress tau_L = tau_L0 + Lambda p [Bair & Winer, J. Lubr. Technol. 101 (1979)
   251], approached smoothly: tau = tau_ve / sqrt(1 + (tau_ve / tau_L)^2).

So tau is linear in u at small slip (slope eta_eff / h_c with eta_eff = eta G t / (eta + G t)),
grows like a logarithm in the Eyring range, and levels off at tau_L. Dividing by p gives the
local traction coefficient. The law is odd in u and vanishes at u = 0 (no regularisation needed).

Rheology parameter array ``rheology`` (float64, length ``RHEOLOGY_SIZE``):
``RH_VISCOSITY`` eta_0 [Pa s] at the inlet temperature; ``RH_PRESSURE_VISCOSITY`` alpha [1/Pa];
``RH_EYRING_STRESS`` tau_0 [Pa]; ``RH_LIMITING_STRESS`` tau_L0 [Pa]; ``RH_LIMITING_SLOPE`` Lambda
[-]; ``RH_SHEAR_MODULUS`` G [Pa]; ``RH_TEMPERATURE_VISCOSITY`` beta [1/K] (for the thermal film
reduction); ``RH_CONDUCTIVITY`` k [W/(m K)].
"""

from __future__ import annotations

import math

from numba import njit

RH_VISCOSITY = 0
RH_PRESSURE_VISCOSITY = 1
RH_EYRING_STRESS = 2
RH_LIMITING_STRESS = 3
RH_LIMITING_SLOPE = 4
RH_SHEAR_MODULUS = 5
RH_TEMPERATURE_VISCOSITY = 6
RH_CONDUCTIVITY = 7
RHEOLOGY_SIZE = 8

#: Largest Barus exponent alpha p used (e^60 ~ 1e26): keeps eta finite at any pressure.
BARUS_EXPONENT_CAP = 60.0


def viscosity_at_temperature(
    reference_viscosity: float,
    reference_temperature: float,
    temperature_viscosity: float,
    temperature: float,
) -> float:
    """Dynamic viscosity [Pa s] at ``temperature`` [degC] from the viscosity at the reference
    temperature and the temperature-viscosity coefficient beta [1/K] (Reynolds' exponential law,
    eta = eta_ref exp(-beta (T - T_ref)))."""
    return reference_viscosity * math.exp(
        -temperature_viscosity * (temperature - reference_temperature)
    )


@njit(cache=True)
def barus_viscosity(viscosity, pressure_viscosity, pressure):
    """eta_0 exp(alpha p) [Pa s], exponent capped at ``BARUS_EXPONENT_CAP``; p <= 0 gives eta_0."""
    x = pressure_viscosity * pressure
    if x <= 0.0:
        return viscosity
    return viscosity * math.exp(min(x, BARUS_EXPONENT_CAP))


@njit(cache=True)
def shear_stress(slip_speed, pressure, film, transit_time, rheology):
    """Magnitude of the film's shear stress [Pa] (>= 0) at sliding speed |u| [m/s], local pressure
    p [Pa], central film h_c [m] and transit time t = b / u_e [s] (module docstring). ``film`` <= 0
    (no film: no entrainment) gives the limiting shear stress for any slip above 1e-9 m/s."""
    u = abs(slip_speed)
    if u <= 0.0:
        return 0.0
    p = max(pressure, 0.0)
    tau_l = rheology[RH_LIMITING_STRESS] + rheology[RH_LIMITING_SLOPE] * p
    if film <= 0.0:
        return tau_l if u > 1e-9 else 0.0
    rate = u / film
    eta = barus_viscosity(rheology[RH_VISCOSITY], rheology[RH_PRESSURE_VISCOSITY], p)
    tau0 = rheology[RH_EYRING_STRESS]
    x = eta * rate / tau0
    tau_v = tau0 * math.log(x + math.sqrt(x * x + 1.0))  # tau_0 asinh(x)
    tau_e = rheology[RH_SHEAR_MODULUS] * rate * transit_time
    tau = tau_v * tau_e / (tau_v + tau_e) if transit_time > 0.0 else tau_v
    r = tau / tau_l
    return tau / math.sqrt(1.0 + r * r)


@njit(cache=True)
def inlet_thermal_factor(
    entrainment, slide_to_roll, viscosity, temperature_viscosity, conductivity, p_max, eprime
):
    """Film reduction factor phi_T <= 1 for inlet shear heating [Gupta, Cheng, Zhu, Forster &
    Schrand, J. Tribol. 114 (1992) 1-6] [M]:
    phi_T = (1 - 13.2 (p_h / E') L^0.42) / (1 + 0.213 (1 + 2.23 SRR^0.83) L^0.64),
    thermal loading L = beta eta_0 u_e^2 / k. Clipped to [0.05, 1]."""
    if not (conductivity > 0.0 and temperature_viscosity > 0.0):
        return 1.0
    load = temperature_viscosity * viscosity * entrainment * entrainment / conductivity
    if load <= 0.0:
        return 1.0
    srr = abs(slide_to_roll)
    num = 1.0 - 13.2 * (p_max / eprime) * load**0.42
    den = 1.0 + 0.213 * (1.0 + 2.23 * srr**0.83) * load**0.64
    return min(1.0, max(0.05, num / den))


@njit(cache=True)
def ehl_rolling_force(entrainment, viscosity, pressure_viscosity, eprime, r_x, load, kappa):
    """Hydrodynamic (EHL) rolling resistance force [N] of the inlet, isothermal
    [Houpert, "Hydrodynamic load calculation in rolling element bearings", Tribol. Trans. 1999;
    form quoted by Harris & Kotzalas, Advanced Concepts of Bearing Technology, 2007] [M]:
    F_R = 2.86 E' R_x^2 kappa^0.348 G^0.022 U^0.66 W^0.47,
    U = eta_0 u_e / (E' R_x), G = alpha E', W = Q / (E' R_x^2). Zero without speed or load."""
    u = abs(entrainment)
    if not (u > 0.0 and load > 0.0 and viscosity > 0.0 and r_x > 0.0):
        return 0.0
    big_u = viscosity * u / (eprime * r_x)
    big_g = pressure_viscosity * eprime
    big_w = load / (eprime * r_x * r_x)
    return 2.86 * eprime * r_x * r_x * kappa**0.348 * big_g**0.022 * big_u**0.66 * big_w**0.47
