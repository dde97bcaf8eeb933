"""A session process answers the front only: a random secret per session, shared by the two.

The front (:mod:`app.serve.front`) makes a secret for each session process it starts and hands it
over outside the command line (an argument of the forked function, or an environment variable of
a new process); the session (:mod:`app.serve.session_process`) refuses every HTTP request, the
websocket handshake included, that does not carry it in :data:`SECRET_HEADER`. The front adds the
header to what it relays, after its own checks of the browser (:mod:`app.access`). So a client
that reaches a session's port directly (another user of the machine, or the network if the port
were ever exposed) cannot drive it, whatever ``Host`` or ``Origin`` it writes.
"""

from __future__ import annotations

import secrets

SECRET_HEADER = "X-Racetrace-Session-Secret"
SECRET_ENV = "RACETRACE_SESSION_SECRET"  # how a session started as a new process receives it


def new_secret() -> str:
    """A random session secret (URL-safe text, 256 bits)."""
    return secrets.token_urlsafe(32)


def secret_problem(given: str | None, secret: str) -> str:
    """Why a request carrying ``given`` in :data:`SECRET_HEADER` is refused ("" if allowed).

    Compared in constant time; an empty ``secret`` refuses everything."""
    if not secret or not given or not secrets.compare_digest(given.encode(), secret.encode()):
        return "refused: this port serves the racetrace front only; open the address it printed"
    return ""


def front_only(secret: str, access):
    """An aiohttp middleware for a session: 403 unless the request carries ``secret`` and
    ``access`` (:class:`app.access.Access`) allows its ``Host`` and ``Origin``."""
    from aiohttp import web

    @web.middleware
    async def check_front(request, handler):
        problem = secret_problem(request.headers.get(SECRET_HEADER), secret) or access.problem(
            request
        )
        if problem:
            return web.Response(status=403, text=f"racetrace: {problem}\n")
        return await handler(request)

    return check_front
