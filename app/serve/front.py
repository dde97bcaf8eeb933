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
whose browsers have all left is stopped after :data:`IDLE_S`. Session processes stop when the
front ends, even when it is killed (they watch their parent).
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
from . import preparing
from .quiet_log import quiet_closed_connections
from .session_guard import SECRET_ENV, SECRET_HEADER, new_secret

log = logging.getLogger("racetrace.front")

COOKIE = "racetrace_session"
IDLE_S = 120.0  # a session without browsers is stopped after this
MAX_SESSIONS = 8  # sessions (browsers) at once; each is a process of about 0.5 GB
# a cold numba cache compiles the quasi-static kernels first: minutes on a busy machine (the page
# says what is being prepared meanwhile, :data:`PREPARING_PATH`)
START_TIMEOUT_S = 1800.0
PREPARING_PATH = "/__racetrace_preparing"  # what the first session waits for, as JSON
STOP_TIMEOUT_S = 40.0  # a session stopping saves its run first (it waits up to 20 s for it)
_HOP_HEADERS = {
    "connection",
    "keep-alive",
    "transfer-encoding",
    "content-encoding",
    "content-length",
    "upgrade",
    "host",
    SECRET_HEADER.lower(),  # the front's to give, never the browser's
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
    sockets: int = 0
    idle_since: float = field(default_factory=time.monotonic)

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
        self.sessions[session.sid] = session
        if not self.shared:
            self._spare = await self._spawn()  # the next browser's
        return session, True

    async def _reap(self) -> None:
        """Stop sessions without browsers for IDLE_S (never the shared one)."""
        while True:
            await asyncio.sleep(5.0)
            now = time.monotonic()
            for sid, session in list(self.sessions.items()):
                if not session.alive:
                    del self.sessions[sid]
                elif not self.shared and session.sockets == 0 and now - session.idle_since > IDLE_S:
                    del self.sessions[sid]
                    await self._stop(session)

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
        if new:
            response.set_cookie(COOKIE, session.sid, httponly=True, samesite="Strict", path="/")
        self.access.grant(request, response)
        return response

    async def _relay_http(self, request: web.Request, session: Session) -> web.Response:
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
        url = f"http://127.0.0.1:{session.port}{request.rel_url}"
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

    async def _relay_websocket(self, request: web.Request, session: Session):
        browser = web.WebSocketResponse(max_msg_size=0, autoping=True, heartbeat=None)
        await browser.prepare(request)
        url = f"ws://127.0.0.1:{session.port}{request.rel_url}"
        session.sockets += 1
        try:
            async with self._http.ws_connect(
                url,
                max_msg_size=0,
                origin=f"http://127.0.0.1:{session.port}",
                headers={SECRET_HEADER: session.secret},
            ) as upstream:
                await asyncio.gather(_pump(browser, upstream), _pump(upstream, browser))
        except OSError as error:
            log.warning("session %s unreachable: %s", session.sid[:6], error)
        finally:
            session.sockets -= 1
            session.idle_since = time.monotonic()
            await browser.close()
        return browser

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


async def _pump(source, target) -> None:
    """Copy websocket messages from ``source`` to ``target`` until either closes."""
    async for message in source:
        if target.closed:
            break
        try:
            if message.type == WSMsgType.TEXT:
                await target.send_str(message.data)
            elif message.type == WSMsgType.BINARY:
                await target.send_bytes(message.data)
            else:
                break
        except ConnectionResetError:  # the target went while this message was on its way
            break
    if not target.closed:
        await target.close()


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
