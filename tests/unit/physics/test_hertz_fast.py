"""Fast (tabulated, numba) Hertz contact against the exact solution of solver.physics.hertz."""

import math

import numpy as np
import pytest
from numba import njit

from solver.physics import hertz, hertz_fast
from solver.physics.hertz_fast import (
    F_MAX,
    X_MAX,
    contact_ellipse_fast,
    contact_stiffness_fast,
    curvature_sum_and_difference_fast,
    equivalent_radii_fast,
    hertz_coefficients_fast,
    hertz_contact_fast,
)

STATED_BOUND = 1e-10  # the accuracy claimed in the module docstring


@njit(cache=True)
def _sweep(load, curvature_sum, f, e_mod):
    """Called from another njit function: all fast outputs for arrays of F."""
    out = np.empty((8, f.size))
    for j in range(f.size):
        out[0, j], out[1, j], out[2, j] = hertz_coefficients_fast(f[j])
        a, b, d, p, k = hertz_contact_fast(load, curvature_sum, f[j], e_mod)
        out[3, j], out[4, j], out[5, j], out[6, j], out[7, j] = a, b, d, p, k
    return out


def test_docstring_states_the_tested_bound():
    assert "1e-10 relative" in hertz_fast.__doc__


def test_dense_sweep_within_stated_error():
    # every table interval: nodes, midpoints and a dense uniform sweep in x = ln(Ry/Rx)
    step = hertz_fast.TABLE_STEP
    x = np.concatenate(
        (np.linspace(0.0, X_MAX, 50_001), (np.arange(round(X_MAX / step)) + 0.5) * step)
    )
    f = np.tanh(0.5 * x)
    load, curvature_sum, e_mod = 1234.0, 180.0, 2.3e11
    fast = _sweep(load, curvature_sum, f, e_mod)
    exact = hertz.hertz_contact(load, curvature_sum, f, e_mod)
    reference = (
        exact.kappa,
        exact.elliptic_k,
        exact.elliptic_e,
        exact.semi_major,
        exact.semi_minor,
        exact.approach,
        exact.max_pressure,
        exact.stiffness,
    )
    for row, ref in zip(fast, reference, strict=True):
        rel = np.max(np.abs(row / ref - 1.0))
        assert rel <= STATED_BOUND


def test_ball_bearing_range_spot_values():
    for f in (0.5, 0.9, 0.93, 0.95, 0.99, 0.9995):
        assert hertz_coefficients_fast(f) == pytest.approx(hertz.ellipticity_exact(f), rel=1e-10)


def test_clamping_outside_table():
    at_max = hertz_coefficients_fast(F_MAX)
    for f in (F_MAX + 1e-9, 0.99999999, 1.0, 1.5, math.inf):
        assert hertz_coefficients_fast(f) == at_max
    for f in (-1e-3, -1.0, -math.inf):
        kappa, big_k, big_e = hertz_coefficients_fast(f)
        assert kappa == pytest.approx(1.0, abs=1e-12)
        assert big_k == pytest.approx(math.pi / 2, abs=1e-12)
        assert big_e == pytest.approx(math.pi / 2, abs=1e-12)
    assert all(math.isnan(v) for v in hertz_coefficients_fast(math.nan))


def test_zero_and_negative_load_give_zero_ellipse():
    assert contact_ellipse_fast(0.0, 150.0, 0.9, 2.3e11) == (0.0, 0.0, 0.0, 0.0)
    assert contact_ellipse_fast(-5.0, 150.0, 0.9, 2.3e11) == (0.0, 0.0, 0.0, 0.0)
    assert contact_ellipse_fast(math.nan, 150.0, 0.9, 2.3e11) == (0.0, 0.0, 0.0, 0.0)


def test_stiffness_consistent_with_ellipse():
    s, f, e = 160.0, 0.93, 2.28e11
    k = contact_stiffness_fast(s, f, e)
    for q in (1.0, 100.0, 1e4):
        delta = contact_ellipse_fast(q, s, f, e)[2]
        assert k * delta**1.5 == pytest.approx(q, rel=1e-12)


@pytest.mark.parametrize("is_inner, race", [(True, "inner"), (False, "outer")])
def test_curvature_and_radii_match_exact(is_inner, race):
    for d, f, g in ((0.022225, 0.5232, 0.1369), (0.0079, 0.56, 0.16), (0.01, 0.515, 0.0)):
        assert curvature_sum_and_difference_fast(d, f, g, is_inner) == pytest.approx(
            hertz.curvature_sum_and_difference(d, f, g, race), rel=1e-14
        )
        assert equivalent_radii_fast(d, f, g, is_inner) == pytest.approx(
            hertz.equivalent_radii(d, f, g, race), rel=1e-14
        )


def test_table_is_read_only():
    with pytest.raises(ValueError):
        hertz_fast._TABLE[0, 0] = 1.0
