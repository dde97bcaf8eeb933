"""Property-based fuzz test over case files: every mutated case ends in a clean CaseError, a clean
NoSolutionError or a finite solution (tests/helpers/fuzz.py says how cases are mutated)."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.helpers.fuzz import OUTCOMES, mutated_case_bytes, outcome

_COMMON = dict(deadline=None, suppress_health_check=[HealthCheck.too_slow], database=None)


@settings(max_examples=200, derandomize=True, **_COMMON)
@given(st.randoms(use_true_random=False))
def test_every_mutated_case_ends_cleanly(rng):
    assert outcome(mutated_case_bytes(rng)) in OUTCOMES


@pytest.mark.slow
@settings(max_examples=5000, **_COMMON)
@given(st.randoms(use_true_random=False))
def test_every_mutated_case_ends_cleanly_many(rng):
    assert outcome(mutated_case_bytes(rng)) in OUTCOMES
