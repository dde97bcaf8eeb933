"""Case.with_values: validated copies, None removes a key, estimates follow the bearing."""

from __future__ import annotations

import math

import pytest
import tomli_w

from solver.case import CaseError, parse_case


@pytest.fixture
def case(valid):
    return parse_case(tomli_w.dumps(valid))


def test_changes_only_the_given_keys(case):
    new = case.with_values(
        {"operating.axial_load_N": 300.0, "operating.radial_load_angle_deg": 45.0}
    )
    assert new.operating.axial_load_N == 300.0 and new.operating.radial_load_angle_deg == 45.0
    assert (
        new.bearing == case.bearing and new.operating.radial_load_N == case.operating.radial_load_N
    )
    assert case.operating.axial_load_N == 500.0  # the original is untouched (frozen)


def test_invalid_values_raise_with_all_problems(case):
    with pytest.raises(CaseError) as info:
        case.with_values({"operating.axial_load_N": -1.0, "bearing.ball_count": 1})
    keys = {p.key for p in info.value.problems}
    assert keys == {"operating.axial_load_N", "bearing.ball_count"}


def test_unknown_key_is_rejected_with_suggestion(case):
    with pytest.raises(CaseError) as info:
        case.with_values({"operating.axial_load": 1.0})
    assert "did you mean operating.axial_load_N?" in str(info.value)


def test_none_removes_a_key_to_switch_to_clearance(case):
    new = case.with_values(
        {"bearing.free_contact_angle_deg": None, "bearing.diametral_clearance_mm": 0.02}
    )
    assert new.bearing.free_contact_angle_deg is None
    a0 = (0.54 + 0.53 - 1.0) * 7.144e-3
    assert math.isclose(new.geometry().free_contact_angle, math.acos(1.0 - 0.02e-3 / (2 * a0)))


def test_estimates_follow_an_edited_bearing(case):
    new = case.with_values({"bearing.ball_diameter_mm": 8.0})
    assert math.isclose(new.cage.pocket_diametral_clearance_mm, 0.028 * 8.0)
    kept = case.with_values({"cage.pocket_diametral_clearance_mm": 0.25}).with_values(
        {"bearing.ball_diameter_mm": 8.0}
    )
    assert kept.cage.pocket_diametral_clearance_mm == 0.25  # given values stay
    assert "cage.pocket_diametral_clearance_mm" not in kept.estimated


def test_sections_and_subtables_are_created(case):
    new = case.with_values({"lubricant.traction.mu_max": 0.07, "lubricant.viscosity_Pas": 0.02})
    assert new.lubricant.traction.mu_max == 0.07 and new.lubricant.viscosity_Pas == 0.02
    assert new.lubricant.traction.mu_infinity == 0.036  # documented default oil
    new = case.with_values(
        {
            "materials.m50": {
                "youngs_modulus_GPa": 203.0,
                "poisson_ratio": 0.28,
                "density_kg_m3": 7600.0,
            },
            "bearing.ring_material": "m50",
        }
    )
    assert new.ring_material.youngs_modulus == 203.0e9 and new.ring_material.name == "m50"
