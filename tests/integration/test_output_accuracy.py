"""The accuracy contract of the outputs a design review signs (docs/numerics.md, "Accuracy contract
of the outputs"): at the default settings every output of each contract case — per-ball contact
angles and loads, cage speed, ball spin, drive power, friction torque, losses by source — within
its allowance of a tolerance-1e-5 run (stored as test data, tests/helpers/accuracy_outputs.py),
and the energy balance closed within 1 % of the losses. Means over the window of the energy
balance, which leaves out the first shaft revolution."""

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
        inputs = A.case_inputs(name)
        balls = inputs.geometry.ball_count
        assert len(case["contact_angle_deg"]) == len(case["contact_load_N"]) == balls, name
        assert len(case["spin_to_roll"]) == 2, name
        # the means leave out the first shaft revolution (the ring-down from the quasi-static
        # start), as the energy balance does
        op = inputs.operating
        period = 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
        assert case["window_start_time_s"] >= period * (1.0 - 1e-9), name


def test_comparison_flags_each_output_just_beyond_its_allowance():
    reference = A.load_reference()["cases"]["209-radial"]
    assert max(A.deviations(reference, reference).values()) == pytest.approx(
        abs(reference["energy_balance_residual"]) / A.RESIDUAL_LIMIT
    )
    total = reference["total_power_loss_W"]
    spin = reference["spin_to_roll"]
    changes = {
        "friction_torque": {"friction_torque_N_m": reference["friction_torque_N_m"] * 1.021},
        "drive_power": {"drive_power_W": reference["drive_power_W"] * 0.979},
        "total_power_loss": {"total_power_loss_W": total * 1.021},
        "power_loss_by_source": {
            "power_loss_W": dict(
                reference["power_loss_W"], drag=reference["power_loss_W"]["drag"] + 0.021 * total
            )
        },
        "cage_speed": {"cage_speed_rad_s": reference["cage_speed_rad_s"] * 1.0011},
        "contact_angle": {
            "contact_angle_deg": [
                [a + 0.0051 for a in ball] for ball in reference["contact_angle_deg"]
            ]
        },
        "contact_load": {
            "contact_load_N": [[q * 1.0021 for q in ball] for ball in reference["contact_load_N"]]
        },
        "spin_to_roll": {"spin_to_roll": [s + 1.011 * max(0.01 * abs(s), 5e-4) for s in spin]},
        "energy_balance_residual": {"energy_balance_residual": 0.0101},
    }
    for output, change in changes.items():
        worst = A.deviations(dict(reference, **change), reference)
        assert worst[output] > 1.0, (output, worst)
        others = {k: v for k, v in worst.items() if k not in (output, "energy_balance_residual")}
        assert max(others.values(), default=0.0) <= 1.0, (output, worst)


def test_case_allowance_widens_only_its_own_output():
    reference = A.load_reference()["cases"]["218-heavy-combined"]
    moved = [[a + 0.02 for a in ball] for ball in reference["contact_angle_deg"]]
    worst = A.deviations(dict(reference, contact_angle_deg=moved), reference)
    assert A.within_contract("218-heavy-combined", worst)
    assert not A.within_contract("spindle-combined-load", worst)
    # an output the case has no allowance for keeps the plain contract
    torque = reference["friction_torque_N_m"] * (1 + 1.01 * A.TORQUE_RELATIVE)
    assert "friction_torque" not in A.CASE_ALLOWANCE["218-heavy-combined"]
    assert not A.within_contract(
        "218-heavy-combined",
        A.deviations(dict(reference, friction_torque_N_m=torque), reference),
    )
    # and an allowed output is still bounded: just past its allowance fails
    factor = 1 + 1.01 * A.LOAD_RELATIVE * A.CASE_ALLOWANCE["218-heavy-combined"]["contact_load"]
    loads = [[q * factor for q in ball] for ball in reference["contact_load_N"]]
    assert not A.within_contract(
        "218-heavy-combined", A.deviations(dict(reference, contact_load_N=loads), reference)
    )
    inside = 1 + 0.99 * A.LOAD_RELATIVE * A.CASE_ALLOWANCE["218-heavy-combined"]["contact_load"]
    loads = [[q * inside for q in ball] for ball in reference["contact_load_N"]]
    assert A.within_contract(
        "218-heavy-combined", A.deviations(dict(reference, contact_load_N=loads), reference)
    )


@pytest.mark.slow
@pytest.mark.parametrize("name", list(A.CASES))
def test_default_settings_keep_every_output_and_the_energy_balance(name):
    reference = A.load_reference()["cases"][name]
    ds = A.run(name)
    got = A.outputs(ds, reference["window_start_time_s"])  # the same window as the reference
    worst = A.deviations(got, reference)
    assert A.within_contract(name, worst), worst
    assert not [w for w in ds.racetrace.warnings() if "energy balance" in w]
