"""The front server of ``racetrace serve``: one session process per browser, behind one address.

The front listens on ``--host``/``--port`` and checks every request (:mod:`app.access`). It gives
each browser a session cookie and its own session process (:mod:`app.serve.session_process`: a trame
server on a loopback port with its own case, run, camera and render size), and relays that
browser's HTTP requests and websocket to it, with the secret that session answers
(:mod:`app.serve.session_guard`): nothing but the front can use a session. With
``shared=True`` every browser gets the same session (a design review on a shared screen). All
sessions use the same runs folder and the same solver slots (:class:`app.services.pool.SolverPool`).

Session processes are forked from a fork server that has imported what they all use
(:mod:`app.serve.forkserver`), so they share that memory instead of each holding a copy; with
``fork=False`` (or where there is no fork server) each is a new Python process.
A spare session is started ahead, so that a new browser does not wait for one to start. The
front listens at once: while the first session is prepared (the fork server imports and loads or
compiles the kernels, minutes on an empty numba cache), a browser gets a page that says what is
being prepared (:mod:`app.serve.preparing`) and opens the app when its session is ready. A session
whose browsers have all left is stopped after :data:`IDLE_S`; its followers
(:mod:`app.serve.follow`) do not keep it: a class ends :data:`IDLE_S` after its presenter left,
its followers told so.
Session processes stop when the front ends, even when it is killed (they watch their parent).
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import os
import secrets
import signal
import socket
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from aiohttp import ClientSession, WSMsgType, web

from ..access import Access
from ..follow_names import FOLLOWER_HEADER, QR_NAME
from . import coalesce, follow, preparing
from .quiet_log import quiet_closed_connections
from .session_guard import SECRET_ENV, SECRET_HEADER, new_secret

log = logging.getLogger("racetrace.front")

COOKIE = "racetrace_session"
IDLE_S = 120.0  # a session without its presenter's browser is stopped after this
REAP_EVERY_S = 5.0  # how often sessions are checked for that
MAX_SESSIONS = 8  # sessions (browsers) at once; each is a process of about 0.5 GB
# a cold numba cache compiles the quasi-static kernels first: minutes on a busy machine (the page
# says what is being prepared meanwhile, :data:`PREPARING_PATH`)
START_TIMEOUT_S = 1800.0
PREPARING_PATH = "/__racetrace_preparing"  # what the first session waits for, as JSON
ENDED_KEPT_S = 3600.0  # an ended class's page says so this long (then: no such class)
# What a session has sent that a browser has not read yet is held here, not in the session (a
# session writing to a slow reader would hold it for every such client, without bound), and the
# state messages among it merge while they wait (app.serve.coalesce): a browser that falls this
# many bytes behind all the same (in what cannot merge) is closed with SLOW_CLOSE. A follower's
# page then joins again (the state it reads on joining is whole); a presenter's page shows it lost
# its connection.
FOLLOWER_BACKLOG_BYTES = 16 * 1024 * 1024
PRESENTER_BACKLOG_BYTES = 96 * 1024 * 1024
SLOW_CLOSE = 4002
SLOW_WRITE_S = 10.0  # a browser closed as too slow gets this long to take the message on its way
STOP_TIMEOUT_S = 50.0  # a session stopping saves its run first (it waits up to 30 s for it)
_HOP_HEADERS = {
    "connection",
    "keep-alive",
    "transfer-encoding",
    "content-encoding",
    "content-length",
    "upgrade",
    "host",
    SECRET_HEADER.lower(),  # the front's to give, never the browser's
    FOLLOWER_HEADER.lower(),  # likewise
}


def free_port() -> int:
    """A TCP port free on the loopback interface now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class NoSession(Exception):
    """No session for this request: a websocket from a browser that did not open the page, or a
    new browser beyond :data:`MAX_SESSIONS`."""


@dataclass
class Session:
    """A session process and the browsers using it."""

    sid: str
    port: int
    secret: str = field(repr=False)  # the session answers requests that carry it, only
    process: asyncio.subprocess.Process  # or a forkserver.ForkedProcess, which behaves alike
    ready: asyncio.Future
    presenters: int = 0  # the presenter's websockets (a page each)
    followers: set = field(default_factory=set)  # its followers' websockets (from their browsers)
    idle_since: float = field(default_factory=time.monotonic)  # since the last presenter left
    join_code: str = ""  # the session's follow-mode join code (read from it once it answers)

    @property
    def alive(self) -> bool:
        return self.process.returncode is None


class Front:
    """The front server (see the module docstring).

    ``session_args``: command-line options passed to every session process (runs folder, case,
    solver slots).
    """

    def __init__(
        self, access: Access, session_args: list[str], shared: bool = False, fork: bool = True
    ):
        from . import forkserver

        self.access = access
        self.fork = fork and forkserver.available()
        self.session_args = session_args
        self.shared = shared
        self.sessions: dict[str, Session] = {}
        self._spare: Session | None = None
        self._http: ClientSession | None = None
        self._reaper = None
        self._spare_lock: asyncio.Lock | None = None  # one spare started at a time
        self._starting = None  # the first spare's start (the front listens meanwhile)
        self._started_at = time.monotonic()
        self._said_ready = False
        self._wrong_codes = follow.WrongCodeLimit()
        self._ended: dict[str, float] = {}  # join codes of classes ended by the idle stop

    # ---- session processes ----------------------------------------------------------------------
    async def _spawn(self) -> Session:
        port = free_port()
        sid = secrets.token_urlsafe(16)
        secret = new_secret()
        argv = ["--port", str(port), *self.session_args]
        if self.fork:  # forked from the pre-imported fork server: shares its memory
            from . import forkserver

            forking = asyncio.ensure_future(
                asyncio.to_thread(forkserver.start_session, argv, secret)
            )
            try:
                process = await asyncio.shield(forking)
            except asyncio.CancelledError:
                # the front stops while this session is forked: stop it too, or the front's exit
                # (which waits for its children) would wait for it forever
                with contextlib.suppress(Exception):
                    (await forking).terminate()
                raise
        else:
            process = await asyncio.create_subprocess_exec(
                sys.executable,
                "-m",
                "app.serve.session_process",
                *argv,
                env={**os.environ, SECRET_ENV: secret},
            )
        session = Session(sid, port, secret, process, asyncio.get_running_loop().create_future())
        asyncio.get_running_loop().create_task(self._wait_ready(session))
        return session

    async def _wait_ready(self, session: Session) -> None:
        deadline = time.monotonic() + START_TIMEOUT_S
        while time.monotonic() < deadline and session.alive:
            try:
                async with self._http.get(
                    f"http://127.0.0.1:{session.port}/", headers={SECRET_HEADER: session.secret}
                ) as response:
                    if response.status == 200:
                        session.join_code = await self._join_code(session)
                        session.ready.set_result(True)
                        if not self._said_ready:
                            self._said_ready = True
                            took = time.monotonic() - self._started_at
                            print(f"racetrace: ready (the first session took {took:.0f} s)")
                        return
            except OSError:
                pass
            await asyncio.sleep(0.2)
        code = session.process.returncode
        error = RuntimeError(
            "the session did not start"
            + (f" (exit code {code})" if code is not None else " in time")
        )
        log.warning("racetrace: %s", error)  # once, even when no browser is waiting for it
        session.ready.set_exception(error)
        session.ready.exception()  # logged above: asyncio need not report it again

    async def _join_code(self, session: Session) -> str:
        """The join code a session shows (:mod:`app.components.follow`); "" if it has none."""
        try:
            async with self._http.get(
                f"http://127.0.0.1:{session.port}{follow.STATUS_PATH}",
                headers={SECRET_HEADER: session.secret},
            ) as response:
                if response.status == 200:
                    return follow.normal_code((await response.json()).get("code", ""))
        except (OSError, ValueError) as error:
            log.warning("session %s: no join code (%s)", session.sid[:6], error)
        return ""

    async def _followers_may_drive(self, session: Session) -> bool:
        """Whether the presenter of ``session`` lets followers drive, asked now (False when the
        session does not answer)."""
        try:
            async with self._http.get(
                f"http://127.0.0.1:{session.port}{follow.STATUS_PATH}",
                headers={SECRET_HEADER: session.secret},
            ) as response:
                return response.status == 200 and (await response.json()).get("drive") is True
        except (OSError, ValueError):
            return False

    def _session_of_code(self, code: str) -> Session | None:
        """The live session whose join code is ``code`` (None for an unknown or ended code)."""
        code = follow.normal_code(code)
        if not code:
            return None
        for session in self.sessions.values():
            if (
                session.alive
                and session.join_code
                and secrets.compare_digest(session.join_code, code)
            ):
                return session
        return None

    async def start_spare(self) -> None:
        """Start the session the next browser gets (the shared one with ``shared``)."""
        if self._spare_lock is None:
            self._spare_lock = asyncio.Lock()
        async with self._spare_lock:
            if self._spare is None or not self._spare.alive:
                self._spare = await self._spawn()

    async def _session_for(self, request: web.Request) -> tuple[Session, bool]:
        """The browser's session (a new one, from the spare, if it has none); and whether it is
        new (its cookie must then be set)."""
        sid = request.cookies.get(COOKIE, "")
        session = self.sessions.get(sid)
        if session is not None and session.alive:
            return session, False
        if request.headers.get("Upgrade", "").lower() == "websocket":
            raise NoSession("no session for this browser: open the page first")
        await self.start_spare()
        if "text/html" in request.headers.get("Accept", "") and not self.shared:
            alive = sum(s.alive for s in self.sessions.values())
            if alive >= MAX_SESSIONS:
                raise NoSession(
                    f"{alive} sessions are open, the most this server keeps: close a browser "
                    "window (its session ends 2 minutes later), or start with --shared"
                )
        if "text/html" not in request.headers.get("Accept", ""):
            # not a page being opened (a script, a health check): every session serves the same
            # files, so the spare answers without being given away
            return self._spare, False
        session = self._spare
        session.idle_since = time.monotonic()  # idle from now on, not since it was started
        self.sessions[session.sid] = session
        if not self.shared:
            self._spare = await self._spawn()  # the next browser's
        return session, True

    async def _reap(self) -> None:
        """Stop sessions without their presenter's browser for IDLE_S, followers or not (never
        the shared one); the followers are told that the presenter has left."""
        while True:
            await asyncio.sleep(REAP_EVERY_S)
            now = time.monotonic()
            for sid, session in list(self.sessions.items()):
                if not session.alive:
                    del self.sessions[sid]
                elif (
                    not self.shared
                    and session.presenters == 0
                    and now - session.idle_since > IDLE_S
                ):
                    del self.sessions[sid]
                    await self._end_class(session)
                    await self._stop(session)

    async def _end_class(self, session: Session) -> None:
        """Close the followers' websockets of ``session``, saying that the presenter has left,
        and remember its join code for an hour (a follower's page opened again says so)."""
        now = time.monotonic()
        self._ended = {c: t for c, t in self._ended.items() if now - t < ENDED_KEPT_S}
        if session.join_code:
            self._ended[session.join_code] = now
        for browser in list(session.followers):
            with contextlib.suppress(Exception):
                await browser.close(
                    code=follow.PRESENTER_LEFT_CLOSE, message=b"the presenter has left"
                )

    async def _stop(self, session: Session) -> None:
        if not session.alive:
            return
        with contextlib.suppress(ProcessLookupError):
            session.process.send_signal(signal.SIGTERM)
        try:
            await asyncio.wait_for(session.process.wait(), STOP_TIMEOUT_S)
        except TimeoutError:
            with contextlib.suppress(ProcessLookupError):
                session.process.kill()
            await session.process.wait()

    async def stop_all(self) -> None:
        """Stop every session process (each saves its run first)."""
        sessions = list(self.sessions.values())
        if self._spare is not None and self._spare not in sessions:
            sessions.append(self._spare)
        await asyncio.gather(*(self._stop(s) for s in sessions))

    def _preparing_status(self, request: web.Request) -> web.Response:
        """``{"ready": bool, "failed": str, "text": str}``: whether the browser's session (or the
        spare) answers, and what is being prepared meanwhile."""
        session = self.sessions.get(request.cookies.get(COOKIE, "")) or self._spare
        ready = session is not None and session.ready.done()
        failed = ""
        if ready and session.ready.exception() is not None:
            failed = f"{session.ready.exception()}; see the terminal of racetrace serve"
        if session is None or not ready:
            text = preparing.read(os.environ.get(preparing.ENV)) or "starting"
        else:
            text = ""
        return web.json_response(
            {"ready": ready and not failed, "failed": failed, "text": text},
            headers={"Cache-Control": "no-store"},
        )

    # ---- relaying -------------------------------------------------------------------------------
    async def handle(self, request: web.Request) -> web.StreamResponse:
        problem = self.access.problem(request)
        if problem:
            return web.Response(status=403, text=f"racetrace: {problem}\n")
        if request.path == PREPARING_PATH:
            return self._preparing_status(request)
        if request.path.startswith(follow.PREFIX):
            return await self._handle_follower(request)
        if request.path == "/" and "follow" in request.query:
            return self._to_follow_page(request)
        if request.path == "/" + QR_NAME:
            session = self.sessions.get(request.cookies.get(COOKIE, ""))
            return self._qr(request, session)
        try:
            session, new = await self._session_for(request)
            if not session.ready.done() and _is_page(request):
                response = web.Response(
                    text=PREPARING_PAGE,
                    content_type="text/html",
                    headers={"Cache-Control": "no-store"},
                )
                if new:
                    response.set_cookie(
                        COOKIE, session.sid, httponly=True, samesite="Strict", path="/"
                    )
                self.access.grant(request, response)
                return response
            await asyncio.shield(session.ready)
        except NoSession as error:
            return web.Response(status=403, text=f"racetrace: {error}\n")
        except RuntimeError as error:
            return web.Response(status=503, text=f"racetrace: {error}; see the server log\n")
        if request.headers.get("Upgrade", "").lower() == "websocket":
            return await self._relay_websocket(request, session)
        response = await self._relay_http(request, session)
        _add_read_script(request, response)
        if new:
            response.set_cookie(COOKIE, session.sid, httponly=True, samesite="Strict", path="/")
        self.access.grant(request, response)
        return response

    # ---- followers (app.serve.follow) -----------------------------------------------------------
    def _to_follow_page(self, request: web.Request) -> web.Response:
        """``/?follow=CODE``: the follower's page, ``/follow/CODE/`` (the token stays in the URL
        and is remembered in the cookie, as for any page)."""
        found = self._follow_target(request, request.query.get("follow", ""))
        if isinstance(found, web.Response):
            return found
        code = found.join_code
        query = {k: v for k, v in request.query.items() if k != "follow"}
        target = f"{follow.PREFIX}{code}/" + (f"?{_urlencode(query)}" if query else "")
        response = web.Response(status=302, headers={"Location": target})
        self.access.grant(request, response)
        return response

    async def _handle_follower(self, request: web.Request) -> web.StreamResponse:
        """A request under ``/follow/CODE/``: relayed to the session of that join code, as a
        follower (its websocket read-only, :class:`app.serve.follow.FollowerGate`)."""
        code, _, rest = request.path[len(follow.PREFIX) :].partition("/")
        found = self._follow_target(request, code)
        if isinstance(found, web.Response):
            return found
        session = found
        if not session.ready.done() or session.ready.exception():
            return _no_class_page(code)
        if not rest and not request.path.endswith("/"):
            location = f"{follow.PREFIX}{follow.normal_code(code)}/"
            return web.Response(status=302, headers={"Location": location})
        inner = "/" + rest + (f"?{request.query_string}" if request.query_string else "")
        if rest == QR_NAME:
            return self._qr(request, session)
        if request.headers.get("Upgrade", "").lower() == "websocket":
            return await self._relay_websocket(request, session, inner, follower=True)
        response = await self._relay_http(request, session, inner)
        if _is_page(request) and response.status == 200 and response.body:
            page = bytes(response.body).decode("utf-8", "replace")
            banner = _follower_banner(session.join_code)
            response.body = page.replace("</body>", banner + "</body>").encode()
        _add_read_script(request, response)
        self.access.grant(request, response)
        return response

    def _follow_target(self, request: web.Request, code: str) -> Session | web.Response:
        """The session of join code ``code``, or the page the requesting client gets instead: too
        many wrong codes from its address (429, :class:`app.serve.follow.WrongCodeLimit`), a
        class ended by the idle stop, or no such class (both 404; counted as wrong codes)."""
        address, now = request.remote or "", time.monotonic()
        wait = self._wrong_codes.retry_after(address, now)
        if wait > 0:
            log.warning("follow: %s refused, too many wrong join codes", address)
            return _too_many_codes_page(wait, self._wrong_codes)
        session = self._session_of_code(code)
        if session is not None:
            return session
        self._wrong_codes.note_wrong(address, now)
        ended = self._ended.get(follow.normal_code(code))
        if ended is not None and now - ended < ENDED_KEPT_S:
            return _class_ended_page(follow.normal_code(code))
        return _no_class_page(code)

    def _qr(self, request: web.Request, session: Session | None) -> web.Response:
        """The QR code of ``session``'s follow address, as the requesting browser reached this
        server (with the token when the server has one)."""
        if session is None or not session.join_code:
            return web.Response(status=404, text="racetrace: no session, so no join code\n")
        url = follow.follow_url(
            request.headers.get("Host", ""), session.join_code, self.access.token
        )
        return web.Response(
            body=follow.qr_svg(url),
            content_type="image/svg+xml",
            headers={"Cache-Control": "no-store"},
        )

    async def _relay_http(
        self, request: web.Request, session: Session, inner: str | None = None
    ) -> web.Response:
        headers = {
            k: v
            for k, v in request.headers.items()
            if k.lower() not in _HOP_HEADERS and k.lower() != "origin"
        }
        if "Origin" in request.headers:  # checked here; a session accepts only the front's origin
            headers["Origin"] = f"http://127.0.0.1:{session.port}"
        headers[SECRET_HEADER] = session.secret
        try:
            body = await request.read()
        except ConnectionResetError:  # the client left while sending: nobody to answer
            log.debug("a client left before its request body arrived")
            return web.Response(status=400, text="racetrace: request cut off\n")
        url = f"http://127.0.0.1:{session.port}{inner or request.rel_url}"
        try:
            async with self._http.request(
                request.method, url, headers=headers, data=body or None, allow_redirects=False
            ) as upstream:
                payload = await upstream.read()
                out = {k: v for k, v in upstream.headers.items() if k.lower() not in _HOP_HEADERS}
                return web.Response(status=upstream.status, headers=out, body=payload)
        except OSError as error:
            return web.Response(
                status=502, text=f"racetrace: the session is not reachable ({error})"
            )

    async def _relay_websocket(
        self, request: web.Request, session: Session, inner: str | None = None, follower=False
    ):
        """Relay a browser's websocket to ``session`` (``inner``: the path there); a
        ``follower``'s messages pass the read-only gate first."""
        browser = web.WebSocketResponse(max_msg_size=0, autoping=True, heartbeat=None)
        await browser.prepare(request)
        coalesce.hold_at_front(request.transport)
        url = f"ws://127.0.0.1:{session.port}{inner or request.rel_url}"
        headers = {SECRET_HEADER: session.secret}
        if follower:
            headers[FOLLOWER_HEADER] = "1"
            session.followers.add(browser)
        else:
            session.presenters += 1
        try:
            async with self._http.ws_connect(
                url,
                max_msg_size=0,
                origin=f"http://127.0.0.1:{session.port}",
                headers=headers,
            ) as upstream:
                reads = coalesce.PageReads()
                inward = (
                    self._pump_follower(browser, upstream, session, reads)
                    if follower
                    else _pump(browser, upstream, reads)
                )
                limit = FOLLOWER_BACKLOG_BYTES if follower else PRESENTER_BACKLOG_BYTES
                await asyncio.gather(inward, _pump_to_browser(upstream, browser, limit, reads))
        except OSError as error:
            log.warning("session %s unreachable: %s", session.sid[:6], error)
        finally:
            if follower:
                session.followers.discard(browser)
            else:
                session.presenters -= 1
                session.idle_since = time.monotonic()
            await browser.close()
        return browser

    async def _pump_follower(
        self, browser, upstream, session: Session, reads: coalesce.PageReads
    ) -> None:
        """Copy a follower's messages to its session, those the read-only gate lets through; a
        refused call is answered with a wslink error (app.serve.follow). The page's count of
        what it has taken goes to ``reads``."""
        gate = follow.FollowerGate()
        async for message in browser:
            if upstream.closed:
                break
            if message.type == WSMsgType.TEXT:
                reads.note(message.data)
                continue  # wslink speaks binary only: nothing to pass on
            if message.type != WSMsgType.BINARY:
                break
            try:
                whole = gate.add_chunk(message.data)
            except ValueError as error:
                log.warning("follower of %s dropped: %s", session.sid[:6], error)
                break
            if whole is None:
                continue
            reason = gate.refusal(whole.rpc, driving=True)
            if not reason and gate.refusal(whole.rpc, driving=False):
                if not await self._followers_may_drive(session):
                    reason = gate.refusal(whole.rpc, driving=False)
            try:
                if reason:
                    reply = follow.refusal_reply(whole.rpc, reason)
                    if reply is not None and not browser.closed:
                        await browser.send_bytes(reply)
                    continue
                for chunk in whole.chunks:
                    await upstream.send_bytes(chunk)
            except ConnectionResetError:
                break
        if not upstream.closed:
            await upstream.close()

    # ---- the aiohttp application ----------------------------------------------------------------
    def application(self) -> web.Application:
        app = web.Application(client_max_size=2 * 1024 * 1024)
        app.router.add_route("*", "/{tail:.*}", self.handle)
        app.on_startup.append(self._on_startup)
        app.on_shutdown.append(self._on_shutdown)
        return app

    async def _on_startup(self, _app) -> None:
        quiet_closed_connections()
        self._http = ClientSession(auto_decompress=True)
        self._started_at = time.monotonic()
        # started in the background: the port listens at once, and a browser is shown what the
        # first session (the fork server's imports and kernels) waits for
        self._starting = asyncio.get_running_loop().create_task(self.start_spare())
        self._reaper = asyncio.get_running_loop().create_task(self._reap())

    async def _on_shutdown(self, _app) -> None:
        if self._reaper is not None:
            self._reaper.cancel()
        if self._starting is not None and not self._starting.done():
            self._starting.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await self._starting
        await self.stop_all()
        if self._http is not None:
            await self._http.close()


def _urlencode(query) -> str:
    import urllib.parse

    return urllib.parse.urlencode(list(query.items()))


def _no_class_page(code: str) -> web.Response:
    """The page a follower gets for a join code no session has now."""
    import html

    shown = html.escape(str(code)[:40]) or "(none)"
    return web.Response(
        status=404,
        content_type="text/html",
        headers={"Cache-Control": "no-store"},
        text=NO_CLASS_PAGE.replace("__CODE__", shown),
    )


def _class_ended_page(code: str) -> web.Response:
    """The page a follower gets for the join code of a class that ended (its presenter left)."""
    return web.Response(
        status=404,
        content_type="text/html",
        headers={"Cache-Control": "no-store"},
        text=CLASS_ENDED_PAGE.replace("__CODE__", code).replace("__IDLE__", _minutes(IDLE_S)),
    )


def _too_many_codes_page(wait_s: float, limit: follow.WrongCodeLimit) -> web.Response:
    """The page (429) a client gets for ``wait_s`` more seconds: it sent too many wrong join
    codes (``limit``)."""
    wait = max(1, round(wait_s))
    text = (
        TOO_MANY_CODES_PAGE.replace("__LIMIT__", str(limit.limit))
        .replace("__WINDOW__", f"{limit.window_s:.0f}")
        .replace("__WAIT__", str(wait))
    )
    return web.Response(
        status=429,
        content_type="text/html",
        headers={"Cache-Control": "no-store", "Retry-After": str(wait)},
        text=text,
    )


def _minutes(seconds: float) -> str:
    """``seconds`` in words, in minutes when whole ones (``120`` -> "2 minutes")."""
    if seconds >= 60 and seconds % 60 == 0:
        n = int(seconds // 60)
        return f"{n} minute" + ("s" if n != 1 else "")
    return f"{seconds:g} s"


def _follower_banner(code: str) -> str:
    """What the front adds to a follower's page: a banner saying it follows, read-only (its
    controls do nothing then: the front refuses their changes), or driving; that the presenter
    has left (and when the class ends unless they come back); and, once the class has ended,
    a page saying so in place of the app."""
    return (
        FOLLOWER_BANNER.replace("__CODE__", code)
        .replace("__IDLE__", _minutes(IDLE_S))
        .replace("__LEFT_CLOSE__", str(follow.PRESENTER_LEFT_CLOSE))
        .replace("__SLOW_CLOSE__", str(SLOW_CLOSE))
    )


def _add_read_script(request: web.Request, response: web.Response) -> None:
    """Add :data:`app.serve.coalesce.READ_SCRIPT` to the app's page in ``response``: the page
    then says what it has taken of its websocket, and the front holds the rest where it merges."""
    if _is_page(request) and response.status == 200 and response.body:
        if response.content_type == "text/html":
            page = bytes(response.body).decode("utf-8", "replace")
            response.body = coalesce.with_read_script(page).encode()


def _is_page(request: web.Request) -> bool:
    """Whether ``request`` opens a page (a browser's GET for HTML)."""
    return request.method == "GET" and "text/html" in request.headers.get("Accept", "")


# Shown while the browser's session is prepared: what is being done (polled every second from
# PREPARING_PATH), then the app itself once the session answers.
PREPARING_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>racetrace: preparing</title>
<style>
body { font-family: Roboto, Arial, sans-serif; margin: 15vh auto; max-width: 40em; color: #222; }
#preparing-text { font-size: 1.2rem; margin: 1em 0; }
#preparing-failed { color: #b00020; }
.bar { height: 6px; background: #e0e0e0; overflow: hidden; border-radius: 3px; }
.bar > div { height: 100%; width: 30%; background: #1976d2; animation: move 1.5s infinite linear; }
@keyframes move { from { margin-left: -30%; } to { margin-left: 100%; } }
</style></head>
<body><h1>racetrace is getting ready</h1>
<div class="bar"><div></div></div>
<p id="preparing-text">starting</p>
<p id="preparing-failed"></p>
<p>The first start after installing (or after a solver update) compiles the solver: a few minutes.
Later starts load the compiled kernels in seconds. This page opens the app by itself.</p>
<script>
(function poll() {
  fetch('__PATH__' + window.location.search, { cache: 'no-store', credentials: 'same-origin' })
    .then(function (r) { return r.json(); })
    .then(function (s) {
      if (s.ready) { window.location.reload(); return; }
      document.getElementById('preparing-text').textContent = s.text;
      document.getElementById('preparing-failed').textContent = s.failed;
      if (!s.failed) setTimeout(poll, 1000);
    })
    .catch(function () { setTimeout(poll, 2000); });
})();
</script></body></html>
""".replace("__PATH__", PREPARING_PATH)


NO_CLASS_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>racetrace: no such class</title>
<style>body { font-family: Roboto, Arial, sans-serif; margin: 15vh auto; max-width: 40em; }</style>
</head><body><h1 id="follow-refused">No class with join code __CODE__</h1>
<p>No racetrace page has this join code now. A join code ends with the presenter's session:
ask the presenter for the code on their screen (under "class" in the toolbar), then open
this server's address with <code>?follow=CODE</code>.</p></body></html>
"""

CLASS_ENDED_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>racetrace: the class has ended</title>
<style>body { font-family: Roboto, Arial, sans-serif; margin: 15vh auto; max-width: 40em; }</style>
</head><body><h1 id="follow-ended">The presenter has left: class __CODE__ has ended</h1>
<p>The presenter's page was closed for __IDLE__, so their session ended. If they start a new
one, it has a new join code: ask them for it, then open this server's address with
<code>?follow=CODE</code>.</p></body></html>
"""

TOO_MANY_CODES_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>racetrace: too many wrong join codes</title>
<style>body { font-family: Roboto, Arial, sans-serif; margin: 15vh auto; max-width: 40em; }</style>
</head><body><h1 id="follow-too-many">Too many wrong join codes</h1>
<p>Your address sent __LIMIT__ join codes that no class has within __WINDOW__ s, so this server
refuses join codes from it for __WAIT__ s more. Check the code on the presenter's screen (under
"class" in the toolbar), wait, then open this server's address with
<code>?follow=CODE</code> again.</p></body></html>
"""

# Added to a follower's page (app.serve.follow): the follower's controls are inert while it is
# read-only (the front refuses their changes anyway), and a banner says so.
FOLLOWER_BANNER = """
<style>
#follow-banner { position: fixed; left: 0; right: 0; bottom: 0; z-index: 3000; padding: 4px 12px;
  background: #0d47a1; color: #fff; font: 14px Roboto, Arial, sans-serif; text-align: center; }
html.rt-read-only .v-main button, html.rt-read-only .v-main input,
html.rt-read-only .v-main .v-field, html.rt-read-only .v-main .v-slider,
html.rt-read-only .v-main .v-selection-control, html.rt-read-only .v-navigation-drawer,
html.rt-read-only .v-toolbar button { pointer-events: none; }
</style>
<div id="follow-banner">following class __CODE__: you see what the presenter shows</div>
<script>
(function () {
  var readOnly = true, ended = false;
  window.racetraceFollower = '__CODE__';
  // the front closes a follower's websocket with __LEFT_CLOSE__ when the class ends (its presenter
  // left): the page says so in place of the app
  var NativeSocket = window.WebSocket;
  window.WebSocket = class extends NativeSocket {
    constructor(url, protocols) {
      super(url, protocols);
      this.addEventListener('close', function (e) {
        if (e.code === __LEFT_CLOSE__) end();
        // too slow to keep up (__SLOW_CLOSE__): join again, reading the session's whole state
        if (e.code === __SLOW_CLOSE__ && !ended) {
          setTimeout(function () { location.reload(); }, 2000);
        }
      });
    }
  };
  function end() {
    ended = true;
    document.title = 'racetrace: the class has ended';
    document.body.innerHTML = '<div style="font: 16px Roboto, Arial, sans-serif; ' +
      'margin: 15vh auto; max-width: 40em"><h1 id="follow-ended">The presenter has left: ' +
      'class __CODE__ has ended</h1><p>The presenter&#39;s page was closed for __IDLE__, so ' +
      'their session ended. If they start a new one, ask them for its join code.</p></div>';
  }
  function update() {
    if (ended) return;
    var s = window.trame && window.trame.state;
    var drive = !!(s && s.get('follow_drive'));
    var left = !!s && s.get('follow_presenter') === false;
    readOnly = !drive;
    document.documentElement.classList.toggle('rt-read-only', readOnly);
    document.getElementById('follow-banner').textContent = 'following class __CODE__: ' +
      (left ? 'the presenter has left; the class ends __IDLE__ after they left unless they ' +
              'come back' :
       drive ? 'the presenter lets you drive' : 'you see what the presenter shows (read-only)');
  }
  window.addEventListener('keydown', function (e) {
    if (readOnly) { e.stopImmediatePropagation(); }
  }, true);
  var asked = 0;
  function join() {
    // connected, its state read, the view's image element there but empty: ask for the picture
    // on show (the session sends it to every page; it answers at most twice a second)
    var t = window.trame, img = document.querySelector('#view-3d img');
    if (!t || !t.trigger || !t.state || !t.state.get('follow_code') || !img) return;
    if (img.getAttribute('src') || Date.now() - asked < 2000) return;
    asked = Date.now();
    Promise.resolve().then(function () { return t.trigger('follow_joined'); })
      .catch(function () { asked = 0; });
  }
  update();
  setInterval(function () { if (!ended) { join(); update(); } }, 500);
})();
</script>
"""


async def _pump(source, target, reads: coalesce.PageReads | None = None) -> None:
    """Copy websocket messages from ``source`` to ``target`` until either closes; a page's
    count of what it has taken goes to ``reads``, not on."""
    async for message in source:
        if target.closed:
            break
        try:
            if message.type == WSMsgType.TEXT:
                if reads is not None and reads.note(message.data):
                    continue
                await target.send_str(message.data)
            elif message.type == WSMsgType.BINARY:
                await target.send_bytes(message.data)
            else:
                break
        except ConnectionResetError:  # the target went while this message was on its way
            break
    if not target.closed:
        await target.close()


async def _pump_to_browser(
    session_socket, browser, limit_bytes: int, reads: coalesce.PageReads | None = None
) -> None:
    """Copy a session's websocket messages to ``browser`` without ever holding the session back:
    they wait here while the browser reads (:class:`app.serve.coalesce.Backlog`: while they wait,
    consecutive state publishes are merged into one, so a page that is behind jumps to the newest
    state; ``reads``: what the page says it has taken, which bounds what is on its way); a
    browser more than ``limit_bytes`` behind in what cannot be merged is closed with
    :data:`SLOW_CLOSE`."""
    backlog = coalesce.Backlog()
    reads = reads or coalesce.PageReads()

    def urgent() -> bool:
        return backlog.urgent > 0

    async def write() -> None:
        while True:
            # meanwhile what the session sends waits, and merges; an urgent message goes at once
            behind = await reads.room(urgent)
            if (message := await backlog.get(behind or urgent())) is None:
                break
            reads.sent += 1
            kind, data = message
            if kind == WSMsgType.TEXT:
                await browser.send_str(data)
            else:
                await browser.send_bytes(data)

    writer = asyncio.create_task(write())
    too_slow = False
    try:
        async for message in session_socket:
            if browser.closed or writer.done():
                break
            if message.type not in (WSMsgType.TEXT, WSMsgType.BINARY):
                break
            if backlog.put(message.type, message.data):
                reads.urge()
            if backlog.bytes > limit_bytes:
                too_slow = True
                break
    finally:
        if too_slow:  # the session stops sending to it; what waits here is dropped, the
            await session_socket.close()  # message on its way is let finish (a frame cut
            backlog.drop()  # short would garble the close that follows)
        backlog.close()
        reads.stop()
        try:
            await asyncio.wait_for(writer, SLOW_WRITE_S if too_slow else None)
        except (TimeoutError, asyncio.CancelledError, ConnectionError, RuntimeError):
            pass  # a browser that reads nothing, or the browser went while a message was on its way
    if backlog.merged:
        log.debug("%d state messages merged for a browser that was behind", backlog.merged)
    if too_slow and not browser.closed:
        log.warning("a browser fell over %d bytes behind its session: closed", limit_bytes)
        await browser.close(code=SLOW_CLOSE, message=b"too slow to follow")
    elif not browser.closed:
        await browser.close()


def run_front(front: Front, host: str, port: int, on_listening=None) -> None:
    """Serve ``front`` until Ctrl-C or SIGTERM; the session processes are stopped on the way out.
    ``on_listening()`` is called once the port listens."""
    web.run_app(
        front.application(),
        host=host,
        port=port,
        print=lambda _: on_listening() if on_listening is not None else None,
        handle_signals=True,
        shutdown_timeout=STOP_TIMEOUT_S,
    )


def pool_dir() -> Path:
    """A fresh folder for the solver slots of this server."""
    import tempfile

    return Path(tempfile.mkdtemp(prefix=f"racetrace-slots-{os.getpid()}-"))
