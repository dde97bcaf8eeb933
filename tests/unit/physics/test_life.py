"""Rating life (ISO 281, ISO/TS 16281) against hand-worked examples.

Every expected number below is worked out step by step in the comments from the clauses of the
standards (ISO 281:2007 Tables 1-3 and eq. 2-5; ISO/TS 16281:2008 ball-bearing raceway ratings,
equivalent loads and the combination with e = 10/9), not by calling the code under test.
"""

import math
import warnings

import numpy as np
import pytest

from solver.physics import life

# 7008C-class spindle bearing (assets/bearings/7008C-hybrid-spindle.toml)
D = 7.144e-3
DM = 54.0e-3
Z = 18
ALPHA = math.radians(15.0)


def test_fc_table_rows_and_interpolation():
    # ISO 281 Table 1 rows are returned as given, and linear in between
    assert life.rating_factor_fc(0.05) == pytest.approx(46.7)
    assert life.rating_factor_fc(0.20) == pytest.approx(59.9)
    # 0.13 lies half-way between 0.12 (57.5) and 0.14 (58.8): 58.15
    assert life.rating_factor_fc(0.13) == pytest.approx(58.15)
    with pytest.raises(life.LifeRangeError, match="Table 1"):
        life.rating_factor_fc(0.45)


def test_basic_dynamic_load_rating_7008c():
    # ISO 281 eq. 2 (D_w = 7.144 mm <= 25.4 mm), i = 1:
    #   gamma = D_w cos(alpha) / D_pw = 7.144 * 0.965926 / 54 = 0.127788
    #   f_c   = 57.5 + (0.127788 - 0.12) / 0.02 * (58.8 - 57.5) = 58.0062   (Table 1)
    #   (i cos alpha)^0.7 = 0.965926^0.7 = 0.976024
    #   Z^(2/3) = 18^(2/3) = 6.868285
    #   D_w^1.8 = 7.144^1.8 = 34.44249
    #   C_r = 1.3 * 58.0062 * 0.976024 * 6.868285 * 34.44249 = 17 410.9 N
    assert life.basic_dynamic_load_rating(D, DM, ALPHA, Z) == pytest.approx(17410.9, rel=2e-5)


def test_basic_dynamic_load_rating_reduced_for_groove_radii_above_the_table():
    # ISO 281 Table 1 holds for f_i <= 0.52, f_o <= 0.53 (ISO/TR 1281-1); the 7008C-class bearing
    # has f_i = 0.54, so f_c is reduced by the ratio of the Lundberg-Palmgren bearing ratings
    # Q_c = (Q_ci^(-10/3) + Q_co^(-10/3))^(-3/10) with its own and with the table's conformities
    # (the factor b_m 98.1 (gamma / cos a)^0.3 D^1.8 Z^(-1/3) common to both raceways cancels):
    #   gamma = 0.127788 (above); (2f/(2f-1))^0.41: 0.52 -> 3.803112, 0.53 -> 3.245887,
    #   0.54 -> 2.906945; inner (1-g)^1.39/(1+g)^(1/3) = 0.794429, outer (1+g)^1.39/(1-g)^(1/3)
    #   = 1.237055
    #   own:   inner 2.906945 * 0.794429 = 2.309361, outer 3.245887 * 1.237055 = 4.015341
    #          (2.309361^(-10/3) + 4.015341^(-10/3))^(-0.3) = 2.209814
    #   table: inner 3.803112 * 0.794429 = 3.021302, outer 4.015341
    #          (3.021302^(-10/3) + 4.015341^(-10/3))^(-0.3) = 2.738590
    #   factor = 2.209814 / 2.738590 = 0.806917; C_r = 17 410.9 * 0.806917 = 14 049.2 N
    ratio = life.groove_radius_factor(D, DM, 0.54, 0.53, ALPHA, Z)
    assert ratio == pytest.approx(0.806917, rel=1e-5)
    rated = life.basic_dynamic_load_rating(D, DM, ALPHA, Z, 1, 0.54, 0.53)
    assert rated == pytest.approx(14049.2, rel=2e-5)
    # radii at or below the table's do not raise the rating (the 209: f_i = f_o = 0.52)
    assert life.groove_radius_factor(D, DM, 0.52, 0.52, ALPHA, Z) == 1.0
    assert life.basic_dynamic_load_rating(D, DM, ALPHA, Z, 1, 0.51, 0.515) == pytest.approx(
        17410.9, rel=2e-5
    )


def test_iso281_and_reference_life_agree_for_a_pure_axial_load_on_the_spindle_bearing():
    """Both standards describe a pure axial load alike (every ball loaded equally), so with the
    bearing's own conformities (f_i = 0.54) in both they agree: L_10 of the reduced C_r (14 049.2
    N, above) at P = Y F_a = 1.342165 * 500 = 671.08 N is (14 049.2 / 671.08)^3 = 9 175.3 million
    revolutions; L_10r at 17 deg = 9 646.2 (test_reference_life_uniform_axial_load): 1.05 times
    it. Table 1's f_c alone (that of f_i = 0.52) gives L_10 = 17 463.7, 45 % above L_10r."""
    c = life.basic_dynamic_load_rating(D, DM, ALPHA, Z, 1, 0.54, 0.53)
    l10 = life.basic_rating_life(c, life.equivalent_dynamic_load(500.0, 0.0, ALPHA, D, Z))
    assert l10 == pytest.approx(9175.35, rel=1e-4)
    assert 9646.18 / l10 == pytest.approx(1.0, abs=0.06)


def test_basic_dynamic_load_rating_large_ball_uses_eq_3():
    # D_w = 30 mm > 25.4 mm: C_r = 3.647 b_m f_c (cos alpha)^0.7 Z^(2/3) D_w^1.4
    #   alpha = 40 deg, D_pw = 30 cos40 / 0.1 = 229.81 mm -> gamma = 0.10, f_c = 55.5
    #   (cos 40)^0.7 = 0.766044^0.7 = 0.829808; 12^(2/3) = 5.241483; 30^1.4 = 116.9418
    #   C_r = 3.647 * 1.3 * 55.5 * 0.829808 * 5.241483 * 116.9418 = 133 836 N
    d, alpha = 30e-3, math.radians(40.0)
    dm = d * math.cos(alpha) / 0.10
    expected = 3.647 * 1.3 * 55.5 * 0.829808 * 5.241483 * 116.9418
    assert life.basic_dynamic_load_rating(d, dm, alpha, 12) == pytest.approx(expected, rel=1e-5)


def test_equivalent_load_15_degree_interpolates_in_relative_axial_load():
    # ISO 281 Table 3, alpha = 15 deg, F_a = 500 N, F_r = 300 N:
    #   f_0 F_a / C_0r = F_a / (i Z D_w^2 cos alpha) = 500 / (18 * 7.144^2 * 0.965926) = 0.56347
    #   between rows 0.357 (e 0.40, Y 1.40) and 0.714 (e 0.43, Y 1.30): t = 0.578347
    #   e = 0.40 + 0.03 t = 0.41735; Y = 1.40 - 0.10 t = 1.342165; X = 0.44
    #   F_a / F_r = 1.667 > e -> P_r = 0.44 * 300 + 1.342165 * 500 = 803.08 N
    x, y, e = life.load_factors(500.0, 300.0, ALPHA, D, Z)
    assert (x, y, e) == pytest.approx((0.44, 1.342165, 0.41735), rel=1e-5)
    assert life.equivalent_dynamic_load(500.0, 300.0, ALPHA, D, Z) == pytest.approx(
        803.083, rel=1e-5
    )
    # L_10 = (17 410.9 / 803.083)^3 = 21.6799^3 = 10 190 million revolutions
    c = life.basic_dynamic_load_rating(D, DM, ALPHA, Z)
    assert life.basic_rating_life(c, 803.083) == pytest.approx(10190.2, rel=1e-4)


def test_equivalent_load_table_rows_by_contact_angle():
    # alpha = 40 deg: e = 1.14, X = 0.35, Y = 0.57. F_a = 2000, F_r = 1000 -> 2 > e:
    #   P = 0.35 * 1000 + 0.57 * 2000 = 1490 N
    alpha = math.radians(40.0)
    assert life.equivalent_dynamic_load(2000.0, 1000.0, alpha, D, Z) == pytest.approx(1490.0)
    # F_a / F_r = 1.0 <= e -> P = F_r
    assert life.equivalent_dynamic_load(1000.0, 1000.0, alpha, D, Z) == pytest.approx(1000.0)
    # alpha = 27.5 deg: half-way between 25 (0.68, 0.41, 0.87) and 30 (0.80, 0.39, 0.76)
    x, y, e = life.load_factors(2000.0, 1000.0, math.radians(27.5), D, Z)
    assert (x, y, e) == pytest.approx((0.40, 0.815, 0.74))
    # pure axial load: P = Y F_a
    assert life.equivalent_dynamic_load(1000.0, 0.0, alpha, D, Z) == pytest.approx(570.0)
    with pytest.raises(life.LifeRangeError, match="contact angle"):
        life.load_factors(1000.0, 0.0, math.radians(10.0), D, Z)
    # a pure radial load is P = F_r at any contact angle (F_a / F_r = 0 <= e in every row)
    assert life.equivalent_dynamic_load(0.0, 800.0, math.radians(10.0), D, Z) == 800.0


def test_raceway_load_ratings_7008c_at_17_degrees():
    # ISO/TS 16281 (Lundberg-Palmgren, ISO/TR 1281-1) with b_m = 1.3, f_i = 0.54, f_o = 0.53,
    # alpha = 17 deg:
    #   gamma = 7.144 cos17 / 54 = 0.1265156
    #   (2f/(2f-1))^0.41: inner (1.08/0.08)^0.41 = 2.906945, outer (1.06/0.06)^0.41 = 3.245887
    #   inner (1-g)^1.39/(1+g)^(1/3) = 0.7963408; outer (1+g)^1.39/(1-g)^(1/3) = 1.2345149
    #   (gamma/cos alpha)^0.3 = (7.144/54)^0.3 = 0.5450851; D^1.8 = 34.44249; Z^(-1/3) = 0.3815714
    #   Q_ci = 1.3 * 98.1 * 2.906945 * 0.7963408 * 0.5450851 * 34.44249 * 0.3815714 = 2114.87 N
    #   Q_co = 1.3 * 98.1 * 3.245887 * 1.2345149 * 0.5450851 * 34.44249 * 0.3815714 = 3660.81 N
    alpha = math.radians(17.0)
    assert life.raceway_load_rating(D, DM, 0.54, alpha, Z, True) == pytest.approx(2114.87, rel=1e-5)
    assert life.raceway_load_rating(D, DM, 0.53, alpha, Z, False) == pytest.approx(
        3660.81, rel=1e-5
    )
    # one rating per contact angle when given an array
    both = life.raceway_load_rating(D, DM, 0.54, np.radians([17.0, 17.0]), Z, True)
    assert both.shape == (2,)


def test_reference_life_uniform_axial_load():
    # Pure axial load 500 N, every ball at 17 deg: Q = 500 / (18 sin 17) = 95.0084 N on both
    # races; every mean (cubic or 10/3) of equal loads is that load.
    #   L_i = (2114.87 / 95.0084)^3 = 11 029.7, L_o = (3660.81 / 95.0084)^3 = 57 206
    #   L_10r = (L_i^(-10/9) + L_o^(-10/9))^(-9/10) = 9 646.2 million revolutions
    alpha = math.radians(17.0)
    q = np.full(Z, 500.0 / (Z * math.sin(alpha)))
    qci = life.raceway_load_rating(D, DM, 0.54, alpha, Z, True)
    qco = life.raceway_load_rating(D, DM, 0.53, alpha, Z, False)
    l_i = life.raceway_life(q, qci, rotating=True)
    l_o = life.raceway_life(q, qco, rotating=False)
    assert l_i == pytest.approx(11029.7, rel=1e-4)
    assert l_o == pytest.approx(57206.3, rel=1e-4)
    assert life.combined_life(l_i, l_o) == pytest.approx(9646.18, rel=1e-4)


def test_equivalent_load_means():
    # loads 100, 0, 0, 0 (one loaded ball of four):
    #   cubic mean  = (100^3 / 4)^(1/3) = 100 / 4^(1/3) = 62.996
    #   10/3 mean   = 100 / 4^(3/10) = 65.975
    q = [100.0, 0.0, 0.0, 0.0]
    assert life.equivalent_contact_load(q, rotating=True) == pytest.approx(62.9961, rel=1e-5)
    assert life.equivalent_contact_load(q, rotating=False) == pytest.approx(65.9754, rel=1e-5)
    # raceway life with Q_c = 1000: (1000 / 62.996)^3 = 4000 (rotating);
    # stationary: (1000 / 65.975)^3 = 4^(9/10) * 1000 = 3482.2
    assert life.raceway_life(q, 1000.0, rotating=True) == pytest.approx(4000.0)
    assert life.raceway_life(q, 1000.0, rotating=False) == pytest.approx(3482.20, rel=1e-5)
    assert life.raceway_life([0.0, 0.0], 1000.0, rotating=True) == math.inf


@pytest.mark.parametrize(("alpha_deg", "gamma"), [(25.0, 0.10), (15.0, 0.1278), (40.0, 0.20)])
def test_reference_life_reproduces_iso281_at_its_defining_load(alpha_deg, gamma):
    """ISO 281's C_r is the radial load for a life of 1 million revolutions with half the ring
    loaded (zero clearance: Q(psi) = Q_max cos(psi)^1.5, the load-zone factor 0.5). Feeding that
    distribution at F_r = C_r, inner ring rotating, into ISO/TS 16281 with the conformities the
    f_c table assumes (f_i = 0.52, f_o = 0.53) must give L_10r close to 1: the two standards come
    from the same Lundberg-Palmgren theory; the table's f_c carries a small reduction against it
    (within 7 % in life here)."""
    alpha = math.radians(alpha_deg)
    z = 14
    dm = D * math.cos(alpha) / gamma
    c = life.basic_dynamic_load_rating(D, dm, alpha, z)
    psi = 2.0 * np.pi * np.arange(z) / z
    shape = np.clip(np.cos(psi), 0.0, None) ** 1.5
    q = c / (math.cos(alpha) * np.sum(shape * np.cos(psi))) * shape  # sum Q cos(a) cos(psi) = C
    l_i = life.raceway_life(q, life.raceway_load_rating(D, dm, 0.52, alpha, z, True), True)
    l_o = life.raceway_life(q, life.raceway_load_rating(D, dm, 0.53, alpha, z, False), False)
    assert life.combined_life(l_i, l_o) == pytest.approx(1.0, abs=0.08)


def test_life_hours():
    # 10 190 million revolutions at 20 000 rpm: 10 190e6 / (20 000 * 60) = 8 491.7 h
    omega = 20000.0 * 2.0 * math.pi / 60.0
    assert life.life_hours(10190.0, omega) == pytest.approx(8491.67, rel=1e-5)
    assert life.life_hours(10190.0, 0.0) == math.inf
    with warnings.catch_warnings():  # a life beyond a float's range is inf, without a warning
        warnings.simplefilter("error")
        assert life.life_hours(np.float64(1e305), np.float64(1e-3)) == math.inf
    assert life.combined_life(math.inf, math.inf) == math.inf
