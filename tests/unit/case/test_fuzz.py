"""Property-based fuzz test over case files: every mutated case ends in a clean CaseError, a clean
NoSolutionError or a finite solution (tests/helpers/fuzz.py says how cases are mutated)."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.helpers.cases import DEEP_GROOVE_BEARING, LUBRICANT, SPINDLE, case_text
from tests.helpers.fuzz import OUTCOMES, mutated_case_bytes, outcome

_COMMON = dict(deadline=None, suppress_health_check=[HealthCheck.too_slow], database=None)


@settings(max_examples=200, derandomize=True, **_COMMON)
@given(st.randoms(use_true_random=False))
def test_every_mutated_case_ends_cleanly(rng):
    assert outcome(mutated_case_bytes(rng)) in OUTCOMES


@pytest.mark.slow
@settings(max_examples=5000, derandomize=True, **_COMMON)  # the same 5000 every run: CI repeatable;
# python -m tests.explore_fuzz --surface case --seeds A-B explores new mutations
@given(st.randoms(use_true_random=False))
def test_every_mutated_case_ends_cleanly_many(rng):
    assert outcome(mutated_case_bytes(rng)) in OUTCOMES


#: Inputs the fuzzing found that once ended in a traceback.
FOUND = {
    # a subnormal ball diameter passed the checks and divided by zero in the quasi-static solver
    "subnormal ball diameter": SPINDLE.replace(
        "ball_diameter_mm = 7.144", "ball_diameter_mm = 5e-324"
    )
    + LUBRICANT,
    # the traction balance's cage-speed bracket lost its sign change when brentq re-evaluated it
    "cage speed bracket": case_text(
        "deep groove, radial load",
        DEEP_GROOVE_BEARING,
        {
            "inner_ring_speed_rpm": 6000.0,
            "radial_load_N": 2000.0,
            "radial_load_angle_deg": 360.0,
            "misalignment_deg": -5.0,
            "outer_ring_speed_rpm": 500000.0,
        },
        "[lubricant.traction]\nmu_max = 1.0\n",
    ),
}


@pytest.mark.parametrize("name", list(FOUND))
def test_inputs_found_by_fuzzing_end_cleanly(name):
    assert outcome(FOUND[name].encode()) in OUTCOMES
