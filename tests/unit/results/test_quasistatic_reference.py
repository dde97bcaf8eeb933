"""The quasi-static Dataset of the speed benchmark's four configurations is the reference kept as
test data (tests/helpers/quasistatic_reference.py): every variable, coordinate and attribute, floats
within 1e-12 relative. Guards the speed work on the Dataset builder against any change of what it
holds."""

from __future__ import annotations

import pytest

from solver.models.quasistatic import solve_quasistatic
from tests.helpers.quasistatic_reference import (
    configuration_key,
    configurations,
    describe,
    differences,
    inputs_with_rule,
    load_reference,
)


@pytest.fixture(scope="module")
def reference():
    return load_reference()


@pytest.mark.parametrize(("name", "rule"), configurations())
def test_dataset_equals_reference(reference, name, rule):
    got = describe(solve_quasistatic(inputs_with_rule(name, rule)))
    found = differences(got, reference[configuration_key(name, rule)])
    assert not found, f"{len(found)} differences, first: " + "; ".join(found[:5])


def test_differences_sees_a_change(reference):
    """The comparison is not blind: a float 1e-11 off, a changed string and a missing key count."""
    want = reference[configuration_key(*configurations()[0])]
    got = describe(solve_quasistatic(inputs_with_rule(*configurations()[0])))
    got["data_vars"]["contact_load"]["values"][0][0] *= 1.0 + 1e-11
    got["attrs"]["kinematics"] += "x"
    del got["coords"]["ball_count"]
    found = differences(got, want)
    assert len(found) == 3, found
