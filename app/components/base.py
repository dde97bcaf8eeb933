"""What every session component shares: the session, its trame state and controller."""

from __future__ import annotations

import functools
import json
import logging
import math

log = logging.getLogger("racetrace.app")


class Component:
    """One part of a session; ``session`` is the :class:`app.state.RacetraceApp` it belongs to."""

    def __init__(self, session):
        self.session = session
        self.state = session.state
        self.ctrl = session.ctrl

    def on_change(self, *keys):
        """Register a state change handler for ``keys``, guarded (see :meth:`guarded`)."""

        def register(handler):
            self.state.change(*keys)(self.guarded(handler))
            return handler

        return register

    def action(self, name: str, handler) -> None:
        """Make ``handler`` the controller action ``name``, guarded (see :meth:`guarded`)."""
        setattr(self.ctrl, name, self.guarded(handler))

    def guarded(self, handler):
        """``handler``, such that a failure (e.g. on a value a client crafted) is logged and said
        in ``status`` instead of ending the handler chain or the server's loop."""

        @functools.wraps(handler)
        def run_guarded(*args, **kwargs):
            try:
                return handler(*args, **kwargs)
            except Exception as error:  # any failure: the page says it, the server goes on
                log.exception("handler %s failed", getattr(handler, "__name__", handler))
                self.state.status = f"error: {type(error).__name__}: {error}"[:300]
                return None

        return run_guarded

    def provide(self, **functions) -> None:
        """Offer ``functions`` to the other components as controller functions, called as
        ``self.ctrl.<name>(...)``: components reach each other only through the controller and the
        state. A failure goes to the caller; the page cannot call them (no widget is bound to
        them)."""
        for name, function in functions.items():
            setattr(self.ctrl, name, function)

    def init_state(self) -> None:
        """Set this component's state keys to their starting values."""

    def bind(self) -> None:
        """Attach this component's change handlers and controller actions."""

    def shutdown(self) -> None:
        """Stop whatever this component runs in the background."""


def fig_json(fig) -> dict:
    """A plotly figure as plain JSON (what the page's chart widgets take)."""
    return json.loads(fig.to_json())


def as_int(value, default: int, lo: int | None = None, hi: int | None = None) -> int:
    """``value`` (as a client sent it) as an int within [lo, hi]; ``default`` if not a number."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        return default
    if not math.isfinite(number):
        return default
    number = int(number)
    if lo is not None:
        number = max(lo, number)
    if hi is not None:
        number = min(hi, number)
    return number


def as_float(value, default: float, lo: float | None = None, hi: float | None = None) -> float:
    """``value`` (as a client sent it) as a finite float within [lo, hi]; else ``default``."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        return default
    if not math.isfinite(number):
        return default
    if lo is not None:
        number = max(lo, number)
    if hi is not None:
        number = min(hi, number)
    return number
