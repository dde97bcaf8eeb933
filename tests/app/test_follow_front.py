"""Follow mode at the front (app.serve.front), in-process, without session processes: a stand-in
session (a small aiohttp server that answers the page, the follow status and a websocket) behind
a real front on a loopback port. A class ends at the idle stop once its presenter has left, even
with followers, and they are told; wrong join codes are refused per client address after
:data:`app.serve.follow.WRONG_CODES_PER_MINUTE` of them."""

from __future__ import annotations

import asyncio
import contextlib
import signal
import threading
import time

import aiohttp
import pytest
from aiohttp import WSMsgType, web
from aiohttp.test_utils import TestServer

from app.access import Access
from app.serve import follow
from app.serve import front as front_module
from app.serve.front import Front, Session

CODE = "ABC234"


class StandInProcess:
    """What the front knows of a session process: whether it runs, a signal, its end."""

    def __init__(self):
        self.returncode = None
        self.signals: list[int] = []

    def send_signal(self, sig: int) -> None:
        self.signals.append(sig)
        self.returncode = 0

    def kill(self) -> None:
        self.returncode = -9

    async def wait(self) -> int:
        return self.returncode


def _stand_in_session(
    page_html: str = "<html><body>app</body></html>", websocket=None
) -> web.Application:
    """A session's answers the front relays: the page (``page_html``), the follow status, a
    websocket (the handler ``websocket``, by default one that stays open until the other side
    closes it)."""

    async def page(_request):
        return web.Response(text=page_html, content_type="text/html")

    async def status(_request):
        return web.json_response({"code": CODE, "drive": False})

    async def socket(request):
        ws = web.WebSocketResponse()
        await ws.prepare(request)
        async for _ in ws:
            pass
        return ws

    app = web.Application()
    app.router.add_get(follow.STATUS_PATH, status)
    app.router.add_get("/ws", websocket or socket)
    app.router.add_get("/{tail:.*}", page)
    return app


async def _served_front(monkeypatch, upstream: TestServer):
    """A front whose sessions are the stand-in at ``upstream`` (each with its own process)."""
    front = Front(Access("127.0.0.1"), [])
    processes = []

    async def spawn():
        ready = asyncio.get_running_loop().create_future()
        ready.set_result(True)
        processes.append(StandInProcess())
        session = Session(f"s{len(processes)}", upstream.port, "", processes[-1], ready)
        session.join_code = CODE
        return session

    monkeypatch.setattr(front, "_spawn", spawn)
    server = TestServer(front.application(), host="127.0.0.1")
    await server.start_server()
    return front, server, processes


@contextlib.contextmanager
def front_in_thread(monkeypatch, session_app: web.Application):
    """A front on a loopback port, serving in a thread of its own (for a browser test), whose
    sessions are the stand-in ``session_app``: yields its base URL and the sessions' processes;
    stopped on the way out."""
    loop = asyncio.new_event_loop()
    started: dict = {}

    async def start():
        upstream = TestServer(session_app, host="127.0.0.1")
        await upstream.start_server()
        _front, server, processes = await _served_front(monkeypatch, upstream)
        started.update(upstream=upstream, server=server, processes=processes)

    def serve():
        asyncio.set_event_loop(loop)
        loop.run_until_complete(start())
        loop.run_forever()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    while "server" not in started and thread.is_alive():
        threading.Event().wait(0.05)
    try:
        yield f"http://127.0.0.1:{started['server'].port}", started["processes"]
    finally:

        async def stop():
            await started["server"].close()
            await started["upstream"].close()

        asyncio.run_coroutine_threadsafe(stop(), loop).result(timeout=30)
        loop.call_soon_threadsafe(loop.stop)
        thread.join(timeout=30)


def test_a_class_ends_when_its_presenter_has_left_for_the_idle_time(monkeypatch):
    monkeypatch.setattr(front_module, "IDLE_S", 1.0)
    monkeypatch.setattr(front_module, "REAP_EVERY_S", 0.1)

    async def scenario():
        upstream = TestServer(_stand_in_session(), host="127.0.0.1")
        await upstream.start_server()
        front, server, processes = await _served_front(monkeypatch, upstream)
        base = f"http://127.0.0.1:{server.port}"
        jar = aiohttp.CookieJar(unsafe=True)
        async with aiohttp.ClientSession(cookie_jar=jar) as http:
            async with http.get(base + "/", headers={"Accept": "text/html"}) as page:
                assert page.status == 200
            (session,) = front.sessions.values()
            presenter = await http.ws_connect(base.replace("http", "ws") + "/ws", origin=base)
            async with aiohttp.ClientSession() as follower_http:
                async with follower_http.get(
                    f"{base}/?follow={CODE}", headers={"Accept": "text/html"}
                ) as page:
                    assert page.status == 200 and "following class" in await page.text()
                follower = await follower_http.ws_connect(
                    f"ws://127.0.0.1:{server.port}/follow/{CODE}/ws", origin=base
                )
                assert session.presenters == 1 and len(session.followers) == 1
                # with its presenter there, a session lasts past the idle time
                await asyncio.sleep(2.0)
                assert session.alive and not processes[0].signals
                # the presenter leaves: the followers do not keep the session
                await presenter.close()
                left = time.monotonic()
                message = await asyncio.wait_for(follower.receive(), timeout=15)
                assert message.type in (WSMsgType.CLOSE, WSMsgType.CLOSED)
                assert follower.close_code == follow.PRESENTER_LEFT_CLOSE
                assert time.monotonic() - left >= 0.9  # not before the idle time
                for _ in range(100):  # the session process is then stopped
                    if processes[0].signals:
                        break
                    await asyncio.sleep(0.05)
                assert processes[0].signals == [signal.SIGTERM]
                assert session.sid not in front.sessions
                # a follower opening the page again is told that the class has ended
                async with follower_http.get(
                    f"{base}/follow/{CODE}/", headers={"Accept": "text/html"}
                ) as page:
                    text = await page.text()
                    assert page.status == 404 and "The presenter has left" in text
                    assert f"class {CODE} has ended" in text
        await server.close()
        await upstream.close()

    asyncio.run(scenario())


def test_the_followers_page_says_when_the_presenter_has_left():
    banner = front_module._follower_banner(CODE)
    assert "follow_presenter" in banner and "the presenter has left" in banner
    assert f"e.code === {follow.PRESENTER_LEFT_CLOSE}" in banner
    assert "2 minutes" in banner and "__" not in banner  # every placeholder filled


def test_guessing_join_codes_is_refused_after_too_many_wrong_ones(monkeypatch):
    async def scenario():
        upstream = TestServer(_stand_in_session(), host="127.0.0.1")
        await upstream.start_server()
        front, server, _ = await _served_front(monkeypatch, upstream)
        front._wrong_codes = follow.WrongCodeLimit(limit=4)
        base = f"http://127.0.0.1:{server.port}"
        html = {"Accept": "text/html"}
        async with aiohttp.ClientSession(cookie_jar=aiohttp.CookieJar(unsafe=True)) as http:
            async with http.get(base + "/", headers=html) as page:  # the presenter's session
                assert page.status == 200
            wrong = ["ZZZZZZ", "YYYYYY", "/follow/XXXXXX/", "/follow/WWWWWW/ws"]
            for guess in wrong:
                url = base + (guess if guess.startswith("/") else f"/?follow={guess}")
                async with http.get(url, headers=html, allow_redirects=False) as r:
                    assert r.status == 404, guess
            # the limit reached: every code is refused now, the right one too (or it would tell)
            for url in (f"/?follow={CODE}", f"/follow/{CODE}/", "/?follow=VVVVVV"):
                async with http.get(base + url, headers=html, allow_redirects=False) as r:
                    assert r.status == 429, url
                    assert 0 < int(r.headers["Retry-After"]) <= 60
                    text = await r.text()
                    assert "Too many wrong join codes" in text and "4 join codes" in text
            with pytest.raises(aiohttp.WSServerHandshakeError) as refused:
                await http.ws_connect(f"ws://127.0.0.1:{server.port}/follow/{CODE}/ws")
            assert refused.value.status == 429
            # the presenter's own page is not a join code: still served
            async with http.get(base + "/", headers=html) as page:
                assert page.status == 200
            # a minute later the address may try again
            front._wrong_codes._wrong = {
                address: type(times)(t - 61.0 for t in times)
                for address, times in front._wrong_codes._wrong.items()
            }
            async with http.get(f"{base}/?follow={CODE}", headers=html, allow_redirects=False) as r:
                assert r.status == 302 and r.headers["Location"] == f"/follow/{CODE}/"
        await server.close()
        await upstream.close()

    asyncio.run(scenario())


def test_a_follower_that_does_not_read_never_holds_its_session_back(monkeypatch):
    """A session streams 24 MB to a follower that reads nothing: the session's sends all
    complete at once (what the follower has not read waits at the front, not in the session),
    and the front closes the follower with SLOW_CLOSE once it is past its backlog bound."""
    monkeypatch.setattr(front_module, "FOLLOWER_BACKLOG_BYTES", 2 * 1024 * 1024)
    message_bytes, count = 256 * 1024, 96
    sent = asyncio.Event()

    async def scenario():
        async def streaming(request):
            ws = web.WebSocketResponse()
            await ws.prepare(request)
            if request.headers.get(front_module.FOLLOWER_HEADER):
                for _ in range(count):
                    await ws.send_bytes(b"x" * message_bytes)
                sent.set()
            async for _ in ws:
                pass
            return ws

        upstream = TestServer(_stand_in_session(websocket=streaming), host="127.0.0.1")
        await upstream.start_server()
        front, server, _processes = await _served_front(monkeypatch, upstream)
        base = f"http://127.0.0.1:{server.port}"
        jar = aiohttp.CookieJar(unsafe=True)
        async with aiohttp.ClientSession(cookie_jar=jar) as http:
            async with http.get(base + "/", headers={"Accept": "text/html"}) as page:
                assert page.status == 200
            async with aiohttp.ClientSession() as follower_http:
                follower = await follower_http.ws_connect(
                    f"ws://127.0.0.1:{server.port}/follow/{CODE}/ws", origin=base
                )
                # the follower reads nothing: the session is not held back all the same
                await asyncio.wait_for(sent.wait(), timeout=20)
                received = 0
                while True:
                    message = await asyncio.wait_for(follower.receive(), timeout=20)
                    if message.type != WSMsgType.BINARY:
                        break
                    received += 1
                assert message.type == WSMsgType.CLOSE and message.data == front_module.SLOW_CLOSE
                assert received < count
        await server.close()
        await upstream.close()

    asyncio.run(scenario())
