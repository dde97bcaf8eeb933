"""Hamrock-Dowson film thickness: exponents, limits, validation."""

import math

import pytest
from numba import njit

from solver.physics.ehl import (
    W_FLOOR,
    film_thickness,
    film_thickness_central,
    film_thickness_minimum,
)

# a typical steel ball / inner race contact of a 7008-class spindle bearing
BASE = dict(
    u_e=10.0,
    viscosity=0.01,
    pressure_viscosity=2.0e-8,
    effective_modulus=2.28e11,
    r_x=0.0045,
    load=200.0,
    kappa=8.0,
)
ORDER = ("u_e", "viscosity", "pressure_viscosity", "effective_modulus", "r_x", "load", "kappa")


def _args(**changes):
    values = dict(BASE, **changes)
    return tuple(values[k] for k in ORDER)


def _ratio_exponent(func, name, factor=3.0):
    h1 = func(*_args())
    h2 = func(*_args(**{name: BASE[name] * factor}))
    return math.log(h2 / h1) / math.log(factor)


@pytest.mark.parametrize(
    "func, speed_exp, g_exp, w_exp",
    [(film_thickness_central, 0.67, 0.53, -0.067), (film_thickness_minimum, 0.68, 0.49, -0.073)],
)
def test_power_law_exponents(func, speed_exp, g_exp, w_exp):
    assert _ratio_exponent(func, "u_e") == pytest.approx(speed_exp, abs=1e-12)
    assert _ratio_exponent(func, "viscosity") == pytest.approx(speed_exp, abs=1e-12)
    assert _ratio_exponent(func, "pressure_viscosity") == pytest.approx(g_exp, abs=1e-12)
    assert _ratio_exponent(func, "load") == pytest.approx(w_exp, abs=1e-12)
    # E' enters U^a G^b W^c: exponent -a + b - c
    assert _ratio_exponent(func, "effective_modulus") == pytest.approx(
        -speed_exp + g_exp - w_exp, abs=1e-12
    )
    # R_x enters R_x U^a W^c: exponent 1 - a - 2c
    assert _ratio_exponent(func, "r_x") == pytest.approx(1 - speed_exp - 2 * w_exp, abs=1e-12)


def test_zero_speed_gives_no_film_and_sign_of_speed_ignored():
    for func in (film_thickness_central, film_thickness_minimum):
        assert func(*_args(u_e=0.0)) == 0.0
        assert func(*_args(u_e=-10.0)) == func(*_args())


def test_zero_load_is_capped_at_floor():
    floor_load = W_FLOOR * BASE["effective_modulus"] * BASE["r_x"] ** 2
    for func in (film_thickness_central, film_thickness_minimum):
        capped = func(*_args(load=floor_load))
        assert math.isfinite(capped) and capped > func(*_args())
        for q in (0.0, -1.0, floor_load * 0.5, math.nan):
            assert func(*_args(load=q)) == capped
        assert func(*_args(load=floor_load * 2)) < capped


def test_callable_from_njit_and_wrapper_validates():
    @njit
    def both(u):
        return film_thickness_central(
            u, 0.01, 2e-8, 2.28e11, 0.0045, 200.0, 8.0
        ), film_thickness_minimum(u, 0.01, 2e-8, 2.28e11, 0.0045, 200.0, 8.0)

    assert both(10.0) == film_thickness(*_args())
    with pytest.raises(ValueError, match="viscosity"):
        film_thickness(*_args(viscosity=0.0))
    with pytest.raises(ValueError, match="load"):
        film_thickness(*_args(load=-1.0))
    with pytest.raises(ValueError, match="kappa"):
        film_thickness(*_args(kappa=0.5))


def test_explicit_evaluation_and_ellipticity_factor():
    """Dimensionless groups evaluated by hand for BASE, and the κ factors of the two fits."""
    u = 0.01 * 10.0 / (2.28e11 * 0.0045)
    g = 2.0e-8 * 2.28e11
    w = 200.0 / (2.28e11 * 0.0045**2)
    assert (u, g, w) == pytest.approx((9.74659e-11, 4560.0, 4.33182e-05), rel=1e-5)
    h_c = 0.0045 * 2.69 * u**0.67 * g**0.53 * w**-0.067 * (1 - 0.61 * math.exp(-0.73 * 8.0))
    h_min = 0.0045 * 3.63 * u**0.68 * g**0.49 * w**-0.073 * (1 - math.exp(-0.68 * 8.0))
    assert film_thickness_central(*_args()) == pytest.approx(h_c, rel=1e-12)
    assert film_thickness_minimum(*_args()) == pytest.approx(h_min, rel=1e-12)
    # a typical spindle-bearing film is a few tenths of a micrometre, and h_min < h_c
    assert 0.05e-6 < h_min < h_c < 1e-6
    # κ enters only through (1 - 0.61 e^{-0.73κ}) and (1 - e^{-0.68κ})
    for kappa in (1.0, 3.0, 20.0):
        ratio_c = film_thickness_central(*_args(kappa=kappa)) / film_thickness_central(*_args())
        ratio_m = film_thickness_minimum(*_args(kappa=kappa)) / film_thickness_minimum(*_args())
        assert ratio_c == pytest.approx(
            (1 - 0.61 * math.exp(-0.73 * kappa)) / (1 - 0.61 * math.exp(-0.73 * 8.0)), rel=1e-12
        )
        assert ratio_m == pytest.approx(
            (1 - math.exp(-0.68 * kappa)) / (1 - math.exp(-0.68 * 8.0)), rel=1e-12
        )
