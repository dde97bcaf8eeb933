"""Fixtures for the case-file tests: a valid case as a nested dict, and a helper that collects the
problems an edited copy of it produces."""

from __future__ import annotations

import copy

import pytest

from solver.case.validate import validate
from solver.errors import CaseError

VALID = {
    "title": "test spindle",
    "bearing": {
        "designation": "test 7008C",
        "provenance": "estimated",
        "ball_count": 18,
        "ball_diameter_mm": 7.144,
        "pitch_diameter_mm": 54.0,
        "inner_groove_radius_ratio": 0.54,
        "outer_groove_radius_ratio": 0.53,
        "free_contact_angle_deg": 15.0,
        "ball_material": "silicon_nitride",
        "ring_material": "bearing_steel",
    },
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
