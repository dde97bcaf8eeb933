"""The quasi-static Dataset of the speed benchmark's four configurations is the reference kept as
test data (tests/helpers/quasistatic_reference.py): every variable, coordinate and attribute, floats
within the solver's convergence tolerance (TOLERANCE there, relative to the largest magnitude of
each variable). Guards the speed work on the solve and the Dataset builder against any change of
what it holds beyond that tolerance."""

from __future__ import annotations

import pytest

from solver.models.quasistatic import solve_quasistatic
from solver.models.quasistatic.solver import RING_TOLERANCE
from tests.helpers.quasistatic_reference import (
    TOLERANCE,
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
    """The comparison is not blind: a float 100 tolerances off, a changed string, a missing key and
    a residual above the ring tolerance count; a float a tenth of a tolerance off and another
    iteration count do not."""
    want = reference[configuration_key(*configurations()[0])]
    got = describe(solve_quasistatic(inputs_with_rule(*configurations()[0])))
    assert not differences(got, want)
    loads = got["data_vars"]["contact_load"]["values"]
    largest = max(abs(x) for row in loads for x in row)
    loads[0][0] += 100.0 * TOLERANCE * largest
    loads[1][0] += 0.1 * TOLERANCE * largest
    got["attrs"]["kinematics"] += "x"
    got["attrs"]["solver_iterations"] += 1
    got["attrs"]["solver_residual"] = 10.0 * RING_TOLERANCE
    del got["coords"]["ball_count"]
    found = differences(got, want)
    assert len(found) == 4, found
    assert any("contact_load" in entry for entry in found), found
