"""The front server's choice of session per request (app.serve.front), without processes."""

from __future__ import annotations

import asyncio
import itertools

import pytest
from aiohttp.test_utils import make_mocked_request

from app.access import Access
from app.serve import front as front_module
from app.serve.front import COOKIE, Front, NoSession, Session


class FakeProcess:
    returncode = None


def _front(monkeypatch, shared=False) -> Front:
    front = Front(Access("127.0.0.1"), [], shared=shared)
    ports = itertools.count(40000)

    async def spawn():
        ready = asyncio.get_running_loop().create_future()
        ready.set_result(True)
        port = next(ports)
        return Session(f"s{port}", port, f"secret{port}", FakeProcess(), ready)

    monkeypatch.setattr(front, "_spawn", spawn)
    return front


def _request(cookie: str = "", accept: str = "text/html", websocket: bool = False):
    headers = {"Host": "127.0.0.1:8080", "Accept": accept}
    if cookie:
        headers["Cookie"] = f"{COOKIE}={cookie}"
    if websocket:
        headers.update({"Upgrade": "websocket", "Connection": "Upgrade"})
    return make_mocked_request("GET", "/ws" if websocket else "/", headers=headers)


def test_each_new_browser_gets_its_own_session(monkeypatch):
    async def scenario():
        front = _front(monkeypatch)
        a, new_a = await front._session_for(_request())
        b, new_b = await front._session_for(_request())
        assert new_a and new_b and a.sid != b.sid
        again, new = await front._session_for(_request(cookie=a.sid))
        assert again is a and not new
        # a script or a health check without a cookie is answered by the spare, not given it
        spare, new = await front._session_for(_request(accept="*/*"))
        assert not new and spare.sid not in front.sessions
        # a websocket without a session is refused
        with pytest.raises(NoSession, match="open the page first"):
            await front._session_for(_request(websocket=True))
        ws, _ = await front._session_for(_request(cookie=b.sid, websocket=True))
        assert ws is b

    asyncio.run(scenario())


def test_new_browsers_beyond_the_limit_are_told_why(monkeypatch):
    monkeypatch.setattr(front_module, "MAX_SESSIONS", 2)

    async def scenario():
        front = _front(monkeypatch)
        await front._session_for(_request())
        await front._session_for(_request())
        with pytest.raises(NoSession, match="--shared"):
            await front._session_for(_request())

    asyncio.run(scenario())


def test_shared_mode_gives_everyone_one_session(monkeypatch):
    async def scenario():
        front = _front(monkeypatch, shared=True)
        sids = {(await front._session_for(_request()))[0].sid for _ in range(4)}
        assert len(sids) == 1

    asyncio.run(scenario())


def test_a_session_answers_only_requests_carrying_its_secret():
    from aiohttp import web

    from app.serve.session_guard import SECRET_HEADER, front_only

    check = front_only("the-secret", Access("127.0.0.1"))

    async def handler(_request):
        return web.Response(text="served")

    def status(**headers) -> int:
        headers = {"Host": "127.0.0.1:5000", **headers}
        request = make_mocked_request("GET", "/ws", headers=headers)
        return asyncio.run(check(request, handler)).status

    secret = {SECRET_HEADER: "the-secret"}
    assert status(**secret) == 200
    assert status() == 403
    assert status(**{SECRET_HEADER: "the-secreT"}) == 403
    assert status(**{SECRET_HEADER: ""}) == 403
    # the secret does not lift the Host and Origin rules
    assert status(**secret, Host="rebind.example") == 403
    assert status(**secret, Origin="http://evil.example") == 403
    # a session without a secret answers nobody
    open_session = front_only("", Access("127.0.0.1"))
    request = make_mocked_request("GET", "/", headers={"Host": "127.0.0.1", SECRET_HEADER: ""})
    assert asyncio.run(open_session(request, handler)).status == 403
