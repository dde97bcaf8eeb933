"""Fixtures for the case-file tests: a valid case as a nested dict, and a helper that collects the
problems an edited copy of it produces."""

from __future__ import annotations

import copy

import pytest

from solver.case.validate import validate
from solver.errors import CaseError
from tests.helpers.cases import SPINDLE_BEARING

VALID = {
    "title": "test spindle",
    "bearing": {"designation": "test 7008C", "provenance": "estimated"} | SPINDLE_BEARING,
    "operating": {
        "inner_ring_speed_rpm": 20000.0,
        "axial_load_N": 500.0,
        "radial_load_N": 300.0,
    },
}


@pytest.fixture
def valid():
    """A fresh, valid case dict (edit it freely)."""
    return copy.deepcopy(VALID)


def problems_of(data):
    """{key: [messages]} of the CaseError that ``data`` raises (fails the test if it is valid)."""
    with pytest.raises(CaseError) as info:
        validate(data)
    out: dict[str, list[str]] = {}
    for p in info.value.problems:
        out.setdefault(p.key, []).append(p.message)
    return out


@pytest.fixture
def problems():
    return problems_of
