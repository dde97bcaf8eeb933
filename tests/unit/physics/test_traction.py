"""Tests of solver.physics.traction: curve, quadrature, traction kernels, damped normal force.

References are independent of the kernels: published curve values (physics.md §2.6.4), closed
forms (uniform sliding, moments of the Hertz pressure), scipy dblquad, an independent polar
Gauss–Legendre integration of the local-shear integrand written directly from its definition in
vector form (checked once against scipy cubature to 1e-9), and scipy solve_ivp for the impacts.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from solver.physics import traction as tr
from solver.physics.rheology import (
    RH_EYRING_STRESS,
    RH_LIMITING_SLOPE,
    RH_LIMITING_STRESS,
    RH_PRESSURE_VISCOSITY,
    RH_SHEAR_MODULUS,
    RH_VISCOSITY,
    RHEOLOGY_SIZE,
)

ADORE = dict(mu_zero=0.0, mu_max=0.050, slip_at_max=1.0, mu_infinity=0.036)


# ------------------------------------------------------------------------------------------------
# traction curve
# ------------------------------------------------------------------------------------------------
def test_adore_example_coefficients():
    a, b, c, d = tr.traction_curve_parameters(**ADORE)
    assert a == pytest.approx(-0.036, abs=1e-12)
    assert b == pytest.approx(0.1018, abs=5e-5)
    assert c == pytest.approx(1.547, abs=5e-4)
    assert d == pytest.approx(0.036, abs=1e-12)


@pytest.mark.parametrize(
    "u, mu",
    [
        (0.05, 0.0074),
        (0.1, 0.014),
        (0.2, 0.025),
        (0.5, 0.043),
        (1.0, 0.050),
        (2.0, 0.044),
        (5.0, 0.036),
        (20.0, 0.036),
    ],
)
def test_adore_example_curve_values(u, mu):
    curve = tr.traction_curve_parameters(**ADORE)
    # physics.md quotes two significant digits
    assert tr.traction_coefficient(u, curve) == pytest.approx(mu, abs=5.1e-4)


def test_adore_initial_slope():
    curve = tr.traction_curve_parameters(**ADORE)
    h = 1e-7
    assert tr.traction_coefficient(h, curve) / h == pytest.approx(0.157, abs=1e-3)


@settings(max_examples=60, deadline=None)
@given(
    mu_zero=st.floats(0.0, 0.2),
    excess=st.floats(1e-3, 0.1),
    um=st.floats(0.01, 20.0),
    drop=st.floats(0.0, 1.0),
)
def test_curve_properties(mu_zero, excess, um, drop):
    mu_max = mu_zero + excess
    mu_inf = drop * mu_max * 0.999
    curve = tr.traction_curve_parameters(mu_zero, mu_max, um, mu_inf)
    assert curve[tr.CURVE_B] > 0 and curve[tr.CURVE_C] > 0
    assert tr.traction_coefficient(0.0, curve) == pytest.approx(mu_zero, abs=1e-12)
    assert tr.traction_coefficient(um, curve) == pytest.approx(mu_max, rel=1e-9)
    u = np.linspace(0.0, 40.0 * um, 4001)
    mu = np.array([tr.traction_coefficient(x, curve) for x in u])
    assert mu.max() <= mu_max * (1 + 1e-9)
    assert u[np.argmax(mu)] == pytest.approx(um, abs=40.0 * um / 4000 * 1.01)
    # derivative zero at the maximum (central difference)
    h = um * 1e-5
    slope = (tr.traction_coefficient(um + h, curve) - tr.traction_coefficient(um - h, curve)) / (
        2 * h
    )
    assert abs(slope) < 1e-6 * mu_max / um
    assert tr.traction_coefficient(1e3 * um, curve) == pytest.approx(mu_inf, abs=1e-9)


@pytest.mark.parametrize(
    "kwargs, key",
    [
        (
            dict(mu_zero=0.06, mu_max=0.05, slip_at_max=1.0, mu_infinity=0.0),
            "mu_zero",
        ),
        (
            dict(mu_zero=0.0, mu_max=0.05, slip_at_max=1.0, mu_infinity=0.051),
            "mu_infinity",
        ),
        (
            dict(mu_zero=0.0, mu_max=1.2, slip_at_max=1.0, mu_infinity=0.03),
            "mu_max",
        ),
        (
            dict(mu_zero=0.0, mu_max=0.05, slip_at_max=0.0, mu_infinity=0.03),
            "slip_at_max",
        ),
        (
            dict(mu_zero=0.0, mu_max=float("nan"), slip_at_max=1.0, mu_infinity=0.03),
            "mu_max",
        ),
        (
            dict(mu_zero=-0.01, mu_max=0.05, slip_at_max=1.0, mu_infinity=0.03),
            "mu_zero",
        ),
    ],
)
def test_curve_rejects_bad_input(kwargs, key):
    """A programming error (the case validation keeps case values within the rules): ValueError
    naming the argument."""
    with pytest.raises(ValueError) as err:
        tr.traction_curve_parameters(**kwargs)
    assert f"{key} = " in str(err.value)


def test_regularised_factor_continuous_through_zero():
    curve = tr.constant_traction_parameters(0.1)  # mu(0) = 0.1 > 0: needs the regularisation
    ureg = 1e-3
    f = [tr.regularised_traction_factor(u, curve, ureg) * u for u in (0.0, 1e-9, 1e-6, 1e-3, 1.0)]
    assert f[0] == 0.0
    assert f[1] < 1e-6 * 0.1 * 1.01
    assert f[3] == pytest.approx(0.1 / math.sqrt(2), rel=1e-12)
    assert f[4] == pytest.approx(0.1, rel=1e-6)
    assert tr.regularised_traction_factor(0.0, curve, 0.0) == 0.0


# ------------------------------------------------------------------------------------------------
# quadrature
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "nr, nt", [(1, 1), (2, 3), (tr.DEFAULT_N_ROLLING, tr.DEFAULT_N_TRANSVERSE), (7, 16)]
)
def test_quadrature_integrates_hertz_pressure(nr, nt):
    nodes = tr.ellipse_quadrature(nr, nt)
    assert nodes.shape == (nr * nt, tr.NODE_COLUMNS)
    a, b, q = 2.0e-3, 0.3e-3, 850.0
    pmax = 1.5 * q / (math.pi * a * b)
    x, y = nodes[:, tr.NODE_ROLLING], nodes[:, tr.NODE_TRANSVERSE]
    assert np.all(x**2 + y**2 < 1.0)
    p = pmax * np.sqrt(1.0 - x**2 - y**2)
    assert np.sum(nodes[:, tr.NODE_AREA] * p) * a * b == pytest.approx(q, rel=1e-3)
    assert np.sum(nodes[:, tr.NODE_LOAD]) == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(
        nodes[:, tr.NODE_LOAD], nodes[:, tr.NODE_AREA] * p * a * b / q, rtol=1e-12
    )
    np.testing.assert_allclose(nodes[:, tr.NODE_PRESSURE], p / pmax, rtol=1e-12)
    # nodes of one strip are consecutive (the kernels compute the strip terms once per strip)
    strips = np.flatnonzero(np.diff(y) != 0.0).size + 1
    assert strips == nt


def test_quadrature_pressure_moments():
    # <x^2> = <y^2> = 1/5 and <x^2 y^2> = 1/35 for the Hertz pressure on the unit disc
    nodes = tr.ellipse_quadrature(3, 3)
    w, x, y = nodes[:, tr.NODE_LOAD], nodes[:, tr.NODE_ROLLING], nodes[:, tr.NODE_TRANSVERSE]
    assert np.sum(w * x**2) == pytest.approx(0.2, rel=1e-12)
    assert np.sum(w * y**2) == pytest.approx(0.2, rel=1e-12)
    assert np.sum(w * x**2 * y**2) == pytest.approx(1.0 / 35.0, rel=1e-12)
    assert abs(np.sum(w * x)) < 1e-15 and abs(np.sum(w * y)) < 1e-15


def test_quadrature_rejects_bad_counts():
    with pytest.raises(ValueError, match="n_rolling"):
        tr.ellipse_quadrature(0, 4)
    with pytest.raises(ValueError, match="n_transverse"):
        tr.ellipse_quadrature(4, 2.5)


# ------------------------------------------------------------------------------------------------
# helpers: a tilted contact frame and body kinematics
# ------------------------------------------------------------------------------------------------
def _frame(seed=1):
    rng = np.random.default_rng(seed)
    m, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    n, t1 = m[:, 0], m[:, 1]
    t2 = np.cross(n, t1)
    return n, t1, t2


def _contact(P, n, t1, a, b, q, kappa):
    c = np.zeros(tr.CONTACT_SIZE)
    c[tr.CT_POINT : tr.CT_POINT + 3] = P
    c[tr.CT_NORMAL : tr.CT_NORMAL + 3] = n
    c[tr.CT_ROLLING : tr.CT_ROLLING + 3] = t1
    c[tr.CT_SEMI_MAJOR] = a
    c[tr.CT_SEMI_MINOR] = b
    c[tr.CT_LOAD] = q
    c[tr.CT_CURVATURE] = kappa
    return c


def _kin(cb, vb, wb, cr, vr, wr):
    k = np.zeros(tr.KIN_SIZE)
    k[tr.KIN_BALL_CENTRE : tr.KIN_BALL_CENTRE + 3] = cb
    k[tr.KIN_BALL_VELOCITY : tr.KIN_BALL_VELOCITY + 3] = vb
    k[tr.KIN_BALL_OMEGA : tr.KIN_BALL_OMEGA + 3] = wb
    k[tr.KIN_RING_POINT : tr.KIN_RING_POINT + 3] = cr
    k[tr.KIN_RING_VELOCITY : tr.KIN_RING_VELOCITY + 3] = vr
    k[tr.KIN_RING_OMEGA : tr.KIN_RING_OMEGA + 3] = wr
    return k


def _run(contact, kin, curve, ureg=1e-4, nodes=None):
    out = np.full(tr.TRACTION_OUT_SIZE, np.nan)
    tr.ellipse_traction(
        contact, kin, curve, ureg, tr.ellipse_quadrature() if nodes is None else nodes, out
    )
    return out


def _integrand(contact, kin, curve, ureg, stress=None):
    """Local shear and its moments at contact-plane points (xi, eta), written from the definitions.
    ``stress(u, p)``: magnitude of the local shear stress instead of mu(u) p (ureg then unused).

    The surface across the groove is the circle p(eta) = P + eta t2 + (sqrt(Rd^2 - eta^2) - Rd) n;
    the slip is the rigid-body velocity difference with its n component (approach rate) removed and
    its t2 component laid along the surface tangent dp/deta."""
    P = contact[0:3]
    n = contact[3:6]
    t1 = contact[6:9]
    t2 = np.cross(n, t1)
    a, b, q, kappa = contact[9], contact[10], contact[11], contact[12]
    cb, vb, wb, cr, vr, wr = (kin[i : i + 3] for i in range(0, 18, 3))
    pmax = 1.5 * q / (math.pi * a * b)
    Rd = 1.0 / kappa if kappa > 0 else np.inf

    def f(xi, eta):
        if np.isfinite(Rd):
            z = np.sqrt(Rd**2 - eta**2) - Rd
            dz = -eta / np.sqrt(Rd**2 - eta**2)  # dz/deta
        else:
            z = dz = 0.0 * eta
        p = P + np.outer(xi, t1) + np.outer(eta, t2) + np.outer(z, n)
        tang = t2[None, :] + np.outer(dz, n)
        tang /= np.linalg.norm(tang, axis=1)[:, None]
        dv = (vb + np.cross(wb, p - cb)) - (vr + np.cross(wr, p - cr))
        dv = np.outer(dv @ t1, t1) + (dv @ t2)[:, None] * tang
        u = np.linalg.norm(dv, axis=1)
        pres = pmax * np.sqrt(np.clip(1.0 - (xi / b) ** 2 - (eta / a) ** 2, 0.0, None))
        if stress is None:
            mu = (curve[0] + curve[1] * u) * np.exp(-curve[2] * u) + curve[3]
            tau = -(mu * pres / np.sqrt(u**2 + ureg**2))[:, None] * dv
        else:
            tau = -(stress(u, pres) / u)[:, None] * dv
        return np.hstack(
            [tau, np.cross(p - P, tau), np.cross(p - cb, tau), -np.sum(tau * dv, axis=1)[:, None]]
        )

    return f


def _reference(contact, kin, curve, ureg, n_panels=40, order=6, stress=None):
    """Independent integral over the ellipse in polar coordinates, xi = b sin(s) cos(th),
    eta = a sin(s) sin(th) (rho = sin(s) removes the square-root edge of the pressure), composite
    Gauss–Legendre
    panels in s and th. Returns (F, M about P, M about ball centre, power)."""
    a, b = contact[9], contact[10]
    g, w = np.polynomial.legendre.leggauss(order)

    def composite(lo, hi, panels):
        edges = np.linspace(lo, hi, panels + 1)
        h = 0.5 * (edges[1:] - edges[:-1])
        mid = 0.5 * (edges[1:] + edges[:-1])
        return (mid[:, None] + h[:, None] * g[None, :]).ravel(), (h[:, None] * w[None, :]).ravel()

    s, ws = composite(0.0, 0.5 * math.pi, n_panels)
    th, wt = composite(0.0, 2.0 * math.pi, 2 * n_panels)
    S, TH = np.meshgrid(s, th, indexing="ij")
    W = np.outer(ws, wt) * a * b * np.sin(S) * np.cos(S)  # dA = a b rho drho dth, drho = cos(s) ds
    xi = (b * np.sin(S) * np.cos(TH)).ravel()
    eta = (a * np.sin(S) * np.sin(TH)).ravel()
    v = W.ravel() @ _integrand(contact, kin, curve, ureg, stress)(xi, eta)
    return v[0:3], v[3:6], v[6:9], v[9]


# typical 7008C inner contact numbers
A_, B_, Q_, R_BALL = 0.55e-3, 0.09e-3, 95.0, 3.572e-3
KAPPA = tr.deformed_surface_curvature(0.54 * 7.144e-3, 7.144e-3)


def test_deformed_curvature_formula():
    r, D = 3.8e-3, 7.144e-3
    Rd = 1.0 / tr.deformed_surface_curvature(r, D)
    # harmonic mean of the groove radius and the ball radius
    assert Rd == pytest.approx(2.0 / (1.0 / r + 1.0 / (D / 2)), rel=1e-14)


# ------------------------------------------------------------------------------------------------
# ellipse traction
# ------------------------------------------------------------------------------------------------
def test_pure_rolling_without_spin_gives_no_force():
    n, t1, t2 = _frame(3)
    P = np.array([0.01, 0.02, -0.005])
    cb = P - R_BALL * n
    w1, w2 = 120.0, -900.0
    wb = w1 * t1 + w2 * t2  # in the tangent plane: rolling, no spin
    vr = R_BALL * (w2 * t1 - w1 * t2)  # flat ring translating with the ball surface
    contact = _contact(P, n, t1, A_, B_, Q_, 0.0)
    kin = _kin(cb, np.zeros(3), wb, np.array([0.0, 0.0, 0.0]), vr, np.zeros(3))
    out = _run(contact, kin, tr.traction_curve_parameters(**ADORE))
    scale = Q_ * 0.05
    assert np.max(np.abs(out[tr.TR_FORCE : tr.TR_FORCE + 3])) < 1e-12 * scale
    assert np.max(np.abs(out[tr.TR_MOMENT_BALL : tr.TR_MOMENT_BALL + 3])) < 1e-12 * scale * R_BALL
    assert out[tr.TR_SLIP_SPEED] < 1e-12
    assert abs(out[tr.TR_SPIN]) < 1e-12
    assert out[tr.TR_ENTRAINMENT] == pytest.approx(np.linalg.norm(vr), rel=1e-12)


@pytest.mark.parametrize("kappa", [0.0, KAPPA])
@pytest.mark.parametrize("u", [0.05, 0.7, 3.0])
def test_uniform_sliding_force_is_q_mu(kappa, u):
    n, t1, t2 = _frame(5)
    P = np.array([0.0, 0.025, 0.0])
    cb = P - R_BALL * n
    curve = tr.traction_curve_parameters(**ADORE)
    ureg = 1e-4
    contact = _contact(P, n, t1, A_, B_, Q_, kappa)
    vb = u * t1  # translation only: the same slip at every point, tangent to the curved surface too
    out = _run(
        contact, _kin(cb, vb, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)), curve, ureg
    )
    expected = -Q_ * tr.traction_coefficient(u, curve) * u / math.hypot(u, ureg) * t1
    np.testing.assert_allclose(out[tr.TR_FORCE : tr.TR_FORCE + 3], expected, rtol=1e-12, atol=1e-15)
    assert out[tr.TR_POWER] == pytest.approx(-np.dot(expected, vb), rel=1e-12)
    # single-point variant agrees for uniform slip
    out1 = np.zeros(tr.TRACTION_OUT_SIZE)
    tr.centre_traction(
        contact, _kin(cb, vb, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)), curve, ureg, out1
    )
    np.testing.assert_allclose(
        out1[tr.TR_FORCE : tr.TR_FORCE + 3], expected, rtol=1e-12, atol=1e-15
    )


def test_uniform_sliding_any_direction_flat():
    n, t1, t2 = _frame(7)
    P = np.array([0.0, 0.0, 0.03])
    curve = tr.traction_curve_parameters(**ADORE)
    direction = 0.6 * t1 - 0.8 * t2
    u = 0.4
    contact = _contact(P, n, t1, A_, B_, Q_, 0.0)
    out = _run(
        contact,
        _kin(P - R_BALL * n, u * direction, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)),
        curve,
        0.0,
    )
    np.testing.assert_allclose(
        out[tr.TR_FORCE : tr.TR_FORCE + 3],
        -Q_ * tr.traction_coefficient(u, curve) * direction,
        rtol=1e-12,
    )


def _spin_case(omega_s, nodes=None, curve=None):
    n, t1, t2 = _frame(11)
    P = np.array([0.004, -0.02, 0.01])
    cb = P - R_BALL * n
    contact = _contact(P, n, t1, A_, B_, Q_, 0.0)
    kin = _kin(cb, np.zeros(3), omega_s * n, np.zeros(3), np.zeros(3), np.zeros(3))
    curve = tr.constant_traction_parameters(0.05) if curve is None else curve
    return n, _run(contact, kin, curve, 0.0, nodes)


@pytest.mark.parametrize("omega_s", [300.0, -50.0])
def test_pure_spin_moment_matches_dblquad(omega_s):
    mu = 0.05
    n, out = _spin_case(omega_s, tr.ellipse_quadrature(8, 16))
    pmax = 1.5 * Q_ / (math.pi * A_ * B_)
    # independent: M = -mu sign(w) n * integral of p |r| over the ellipse
    val, _ = integrate.dblquad(
        lambda eta, xi: (
            pmax * math.sqrt(max(0.0, 1 - (xi / B_) ** 2 - (eta / A_) ** 2)) * math.hypot(xi, eta)
        ),
        -B_,
        B_,
        lambda xi: -A_ * math.sqrt(1 - (xi / B_) ** 2),
        lambda xi: A_ * math.sqrt(1 - (xi / B_) ** 2),
        epsrel=1e-10,
    )
    expected = -mu * math.copysign(1.0, omega_s) * val * n
    mp = out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3]
    np.testing.assert_allclose(mp, expected, rtol=2e-3, atol=1e-3 * abs(val) * mu)
    # the spin moment opposes the spin
    assert np.dot(mp, n) * omega_s < 0
    # no net force (symmetric slip field); the ball moment is the point moment plus (P - c_b) x F
    assert np.linalg.norm(out[tr.TR_FORCE : tr.TR_FORCE + 3]) < 1e-9 * Q_ * mu
    np.testing.assert_allclose(
        out[tr.TR_MOMENT_BALL : tr.TR_MOMENT_BALL + 3], mp, rtol=1e-9, atol=1e-15
    )
    assert out[tr.TR_SPIN] == pytest.approx(omega_s, rel=1e-12)


def test_spin_moment_converges_with_node_count():
    n, ref = _spin_case(300.0, tr.ellipse_quadrature(24, 48))
    errs = []
    for nr, nt in [(2, 4), (4, 8), (8, 16)]:
        _, out = _spin_case(300.0, tr.ellipse_quadrature(nr, nt))
        errs.append(
            abs(
                out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] @ n
                - ref[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] @ n
            )
        )
    assert errs[2] < errs[1] < errs[0]


def _general_case(seed=2, kappa=KAPPA):
    """Ball on a rotating inner-ring-like body: rolling + sliding + spin + curved surface."""
    n, t1, t2 = _frame(seed)
    cr = np.array([0.0, 0.0, 0.0])
    P = np.array([0.001, 0.0236, 0.0004])
    cb = P - R_BALL * n
    wr = np.array([2094.0, 0.0, 0.0])  # 20 000 rpm about x
    vring_P = np.cross(wr, P - cr)
    # ball angular velocity: roughly rolling on the ring plus spin and a small mismatch
    vt = vring_P - np.dot(vring_P, n) * n
    # w x (P - c_b) = w x (R n) = vt  =>  w = n x vt / R (component in the tangent plane)
    w_roll = np.cross(n, vt) / R_BALL
    wb = w_roll + 400.0 * n + 30.0 * t1
    vb = 0.15 * t1 - 0.05 * t2 + np.cross(wr, cb - cr) * 0.0
    contact = _contact(P, n, t1, A_, B_, Q_, kappa)
    kin = _kin(cb, vb, wb, cr, np.zeros(3), wr)
    return contact, kin


@pytest.mark.parametrize("kappa", [0.0, KAPPA])
def test_general_contact_matches_independent_integration(kappa):
    contact, kin = _general_case(kappa=kappa)
    curve = tr.traction_curve_parameters(**ADORE)
    ureg = 1e-3
    F, MP, MB, pw = _reference(contact, kin, curve, ureg)
    out = _run(contact, kin, curve, ureg, tr.ellipse_quadrature(16, 32))
    fs = np.linalg.norm(F)
    ms = np.linalg.norm(MP)
    np.testing.assert_allclose(out[tr.TR_FORCE : tr.TR_FORCE + 3], F, atol=1e-7 * fs)
    np.testing.assert_allclose(out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3], MP, atol=1e-7 * ms)
    np.testing.assert_allclose(
        out[tr.TR_MOMENT_BALL : tr.TR_MOMENT_BALL + 3], MB, atol=1e-7 * np.linalg.norm(MB)
    )
    assert out[tr.TR_POWER] == pytest.approx(pw, rel=1e-7)
    assert out[tr.TR_POWER] > 0
    # default node count: within 1e-3 of the converged integral
    out_d = _run(contact, kin, curve, ureg)
    np.testing.assert_allclose(out_d[tr.TR_FORCE : tr.TR_FORCE + 3], F, atol=1e-3 * fs)
    np.testing.assert_allclose(
        out_d[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3], MP, atol=1e-3 * ms
    )
    # the single-point variant misses the spin and Heathcote contributions entirely
    out1 = np.zeros(tr.TRACTION_OUT_SIZE)
    tr.centre_traction(contact, kin, curve, ureg, out1)
    assert np.linalg.norm(out1[tr.TR_FORCE : tr.TR_FORCE + 3] - F) > 0.05 * fs


def _rheology_stress(u, p, film, transit, r):
    """Local shear stress of solver.physics.rheology written out from its definition (numpy):
    Barus viscosity, Eyring and elastic stresses in series, smooth limit at tau_L0 + Lambda p."""
    eta = r[RH_VISCOSITY] * np.exp(np.minimum(r[RH_PRESSURE_VISCOSITY] * p, 60.0))
    tau_v = r[RH_EYRING_STRESS] * np.arcsinh(eta * (u / film) / r[RH_EYRING_STRESS])
    tau_e = r[RH_SHEAR_MODULUS] * (u / film) * transit
    tau = tau_v * tau_e / (tau_v + tau_e)
    tau_l = r[RH_LIMITING_STRESS] + r[RH_LIMITING_SLOPE] * p
    return tau / (1.0 + (tau / tau_l) ** 4) ** 0.25


@pytest.mark.parametrize("kappa", [0.0, KAPPA])
def test_rheology_law_matches_independent_integration(kappa):
    """The ellipse integral with the rheological law (its own node loop, per-contact constants)
    against the polar integration of the law written out in numpy, on a contact with rolling,
    sliding and spin: a stress that saturates at a few mm/s of slip, around the spin pole too."""
    contact, kin = _general_case(kappa=kappa)
    r = _rheology_params()
    film, transit = 0.3e-6, 5.0e-6
    out = np.full(tr.TRACTION_OUT_SIZE, np.nan)
    curve = np.zeros(tr.CURVE_SIZE)

    def integrate_law(points, strips):
        tr.ellipse_traction_law(
            contact,
            kin,
            tr.LAW_RHEOLOGY,
            curve,
            r,
            film,
            transit,
            0.0,
            tr.ellipse_quadrature(points, strips),
            out,
        )

    integrate_law(16, 32)
    F, MP, MB, pw = _reference(
        contact,
        kin,
        curve,
        0.0,
        n_panels=60,
        stress=lambda u, p: _rheology_stress(u, p, film, transit, r),
    )
    fs, ms = np.linalg.norm(F), np.linalg.norm(MP)
    # the product rule converges slowly on the kink of the saturating law: 16 x 32 nodes within
    # 5e-4, the dynamic model's default 4 x 8 within 2 % (1.4e-4 and 0.8 % here)
    np.testing.assert_allclose(out[tr.TR_FORCE : tr.TR_FORCE + 3], F, atol=5e-4 * fs)
    np.testing.assert_allclose(out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3], MP, atol=5e-4 * ms)
    assert out[tr.TR_POWER] == pytest.approx(pw, rel=5e-4)
    integrate_law(4, 8)
    np.testing.assert_allclose(out[tr.TR_FORCE : tr.TR_FORCE + 3], F, atol=2e-2 * fs)
    # the traction is near its limit: |F| between 0.5 and 1 of the load-weighted tau_L
    pmean_tl = 2e6 * math.pi * A_ * B_ + 0.075 * Q_
    assert 0.5 * pmean_tl < fs < pmean_tl


def test_heathcote_slip_from_curvature():
    """Pure rolling at the centre on a curved (conformal) surface still gives traction (Heathcote);
    the same kinematics on a flat contact gives none."""
    n, t1, t2 = _frame(4)
    P = np.zeros(3)
    cb = P - R_BALL * n
    V = 20.0
    # ball rolls along t1 about an axis through its centre: w x (P - c_b) = V t1
    wb = (V / R_BALL) * t2
    vr = V * t1
    curve = tr.traction_curve_parameters(**ADORE)
    kin = _kin(cb, np.zeros(3), wb, np.zeros(3), vr, np.zeros(3))
    flat = _run(_contact(P, n, t1, A_, B_, Q_, 0.0), kin, curve)
    curved_c = _contact(P, n, t1, A_, B_, Q_, KAPPA)
    curved = _run(curved_c, kin, curve, nodes=tr.ellipse_quadrature(8, 24))
    assert np.linalg.norm(flat[tr.TR_FORCE : tr.TR_FORCE + 3]) < 1e-12
    F, MP, MB, pw = _reference(curved_c, kin, curve, 1e-4)
    f_c = curved[tr.TR_FORCE : tr.TR_FORCE + 3]
    # ball surface at |eta| > 0 is nearer the rolling axis: it lags the ring, so the ring drives it
    assert np.dot(f_c, t1) > 0.0
    np.testing.assert_allclose(f_c, F, atol=5e-3 * np.linalg.norm(F))
    assert curved[tr.TR_POWER] == pytest.approx(pw, rel=5e-3)


def test_moment_identity_and_ring_reaction():
    contact, kin = _general_case(seed=9)
    curve = tr.traction_curve_parameters(**ADORE)
    out = _run(contact, kin, curve, 1e-3)
    P = contact[0:3]
    cb = kin[0:3]
    F = out[tr.TR_FORCE : tr.TR_FORCE + 3]
    MP = out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3]
    np.testing.assert_allclose(
        out[tr.TR_MOMENT_BALL : tr.TR_MOMENT_BALL + 3],
        np.cross(P - cb, F) + MP,
        rtol=1e-10,
        atol=1e-18,
    )


def test_spin_moment_absent_in_single_point_variant():
    curve = tr.constant_traction_parameters(0.05)
    n, out = _spin_case(300.0, curve=curve)
    assert abs(out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] @ n) > 0
    n2, t1, _ = _frame(11)
    P = np.array([0.004, -0.02, 0.01])
    contact = _contact(P, n2, t1, A_, B_, Q_, 0.0)
    out1 = np.zeros(tr.TRACTION_OUT_SIZE)
    tr.centre_traction(
        contact,
        _kin(P - R_BALL * n2, np.zeros(3), 300.0 * n2, np.zeros(3), np.zeros(3), np.zeros(3)),
        curve,
        1e-6,
        out1,
    )
    assert np.all(out1[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] == 0.0)
    # the centre does not slip under pure spin (rounding-level slip only, regularised)
    assert np.linalg.norm(out1[tr.TR_FORCE : tr.TR_FORCE + 3]) < 1e-9


def test_no_nan_for_zero_load_and_zero_slip():
    n, t1, _ = _frame(1)
    contact = _contact(np.zeros(3), n, t1, A_, B_, 0.0, KAPPA)
    out = _run(
        contact,
        _kin(-R_BALL * n, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)),
        tr.constant_traction_parameters(0.1),
        0.0,
    )
    assert np.all(np.isfinite(out))
    assert np.all(out[0:9] == 0.0)


# ------------------------------------------------------------------------------------------------
# damped normal force
# ------------------------------------------------------------------------------------------------
K_HERTZ = 8.0e9  # N/m^1.5, a typical ball-race constant
M_BALL = 0.0015


def test_normal_force_limits():
    f = tr.damped_normal_force
    assert f(-1e-6, 1.0, K_HERTZ, 0.1, M_BALL) == 0.0
    assert f(0.0, 1.0, K_HERTZ, 0.1, M_BALL) == 0.0
    d = 3e-6
    assert f(d, 0.0, K_HERTZ, 0.3, M_BALL) == pytest.approx(K_HERTZ * d**1.5, rel=1e-14)
    assert f(d, 0.2, K_HERTZ, 0.0, M_BALL) == pytest.approx(K_HERTZ * d**1.5, rel=1e-14)
    c = 2 * 0.1 * math.sqrt(1.5 * K_HERTZ * math.sqrt(d) * M_BALL)
    assert f(d, 0.05, K_HERTZ, 0.1, M_BALL) == pytest.approx(K_HERTZ * d**1.5 + c * 0.05, rel=1e-14)


def test_normal_force_never_tension():
    for rate in (-10.0, -1.0, -0.1):
        for d in (1e-9, 1e-7, 1e-6):
            assert tr.damped_normal_force(d, rate, K_HERTZ, 1.0, M_BALL) >= 0.0
    assert tr.damped_normal_force(1e-7, -10.0, K_HERTZ, 1.0, M_BALL) == 0.0


def test_normal_force_continuous_at_onset():
    # with a large approach rate the force still goes to zero with the approach
    vals = [
        tr.damped_normal_force(d, 1.0, K_HERTZ, 0.2, M_BALL) for d in (1e-8, 1e-10, 1e-12, 1e-14)
    ]
    assert vals[0] > vals[1] > vals[2] > vals[3] > 0.0
    # the damping term vanishes like d^(1/4) (c ~ d^(1/4)); six decades of d -> factor 10^-1.5
    assert vals[-1] / vals[0] == pytest.approx(10**-1.5, rel=0.05)
    assert tr.damped_normal_force(0.0, 1.0, K_HERTZ, 0.2, M_BALL) == 0.0


def _impact(zeta, v0, K=K_HERTZ, m=M_BALL):
    """1-DOF mass hitting a Hertz spring: returns (restitution, E0, E_end + dissipated)."""

    def rhs(t, s):
        d, v, _diss = s
        q = tr.damped_normal_force(d, v, K, zeta, m)
        return [v, -q / m, (q - K * max(d, 0.0) ** 1.5) * v if d > 0 else 0.0]

    def leave(t, s):
        return s[0]

    leave.terminal = True
    leave.direction = -1
    # contact duration scale sqrt(m/k_lin): integrate well past it
    t_end = 50.0 * (m**2 / (K**2 * v0)) ** 0.2
    sol = integrate.solve_ivp(
        rhs,
        (0.0, t_end),
        [1e-30, v0, 0.0],
        events=leave,
        rtol=1e-11,
        atol=[1e-18, 1e-12, 1e-15],
        method="DOP853",
    )
    assert sol.status == 1, "the mass did not leave the contact"
    d, v, diss = sol.y[:, -1]
    e0 = 0.5 * m * v0**2
    e_end = 0.5 * m * v**2 + 0.4 * K * max(d, 0.0) ** 2.5
    return -v / v0, e0, e_end + diss


def test_impact_conserves_energy_without_damping():
    e, e0, e1 = _impact(0.0, 0.5)
    assert e == pytest.approx(1.0, abs=1e-6)
    assert e1 == pytest.approx(e0, rel=1e-6)


@pytest.mark.parametrize("zeta", [0.05, 0.2])
def test_impact_dissipates_with_damping(zeta):
    e_slow, e0, e1 = _impact(zeta, 0.05)
    e_fast, _, _ = _impact(zeta, 1.0)
    assert e_slow < 1.0 - 0.5 * zeta  # clearly below 1
    assert e1 == pytest.approx(e0, rel=1e-6)  # kinetic + elastic + dissipated = initial
    # this damping law is scale-free: the restitution does not depend on the impact speed
    assert e_fast == pytest.approx(e_slow, rel=1e-5)


def test_restitution_decreases_with_damping_ratio():
    es = [_impact(z, 0.3)[0] for z in (0.0, 0.05, 0.1, 0.3)]
    assert es[0] > es[1] > es[2] > es[3] > 0.0


def test_force_continuous_through_zero_slip_no_chattering():
    """Sweeping the sliding speed through zero: the force changes sign smoothly (no jump), also
    with mu(0) > 0 where only the regularisation makes it continuous."""
    n, t1, _ = _frame(8)
    P = np.zeros(3)
    ureg = 1e-3
    for curve in (tr.traction_curve_parameters(**ADORE), tr.constant_traction_parameters(0.08)):
        contact = _contact(P, n, t1, A_, B_, Q_, KAPPA)
        us = np.linspace(-5e-3, 5e-3, 201)
        f = np.array(
            [
                _run(
                    contact,
                    _kin(-R_BALL * n, u * t1, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)),
                    curve,
                    ureg,
                )[tr.TR_FORCE : tr.TR_FORCE + 3]
                @ t1
                for u in us
            ]
        )
        assert f[100] == 0.0
        assert np.all(np.diff(f) < 0.0)  # friction opposes the slip, strictly monotone
        # the largest step between neighbours is bounded by the slope at zero times the step
        slope0 = Q_ * max(tr.traction_coefficient(0.0, curve) / ureg, 0.2)
        assert np.max(np.abs(np.diff(f))) <= 1.01 * slope0 * (us[1] - us[0])


def test_kernels_callable_from_numba():
    from numba import njit

    @njit
    def wrapped(contact, kin, curve, nodes, out, out1):
        tr.ellipse_traction(contact, kin, curve, 1e-3, nodes, out)
        tr.centre_traction(contact, kin, curve, 1e-3, out1)
        return tr.damped_normal_force(1e-6, 0.1, 1e10, 0.05, 1e-3) + tr.traction_coefficient(
            0.5, curve
        )

    contact, kin = _general_case()
    curve = tr.traction_curve_parameters(**ADORE)
    out = np.zeros(tr.TRACTION_OUT_SIZE)
    out1 = np.zeros(tr.TRACTION_OUT_SIZE)
    v = wrapped(contact, kin, curve, tr.ellipse_quadrature(), out, out1)
    assert v == pytest.approx(
        1e10 * 1e-9 + 2 * 0.05 * math.sqrt(1.5e10 * 1e-3 * 1e-3) * 0.1 + 0.04287, rel=1e-3
    )
    np.testing.assert_array_equal(out, _run(contact, kin, curve, 1e-3))


_vec = st.tuples(*(st.floats(-1.0, 1.0),) * 3).map(np.array)


@settings(max_examples=60, deadline=None)
@given(vb=_vec, wb=_vec, wr=_vec, seed=st.integers(0, 1000), curved=st.booleans())
def test_traction_dissipates_and_balances_power(vb, wb, wr, seed, curved):
    """Friction power is never negative; for a flat contact it equals minus the power of the force
    and the moment (about P) on the relative motion, -(F . dv_P + M_P . (w_b - w_r)): the moments
    are consistent with the forces (a virtual-power identity)."""
    n, t1, _ = _frame(seed)
    P = np.array([0.002, 0.02, -0.01])
    cb = P - R_BALL * n
    cr = np.zeros(3)
    kin = _kin(cb, 2.0 * vb, 3000.0 * wb, cr, np.zeros(3), 3000.0 * wr)
    contact = _contact(P, n, t1, A_, B_, Q_, KAPPA if curved else 0.0)
    out = _run(contact, kin, tr.traction_curve_parameters(**ADORE), 1e-3)
    assert np.all(np.isfinite(out))
    assert out[tr.TR_POWER] >= 0.0
    if not curved:
        dv_p = (kin[3:6] + np.cross(kin[6:9], P - cb)) - np.cross(kin[15:18], P - cr)
        omega = kin[6:9] - kin[15:18]
        p_mech = -(out[0:3] @ dv_p + out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] @ omega)
        assert p_mech == pytest.approx(out[tr.TR_POWER], rel=1e-9, abs=1e-12)


def test_convergence_with_node_count_rolling_contact_with_spin():
    """Inner-race-like contact at 20 000 rpm: rolling, spin (omega_s = 0.25 omega_roll) and a small
    sliding speed, so that the slip field has zero lines (kinks) inside the ellipse. Errors against
    the independent integration shrink as nodes are added; the default rule is within 0.5 % of
    Q mu_max for the force and 0.5 % for the moment and the power."""
    n, t1, t2 = _frame(2)
    cr = np.zeros(3)
    P = np.array([0.001, 0.0236, 0.0004])
    cb = P - R_BALL * n
    wr = np.array([2094.0, 0.0, 0.0])
    vP = np.cross(wr, P - cr)
    vt = vP - np.dot(vP, n) * n
    wb = np.cross(n, vt) / R_BALL + 0.25 * np.linalg.norm(vt) / R_BALL * n
    contact = _contact(P, n, t1, A_, B_, Q_, KAPPA)
    kin = _kin(cb, 0.02 * t1, wb, cr, np.zeros(3), wr)
    curve = tr.traction_curve_parameters(**ADORE)
    F, MP, _, pw = _reference(contact, kin, curve, 1e-3, n_panels=80)
    scale_f = Q_ * 0.05
    errs = []
    for nr, nt in [(2, 4), (tr.DEFAULT_N_ROLLING, tr.DEFAULT_N_TRANSVERSE), (8, 24)]:
        o = _run(contact, kin, curve, 1e-3, tr.ellipse_quadrature(nr, nt))
        errs.append(
            (
                np.linalg.norm(o[0:3] - F) / scale_f,
                np.linalg.norm(o[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] - MP)
                / np.linalg.norm(MP),
                abs(o[tr.TR_POWER] - pw) / pw,
            )
        )
    errs = np.array(errs)
    assert np.all(errs[2] < errs[1]) and np.all(errs[1] < errs[0])
    assert np.all(errs[1] < 5e-3)


@pytest.mark.parametrize(
    "mu_zero, mu_max, mu_inf",
    [(0.05, 0.05, 0.02), (0.0, 0.05, 0.05), (0.04, 0.04, 0.04), (0.03, 0.05, 0.05 * (1 - 1e-12))],
)
def test_curve_without_interior_peak_is_monotone_and_bounded(mu_zero, mu_max, mu_inf):
    """Equalities allowed by the case validation (mu_zero = mu_max or mu_infinity = mu_max) give
    the monotone limit of the family, bounded by mu_max, from mu_zero to mu_infinity."""
    um = 0.8
    curve = tr.traction_curve_parameters(mu_zero, mu_max, um, mu_inf)
    u = np.linspace(0.0, 50.0, 2001)
    mu = np.array([tr.traction_coefficient(x, curve) for x in u])
    assert mu[0] == pytest.approx(mu_zero, abs=1e-15)
    assert mu[-1] == pytest.approx(mu_inf, abs=1e-12)
    assert np.all(mu <= mu_max * (1 + 1e-12))
    d = np.diff(mu)
    assert np.all(d <= 1e-15) or np.all(d >= -1e-15)
    # 1 - 1/e of the change at slip_at_max
    if mu_zero != mu_inf:
        frac = (tr.traction_coefficient(um, curve) - mu_zero) / (mu_inf - mu_zero)
        assert frac == pytest.approx(1 - math.exp(-1), rel=1e-9)


def test_spin_moment_circular_contact_closed_form():
    """Full-slip spin of a circular Hertz contact with constant mu: M = (3 pi / 16) mu Q a
    (Johnson, Contact Mechanics §8.3; the integral of p |r| over the Hertz disc)."""
    n, t1, _ = _frame(21)
    P = np.array([0.0, 0.01, 0.0])
    a = 0.3e-3
    mu = 0.07
    contact = _contact(P, n, t1, a, a, Q_, 0.0)
    kin = _kin(P - R_BALL * n, np.zeros(3), -800.0 * n, np.zeros(3), np.zeros(3), np.zeros(3))
    out = _run(
        contact, kin, tr.constant_traction_parameters(mu), 0.0, tr.ellipse_quadrature(12, 24)
    )
    m = out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] @ n
    assert m == pytest.approx(3.0 * math.pi / 16.0 * mu * Q_ * a, rel=1e-3)
    # the spin power is the moment times the spin speed
    assert out[tr.TR_POWER] == pytest.approx(abs(m) * 800.0, rel=1e-12)


# ------------------------------------------------------------------------------------------------
# plain-area weights and the split rule (rheology on the ellipse)
# ------------------------------------------------------------------------------------------------
def _disc_moment(p, q):
    """Integral of x^(2p) y^(2q) over the unit disc: Gamma(p+1/2) Gamma(q+1/2) / Gamma(p+q+2)."""
    return math.gamma(p + 0.5) * math.gamma(q + 0.5) / math.gamma(p + q + 2)


@pytest.mark.parametrize("nr, nt", [(1, 1), (2, 8), (3, 5), (4, 8), (5, 9)])
def test_plain_area_weights_integrate_polynomials_on_the_disc(nr, nt):
    """NODE_UNIFORM integrates x^(2p) y^(2q) = (1 - y^2)^p t^(2p) y^(2q) exactly for 2p <= nr - 1
    along the strip and 2p + 2q <= nt - 1 across; odd moments vanish. The pressure-weighted
    area weight NODE_AREA misses the plain area (9.5 % with two points along rolling)."""
    nodes = tr.ellipse_quadrature(nr, nt)
    w = nodes[:, tr.NODE_UNIFORM]
    x, y = nodes[:, tr.NODE_ROLLING], nodes[:, tr.NODE_TRANSVERSE]
    checked = 0
    for p in range(3):
        for q in range(4):
            if 2 * p <= nr - 1 and 2 * p + 2 * q <= nt - 1:
                assert np.sum(w * x ** (2 * p) * y ** (2 * q)) == pytest.approx(
                    _disc_moment(p, q), rel=1e-12
                )
                checked += 1
    assert checked >= 1
    assert abs(np.sum(w * x)) < 1e-14 and abs(np.sum(w * y * x**2)) < 1e-14
    if nr == 2:
        assert np.sum(nodes[:, tr.NODE_AREA]) < 0.91 * math.pi


def _rheology_params(tau_l0=2e6):
    r = np.zeros(RHEOLOGY_SIZE)
    r[RH_VISCOSITY], r[RH_PRESSURE_VISCOSITY] = 0.01, 2.0e-8
    r[RH_EYRING_STRESS], r[RH_LIMITING_STRESS], r[RH_LIMITING_SLOPE] = 5e6, tau_l0, 0.075
    r[RH_SHEAR_MODULUS] = 0.5e9
    return r


def _law(contact, kin, nodes, law=tr.LAW_RHEOLOGY, curve=None, film=0.3e-6, r=None, ureg=0.0):
    out = np.full(tr.TRACTION_OUT_SIZE, np.nan)
    tr.ellipse_traction_law(
        contact,
        kin,
        law,
        np.zeros(tr.CURVE_SIZE) if curve is None else curve,
        _rheology_params() if r is None else r,
        film,
        5.0e-6,
        ureg,
        nodes,
        out,
    )
    return out


RULES = [
    tr.ellipse_quadrature(1, 1),
    tr.ellipse_quadrature(2, 8),
    tr.ellipse_quadrature(4, 8),
    tr.split_ellipse_rule(1, 1),
    tr.split_ellipse_rule(2, 3),
    tr.split_ellipse_rule(3, 2),
]


@pytest.mark.parametrize("nodes", RULES)
def test_saturated_rheology_is_exact_for_any_rule(nodes):
    """Without a film the stress is the limiting shear stress tau_L0 + Lambda p at every point; for
    uniform sliding the force is then (tau_L0 pi a b + Lambda Q) against the slip, exactly for any
    rule (plain-area weight for tau_L0, load weight for Lambda p). tau_L0 is made large here so
    that its part (38 % of the force) shows."""
    n, t1, t2 = _frame(7)
    P = np.array([0.0, 0.025, 0.0])
    cb = P - R_BALL * n
    contact = _contact(P, n, t1, A_, B_, Q_, 0.0)
    direction = (0.6 * t1 - 0.8 * t2) / np.linalg.norm(0.6 * t1 - 0.8 * t2)
    kin = _kin(cb, 0.3 * direction, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3))
    r = _rheology_params(tau_l0=50e6)
    out = _law(contact, kin, nodes, film=0.0, r=r)
    expected = -(50e6 * math.pi * A_ * B_ + 0.075 * Q_) * direction
    np.testing.assert_allclose(out[tr.TR_FORCE : tr.TR_FORCE + 3], expected, rtol=1e-12)


@pytest.mark.parametrize("counts", [(1, 1), (2, 3), (3, 2), (1, 5)])
@pytest.mark.parametrize("kappa", [0.0, KAPPA])
def test_split_rule_uniform_sliding_force_is_q_mu(counts, kappa):
    """The split rule's load weights integrate the Hertz pressure exactly for any counts: a
    Coulomb coefficient gives Q mu (also on the curved surface, sliding along the rolling
    direction); the strips lie on one piece (no zero of the rolling slip)."""
    n, t1, _ = _frame(5)
    P = np.array([0.0, 0.025, 0.0])
    cb = P - R_BALL * n
    contact = _contact(P, n, t1, A_, B_, Q_, kappa)
    vb = 0.4 * t1
    kin = _kin(cb, vb, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3))
    curve = tr.constant_traction_parameters(0.07)
    out = _law(contact, kin, tr.split_ellipse_rule(*counts), tr.LAW_SLIP_CURVE, curve)
    np.testing.assert_allclose(out[tr.TR_FORCE : tr.TR_FORCE + 3], -0.07 * Q_ * t1, rtol=1e-12)


def test_rolling_slip_zeros_match_a_root_finder():
    """The lines of zero rolling slip v1(eta) = s01 + o2 z(eta) - on eta (z on the deformed surface
    of curvature kappa) against brentq on the exact v1, to 1e-9 of the half-width; without a zero,
    both break points sit where v1 comes closest to zero (where the two zeros will appear)."""
    from scipy import optimize

    a, kappa = 1.2e-3, 1.0 / 2.2e-3

    def v1(y, s01, o2, on, kappa=kappa):
        eta = a * y
        z = math.sqrt(1.0 / kappa**2 - eta**2) - 1.0 / kappa if kappa > 0.0 else 0.0
        return s01 + o2 * z - on * eta

    counts = []
    for s01, o2, on, k in (
        (0.05, 3000.0, 300.0, kappa),
        (-0.2, 2500.0, -100.0, kappa),
        (0.01, 0.0, 500.0, kappa),
        (0.1, 800.0, -400.0, 0.0),
    ):
        ys = np.linspace(-1.0, 1.0, 2001)
        vals = np.array([v1(y, s01, o2, on, k) for y in ys])
        flips = np.flatnonzero(np.sign(vals[1:]) != np.sign(vals[:-1]))
        roots = sorted(
            optimize.brentq(v1, ys[i], ys[i + 1], args=(s01, o2, on, k), xtol=1e-14) for i in flips
        )
        lo, hi = tr._rolling_slip_zeros(a, k, s01, o2, on)
        found = sorted({r for r in (lo, hi) if r > -1.5})  # a double break point counts once
        counts.append(len(roots))
        if roots:
            assert len(found) == len(roots)
            np.testing.assert_allclose(found, roots, atol=1e-9)
        else:  # the closest approach: a minimum of |v1| inside the ellipse
            assert lo == hi and abs(v1(lo, s01, o2, on, k)) == pytest.approx(
                np.min(np.abs(vals)), rel=1e-3
            )
    assert counts == [2, 0, 1, 1]


def test_split_rule_converges_to_the_independent_integral():
    """Rheology law on a contact with rolling, sliding, spin and curvature (two lines of zero
    rolling slip cross the ellipse): the split rule converges to the independent polar integral
    (max of the force and moment errors 0.2, 0.009, 0.002, 1.2e-4 with 2 x 2 ... 16 x 16). On the
    running contacts of the catalogue cases it beats the product rule at equal node counts
    (benchmarks/experiments/traction_rules.py)."""
    contact, kin = _general_case(kappa=KAPPA)
    r = _rheology_params()
    film, transit = 0.3e-6, 5.0e-6
    F, MP, _, pw = _reference(
        contact,
        kin,
        np.zeros(tr.CURVE_SIZE),
        0.0,
        n_panels=60,
        stress=lambda u, p: _rheology_stress(u, p, film, transit, r),
    )
    fs, ms = np.linalg.norm(F), np.linalg.norm(MP)

    def error(nodes):
        out = _law(contact, kin, nodes, film=film, r=r)
        return max(
            np.linalg.norm(out[tr.TR_FORCE : tr.TR_FORCE + 3] - F) / fs,
            np.linalg.norm(out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3] - MP) / ms,
        )

    errors = [error(tr.split_ellipse_rule(n, n)) for n in (2, 4, 8, 16)]
    assert errors[-1] < 5e-4
    assert errors[1] < 0.02
    assert all(errors[i + 1] < errors[i] for i in range(len(errors) - 1))


def test_split_rule_rejects_bad_counts():
    with pytest.raises(ValueError, match="n_rolling"):
        tr.split_ellipse_rule(0, 3)
    with pytest.raises(ValueError, match="strips_per_piece"):
        tr.split_ellipse_rule(2, 1.5)


@pytest.mark.parametrize("law", [tr.LAW_SLIP_CURVE, tr.LAW_RHEOLOGY])
@pytest.mark.parametrize("load", [0.0, Q_])
def test_split_rule_no_nan_without_slip(law, load):
    """No slip anywhere (and no load): the split rule gives zero force and moments, no NaN."""
    n, t1, _ = _frame(1)
    contact = _contact(np.zeros(3), n, t1, A_, B_, load, KAPPA)
    kin = _kin(-R_BALL * n, np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3))
    out = _law(contact, kin, tr.split_ellipse_rule(3, 3), law, tr.constant_traction_parameters(0.1))
    assert np.all(np.isfinite(out))
    assert np.all(out[0:9] == 0.0)


@pytest.mark.parametrize("kappa", [0.0, KAPPA])
def test_split_rule_is_continuous_where_lines_of_pure_rolling_appear(kappa):
    """As the centre slip is swept, a line of pure rolling enters the ellipse at an edge (flat
    contact) or two of them appear together (curved contact, where the parabola of the rolling slip
    touches zero): the split rule's traction changes smoothly through it, with no step larger than
    twice the typical change between neighbouring sweep points."""
    n, t1, t2 = _frame(3)
    P = np.array([0.0, 0.025, 0.0])
    cb = P - R_BALL * n
    contact = _contact(P, n, t1, A_, B_, Q_, kappa)
    spin, roll = 300.0, 4000.0 if kappa > 0.0 else 0.0
    # v1(eta) = s01 + roll z(eta) - spin eta: zero at the edge eta = -a (flat) or at the vertex
    if kappa > 0.0:
        eta_v = -spin / (roll * kappa)
        s_edge = spin * eta_v + 0.5 * roll * kappa * eta_v**2
    else:
        s_edge = -spin * A_
    sweep = s_edge + np.linspace(-0.02, 0.02, 81) * abs(s_edge)
    forces = []
    for s01 in sweep:
        # the ball's rolling adds R roll t1 at P: the ball velocity makes the centre slip s01
        vb = (s01 - R_BALL * roll) * t1 + 0.01 * t2
        kin = _kin(cb, vb, spin * n + roll * t2, np.zeros(3), np.zeros(3), np.zeros(3))
        out = _law(contact, kin, tr.split_ellipse_rule(3, 3))
        forces.append(out[tr.TR_FORCE : tr.TR_FORCE + 3])
    breaks = [
        len({r for r in tr._rolling_slip_zeros(A_, kappa, s01, roll, spin) if r > -1.5})
        for s01 in (sweep[0], sweep[-1])
    ]
    assert breaks[0] != breaks[-1]  # the sweep passes the change of pieces
    steps = np.linalg.norm(np.diff(np.array(forces), axis=0), axis=1)
    assert np.all(np.isfinite(steps))
    assert steps.max() < 2.0 * np.median(steps)


# ------------------------------------------------------------------------------------------------
# node batches (ellipse_traction_into): the vectorised law against the node-by-node formulation
# ------------------------------------------------------------------------------------------------
def _node_by_node(contact, kin, law, curve, r, film, transit, ureg, nodes):
    """(force, moment about P, power) of the ellipse integral written node by node, as the kernel
    did before its node loop was batched: the law at each node with math.exp / math.log
    (solver.physics.rheology.saturation_over_slip), the sums in node order."""
    from solver.physics.rheology import contact_constants, saturation_over_slip

    n = contact[tr.CT_NORMAL : tr.CT_NORMAL + 3]
    n = n / np.linalg.norm(n)
    t1 = contact[tr.CT_ROLLING : tr.CT_ROLLING + 3]
    t1 = t1 - np.dot(t1, n) * n
    t1 = t1 / np.linalg.norm(t1)
    t2 = np.cross(n, t1)
    P = contact[tr.CT_POINT : tr.CT_POINT + 3]
    cb = kin[tr.KIN_BALL_CENTRE : tr.KIN_BALL_CENTRE + 3]
    cr = kin[tr.KIN_RING_POINT : tr.KIN_RING_POINT + 3]
    wb = kin[tr.KIN_BALL_OMEGA : tr.KIN_BALL_OMEGA + 3]
    wr = kin[tr.KIN_RING_OMEGA : tr.KIN_RING_OMEGA + 3]
    s0 = (kin[tr.KIN_BALL_VELOCITY : tr.KIN_BALL_VELOCITY + 3] + np.cross(wb, P - cb)) - (
        kin[tr.KIN_RING_VELOCITY : tr.KIN_RING_VELOCITY + 3] + np.cross(wr, P - cr)
    )
    om = wb - wr
    s01, s02 = np.dot(s0, t1), np.dot(s0, t2)
    o1, o2, on = np.dot(om, t1), np.dot(om, t2), np.dot(om, n)
    a, b, q = contact[tr.CT_SEMI_MAJOR], contact[tr.CT_SEMI_MINOR], contact[tr.CT_LOAD]
    kappa = contact[tr.CT_CURVATURE]
    p_max = 1.5 * q / (math.pi * a * b)
    ln_c, elastic = contact_constants(film, transit, r) if film > 0.0 else (0.0, 0.0)

    def factor(u2, ps, w_load, w_uniform):
        if law == tr.LAW_SLIP_CURVE:
            den = math.sqrt(u2 + ureg * ureg)
            u = math.sqrt(u2)
            mu = (curve[0] + curve[1] * u) * math.exp(-curve[2] * u) + curve[3]
            return -q * w_load * mu / den if den > 0.0 else 0.0
        weight = r[RH_LIMITING_STRESS] * a * b * w_uniform + r[RH_LIMITING_SLOPE] * q * w_load
        if u2 <= 0.0:
            return 0.0
        if film <= 0.0:
            return -weight / math.sqrt(u2) if math.sqrt(u2) > 1e-9 else 0.0
        return -weight * saturation_over_slip(
            math.sqrt(u2),
            0.5 * math.log(u2),
            r[RH_PRESSURE_VISCOSITY] * p_max * ps,
            r[RH_LIMITING_STRESS] + r[RH_LIMITING_SLOPE] * p_max * ps,
            ln_c,
            elastic,
            r[RH_EYRING_STRESS],
        )

    points = []  # (xi, y, ps, w_load, w_uniform)
    if nodes.shape[1] == tr.SPLIT_COLUMNS:
        n_t, n_y = int(nodes[0, tr.SPLIT_COUNTS]), int(nodes[1, tr.SPLIT_COUNTS])
        ra, rb = tr._rolling_slip_zeros(a, kappa, s01, o2, on)
        lo, area_lo = -1.0, -0.25 * math.pi
        for hi in (ra, rb, 1.0):
            if hi - lo <= 1e-9:
                continue
            ys = 0.5 * (lo + hi) + 0.5 * (hi - lo) * nodes[:n_y, tr.SPLIT_Y]
            wy = nodes[:n_y, tr.SPLIT_Y_WEIGHT]
            sy = np.sqrt(np.maximum(1.0 - ys * ys, 0.0))
            area_hi = 0.5 * (hi * math.sqrt(max(1.0 - hi * hi, 0.0)) + math.asin(min(hi, 1.0)))
            area_scale = (area_hi - area_lo) / np.sum(wy * sy)
            load_scale = (
                1.5 / math.pi * ((hi - hi**3 / 3.0) - (lo - lo**3 / 3.0)) / np.sum(wy * sy**2)
            )
            lo, area_lo = hi, area_hi
            for j in range(n_y):
                for i in range(n_t):
                    points.append(
                        (
                            b * sy[j] * nodes[i, tr.SPLIT_T],
                            ys[j],
                            sy[j] * nodes[i, tr.SPLIT_T_PRESSURE],
                            load_scale * sy[j] ** 2 * wy[j] * nodes[i, tr.SPLIT_T_LOAD],
                            area_scale * sy[j] * wy[j] * nodes[i, tr.SPLIT_T_UNIFORM],
                        )
                    )
    else:
        for row in nodes:
            points.append(
                (
                    b * row[tr.NODE_ROLLING],
                    row[tr.NODE_TRANSVERSE],
                    row[tr.NODE_PRESSURE],
                    row[tr.NODE_LOAD],
                    row[tr.NODE_UNIFORM],
                )
            )
    f = np.zeros(3)  # (rolling, transverse, normal) components
    m = np.zeros(3)
    power = 0.0
    for xi, y, ps, w_load, w_uniform in points:
        eta = a * y
        sphi = kappa * eta
        cphi = math.sqrt(max(1.0 - sphi * sphi, 0.0))
        z = -kappa * eta * eta / (1.0 + cphi)
        v1 = s01 + o2 * z - on * eta
        v2 = s02 + on * xi - o1 * z
        u2 = v1 * v1 + v2 * v2
        g = factor(u2, ps, w_load, w_uniform)
        tau = np.array([g * v1, g * v2 * cphi, -g * v2 * sphi])
        f += tau
        m += np.cross([xi, eta, z], tau)
        power -= g * u2
    basis = np.array([t1, t2, n])
    return f @ basis, m @ basis, power


def _batch_cases():
    """Random contacts around the general case: rolling, sliding and spin of random size."""
    rng = np.random.default_rng(11)
    cases = []
    for seed in range(6):
        contact, kin = _general_case(seed=seed + 3, kappa=KAPPA if seed % 2 else 0.0)
        kin[tr.KIN_BALL_VELOCITY : tr.KIN_BALL_VELOCITY + 3] *= rng.uniform(0.01, 3.0)
        kin[tr.KIN_BALL_OMEGA : tr.KIN_BALL_OMEGA + 3] += rng.normal(scale=300.0, size=3)
        contact[tr.CT_LOAD] *= rng.uniform(0.2, 3.0)
        cases.append((contact, kin))
    return cases


BATCH_LAWS = {
    "slip curve": (tr.LAW_SLIP_CURVE, 0.3e-6, None),
    "rheology": (tr.LAW_RHEOLOGY, 0.3e-6, None),
    # a low pressure-viscosity coefficient: x = eta gamma_dot / tau_0 below 1e3 at many nodes,
    # where the Eyring stress needs the full asinh (the nodes redone after the vectorised loop)
    "rheology, small x": (tr.LAW_RHEOLOGY, 0.3e-6, 2.0e-9),
    "rheology, no film": (tr.LAW_RHEOLOGY, 0.0, None),
}
BATCH_RULES = [
    tr.ellipse_quadrature(2, 8),
    tr.ellipse_quadrature(4, 8),
    tr.split_ellipse_rule(3, 3),
    tr.split_ellipse_rule(2, 3),
]


@pytest.mark.parametrize("law_name", list(BATCH_LAWS))
@pytest.mark.parametrize("rule", range(len(BATCH_RULES)))
def test_batched_kernel_matches_node_by_node_formulation(law_name, rule):
    """The batched kernel (law in a vectorised loop, exp and log of solver.physics.lanes) equals
    the node-by-node formulation with math.exp and math.log to rounding; and the batch's capacity
    (1 node, a few, the default 64) does not change the result at all."""
    law, film, alpha = BATCH_LAWS[law_name]
    nodes = BATCH_RULES[rule]
    curve = tr.traction_curve_parameters(**ADORE)
    r = _rheology_params()
    if alpha is not None:
        r[RH_PRESSURE_VISCOSITY] = alpha
    for contact, kin in _batch_cases():
        outs = []
        for capacity in (tr.NODE_BATCH, 1, 5):
            out = np.full(tr.TRACTION_OUT_SIZE, np.nan)
            tr.ellipse_traction_into(
                contact,
                kin,
                law,
                curve,
                r,
                film,
                5.0e-6,
                1e-3,
                nodes,
                out,
                np.empty((tr.NODE_BATCH_ROWS, capacity)),
            )
            outs.append(out)
        for out in outs[1:]:
            np.testing.assert_array_equal(out, outs[0])
        out = outs[0]
        force, moment, power = _node_by_node(contact, kin, law, curve, r, film, 5.0e-6, 1e-3, nodes)
        fs, ms = np.linalg.norm(force), np.linalg.norm(moment)
        assert fs > 0.0
        np.testing.assert_allclose(
            out[tr.TR_FORCE : tr.TR_FORCE + 3], force, rtol=0, atol=1e-13 * fs
        )
        np.testing.assert_allclose(
            out[tr.TR_MOMENT_POINT : tr.TR_MOMENT_POINT + 3], moment, rtol=0, atol=1e-13 * ms
        )
        assert out[tr.TR_POWER] == pytest.approx(power, rel=1e-13)
