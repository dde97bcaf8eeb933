"""Tests of solver.physics.cage_contact: ball–pocket contact and the cage–land short-bearing force.

References: closed forms (Ocvirk steady short bearing, short-bearing squeeze damping at the centre,
Petroff torque, sphere-on-flat Hertz), direct numerical integration (scipy quad) of the
short-bearing pressure P = -eta L^3 G / h^3 with the half-Sommerfeld condition, and
limits/continuity.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate, optimize

from solver.materials import BUILTIN_MATERIALS, Material, effective_modulus
from solver.physics import cage_contact as cc
from solver.physics.traction import damped_normal_force

STEEL = BUILTIN_MATERIALS["bearing_steel"]
D_BALL = 7.144e-3
CP = 0.2e-3
M_BALL = 3200.0 * math.pi * D_BALL**3 / 6.0


# ------------------------------------------------------------------------------------------------
# shared normal law
# ------------------------------------------------------------------------------------------------
def test_power_law_matches_hertz_damped_force():
    for d in (1e-7, 2e-6, 1e-5):
        for rate in (-0.3, 0.0, 0.4):
            a = cc.damped_power_law_force(d, rate, 5e9, 1.5, 0.1, 2e-3, 0.0)
            b = damped_normal_force(d, rate, 5e9, 0.1, 2e-3)
            assert a == pytest.approx(b, rel=1e-13, abs=1e-300)


def test_power_law_linear_with_ramp_is_continuous_at_onset():
    k, m, z, depth = 5e6, 2e-3, 0.2, 1e-6
    f = [cc.damped_power_law_force(d, 1.0, k, 1.0, z, m, depth) for d in (0.0, 1e-12, 1e-10, 1e-8)]
    assert f[0] == 0.0
    assert f[1] < 1e-4 and f[1] < f[2] < f[3]
    # full critical damping beyond the ramp
    c = 2 * z * math.sqrt(k * m)
    assert cc.damped_power_law_force(2e-6, 1.0, k, 1.0, z, m, depth) == pytest.approx(k * 2e-6 + c)
    # without the ramp the linear law jumps at onset (the reason for the ramp)
    assert cc.damped_power_law_force(1e-15, 1.0, k, 1.0, z, m, 0.0) == pytest.approx(c, rel=1e-6)
    assert cc.damped_power_law_force(1e-6, -100.0, k, 1.0, z, m, depth) == 0.0


# ------------------------------------------------------------------------------------------------
# ball–pocket contact
# ------------------------------------------------------------------------------------------------
def _pocket(n=1.5, k=2e9, zeta=0.0, mu=0.08, ureg=1e-4, depth=None):
    return cc.pocket_parameters(k, n, zeta, M_BALL, mu, CP, D_BALL, ureg, depth)


def _pkin(pos, vel=(0, 0, 0), omega=(0, 0, 0)):
    k = np.zeros(cc.POCKET_KIN_SIZE)
    k[cc.PK_POSITION : cc.PK_POSITION + 3] = pos
    k[cc.PK_VELOCITY : cc.PK_VELOCITY + 3] = vel
    k[cc.PK_OMEGA : cc.PK_OMEGA + 3] = omega
    return k


def _prun(kin, params):
    out = np.full(cc.POCKET_OUT_SIZE, np.nan)
    cc.pocket_contact(kin, params, out)
    return out


def test_pocket_no_force_inside_clearance():
    p = _pocket()
    for pos in [(0, 0, 0), (0, 1e-3, 0.09e-3), (0.05e-3, 0, -0.08e-3), (0, 0, 0.1e-3)]:
        out = _prun(_pkin(pos, (0.1, 0.2, -0.3), (100, 0, 5)), p)
        assert np.all(np.isfinite(out))
        assert np.all(out[cc.PO_FORCE : cc.PO_FORCE + 6] == 0.0)
        assert out[cc.PO_NORMAL_FORCE] == 0.0
        assert out[cc.PO_GAP] == pytest.approx(CP / 2 - math.hypot(pos[0], pos[2]))


@pytest.mark.parametrize("n, k", [(1.5, 2e9), (1.0, 8e6)])
@pytest.mark.parametrize("angle", [0.0, 0.7, math.pi / 2, 2.5, -1.2])
def test_pocket_static_normal_force(n, k, angle):
    pen = 3e-6
    rho = CP / 2 + pen
    pos = (rho * math.sin(angle), 0.4e-3, rho * math.cos(angle))  # (x, r, theta)
    out = _prun(_pkin(pos), _pocket(n=n, k=k))
    fn = k * pen**n
    e_rho = np.array([math.sin(angle), 0.0, math.cos(angle)])
    np.testing.assert_allclose(
        out[cc.PO_FORCE : cc.PO_FORCE + 3], -fn * e_rho, rtol=1e-9, atol=1e-12
    )
    assert out[cc.PO_NORMAL_FORCE] == pytest.approx(fn, rel=1e-9)
    # contact point on the pocket wall, one ball radius beyond the centre
    np.testing.assert_allclose(
        out[cc.PO_POINT : cc.PO_POINT + 3], np.array(pos) + D_BALL / 2 * e_rho, rtol=1e-12
    )
    assert np.linalg.norm(out[cc.PO_MOMENT_BALL : cc.PO_MOMENT_BALL + 3]) < 1e-15


def test_pocket_friction_from_radial_sliding():
    pen, mu = 2e-6, 0.08
    pos = (0.0, 0.0, CP / 2 + pen)  # pushed forward against the pocket face
    out = _prun(_pkin(pos, vel=(0.0, 0.5, 0.0)), _pocket(mu=mu, ureg=1e-6))
    fn = 2e9 * pen**1.5
    np.testing.assert_allclose(
        out[cc.PO_FORCE : cc.PO_FORCE + 3], [0.0, -mu * fn, -fn], rtol=1e-9, atol=1e-15
    )
    assert out[cc.PO_SLIP_SPEED] == pytest.approx(0.5)


@pytest.mark.parametrize("wx", [300.0, -1000.0])
def test_pocket_friction_opposes_ball_spin(wx):
    # ball touching the theta-face and spinning about the bearing axis: x × theta = -r, so the ball
    # surface slides along -r sign(wx), friction pushes it along +r sign(wx); moment opposes wx
    pen, mu = 2e-6, 0.08
    out = _prun(_pkin((0.0, 0.0, CP / 2 + pen), omega=(wx, 0.0, 0.0)), _pocket(mu=mu, ureg=1e-6))
    fn = 2e9 * pen**1.5
    assert out[cc.PO_FORCE + 1] == pytest.approx(math.copysign(mu * fn, wx), rel=1e-6)
    m = out[cc.PO_MOMENT_BALL : cc.PO_MOMENT_BALL + 3]
    assert m[0] * wx < 0
    assert m[0] == pytest.approx(-math.copysign(mu * fn * D_BALL / 2, wx), rel=1e-6)
    assert out[cc.PO_SLIP_SPEED] == pytest.approx(abs(wx) * D_BALL / 2)


def test_pocket_damping_and_no_tension():
    pen = 2e-6
    pos = (0.0, 0.0, -(CP / 2 + pen))  # against the rear face
    p = _pocket(zeta=0.2)
    static = _prun(_pkin(pos), p)[cc.PO_NORMAL_FORCE]
    closing = _prun(_pkin(pos, vel=(0, 0, -0.05)), p)[cc.PO_NORMAL_FORCE]
    opening = _prun(_pkin(pos, vel=(0, 0, 0.05)), p)[cc.PO_NORMAL_FORCE]
    assert closing > static > opening >= 0.0
    c = 2 * 0.2 * math.sqrt(1.5 * 2e9 * math.sqrt(pen) * M_BALL)
    assert closing - static == pytest.approx(c * 0.05, rel=1e-9)
    assert _prun(_pkin(pos, vel=(0, 0, 50.0)), p)[cc.PO_NORMAL_FORCE] == 0.0


def test_pocket_force_continuous_at_contact():
    p = _pocket(n=1.0, k=8e6, zeta=0.1)  # linear polymer law with damping ramp
    f = [
        _prun(_pkin((0, 0, CP / 2 + d), vel=(0, 0, 0.2)), p)[cc.PO_FORCE + 2]
        for d in (-1e-9, 0.0, 1e-12, 1e-10)
    ]
    assert f[0] == 0.0 and f[1] == 0.0
    assert abs(f[2]) < 1e-5 and abs(f[2]) < abs(f[3]) < 1e-2


def test_pocket_stiffness_estimate_limits():
    # huge clearance -> sphere on a flat: K = (4/3) E* sqrt(R) with E* = E'/2
    e_prime = effective_modulus(STEEL, STEEL)
    k_flat = cc.pocket_stiffness_estimate(D_BALL, 1e3 * D_BALL, STEEL, STEEL)
    assert k_flat == pytest.approx(2.0 / 3.0 * e_prime * math.sqrt(D_BALL / 2), rel=2e-3)
    # a conforming pocket is stiffer than a flat
    assert cc.pocket_stiffness_estimate(D_BALL, CP, STEEL, STEEL) > 1.5 * k_flat
    # polymer secant stiffness: F_ref = k_lin * delta(F_ref) on the same Hertz law
    pa = Material("pa66_gf25", 8.0e9, 0.4, 1300.0)
    kh = cc.pocket_stiffness_estimate(D_BALL, CP, BUILTIN_MATERIALS["silicon_nitride"], pa)
    klin = cc.pocket_stiffness_estimate(
        D_BALL, CP, BUILTIN_MATERIALS["silicon_nitride"], pa, exponent=1.0, reference_load=10.0
    )
    delta = (10.0 / kh) ** (2.0 / 3.0)
    assert klin * delta == pytest.approx(10.0, rel=1e-12)
    assert 1e6 < klin < 3e7  # physics.md: polymer cages ~1e6–1e7 N/m


def test_pocket_parameters_validation():
    """Arguments out of range are programming errors (the case validation keeps case values in
    range): ValueError naming every argument at fault, never a case key."""
    with pytest.raises(ValueError) as err:
        cc.pocket_parameters(-1.0, 1.5, 0.1, M_BALL, 0.08, 0.0, D_BALL)
    message = str(err.value)
    assert "stiffness = -1.0" in message and "clearance = 0.0" in message
    assert "cage." not in message
    with pytest.raises(ValueError, match="exponent"):
        cc.pocket_parameters(1e9, 5.0, 0.1, M_BALL, 0.08, CP, D_BALL)


# ------------------------------------------------------------------------------------------------
# cage–land force
# ------------------------------------------------------------------------------------------------
R_LAND, L_LAND, C_LAND, ETA = 30.0e-3, 5.0e-3, 0.15e-3, 0.01
M_CAGE = 0.012


def _land(inside=True, eta=ETA, k=5e8, n=1.0, eps_c=0.95, eps_m=0.98, mu=0.08, zeta=0.05):
    return cc.land_parameters(
        R_LAND, L_LAND, C_LAND, eta, k, M_CAGE, inside, n, zeta, mu, eps_c, eps_m
    )


def _lkin(offset, vel=(0.0, 0.0), wc=0.0, wr=0.0):
    k = np.zeros(cc.LAND_KIN_SIZE)
    k[cc.LK_OFFSET : cc.LK_OFFSET + 2] = offset
    k[cc.LK_VELOCITY : cc.LK_VELOCITY + 2] = vel
    k[cc.LK_CAGE_SPEED] = wc
    k[cc.LK_RING_SPEED] = wr
    return k


def _lrun(kin, params):
    out = np.full(cc.LAND_OUT_SIZE, np.nan)
    cc.land_force(kin, params, out)
    return out


@pytest.mark.parametrize("eps", [0.1, 0.4, 0.7, 0.9])
@pytest.mark.parametrize("angle", [0.0, 2.0])
@pytest.mark.parametrize("wc, wr", [(900.0, 0.0), (-400.0, 0.0), (900.0, 2000.0)])
def test_land_steady_ocvirk_closed_form(eps, angle, wc, wr):
    u_dir = np.array([math.cos(angle), math.sin(angle)])
    perp = np.array([-u_dir[1], u_dir[0]])  # x × e_par: +90° in the +x rotation sense
    out = _lrun(_lkin(eps * C_LAND * u_dir, wc=wc, wr=wr), _land())
    U = R_LAND * (
        wc + wr
    )  # sum of the surface speeds (physics.md's R|w_c - w_land| when w_land = 0)
    f_rad = ETA * abs(U) * L_LAND**3 / C_LAND**2 * eps**2 / (1 - eps**2) ** 2
    f_tan = math.pi * ETA * abs(U) * L_LAND**3 / (4 * C_LAND**2) * eps / (1 - eps**2) ** 1.5
    f = out[cc.LO_FORCE : cc.LO_FORCE + 2]
    # radial: back towards the centre; tangential: 90° ahead in the direction of rotation
    assert f @ u_dir == pytest.approx(-f_rad, rel=1e-10)
    assert f @ perp == pytest.approx(math.copysign(f_tan, U), rel=1e-10)
    assert out[cc.LO_METAL_NORMAL] == 0.0
    assert out[cc.LO_ECCENTRICITY] == pytest.approx(eps)


def _numerical_short_bearing(offset, vel, wc, wr):
    """Force on the cage from P = -eta L^3 G / h^3, with G = w_mean dh/dtheta + dh/dt written in
    absolute angles theta and integrated with quad over the positive-pressure arcs."""
    ey, ez = offset
    vy, vz = vel
    wbar = 0.5 * (wc + wr)

    # film at absolute angle th: h = C - (e . n(th)); its time derivative; surface-drag term
    def G(th):
        n = (math.cos(th), math.sin(th))
        dh_dth = ey * math.sin(th) - ez * math.cos(th)  # d/dth of -(e . n)
        dh_dt = -(vy * n[0] + vz * n[1])
        return wbar * dh_dth + dh_dt

    def P(th):
        h = C_LAND - (ey * math.cos(th) + ez * math.sin(th))
        return max(0.0, -ETA * L_LAND**3 * G(th) / h**3)

    ths = np.linspace(0, 2 * math.pi, 721)
    g = np.array([G(t) for t in ths])
    roots = [
        optimize.brentq(G, ths[i], ths[i + 1], xtol=1e-15)
        for i in np.nonzero(np.diff(np.sign(g)))[0]
    ]
    return np.array(
        [
            integrate.quad(
                lambda t, direction: -R_LAND * P(t) * direction(t),
                0,
                2 * math.pi,
                args=(direction,),
                points=roots,
                limit=400,
                epsabs=1e-13,
                epsrel=1e-11,
            )[0]
            for direction in (math.cos, math.sin)  # y, z
        ]
    )


@pytest.mark.parametrize(
    "offset, vel, wc, wr",
    [
        ((0.6 * C_LAND, 0.2 * C_LAND), (0.02, -0.05), 900.0, 0.0),
        ((-0.3 * C_LAND, 0.5 * C_LAND), (-0.2, 0.1), 300.0, 2000.0),
        ((0.0, 0.85 * C_LAND), (0.0, 0.3), -500.0, 0.0),
        ((0.2 * C_LAND, 0.0), (0.0, 0.0), 0.0, 0.0),
        (
            (0.7 * C_LAND, 0.0),
            (0.0, 0.7 * C_LAND * 450.0),
            900.0,
            0.0,
        ),  # half-speed whirl: no wedge
    ],
)
def test_land_dynamic_force_matches_numerical_reynolds(offset, vel, wc, wr):
    out = _lrun(_lkin(offset, vel, wc, wr), _land())
    ref = _numerical_short_bearing(offset, vel, wc, wr)
    f = out[cc.LO_FORCE : cc.LO_FORCE + 2]
    np.testing.assert_allclose(f, ref, rtol=1e-7, atol=1e-9 * (1 + np.linalg.norm(ref)))


def test_land_zero_force_when_concentric_and_still():
    out = _lrun(_lkin((0.0, 0.0), wc=900.0, wr=0.0), _land())
    assert np.all(out[cc.LO_FORCE : cc.LO_FORCE + 2] == 0.0)
    # Petroff torque of the concentric film, opposing the cage rotation
    petroff = ETA * R_LAND**3 * L_LAND * 2 * math.pi * (0.0 - 900.0) / C_LAND
    assert out[cc.LO_TORQUE] == pytest.approx(petroff, rel=1e-12)
    assert out[cc.LO_RING_TORQUE] == pytest.approx(-petroff, rel=1e-12)


def test_land_squeeze_damping_at_centre():
    # short-bearing damping coefficient at the centre: c = pi eta R L^3 / (2 C^3), any direction
    v = np.array([0.03, -0.04])
    out = _lrun(_lkin((0.0, 0.0), v, wc=0.0, wr=0.0), _land())
    c = math.pi * ETA * R_LAND * L_LAND**3 / (2 * C_LAND**3)
    np.testing.assert_allclose(out[cc.LO_FORCE : cc.LO_FORCE + 2], -c * v, rtol=1e-12)
    # and the limit e -> 0 from any side matches it (no special case hidden at e = 0)
    out2 = _lrun(_lkin((1e-12 * C_LAND, 3e-12 * C_LAND), v, wc=0.0, wr=0.0), _land())
    np.testing.assert_allclose(out2[cc.LO_FORCE : cc.LO_FORCE + 2], -c * v, rtol=1e-6)


def test_land_torque_couette_matches_numerical_integral():
    eps = 0.6
    wc, wr = 900.0, 0.0
    out = _lrun(_lkin((eps * C_LAND, 0.0), wc=wc, wr=wr), _land())
    couette = integrate.quad(
        lambda th: ETA * R_LAND**3 * L_LAND * (wr - wc) / (C_LAND * (1 - eps * math.cos(th))),
        0,
        2 * math.pi,
        epsrel=1e-12,
    )[0]
    f_perp = out[cc.LO_FORCE + 1]  # e along +y, so e_perp = +z
    # pressure (Poiseuille) part of the shear on the cage: -(R/2) integral of h dP/dtheta
    th = np.linspace(0, 2 * math.pi, 200001)
    h = C_LAND * (1 - eps * np.cos(th))
    G = 0.5 * (wc + wr) * eps * C_LAND * np.sin(th)
    P = np.maximum(0.0, -ETA * L_LAND**3 * G / h**3)
    dP = np.gradient(P, th)
    pressure_torque = -0.5 * R_LAND * np.trapezoid(h * dP, th)
    assert pressure_torque == pytest.approx(-0.5 * eps * C_LAND * f_perp, rel=1e-4)
    assert out[cc.LO_TORQUE] == pytest.approx(couette + pressure_torque, rel=1e-5)


@pytest.mark.parametrize("inside", [True, False])
def test_land_moment_balance_and_guidance_symmetry(inside):
    kin = _lkin((0.5 * C_LAND, -0.3 * C_LAND), (0.01, 0.02), wc=800.0, wr=100.0)
    out = _lrun(kin, _land(inside=inside))
    e = kin[0:2]
    f = out[cc.LO_FORCE : cc.LO_FORCE + 2]
    assert out[cc.LO_RING_TORQUE] + out[cc.LO_TORQUE] + (
        e[0] * f[1] - e[1] * f[0]
    ) == pytest.approx(0.0, abs=1e-14)
    # hydrodynamic film: same force and torque whether the cage is inside or outside the land
    other = _lrun(kin, _land(inside=not inside))
    np.testing.assert_allclose(
        out[cc.LO_FORCE : cc.LO_TORQUE + 1], other[cc.LO_FORCE : cc.LO_TORQUE + 1], rtol=1e-14
    )


def test_land_continuous_across_metal_threshold():
    p = _land(eps_c=0.95, eps_m=0.98, k=5e8, n=1.0)
    u = np.array([0.6, 0.8])
    vals = []
    for eps in (0.95 - 1e-9, 0.95, 0.95 + 1e-9):
        out = _lrun(_lkin(eps * C_LAND * u, (0.0, 0.0), wc=900.0), p)
        vals.append(out)
    f = np.array([v[cc.LO_FORCE : cc.LO_FORCE + 2] for v in vals])
    assert np.max(np.abs(f[2] - f[0])) < 1e-6 * np.linalg.norm(f[1])
    assert vals[0][cc.LO_METAL_NORMAL] == 0.0 and vals[1][cc.LO_METAL_NORMAL] == 0.0
    assert vals[2][cc.LO_METAL_NORMAL] > 0.0
    # the hydrodynamic part saturates (no singularity) and the metal contact takes over
    deep = [
        _lrun(_lkin(eps * C_LAND * u, (0.0, 0.0), wc=900.0), p) for eps in (0.99, 1.0, 1.2, 2.0)
    ]
    for out in deep:
        assert np.all(np.isfinite(out))
    radial = [-(out[cc.LO_FORCE : cc.LO_FORCE + 2] @ u) for out in deep]
    assert radial[0] < radial[1] < radial[2] < radial[3]
    hydro = [np.linalg.norm(out[cc.LO_HYDRO_FORCE : cc.LO_HYDRO_FORCE + 2]) for out in deep]
    assert max(hydro) < 1.01 * hydro[-1]
    assert deep[-1][cc.LO_METAL_NORMAL] == pytest.approx(5e8 * (2.0 - 0.95) * C_LAND, rel=1e-12)
    assert deep[-1][cc.LO_FILM] == pytest.approx(-C_LAND)


@pytest.mark.parametrize("inside, side", [(True, 1.0), (False, -1.0)])
def test_land_metal_friction_drags_cage_towards_ring_speed(inside, side):
    # dry land (no oil), cage pressed into the land and spinning faster than the ring
    p = _land(inside=inside, eta=0.0, mu=0.1)
    out = _lrun(_lkin((1.1 * C_LAND, 0.0), (0.0, 0.0), wc=900.0, wr=0.0), p)
    fn = out[cc.LO_METAL_NORMAL]
    assert fn == pytest.approx(5e8 * (1.1 - 0.95) * C_LAND)
    assert out[cc.LO_TORQUE] == pytest.approx(-0.1 * fn * R_LAND, rel=1e-6)
    # friction force on the cage at the contact point opposes the cage surface motion there
    assert out[cc.LO_FORCE + 1] == pytest.approx(-side * 0.1 * fn, rel=1e-6)


def test_land_parameters_validation():
    with pytest.raises(ValueError) as err:
        cc.land_parameters(
            R_LAND,
            L_LAND,
            C_LAND,
            ETA,
            5e8,
            M_CAGE,
            True,
            contact_eccentricity=0.99,
            max_eccentricity=0.98,
        )
    assert "contact_eccentricity = 0.99 and max_eccentricity = 0.98" in str(err.value)
    with pytest.raises(ValueError) as err:
        cc.land_parameters(R_LAND, -1.0, 0.0, ETA, 5e8, M_CAGE, True)
    assert "width = -1.0" in str(err.value) and "radial_clearance = 0.0" in str(err.value)


def test_land_stiffness_estimate():
    e_prime = effective_modulus(STEEL, STEEL)
    assert cc.land_contact_stiffness_estimate(5e-3, e_prime) == pytest.approx(
        math.pi * e_prime * 5e-3 / 4
    )
    with pytest.raises(ValueError, match="land_width = 0.0"):
        cc.land_contact_stiffness_estimate(0.0, e_prime)


@settings(max_examples=150, deadline=None)
@given(
    eps=st.floats(0.0, 0.94),
    angle=st.floats(0.0, 2 * math.pi),
    v=st.tuples(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2)),
    wc=st.floats(-3000.0, 3000.0),
    wr=st.floats(-3000.0, 3000.0),
)
def test_land_film_dissipates_energy(eps, angle, v, wc, wr):
    """The film is passive: the power the cage and ring put into it, -(F . v_rel + T_c w_c +
    T_r w_r), is never negative (Couette part c (w_c - w_r)^2 >= 0 plus the squeeze/wedge part)."""
    off = eps * C_LAND * np.array([math.cos(angle), math.sin(angle)])
    out = _lrun(_lkin(off, v, wc, wr), _land())
    assert np.all(np.isfinite(out))
    power_in = -(
        out[cc.LO_FORCE : cc.LO_FORCE + 2] @ np.array(v)
        + out[cc.LO_TORQUE] * wc
        + out[cc.LO_RING_TORQUE] * wr
    )
    scale = (
        abs(out[cc.LO_FORCE : cc.LO_FORCE + 2] @ np.array(v))
        + abs(out[cc.LO_TORQUE] * wc)
        + abs(out[cc.LO_RING_TORQUE] * wr)
    )
    assert power_in >= -1e-12 * scale


@settings(max_examples=150, deadline=None)
@given(
    pos=st.tuples(st.floats(-2e-4, 2e-4), st.floats(-1e-3, 1e-3), st.floats(-2e-4, 2e-4)),
    vel=st.tuples(*(st.floats(-1.0, 1.0),) * 3),
    omega=st.tuples(*(st.floats(-3000.0, 3000.0),) * 3),
    zeta=st.floats(0.0, 0.5),
)
def test_pocket_finite_and_friction_dissipative(pos, vel, omega, zeta):
    out = _prun(_pkin(pos, vel, omega), _pocket(zeta=zeta))
    assert np.all(np.isfinite(out))
    assert out[cc.PO_NORMAL_FORCE] >= 0.0
    # friction power at the contact point: -(F_t . s) >= 0, with s the sliding velocity there
    r = out[cc.PO_POINT : cc.PO_POINT + 3] - np.array(pos)
    s = np.array(vel) + np.cross(np.array(omega), r)
    f = out[cc.PO_FORCE : cc.PO_FORCE + 3]
    e = r / np.linalg.norm(r)
    f_t = f - (f @ e) * e
    s_t = s - (s @ e) * e
    assert -(f_t @ s_t) >= -1e-15
