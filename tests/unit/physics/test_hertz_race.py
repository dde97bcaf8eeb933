"""Per-race Hertz table (solver.physics.hertz_race) against the exact solution of
solver.physics.hertz, through its documented relations to K, a and b."""

import math

import numpy as np
import pytest
from numba import njit

from solver.physics import hertz
from solver.physics.hertz_race import (
    RACE_TABLE_NODES,
    race_coefficients,
    race_coefficients_direct,
    race_table,
)

STATED_BOUND = 1e-10  # the accuracy stated in the module docstring

# (D, d_m, f_i, f_o): a spindle bearing, a 218-size bearing, and very close and very open grooves
BEARINGS = [
    (0.00794, 0.0525, 0.52, 0.52),
    (0.0222, 0.115, 0.515, 0.5225),
    (0.0127, 0.07, 0.5005, 0.5005),
    (0.0127, 0.07, 0.57, 0.6),
]


@njit(cache=True)
def _sweep(table, c):
    """Called from another njit function, as the dynamic model does."""
    out = np.empty((6, c.size))
    for j in range(c.size):
        k, s, a, b, film, rolling = race_coefficients(table, c[j])
        out[0, j], out[1, j], out[2, j], out[3, j], out[4, j], out[5, j] = k, s, a, b, film, rolling
    return out


@pytest.mark.parametrize("bearing", BEARINGS)
@pytest.mark.parametrize("race", ["inner", "outer"])
def test_dense_sweep_within_stated_error(bearing, race):
    d, dm, fi, fo = bearing
    f = fi if race == "inner" else fo
    table = race_table(d, dm, f, race == "inner")
    # nodes, two points inside every interval, and a dense uniform sweep
    n = RACE_TABLE_NODES - 1
    c = np.concatenate(
        (np.linspace(0.0, 1.0, 4001), (np.arange(n) + 0.31) / n, (np.arange(n) + 0.77) / n)
    )
    got = _sweep(table, c)
    load, e_mod = 350.0, 2.3e11
    csum, fdiff = hertz.curvature_sum_and_difference(d, f, d * c / dm, race)
    exact = hertz.hertz_contact(load, csum, fdiff, e_mod)
    q13 = (load / e_mod) ** (1.0 / 3.0)
    np.testing.assert_allclose(got[0], exact.kappa, rtol=STATED_BOUND, atol=0)
    np.testing.assert_allclose(got[1] * e_mod, exact.stiffness, rtol=STATED_BOUND, atol=0)
    np.testing.assert_allclose(got[2] * q13, exact.semi_major, rtol=STATED_BOUND, atol=0)
    np.testing.assert_allclose(got[3] * q13, exact.semi_minor, rtol=STATED_BOUND, atol=0)
    # the film laws' ellipticity terms, from kappa as defined in solver.physics.ehl / rheology
    np.testing.assert_allclose(
        got[4], 1.0 - 0.61 * np.exp(-0.73 * exact.kappa), rtol=STATED_BOUND, atol=0
    )
    np.testing.assert_allclose(got[5], 0.348 * np.log(exact.kappa), rtol=0, atol=STATED_BOUND)


@pytest.mark.parametrize("race", ["inner", "outer"])
def test_direct_values_match_the_table(race):
    """The fallback outside the table computes the same six values."""
    d, dm, fi, fo = BEARINGS[1]
    f = fi if race == "inner" else fo
    table = race_table(d, dm, f, race == "inner")
    for c in (0.0, 0.3, 0.77, 1.0):
        direct = race_coefficients_direct(d, f, d * c / dm, race == "inner")
        np.testing.assert_allclose(_sweep(table, np.array([c]))[:, 0], direct, rtol=1e-10)


def test_outside_the_table_is_nan():
    table = race_table(*BEARINGS[0][:3], True)
    for c in (-1e-9, 1.0 + 1e-12, math.nan):
        assert all(math.isnan(v) for v in _sweep(table, np.array([c]))[:, 0])
    assert not any(math.isnan(v) for v in _sweep(table, np.array([0.0, 1.0])).ravel())
