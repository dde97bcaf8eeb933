"""Tests of solver.physics.drag: the oil-air drag moment on the cage.

References: the free-disc closed forms of Schlichting & Gersten (laminar moment on both faces
2 M = 0.616 pi rho R^4 sqrt(nu omega^3); turbulent 1/2 C_M rho omega^2 R^5 with
C_M = 0.146 Re^-1/5), the annulus as a disc minus its hole (wall shear ~ r laminar, ~ r^8/5
turbulent, by direct numerical integration), and limits.
"""

from __future__ import annotations

import math

import pytest
from scipy import integrate

from solver.physics.drag import cage_drag_coefficients, cage_drag_moment, cage_drag_moment_from

RHO_OIL_AIR = 0.01 * 870.0 + 0.99 * 1.13  # 1 % oil in air [kg/m^3]
ETA_OIL_AIR = 0.01 * 0.02 + 0.99 * 1.9e-5  # [Pa s]
R_OUT, R_IN = 0.030, 0.025


def test_zero_at_rest_and_without_mixture():
    assert cage_drag_moment(0.0, RHO_OIL_AIR, ETA_OIL_AIR, R_OUT, R_IN) == 0.0
    assert cage_drag_moment(500.0, 0.0, ETA_OIL_AIR, R_OUT, R_IN) == 0.0


@pytest.mark.parametrize("omega", [0.5, 50.0, 1000.0, -1000.0])
def test_opposes_rotation_and_is_odd(omega):
    m = cage_drag_moment(omega, RHO_OIL_AIR, ETA_OIL_AIR, R_OUT, R_IN)
    assert m * omega < 0.0
    assert cage_drag_moment(-omega, RHO_OIL_AIR, ETA_OIL_AIR, R_OUT, R_IN) == -m


def test_laminar_full_disc_is_von_karman():
    """Slow, viscous: Re = omega R^2 / nu = 5 (laminar branch); full disc (r_in = 0)."""
    rho, eta, r, w = 900.0, 0.5, 0.05, 1000.0
    assert rho * w * r * r / eta < 1e4
    expected = 0.616 * math.pi * rho * r**4 * math.sqrt(eta / rho * w**3)
    assert -cage_drag_moment(w, rho, eta, r, 0.0) == pytest.approx(expected, rel=2e-3)


def test_turbulent_full_disc():
    """Fast, light mixture: Re ~ 1e6 (turbulent branch)."""
    rho, eta, r, w = RHO_OIL_AIR, ETA_OIL_AIR, 0.05, 2000.0
    re = rho * w * r * r / eta
    assert re > 1e5
    expected = 0.5 * 0.146 * re**-0.2 * rho * w**2 * r**5
    assert -cage_drag_moment(w, rho, eta, r, 0.0) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(("w", "shear_exponent"), [(1000.0, 1.0), (2000.0, 1.6)])
def test_annulus_is_the_integral_of_the_wall_shear(w, shear_exponent):
    """Annulus = integral of the disc's wall shear tau(r) = c r^n over r_in..r_out (both faces),
    c fixed by the full-disc moment (laminar case: viscous oil; turbulent: the oil-air mixture)."""
    rho, eta = (900.0, 0.5) if shear_exponent == 1.0 else (RHO_OIL_AIR, ETA_OIL_AIR)
    full = cage_drag_moment(w, rho, eta, R_OUT, 0.0)

    def face(a, b):
        return integrate.quad(lambda r: r**shear_exponent * r * 2.0 * math.pi * r, a, b)[0]

    expected = full * face(R_IN, R_OUT) / face(0.0, R_OUT)
    assert cage_drag_moment(w, rho, eta, R_OUT, R_IN) == pytest.approx(expected, rel=1e-9)


def test_scaling_with_density_and_speed():
    """Laminar: M ~ rho^1/2 omega^3/2 at fixed viscosity; turbulent: M ~ rho^4/5 omega^9/5."""
    eta = 0.5
    lam = [cage_drag_moment(w, rho, eta, R_OUT, R_IN) for w, rho in ((100, 900), (400, 900))]
    assert lam[1] / lam[0] == pytest.approx(4.0**1.5, rel=1e-12)
    lam_rho = cage_drag_moment(100.0, 3600.0, eta, R_OUT, R_IN) / lam[0]
    assert lam_rho == pytest.approx(2.0, rel=1e-12)
    eta = ETA_OIL_AIR
    tur = [cage_drag_moment(w, 10.0, eta, R_OUT, R_IN) for w in (2000.0, 4000.0)]
    assert tur[1] / tur[0] == pytest.approx(2.0**1.8, rel=1e-12)
    tur_rho = cage_drag_moment(2000.0, 20.0, eta, R_OUT, R_IN) / tur[0]
    assert tur_rho == pytest.approx(2.0**0.8, rel=1e-12)


def test_continuous_between_the_branches():
    """The larger coefficient is taken: no jump where the turbulent branch takes over."""
    rho, eta = RHO_OIL_AIR, ETA_OIL_AIR
    ws = [10.0 * 1.01**i for i in range(800)]
    ms = [-cage_drag_moment(w, rho, eta, R_OUT, 0.0) for w in ws]
    assert all(b > a for a, b in zip(ms, ms[1:], strict=False))
    assert max(b / a for a, b in zip(ms, ms[1:], strict=False)) < 1.01**2.1


@pytest.mark.parametrize(("rho", "eta"), [(900.0, 0.5), (RHO_OIL_AIR, ETA_OIL_AIR), (1.13, 1.9e-5)])
@pytest.mark.parametrize("omega", [3.0, 300.0, -3000.0])
def test_precomputed_coefficients_give_the_same_moment(rho, eta, omega):
    """The kernel's form (coefficients fixed per mixture and cage) = the Reynolds-number form."""
    lam, turb = cage_drag_coefficients(rho, eta, R_OUT, R_IN)
    assert cage_drag_moment_from(omega, lam, turb) == pytest.approx(
        cage_drag_moment(omega, rho, eta, R_OUT, R_IN), rel=1e-12
    )
