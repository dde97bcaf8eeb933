"""The accuracy contract of the outputs a design review signs (docs/numerics.md): at the default
settings the friction torque and the losses are within 2 % and the cage speed within 0.1 % of a
tolerance-1e-5 run (stored as test data, tests/helpers/accuracy_outputs.py), and the energy balance
closes within 1 % of the losses."""

from __future__ import annotations

import math

import pytest

from tests.helpers import accuracy_outputs as A


def test_reference_data_says_how_it_was_made():
    reference = A.load_reference()
    assert reference["tolerance"] == A.REFERENCE_TOLERANCE
    assert set(reference["cases"]) == set(A.CASES)
    for name, case in reference["cases"].items():
        # the tight runs close their own energy balance and carry every output
        assert abs(case["energy_balance_residual"]) <= A.RESIDUAL_LIMIT, name
        assert math.isfinite(case["friction_torque_N_m"]) and case["friction_torque_N_m"] > 0.0
        assert sum(case["power_loss_W"].values()) == pytest.approx(case["total_power_loss_W"])


def test_torque_comparison_flags_a_deviation_beyond_two_percent():
    reference = A.load_reference()["cases"]["209-radial"]
    off = dict(reference, friction_torque_N_m=reference["friction_torque_N_m"] * 1.021)
    within = dict(reference, friction_torque_N_m=reference["friction_torque_N_m"] * 0.981)
    assert A.deviation(off, reference) > A.TORQUE_RELATIVE
    assert A.deviation(within, reference) <= A.TORQUE_RELATIVE


@pytest.mark.slow
@pytest.mark.parametrize("name", A.CASES)
def test_default_settings_keep_torque_and_energy_balance(name):
    reference = A.load_reference()["cases"][name]
    ds = A.run(name)
    got = A.outputs(ds)
    assert abs(got["energy_balance_residual"]) <= A.RESIDUAL_LIMIT, got
    assert A.deviation(got, reference) <= A.TORQUE_RELATIVE, (got, reference)
    assert A.deviation(got, reference, "total_power_loss_W") <= A.LOSS_RELATIVE
    assert A.deviation(got, reference, "cage_speed_rad_s") <= A.CAGE_RELATIVE
    assert not [w for w in ds.racetrace.warnings() if "energy balance" in w]
