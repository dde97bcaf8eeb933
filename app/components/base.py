"""What every session component shares: the session, its trame state and controller."""

from __future__ import annotations

import asyncio
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

    #: Names of the methods this component offers the others as controller functions.
    PROVIDES: tuple[str, ...] = ()

    def provide(self) -> None:
        """Offer the methods named in :attr:`PROVIDES` to the other components as controller
        functions, called as ``self.ctrl.<name>(...)``: components reach each other only through
        the controller and the state. A failure goes to the caller; the page cannot call them (no
        widget is bound to them)."""
        for name in self.PROVIDES:
            setattr(self.ctrl, name, getattr(self, name))

    async def poll_until_done(self, poll, period_s: float) -> None:
        """Call ``poll()`` (under the state lock, so its changes go out together) every
        ``period_s`` seconds until it returns True."""
        while True:
            with self.state:
                finished = poll()
            if finished:
                return
            await asyncio.sleep(period_s)

    def init_state(self) -> None:
        """Set this component's state keys to their starting values."""

    def bind(self) -> None:
        """Attach this component's change handlers and controller actions."""

    def shutdown(self) -> None:
        """Stop whatever this component runs in the background."""


def running_loop():
    """The event loop running now, or None (outside the server, where scripts and tests drive a
    component's background work themselves)."""
    try:
        return asyncio.get_running_loop()
    except RuntimeError:
        return None


def fig_json(fig) -> dict:
    """A plotly figure as plain JSON (what the page's chart widgets take)."""
    return json.loads(fig.to_json())


def as_int(value, default: int, lo: int | None = None, hi: int | None = None) -> int:
    """``value`` (as a client sent it) as an int within [lo, hi]; ``default`` if not a number."""
    number = _finite(value)
    return default if number is None else _clamp(int(number), lo, hi)


def as_float(value, default: float, lo: float | None = None, hi: float | None = None) -> float:
    """``value`` (as a client sent it) as a finite float within [lo, hi]; else ``default``."""
    number = _finite(value)
    return default if number is None else _clamp(number, lo, hi)


def _finite(value) -> float | None:
    """``value`` as a finite float, or None (not a number, NaN or infinite)."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


def _clamp(number, lo, hi):
    """``number`` within [lo, hi] (a bound of None is no bound)."""
    if lo is not None:
        number = max(lo, number)
    if hi is not None:
        number = min(hi, number)
    return number
