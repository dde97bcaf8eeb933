"""In headless Chromium: a page the front serves says how many websocket messages it has
applied (app.serve.coalesce.READ_SCRIPT), counted once reads like trame's own (the message as a
Blob, its header then its body) are done, with trame's handler set after the socket is made; and
it gets the session's last state."""

from __future__ import annotations

import contextlib
import threading

import pytest
from aiohttp import web

from app.serve import coalesce
from tests.app.test_coalesce import _state
from tests.app.test_follow_front import _stand_in_session, front_in_thread
from tests.helpers.browser import BROWSER_MARKS

pytestmark = BROWSER_MARKS

MESSAGES = 40
# as trame's client: the socket made, then its handlers set; each message read as a Blob, in two
# reads, before it is applied
PAGE = """<html><head><title>stand-in</title></head><body><div id="app">app</div>
<script>
window.applied = 0;
window.addEventListener('load', () => {
  const socket = new WebSocket(window.location.href.replace(/^http/, 'ws').split('?')[0] + 'ws');
  socket.binaryType = 'blob';
  socket.onmessage = async (e) => {
    await e.data.slice(0, 12).arrayBuffer();
    const body = new Uint8Array(await e.data.slice(12).arrayBuffer());
    window.applied += 1;
    window.frame = body[body.length - 1];  // {..., "result": {"frame": i}}: i, a fixint
  };
  window.socket = socket;
});
</script></body></html>"""


def _count(text: str) -> int:
    """The number of messages a page's count ``racetrace-read:N`` says."""
    return int(text[len(coalesce.READ_PREFIX) :])


@contextlib.contextmanager
def _counting_front(monkeypatch, page: str):
    """A front on a loopback port, in a thread of its own, whose stand-in session serves
    ``page`` and sends it MESSAGES state messages; its base URL and the page's counts the front
    noted."""
    noted: list[str] = []
    note = coalesce.PageReads.note

    def noting(self, text):
        noted.append(text)
        return note(self, text)

    monkeypatch.setattr(coalesce.PageReads, "note", noting)

    async def streaming(request):
        ws = web.WebSocketResponse()
        await ws.prepare(request)
        for i in range(MESSAGES):
            await ws.send_bytes(_state({"frame": i}))
        async for _ in ws:
            pass
        return ws

    with front_in_thread(monkeypatch, _stand_in_session(page, websocket=streaming)) as served:
        yield served[0], noted


@contextlib.contextmanager
def _opened(browser, base: str):
    """A new page of ``browser`` at ``base``, and the list its uncaught errors go to."""
    context = browser.new_context()
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda error: errors.append(error))
    try:
        page.goto(base + "/")
        yield page, errors
    finally:
        context.close()


@pytest.fixture
def counting_front(monkeypatch):
    """:func:`_counting_front` of :data:`PAGE`."""
    with _counting_front(monkeypatch, PAGE) as served:
        yield served


def test_a_page_says_how_many_messages_it_has_applied(browser, counting_front):
    base, noted = counting_front
    with _opened(browser, base) as (page, errors):
        page.wait_for_function(f"window.frame === {MESSAGES - 1}", timeout=30_000, polling=100)
        applied = page.evaluate("window.applied")
        expected = f"{coalesce.READ_PREFIX}{applied}"
        for _ in range(100):
            if expected in noted:
                break
            threading.Event().wait(0.05)
        counts = [_count(text) for text in noted]
        # from the socket's opening on, what the page applied is counted, in order (the
        # messages applied before one animation frame together); the page got the last frame,
        # in as many messages as were sent (merged when it was behind)
        assert counts[0] == 0 and counts[-1] == applied, counts
        assert all(a < b for a, b in zip(counts, counts[1:], strict=False)), counts
        assert 1 <= applied <= MESSAGES
        assert not errors


DRAWING_MS = 150
# as the app's page with its 3-D view in software WebGL: each message applied asks for a drawing
# at the next animation frame, which holds the main thread DRAWING_MS; the page notes, for each
# count it sends, how many messages it had drawn then
SLOW_PAGE = (
    PAGE.replace(
        'window.frame = body[body.length - 1];  // {..., "result": {"frame": i}}: i, a fixint',
        """window.frame = body[body.length - 1];  // {..., "result": {"frame": i}}: i, a fixint
    if (!window.asked) window.asked = requestAnimationFrame(() => {
      const upto = window.applied, start = performance.now();
      while (performance.now() - start < __DRAWING__) {}
      window.drawn = upto;
      window.asked = 0;
    });""",
    )
    .replace(
        "  window.socket = socket;",
        """  window.socket = socket;
  window.told = [];
  const send = socket.send.bind(socket);
  socket.send = (data) => { window.told.push([String(data), window.drawn || 0]); send(data); };""",
    )
    .replace("__DRAWING__", str(DRAWING_MS))
)


@pytest.fixture
def slow_counting_front(monkeypatch):
    """:func:`_counting_front` of :data:`SLOW_PAGE`."""
    with _counting_front(monkeypatch, SLOW_PAGE) as served:
        yield served


def test_a_page_that_draws_slowly_counts_a_message_once_drawn(browser, slow_counting_front):
    """A page whose drawing takes DRAWING_MS counts a message only once it has drawn it: the
    front's next message then brings the newest state, not one from before the drawing."""
    assert "window.told" in SLOW_PAGE
    assert "__DRAWING__" not in SLOW_PAGE and "performance.now() - start" in SLOW_PAGE
    base, noted = slow_counting_front
    with _opened(browser, base) as (page, errors):
        page.wait_for_function(f"window.frame === {MESSAGES - 1}", timeout=60_000, polling=100)
        page.wait_for_function("window.drawn === window.applied", timeout=30_000, polling=100)
        applied = page.evaluate("window.applied")
        for _ in range(100):
            if noted and _count(noted[-1]) == applied:
                break
            threading.Event().wait(0.05)
        told = page.evaluate("window.told")
        counts = [(_count(text), drawn) for text, drawn in told]
        assert counts[-1][0] == applied, told
        # every message counted had been drawn when the count went
        assert all(count <= drawn for count, drawn in counts[1:]), told
        assert [text for text, _ in told] == noted[: len(told)]
        assert not errors
