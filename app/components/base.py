"""What every session component shares: the session, its trame state and controller."""

from __future__ import annotations

import json


class Component:
    """One part of a session; ``session`` is the :class:`app.state.RacetraceApp` it belongs to."""

    def __init__(self, session):
        self.session = session
        self.state = session.state
        self.ctrl = session.ctrl

    def init_state(self) -> None:
        """Set this component's state keys to their starting values."""

    def bind(self) -> None:
        """Attach this component's change handlers and controller actions."""

    def shutdown(self) -> None:
        """Stop whatever this component runs in the background."""


def fig_json(fig) -> dict:
    """A plotly figure as plain JSON (what the page's chart widgets take)."""
    return json.loads(fig.to_json())
