"""Traction that follows temperature: the rheology's temperature laws at the inlet
(solver.physics.rheology.rheology_at_temperature, read by solver.inputs) and the thermal softening
of the film at large slip (solver.physics.rheology.thermal_softening), each against its closed
form, and the traction coefficient of a contact through the whole chain case -> inputs -> film ->
ellipse kernel (docs/traction.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.case import parse_case
from solver.inputs import to_inputs
from solver.physics import rheology as rh
from solver.physics import traction as tr
from solver.physics.rheology import (
    CELSIUS_ZERO,
    film_and_rolling_force,
    rheology_at_temperature,
    shear_stress,
)
from tests.helpers.cases import SPINDLE

E_PRIME, R_X, KAPPA = 2.28e11, 9.5e-3, 10.0  # steel ball-race contact: E', R_x [m], a / b
H, T = 0.3e-6, 2.0e-5  # film [m], transit time b / u_e [s]


def rheology(softening=0.005, k=0.13):
    r = np.zeros(rh.RHEOLOGY_SIZE)
    r[rh.RH_VISCOSITY] = 0.01
    r[rh.RH_PRESSURE_VISCOSITY] = 2.0e-8
    r[rh.RH_EYRING_STRESS] = 5.0e6
    r[rh.RH_LIMITING_STRESS] = 2.0e6
    r[rh.RH_LIMITING_SLOPE] = 0.075
    r[rh.RH_SHEAR_MODULUS] = 0.5e9
    r[rh.RH_TEMPERATURE_VISCOSITY] = 0.03
    r[rh.RH_CONDUCTIVITY] = k
    r[rh.RH_SOFTENING] = softening
    return r


def lubricant(temperature, extra="", oil=None):
    """LubricantInputs of the spindle test case with [lubricant] at inlet ``temperature``."""
    named = f'oil = "{oil}"\n' if oil else ""
    text = SPINDLE + f"\n[lubricant]\n{named}inlet_temperature_C = {temperature}\n{extra}"
    return to_inputs(parse_case(text)).lubricant


def contact_mu(srr, lub, p_max=1.5e9, entrainment=10.0):
    """Traction coefficient F / Q of a flat steel contact (R_x 9.5 mm, a / b = 10, E' 228 GPa) in
    uniform slip srr * u_e along the rolling direction, with the lubricant's rheology, the model's
    film (Hamrock-Dowson with the inlet thermal reduction) and the dynamic model's ellipse
    kernel."""
    r = lub.rheology_array()
    b = 2.0 * p_max * R_X / E_PRIME * math.pi
    a = KAPPA * b
    q = 2.0 / 3.0 * math.pi * a * b * p_max
    film, _, _ = film_and_rolling_force(entrainment, srr, q, R_X, KAPPA, p_max, E_PRIME, r)
    contact = np.zeros(tr.CONTACT_SIZE)
    contact[tr.CT_NORMAL + 2] = 1.0
    contact[tr.CT_ROLLING] = 1.0
    contact[tr.CT_SEMI_MAJOR] = a
    contact[tr.CT_SEMI_MINOR] = b
    contact[tr.CT_LOAD] = q
    kin = np.zeros(tr.KIN_SIZE)
    kin[tr.KIN_BALL_VELOCITY] = entrainment * (1.0 + 0.5 * srr)
    kin[tr.KIN_RING_VELOCITY] = entrainment * (1.0 - 0.5 * srr)
    out = np.zeros(tr.TRACTION_OUT_SIZE)
    nodes = tr.ellipse_quadrature(8, 16)
    law, curve = tr.LAW_RHEOLOGY, np.zeros(tr.CURVE_SIZE)
    tr.ellipse_traction_law(contact, kin, law, curve, r, film, b / entrainment, 0.0, nodes, out)
    return -out[tr.TR_FORCE] / q


# ---- the laws against their closed forms -------------------------------------------------------
@pytest.mark.parametrize("u", [1e-4, 1e-2, 0.3, 3.0, 30.0])
@pytest.mark.parametrize("p", [0.5e9, 1.5e9])
def test_softened_stress_solves_the_film_heating_and_the_linear_temperature_law(u, p):
    """The softened stress tau and the mid-film temperature rise dT = tau u h / (8 k) satisfy
    tau = tau_iso (1 - c dT) together, tau_iso being the isothermal law (c = 0)."""
    c, k = 0.005, 0.13
    tau_iso = shear_stress(u, p, H, T, rheology(softening=0.0))
    tau = shear_stress(u, p, H, T, rheology(softening=c, k=k))
    rise = tau * u * H / (8.0 * k)
    assert tau == pytest.approx(tau_iso * (1.0 - c * rise), rel=1e-12)
    assert 0.0 < tau <= tau_iso


def test_softening_vanishes_with_the_temperature_rise_and_takes_over_at_large_slip():
    """No temperature rise (no softening coefficient, no conductivity, no film) gives the
    isothermal law exactly; at small slip the factor tends to 1; at large slip the stress tends to
    8 k / (c u h), the stress whose heating balances the linear temperature law."""
    iso = rheology(softening=0.0)
    for u in (1e-6, 1e-2, 1.0, 20.0):
        assert shear_stress(u, 1e9, H, T, rheology(softening=0.0)) == shear_stress(
            u, 1e9, H, T, iso
        )
        assert shear_stress(u, 1e9, H, T, rheology(k=0.0)) == shear_stress(u, 1e9, H, T, iso)
        assert shear_stress(u, 1e9, 0.0, T, rheology()) == shear_stress(u, 1e9, 0.0, T, iso)
    small = 1e-7
    assert shear_stress(small, 1e9, H, T, rheology()) == pytest.approx(
        shear_stress(small, 1e9, H, T, iso), rel=1e-9
    )
    c, k, big = 0.005, 0.13, 1.0e4
    tau = shear_stress(big, 1e9, H, T, rheology(softening=c, k=k))
    assert tau == pytest.approx(8.0 * k / (c * big * H), rel=0.01)


def test_inlet_temperature_laws_against_their_closed_forms():
    """Each law of rheology_at_temperature: unchanged at the reference temperature; the
    viscosity, pressure-viscosity, limiting shear stress and film shear modulus fall
    exponentially with their coefficients; the Eyring stress grows with absolute temperature."""
    ref = dict(
        viscosity=0.02,
        temperature_viscosity=0.03,
        pressure_viscosity=2.2e-8,
        pressure_viscosity_temperature=0.0077,
        eyring_stress=5e6,
        limiting_stress=2e6,
        limiting_slope=0.07,
        limiting_temperature=0.005,
        shear_modulus=0.5e9,
        shear_modulus_temperature=0.004,
    )
    same = rheology_at_temperature(40.0, 40.0, **ref)
    for key in same:
        assert same[key] == pytest.approx(ref[key], rel=1e-15), key
    hot = rheology_at_temperature(40.0, 120.0, **ref)
    assert hot["viscosity"] == pytest.approx(0.02 * math.exp(-0.03 * 80.0), rel=1e-14)
    assert hot["pressure_viscosity"] == pytest.approx(2.2e-8 * math.exp(-0.0077 * 80), rel=1e-14)
    assert hot["eyring_stress"] == pytest.approx(
        5e6 * (120.0 + CELSIUS_ZERO) / (40.0 + CELSIUS_ZERO), rel=1e-14
    )
    assert hot["limiting_stress"] == pytest.approx(2e6 * math.exp(-0.4), rel=1e-14)
    assert hot["limiting_slope"] == pytest.approx(0.07 * math.exp(-0.4), rel=1e-14)
    assert hot["shear_modulus"] == pytest.approx(0.5e9 * math.exp(-0.32), rel=1e-14)


def test_case_keys_reach_the_rheology_at_the_inlet_temperature():
    """The case's reference values and coefficients become the rheology at the inlet; the
    softening coefficient is the limiting shear stress's, 0 with thermal_softening = false."""
    extra = (
        "pressure_viscosity_per_GPa = 20.0\npressure_viscosity_temperature_per_K = 0.008\n"
        "limiting_shear_temperature_per_K = 0.006\nfilm_shear_modulus_temperature_per_K = 0.004\n"
    )
    r = lubricant(100.0, extra).rheology_array()
    assert r[rh.RH_PRESSURE_VISCOSITY] == pytest.approx(20e-9 * math.exp(-0.008 * 60), rel=1e-12)
    assert r[rh.RH_LIMITING_SLOPE] == pytest.approx(0.075 * math.exp(-0.006 * 60), rel=1e-12)
    assert r[rh.RH_LIMITING_STRESS] == pytest.approx(2e6 * math.exp(-0.006 * 60), rel=1e-12)
    assert r[rh.RH_SHEAR_MODULUS] == pytest.approx(0.5e9 * math.exp(-0.004 * 60), rel=1e-12)
    assert r[rh.RH_EYRING_STRESS] == pytest.approx(5e6 * 373.15 / 313.15, rel=1e-12)
    assert r[rh.RH_SOFTENING] == 0.006
    off = lubricant(100.0, extra + "thermal_softening = false\n").rheology_array()
    assert off[rh.RH_SOFTENING] == 0.0


def test_kernel_softening_matches_the_scalar_law_over_the_ellipse():
    """The dynamic model's vectorised node loop applies the same softening as shear_stress: the
    kernel's force equals the quadrature sum of shear_stress over its own nodes, at small and
    large slip, with softening on."""
    p_max, ue = 1.5e9, 10.0
    lub = lubricant(80.0)
    r = lub.rheology_array()
    assert r[rh.RH_SOFTENING] > 0.0
    b = 2.0 * p_max * R_X / E_PRIME * math.pi
    a = KAPPA * b
    q = 2.0 / 3.0 * math.pi * a * b * p_max
    nodes = tr.ellipse_quadrature(8, 16)
    for srr in (1e-3, 0.05, 0.5):
        film, _, _ = film_and_rolling_force(ue, srr, q, R_X, KAPPA, p_max, E_PRIME, r)
        force = 0.0
        for k in range(len(nodes)):
            p = p_max * nodes[k, tr.NODE_PRESSURE]
            # tau dA = s (tau_L0 dA + Lambda p dA) with the uniform and load weights (traction.py)
            tau_l = r[rh.RH_LIMITING_STRESS] + r[rh.RH_LIMITING_SLOPE] * p
            s = shear_stress(srr * ue, p, film, b / ue, r) / tau_l
            force += s * (
                r[rh.RH_LIMITING_STRESS] * a * b * nodes[k, tr.NODE_UNIFORM]
                + r[rh.RH_LIMITING_SLOPE] * q * nodes[k, tr.NODE_LOAD]
            )
        assert contact_mu(srr, lub, p_max, ue) == pytest.approx(force / q, rel=1e-9)


# ---- the traction coefficient of a contact -----------------------------------------------------
OILS = [None, "spindle-mineral-vg32", "ester-vg22", "jet-oil-mil-prf-23699"]


@pytest.mark.parametrize("srr", [1e-4, 1e-3, 1e-1])
@pytest.mark.parametrize("p_max", [1.0e9, 1.5e9, 2.0e9])
@pytest.mark.parametrize("oil", OILS)
def test_traction_falls_with_inlet_temperature(srr, p_max, oil):
    """Issue 22: at slide-to-roll 1e-4, 1e-3 and 0.1 the traction coefficient of a contact falls
    as the inlet warms from 40 to 80 to 120 degC (the default oil and each named oil, 10 m/s)."""
    mu = [contact_mu(srr, lubricant(t, oil=oil), p_max) for t in (40.0, 80.0, 120.0)]
    assert mu[0] > mu[1] > mu[2] > 0.0, mu


@pytest.mark.parametrize("temperature", [40.0, 80.0, 120.0])
def test_traction_curve_has_a_maximum_only_with_thermal_softening(temperature):
    """With thermal softening (the default) the traction curve mu(SRR) rises to a maximum inside
    0.001 < SRR < 2 and falls after it (at SRR 2 at least 5 % below the peak); the isothermal
    film's curve only rises."""
    srr = np.logspace(-3, math.log10(2.0), 25)
    on = np.array([contact_mu(s, lubricant(temperature)) for s in srr])
    peak = int(np.argmax(on))
    assert 0 < peak < len(srr) - 1
    assert on[-1] < 0.95 * on[peak]
    assert np.all(np.diff(on[: peak + 1]) > 0.0) and np.all(np.diff(on[peak:]) < 0.0)
    off_lub = lubricant(temperature, "thermal_softening = false\n")
    off = np.array([contact_mu(s, off_lub) for s in srr])
    assert np.all(np.diff(off) > 0.0)
    assert np.all(on <= off * (1.0 + 1e-12))
