"""In headless Chromium: a page the front serves says how many websocket messages it has
applied (app.serve.coalesce.READ_SCRIPT), read as trame's client reads them (as a Blob, its header
then its body, with trame's handler set after the socket is made), and applies each in the task
that received it; and it gets the session's last state."""

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
    let later = false;  // a task queued as the message came has run
    setTimeout(() => { later = true; }, 0);
    await e.data.slice(0, 12).arrayBuffer();
    const body = new Uint8Array(await e.data.slice(12).arrayBuffer());
    window.inItsTask = (window.inItsTask || 0) + (later ? 0 : 1);
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


# what a socket of the page gets for a message: as Blobs (the default, or asked for), as
# ArrayBuffers (asked for); read as trame reads a Blob
KINDS = """async () => {
  const url = window.location.href.replace(/^http/, 'ws').split('?')[0] + 'ws';
  const first = (ask) => new Promise((done) => {
    const socket = new WebSocket(url);
    if (ask) socket.binaryType = ask;
    socket.addEventListener('message', async (e) => {
      socket.close();
      const data = e.data;
      const whole = data instanceof ArrayBuffer ? data : await data.arrayBuffer();
      const head = data instanceof ArrayBuffer ? null
        : new Uint8Array(await data.slice(0, 12).arrayBuffer());
      const tail = data instanceof ArrayBuffer ? null
        : new Uint8Array(await data.slice(-3).arrayBuffer());
      const bytes = new Uint8Array(whole);
      done({ binaryType: socket.binaryType, arrayBuffer: data instanceof ArrayBuffer,
             size: data instanceof ArrayBuffer ? data.byteLength : data.size,
             bytes: bytes.length, head: head && Array.from(head).join() === Array.from(
               bytes.subarray(0, 12)).join(),
             tail: tail && Array.from(tail).join() === Array.from(bytes.subarray(-3)).join() });
    });
  });
  return [await first(null), await first('blob'), await first('arraybuffer')];
}"""


def test_a_page_that_asks_for_blobs_applies_each_message_in_the_task_that_received_it(
    browser, counting_front
):
    """trame's client reads a message as a Blob in two asynchronous reads; given the received
    ArrayBuffer's bytes in a Blob's place, it applies the message before any task queued as it
    came (Blob reads take tasks of their own: tens of ms in a busy page). A socket that asks
    for ArrayBuffers gets them."""
    base, _ = counting_front
    with _opened(browser, base) as (page, errors):
        page.wait_for_function(f"window.frame === {MESSAGES - 1}", timeout=30_000, polling=100)
        assert page.evaluate("window.inItsTask") == page.evaluate("window.applied")
        assert page.evaluate("window.socket.binaryType") == "blob"
        as_blob, asked_blob, asked_buffer = page.evaluate(KINDS)
        for got in (as_blob, asked_blob):
            assert got["binaryType"] == "blob" and not got["arrayBuffer"], got
            assert got["size"] == got["bytes"] > 12 and got["head"] and got["tail"], got
        assert asked_buffer["binaryType"] == "arraybuffer" and asked_buffer["arrayBuffer"]
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
