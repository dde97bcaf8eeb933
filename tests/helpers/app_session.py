"""A session of the app without a browser needs a trame server of its own."""

from __future__ import annotations

import uuid


def trame_server():
    """A new trame server with a unique name, its state ready (change callbacks fire on flush, as
    in a running server)."""
    from trame.app import get_server

    server = get_server(f"racetrace-test-{uuid.uuid4().hex}", client_type="vue3")
    server.state.ready()
    return server
