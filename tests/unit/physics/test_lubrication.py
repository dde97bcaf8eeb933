"""The oil fraction of the drag mixture by lubrication method (solver.physics.lubrication) against
closed forms and limits: no supply gives air only, a bath below the lowest ball gives no churning,
the fraction grows with the supply and falls with the speed."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.physics import lubrication as lub

DM, D, Z = 54.0e-3, 7.144e-3, 18


def test_cavity_is_the_swept_annulus_less_the_balls():
    annulus = math.pi * DM * (0.7 * D) * D
    assert lub.cavity_volume(DM, D, Z) == pytest.approx(annulus - Z * math.pi * D**3 / 6.0)
    with pytest.raises(ValueError):
        lub.cavity_volume(DM, 0.0, Z)


def test_cage_speed_of_rolling_without_slip():
    """Inner ring turning, outer at rest: the cage turns at (1 - D cos(a) / d_m) / 2 of the shaft;
    both rings at one speed: the cage with them."""
    a = math.radians(15.0)
    g = D * math.cos(a) / DM
    assert lub.epicyclic_cage_speed(100.0, 0.0, DM, D, a) == pytest.approx(50.0 * (1 - g))
    assert lub.epicyclic_cage_speed(100.0, 100.0, DM, D, a) == pytest.approx(100.0)


def test_no_supply_is_air_only_and_the_fraction_grows_with_the_flow():
    cavity = lub.cavity_volume(DM, D, Z)
    assert lub.supply_oil_fraction(0.0, 900.0, cavity) == 0.0
    flows = np.geomspace(1e-12, 1e-5, 15)
    phis = [lub.supply_oil_fraction(q, 900.0, cavity) for q in flows]
    assert all(b > a for a, b in zip(phis, phis[1:], strict=False) if b < 1.0)
    # below the cap: the oil held for one cage revolution, Q 2 pi / w_c, over the cavity
    q = 1e-7
    assert phis[0] > 0.0
    assert lub.supply_oil_fraction(q, 900.0, cavity) == pytest.approx(
        q * 2 * math.pi / 900.0 / cavity
    )


def test_supply_fraction_falls_as_one_over_speed_and_is_capped():
    cavity = lub.cavity_volume(DM, D, Z)
    slow = lub.supply_oil_fraction(1e-6, 500.0, cavity)
    fast = lub.supply_oil_fraction(1e-6, 1000.0, cavity)
    assert slow == pytest.approx(2.0 * fast)
    assert lub.supply_oil_fraction(1.0, 500.0, cavity) == 1.0
    assert lub.supply_oil_fraction(1e-6, 0.0, cavity) == 1.0  # a cage at rest fills up
    assert lub.supply_oil_fraction(1e-6, -500.0, cavity) == slow
    with pytest.raises(ValueError):
        lub.supply_oil_fraction(-1e-6, 500.0, cavity)


def test_spherical_cap_fraction():
    assert lub.immersed_ball_fraction(0.5 * D, D) == pytest.approx(0.5)
    assert lub.immersed_ball_fraction(D, D) == pytest.approx(1.0)
    assert lub.immersed_ball_fraction(-D, D) == 0.0
    # a cap of height h: pi h^2 (3R - h) / 3 over 4 pi R^3 / 3
    h, r = 0.2 * D, 0.5 * D
    assert lub.immersed_ball_fraction(h, D) == pytest.approx(h * h * (3 * r - h) / (4 * r**3))


def test_bath_below_the_lowest_ball_does_not_churn_and_a_full_bath_submerges():
    assert lub.bath_oil_fraction(0.0, DM, D) == 0.0
    assert lub.bath_oil_fraction(-1e-3, DM, D) == 0.0
    assert lub.bath_oil_fraction(DM + D, DM, D) == pytest.approx(1.0)
    # the surface through the bearing's axis: half of every orbit, by symmetry
    assert lub.bath_oil_fraction(0.5 * (DM + D), DM, D) == pytest.approx(0.5, abs=1e-9)


def test_bath_fraction_rises_with_the_level():
    levels = np.linspace(0.0, DM + D, 40)
    phis = np.array([lub.bath_oil_fraction(h, DM, D) for h in levels])
    assert np.all(np.diff(phis) > 0.0)
    # a shallow bath wets only the balls near the bottom: far below the fraction of the orbit
    # under the level would give if whole balls were immersed
    shallow = lub.bath_oil_fraction(0.5 * D, DM, D)
    arc = math.acos(1.0 - 0.5 * D / (0.5 * DM)) / math.pi  # orbit share of centres below it
    assert 0.0 < shallow < arc
