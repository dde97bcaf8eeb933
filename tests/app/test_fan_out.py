"""A message a session publishes is packed once and the same bytes go to every page
(app.fan_out): a played frame costs the session one serialisation whatever the followers, and a
change one page made reaches each other page once."""

from __future__ import annotations

import asyncio
from types import SimpleNamespace

import msgpack
import wslink.protocol
from wslink.protocol import WslinkHandler
from wslink.websocket import LinkProtocol, ServerProtocol

import app.fan_out
from app.fan_out import FanOut, publish_once

PAGES = 31  # a presenter and 30 followers


class Page:
    """A page's websocket as the session's handler sees it: what it was sent."""

    def __init__(self, fail: bool = False):
        self.sent: list[bytes] = []
        self.closed = False
        self.fail = fail

    async def send_bytes(self, data: bytes) -> None:
        if self.fail:
            raise ConnectionResetError("the page went")
        self.sent.append(bytes(data))


class Root(ServerProtocol):
    def initialize(self):
        self.link = LinkProtocol()
        self.registerLinkProtocol(self.link)


def _session(pages: list[Page], last_active: str = "") -> tuple[Root, WslinkHandler]:
    """A wslink handler with ``pages`` connected and authenticated, as a trame session has them
    once its pages said hello."""
    root = Root()
    handler = WslinkHandler(root, SimpleNamespace(last_active_client_id=last_active))
    for i, page in enumerate(pages):
        handler.connections[f"c{i}"] = page
        handler.authentified_client_ids.add(f"c{i}")
    return root, handler


def _counting_packb(monkeypatch) -> list[int]:
    """Count msgpack packings done by wslink's handler and by app.fan_out."""
    calls = [0]
    pack = msgpack.packb

    def counted(*args, **kwargs):
        calls[0] += 1
        return pack(*args, **kwargs)

    monkeypatch.setattr(wslink.protocol.msgpack, "packb", counted)
    monkeypatch.setattr(app.fan_out.msgpack, "packb", counted)
    return calls


async def _settle(handler) -> None:
    """Let the scheduled sends run to their end."""
    for _ in range(200):
        await asyncio.sleep(0)
        if handler.network_monitor.pending == 0:
            return
    raise AssertionError("the published messages were not sent")


def _decoded(page: Page) -> list[dict]:
    # one chunk per message here (a few bytes, far under wslink's chunk size): header, then body
    return [msgpack.unpackb(chunk[12:], raw=False) for chunk in page.sent]


def test_a_frame_published_to_31_pages_is_packed_once_and_sent_as_the_same_bytes(monkeypatch):
    async def run():
        pages = [Page() for _ in range(PAGES)]
        pages[7].fail = True  # a page that went while the frame was on its way
        root, handler = _session(pages)
        publish_once(root)
        packed = _counting_packb(monkeypatch)
        root.publish("trame.state.topic", {"frame": 42, "rt3d_frame": {"index": 42}})
        root.publish("trame.state.topic", {"frame": 43, "rt3d_frame": {"index": 43}})
        await _settle(handler)
        return pages, packed[0]

    pages, packed = asyncio.run(run())
    assert packed == 2, f"two frames for {PAGES} pages were packed {packed} times"
    assert pages[7].sent == []
    pages = pages[:7] + pages[8:]
    assert all(len(p.sent) == 2 for p in pages), [len(p.sent) for p in pages]
    assert len({tuple(p.sent) for p in pages}) == 1  # the same bytes for every page
    first, second = _decoded(pages[0])
    assert first["id"] == second["id"] == "publish:trame.state.topic:0"
    assert [first["result"], second["result"]] == [
        {"frame": 42, "rt3d_frame": {"index": 42}},
        {"frame": 43, "rt3d_frame": {"index": 43}},
    ]


def test_a_change_a_page_made_reaches_each_other_page_once(monkeypatch):
    async def run():
        pages = [Page() for _ in range(5)]
        root, handler = _session(pages, last_active="c2")  # page c2 made the change
        assert publish_once(root) is True
        assert publish_once(root) is False  # once per session, however many pages connect
        assert isinstance(root.link.publish.__self__, FanOut)  # the link protocols' too
        root.publish("trame.state.topic", {"speed": 3}, skip_last_active_client=True)
        root.link.publish("trame.state.topic", {"frame": 7}, client_id="c1")  # to c1 alone
        await _settle(handler)
        return pages

    pages = asyncio.run(run())
    assert [len(p.sent) for p in pages] == [1, 2, 0, 1, 1]
    assert [m["result"] for m in _decoded(pages[1])] == [{"speed": 3}, {"frame": 7}]
