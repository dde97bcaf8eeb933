"""Palmgren's M0 + M1 and the SKF friction model (solver.physics.friction_estimates) against
numbers worked by hand from the catalogue formulas, in the catalogue's units (N mm, mm, mm^2/s,
r/min), with round inputs: d_m = 100 mm, nu = 10 mm^2/s, n = 1000 r/min. No published worked
example with numbers was found (docs/sources.md); the hand arithmetic is written out beside each
expected value. Then the low-speed branch and the monotonicity in load and speed."""

from __future__ import annotations

import itertools
import math

import pytest

from solver.physics import friction_estimates as fe

RPM = 2.0 * math.pi / 60.0  # rad/s per r/min
DM = 0.1  # m (100 mm)
NU = 10.0e-6  # m^2/s (10 mm^2/s)
N = 1000.0 * RPM  # rad/s
ACBB = fe.SKF_SERIES["72 B"]
SPEEDS_RPM = (300.0, 1000.0, 3000.0, 10000.0)
LOADS_N = (100.0, 1000.0, 5000.0, 20000.0)


def increasing(values) -> bool:
    return all(later > earlier for earlier, later in itertools.pairwise(values))


def test_palmgren_viscous_torque_above_the_switch():
    # nu n = 10 * 1000 = 1e4; 1e4^(2/3) = 464.16; M0 = 1e-7 * 1 * 464.16 * 100^3 = 46.416 N mm
    assert fe.palmgren_viscous_torque(1.0, DM, NU, N) == pytest.approx(46.416e-3, rel=1e-4)


def test_palmgren_viscous_torque_low_speed_branch_does_not_vanish():
    # nu n = 10 * 100 = 1000 < 2000: M0 = 160e-7 * 1 * 100^3 = 16 N mm, whatever the speed below
    low = fe.palmgren_viscous_torque(1.0, DM, NU, 100.0 * RPM)
    assert low == pytest.approx(16.0e-3, rel=1e-12)
    assert fe.palmgren_viscous_torque(1.0, DM, NU, 1.0 * RPM) == pytest.approx(low, rel=1e-12)
    # the two branches meet at nu n = 2000 within Palmgren's rounding (158.7 against 160): just
    # above, nu n = 2010, M0 = 1e-7 * 2010^(2/3) * 100^3 = 1e-7 * 159.27 * 1e6 = 15.927 N mm
    just_above = fe.palmgren_viscous_torque(1.0, DM, NU, 201.0 * RPM)
    assert just_above == pytest.approx(15.927e-3, rel=1e-4)
    assert abs(just_above / low - 1.0) < 0.01


def test_palmgren_load_torque_and_its_load():
    # angular contact: P1 = max(F_r, F_a - 0.1 F_r) = max(1000, 2000 - 100) = 1900 N
    assert fe.palmgren_load(fe.ANGULAR_CONTACT, 1000.0, 2000.0) == pytest.approx(1900.0)
    # deep groove: P1 = max(F_r, 3 F_a - 0.1 F_r) = max(1000, 300 - 100) = 1000 N
    assert fe.palmgren_load(fe.DEEP_GROOVE, 1000.0, 100.0) == pytest.approx(1000.0)
    assert fe.palmgren_load(fe.DEEP_GROOVE, 1000.0, 1000.0) == pytest.approx(2900.0)
    # f1 = 0.001 (P0/C0)^0.33 = 0.001 * 0.1^0.33 = 4.677e-4; M1 = f1 1900 N * 100 mm = 88.87 N mm
    f1 = fe.palmgren_load_factor(fe.ANGULAR_CONTACT, 1000.0, 10000.0)
    assert f1 == pytest.approx(4.6774e-4, rel=1e-4)
    assert fe.palmgren_load_torque(f1, 1900.0, DM) == pytest.approx(88.87e-3, rel=1e-3)


def test_iso76_static_equivalent_load():
    # deep groove: max(F_r, 0.6 F_r + 0.5 F_a) = max(1000, 600 + 1000) = 1600 N
    assert fe.static_equivalent_load(fe.DEEP_GROOVE, 1000.0, 2000.0, 0.0) == pytest.approx(1600.0)
    # 40 deg: 0.5 * 1000 + 0.26 * 2000 = 1020 N
    forty = math.radians(40.0)
    assert fe.static_equivalent_load(fe.ANGULAR_CONTACT, 1000.0, 2000.0, forty) == pytest.approx(
        1020.0
    )


def test_static_load_rating_from_the_reference_stress():
    # 4.2 GPa reached at Q = (4.2e9 / 1e9)^3 = 74.09 N when 1 N gives 1 GPa; C0 = 10 * 74.09 / 5
    assert fe.static_load_rating(10, 0.0, 1.0e9) == pytest.approx(148.18, rel=1e-4)


def test_skf_factors_by_hand():
    # phi_ish = 1 / (1 + 1.84e-9 (1000 * 100)^1.28 * 10^0.64) = 1 / (1 + 1.84e-9 * 2.5119e6 *
    # 4.3652) = 1 / 1.020176 = 0.98022
    assert fe.skf_inlet_shear_factor(DM, NU, N) == pytest.approx(0.98022, rel=1e-4)
    # phi_rs (d = 60, D = 140 mm, K_Z = 4.4, K_rs = 6e-8): 6e-8 * 10 * 1000 * 200 *
    # sqrt(4.4 / 160) = 0.12 * 0.16583 = 0.019900; exp(-0.019900) = 0.98030
    assert fe.skf_replenishment_factor(0.06, 0.14, NU, N, 4.4) == pytest.approx(0.98030, rel=1e-4)
    # phi_bl = exp(-2.6e-8 (1e4)^1.4 * 100) = exp(-2.6e-8 * 3.98107e5 * 100) = exp(-1.03508)
    assert fe.skf_boundary_weighting(DM, NU, N) == pytest.approx(0.35520, rel=1e-4)


def test_skf_angular_contact_torque_by_hand():
    # 72 B: F_g = 1.90e-12 * 100^4 * 1000^2 = 190 N (rolling), 191 N (sliding, S3)
    # G_rr = 5.03e-7 * 100^1.97 * (1000 + 190 + 1.97 * 2000)^0.54 = 0.44160
    # G_sl = 1.30e-2 * 100^0.26 * ((1000 + 191)^(4/3) + 0.68 * 2000^(4/3)) = 1281.06
    g_rr, g_sl = fe.skf_load_variables(ACBB, DM, N, 1000.0, 2000.0, 1.0)
    assert g_rr == pytest.approx(0.44160, rel=1e-4)
    assert g_sl == pytest.approx(1281.06, rel=1e-5)
    skf = fe.skf_torque(ACBB, 0.06, 0.14, NU, N, 1000.0, 2000.0, 1.0, mu_ehl=0.05)
    # M_rr = 0.98022 * 0.98030 * 0.44160 * (1e4)^0.6 = 0.424336 * 251.189 = 106.59 N mm
    assert skf.rolling == pytest.approx(106.59e-3, rel=1e-3)
    # mu_sl = 0.35520 * 0.15 + 0.64480 * 0.05 = 0.085520; M_sl = 1281.06 * 0.085520 = 109.56 N mm
    assert skf.sliding_friction == pytest.approx(0.085520, rel=1e-4)
    assert skf.sliding == pytest.approx(109.56e-3, rel=1e-3)
    assert skf.drag == 0.0
    assert skf.total == pytest.approx(216.15e-3, rel=1e-3)


def test_skf_deep_groove_load_variables_by_hand():
    # 62: radial only, d_m = 65 mm, F_r = 4450 N: G_rr = 3.9e-7 * 65^1.96 * 4450^0.54 =
    # 3.9e-7 * 3576.4 * 93.34 = 0.13017, G_sl = 3.23e-3 * 65^-0.26 * 4450^(5/3) = 1313.5
    series = fe.SKF_SERIES["62"]
    g_rr, g_sl = fe.skf_load_variables(series, 0.065, N, 4450.0, 0.0, 2.0e4)
    assert g_rr == pytest.approx(3.9e-7 * 65**1.96 * 4450**0.54, rel=1e-12)
    assert g_rr == pytest.approx(0.13016, rel=1e-4)
    assert g_sl == pytest.approx(1313.5, rel=1e-4)
    # with an axial load the contact angle alpha_F = 24.6 (F_a / C0)^0.24 deg enters:
    # F_a = 1000, C0 = 20000: alpha_F = 24.6 * 0.05^0.24 = 11.986 deg, sin = 0.20768
    g_rr_a, _ = fe.skf_load_variables(series, 0.065, N, 4450.0, 1000.0, 2.0e4)
    assert g_rr_a == pytest.approx(
        3.9e-7 * 65**1.96 * (4450.0 + 1.7 / 0.20768 * 1000.0) ** 0.54, rel=1e-3
    )


@pytest.mark.parametrize("kind", fe.BEARING_KINDS)
def test_palmgren_grows_with_load_and_speed(kind):
    def total(speed_rpm, fr, fa):
        p0 = fe.static_equivalent_load(kind, fr, fa, math.radians(40.0))
        f1 = fe.palmgren_load_factor(kind, p0, 50_000.0)
        m1 = fe.palmgren_load_torque(f1, fe.palmgren_load(kind, fr, fa), DM)
        return fe.palmgren_viscous_torque(1.0, DM, NU, speed_rpm * RPM) + m1

    assert increasing([total(speed, 1000, 500) for speed in SPEEDS_RPM])
    assert increasing([total(1000, load, load) for load in LOADS_N])


@pytest.mark.parametrize("label", ["62", "72 B"])
def test_skf_grows_with_load_and_speed(label):
    series = fe.SKF_SERIES[label]

    def total(speed_rpm, fr, fa):
        return fe.skf_torque(series, 0.06, 0.14, NU, speed_rpm * RPM, fr, fa, 50_000.0, 0.05).total

    assert increasing([total(speed, 1000, 500) for speed in SPEEDS_RPM])
    assert increasing([total(1000, load, load) for load in LOADS_N])
