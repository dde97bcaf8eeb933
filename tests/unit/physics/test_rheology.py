"""Rheological traction law (solver.physics.rheology): limits, dependences and the film/rolling
force pass, each against an independent closed form written out here."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit

from solver.physics.ehl import W_FLOOR, film_thickness_central
from solver.physics.rheology import (
    BARUS_EXPONENT_CAP,
    RH_CONDUCTIVITY,
    RH_EYRING_STRESS,
    RH_LIMITING_SLOPE,
    RH_LIMITING_STRESS,
    RH_PRESSURE_VISCOSITY,
    RH_SHEAR_MODULUS,
    RH_TEMPERATURE_VISCOSITY,
    RH_VISCOSITY,
    RHEOLOGY_SIZE,
    ehl_rolling_force,
    film_and_rolling_force,
    film_and_rolling_lanes,
    film_ellipticity_factor,
    film_law_constants,
    inlet_thermal_factor,
    rolling_ellipticity_log,
    shear_stress,
    viscosity_at_temperature,
)


def rheology(eta=0.01, alpha=2.0e-8, tau0=5.0e6, tau_l0=2.0e6, slope=0.075, g=0.5e9):
    r = np.zeros(RHEOLOGY_SIZE)
    r[RH_VISCOSITY] = eta
    r[RH_PRESSURE_VISCOSITY] = alpha
    r[RH_EYRING_STRESS] = tau0
    r[RH_LIMITING_STRESS] = tau_l0
    r[RH_LIMITING_SLOPE] = slope
    r[RH_SHEAR_MODULUS] = g
    r[RH_TEMPERATURE_VISCOSITY] = 0.03
    r[RH_CONDUCTIVITY] = 0.13
    return r


def reference_stress(u, p, h, t, r):
    """Direct evaluation of the module's law (numpy, no shortcuts)."""
    eta = r[RH_VISCOSITY] * math.exp(min(r[RH_PRESSURE_VISCOSITY] * p, BARUS_EXPONENT_CAP))
    rate = u / h
    tau_v = r[RH_EYRING_STRESS] * np.arcsinh(eta * rate / r[RH_EYRING_STRESS])
    tau_e = r[RH_SHEAR_MODULUS] * rate * t
    tau = tau_v * tau_e / (tau_v + tau_e)
    tau_l = r[RH_LIMITING_STRESS] + r[RH_LIMITING_SLOPE] * p
    return tau / (1.0 + (tau / tau_l) ** 4) ** 0.25


H, T = 0.3e-6, 1.0e-5  # film [m], transit time b / u_e [s]


@pytest.mark.parametrize("p", [0.0, 0.3e9, 1.0e9, 2.0e9])
@pytest.mark.parametrize("u", [1e-6, 1e-3, 0.05, 1.0, 20.0])
def test_shear_stress_matches_direct_evaluation(u, p):
    r = rheology()
    assert shear_stress(u, p, H, T, r) == pytest.approx(reference_stress(u, p, H, T, r), rel=1e-7)


def test_linear_newtonian_response_at_low_slip():
    """At small slip tau = eta_eff u / h with eta_eff = eta G t / (eta + G t) (viscous and elastic
    in series): twice the slip gives twice the stress, and the slope is that of eta_eff."""
    r = rheology()
    p = 1.0e9
    eta = r[RH_VISCOSITY] * math.exp(r[RH_PRESSURE_VISCOSITY] * p)
    eta_eff = eta * r[RH_SHEAR_MODULUS] * T / (eta + r[RH_SHEAR_MODULUS] * T)
    u = 1e-9
    tau = shear_stress(u, p, H, T, r)
    assert tau == pytest.approx(eta_eff * u / H, rel=1e-6)
    assert shear_stress(2 * u, p, H, T, r) == pytest.approx(2 * tau, rel=1e-6)
    # a low pressure (Newtonian viscous, elastic negligible): tau = eta_0 u / h
    r_low = rheology(alpha=1e-12, g=1e15)
    assert shear_stress(1e-6, 0.0, H, T, r_low) == pytest.approx(0.01 * 1e-6 / H, rel=1e-6)


@pytest.mark.parametrize("p", [0.5e9, 1.0e9, 2.0e9])
def test_plateau_at_the_limiting_shear_stress(p):
    """Large slip: tau -> tau_L = tau_L0 + Lambda p (within 1 % once the Eyring stress is well
    above it: a stiff oil, tau_0 = 20 MPa), never above it."""
    r = rheology(tau0=20e6)
    tau_l = r[RH_LIMITING_STRESS] + r[RH_LIMITING_SLOPE] * p
    big = shear_stress(10.0, p, H, T, r)
    assert big == pytest.approx(tau_l, rel=0.01)
    speeds = np.logspace(-6, 2, 60)
    taus = np.array([shear_stress(u, p, H, T, r) for u in speeds])
    assert np.all(taus <= tau_l)
    assert np.all(np.diff(taus) > 0.0)  # monotone: no spurious peak


def test_stress_rises_with_pressure_and_viscosity():
    r = rheology()
    u = 0.5
    taus = [shear_stress(u, p, H, T, r) for p in (0.5e9, 1.0e9, 1.5e9, 2.0e9)]
    assert np.all(np.diff(taus) > 0.0)
    # in the viscous (Eyring) range a more viscous oil shears harder: a low-viscosity oil and a
    # compliant-free film (large G) so that the elastic response does not cap the stress
    thin, thick = rheology(eta=0.005, g=1e15), rheology(eta=0.05, g=1e15)
    p, u = 0.4e9, 1e-3
    assert shear_stress(u, p, H, T, thick) > 1.5 * shear_stress(u, p, H, T, thin)
    # the limiting shear stress coefficient sets the plateau
    high, low = rheology(tau0=20e6, slope=0.1), rheology(tau0=20e6, slope=0.075)
    assert shear_stress(10.0, 1e9, H, T, high) == pytest.approx(
        shear_stress(10.0, 1e9, H, T, low) * (2e6 + 0.1e9) / (2e6 + 0.075e9), rel=0.02
    )


def test_no_film_gives_the_limiting_stress_and_zero_slip_no_stress():
    r = rheology()
    assert shear_stress(0.0, 1e9, H, T, r) == 0.0
    assert shear_stress(0.1, 1e9, 0.0, T, r) == pytest.approx(2e6 + 0.075e9)


def test_viscosity_at_temperature():
    assert viscosity_at_temperature(0.03, 40.0, 0.03, 40.0) == pytest.approx(0.03)
    assert viscosity_at_temperature(0.03, 40.0, 0.03, 100.0) == pytest.approx(0.03 * math.exp(-1.8))


def test_film_and_rolling_force_pass_matches_the_separate_formulas():
    r = rheology(eta=0.02)
    args = dict(entrainment=12.0, load=300.0, r_x=4.0e-3, kappa=6.0, p_max=1.5e9, eprime=2.6e11)
    film, phi, rolling = film_and_rolling_force(
        args["entrainment"],
        0.02,
        args["load"],
        args["r_x"],
        args["kappa"],
        args["p_max"],
        args["eprime"],
        r,
    )
    h = film_thickness_central(
        args["entrainment"], 0.02, 2e-8, args["eprime"], args["r_x"], args["load"], args["kappa"]
    )
    f = ehl_rolling_force(
        args["entrainment"], 0.02, 2e-8, args["eprime"], args["r_x"], args["load"], args["kappa"]
    )
    phi_ref = inlet_thermal_factor(
        args["entrainment"], 0.02, 0.02, 0.03, 0.13, args["p_max"], args["eprime"]
    )
    assert 0.05 < phi_ref < 1.0
    assert phi == pytest.approx(phi_ref, rel=1e-12)
    assert film == pytest.approx(h * phi_ref, rel=1e-12)
    assert rolling == pytest.approx(f * phi_ref, rel=1e-12)
    # the rolling force grows like U^0.66 W^0.47 (Houpert): doubling speed x 2^0.66 isothermally
    f2 = ehl_rolling_force(24.0, 0.02, 2e-8, 2.6e11, 4.0e-3, 300.0, 6.0)
    assert f2 / f == pytest.approx(2.0**0.66, rel=1e-12)


@njit(cache=True)
def _films_in_one_loop(u, srr, load, r_x, kappa, p_max, eprime, r, out):
    """film_and_rolling_lanes over arrays in one loop (the dynamic model's film pass)."""
    constants = film_law_constants(r, eprime)
    for i in range(u.shape[0]):
        film, phi, rolling = film_and_rolling_lanes(
            u[i],
            srr[i],
            load[i],
            r_x[i],
            film_ellipticity_factor(kappa[i]),
            rolling_ellipticity_log(kappa[i]),
            p_max[i],
            eprime,
            constants,
        )
        out[0, i] = film
        out[1, i] = phi
        out[2, i] = rolling


@pytest.mark.parametrize("thermal", [True, False])
def test_film_pass_over_contacts_matches_the_separate_formulas(thermal):
    """The vectorisable form, called for many contacts in one loop (with edge cases: no speed, no
    load, no slide, a load below the W floor), gives the separate formulas' film, thermal factor
    and rolling force, and (0, 1, 0) where there is no speed or load."""
    r = rheology(eta=0.02)
    if not thermal:
        r[RH_CONDUCTIVITY] = 0.0
    rng = np.random.default_rng(3)
    m = 37  # not a multiple of the vector width: the loop's remainder is checked as well
    u = rng.uniform(1.0, 40.0, m)
    srr = rng.uniform(-0.2, 0.2, m)
    load = rng.uniform(20.0, 5000.0, m)
    r_x = rng.uniform(2e-3, 8e-3, m)
    kappa = rng.uniform(4.0, 11.0, m)
    p_max = rng.uniform(0.5e9, 2.5e9, m)
    u[3], load[5], srr[7], load[11] = 0.0, 0.0, 0.0, 1e-12
    eprime = 2.6e11
    out = np.empty((3, m))
    _films_in_one_loop(u, srr, load, r_x, kappa, p_max, eprime, r, out)
    for i in range(m):
        if u[i] == 0.0 or load[i] == 0.0:
            assert tuple(out[:, i]) == (0.0, 1.0, 0.0)
            continue
        args = (u[i], 0.02, 2e-8, eprime, r_x[i], load[i], kappa[i])
        # both laws use W at its floor below it (the rolling force's own formula does not)
        floor_load = W_FLOOR * eprime * r_x[i] ** 2
        rolling_args = (*args[:5], max(load[i], floor_load), kappa[i])
        phi = (
            inlet_thermal_factor(u[i], srr[i], 0.02, 0.03, 0.13, p_max[i], eprime)
            if thermal
            else 1.0
        )
        assert out[1, i] == pytest.approx(phi, rel=1e-12)
        assert out[0, i] == pytest.approx(film_thickness_central(*args) * phi, rel=1e-12)
        assert out[2, i] == pytest.approx(ehl_rolling_force(*rolling_args) * phi, rel=1e-12)


def test_named_oils_are_valid_lubricant_sections():
    """Every named oil is a [lubricant] section the case validation accepts, and its inlet
    viscosity at 40 degC is its ISO grade viscosity times its density."""
    import tomli_w

    from solver.case import parse_case
    from solver.lubricants import lubricant_table, oil_names
    from tests.helpers.cases import SPINDLE

    assert len(oil_names()) >= 3
    for name in oil_names():
        text = SPINDLE + "\n[lubricant]\n" + tomli_w.dumps(lubricant_table(name))
        case = parse_case(text)
        assert case.lubricant.traction_model == "rheology"
        assert case.lubricant.viscosity_Pas == pytest.approx(lubricant_table(name)["viscosity_Pas"])
    with pytest.raises(ValueError, match="known oils"):
        lubricant_table("castor")


def test_every_named_oil_value_has_a_source_or_is_marked_an_estimate():
    """Each key of each oil names a document of the oils file's [documents] table in brackets or
    starts with ESTIMATE; the rheology numbers are estimates (no measured values were found)."""
    from solver.lubricants import documents, oil, oil_names

    cited_refs = [f"[{ref}]" for ref in documents()]
    for name in oil_names():
        entry = oil(name)
        assert set(entry.sources) == set(entry.values), name
        for key, source in entry.sources.items():
            cited = any(ref in source for ref in cited_refs)
            assert cited or source.startswith("ESTIMATE") or key == "traction_model", (name, key)
        assert "eyring_stress_MPa" in entry.estimated_keys()
    assert "pressure_viscosity_per_GPa" not in oil("spindle-mineral-vg32").estimated_keys()


def test_named_oil_film_shear_modulus_lies_in_the_measured_range_its_source_cites():
    """Each oil's source says its film shear modulus G lies inside the 0.1-1.0 GPa measured for a
    high-viscosity mineral oil at 23 degC and 1.0-2.0 GPa contact pressure ([VEO]: abstract of
    "Observations of viscoelastic behaviour of an elastohydrodynamic lubricant film", scilit
    record c72484bb7d8f02b302ce42281110aa4a). The value stays an estimate (other oils, other
    temperatures); this keeps the stated bound true."""
    from solver.lubricants import lubricant_table, oil, oil_names

    for name in oil_names():
        assert "[VEO]" in oil(name).sources["film_shear_modulus_GPa"], name
        assert 0.1 <= lubricant_table(name)["film_shear_modulus_GPa"] <= 1.0, name


E_PRIME, R_X, KAPPA = 2.28e11, 9.5e-3, 10.0  # steel ball-race contact: E', R_x [m], a / b


def _contact(p_max):
    """Semi-axes a, b [m] and load Q [N] of the contact with Hertz pressure p_max [Pa]."""
    b = 2.0 * p_max * R_X / E_PRIME * math.pi
    a = KAPPA * b
    return a, b, 2.0 / 3.0 * math.pi * a * b * p_max


def _mu(slip, r, p_max, entrainment=10.0, n_nodes=(8, 16)):
    """Traction coefficient F / Q of the contact under uniform slip [m/s], integrated over the
    Hertz ellipse with rheology ``r`` and the Hamrock-Dowson central film."""
    from solver.physics.traction import NODE_AREA, NODE_LOAD, ellipse_quadrature

    a, b, q = _contact(p_max)
    h = film_thickness_central(
        entrainment, r[RH_VISCOSITY], r[RH_PRESSURE_VISCOSITY], E_PRIME, R_X, q, KAPPA
    )
    nodes = ellipse_quadrature(*n_nodes)
    force = 0.0
    for k in range(len(nodes)):
        area = a * b * nodes[k, NODE_AREA]
        force += shear_stress(slip, q * nodes[k, NODE_LOAD] / area, h, b / entrainment, r) * area
    return force / q


def _oil(oil, temperature):
    from solver.lubricants import lubricant_table

    o = lubricant_table(oil)
    eta = viscosity_at_temperature(
        o["viscosity_Pas"], 40.0, o["temperature_viscosity_per_K"], temperature
    )
    return rheology(
        eta=eta,
        alpha=o["pressure_viscosity_per_GPa"] * 1e-9,
        tau0=o["eyring_stress_MPa"] * 1e6,
        tau_l0=o["limiting_shear_stress_MPa"] * 1e6,
        slope=o["limiting_shear_coefficient"],
        g=o["film_shear_modulus_GPa"] * 1e9,
    )


def _contact_traction_coefficient(slip, oil, temperature, p_max, entrainment=10.0):
    """Traction coefficient F / Q of a steel ball-race contact (R_x 9.5 mm, ellipticity 10,
    E' 228 GPa) under uniform slip, integrated over the Hertz ellipse with the oil's rheology."""
    return _mu(slip, _oil(oil, temperature), p_max, entrainment)


def test_contact_traction_is_linear_at_low_slide_to_roll_ratio():
    """Contact level, small slide-to-roll ratio: mu = SRR u_e / (h Q) * integral of eta_eff dA,
    eta_eff = eta(p) G t / (eta(p) + G t) (viscous and elastic responses in series), the integral
    written out here on a fine polar grid independent of the kernel's nodes."""
    r = _oil("spindle-mineral-vg32", 60.0)
    p_max, ue = 1.2e9, 10.0
    a, b, q = _contact(p_max)
    h = film_thickness_central(
        ue, r[RH_VISCOSITY], r[RH_PRESSURE_VISCOSITY], E_PRIME, R_X, q, KAPPA
    )
    gt = r[RH_SHEAR_MODULUS] * b / ue
    rho = (np.arange(4000) + 0.5) / 4000
    p = p_max * np.sqrt(1.0 - rho**2)
    eta = r[RH_VISCOSITY] * np.exp(np.minimum(r[RH_PRESSURE_VISCOSITY] * p, BARUS_EXPONENT_CAP))
    eta_area = np.sum(eta * gt / (eta + gt) * 2.0 * math.pi * rho / 4000) * a * b
    srr = 1e-7
    expected = srr * ue * eta_area / (h * q)
    # the product rule converges slowly where eta(p) crosses G t (1.4 % off with 8 x 16 nodes)
    fine = (24, 48)
    assert _mu(srr * ue, r, p_max, ue, fine) == pytest.approx(expected, rel=2e-3)
    assert _mu(2 * srr * ue, r, p_max, ue, fine) == pytest.approx(2 * expected, rel=2e-3)


def test_contact_traction_plateau_is_the_load_weighted_limiting_stress():
    """Large slip: mu -> integral of (tau_L0 + Lambda p) dA / Q = Lambda + 1.5 tau_L0 / p_max
    (Hertz: Q = 2/3 pi a b p_max), approached from below (a stiff Eyring stress, 20 MPa, so that
    the viscous stress is well above the limit over most of the ellipse)."""
    r = rheology(tau0=20e6)
    for p_max in (1.0e9, 2.0e9):
        limit = r[RH_LIMITING_SLOPE] + 1.5 * r[RH_LIMITING_STRESS] / p_max
        mu = _mu(20.0, r, p_max)
        assert mu < limit
        assert mu == pytest.approx(limit, rel=0.01)


def test_contact_traction_follows_the_published_trends_of_traction_fluids():
    """Loewenthal & Rohn, "Regression analysis of traction characteristics of traction fluids",
    NASA TP-2154 (1983), abstract (Santotrac 50 and TDF-88, disc machine): traction increases
    with contact pressure up to about 2.0 GPa, and the apparent stiffness of the contact (the
    initial slope of the traction curve) increases with contact pressure and decreases with
    speed. The report's tables and figures were not available through the project's tools, so
    these are checked as trends, not values, with the jet oil at 100 degC."""
    r = _oil("jet-oil-mil-prf-23699", 100.0)
    ue = 10.0
    mu_at = {p: _mu(0.02 * ue, r, p, ue) for p in (1.0e9, 1.5e9, 2.0e9)}  # SRR 2 %
    assert mu_at[1.0e9] < mu_at[1.5e9] < mu_at[2.0e9]

    def slope(p_max, speed):  # d mu / d SRR at SRR -> 0
        return _mu(1e-7 * speed, r, p_max, speed) / 1e-7

    assert slope(1.0e9, ue) < slope(1.5e9, ue) < slope(2.0e9, ue)
    assert slope(1.5e9, 5.0) > slope(1.5e9, 10.0) > slope(1.5e9, 20.0)


def test_newtonian_contact_traction_grows_with_viscosity_like_the_film_allows():
    """Low pressure, compliant-free oil (G -> infinity), small slip: tau = eta u / h with h ~
    eta^0.67 (Hamrock-Dowson), so doubling the viscosity raises the traction by 2^0.33."""
    thin, thick = rheology(eta=0.01, alpha=1e-12, g=1e15), rheology(eta=0.02, alpha=1e-12, g=1e15)
    ratio = _mu(1e-6, thick, 0.3e9) / _mu(1e-6, thin, 0.3e9)
    assert ratio == pytest.approx(2.0**0.33, rel=1e-3)


def test_jet_oil_traction_against_the_mil_l_23699_data_set():
    """Plausibility against published data: the ADORE example data set for a MIL-L-23699 jet oil
    in ball-race contacts (physics.md §2.6.4, from the public ADORE-port Data.txt: mu = 0.050 at
    1 m/s slip, 0.036 at 5 m/s and beyond; the data set does not state pressure, speed or
    temperature). With the named jet oil at a typical 100 degC inlet, p_max 1.5 GPa and 10 m/s
    entrainment, the rheology gives the same order: within a factor 2 of both values (measured
    0.028 against 0.050 and 0.033 against 0.036), rising with slip like the data up to the peak.
    The falling branch of the data (shear heating in the film) is left out here: the rheology
    arrays of this file have no thermal softening (docs/traction.md)."""
    mu = {
        u: _contact_traction_coefficient(u, "jet-oil-mil-prf-23699", 100.0, 1.5e9)
        for u in (0.05, 0.2, 1.0, 5.0)
    }
    assert 0.050 / 2.0 < mu[1.0] < 0.050 * 2.0
    assert 0.036 / 2.0 < mu[5.0] < 0.036 * 2.0
    assert mu[0.05] < mu[0.2] < mu[1.0]
    # at higher pressure the plateau rises towards Lambda + tau_L0 / p (Bair-Winer)
    assert _contact_traction_coefficient(5.0, "jet-oil-mil-prf-23699", 100.0, 2.0e9) > mu[5.0]


@pytest.mark.parametrize("film, transit", [(1e-15, 1e3), (1e-12, 1e-3), (1e-6, 1e-12)])
def test_extreme_film_and_transit_stay_finite_and_below_the_limit(film, transit):
    """A vanishing film with a long transit (entrainment -> 0) makes the elastic stress huge: the
    stress stays finite, positive and at most tau_L; a tiny transit makes it elastic-limited."""
    r = rheology()
    for u in (1e-9, 1e-3, 1.0, 30.0):
        for p in (0.0, 1e9, 3e9):
            tau = shear_stress(u, p, film, transit, r)
            tau_l = r[RH_LIMITING_STRESS] + r[RH_LIMITING_SLOPE] * p
            assert math.isfinite(tau) and 0.0 < tau <= tau_l * (1.0 + 1e-12)
            assert tau == pytest.approx(reference_stress(u, p, film, transit, r), rel=1e-6)
