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


@pytest.fixture
def ctrl_c_at_first_progress(monkeypatch):
    """``racetrace simulate``'s progress bar sends SIGINT (what Ctrl-C delivers) to the process
    at its first report, after the first chunk."""
    import os
    import signal

    from racetrace.commands import simulate as command

    calls = []
    original = command.ProgressBar.__call__

    def interrupting(self, fraction, t, message=""):
        calls.append(fraction)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)
        original(self, fraction, t, message)

    monkeypatch.setattr(command.ProgressBar, "__call__", interrupting)
