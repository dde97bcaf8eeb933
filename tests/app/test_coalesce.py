"""A browser that is behind its session gets only the newest state (app.serve.coalesce): while
messages wait at the front for a browser, consecutive trame state publishes are merged into one
(the later value of a key wins), anything else is a barrier kept in order, and a browser that
keeps up gets the session's bytes unchanged."""

from __future__ import annotations

import asyncio
import secrets

import aiohttp
import msgpack
from aiohttp import WSMsgType, web
from aiohttp.test_utils import TestServer

from app.front_keys import URGENT_KEY
from app.serve import coalesce
from app.serve import front as front_module
from app.serve.coalesce import Backlog
from tests.app.test_follow_front import CODE, _served_front, _stand_in_session


def _chunk(body: dict) -> bytes:
    packed = msgpack.packb(body)
    ident = secrets.randbits(32).to_bytes(4, "little")
    return ident + (0).to_bytes(4, "little") + len(packed).to_bytes(4, "little") + packed


def _call(method: str) -> bytes:
    """A page's call (one a follower may make)."""
    return _chunk({"wslink": "1.0", "id": "rpc:c0:1", "method": method, "args": []})


def _state(changes: dict) -> bytes:
    """A trame state publish, as app.fan_out sends it."""
    return _chunk({"wslink": "1.0", "id": "publish:trame.state.topic:0", "result": changes})


def _reply(n: int) -> bytes:
    """A barrier: the reply to a page's call."""
    return _chunk({"wslink": "1.0", "id": f"rpc:c0:{n}", "result": {"n": n}})


def _image(n: int) -> bytes:
    """A barrier: a message of another topic (an image of the server-rendered view)."""
    return _chunk({"wslink": "1.0", "id": "publish:trame.rca.topic.stream:0", "result": [n]})


def _picture(n: int, view: str = "view-3d", kind: str = "image/jpeg") -> bytes:
    """A picture of a server-rendered view, as trame-rca publishes it (``kind``
    ``application/octet-stream``: a video packet, which builds on the one before)."""
    meta = {"type": kind, "codec": "", "w": 8, "h": 8, "st": n, "key": "key"}
    body = {"name": view, "meta": meta, "content": bytes([n % 251]) * 50}
    return _chunk({"wslink": "1.0", "id": f"publish:trame.rca.topic.stream:{n}", "result": body})


def _decoded(data: bytes) -> dict:
    size = int.from_bytes(data[8:12], "little")
    assert int.from_bytes(data[4:8], "little") == 0 and size == len(data) - 12
    return msgpack.unpackb(data[12:], raw=False)


def _session_stream(n: int, barrier_every: int, filler: int) -> list[bytes]:
    """What a session sends while playing: ``n`` frames' state (``frame``, its words, a payload
    of ``filler`` bytes), a chart now and then (a key not in every message), and a barrier (a
    reply or an image) after every ``barrier_every`` frames."""
    stream = []
    for i in range(n):
        changes = {"frame": i, "frame_time": f"t = {i}", "rt3d_frame": bytes([i % 251]) * filler}
        if i % 7 == 0:
            changes["chart_contact_angle"] = f"chart at frame {i}"
        stream.append(_state(changes))
        if i % barrier_every == barrier_every - 1:
            stream.append(_reply(i) if i % 2 else _image(i))
    return stream


def _replay(received: list[bytes]) -> tuple[dict, list[tuple[str, dict]]]:
    """The state a page ends with after applying ``received`` in order, and each barrier's id
    with the state the page had when it arrived."""
    state, barriers = {}, []
    for data in received:
        body = _decoded(data)
        if body["id"].startswith(coalesce.STATE_ID_PREFIX):
            state.update(body["result"])
        else:
            barriers.append((f"{body['id']} {body['result']}", dict(state)))
    return state, barriers


def test_waiting_state_publishes_merge_and_barriers_keep_their_order():
    async def scenario():
        backlog = Backlog()
        stream = _session_stream(60, barrier_every=9, filler=100)
        backlog.put(WSMsgType.BINARY, stream[0])
        first = await backlog.get()  # on its way to the browser: what comes next waits
        for data in stream[1:]:
            backlog.put(WSMsgType.BINARY, data)
        backlog.close()
        received = [first[1]]
        while (message := await backlog.get()) is not None:
            received.append(message[1])
        return received, backlog

    received, backlog = asyncio.run(scenario())
    stream = _session_stream(60, barrier_every=9, filler=100)
    assert _replay(received) == _replay(stream)  # the same final state, the same barriers
    # between two barriers the waiting frames became one message
    barriers = sum(not _decoded(d)["id"].startswith(coalesce.STATE_ID_PREFIX) for d in stream)
    assert len(received) == 1 + barriers + (barriers + 1)
    assert backlog.merged == len(stream) - len(received) and backlog.bytes == 0


def test_a_text_message_a_multi_chunk_message_and_odd_bodies_are_barriers():
    async def scenario(odd: tuple[WSMsgType, bytes | str]):
        backlog = Backlog()
        backlog.put(WSMsgType.BINARY, _reply(0))
        await backlog.get()
        backlog.put(WSMsgType.BINARY, _state({"frame": 1}))
        backlog.put(*odd)
        backlog.put(WSMsgType.BINARY, _state({"frame": 2}))
        backlog.put(WSMsgType.BINARY, _state({"frame": 3}))
        return backlog

    whole = _state({"frame": 9, "rt3d_frame": b"x" * 40})
    first_part = whole[:4] + (0).to_bytes(4, "little") + whole[8:30]  # offset 0 of a longer body
    not_msgpack = whole[:12] + b"publish:trame.state.topic:0" + b"\xc1" * 8
    not_msgpack = not_msgpack[:8] + (len(not_msgpack) - 12).to_bytes(4, "little") + not_msgpack[12:]
    other_keys = _chunk({"wslink": "1.0", "id": "publish:trame.state.topic:0", "error": {}})
    for odd in (
        (WSMsgType.TEXT, "publish:trame.state.topic:0"),
        (WSMsgType.BINARY, first_part),
        (WSMsgType.BINARY, not_msgpack),
        (WSMsgType.BINARY, other_keys),
    ):
        backlog = asyncio.run(scenario(odd))
        # frame 1, the barrier, frames 2 and 3 merged: nothing merged across the barrier
        assert len(backlog) == 3 and backlog.merged == 1, odd
        assert backlog._waiting[1].data == odd[1]


def test_a_later_picture_of_a_view_replaces_a_waiting_one_and_the_states_around_it_merge():
    """While playing, a frame's state and its picture alternate: a picture replaces the one of
    the same view that waits, so the states merge and what waits stays one state and one
    picture. A picture of another view and a video packet are kept."""

    other, video = _picture(99, view="other"), _picture(98, kind="application/octet-stream")

    async def scenario(behind: bool):
        backlog = Backlog()
        stream = []
        for i in range(40):
            stream += [_state({"frame": i, "frame_time": f"t = {i}"}), _picture(i)]
        stream[41:41] = [other]
        stream[61:61] = [video]
        if behind:  # all came while the writer waited: dropped when the page is behind
            getting = asyncio.get_running_loop().create_task(backlog.get())
            await asyncio.sleep(0)
            for data in stream:
                backlog.put(WSMsgType.BINARY, data)
            first = await getting
            waiting = len(backlog)
            second = await backlog.get(behind=True)
            rest = [first[1], second[1]]
        else:  # one on its way: each came while another was on its way
            backlog.put(WSMsgType.BINARY, stream[0])
            rest = [(await backlog.get())[1]]
            for data in stream[1:]:
                backlog.put(WSMsgType.BINARY, data)
            waiting = len(backlog)
        backlog.close()
        while (message := await backlog.get(behind=behind)) is not None:
            rest.append(message[1])
        return stream, rest, waiting, backlog

    for behind in (False, True):
        stream, received, waiting, backlog = asyncio.run(scenario(behind))
        ids = [_decoded(d)["id"] for d in received]
        pictures = [d for d in received if "rca" in _decoded(d)["id"]]
        # the newest picture of the view is the last message; the other view's picture and the
        # video packet are kept
        assert received[-1] == stream[-1] and other in pictures and video in pictures
        assert len(pictures) == 3, ids
        assert _replay(received)[0] == _replay(stream)[0]  # the page ends in the same state
        assert backlog.replaced == 39 and backlog.bytes == 0
        if not behind:
            assert waiting == 6, ids  # state, other view, state, video packet, state, picture
        else:
            assert waiting == len(stream) - 1  # nothing dropped before the page was behind


def test_nothing_merges_while_the_writer_waits_for_a_message():
    """Messages that arrive together while nothing is on its way to the browser are passed as
    they came: merging is for a browser that has not taken the message before."""

    async def scenario():
        backlog = Backlog()
        stream = _session_stream(10, barrier_every=100, filler=10)
        getting = asyncio.get_running_loop().create_task(backlog.get())
        await asyncio.sleep(0)  # the writer waits for a message
        for data in stream:
            backlog.put(WSMsgType.BINARY, data)
        backlog.close()
        received = [(await getting)[1]]
        while (message := await backlog.get()) is not None:
            received.append(message[1])
        return stream, received

    stream, received = asyncio.run(scenario())
    assert received == stream


async def _through_front(
    monkeypatch, stream: list[bytes], read_pause_s: float | None, says_what_it_took=False
):
    """``stream`` sent by a stand-in session to a follower through a real front; the follower
    reads nothing until the session has sent it all (``read_pause_s`` None) or reads each
    message as it comes while the session pauses ``read_pause_s`` after every third message.
    ``says_what_it_took``: the follower says how many messages it has taken, as the page's
    script does (:data:`app.serve.coalesce.READ_SCRIPT`). What the follower received."""
    sent = asyncio.Event()
    sending = float(read_pause_s or 0.0)

    async def streaming(request):
        ws = web.WebSocketResponse()
        await ws.prepare(request)
        if request.headers.get(front_module.FOLLOWER_HEADER):
            await ws.receive()  # the page's first call: it is there
            for i, data in enumerate(stream):
                await ws.send_bytes(data)
                if sending and i % 3 == 2:  # in bursts of three, as a frame and a reply come
                    await asyncio.sleep(sending)
            sent.set()
        async for _ in ws:
            pass
        return ws

    upstream = TestServer(_stand_in_session(websocket=streaming), host="127.0.0.1")
    await upstream.start_server()
    front, server, _ = await _served_front(monkeypatch, upstream)
    base = f"http://127.0.0.1:{server.port}"
    received = []
    async with aiohttp.ClientSession(cookie_jar=aiohttp.CookieJar(unsafe=True)) as http:
        async with http.get(base + "/", headers={"Accept": "text/html"}) as page:
            assert page.status == 200
        async with aiohttp.ClientSession() as follower_http:
            follower = await follower_http.ws_connect(
                f"ws://127.0.0.1:{server.port}/follow/{CODE}/ws", origin=base, max_msg_size=0
            )
            if says_what_it_took:  # on open, before its first call
                await follower.send_str(f"{coalesce.READ_PREFIX}0")
            await follower.send_bytes(_call("trame.state.get"))
            if read_pause_s is None:
                await asyncio.wait_for(sent.wait(), timeout=30)
            told = 0
            while len(received) < len(stream):
                try:
                    message = await asyncio.wait_for(follower.receive(), timeout=2 + 3 * sending)
                except TimeoutError:
                    break  # merged: fewer messages than were sent
                if message.type != WSMsgType.BINARY:
                    break
                received.append(message.data)
                if says_what_it_took and len(received) - told >= max(1, coalesce.READ_WINDOW // 2):
                    told = len(received)
                    await follower.send_str(f"{coalesce.READ_PREFIX}{told}")
            await follower.close()
    await server.close()
    await upstream.close()
    return received


def test_a_follower_that_reads_slowly_gets_fewer_messages_and_the_sessions_state(monkeypatch):
    """A session plays 400 frames of 20 kB (8 MB, less than the follower's backlog bound) to a
    follower that reads nothing meanwhile: it then gets far fewer messages, the session's state
    at the end, and every barrier in order with the state it came after."""
    stream = _session_stream(400, barrier_every=50, filler=20_000)

    received = asyncio.run(_through_front(monkeypatch, stream, read_pause_s=None))
    final, barriers = _replay(received)
    assert (final, barriers) == _replay(stream)
    assert len(received) < len(stream) // 2, (len(received), len(stream))


def test_a_follower_that_keeps_up_gets_the_sessions_bytes(monkeypatch):
    stream = _session_stream(60, barrier_every=9, filler=2_000)

    received = asyncio.run(_through_front(monkeypatch, stream, read_pause_s=0.01))
    assert received == stream


def test_a_large_waiting_state_is_not_packed_again_for_every_frame_merged_into_it(monkeypatch):
    """A chart (1 MB) waits with a frame's state; 200 frames merge into it: the merged state is
    packed a few times (when its bound doubles, and once when sent), not once per frame."""
    packed = []
    pack = coalesce.state_message

    def counted(rpc_id, state):
        packed.append(rpc_id)
        return pack(rpc_id, state)

    monkeypatch.setattr(coalesce, "state_message", counted)

    async def scenario():
        backlog = Backlog()
        backlog.put(WSMsgType.BINARY, _reply(0))
        await backlog.get()
        backlog.put(WSMsgType.BINARY, _state({"frame": 0, "chart_raceway_map": "x" * 1_000_000}))
        for i in range(1, 201):
            backlog.put(WSMsgType.BINARY, _state({"frame": i, "rt3d_frame": b"m" * 18_000}))
            assert backlog.bytes >= len(
                pack("publish:trame.state.topic:0", backlog._waiting[0].state)
            )
        sent = await backlog.get()
        return backlog, sent

    backlog, sent = asyncio.run(scenario())
    assert len(packed) <= 4, len(packed)
    state = _decoded(sent[1])["result"]
    assert state["frame"] == 200 and len(state["chart_raceway_map"]) == 1_000_000
    assert backlog.merged == 200 and backlog.bytes == 0 and len(backlog) == 0


def test_a_page_that_says_what_it_took_has_a_few_messages_on_their_way_the_rest_merge(
    monkeypatch,
):
    """Small frames (2 kB: the operating system's buffers would hold them all) to a follower
    that says what it has taken, as the page's script does, and reads nothing until the session
    has sent them all: it gets the READ_WINDOW messages on their way, then merged ones, and the
    session's state and barriers."""
    stream = _session_stream(400, barrier_every=50, filler=2_000)
    barriers = len(stream) - 400

    received = asyncio.run(
        _through_front(monkeypatch, stream, read_pause_s=None, says_what_it_took=True)
    )
    assert _replay(received) == _replay(stream)
    # the window's messages and those that came at once while nothing was on its way, then
    # each barrier with the frames merged before it: a message for every 8 frames at most (without
    # the window, the buffers on the way held 93 of the 408 messages here)
    assert len(received) < 50, len(received)
    assert barriers == 8


def test_page_reads_bound_what_is_on_its_way_once_the_page_counts():
    async def scenario():
        reads = coalesce.PageReads(window=3)
        reads.sent = 5
        await asyncio.wait_for(reads.room(), 1)  # a page that has not said anything: no bound
        assert not reads.note("hello") and reads.note(f"{coalesce.READ_PREFIX}1")
        waiting = asyncio.get_running_loop().create_task(reads.room())
        await asyncio.sleep(0.05)
        assert not waiting.done()  # 5 sent, 1 taken: 4 on their way, more than 3
        reads.note(f"{coalesce.READ_PREFIX}99")  # at most what was sent
        await asyncio.wait_for(waiting, 1)
        assert reads.taken == 5
        reads.sent = 9
        waiting = asyncio.get_running_loop().create_task(reads.room())
        await asyncio.sleep(0.05)
        assert not waiting.done()
        reads.stop()  # the socket closes: nothing waits for the page any more
        await asyncio.wait_for(waiting, 1)

    asyncio.run(scenario())


def test_an_urgent_state_publish_is_counted_while_it_waits_also_once_merged():
    backlog = Backlog()
    assert not backlog.put(WSMsgType.BINARY, _state({"frame": 0}))
    asyncio.run(backlog.get())  # on its way: what comes now waits
    assert not backlog.put(WSMsgType.BINARY, _state({"frame": 1}))
    # the key's name elsewhere (a word in a value, another topic) is not urgent
    assert not backlog.put(WSMsgType.BINARY, _state({"words": URGENT_KEY}))
    assert not backlog.put(WSMsgType.BINARY, _reply(7))
    assert backlog.urgent == 0
    assert backlog.put(WSMsgType.BINARY, _state({"frame": 2, URGENT_KEY: 1}))
    assert backlog.put(WSMsgType.BINARY, _state({"frame": 3, URGENT_KEY: 2}))
    assert backlog.urgent == 1 and len(backlog) == 3  # the two urgent frames merged in one
    assert not backlog.put(WSMsgType.BINARY, _state({"frame": 4}))
    assert backlog.urgent == 1 and len(backlog) == 3  # merged into the urgent one: it stays
    sent = [_decoded(asyncio.run(backlog.get())[1])["result"] for _ in range(2)]
    assert backlog.urgent == 1 and sent[-1] == {"n": 7}
    last = _decoded(asyncio.run(backlog.get())[1])["result"]
    assert last == {"frame": 4, URGENT_KEY: 2} and backlog.urgent == 0


def test_an_urgent_message_ends_the_wait_for_room():
    async def scenario():
        reads = coalesce.PageReads(window=2)
        reads.note(f"{coalesce.READ_PREFIX}0")
        reads.sent = 2
        urgent = []
        waiting = asyncio.get_running_loop().create_task(reads.room(lambda: bool(urgent)))
        await asyncio.sleep(0.05)
        reads.urge()  # nothing urgent yet: it still waits
        await asyncio.sleep(0.05)
        assert not waiting.done()
        urgent.append(1)
        reads.urge()
        assert await asyncio.wait_for(waiting, 1) is True

    asyncio.run(scenario())


def test_an_urgent_frame_goes_to_a_page_whose_window_is_full(monkeypatch):
    """A page that counts what it took has two messages on their way and takes nothing more (it
    is drawing); the session's next frames wait at the front, but an urgent one goes at once,
    with the frames that waited before it merged into it."""
    frames = [_state({"frame": i, "rt3d_frame": bytes([i]) * 2_000}) for i in range(5)]
    urgent = _state({"frame": 5, URGENT_KEY: 1})
    after = _state({"frame": 6})
    go_on = asyncio.Event()

    async def streaming(request):
        ws = web.WebSocketResponse()
        await ws.prepare(request)
        if request.headers.get(front_module.FOLLOWER_HEADER):
            await ws.receive()
            for data in frames:
                await ws.send_bytes(data)
            await go_on.wait()
            await ws.send_bytes(urgent)
            await asyncio.sleep(0.3)  # the urgent frame went on its own: this one waits
            await ws.send_bytes(after)
        async for _ in ws:
            pass
        return ws

    async def scenario():
        upstream = TestServer(_stand_in_session(websocket=streaming), host="127.0.0.1")
        await upstream.start_server()
        front, server, _ = await _served_front(monkeypatch, upstream)
        base = f"http://127.0.0.1:{server.port}"
        received = []

        async def receive_for(seconds):
            while True:
                try:
                    message = await asyncio.wait_for(follower.receive(), timeout=seconds)
                except TimeoutError:
                    return
                received.append(_decoded(message.data)["result"])

        async with aiohttp.ClientSession(cookie_jar=aiohttp.CookieJar(unsafe=True)) as http:
            async with http.get(base + "/", headers={"Accept": "text/html"}) as page:
                assert page.status == 200
            async with aiohttp.ClientSession() as follower_http:
                follower = await follower_http.ws_connect(
                    f"ws://127.0.0.1:{server.port}/follow/{CODE}/ws", origin=base
                )
                await follower.send_str(f"{coalesce.READ_PREFIX}0")
                await follower.send_bytes(_call("trame.state.get"))
                await receive_for(1.0)
                before = list(received)
                go_on.set()
                await receive_for(1.0)
                await follower.close()
        await server.close()
        await upstream.close()
        return before, received

    before, received = asyncio.run(scenario())
    assert [r["frame"] for r in before] == [0, 1]  # the window: the rest waits
    assert len(received) == 3, received  # the urgent frame went; the frame after it waits
    assert received[2]["frame"] == 5 and received[2][URGENT_KEY] == 1
    assert received[2]["rt3d_frame"] == bytes([4]) * 2_000  # what waited, merged into it


def test_every_page_the_front_serves_says_what_it_took_before_its_own_scripts():
    page = "<html><head><script src='app.js'></script></head><body>app</body></html>"
    added = coalesce.with_read_script(page)
    assert added.index(coalesce.READ_PREFIX) < added.index("app.js")
    assert added.replace(coalesce.READ_SCRIPT, "") == page
    assert f"every = {max(1, coalesce.READ_WINDOW // 2)}" in coalesce.READ_SCRIPT
