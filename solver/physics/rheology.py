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
   251], approached smoothly: tau = tau_ve / (1 + (tau_ve / tau_L)^4)^(1/4) [E: a smooth minimum,
   within 1 % of tau_L once tau_ve > 2.2 tau_L, never above it].

6. thermal softening (shear heating of the film): the stress of steps 1-5, tau_iso, is taken at
   the inlet temperature. Sliding heats the film: with the dissipation tau u / h_c spread evenly
   across the film and conducted to both surfaces, held at the inlet temperature, the mid-film
   temperature rises by dT = tau u h_c / (8 k) (steady one-dimensional conduction, k the oil's
   conductivity) [D; the mid-film temperature is the one that governs the traction of an Eyring
   film: Johnson & Greenwood, Wear 61 (1980) 353]. The film's stress falls with temperature as
   its limiting shear stress does, linearly about the inlet, tau(T_in + dT) = tau_iso (1 - c dT)
   (c = ``RH_SOFTENING``, the temperature coefficient of tau_L). Solving both together gives
   tau = tau_iso / (1 + c tau_iso u h_c / (8 k)) (:func:`thermal_softening`): 1 at c = 0 (the
   isothermal law exactly), and tau ~ 8 k / (c u h_c) at large slip, so the traction curve
   peaks and falls. The surfaces' own flash temperature is not added (it would soften more).

So tau is linear in u at small slip (slope eta_eff / h_c with eta_eff = eta G t / (eta + G t)),
grows like a logarithm in the Eyring range, and levels off at tau_L, then falls as the film heats
(step 6). Dividing by p gives the local traction coefficient. The law is odd in u and vanishes at
u = 0 (no regularisation needed).

The parameters are those of the inlet temperature: :func:`rheology_at_temperature` takes the
values a case gives at its reference temperature to the inlet (docs/traction.md).

Rheology parameter array ``rheology`` (float64, length ``RHEOLOGY_SIZE``), values at the inlet
temperature: ``RH_VISCOSITY`` eta_0 [Pa s]; ``RH_PRESSURE_VISCOSITY`` alpha [1/Pa];
``RH_EYRING_STRESS`` tau_0 [Pa]; ``RH_LIMITING_STRESS`` tau_L0 [Pa]; ``RH_LIMITING_SLOPE`` Lambda
[-]; ``RH_SHEAR_MODULUS`` G [Pa]; ``RH_TEMPERATURE_VISCOSITY`` beta [1/K] (for the thermal film
reduction); ``RH_CONDUCTIVITY`` k [W/(m K)]; ``RH_SOFTENING`` c [1/K], the thermal softening
coefficient of step 6 (0: no softening, the isothermal law).
"""

from __future__ import annotations

import math

from numba import njit

from .ehl import W_FLOOR
from .lanes import exp_lanes, log_lanes

RH_VISCOSITY = 0
RH_PRESSURE_VISCOSITY = 1
RH_EYRING_STRESS = 2
RH_LIMITING_STRESS = 3
RH_LIMITING_SLOPE = 4
RH_SHEAR_MODULUS = 5
RH_TEMPERATURE_VISCOSITY = 6
RH_CONDUCTIVITY = 7
RH_SOFTENING = 8
RHEOLOGY_SIZE = 9

#: Zero of the Celsius scale [K] (the Eyring stress is proportional to the absolute temperature).
CELSIUS_ZERO = 273.15

#: Largest Barus exponent alpha p used (e^60 ~ 1e26): keeps eta finite at any pressure.
BARUS_EXPONENT_CAP = 60.0

#: Entrainment speed u_min [m/s] below which the dynamic model's contacts keep the film and the
#: film's transit time of u_min (solver.models.dynamic.kernels; docs/numerics.md, "Low
#: entrainment speed"). As u_e -> 0 the film h_c ~ u_e^0.67 and the transit time b / u_e make
#: the rheology's stress a Coulomb law at tau_L whose slope against slip, ~ G t / h_c, grows
#: without bound (at rest the film law has no film and jumps at zero slip), which no integrator
#: steps through. Below about 1 m/s the film is no thicker than the surfaces are rough (209 case,
#: 500 N: h_c = 85 nm at 1 m/s, 18 nm at 0.1 m/s), so the contact runs in mixed or boundary
#: lubrication, where the film's rheology is no longer the law; the law frozen at u_min acts
#: there as boundary friction at about the limiting shear stress (mu = 0.065 for that contact),
#: reached within about 1 cm/s of slip (half of it at 11 mm/s). Every shipped dynamic case runs
#: at entrainment speeds above 7 m/s, where nothing changes.
ENTRAINMENT_FLOOR = 1.0


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


def exponential_temperature_law(
    reference_value: float, reference_temperature: float, coefficient: float, temperature: float
) -> float:
    """reference_value exp(-coefficient (T - T_ref)): a property that falls by the fraction
    ``coefficient`` [1/K] per kelvin (temperatures in degC)."""
    return reference_value * math.exp(-coefficient * (temperature - reference_temperature))


def rheology_at_temperature(
    reference_temperature: float,
    temperature: float,
    *,
    viscosity: float,
    temperature_viscosity: float,
    pressure_viscosity: float,
    pressure_viscosity_temperature: float,
    eyring_stress: float,
    limiting_stress: float,
    limiting_slope: float,
    limiting_temperature: float,
    shear_modulus: float,
    shear_modulus_temperature: float,
) -> dict:
    """The rheology's parameters at ``temperature`` [degC] from their values at
    ``reference_temperature`` [degC] (SI; keys as the arguments):

    - viscosity eta_0 exp(-beta dT) (:func:`viscosity_at_temperature`, Reynolds);
    - pressure-viscosity alpha exp(-c_alpha dT) (the coefficient falls with temperature, e.g. by
      0.74-0.79 %/K for the spindle oils of Stachowiak & Batchelor's Table 2.3);
    - Eyring stress tau_0 T / T_ref in absolute temperature (Eyring's theory: tau_0 = k_B T / V,
      V the activation volume; Eyring, J. Chem. Phys. 4 (1936) 283);
    - limiting shear stress (tau_L0 and Lambda) exp(-c_L dT) (Lambda depends on temperature:
      Wikstrom & Hoglund, J. Tribol. 116 (1994) 612; it falls by 0.52 %/K for Santotrac 50 in the
      linear correlation of Delkhosh et al. quoted in docs/sources.md);
    - film shear modulus G exp(-c_G dT) (G and tau_L rise together with pressure, their ratio
      nearly constant: "The elastic properties of films in e.h.l. contacts", Proc. R. Soc. Lond.
      A 372 (1980) 155; the named oils take c_G = c_L, an estimate).

    With ``temperature`` = ``reference_temperature`` every value is returned unchanged."""
    dt = temperature - reference_temperature
    limiting = math.exp(-limiting_temperature * dt)
    return {
        "viscosity": viscosity_at_temperature(
            viscosity, reference_temperature, temperature_viscosity, temperature
        ),
        "pressure_viscosity": exponential_temperature_law(
            pressure_viscosity, reference_temperature, pressure_viscosity_temperature, temperature
        ),
        "eyring_stress": eyring_stress
        * (temperature + CELSIUS_ZERO)
        / (reference_temperature + CELSIUS_ZERO),
        "limiting_stress": limiting_stress * limiting,
        "limiting_slope": limiting_slope * limiting,
        "shear_modulus": exponential_temperature_law(
            shear_modulus, reference_temperature, shear_modulus_temperature, temperature
        ),
    }


#: Above this x = eta gamma_dot / tau_0 the Eyring law uses asinh(x) = ln(2 x) (relative error
#: below 4e-8), which needs no exponential of the Barus exponent.
_ASINH_LOG_FROM = 1.0e3
_LN_ASINH_LOG_FROM = math.log(_ASINH_LOG_FROM)
_LN2 = math.log(2.0)
#: ln x above which the Eyring law's asinh(x) is ln(2 x) (:func:`eyring_asinh_large`).
EYRING_LARGE_FROM = _LN_ASINH_LOG_FROM


#: From this x on, :func:`eyring_asinh` uses the series of asinh(x) in 1/x^2 (five terms,
#: relative error below 1e-7).
_ASINH_SERIES_FROM = 3.0
_LN_ASINH_SERIES_FROM = math.log(_ASINH_SERIES_FROM)


@njit(cache=True, inline="always")
def eyring_asinh(ln_x):
    """asinh(x) from ln x: ln(2x) above x = 1e3 (:func:`eyring_asinh_large`); ln(2x) + sum_n
    (-1)^(n-1) (2n-1)!! / (2n (2n)!!) x^(-2n), n = 1..5, above x = 3 (one exponential, no
    logarithm); the closed form below."""
    if ln_x > EYRING_LARGE_FROM:
        return eyring_asinh_large(ln_x)
    if ln_x > _LN_ASINH_SERIES_FROM:
        w = math.exp(-2.0 * ln_x)
        series = w * (
            0.25 - w * (0.09375 - w * (0.052083333333333336 - w * (0.0341796875 - w * 0.024609375)))
        )
        return _LN2 + ln_x + series
    return math.asinh(math.exp(ln_x))  # accurate also for x -> 0 (Newtonian limit)


@njit(cache=True, inline="always")
def eyring_asinh_large(ln_x):
    """asinh(x) = ln(2 x) from ln x, for ln x > ``EYRING_LARGE_FROM`` (relative error below
    4e-8): no library call, so a loop that calls it vectorises."""
    return _LN2 + ln_x


@njit(cache=True, inline="always")
def eyring_log_argument(ln_u, alpha_p, ln_c):
    """ln x of the Eyring law's argument x = eta gamma_dot / tau_0 at slip speed u (``ln_u`` = ln
    u [ln(m/s)]), Barus exponent ``alpha_p`` = alpha p (capped at ``BARUS_EXPONENT_CAP``) and the
    per-contact ``ln_c`` = ln(eta_0 / (tau_0 h_c)) of :func:`contact_constants`."""
    # min(alpha_p, cap) written as a selection: numba's min() stops the loop vectoriser
    return ln_c + ln_u + (BARUS_EXPONENT_CAP if BARUS_EXPONENT_CAP < alpha_p else alpha_p)


@njit(cache=True)
def contact_constants(film, transit_time, rheology):
    """Per-contact constants of :func:`shear_stress_from_constants`: (ln(eta_0 / (tau_0 h_c)),
    G t / h_c [Pa s/m]). ``film`` must be > 0."""
    ln_c = math.log(rheology[RH_VISCOSITY] / (rheology[RH_EYRING_STRESS] * film))
    return ln_c, rheology[RH_SHEAR_MODULUS] * transit_time / film


#: Largest elastic stress G gamma_dot t [Pa] used by :func:`stress_over_slip` (~ 1e30: keeps the
#: fourth powers there finite when the entrainment, and so the film, vanishes; far above any
#: limiting shear stress, so the result is unchanged).
_ELASTIC_STRESS_CAP = 1.0e30


@njit(cache=True, inline="always")
def saturation_over_slip(u, ln_u, alpha_p, tau_l, ln_c, elastic, tau_0):
    """s / u [s/m], s = tau / tau_L the saturation (in [0, 1)) of :func:`shear_stress` at slip
    speed u > 0 [m/s] (``ln_u`` = ln u), with the node's Barus exponent ``alpha_p`` = alpha p,
    limiting shear stress ``tau_l`` = tau_L0 + Lambda p [Pa], the per-contact constants of
    :func:`contact_constants` and the Eyring stress ``tau_0`` [Pa]: one logarithm, two square
    roots and one division (0 where that division would be by zero: no limiting or viscous
    stress). The traction kernel's vectorised node loop composes the same pieces
    (:func:`eyring_log_argument`, :func:`eyring_asinh_large` or :func:`eyring_asinh`,
    :func:`saturation_from_eyring`).

    With tau_v the Eyring stress and tau_e = E u (E = ``elastic``), the series combination
    tau_ve = N / D (N = tau_v E u, D = tau_v + E u) and the smooth limit tau = tau_ve tau_L /
    (tau_L^4 + tau_ve^4)^(1/4) give s / u = tau_v E / ((tau_L D)^4 + N^4)^(1/4).
    """
    return saturation_from_eyring(
        u, tau_0 * eyring_asinh(eyring_log_argument(ln_u, alpha_p, ln_c)), tau_l, elastic
    )


@njit(cache=True, inline="always")
def saturation_from_eyring(u, tau_v, tau_l, elastic):
    """s / u [s/m] of :func:`saturation_over_slip` from the node's Eyring stress ``tau_v`` =
    tau_0 asinh(x) [Pa], at slip speed u > 0 [m/s], limiting shear stress ``tau_l`` [Pa] and the
    per-contact ``elastic`` = G t / h_c [Pa s/m] (formula there)."""
    if elastic > 0.0:
        eu = elastic * u
        eu = _ELASTIC_STRESS_CAP if _ELASTIC_STRESS_CAP < eu else eu  # min(), vectorisable
        ld = tau_l * (tau_v + eu)
        n = tau_v * eu
        ld2 = ld * ld
        n2 = n * n
        den = u * math.sqrt(math.sqrt(ld2 * ld2 + n2 * n2))
        return tau_v * eu / den if den > 0.0 else 0.0
    l2 = tau_l * tau_l
    v2 = tau_v * tau_v
    den = u * math.sqrt(math.sqrt(l2 * l2 + v2 * v2))
    return tau_v / den if den > 0.0 else 0.0


@njit(cache=True, inline="always")
def stress_over_slip(u, ln_u, alpha_p, tau_l, ln_c, elastic, tau_0):
    """tau / u [Pa s/m] of :func:`shear_stress`: tau_L times :func:`saturation_over_slip` (same
    arguments)."""
    return tau_l * saturation_over_slip(u, ln_u, alpha_p, tau_l, ln_c, elastic, tau_0)


@njit(cache=True, inline="always")
def softening_constant(film, rheology):
    """c h_c / (8 k) [m^2/W] of :func:`thermal_softening` for the central film ``film`` [m]: the
    softening coefficient times the film's mid-plane thermal resistance (0 without softening,
    conductivity or film)."""
    c = rheology[RH_SOFTENING]
    k = rheology[RH_CONDUCTIVITY]
    return c * film / (8.0 * k) if (c > 0.0 and k > 0.0 and film > 0.0) else 0.0


@njit(cache=True, inline="always")
def thermal_softening(heating, stress_power):
    """Factor 1 / (1 + c dT_iso) <= 1 of the film's stress for shear heating (module docstring,
    step 6): ``heating`` = c h_c / (8 k) [m^2/W] (:func:`softening_constant`) times
    ``stress_power`` = tau_iso u [W/m^2], the isothermal stress times the slip speed. 1 for
    ``heating`` = 0."""
    return 1.0 / (1.0 + heating * stress_power)


@njit(cache=True, inline="always")
def shear_stress_from_constants(u, pressure, ln_c, elastic, rheology, heating=0.0):
    """:func:`shear_stress` for u > 0 with the per-contact constants of
    :func:`contact_constants` (through :func:`stress_over_slip`) and ``heating`` of
    :func:`softening_constant` (0: isothermal)."""
    p = max(pressure, 0.0)
    tau = u * stress_over_slip(
        u,
        math.log(u),
        rheology[RH_PRESSURE_VISCOSITY] * p,
        rheology[RH_LIMITING_STRESS] + rheology[RH_LIMITING_SLOPE] * p,
        ln_c,
        elastic,
        rheology[RH_EYRING_STRESS],
    )
    return tau * thermal_softening(heating, tau * u)


@njit(cache=True)
def shear_stress(slip_speed, pressure, film, transit_time, rheology):
    """Magnitude of the film's shear stress [Pa] (>= 0) at sliding speed |u| [m/s], local pressure
    p [Pa], central film h_c [m] and transit time t = b / u_e [s] (module docstring, steps 1-6).
    ``film`` <= 0 (no film: no entrainment) gives the limiting shear stress for any slip above
    1e-9 m/s (no film to heat)."""
    u = abs(slip_speed)
    if u <= 0.0:
        return 0.0
    p = max(pressure, 0.0)
    if film <= 0.0:
        tau_l = rheology[RH_LIMITING_STRESS] + rheology[RH_LIMITING_SLOPE] * p
        return tau_l if u > 1e-9 else 0.0
    ln_c, elastic = contact_constants(film, transit_time, rheology)
    return shear_stress_from_constants(
        u, p, ln_c, elastic, rheology, softening_constant(film, rheology)
    )


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


@njit(cache=True)
def film_ellipticity_factor(kappa):
    """The ellipticity factor 1 - 0.61 exp(-0.73 kappa) of the Hamrock–Dowson central film."""
    return 1.0 - 0.61 * math.exp(-0.73 * kappa)


@njit(cache=True)
def rolling_ellipticity_log(kappa):
    """ln(kappa^0.348): the ellipticity term of :func:`ehl_rolling_force`, as a logarithm."""
    return 0.348 * math.log(kappa)


@njit(cache=True)
def film_and_rolling_force(entrainment, slide_to_roll, load, r_x, kappa, p_max, eprime, rheology):
    """(central film h_c [m], thermal factor phi_T, EHL rolling force [N]) of one contact in one
    pass: Hamrock–Dowson h_c (solver.physics.ehl.film_thickness_central, same W floor) and
    :func:`ehl_rolling_force`, both times :func:`inlet_thermal_factor`, with the power laws
    evaluated through shared logarithms (the per-contact cost in the dynamic model). Viscosity and
    pressure-viscosity from ``rheology``. No speed or load: (0, 1, 0)."""
    return film_and_rolling_from_factors(
        entrainment,
        slide_to_roll,
        load,
        r_x,
        film_ellipticity_factor(kappa),
        rolling_ellipticity_log(kappa),
        p_max,
        eprime,
        rheology,
    )


@njit(cache=True, inline="always")
def film_and_rolling_from_factors(
    entrainment, slide_to_roll, load, r_x, film_factor, rolling_log, p_max, eprime, rheology
):
    """:func:`film_and_rolling_force` with the ellipticity's two terms given:
    ``film_factor`` = :func:`film_ellipticity_factor` and ``rolling_log`` =
    :func:`rolling_ellipticity_log` of kappa (the dynamic model tabulates them per race against
    the contact angle, solver.physics.hertz_race). One contact of :func:`film_and_rolling_lanes`."""
    return film_and_rolling_lanes(
        entrainment,
        slide_to_roll,
        load,
        r_x,
        film_factor,
        rolling_log,
        p_max,
        eprime,
        film_law_constants(rheology, eprime),
    )


@njit(cache=True, inline="always")
def film_law_constants(rheology, eprime):
    """The film and rolling-force laws' terms that are the same at every contact of a bearing:
    (ln(alpha E'), ln(eta_0 / E'), ln(beta eta_0 / k), thermal reduction on, viscosity and
    pressure-viscosity positive), for :func:`film_and_rolling_lanes` (``eprime`` E' [Pa])."""
    eta = rheology[RH_VISCOSITY]
    alpha = rheology[RH_PRESSURE_VISCOSITY]
    beta = rheology[RH_TEMPERATURE_VISCOSITY]
    k = rheology[RH_CONDUCTIVITY]
    viscous = eta > 0.0 and alpha > 0.0
    thermal = beta > 0.0 and k > 0.0
    return (
        math.log(alpha * eprime) if viscous else 0.0,
        math.log(eta / eprime) if viscous else 0.0,
        math.log(beta * eta / k) if thermal and viscous else 0.0,
        thermal,
        viscous,
    )


@njit(cache=True, inline="always")
def film_and_rolling_lanes(
    entrainment, slide_to_roll, load, r_x, film_factor, rolling_log, p_max, eprime, constants
):
    """(central film h_c [m], thermal factor phi_T, EHL rolling force [N]) of one contact, as
    :func:`film_and_rolling_force` (``constants`` of :func:`film_law_constants`), in a form that
    vectorises when a loop calls it for several contacts: exp and log of solver.physics.lanes (the
    power laws through shared logarithms), selections instead of branches. No speed or load, or no
    viscosity: (0, 1, 0)."""
    ln_g, ln_eta_e, ln_thermal, thermal, viscous = constants
    u = abs(entrainment)
    ln_speed = log_lanes(u)
    ln_rx = log_lanes(r_x)
    ln_u = ln_eta_e + ln_speed - ln_rx  # ln U = ln(eta_0 u_e / (E' R_x))
    w = load / (eprime * r_x * r_x)
    ln_w = log_lanes(W_FLOOR if W_FLOOR > w else w)  # max(), vectorisable
    film = 2.69 * r_x * exp_lanes(0.67 * ln_u + 0.53 * ln_g - 0.067 * ln_w) * film_factor
    ln_rolling = rolling_log + 0.022 * ln_g + 0.66 * ln_u + 0.47 * ln_w
    rolling = 2.86 * eprime * r_x * r_x * exp_lanes(ln_rolling)
    # inlet shear heating (inlet_thermal_factor), thermal loading L = beta eta_0 u_e^2 / k
    ln_l = ln_thermal + 2.0 * ln_speed
    srr = abs(slide_to_roll)
    s83 = exp_lanes(0.83 * log_lanes(srr))
    s83 = s83 if srr > 0.0 else 0.0
    num = 1.0 - 13.2 * (p_max / eprime) * exp_lanes(0.42 * ln_l)
    den = 1.0 + 0.213 * (1.0 + 2.23 * s83) * exp_lanes(0.64 * ln_l)
    phi = num / den
    phi = 1.0 if phi > 1.0 else phi
    phi = 0.05 if 0.05 > phi else phi
    phi = phi if thermal else 1.0
    live = viscous & (u > 0.0) & (load > 0.0) & (r_x > 0.0)
    return (film * phi if live else 0.0), (phi if live else 1.0), (rolling * phi if live else 0.0)
