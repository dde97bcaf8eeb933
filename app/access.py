"""Who may use the server: the request's ``Host`` and ``Origin``, and the access token.

- A page from another site must not drive the app: a request that carries an ``Origin`` header
  (every websocket a browser opens does) is refused unless that origin is the page's own
  (``http://`` + the request's ``Host``).
- On a loopback address the ``Host`` must name the loopback interface (``localhost``,
  ``127.0.0.1``, ``[::1]``), so a foreign name that resolves to this machine (DNS rebinding) is
  refused too.
- On any other address the app is reachable from the network: every request must carry the random
  access token, in the URL (``?token=...``, as printed at start) or in the cookie the server sets
  on the first page that had it.
"""

from __future__ import annotations

import ipaddress
import secrets
import socket
import urllib.parse

TOKEN_COOKIE = "racetrace_token"
LOOPBACK_NAMES = ("localhost", "127.0.0.1", "::1")


def is_loopback(host: str) -> bool:
    """Whether ``host`` (a name or an address) is only reachable from this machine."""
    if host in ("localhost",):
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        pass
    try:
        infos = socket.getaddrinfo(host, None)
    except socket.gaierror:
        return False
    return all(ipaddress.ip_address(info[4][0]).is_loopback for info in infos)


def _host_name(host_header: str) -> str:
    """The name part of a ``Host`` header (``[::1]:8080`` -> ``::1``)."""
    host = host_header.strip().lower()
    if host.startswith("["):
        return host[1 : host.find("]")] if "]" in host else host
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


class Access:
    """The rules for a server bound to ``host``; ``token`` ("" for none) is required on every
    request when set (:func:`new_token` makes one)."""

    def __init__(self, host: str, token: str = ""):
        self.loopback = is_loopback(host)
        self.token = token

    def check(
        self, host_header: str, origin: str | None, query_token: str = "", cookie_token: str = ""
    ) -> str:
        """Why a request with these headers is refused ("" when it is allowed)."""
        if self.loopback and _host_name(host_header) not in LOOPBACK_NAMES:
            return f"refused: host {host_header!r} is not this machine's loopback address"
        if origin is not None and origin != "null":
            parts = urllib.parse.urlsplit(origin)
            if parts.scheme not in ("http", "https") or parts.netloc.lower() != (
                host_header.strip().lower()
            ):
                return f"refused: requests from {origin} are not allowed (foreign origin)"
        elif origin == "null":
            return "refused: requests from an opaque origin are not allowed"
        if self.token:
            given = query_token or cookie_token
            if not given or not secrets.compare_digest(given, self.token):
                return (
                    "access token required: open the address with ?token=... that "
                    "racetrace serve printed at start"
                )
        return ""

    def problem(self, request) -> str:
        """:meth:`check` for an aiohttp request."""
        return self.check(
            request.headers.get("Host", ""),
            request.headers.get("Origin"),
            request.query.get("token", ""),
            request.cookies.get(TOKEN_COOKIE, ""),
        )

    def grant(self, request, response) -> None:
        """Remember the token given in the URL in a cookie, for the page's later requests."""
        if self.token and request.query.get("token") and not request.cookies.get(TOKEN_COOKIE):
            response.set_cookie(
                TOKEN_COOKIE, self.token, httponly=True, samesite="Strict", path="/"
            )


def new_token() -> str:
    """A random access token (URL-safe)."""
    return secrets.token_urlsafe(24)


def middleware(access: Access):
    """An aiohttp middleware refusing, with 403 and the reason, what ``access`` refuses."""
    from aiohttp import web

    @web.middleware
    async def check_access(request, handler):
        problem = access.problem(request)
        if problem:
            return web.Response(status=403, text=f"racetrace: {problem}\n")
        return await handler(request)

    return check_access
