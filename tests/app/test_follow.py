"""Follow mode: the front's read-only gate on a follower's wslink messages (app.serve.follow), the
join code and hand-over of a session (app.components.follow), and, against a real
``racetrace serve``, followers at the websocket level: a wrong code refused, a follower counted,
its changes refused until the presenter hands over, let through then, refused after take-back."""

from __future__ import annotations

import asyncio
import re

import aiohttp
import msgpack
import pytest

from app.components.follow import CODE_ALPHABET, CODE_LENGTH, new_join_code
from app.follow_names import QR_NAME
from app.serve import follow
from app.serve.follow import FollowerGate, WrongCodeLimit, normal_code, refusal_reply
from tests.helpers.serve import start_server, stop_server
from tests.helpers.wslink_client import WslinkClient, chunk


def _rpc(method: str, *args, rpcid: str = "rpc:c0:1") -> dict:
    return {"wslink": "1.0", "id": rpcid, "method": method, "args": list(args)}


def _update(**changes) -> dict:
    return _rpc("trame.state.update", [{"key": k, "value": v} for k, v in changes.items()])


# ---- the gate, pure ------------------------------------------------------------------------------
def test_a_follower_may_read_but_not_change_unless_driving():
    refusal = FollowerGate.refusal
    hello = _rpc("wslink.hello", {"secret": "wslink-secret"}, rpcid="system:c0:0")
    for call in (
        hello,
        _rpc("trame.state.get"),
        _rpc("trame.error.client", "boom"),
        _rpc("trame.lifecycle.update", "client_connected"),
    ):
        assert refusal(call, driving=False) == "", call
    assert refusal(_rpc("trame.trigger", "follow_joined", [], {}), driving=False) == ""
    for call in (_update(frame=3), _rpc("trame.trigger", "trigger__1", [], {})):
        assert "has not handed over" in refusal(call, driving=False)
        assert refusal(call, driving=True) == ""
    # never a follower's, even driving: handing itself the controls, sizing or feeding the render,
    # an unknown lifecycle name (it would call a server callback), what is not a wslink call
    for call in (
        _update(follow_drive=True),
        _update(frame=3, follow_count=0),
        _rpc("trame.rca.size", "view", "self", {"w": 10, "h": 10}),
        _rpc("trame.rca.push", "view", {}, b"x"),
        _rpc("trame.rca.drop", "view", 0),
        _rpc("trame.lifecycle.update", "server_ready"),
        _rpc("wslink.hello", {"secret": "x"}),  # a hello outside the system ids
        _rpc("trame.state.update", "frame"),  # not a list of changes
        {"id": "rpc:c0:1"},
        None,
    ):
        assert refusal(call, driving=True), call
    assert "only the presenter changes follow_drive" in refusal(
        _update(follow_drive=False), driving=True
    )


def test_the_gate_joins_chunks_and_refuses_what_no_page_sends():
    message = msgpack.packb(_update(frame=7))
    parts = [message[:5], message[5:]]
    gate = FollowerGate()
    ident = (1234).to_bytes(4, "little")
    size = len(message).to_bytes(4, "little")
    first = ident + (0).to_bytes(4, "little") + size + parts[0]
    second = ident + len(parts[0]).to_bytes(4, "little") + size + parts[1]
    assert gate.add_chunk(first) is None
    whole = gate.add_chunk(second)
    assert whole.chunks == [first, second] and whole.rpc["args"][0][0] == {
        "key": "frame",
        "value": 7,
    }
    assert gate.add_chunk(chunk({"method": "trame.state.get", "id": "x"})).rpc["id"] == "x"
    with pytest.raises(ValueError, match="shorter than its header"):
        gate.add_chunk(b"1234")
    huge = (follow.MAX_MESSAGE_BYTES + 1).to_bytes(4, "little")
    with pytest.raises(ValueError, match="at most"):
        gate.add_chunk(ident + (0).to_bytes(4, "little") + huge + b"x")
    with pytest.raises(ValueError, match="does not fit"):
        gate.add_chunk(ident + (5).to_bytes(4, "little") + (6).to_bytes(4, "little") + b"xyz")
    # a body that is not msgpack is read as "not a wslink call"
    junk = gate.add_chunk(
        ident + (0).to_bytes(4, "little") + (2).to_bytes(4, "little") + b"\xc1\xc1"
    )
    assert junk.rpc is None and FollowerGate.refusal(junk.rpc, True) == "not a wslink call"


def test_a_refused_call_is_answered_with_a_wslink_error():
    reply = refusal_reply(_update(frame=1), "read-only: the presenter has not handed over")
    size = int.from_bytes(reply[8:12], "little")
    message = msgpack.unpackb(reply[12:], raw=False)
    assert size == len(reply) - 12 and message["id"] == "rpc:c0:1"
    assert message["error"]["message"].endswith("has not handed over")
    assert refusal_reply({"method": "x"}, "why") is None  # nothing to answer


def test_join_codes():
    codes = {new_join_code() for _ in range(200)}
    assert len(codes) == 200
    assert all(len(c) == CODE_LENGTH and set(c) <= set(CODE_ALPHABET) for c in codes)
    assert normal_code(" abc-234 ") == "ABC234"
    assert normal_code("../x") == "" and normal_code("") == ""


def test_the_session_counts_followers_and_says_whether_they_drive(app):
    follow_part = app.follow
    assert app.state.follow_code == follow_part.code and follow_part.status()["drive"] is False
    app.state.follow_drive = "yes"  # only a real True hands over
    assert follow_part.status()["drive"] is False
    app.state.follow_drive = True
    assert follow_part.status() == {"code": follow_part.code, "drive": True}


def test_the_session_says_whether_its_presenter_is_there(app):
    """``follow_presenter``: a websocket the front did not mark as a follower's is the
    presenter's; followers' pages read it to say that the presenter has left."""
    from app.follow_names import FOLLOWER_HEADER

    class Protocol:
        def onConnect(self, request, client_id):  # noqa: N802 - wslink's name
            pass

        def onClose(self, client_id):  # noqa: N802
            pass

    class Request:
        def __init__(self, follower: bool):
            self.headers = {FOLLOWER_HEADER: "1"} if follower else {}

    protocol = Protocol()
    app.follow._configure_protocol(protocol)
    assert app.state.follow_presenter is False
    protocol.onConnect(Request(follower=False), "presenter")
    protocol.onConnect(Request(follower=True), "follower")
    assert app.state.follow_presenter is True and app.state.follow_count == 1
    protocol.onConnect(Request(follower=False), "presenter-second-tab")
    protocol.onClose("presenter")
    assert app.state.follow_presenter is True  # another page of the presenter's is open
    protocol.onClose("presenter-second-tab")
    assert app.state.follow_presenter is False and app.state.follow_count == 1
    protocol.onConnect(Request(follower=False), "presenter-back")
    assert app.state.follow_presenter is True
    protocol.onClose("follower")
    assert app.state.follow_count == 0 and app.state.follow_presenter is True


def test_wrong_join_codes_are_limited_per_address_and_minute():
    limit = WrongCodeLimit(limit=3, window_s=60.0, max_addresses=2)
    for t in (0.0, 10.0, 20.0):
        assert limit.retry_after("10.0.0.1", t) == 0.0
        limit.note_wrong("10.0.0.1", t)
    # the third wrong code within the minute: refused until the first is a minute old
    assert limit.retry_after("10.0.0.1", 30.0) == pytest.approx(30.0)
    assert limit.retry_after("10.0.0.2", 30.0) == 0.0  # another address is not
    assert limit.retry_after("10.0.0.1", 60.5) == 0.0
    limit.note_wrong("10.0.0.1", 71.0)  # two within the minute again (0 and 10 gone: 20, 71)
    assert limit.retry_after("10.0.0.1", 72.0) == 0.0
    limit.note_wrong("10.0.0.1", 72.0)
    assert limit.retry_after("10.0.0.1", 73.0) == pytest.approx(7.0)
    # at most max_addresses remembered: the longest quiet one is forgotten
    limit.note_wrong("10.0.0.2", 74.0)
    limit.note_wrong("10.0.0.3", 75.0)
    assert set(limit._wrong) == {"10.0.0.2", "10.0.0.3"}


# ---- against a real server -----------------------------------------------------------------------
@pytest.fixture(scope="module")
def served(tmp_path_factory):
    root = tmp_path_factory.mktemp("follow")
    server = start_server(root / "runs", root / "serve.log")
    yield server
    stop_server(server, timeout_s=60)


async def _presenter(http, server) -> WslinkClient:
    """The presenter's page: opened (a session of its own), then its websocket."""
    base = f"http://127.0.0.1:{server['port']}"
    async with http.get(base + "/", headers={"Accept": "text/html"}) as page:
        assert page.status == 200
    client = WslinkClient()
    await client.connect(http, f"ws://127.0.0.1:{server['port']}/ws", origin=base)
    return client


async def _follower(server, code: str) -> tuple[aiohttp.ClientSession, WslinkClient]:
    base = f"http://127.0.0.1:{server['port']}"
    http = aiohttp.ClientSession(cookie_jar=aiohttp.CookieJar(unsafe=True))
    async with http.get(f"{base}/?follow={code.lower()}", headers={"Accept": "text/html"}) as page:
        assert page.status == 200 and page.url.path.startswith(f"/follow/{code}/")
        assert "following class" in await page.text()
    client = WslinkClient()
    await client.connect(http, f"ws://127.0.0.1:{server['port']}/follow/{code}/ws", origin=base)
    return http, client


def test_followers_watch_read_only_until_handed_over(served):
    async def scenario():
        base = f"http://127.0.0.1:{served['port']}"
        jar = aiohttp.CookieJar(unsafe=True)
        async with aiohttp.ClientSession(cookie_jar=jar) as http:
            presenter = await _presenter(http, served)
            code = presenter.state["follow_code"]
            assert re.fullmatch(f"[{CODE_ALPHABET}]{{{CODE_LENGTH}}}", code)
            await presenter.update(playing=False)
            await presenter.update(frame=2)

            # a wrong code gets a page saying so, and no websocket
            async with http.get(f"{base}/?follow=ZZZZZZ", headers={"Accept": "text/html"}) as r:
                assert r.status == 404 and "No class with join code ZZZZZZ" in await r.text()
            with pytest.raises(aiohttp.WSServerHandshakeError):
                await http.ws_connect(
                    f"ws://127.0.0.1:{served['port']}/follow/ZZZZZZ/ws", origin=base
                )
            # the QR code is of the follow address as the presenter reached the server
            async with http.get(f"{base}/{QR_NAME}") as r:
                assert r.status == 200 and r.content_type == "image/svg+xml"
                expected = follow.qr_svg(follow.follow_url(f"127.0.0.1:{served['port']}", code))
                assert await r.read() == expected

            follower_http, follower = await _follower(served, code)
            try:
                assert follower.state["frame"] == 2
                assert follower.state["follow_code"] == code
                await presenter.wait_for("follow_count", lambda n: n == 1)
                # the presenter's changes reach the follower
                await presenter.update(frame=5)
                await follower.wait_for("frame", lambda f: f == 5)
                # the follower's are refused, answered, and change nothing
                with pytest.raises(RuntimeError, match="has not handed over"):
                    await follower.update(frame=9)
                with pytest.raises(RuntimeError, match="only the presenter changes follow_drive"):
                    await follower.update(follow_drive=True)
                assert await presenter.call("trame.state.get", []) is not None
                assert (await presenter.call("trame.state.get", []))["state"]["frame"] == 5
                # handed over: the follower drives, the presenter sees it
                await presenter.update(follow_drive=True)
                await follower.wait_for("follow_drive", lambda d: d is True)
                await follower.update(frame=9)
                await presenter.wait_for("frame", lambda f: f == 9)
                with pytest.raises(RuntimeError, match="only the presenter changes"):
                    await follower.update(follow_drive=False)
                # taken back: refused again
                await presenter.update(follow_drive=False)
                with pytest.raises(RuntimeError, match="has not handed over"):
                    await follower.update(frame=11)
                assert (await presenter.call("trame.state.get", []))["state"]["frame"] == 9
            finally:
                await follower.close()
                await follower_http.close()
            await presenter.wait_for("follow_count", lambda n: n == 0)
            await presenter.close()

    asyncio.run(scenario())
