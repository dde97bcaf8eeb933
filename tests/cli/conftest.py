"""Fixtures shared by the command-line tests."""

from __future__ import annotations

import pytest


@pytest.fixture
def fake_case(monkeypatch):
    """``racetrace simulate`` resolves any case name to the test spindle under 300 N radial load
    (tests.helpers.cases.spindle_inputs), so no catalogue case is read."""
    from racetrace.commands import simulate as command
    from tests.helpers.cases import spindle_inputs

    monkeypatch.setattr(command, "_load_case", lambda name: spindle_inputs(radial=300.0))
